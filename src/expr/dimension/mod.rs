//! Physical dimensions: exponents of mass M, length L, time T and charge Q, inferred for any
//! expression from the dimensions of its symbols. A time derivative divides by T. Angles
//! are dimensionless. A power with a symbolic exponent of parameters (`r^n`) has a dimension
//! that depends on the exponent's value: it is reported as undecided (`None`), not refused.

use std::collections::BTreeMap;
use std::fmt;

use num_rational::Rational32;
use num_traits::{ToPrimitive, Zero};
use rustc_hash::FxHashMap;

use super::names;
use super::node::{Func, Id, Node};
use super::pool::Pool;

/// Exponents of M, L, T and Q (electric charge).
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug, Default, PartialOrd, Ord)]
pub struct Dimension {
    pub(crate) m: Rational32,
    pub(crate) l: Rational32,
    pub(crate) t: Rational32,
    pub(crate) q: Rational32,
}

impl Dimension {
    /// Dimensionless.
    pub const NONE: Dimension = Dimension {
        m: Rational32::new_raw(0, 1),
        l: Rational32::new_raw(0, 1),
        t: Rational32::new_raw(0, 1),
        q: Rational32::new_raw(0, 1),
    };

    /// M^m L^l T^t for integer exponents.
    pub fn new(m: i32, l: i32, t: i32) -> Self {
        Dimension {
            m: m.into(),
            l: l.into(),
            t: t.into(),
            q: Rational32::zero(),
        }
    }

    /// Electric charge, Q.
    pub fn charge() -> Self {
        Dimension {
            q: Rational32::from(1),
            ..Dimension::NONE
        }
    }

    /// Energy, M L² T⁻².
    pub fn energy() -> Self {
        Dimension::new(1, 2, -2)
    }

    /// Whether dimensionless.
    pub fn is_none(&self) -> bool {
        self.m.is_zero() && self.l.is_zero() && self.t.is_zero() && self.q.is_zero()
    }

    /// Raised to a rational power.
    pub(crate) fn pow(self, k: Rational32) -> Self {
        Dimension {
            m: self.m * k,
            l: self.l * k,
            t: self.t * k,
            q: self.q * k,
        }
    }

    /// Reads `"M L^2 T^-2"`, `"L T^-2"`, `"Q"` (charge), `"1"`, `""`, `"rad"` or `"angle"`
    /// (dimensionless). Also accepts `*` between factors, `/` before a factor, and Unicode
    /// superscripts.
    pub fn parse(src: &str) -> Result<Dimension, DimensionSyntax> {
        let text: String = src
            .chars()
            .map(|c| match c {
                '·' | '*' => ' ',
                '⁻' => '-',
                c => names::superscript_digit(c)
                    .and_then(|d| char::from_digit(d, 10))
                    .unwrap_or(c),
            })
            .collect();
        let text = text.trim();
        let dimensionless = ["dimensionless", "rad", "radian", "angle"];
        if text.is_empty()
            || text == "1"
            || dimensionless.iter().any(|w| text.eq_ignore_ascii_case(w))
        {
            return Ok(Dimension::NONE);
        }
        let mut d = Dimension::NONE;
        let mut sign = 1;
        let mut rest = text;
        while !rest.is_empty() {
            rest = rest.trim_start();
            if let Some(r) = rest.strip_prefix('/') {
                sign = -1;
                rest = r;
                continue;
            }
            let mut chars = rest.chars();
            let base = chars.next().ok_or(DimensionSyntax::Empty)?;
            rest = chars.as_str();
            let mut exp = Rational32::from(1);
            let tail = rest.trim_start_matches('^');
            let has_caret = tail.len() != rest.len();
            // An exponent: optional `-`, digits, and optionally `/digits` (`L^1/2`).
            let b = tail.as_bytes();
            let mut k = usize::from(b.first() == Some(&b'-'));
            let digits = |k: &mut usize| {
                let s = *k;
                while *k < b.len() && b[*k].is_ascii_digit() {
                    *k += 1;
                }
                *k > s
            };
            let mut digits_end = 0;
            if digits(&mut k) {
                digits_end = k;
                if k < b.len() && b[k] == b'/' {
                    let mut j = k + 1;
                    if digits(&mut j) {
                        digits_end = j;
                    }
                }
            }
            if digits_end > 0 {
                let e = &tail[..digits_end];
                exp = parse_ratio(e).ok_or_else(|| DimensionSyntax::BadExponent {
                    exponent: e.to_string(),
                    input: src.to_string(),
                })?;
                rest = &tail[digits_end..];
            } else if has_caret {
                return Err(DimensionSyntax::MissingExponent {
                    input: src.to_string(),
                });
            }
            let unit = match base {
                'M' => Dimension::new(1, 0, 0),
                'L' => Dimension::new(0, 1, 0),
                'T' => Dimension::new(0, 0, 1),
                'Q' => Dimension::charge(),
                other => {
                    return Err(DimensionSyntax::UnknownBase {
                        base: other,
                        input: src.to_string(),
                    });
                }
            };
            d = d * unit.pow(exp * Rational32::from(sign));
        }
        Ok(d)
    }

