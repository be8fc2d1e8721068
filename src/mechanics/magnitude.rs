//! Zero tests relative to the size of the quantities. An expression evaluated in floating
//! point carries a rounding error proportional to the largest intermediate values it passed
//! through, not to 1: `m·(cos²x + sin²x) − m` leaves about 1e-16·m, whatever m is, and a
//! lone term `1e-30·x` is never zero however small. [`Magnitudes`] evaluates expressions
//! together with that size (a first-order bound on the rounding, in units of the machine
//! epsilon), so a value is negligible exactly when it is small *relative to its own terms*.
//!
//! Also here: the check that no constant part of an expression overflows (`exp(1000)`),
//! which would make everything containing it undefined at every point.

use num_traits::ToPrimitive;
use rustc_hash::FxHashMap;

use super::error::MechError;
use crate::expr::{Func, Id, Node, Pool, Sym};

/// A value counts as zero when it is within this fraction of its magnitude: rounding leaves
/// about 1e-16 of it, a real difference far more.
pub(crate) const RELATIVE_ZERO: f64 = 1e-9;

/// One step of a magnitude evaluation; operands are indices of earlier steps.
#[derive(Clone, Debug)]
enum Op {
    Const(f64),
    Input(usize),
    Add(Box<[usize]>),
    Mul(Box<[usize]>),
    /// Base, exponent, and whether the exponent is a constant (carries no rounding).
    Pow(usize, usize, bool),
    Func(Func, usize),
}

/// Expressions compiled for evaluation with their rounding magnitudes.
#[derive(Clone, Debug)]
pub(crate) struct Magnitudes {
    ops: Vec<Op>,
    /// The node each step evaluates (to name the one that fails).
    ids: Vec<Id>,
    outputs: Vec<usize>,
}

/// A value and its magnitude: `|computed − exact| ≲ ε · magnitude`, and magnitude ≥ |value|.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Sized {
    pub(crate) value: f64,
    pub(crate) magnitude: f64,
}

impl Sized {
    /// Whether the value is zero up to rounding (an exact zero always is).
    pub(crate) fn negligible(self) -> bool {
        self.value.abs() <= RELATIVE_ZERO * self.magnitude
    }
}

impl Magnitudes {
    /// Compiles `roots` over `inputs`; the error is a variable that is not among them.
    pub(crate) fn new(pool: &Pool, roots: &[Id], inputs: &[(Sym, u8)]) -> Result<Magnitudes, Sym> {
        let reach = reachable(pool, roots);
        let index: FxHashMap<Id, usize> =
            reach.iter().enumerate().map(|(i, &id)| (id, i)).collect();
        let slot = |id: &Id| index[id];
        let mut ops = Vec::with_capacity(reach.len());
        for &id in &reach {
            ops.push(match pool.node(id) {
                Node::Num(v) => Op::Const(v.to_f64().unwrap_or(f64::NAN)),
                Node::Pi => Op::Const(std::f64::consts::PI),
                Node::Var(s, o) => Op::Input(inputs.iter().position(|v| *v == (*s, *o)).ok_or(*s)?),
                Node::Add(ts) => Op::Add(ts.iter().map(slot).collect()),
                Node::Mul(ts) => Op::Mul(ts.iter().map(slot).collect()),
                Node::Pow(b, e) => Op::Pow(slot(b), slot(e), matches!(pool.node(*e), Node::Num(_))),
                Node::Func(f, a) => Op::Func(*f, slot(a)),
            });
        }
        let outputs = roots.iter().map(slot).collect();
        Ok(Magnitudes {
            ops,
            ids: reach,
            outputs,
        })
    }

    /// Evaluates every root at `x`; `None` where something is undefined (not finite).
    pub(crate) fn eval(&self, x: &[f64]) -> Option<Vec<Sized>> {
        self.run(x).ok()
    }

    /// The first part that is not finite at `x`, and whether it overflowed (rather than
    /// being undefined: a pole or a domain error); `None` when everything is defined there.
    pub(crate) fn failure(&self, x: &[f64]) -> Option<(Id, bool)> {
        self.run(x).err()
    }

