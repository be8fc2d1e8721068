//! Primaries: numbers, parentheses, names resolved against the context, function calls,
//! `dot(q)`/`ddot(q)`, and derivative marks (primes and combining dots).

use super::Parser;
use crate::expr::ast::{Ast, AstKind};
use crate::expr::context::{Call, Context, Resolved, call_named};
use crate::expr::error::{MAX_DERIVATIVE_ORDER, ParseError, ParseErrorKind};
use crate::expr::lexer::{Span, Tok};

impl Parser<'_> {
    /// Whether the next tokens are `(t)`.
    pub(super) fn at_time_argument(&self) -> bool {
        self.peek() == Some(&Tok::LParen)
            && matches!(self.peek_at(1), Some(Tok::Name { text, dots: 0 }) if text == "t")
            && self.peek_at(2) == Some(&Tok::RParen)
    }

    /// Applies `order` derivative marks to a name read as `a`; a total order beyond
    /// [`MAX_DERIVATIVE_ORDER`] is refused at the marks, never wrapped or cut.
    pub(super) fn differentiate(
        &mut self,
        a: Ast,
        order: u32,
        end: usize,
    ) -> Result<Ast, ParseError> {
        let span = a.span.start..end;
        let bounded = |total: u32| {
            u8::try_from(total)
                .ok()
                .filter(|&o| usize::from(o) <= MAX_DERIVATIVE_ORDER)
                .ok_or_else(|| {
                    ParseError::new(
                        ParseErrorKind::OrderTooHigh {
                            order: total,
                            max: MAX_DERIVATIVE_ORDER,
                        },
                        span.clone(),
                    )
                })
        };
        match a.kind {
            AstKind::Coordinate { name, order: o } => Ok(Ast {
                kind: AstKind::Coordinate {
                    name,
                    order: bounded(u32::from(o).saturating_add(order))?,
                },
                span,
            }),
            AstKind::Parameter(name) if self.ctx.is_open() && !self.ctx.is_parameter(&name) => {
                let order = bounded(order)?;
                self.implied.insert(name.clone());
                Ok(Ast {
                    kind: AstKind::Coordinate { name, order },
                    span,
                })
            }
            AstKind::Parameter(name) => Err(ParseError::new(
                ParseErrorKind::NotACoordinate { name },
                a.span,
            )),
            AstKind::Time | AstKind::Pi => Err(ParseError::new(
                ParseErrorKind::NotACoordinate {
                    name: if matches!(a.kind, AstKind::Time) {
                        "t"
                    } else {
                        "pi"
                    }
                    .into(),
                },
                a.span,
            )),
            _ => Err(ParseError::new(ParseErrorKind::PrimeWithoutName, span)),
        }
    }

    pub(super) fn primary(&mut self) -> Result<Ast, ParseError> {
        let Some(tok) = self.next() else {
            // Point at the operator left dangling at the end.
            let span = self.tokens.last().map_or(0..self.end, |t| t.span.clone());
            return Err(ParseError::new(
                ParseErrorKind::MissingOperand {
                    context: "at the end of the input".into(),
                },
                span,
            ));
        };
        let span = tok.span.clone();
        match tok.tok {
            Tok::Num(v) => Ok(Ast {
                kind: AstKind::Num(v),
                span,
            }),
            Tok::LParen => {
                self.enter(&span)?;
                let inner = self.sum();
                self.leave();
                let inner = inner?;
                if !self.eat(&Tok::RParen) {
                    return Err(match self.peek() {
                        None | Some(Tok::Comma | Tok::Semi | Tok::Eq) => {
                            ParseError::new(ParseErrorKind::UnclosedParen, span)
                        }
                        Some(t) => ParseError::new(
                            ParseErrorKind::MissingOperand {
                                context: format!("or `)` before {}", t.describe()),
                            },
                            self.here(),
                        ),
                    });
                }
                let end = self.prev_end();
                Ok(Ast {
                    kind: inner.kind,
                    span: span.start..end,
                })
            }
            Tok::Root => {
                self.enter(&span)?;
                let arg = self.postfix();
                self.leave();
                let arg = arg?;
                let span = span.start..arg.span.end;
                Ok(Ast {
                    kind: AstKind::Call(Call::Sqrt, Box::new(arg)),
                    span,
                })
            }
            Tok::Name { text, dots } => self.name(text, dots, span),
            Tok::RParen => Err(ParseError::new(ParseErrorKind::UnmatchedParen, span)),
            other => Err(ParseError::new(
                ParseErrorKind::MissingOperand {
                    context: format!("before {}", other.describe()),
                },
                span,
            )),
        }
    }

    fn name(&mut self, text: String, dots: u32, span: Span) -> Result<Ast, ParseError> {
        if text == "dot" || text == "ddot" {
            return self.dot_call(&text, span);
        }
        if let Some(call) = call_named(&text) {
            return self.function_call(call, span);
        }
        if dots == 0 && !self.ctx.is_declared(&text) {
            if text == "d" && self.at_time_derivative() {
                return self.time_derivative(span);
            }
            if let Some(a) = self.leibniz(&text, &span) {
                return Ok(a);
            }
            if let Some(root) = self.sqrt_of_digits(&text, &span) {
                return Ok(root);
            }
            if let Some(value) = self.defined(&text, &span) {
                return value;
            }
        }
        let resolved = self.ctx.resolve(&text);
        // `theta(t)`: a coordinate written as a function of time is the coordinate itself.
        if let Some(Resolved::Coordinate(name, order)) = &resolved
            && self.at_time_argument()
        {
            self.pos += 3;
            let end = self.prev_end();
            let a = Ast {
                kind: AstKind::Coordinate {
                    name: name.clone(),
                    order: *order,
                },
                span: span.start..end,
            };
            return self.with_dots(a, dots, end);
        }
        if self.peek() == Some(&Tok::LParen) {
            self.check_called_name(&text, resolved.as_ref(), &span)?;
        }
        let Some(resolved) = resolved else {
            return Err(ParseError::new(
                ParseErrorKind::UnknownName {
                    suggestion: self.ctx.suggest(&text),
                    split: self.ctx.split(&text),
                    name: text,
                },
                span,
            ));
        };
        let kind = match resolved {
            Resolved::Coordinate(name, order) => AstKind::Coordinate { name, order },
            Resolved::Parameter(name) => AstKind::Parameter(name),
            Resolved::Time => AstKind::Time,
            Resolved::Pi => AstKind::Pi,
        };
        let end = span.end;
        self.with_dots(Ast { kind, span }, dots, end)
    }

    /// A name the problem defines (`θ₀`), read as its value in parentheses, every node
    /// placed at the name (its text is the problem's, not the student's). `None` for a name
    /// that is not a definition.
    fn defined(&mut self, text: &str, span: &Span) -> Option<Result<Ast, ParseError>> {
        let value = self.ctx.definition(text)?;
        let inner = self.ctx.without_definitions();
        let parsed = match super::parse(value, &inner) {
            Ok(p) => p,
            // A definition that does not read here (a part substituted a parameter it uses
            // away): the name is unknown in this part.
            Err(_) => {
                return Some(Err(ParseError::new(
                    ParseErrorKind::UnknownName {
                        name: text.to_string(),
                        suggestion: None,
                        split: None,
                    },
                    span.clone(),
                )));
            }
        };
        let crate::expr::ast::Statement::Expr(mut a) = parsed.statement else {
            return None;
        };
        place_at(&mut a, span);
        Some(Ok(a))
    }

    /// `a` differentiated `dots` times (combining dots over a name), or `a` itself.
    fn with_dots(&mut self, a: Ast, dots: u32, end: usize) -> Result<Ast, ParseError> {
        if dots > 0 {
            self.differentiate(a, dots, end)
        } else {
            Ok(a)
        }
    }

    /// A name that is not a function but is followed by `(`: an unknown function (with a
    /// suggestion when it looks like a misspelt one) unless it is a declared name, which
    /// then multiplies the parenthesis (as does, in an open context, a name a space away).
    fn check_called_name(
        &self,
        text: &str,
        resolved: Option<&Resolved>,
        span: &Span,
    ) -> Result<(), ParseError> {
        let declared = matches!(
            resolved,
            Some(Resolved::Coordinate(..) | Resolved::Pi | Resolved::Time)
        ) || self.ctx.is_parameter(text);
        // `m g l (1 − cos θ)` in an open context: a name a space away from `(` is a factor,
        // even when it is one letter from a function name (`l`, `ln`); `f(x)` stays a call.
        let spaced = self.here().start > span.end;
        if resolved.is_some() && spaced {
            return Ok(());
        }
        if !declared && let Some(s) = Context::suggest_function(text) {
            return Err(ParseError::new(
                ParseErrorKind::UnknownFunction {
                    name: text.to_string(),
                    suggestion: Some(s),
                },
                span.clone(),
            ));
        }
        if resolved.is_none() {
            return Err(ParseError::new(
                ParseErrorKind::UnknownFunction {
                    name: text.to_string(),
                    suggestion: None,
                },
                span.clone(),
            ));
        }
        Ok(())
    }
}

/// Places every node of `a` at `span` (a definition's value read where its name stands).
fn place_at(a: &mut Ast, span: &Span) {
    a.span = span.clone();
    match &mut a.kind {
        AstKind::Neg(x) | AstKind::Call(_, x) | AstKind::Dt(x) => place_at(x, span),
        AstKind::Pow(x, y) => {
            place_at(x, span);
            place_at(y, span);
        }
        AstKind::Sum(xs) | AstKind::Product(xs) => {
            for (_, x) in xs {
                place_at(x, span);
            }
        }
        AstKind::Num(_)
        | AstKind::Pi
        | AstKind::Time
        | AstKind::Coordinate { .. }
        | AstKind::Parameter(_) => {}
    }
}
