//! Canonical constructors. Every compound node is made here, so every node in a pool is in
//! canonical form: sums and products flattened, like terms and equal bases collected, exact
//! numbers folded, a numeric factor distributed over a single sum, `sin(−x)` written `−sin(x)`.

use std::cmp::Ordering;

use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};
use rustc_hash::FxHashMap;

use super::node::{Func, Id, Node};
use super::order;
use super::pool::Pool;

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
    pub(crate) fn neg(&mut self, a: Id) -> Id {
        let m = self.minus_one();
        self.product([m, a])
    }

    /// a · b.
    pub(crate) fn mul(&mut self, a: Id, b: Id) -> Id {
        self.product([a, b])
    }

    /// a / b.
    pub(crate) fn div(&mut self, a: Id, b: Id) -> Id {
        let r = self.recip(b);
        self.product([a, r])
    }

    /// 1 / a.
    pub(crate) fn recip(&mut self, a: Id) -> Id {
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
    pub(crate) fn scale(&mut self, c: &BigRational, a: Id) -> Id {
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

    /// Whether `id` is the undefined value `1/0` (0^k for a symbolic k is not: it is 0 where
    /// k > 0).
    pub(crate) fn is_undefined(&self, id: Id) -> bool {
        matches!(self.node(id), Node::Pow(b, e)
            if self.is_zero(*b) && self.as_num(*e).is_some_and(|v| *v == -BigRational::one()))
    }

    /// The canonical sum of `terms`.
    pub fn sum(&mut self, terms: impl IntoIterator<Item = Id>) -> Id {
        self.sum_of(terms.into_iter().collect())
    }

    /// [`Pool::sum`] of a list: the work is compiled once, not once per iterator type.
    fn sum_of(&mut self, mut stack: Vec<Id>) -> Id {
        let mut constant = BigRational::zero();
        // Terms and their coefficients; an index is built only for long sums, short ones
        // are scanned (most sums have a handful of terms).
        let mut keys: Vec<(Id, BigRational)> = Vec::new();
        let mut index: Option<FxHashMap<Id, usize>> = None;
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
        crate::sort::sort_unstable(&mut out);
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
    pub(crate) fn split_coeff(&mut self, t: Id) -> (BigRational, Id) {
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
        self.product_of(factors.into_iter().collect())
    }

    /// [`Pool::product`] of a list: the work is compiled once, not once per iterator type.
    fn product_of(&mut self, factors: Vec<Id>) -> Id {
        let (mut coeff, bases) = match self.gather_bases(factors) {
            Ok(x) => x,
            Err(undefined) => return undefined,
        };
        if coeff.is_zero() {
            return self.zero();
        }
        let mut out = Vec::with_capacity(bases.len());
        let mut again = self.merge_exponents(bases, &mut coeff, &mut out);
        again |= self.merge_radicals(&mut out, &mut coeff);
        if again {
            let c = self.num(coeff);
            out.push(c);
            return self.product_of(out);
        }
        self.finish_product(coeff, out)
    }

    /// Flattens the factors `stack` (in order) into a coefficient and bases: for each base,
    /// its first exponent, the factor it came from, and any further exponents. `Err` carries an undefined
    /// factor, which makes the whole product undefined.
    fn gather_bases(&mut self, mut stack: Vec<Id>) -> Result<(BigRational, Vec<Base>), Id> {
        let mut coeff = BigRational::one();
        // Products are short, so bases are found by scanning.
        let mut bases: Vec<Base> = Vec::new();
        stack.reverse();
        let one = self.one();
        while let Some(f) = stack.pop() {
            if self.is_undefined(f) {
                return Err(f);
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
            match bases.iter_mut().find(|x| x.base == b) {
                Some(x) => x.more.push(e),
                None => bases.push(Base {
                    base: b,
                    first: e,
                    original: f,
                    more: Vec::new(),
                }),
            }
        }
        Ok((coeff, bases))
    }

    /// Adds the exponents of each base into `out` (numbers go into `coeff`); true when a
    /// power came out as a product, which needs another pass.
    fn merge_exponents(
        &mut self,
        bases: Vec<Base>,
        coeff: &mut BigRational,
        out: &mut Vec<Id>,
    ) -> bool {
        let mut again = false;
        for b in bases {
            // A lone factor is already canonical; only merged exponents need `pow` again
            // (calling it on a lone `2^(1/2)` would rebuild the same product forever).
            let p = if b.more.is_empty() {
                b.original
            } else {
                let mut es = b.more;
                es.push(b.first);
                let e = self.sum(es);
                self.pow(b.base, e)
            };
            match self.node(p) {
                Node::Num(v) => mul_coeff(coeff, v),
                Node::Mul(_) => {
                    again = true;
                    out.push(p);
                }
                _ => out.push(p),
            }
        }
        again
    }

    /// Numeric radicals with one exponent merge: √2·√3 = √6, √2·√8 = 4. True when a merged
    /// radical came out as a product, which needs another pass.
    fn merge_radicals(&mut self, out: &mut Vec<Id>, coeff: &mut BigRational) -> bool {
        let radical = |pool: &Pool, f: Id| -> Option<(BigRational, Id)> {
            match pool.node(f) {
                Node::Pow(b, e) => match (pool.as_num(*b), pool.as_num(*e)) {
                    (Some(bv), Some(_)) if bv.is_positive() => Some((bv.clone(), *e)),
                    _ => None,
                },
                _ => None,
            }
        };
        let mut again = false;
        let mut k = 0;
        while k < out.len() {
            let Some((bk, ek)) = radical(self, out[k]) else {
                k += 1;
                continue;
            };
            let mut base = bk;
            let mut merged = false;
            let mut j = k + 1;
            while j < out.len() {
                match radical(self, out[j]) {
                    Some((bj, ej)) if ej == ek => {
                        base *= bj;
                        out.remove(j);
                        merged = true;
                    }
                    _ => j += 1,
                }
            }
            if !merged {
                k += 1;
                continue;
            }
            let b = self.num(base);
            let p = self.pow(b, ek);
            out.remove(k);
            match self.node(p) {
                Node::Num(v) => mul_coeff(coeff, v),
                Node::Mul(_) => {
                    again = true;
                    out.push(p);
                }
                _ => out.insert(k, p),
            }
        }
        again
    }

    /// The product node of `coeff` and the merged factors `out`: a number alone, a lone
    /// factor, a numeric factor distributed over a single sum, or a sorted `Mul`.
    fn finish_product(&mut self, coeff: BigRational, mut out: Vec<Id>) -> Id {
        if coeff.is_zero() {
            return self.zero();
        }
        crate::sort::sort_unstable(&mut out);
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
    pub(crate) fn pow(&mut self, b: Id, e: Id) -> Id {
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

    /// The canonical `f(a)`.
    pub(crate) fn func(&mut self, f: Func, a: Id) -> Id {
        if self.is_undefined(a) {
            return a;
        }
        if let Some(v) = self.func_exact(f, a) {
            return v;
        }
        if self.outside_domain(f, a) {
            // log(−1), asin(2): undefined, so that 0·log(−1) is undefined and not 0.
            return self.undefined();
        }
        if (f.is_odd() || f.is_even()) && self.is_negative_form(a) {
            // f(−a) = ±f(a), built through `func` so that f(a) gets every simplification
            // a direct reading would (abs(−π) is π, as abs(π) is).
            let na = self.neg(a);
            let inner = self.func(f, na);
            return if f.is_odd() { self.neg(inner) } else { inner };
        }
        self.intern(Node::Func(f, a))
    }

    /// Whether `f(a)` is undefined for a constant `a` (no variables): a value outside the
    /// function's real domain (log of a negative number or of 0, asin(2)). Overflow (exp(1000))
    /// is a number too large for a float, not a domain error, and is left alone.
    fn outside_domain(&self, f: Func, a: Id) -> bool {
        if !matches!(f, Func::Log | Func::Asin | Func::Acos) || !self.variables(a).is_empty() {
            return false;
        }
        let x = super::eval::eval_tree(self, a, &|_, _| f64::NAN);
        x.is_finite() && !f.apply(x).is_finite()
    }

    /// Whether `a` is written with a leading minus: a negative number, a product with a
    /// negative coefficient, or a sum whose first term (in display order) is negative.
    pub(crate) fn is_negative_form(&self, a: Id) -> bool {
        match self.node(a) {
            Node::Num(v) => v.is_negative(),
            Node::Mul(ch) => self.as_num(ch[0]).is_some_and(|c| c.is_negative()),
            Node::Add(ch) => {
                // The term printed first decides, so a stored sum reads as it prints:
                // (2 − √2), not −(−2 + √2).
                if let Some(v) = self.negative_sum.get(a) {
                    return v;
                }
                let v = self
                    .display_first_term(ch)
                    .is_some_and(|t| self.is_negative_form(t));
                self.negative_sum.insert(a, v);
                v
            }
            _ => false,
        }
    }

    /// Orders terms by their coefficient-free part.
    pub(crate) fn cmp_terms(&self, x: Id, y: Id) -> Ordering {
        let fx = self.factors_without_coeff(x);
        let fy = self.factors_without_coeff(y);
        let mut fx = fx.to_vec();
        let mut fy = fy.to_vec();
        crate::sort::sort_by(&mut fx, |&a, &b| order::cmp(self, a, b));
        crate::sort::sort_by(&mut fy, |&a, &b| order::cmp(self, a, b));
        for (a, b) in fx.iter().zip(&fy) {
            let o = order::cmp(self, *a, *b);
            if o != Ordering::Equal {
                return o;
            }
        }
        fx.len().cmp(&fy.len()).then_with(|| order::cmp(self, x, y))
    }

    /// The factors of a term without its numeric coefficient.
    pub(crate) fn factors_without_coeff(&self, t: Id) -> Vec<Id> {
        match self.node(t) {
            Node::Mul(ch) if self.as_num(ch[0]).is_some() => ch[1..].to_vec(),
            Node::Mul(ch) => ch.to_vec(),
            _ => vec![t],
        }
    }
}

/// One base of a product being built: its first exponent, the factor it came from, and
/// any further exponents to add.
struct Base {
    base: Id,
    first: Id,
    original: Id,
    more: Vec<Id>,
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