    fn run(&self, x: &[f64]) -> Result<Vec<Sized>, (Id, bool)> {
        let mut s: Vec<Sized> = Vec::with_capacity(self.ops.len());
        for (op, &id) in self.ops.iter().zip(&self.ids) {
            let r = step(op, &s, x);
            if !r.value.is_finite() {
                let pole = match op {
                    Op::Pow(b, _, _) => s[*b].value == 0.0,
                    Op::Func(f, _) => *f == Func::Log,
                    _ => false,
                };
                return Err((id, r.value.is_infinite() && !pole));
            }
            // A magnitude that overflows says nothing; the value alone is the safe bound
            // (it makes the test stricter, never calls a nonzero value zero).
            let magnitude = if r.magnitude.is_finite() {
                r.magnitude.max(r.value.abs())
            } else {
                r.value.abs()
            };
            s.push(Sized {
                value: r.value,
                magnitude,
            });
        }
        Ok(self.outputs.iter().map(|&k| s[k]).collect())
    }
}

/// One step: the value, and the first-order propagation of the operands' rounding.
fn step(op: &Op, s: &[Sized], x: &[f64]) -> Sized {
    let exact = |value: f64| Sized {
        value,
        magnitude: value.abs(),
    };
    match op {
        Op::Const(c) => exact(*c),
        Op::Input(k) => exact(x.get(*k).copied().unwrap_or(f64::NAN)),
        Op::Add(ts) => Sized {
            value: ts.iter().map(|&t| s[t].value).sum(),
            magnitude: ts.iter().map(|&t| s[t].magnitude).sum(),
        },
        Op::Mul(ts) => {
            let value: f64 = ts.iter().map(|&t| s[t].value).product();
            // δ(Π vᵢ) = Σ δvᵢ · Π_{j≠i} vⱼ: no division, so an exact zero factor keeps the
            // product exact.
            let spread: f64 = (0..ts.len())
                .map(|i| {
                    let others: f64 = (0..ts.len())
                        .filter(|&j| j != i)
                        .map(|j| s[ts[j]].value.abs())
                        .product();
                    s[ts[i]].magnitude * others
                })
                .sum();
            Sized {
                value,
                magnitude: value.abs() + spread,
            }
        }
        Op::Pow(b, e, constant) => power(s[*b], s[*e], *constant),
        Op::Func(f, a) => {
            let u = s[*a];
            let value = f.apply(u.value);
            Sized {
                value,
                magnitude: value.abs() + slope(*f, u.value, value) * u.magnitude,
            }
        }
    }
}

/// bᵉ, with δ(bᵉ) = e·bᵉ⁻¹·δb + bᵉ·ln|b|·δe (δe = 0 for a constant exponent).
fn power(b: Sized, e: Sized, constant: bool) -> Sized {
    let value = if e.value.fract() == 0.0 && e.value.abs() < 1024.0 {
        b.value.powi(e.value as i32)
    } else {
        b.value.powf(e.value)
    };
    let by_base = if b.value == 0.0 {
        // The slope is infinite or zero at 0: the base's own size, raised, bounds it.
        if e.value > 0.0 {
            b.magnitude.powf(e.value)
        } else {
            0.0
        }
    } else {
        (e.value * b.value.powf(e.value - 1.0)).abs() * b.magnitude
    };
    let by_exponent = if constant {
        0.0
    } else {
        (value * b.value.abs().ln()).abs() * e.magnitude
    };
    Sized {
        value,
        magnitude: value.abs() + by_base + by_exponent,
    }
}

/// |f′(u)|, given u and f(u).
fn slope(f: Func, u: f64, fu: f64) -> f64 {
    match f {
        Func::Sin => u.cos().abs(),
        Func::Cos => u.sin().abs(),
        Func::Tan => 1.0 + fu * fu,
        Func::Asin | Func::Acos => 1.0 / (1.0 - u * u).sqrt(),
        Func::Atan => 1.0 / (1.0 + u * u),
        Func::Sinh => u.cosh(),
        Func::Cosh => u.sinh().abs(),
        Func::Tanh => 1.0 - fu * fu,
        Func::Exp => fu,
        Func::Log => 1.0 / u.abs(),
        Func::Abs => 1.0,
    }
}