    /// Plain form, `M L^2 T^-2` (`1` when dimensionless).
    pub fn plain(&self) -> String {
        self.render(false)
    }

    fn render(&self, unicode: bool) -> String {
        if self.is_none() {
            return if unicode {
                "dimensionless".into()
            } else {
                "1".into()
            };
        }
        let mut parts = Vec::new();
        for (name, e) in [("M", self.m), ("L", self.l), ("T", self.t), ("Q", self.q)] {
            if e.is_zero() {
                continue;
            }
            let exp = if e == Rational32::from(1) {
                String::new()
            } else if e.is_integer() && unicode {
                names::superscript(i64::from(e.to_integer()))
            } else if e.is_integer() {
                format!("^{}", e.to_integer())
            } else {
                format!("^({e})")
            };
            parts.push(format!("{name}{exp}"));
        }
        parts.join(" ")
    }
}

fn parse_ratio(s: &str) -> Option<Rational32> {
    match s.split_once('/') {
        Some((n, d)) => {
            let d: i32 = d.parse().ok()?;
            let n: i32 = n.parse().ok()?;
            (d != 0).then(|| Rational32::new(n, d))
        }
        None => s.parse::<i32>().ok().map(Rational32::from),
    }
}

impl std::ops::Mul for Dimension {
    type Output = Dimension;

    fn mul(self, o: Dimension) -> Dimension {
        Dimension {
            m: self.m + o.m,
            l: self.l + o.l,
            t: self.t + o.t,
            q: self.q + o.q,
        }
    }
}

impl std::ops::Div for Dimension {
    type Output = Dimension;

    fn div(self, o: Dimension) -> Dimension {
        self * o.pow(Rational32::from(-1))
    }
}

impl fmt::Display for Dimension {
    /// Unicode form, `M L² T⁻²`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.render(true))
    }
}

/// The dimensions of named symbols. A coordinate's time derivatives and `t` follow from it.
#[derive(Clone, Debug, Default)]
pub struct Dimensions {
    map: BTreeMap<String, Dimension>,
    /// Names that vary (coordinates): an exponent containing one makes a dimension that
    /// varies, which is an error; an exponent of constants only is merely undecided.
    varying: std::collections::BTreeSet<String>,
}

impl Dimensions {
    /// No symbol has a known dimension yet.
    pub fn new() -> Self {
        Dimensions::default()
    }

    /// Sets the dimension of a symbol.
    pub fn set(&mut self, name: &str, d: Dimension) {
        self.map.insert(names::normalize(name), d);
    }

    /// With one more symbol.
    pub fn with(mut self, name: &str, d: Dimension) -> Self {
        self.set(name, d);
        self
    }

    /// Sets the dimension of a coordinate (a symbol that varies in time).
    pub fn set_coordinate(&mut self, name: &str, d: Dimension) {
        self.set(name, d);
        self.varying.insert(names::normalize(name));
    }

    /// With one more coordinate.
    pub fn with_coordinate(mut self, name: &str, d: Dimension) -> Self {
        self.set_coordinate(name, d);
        self
    }

    /// Whether no symbol has a dimension (a problem pinned to a student's numbers, which
    /// carry no units).
    pub fn is_empty(&self) -> bool {
        self.map.is_empty()
    }

    /// Whether `name` varies (a coordinate, or `t`).
    fn varies(&self, name: &str) -> bool {
        name == super::pool::TIME || self.varying.contains(name)
    }

    /// The dimension of a symbol, if known (`t` is always T).
    pub fn get(&self, name: &str) -> Option<Dimension> {
        match self.map.get(name) {
            Some(d) => Some(*d),
            None if name == super::pool::TIME => Some(Dimension::new(0, 0, 1)),
            None => None,
        }
    }
}

