//! The operator levels of the grammar, loosest first: `;`, `,`, `=`, `+ -`, `* /` and
//! juxtaposition, unary `-`, `^`, postfix `'` and superscripts.

use super::Parser;
use crate::expr::ast::{Ast, AstKind, Statement};
use crate::expr::error::{ParseError, ParseErrorKind};
use crate::expr::lexer::{Span, Tok};

impl Parser<'_> {
    pub(super) fn system(&mut self) -> Result<Statement, ParseError> {
        let mut items = vec![self.list()?];
        while self.eat(&Tok::Semi) {
            items.push(self.list()?);
        }
        Ok(wrap(items, Statement::System))
    }

    fn list(&mut self) -> Result<Statement, ParseError> {
        let mut items = vec![self.item()?];
        while self.eat(&Tok::Comma) {
            items.push(self.item()?);
        }
        Ok(wrap(items, Statement::List))
    }

    fn item(&mut self) -> Result<Statement, ParseError> {
        let lhs = self.sum()?;
        if !self.eat(&Tok::Eq) {
            return Ok(Statement::Expr(lhs));
        }
        let rhs = self.sum()?;
        if self.peek() == Some(&Tok::Eq) {
            return Err(ParseError::new(ParseErrorKind::ChainedEquals, self.here()));
        }
        let span = lhs.span.start..rhs.span.end;
        Ok(Statement::Equation { lhs, rhs, span })
    }

    pub(super) fn sum(&mut self) -> Result<Ast, ParseError> {
        let first = self.product()?;
        let start = first.span.start;
        let mut terms = vec![(false, first)];
        loop {
            let neg = match self.peek() {
                Some(Tok::Plus) => false,
                Some(Tok::Minus) => true,
                _ => break,
            };
            self.pos += 1;
            terms.push((neg, self.product()?));
        }
        if terms.len() == 1 {
            return Ok(terms.pop().map(|(_, a)| a).unwrap_or_else(unreachable_ast));
        }
        let end = terms.last().map_or(start, |(_, a)| a.span.end);
        Ok(Ast {
            kind: AstKind::Sum(terms),
            span: start..end,
        })
    }

    fn product(&mut self) -> Result<Ast, ParseError> {
        let first = self.unary()?;
        let start = first.span.start;
        let mut factors = vec![(false, first)];
        loop {
            match self.peek() {
                Some(Tok::Star) => {
                    self.pos += 1;
                    factors.push((false, self.unary()?));
                }
                Some(Tok::Slash) => {
                    self.pos += 1;
                    factors.push((true, self.unary()?));
                }
                Some(Tok::Num(_)) if matches!(factors.last(), Some((_, a)) if ends_in_number(a)) => {
                    return Err(ParseError::new(
                        ParseErrorKind::MissingOperator,
                        self.here(),
                    ));
                }
                Some(Tok::Num(_) | Tok::Name { .. } | Tok::LParen | Tok::Root) => {
                    factors.push((false, self.power()?));
                }
                _ => break,
            }
        }
        if factors.len() == 1 {
            return Ok(factors
                .pop()
                .map(|(_, a)| a)
                .unwrap_or_else(unreachable_ast));
        }
        let end = factors.last().map_or(start, |(_, a)| a.span.end);
        Ok(Ast {
            kind: AstKind::Product(factors),
            span: start..end,
        })
    }

    fn unary(&mut self) -> Result<Ast, ParseError> {
        match self.peek() {
            Some(Tok::Minus) => {
                let span = self.here();
                self.pos += 1;
                self.enter(&span)?;
                let inner = self.unary();
                self.leave();
                let inner = inner?;
                let span = span.start..inner.span.end;
                Ok(Ast {
                    kind: AstKind::Neg(Box::new(inner)),
                    span,
                })
            }
            Some(Tok::Plus) => {
                let span = self.here();
                self.pos += 1;
                self.enter(&span)?;
                let inner = self.unary();
                self.leave();
                inner
            }
            _ => self.power(),
        }
    }

    fn power(&mut self) -> Result<Ast, ParseError> {
        let base = self.postfix()?;
        if !self.eat(&Tok::Caret) {
            return Ok(base);
        }
        let span = self.here();
        self.enter(&span)?;
        let exp = self.unary();
        self.leave();
        let exp = exp?;
        let span = base.span.start..exp.span.end;
        Ok(Ast {
            kind: AstKind::Pow(Box::new(base), Box::new(exp)),
            span,
        })
    }

    pub(super) fn postfix(&mut self) -> Result<Ast, ParseError> {
        let a = self.primary()?;
        let mut a = self.primes(a)?;
        while let Some(Tok::Super(n)) = self.peek().cloned() {
            let sp = self.here();
            self.pos += 1;
            let exp = Ast {
                kind: AstKind::Num(num_rational::BigRational::from_integer(n)),
                span: sp.clone(),
            };
            let span = a.span.start..sp.end;
            a = Ast {
                kind: AstKind::Pow(Box::new(a), Box::new(exp)),
                span,
            };
        }
        Ok(a)
    }

    /// The derivative marks (`'`) after a primary, and a following `(t)`.
    pub(super) fn primes(&mut self, mut a: Ast) -> Result<Ast, ParseError> {
        let mut primes = 0u32;
        let mut prime_span = a.span.clone();
        while self.peek() == Some(&Tok::Prime) {
            prime_span = self.here();
            self.pos += 1;
            primes = primes.saturating_add(1);
        }
        if primes > 0 {
            a = self.differentiate(a, primes, prime_span.end)?;
            // `theta'(t)`: the derivative written as a function of time.
            if matches!(a.kind, AstKind::Coordinate { .. }) && self.at_time_argument() {
                self.pos += 3;
                a.span.end = self.prev_end();
            }
        }
        Ok(a)
    }
}

fn ends_in_number(a: &Ast) -> bool {
    match &a.kind {
        AstKind::Num(_) => true,
        AstKind::Product(f) => f.last().is_some_and(|(_, x)| ends_in_number(x)),
        _ => false,
    }
}

fn wrap(mut items: Vec<Statement>, f: fn(Vec<Statement>, Span) -> Statement) -> Statement {
    if items.len() == 1 {
        return items
            .pop()
            .unwrap_or_else(|| Statement::Expr(unreachable_ast()));
    }
    let span =
        items.first().map_or(0, |s| s.span().start)..items.last().map_or(0, |s| s.span().end);
    f(items, span)
}

/// Never reached: callers check lengths first. Kept instead of `unwrap` so the parser has no
/// panicking path at all.
fn unreachable_ast() -> Ast {
    Ast {
        kind: AstKind::Num(num_rational::BigRational::default()),
        span: 0..0,
    }
}
