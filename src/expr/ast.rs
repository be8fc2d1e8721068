//! The syntax tree the parser produces: every node carries the byte span it was read from.
//! Names are already resolved against the context; lowering to canonical [`Id`](super::Id)s happens in
//! `lower.rs`.

use num_rational::BigRational;

use super::context::Call;
use super::lexer::Span;

/// One node of the syntax tree.
#[derive(Clone, Debug, PartialEq)]
pub struct Ast {
    pub(crate) kind: AstKind,
    pub(crate) span: Span,
}

/// The node kinds.
#[derive(Clone, Debug, PartialEq)]
pub enum AstKind {
    Num(BigRational),
    Pi,
    Time,
    /// A coordinate with its derivative order.
    Coordinate {
        name: String,
        order: u8,
    },
    Parameter(String),
    Neg(Box<Ast>),
    /// Terms, each with `true` when subtracted.
    Sum(Vec<(bool, Ast)>),
    /// Factors, each with `true` when divided by.
    Product(Vec<(bool, Ast)>),
    Pow(Box<Ast>, Box<Ast>),
    Call(Call, Box<Ast>),
    /// `d/dt(…)`: the total time derivative of the argument.
    Dt(Box<Ast>),
}

/// What a whole input is: an expression, an equation, or lists of them.
#[derive(Clone, Debug, PartialEq)]
pub enum Statement {
    Expr(Ast),
    Equation {
        lhs: Ast,
        rhs: Ast,
        span: Span,
    },
    /// Items separated by `,`.
    List(Vec<Statement>, Span),
    /// Items separated by `;` (the equations of a system).
    System(Vec<Statement>, Span),
}

impl Statement {
    /// The span of the whole statement.
    pub fn span(&self) -> Span {
        match self {
            Statement::Expr(a) => a.span.clone(),
            Statement::Equation { span, .. }
            | Statement::List(_, span)
            | Statement::System(_, span) => span.clone(),
        }
    }
}
