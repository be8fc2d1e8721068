//! Lowering: the span-carrying syntax tree to canonical expressions in a [`Pool`], and the
//! convenience readers (`read_expr`, `read_equation`, `read`) most callers use.

use super::ast::{Ast, AstKind, Statement};
use super::context::{Call, Context};
use super::error::{ParseError, ParseErrorKind};
use super::lexer::Span;
use super::node::{Func, Id};
use super::parser::parse;
use super::pool::Pool;

/// An input read into a pool: an expression, an equation `lhs = rhs`, or lists of them.
#[derive(Clone, Debug, PartialEq)]
pub enum Reading {
    Expr(Id, Span),
    Equation { lhs: Id, rhs: Id, span: Span },
    List(Vec<Reading>, Span),
    System(Vec<Reading>, Span),
}

impl Reading {
    /// The span of the input this came from.
    pub fn span(&self) -> Span {
        match self {
            Reading::Expr(_, s)
            | Reading::Equation { span: s, .. }
            | Reading::List(_, s)
            | Reading::System(_, s) => s.clone(),
        }
    }

    /// The reading in Unicode: an expression, `lhs = rhs`, or items joined by `, ` (a list)
    /// or `; ` (a system).
    pub fn unicode(&self, pool: &Pool) -> String {
        let join = |items: &[Reading], sep: &str| {
            let shown: Vec<String> = items.iter().map(|i| i.unicode(pool)).collect();
            shown.join(sep)
        };
        match self {
            Reading::Expr(id, _) => pool.unicode(*id),
            Reading::Equation { lhs, rhs, .. } => {
                format!("{} = {}", pool.unicode(*lhs), pool.unicode(*rhs))
            }
            Reading::List(items, _) => join(items, ", "),
            Reading::System(items, _) => join(items, "; "),
        }
    }
}

/// Lowers one syntax node. Recursion follows the syntax tree, whose depth the parser limits.
pub(crate) fn lower(pool: &mut Pool, ast: &Ast) -> Id {
    match &ast.kind {
        AstKind::Num(v) => pool.num(v.clone()),
        AstKind::Pi => pool.pi(),
        AstKind::Time => {
            let t = pool.time();
            pool.var(t, 0)
        }
        AstKind::Coordinate { name, order } => {
            let s = pool.symbol(name);
            pool.var(s, *order)
        }
        AstKind::Parameter(name) => pool.sym(name),
        AstKind::Neg(a) => {
            let x = lower(pool, a);
            pool.neg(x)
        }
        AstKind::Sum(terms) => {
            let ids: Vec<Id> = terms
                .iter()
                .map(|(neg, a)| {
                    let x = lower(pool, a);
                    if *neg { pool.neg(x) } else { x }
                })
                .collect();
            pool.sum(ids)
        }
        AstKind::Product(factors) => {
            // Left to right, so `a/b*c` is (a/b)·c.
            let ids: Vec<Id> = factors
                .iter()
                .map(|(div, a)| {
                    let x = lower(pool, a);
                    if *div { pool.recip(x) } else { x }
                })
                .collect();
            pool.product(ids)
        }
        AstKind::Pow(b, e) => {
            let b = lower(pool, b);
            let e = lower(pool, e);
            pool.pow(b, e)
        }
        AstKind::Dt(a) => {
            let x = lower(pool, a);
            let mut names = Vec::new();
            coordinates_in(a, &mut names);
            let coords: Vec<_> = names.iter().map(|n| pool.symbol(n)).collect();
            pool.dt(x, &coords)
        }
        AstKind::Call(call, a) => {
            let x = lower(pool, a);
            match call {
                Call::F(f) => pool.func(*f, x),
                Call::Sqrt => pool.sqrt(x),
                Call::Sec => {
                    let c = pool.func(Func::Cos, x);
                    pool.recip(c)
                }
                Call::Csc => {
                    let s = pool.func(Func::Sin, x);
                    pool.recip(s)
                }
                Call::Cot => {
                    let c = pool.func(Func::Cos, x);
                    let s = pool.func(Func::Sin, x);
                    pool.div(c, s)
                }
            }
        }
    }
}

/// The coordinates named in `ast` (for `d/dt`, which moves each up one order). Recursion
/// follows the syntax tree, whose depth the parser limits.
fn coordinates_in(ast: &Ast, out: &mut Vec<String>) {
    match &ast.kind {
        AstKind::Coordinate { name, .. } => {
            if !out.contains(name) {
                out.push(name.clone());
            }
        }
        AstKind::Neg(a) | AstKind::Call(_, a) | AstKind::Dt(a) => coordinates_in(a, out),
        AstKind::Sum(xs) | AstKind::Product(xs) => {
            xs.iter().for_each(|(_, a)| coordinates_in(a, out));
        }
        AstKind::Pow(b, e) => {
            coordinates_in(b, out);
            coordinates_in(e, out);
        }
        AstKind::Num(_) | AstKind::Pi | AstKind::Time | AstKind::Parameter(_) => {}
    }
}

/// Lowers a whole statement.
pub(crate) fn lower_statement(pool: &mut Pool, st: &Statement) -> Reading {
    match st {
        Statement::Expr(a) => Reading::Expr(lower(pool, a), a.span.clone()),
        Statement::Equation { lhs, rhs, span } => Reading::Equation {
            lhs: lower(pool, lhs),
            rhs: lower(pool, rhs),
            span: span.clone(),
        },
        Statement::List(items, span) => Reading::List(
            items.iter().map(|s| lower_statement(pool, s)).collect(),
            span.clone(),
        ),
        Statement::System(items, span) => Reading::System(
            items.iter().map(|s| lower_statement(pool, s)).collect(),
            span.clone(),
        ),
    }
}

/// Reads any input.
pub fn read(src: &str, ctx: &Context, pool: &mut Pool) -> Result<Reading, ParseError> {
    let parsed = parse(src, ctx)?;
    Ok(lower_statement(pool, &parsed.statement))
}

/// Reads a single expression; an `=` or a list is an error.
pub fn read_expr(src: &str, ctx: &Context, pool: &mut Pool) -> Result<Id, ParseError> {
    match read(src, ctx, pool)? {
        Reading::Expr(id, _) => Ok(id),
        Reading::Equation { span, .. } => Err(ParseError::new(
            ParseErrorKind::EquationNotAllowed,
            equals_span(src, &span),
        )),
        Reading::List(_, span) | Reading::System(_, span) => {
            Err(ParseError::new(ParseErrorKind::ListNotAllowed, span))
        }
    }
}

/// Reads a single equation; a bare expression `e` is read as `e = 0`.
pub fn read_equation(src: &str, ctx: &Context, pool: &mut Pool) -> Result<(Id, Id), ParseError> {
    match read(src, ctx, pool)? {
        Reading::Expr(id, _) => Ok((id, pool.zero())),
        Reading::Equation { lhs, rhs, .. } => Ok((lhs, rhs)),
        Reading::List(_, span) | Reading::System(_, span) => {
            Err(ParseError::new(ParseErrorKind::ListNotAllowed, span))
        }
    }
}

/// The span of the first `=` inside `span`, for pointing at it.
fn equals_span(src: &str, span: &Span) -> Span {
    src.get(span.clone())
        .and_then(|s| s.find('='))
        .map_or(span.clone(), |i| span.start + i..span.start + i + 1)
}
