//! Canonical constructors. Every compound node is made here, so every node in a pool is in
//! canonical form: sums and products flattened, like terms and equal bases collected, exact
//! numbers folded, a numeric factor distributed over a single sum, `sin(−x)` written `−sin(x)`.

use std::cmp::Ordering;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use rustc_hash::FxHashMap;

use super::node::{Func, Id, Node};
use super::order;
use super::pool::Pool;

/// Largest integer exponent folded exactly; larger powers stay symbolic (and evaluate to
/// "undefined" if they overflow), so `2^2^2^2^2^2` cannot exhaust memory.
const MAX_EXACT_EXPONENT: i64 = 4096;
/// Largest result, in bits, of an exact power.
const MAX_EXACT_BITS: u64 = 65_536;

impl Pool {
    /// a + b.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        self.sum([a, b])
    }

    /// a − b.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.sum([a, nb])
    }

    /// −a.
    pub fn neg(&mut self, a: Id) -> Id {
        let m = self.minus_one();
        self.product([m, a])
    }

    /// a · b.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        self.product([a, b])
    }

    /// a / b.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let r = self.recip(b);
        self.product([a, r])
    }

    /// 1 / a.
    pub fn recip(&mut self, a: Id) -> Id {
        let m = self.minus_one();
        self.pow(a, m)
    }

    /// a ^ n for an integer n.
    pub fn powi(&mut self, a: Id, n: i64) -> Id {
        let e = self.int(n);
        self.pow(a, e)
    }

    /// √a.
    pub fn sqrt(&mut self, a: Id) -> Id {
        let h = self.ratio(1, 2);
        self.pow(a, h)
    }

    /// c · a for an exact rational c.
    pub fn scale(&mut self, c: &BigRational, a: Id) -> Id {
        let n = self.num(c.clone());
        self.product([n, a])
    }

    /// The canonical "undefined" value, `1/0`: anything built from it is undefined too, so
    /// `x/(x − x)` is one node however it was written.
    pub fn undefined(&mut self) -> Id {
        let z = self.zero();
        let m = self.minus_one();
        self.intern(Node::Pow(z, m))
    }

    /// Whether `id` is the undefined value `1/0`.
    pub fn is_undefined(&self, id: Id) -> bool {
        matches!(self.node(id), Node::Pow(b, _) if self.is_zero(*b))
    }

    /// The canonical sum of `terms`.
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Id>) -> Id {
        let mut constant = BigRational::zero();
        // Terms and their coefficients; an index is built only for long sums, short ones
        // are scanned (most sums have a handful of terms).
        let mut keys: Vec<(Id, BigRational)> = Vec::new();
        let mut index: Option<FxHashMap<Id, usize>> = None;
        let mut stack: Vec<Id> = terms.into_iter().collect();
        stack.reverse();
        while let Some(t) = stack.pop() {
            if self.is_undefined(t) {
                return t;
            }
            match self.node(t) {
                Node::Num(v) => {
                    add_coeff(&mut constant, v);
                    continue;
                }
                Node::Add(ch) => {
                    stack.extend(ch.iter().rev());
                    continue;
                }
                _ => {}
            }
            let (c, k) = self.split_coeff(t);
            let found = match &index {
                Some(ix) => ix.get(&k).copied(),
                None => keys.iter().position(|(x, _)| *x == k),
            };
            match found {
                Some(i) => add_coeff(&mut keys[i].1, &c),
                None => {
                    keys.push((k, c));
                    if let Some(ix) = index.as_mut() {
                        ix.insert(k, keys.len() - 1);
                    } else if keys.len() > 16 {
                        index = Some(keys.iter().enumerate().map(|(i, (x, _))| (*x, i)).collect());
                    }
                }
            }
        }
        let mut out = Vec::with_capacity(keys.len() + 1);
        for (k, c) in keys {
            if c.is_zero() {
                continue;
            }
            let term = self.with_coeff(c, k);
            out.push(term);
        }
        out.sort_unstable();
        if !constant.is_zero() {
            let n = self.num(constant);
            out.insert(0, n);
        }
        match out.len() {
            0 => self.zero(),
            1 => out[0],
            _ => self.intern(Node::Add(out.into_boxed_slice())),
        }
    }

    /// Splits a term into its rational coefficient and the rest (`3·x·y` → (3, x·y)).
    pub fn split_coeff(&mut self, t: Id) -> (BigRational, Id) {
        if let Node::Mul(ch) = self.node(t)
            && let Node::Num(c) = self.node(ch[0])
        {
            let c = c.clone();
            let rest: Vec<Id> = ch[1..].to_vec();
            let k = if rest.len() == 1 {
                rest[0]
            } else {
                self.intern(Node::Mul(rest.into_boxed_slice()))
            };
            return (c, k);
        }
        if let Node::Num(c) = self.node(t) {
            let c = c.clone();
            return (c, self.one());
        }
        (BigRational::one(), t)
    }

    /// c · k where k carries no numeric coefficient and is not a sum.
    fn with_coeff(&mut self, c: BigRational, k: Id) -> Id {
        if c.is_one() {
            return k;
        }
        let n = self.num(c);
        let mut ch = vec![n];
        match self.node(k) {
            Node::Mul(f) => ch.extend(f.iter()),
            _ => ch.push(k),
        }
        self.intern(Node::Mul(ch.into_boxed_slice()))
    }

    /// The canonical product of `factors`.
    pub fn product(&mut self, factors: impl IntoIterator<Item = Id>) -> Id {
        let mut coeff = BigRational::one();
        // For each base: its first exponent, the factor it came from, and any further
        // exponents. Products are short, so bases are found by scanning.
        let mut bases: Vec<(Id, Id, Id, Vec<Id>)> = Vec::new();
        let mut stack: Vec<Id> = factors.into_iter().collect();
        stack.reverse();
        let one = self.one();
        while let Some(f) = stack.pop() {
            if self.is_undefined(f) {
                return f;
            }
            let (b, e) = match self.node(f) {
                Node::Num(v) => {
                    mul_coeff(&mut coeff, v);
                    continue;
                }
                Node::Mul(ch) => {
                    stack.extend(ch.iter().rev());
                    continue;
                }
                Node::Pow(b, e) => (*b, *e),
                Node::Add(_) => {
                    // A sum as a factor is kept primitive: (−2x − 2y)·z = −2·(x + y)·z.
                    let (c, p) = self.content(f);
                    mul_coeff(&mut coeff, &c);
                    (p, one)
                }
                _ => (f, one),
            };
            let f = if matches!(self.node(f), Node::Add(_)) {
                b
            } else {
                f
            };
            match bases.iter_mut().find(|x| x.0 == b) {
                Some(x) => x.3.push(e),
                None => bases.push((b, e, f, Vec::new())),
            }
        }
        if coeff.is_zero() {
            return self.zero();
        }
        let mut out = Vec::with_capacity(bases.len());
        let mut again = false;
        for (b, first, original, more) in bases {
            // A lone factor is already canonical; only merged exponents need `pow` again
            // (calling it on a lone `2^(1/2)` would rebuild the same product forever).
            let p = if more.is_empty() {
                original
            } else {
                let mut es = more;
                es.push(first);
                let e = self.sum(es);
                self.pow(b, e)
            };
            match self.node(p) {
                Node::Num(v) => mul_coeff(&mut coeff, v),
                Node::Mul(_) => {
                    again = true;
                    out.push(p);
                }
                _ => out.push(p),
            }
        }
        if again {
            let c = self.num(coeff);
            out.push(c);
            return self.product(out);
        }
        if coeff.is_zero() {
            return self.zero();
        }
        out.sort_unstable();
        if out.is_empty() {
            return self.num(coeff);
        }
        if !coeff.is_one()
            && out.len() == 1
            && let Node::Add(terms) = self.node(out[0])
        {
            let terms = terms.to_vec();
            let scaled: Vec<Id> = terms.into_iter().map(|t| self.scale(&coeff, t)).collect();
            return self.sum(scaled);
        }
        if coeff.is_one() {
            if out.len() == 1 {
                return out[0];
            }
        } else {
            let n = self.num(coeff);
            out.insert(0, n);
        }
        self.intern(Node::Mul(out.into_boxed_slice()))
    }

    /// The canonical power `b ^ e`.
    pub fn pow(&mut self, b: Id, e: Id) -> Id {
        if self.is_undefined(b) || self.is_undefined(e) {
            return self.undefined();
        }
        if self.is_zero(e) || b == self.one() {
            return self.one();
        }
        if e == self.one() {
            return b;
        }
        let ev = self.as_num(e).cloned();
        if let Some(ev) = &ev {
            if self.is_zero(b) {
                return if ev.is_positive() {
                    self.zero()
                } else {
                    self.undefined()
                };
            }
            if let Some(bv) = self.as_num(b).cloned() {
                return self.num_pow(&bv, ev, b, e);
            }
        }
        match self.node(b).clone() {
            Node::Pow(bb, be) if ev.as_ref().is_some_and(|v| v.is_integer()) => {
                let ne = self.mul(be, e);
                self.pow(bb, ne)
            }
            Node::Mul(ch) if ev.as_ref().is_some_and(|v| v.is_integer()) => {
                let parts: Vec<Id> = ch.iter().map(|&c| self.pow(c, e)).collect();
                self.product(parts)
            }
            Node::Mul(ch)
                if ev.is_some() && self.as_num(ch[0]).is_some_and(|c| c.is_positive()) =>
            {
                // (c·X)^e = c^e · X^e for c > 0: both sides are defined at the same points.
                let c = ch[0];
                let rest = if ch.len() == 2 {
                    ch[1]
                } else {
                    self.intern(Node::Mul(ch[1..].to_vec().into_boxed_slice()))
                };
                let pc = self.pow(c, e);
                let pr = self.pow(rest, e);
                self.product([pc, pr])
            }
            Node::Func(Func::Exp, a) => {
                let ae = self.mul(a, e);
                self.func(Func::Exp, ae)
            }
            Node::Add(_) if ev.is_some() => {
                // (c·P)^e = c^e · P^e with P primitive, when c > 0 or e is an integer.
                let (c, p) = self.content(b);
                let integer = ev.as_ref().is_some_and(|v| v.is_integer());
                if c.is_one() || (c.is_negative() && !integer) {
                    return self.intern(Node::Pow(b, e));
                }
                let cn = self.num(c);
                let pc = self.pow(cn, e);
                let pp = self.pow(p, e);
                self.product([pc, pp])
            }
            Node::Func(Func::Abs, a)
                if ev
                    .as_ref()
                    .is_some_and(|v| v.is_integer() && v.to_integer().is_even()) =>
            {
                self.pow(a, e)
            }
            _ => self.intern(Node::Pow(b, e)),
        }
    }

    /// `bv ^ ev` for exact numbers; `b` and `e` are their ids (used when the power stays
    /// symbolic, e.g. `2^(1/2)`).
    fn num_pow(&mut self, bv: &BigRational, ev: &BigRational, b: Id, e: Id) -> Id {
        if ev.is_integer() {
            return match exact_int_pow(bv, ev) {
                Some(v) => self.num(v),
                None => self.intern(Node::Pow(b, e)),
            };
        }
        let q = ev.denom().clone();
        if bv.is_negative() {
            if q.is_odd() {
                // (−x)^(p/q) = (−1)^p · x^(p/q) for odd q.
                let sign = if ev.numer().is_odd() { -1 } else { 1 };
                let s = self.int(sign);
                let abs = self.num(bv.abs());
                let p = self.pow(abs, e);
                return self.product([s, p]);
            }
            return self.intern(Node::Pow(b, e));
        }
        if !bv.denom().is_one() {
            // (a/c)^e = a^e · c^(−e): keeps radicals in numerators (√2/2, not 1/√2).
            let a = self.num(BigRational::from_integer(bv.numer().clone()));
            let c = self.num(BigRational::from_integer(bv.denom().clone()));
            let ne = self.num(-ev);
            let pa = self.pow(a, e);
            let pc = self.pow(c, ne);
            return self.product([pa, pc]);
        }
        // Integer base n > 1, exponent k + r/q with 0 < r < q.
        let k = ev.floor();
        let r = ev - &k;
        let n = bv.numer().clone();
        let whole = match exact_int_pow(bv, &k) {
            Some(v) => v,
            None => return self.intern(Node::Pow(b, e)),
        };
        let (root, rest) = extract_perfect_power(&n, &q);
        let root_part = exact_int_pow(
            &BigRational::from_integer(root),
            &(&r * BigRational::from_integer(q.clone())),
        );
        let Some(root_part) = root_part else {
            return self.intern(Node::Pow(b, e));
        };
        let coeff = whole * root_part;
        if rest.is_one() {
            return self.num(coeff);
        }
        let c = self.num(coeff);
        let rb = self.num(BigRational::from_integer(rest));
        let re = self.num(r);
        let radical = self.intern(Node::Pow(rb, re));
        self.product([c, radical])
    }

    /// Splits a sum into its rational content and a primitive sum: `−4x/3 − 2y` is
    /// (−2/3)·(2x + 3y). The content's sign makes the primitive sum's leading term positive
    /// (the same choice as [`is_negative_form`](Self::is_negative_form)).
    pub fn content(&mut self, add: Id) -> (BigRational, Id) {
        if let Some(r) = self.contents.get(&add) {
            return r.clone();
        }
        let r = self.content_uncached(add);
        self.contents.insert(add, r.clone());
        r
    }

    fn content_uncached(&mut self, add: Id) -> (BigRational, Id) {
        let Node::Add(terms) = self.node(add) else {
            return (BigRational::one(), add);
        };
        let terms = terms.to_vec();
        let mut g = BigInt::zero();
        let mut l = BigInt::one();
        for &t in &terms {
            let c = match self.node(t) {
                Node::Num(v) => v.clone(),
                Node::Mul(ch) => self.as_num(ch[0]).cloned().unwrap_or_else(BigRational::one),
                _ => BigRational::one(),
            };
            g = g.gcd(c.numer());
            l = l.lcm(c.denom());
        }
        if g.is_zero() {
            return (BigRational::one(), add);
        }
        let mut c = BigRational::new(g, l);
        if self.is_negative_form(add) {
            c = -c;
        }
        if c.is_one() {
            return (c, add);
        }
        let inv = c.recip();
        let scaled: Vec<Id> = terms.iter().map(|&t| self.scale(&inv, t)).collect();
        (c, self.sum(scaled))
    }

    /// The canonical `f(a)`.
    pub fn func(&mut self, f: Func, a: Id) -> Id {
        if self.is_undefined(a) {
            return a;
        }
        if let Some(v) = self.func_exact(f, a) {
            return v;
        }
        if (f.is_odd() || f.is_even()) && self.is_negative_form(a) {
            let na = self.neg(a);
            let inner = self.intern(Node::Func(f, na));
            return if f.is_odd() { self.neg(inner) } else { inner };
        }
        self.intern(Node::Func(f, a))
    }

    /// Exact values: sin(0), cos(π), log(1), log(exp(x)), |−3| and the like.
    fn func_exact(&mut self, f: Func, a: Id) -> Option<Id> {
        if self.is_zero(a) {
            return match f {
                Func::Cos | Func::Cosh | Func::Exp => Some(self.one()),
                Func::Acos => {
                    let pi = self.pi();
                    let h = self.ratio(1, 2);
                    Some(self.mul(h, pi))
                }
                Func::Log => None,
                _ => Some(self.zero()),
            };
        }
        if a == self.one() {
            match f {
                Func::Log | Func::Acos => return Some(self.zero()),
                Func::Abs => return Some(a),
                _ => {}
            }
        }
        match (f, self.node(a)) {
            (Func::Abs, Node::Num(v)) => {
                let v = v.abs();
                return Some(self.num(v));
            }
            (Func::Abs, Node::Pi) => return Some(a),
            (Func::Log, Node::Func(Func::Exp, x)) => return Some(*x),
            _ => {}
        }
        if matches!(f, Func::Sin | Func::Cos | Func::Tan) {
            let c = self.pi_multiple(a)?;
            return self.trig_of_pi_multiple(f, &c);
        }
        None
    }

    /// `Some(c)` when `a` is `c·π` for a rational c.
    fn pi_multiple(&self, a: Id) -> Option<BigRational> {
        match self.node(a) {
            Node::Pi => Some(BigRational::one()),
            Node::Mul(ch) if ch.len() == 2 && matches!(self.node(ch[1]), Node::Pi) => {
                self.as_num(ch[0]).cloned()
            }
            _ => None,
        }
    }

    /// sin, cos, tan at c·π where 12c is an integer and the value is a known radical.
    fn trig_of_pi_multiple(&mut self, f: Func, c: &BigRational) -> Option<Id> {
        let twelve = BigRational::from_integer(BigInt::from(12));
        let n = c * &twelve;
        if !n.is_integer() {
            return None;
        }
        let n = n.to_integer().mod_floor(&BigInt::from(24)).to_i64()?;
        let sin_at = |k: i64| -> Option<(i64, u8)> {
            // sin(kπ/12) as sign and one of: 0, ½, √2/2, √3/2, 1.
            let k = k.rem_euclid(24);
            let (sign, k) = if k >= 12 { (-1, k - 12) } else { (1, k) };
            let kind = match k.min(12 - k) {
                0 => 0,
                2 => 1,
                3 => 2,
                4 => 3,
                6 => 4,
                _ => return None,
            };
            Some((sign, kind))
        };
        let value = |pool: &mut Pool, (sign, kind): (i64, u8)| -> Id {
            let v = match kind {
                0 => pool.zero(),
                1 => pool.ratio(1, 2),
                2 | 3 => {
                    let r = pool.int(if kind == 2 { 2 } else { 3 });
                    let s = pool.sqrt(r);
                    let h = pool.ratio(1, 2);
                    pool.mul(h, s)
                }
                _ => pool.one(),
            };
            if sign < 0 { pool.neg(v) } else { v }
        };
        match f {
            Func::Sin => sin_at(n).map(|s| value(self, s)),
            Func::Cos => sin_at(n + 6).map(|s| value(self, s)),
            _ => {
                let (s, c) = (sin_at(n)?, sin_at(n + 6)?);
                if c.1 == 0 {
                    return None;
                }
                let sv = value(self, s);
                let cv = value(self, c);
                Some(self.div(sv, cv))
            }
        }
    }

    /// Whether `a` is written with a leading minus: a negative number, a product with a
    /// negative coefficient, or a sum whose first term (in display order) is negative.
    pub fn is_negative_form(&self, a: Id) -> bool {
        match self.node(a) {
            Node::Num(v) => v.is_negative(),
            Node::Mul(ch) => self.as_num(ch[0]).is_some_and(|c| c.is_negative()),
            Node::Add(ch) => {
                // The term printed first decides, so a stored sum reads as it prints:
                // (2 − √2), not −(−2 + √2).
                if let Some(&v) = self.negative_sum.borrow().get(&a) {
                    return v;
                }
                let v = self
                    .display_first_term(ch)
                    .is_some_and(|t| self.is_negative_form(t));
                self.negative_sum.borrow_mut().insert(a, v);
                v
            }
            _ => false,
        }
    }

    /// Orders terms by their coefficient-free part.
    pub fn cmp_terms(&self, x: Id, y: Id) -> Ordering {
        let fx = self.factors_without_coeff(x);
        let fy = self.factors_without_coeff(y);
        let mut fx = fx.to_vec();
        let mut fy = fy.to_vec();
        fx.sort_by(|&a, &b| order::cmp(self, a, b));
        fy.sort_by(|&a, &b| order::cmp(self, a, b));
        for (a, b) in fx.iter().zip(&fy) {
            let o = order::cmp(self, *a, *b);
            if o != Ordering::Equal {
                return o;
            }
        }
        fx.len().cmp(&fy.len()).then_with(|| order::cmp(self, x, y))
    }

    /// The factors of a term without its numeric coefficient.
    pub fn factors_without_coeff(&self, t: Id) -> Vec<Id> {
        match self.node(t) {
            Node::Mul(ch) if self.as_num(ch[0]).is_some() => ch[1..].to_vec(),
            Node::Mul(ch) => ch.to_vec(),
            _ => vec![t],
        }
    }
}

