//! The node types of the expression arena: ids, symbols, functions and the node enum itself.
//!
//! A node refers to its children by [`Id`]; children are always created before their parents,
//! so an `Id` is also a topological position (as in egg's `RecExpr`).

use num_rational::BigRational;

/// Index of a node in a [`Pool`](super::Pool). Equal ids in one pool mean equal expressions.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Id(pub(crate) u32);

impl Id {
    /// The position of the node in its pool.
    pub(crate) fn index(self) -> usize {
        self.0 as usize
    }
}

/// An interned symbol name (a coordinate, a parameter or the time `t`).
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub struct Sym(pub(crate) u32);

/// The elementary functions of the language. `sec`, `csc`, `cot`, `sqrt` and `ln` are not
/// here: they are written in terms of these when built.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
pub enum Func {
    Sin,
    Cos,
    Tan,
    Asin,
    Acos,
    Atan,
    Sinh,
    Cosh,
    Tanh,
    Exp,
    Log,
    Abs,
}

impl Func {
    /// Every function, in a fixed order.
    pub const ALL: [Func; 12] = [
        Func::Sin,
        Func::Cos,
        Func::Tan,
        Func::Asin,
        Func::Acos,
        Func::Atan,
        Func::Sinh,
        Func::Cosh,
        Func::Tanh,
        Func::Exp,
        Func::Log,
        Func::Abs,
    ];

    /// The name used when printing in plain syntax.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
            Func::Asin => "asin",
            Func::Acos => "acos",
            Func::Atan => "atan",
            Func::Sinh => "sinh",
            Func::Cosh => "cosh",
            Func::Tanh => "tanh",
            Func::Exp => "exp",
            Func::Log => "log",
            Func::Abs => "abs",
        }
    }

    /// f(−x) = −f(x).
    pub(crate) fn is_odd(self) -> bool {
        matches!(
            self,
            Func::Sin | Func::Tan | Func::Asin | Func::Atan | Func::Sinh | Func::Tanh
        )
    }

    /// f(−x) = f(x).
    pub(crate) fn is_even(self) -> bool {
        matches!(self, Func::Cos | Func::Cosh | Func::Abs)
    }

    /// The argument must be dimensionless (every function here except `abs`).
    pub(crate) fn needs_dimensionless(self) -> bool {
        !matches!(self, Func::Abs)
    }

    /// Numeric value in f64.
    pub(crate) fn apply(self, x: f64) -> f64 {
        self.as_fn()(x)
    }

    /// The function on f64 as a plain function pointer (chosen once for a loop over lanes).
    pub(crate) fn as_fn(self) -> fn(f64) -> f64 {
        match self {
            Func::Sin => f64::sin,
            Func::Cos => f64::cos,
            Func::Tan => f64::tan,
            Func::Asin => f64::asin,
            Func::Acos => f64::acos,
            Func::Atan => f64::atan,
            Func::Sinh => f64::sinh,
            Func::Cosh => f64::cosh,
            Func::Tanh => f64::tanh,
            Func::Exp => f64::exp,
            Func::Log => f64::ln,
            Func::Abs => f64::abs,
        }
    }
}

/// One node of the arena. Sums and products are n-ary, flattened and ordered; numbers are
/// exact rationals. The constructors on [`Pool`](super::Pool) keep these invariants.
#[derive(Clone, PartialEq, Eq, Hash, Debug)]
pub enum Node {
    /// An exact rational number.
    Num(BigRational),
    /// A symbol and its time-derivative order (`q` is 0, `q'` is 1, `q''` is 2).
    Var(Sym, u8),
    /// The constant π.
    Pi,
    /// A sum of at least two terms; a numeric term, if any, comes first.
    Add(Box<[Id]>),
    /// A product of at least two factors; a numeric coefficient, if any, comes first.
    Mul(Box<[Id]>),
    /// Base and exponent.
    Pow(Id, Id),
    /// An elementary function applied to one argument.
    Func(Func, Id),
}
