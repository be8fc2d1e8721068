//! Exact arithmetic the canonical constructors rely on: rational powers of rationals (√8 =
//! 2√2, 8^(1/3) = 2, (1/2)^(1/2) = √2/2), bounded so no input can exhaust memory, and the exact
//! values of functions at special points (sin(π/6) = ½, log(exp(x)) = x).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::node::{Func, Id, Node};
use super::pool::Pool;

/// Largest integer exponent folded exactly; larger powers stay symbolic (and evaluate to
/// "undefined" if they overflow), so `2^2^2^2^2^2` cannot exhaust memory.
const MAX_EXACT_EXPONENT: i64 = 4096;
/// Largest result, in bits, of an exact power: about 900 digits, so every number the printer
/// writes stays within the reader's 1000-digit limit (10^1000 stays `10^1000`, and reads
/// back), and huge exact numbers do not slow every later operation on them.
const MAX_EXACT_BITS: u64 = 3_000;

impl Pool {
    /// `bv ^ ev` for exact numbers; `b` and `e` are their ids (used when the power stays
    /// symbolic, e.g. `2^(1/2)`).
    pub(super) fn num_pow(&mut self, bv: &BigRational, ev: &BigRational, b: Id, e: Id) -> Id {
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
        // Folded only if the power of the next integer in size folds too, so that x^e and
        // x^(−e) fold alike (their floors differ by one in size) and 1/x^e reads back as the
        // node it was printed from.
        let (Some(whole), Some(_)) = (exact_int_pow(bv, &k), exact_int_pow(bv, &ev.abs().ceil()))
        else {
            return self.intern(Node::Pow(b, e));
        };
        let (root, rest) = extract_perfect_power(&n, &q);
        // A root of 1 is 1 whatever the exponent (which may be too large to raise anything
        // else to: 100000^(−10000001/10000000) has r·q = 9999999).
        let root_part = if root.is_one() {
            Some(BigRational::one())
        } else {
            exact_int_pow(
                &BigRational::from_integer(root),
                &(&r * BigRational::from_integer(q.clone())),
            )
        };
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
    pub(crate) fn content(&mut self, add: Id) -> (BigRational, Id) {
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

    /// Exact values: sin(0), cos(π), log(1), log(exp(x)), |−3| and the like.
    pub(super) fn func_exact(&mut self, f: Func, a: Id) -> Option<Id> {
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
    let rest = n.clone();
    let Some(q) = q.to_u32() else {
        return (BigInt::one(), rest);
    };
    if rest.bits() > 128 || q > 64 {
        return (BigInt::one(), rest);
    }
    if let Some(n) = rest.to_u128().filter(|&n| n > 0) {
        return extract_small(n, q);
    }
    extract_big(rest, q)
}

/// [`extract_perfect_power`]'s trial division in big integers.
fn extract_big(mut rest: BigInt, q: u32) -> (BigInt, BigInt) {
    let mut root = BigInt::one();
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

/// [`extract_perfect_power`] for a positive `n` that fits in 128 bits, in machine integers
/// (a decimal coefficient such as 1.000003 has its numerator and denominator checked on every
/// reading), 64-bit ones when `n` fits. The same trial division, stopped once p^q exceeds what
/// is left: no larger prime power divides it then, so the result is the same.
fn extract_small(rest: u128, q: u32) -> (BigInt, BigInt) {
    match u64::try_from(rest) {
        Ok(n) => extract_machine(n, q),
        Err(_) => extract_machine(rest, q),
    }
}

/// [`extract_small`] in the integer type `T`.
fn extract_machine<T>(mut rest: T, q: u32) -> (BigInt, BigInt)
where
    T: num_traits::PrimInt + From<u32> + Into<BigInt>,
{
    let mut root = T::one();
    let mut p = 2u32;
    while p < 1000 {
        let Some(pq) =
            num_traits::checked_pow(<T as From<u32>>::from(p), q as usize).filter(|&pq| pq <= rest)
        else {
            break;
        };
        while (rest % pq).is_zero() {
            rest = rest / pq;
            root = root * <T as From<u32>>::from(p);
        }
        p += if p == 2 { 1 } else { 2 };
    }
    (root.into(), rest.into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn machine_integers_extract_the_same_powers() {
        let mut ns: Vec<u128> = (1..3000).collect();
        ns.extend([
            1_000_000,
            1_000_003,
            999_983 * 999_983,
            (1 << 100) * 243,
            u128::MAX,
            u128::MAX - 1,
        ]);
        for n in ns {
            for q in [1, 2, 3, 5, 64] {
                let big = extract_big(BigInt::from(n), q);
                assert_eq!(extract_machine(n, q), big, "{n}^(1/{q})");
                if let Ok(m) = u64::try_from(n) {
                    assert_eq!(extract_machine(m, q), big, "{n}^(1/{q}) in 64 bits");
                }
            }
        }
    }
}