/// Why a written dimension (`"M L^2 T^-2"`) cannot be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DimensionSyntax {
    /// Nothing where a base dimension was expected.
    #[error("empty dimension")]
    Empty,
    /// An exponent that is not an integer or a ratio of integers.
    #[error("bad exponent `{exponent}` in `{input}`")]
    BadExponent {
        /// The exponent as written.
        exponent: String,
        /// The whole dimension as written.
        input: String,
    },
    /// `^` with no exponent after it.
    #[error("missing exponent after `^` in `{input}`")]
    MissingExponent {
        /// The whole dimension as written.
        input: String,
    },
    /// A base other than M, L, T and Q.
    #[error("unknown dimension `{base}` in `{input}`: use M, L, T and Q (charge), e.g. \"L T^-2\"")]
    UnknownBase {
        /// The base as written.
        base: char,
        /// The whole dimension as written.
        input: String,
    },
}

/// A dimension error, naming the offending parts (printed in Unicode).
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum DimError {
    #[error("terms of different dimensions are added: {}", list(.terms))]
    UnlikeTerms { terms: Vec<(String, Dimension)> },
    #[error("the argument of {func} must be dimensionless, but {arg} is {dim}")]
    DimensionfulArgument {
        func: &'static str,
        arg: String,
        dim: Dimension,
    },
    #[error("an exponent must be dimensionless, but {exponent} is {dim}")]
    DimensionfulExponent { exponent: String, dim: Dimension },
    #[error("{base} has dimension {dim}, so its exponent must be a number, not {exponent}")]
    SymbolicExponent {
        base: String,
        dim: Dimension,
        exponent: String,
    },
    #[error("the two sides differ in dimension: {lhs} is {lhs_dim}, {rhs} is {rhs_dim}")]
    UnlikeSides {
        lhs: String,
        lhs_dim: Dimension,
        rhs: String,
        rhs_dim: Dimension,
    },
}

fn list(terms: &[(String, Dimension)]) -> String {
    terms
        .iter()
        .map(|(t, d)| format!("{t} is {d}"))
        .collect::<Vec<_>>()
        .join(", ")
}

mod infer;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_dimensions() {
        let cases = [
            ("M", Dimension::new(1, 0, 0)),
            ("L T^-2", Dimension::new(0, 1, -2)),
            ("M L^2 T^-2", Dimension::energy()),
            ("M L² T⁻²", Dimension::energy()),
            ("M*L/T", Dimension::new(1, 1, -1)),
            ("1", Dimension::NONE),
            ("", Dimension::NONE),
            ("T^-1", Dimension::new(0, 0, -1)),
            ("Q", Dimension::charge()),
            ("Q T^-1", Dimension::charge() / Dimension::new(0, 0, 1)),
            ("rad", Dimension::NONE),
            ("angle", Dimension::NONE),
        ];
        for (src, want) in cases {
            assert_eq!(Dimension::parse(src), Ok(want), "{src}");
        }
        assert!(matches!(
            Dimension::parse("K"),
            Err(DimensionSyntax::UnknownBase { base: 'K', .. })
        ));
        assert!(matches!(
            Dimension::parse("L^"),
            Err(DimensionSyntax::MissingExponent { .. })
        ));
        assert_eq!(
            Dimension::parse("L^").map_err(|e| e.to_string()),
            Err("missing exponent after `^` in `L^`".to_string())
        );
        assert_eq!(
            Dimension::parse("L^1/2").map(|d| d.l),
            Ok(Rational32::new(1, 2))
        );
    }

    #[test]
    fn display() {
        assert_eq!(Dimension::energy().to_string(), "M L² T⁻²");
        assert_eq!(Dimension::energy().plain(), "M L^2 T^-2");
        assert_eq!(Dimension::NONE.to_string(), "dimensionless");
    }

    #[test]
    fn charge_is_shown() {
        let e_field = Dimension::parse("M L T^-2 Q^-1").unwrap();
        assert_eq!(e_field.plain(), "M L T^-2 Q^-1");
        // q·E is a force.
        assert_eq!(Dimension::charge() * e_field, Dimension::new(1, 1, -2));
    }

    #[test]
    fn a_symbolic_exponent_of_constants_is_undecided() {
        let mut pool = Pool::new();
        let r = pool.sym("r");
        let n = pool.sym("n");
        let theta = pool.sym("theta");
        let rn = pool.pow(r, n);
        let rtheta = pool.pow(r, theta);
        let dims = Dimensions::new()
            .with_coordinate("r", Dimension::new(0, 1, 0))
            .with_coordinate("theta", Dimension::NONE)
            .with("n", Dimension::NONE);
        assert_eq!(pool.dimension(rn, &dims), Ok(None));
        // A varying exponent makes a varying dimension: an error.
        assert!(pool.dimension(rtheta, &dims).is_err());
    }
}