/// acc ← acc · v, skipping the gcd normalization where it cannot change anything.
fn mul_coeff(acc: &mut BigRational, v: &BigRational) {
    if v.is_one() {
        return;
    }
    if acc.is_one() {
        *acc = v.clone();
    } else if acc.is_integer() && v.is_integer() {
        *acc = BigRational::from_integer(acc.numer() * v.numer());
    } else {
        *acc *= v;
    }
}

/// acc ← acc + v, likewise.
fn add_coeff(acc: &mut BigRational, v: &BigRational) {
    if v.is_zero() {
        return;
    }
    if acc.is_zero() {
        *acc = v.clone();
    } else if acc.is_integer() && v.is_integer() {
        *acc = BigRational::from_integer(acc.numer() + v.numer());
    } else {
        *acc += v;
    }
}

/// `b ^ e` exactly, for an integer `e`, if the result is of reasonable size.
fn exact_int_pow(b: &BigRational, e: &BigRational) -> Option<BigRational> {
    let n = e.to_integer().to_i64()?;
    if n.abs() > MAX_EXACT_EXPONENT {
        return None;
    }
    if b.is_zero() {
        return if n > 0 {
            Some(BigRational::zero())
        } else {
            None
        };
    }
    let bits = b.numer().bits().max(b.denom().bits()).max(1);
    if bits.saturating_mul(n.unsigned_abs()) > MAX_EXACT_BITS {
        return None;
    }
    let n = i32::try_from(n).ok()?;
    Some(num_traits::Pow::pow(b, n))
}

/// Writes `n = root^q · rest` with `root` as large as trial division by small primes finds.
fn extract_perfect_power(n: &BigInt, q: &BigInt) -> (BigInt, BigInt) {
    let mut root = BigInt::one();
    let mut rest = n.clone();
    let Some(q) = q.to_u32() else {
        return (root, rest);
    };
    if rest.bits() > 128 || q > 64 {
        return (root, rest);
    }
    let mut p = 2u32;
    while p < 1000 {
        let pq = num_traits::Pow::pow(BigInt::from(p), q);
        while (&rest % &pq).is_zero() {
            rest /= &pq;
            root *= p;
        }
        p += if p == 2 { 1 } else { 2 };
    }
    (root, rest)
}