/// Every node reachable from `roots`, children before parents (ascending id).
fn reachable(pool: &Pool, roots: &[Id]) -> Vec<Id> {
    let mut seen = rustc_hash::FxHashSet::default();
    let mut stack: Vec<Id> = roots.to_vec();
    let mut out = Vec::new();
    let mut children = Vec::new();
    while let Some(n) = stack.pop() {
        if seen.insert(n) {
            out.push(n);
            children.clear();
            pool.push_children(n, &mut children);
            stack.extend(children.iter().copied());
        }
    }
    crate::sort::sort_unstable(&mut out);
    out
}

/// The first constant (variable-free) part of `roots` whose value is not finite, as an
/// error naming it: `exp(1000)` overflows, `log(-1)` is undefined.
pub(crate) fn non_finite_constant(pool: &Pool, roots: &[Id]) -> Option<MechError> {
    let reach = reachable(pool, roots);
    // value of each constant node; None for nodes that depend on a variable.
    let mut value: FxHashMap<Id, f64> = FxHashMap::default();
    let mut children = Vec::new();
    for &id in &reach {
        children.clear();
        pool.push_children(id, &mut children);
        let v = match pool.node(id) {
            Node::Var(..) => continue,
            Node::Num(v) => v.to_f64().unwrap_or(f64::NAN),
            Node::Pi => std::f64::consts::PI,
            _ if children.iter().any(|c| !value.contains_key(c)) => continue,
            Node::Add(ts) => ts.iter().map(|t| value[t]).sum(),
            Node::Mul(ts) => ts.iter().map(|t| value[t]).product(),
            Node::Pow(b, e) => value[b].powf(value[e]),
            Node::Func(f, a) => f.apply(value[a]),
        };
        if !v.is_finite() {
            // ±∞ from finite operands is an overflow, unless it is a pole (1/0, log 0).
            let pole = match pool.node(id) {
                Node::Pow(b, _) => value[b] == 0.0,
                Node::Func(f, _) => *f == Func::Log,
                _ => false,
            };
            return Some(if v.is_infinite() && !pole {
                MechError::Overflow {
                    expr: pool.plain(id),
                }
            } else {
                MechError::UndefinedConstant {
                    expr: pool.plain(id),
                }
            });
        }
        value.insert(id, v);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::{Context, read_expr};

    fn at(src: &str, x: f64) -> Sized {
        let mut pool = Pool::new();
        let e = read_expr(src, &Context::open(), &mut pool).unwrap();
        let xs = pool.symbol("x");
        let m = Magnitudes::new(&pool, &[e], &[(xs, 0)]).unwrap();
        m.eval(&[x]).unwrap()[0]
    }

    #[test]
    fn cancellation_is_zero_at_every_scale() {
        for x in [1e-30, 0.7, 1e30] {
            assert!(at("x*(cos(1)^2 + sin(1)^2) - x", x).negligible(), "{x}");
            assert!(!at("x", x).negligible(), "{x}");
            assert!(!at("1e-12*x", x).negligible(), "{x}");
        }
        // An exact zero factor keeps the product exact.
        assert_eq!(at("x*(1 + cos(2))", 0.0).magnitude, 0.0);
    }

    #[test]
    fn constant_overflow_is_named() {
        let mut pool = Pool::new();
        let e = read_expr("x*exp(1000) + 1", &Context::open(), &mut pool).unwrap();
        assert_eq!(
            non_finite_constant(&pool, &[e]),
            Some(MechError::Overflow {
                expr: "exp(1000)".into()
            })
        );
        let ok = read_expr("x*exp(10)", &Context::open(), &mut pool).unwrap();
        assert_eq!(non_finite_constant(&pool, &[ok]), None);
    }
}
