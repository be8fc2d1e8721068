//! Function calls and the notations built on them: `sin(θ)`, a bare argument (`sin θ`,
//! `sin 2θ`), powers of functions (`sin^2(θ)`, `sin²θ`, `cos^2 θ`), `dot(q)`/`ddot(q)`,
//! `sqrt2`, and the total time derivative `d/dt(…)`.
//!
//! The bare-argument rule: without `(`, a function's argument is the shortest factor that
//! follows — an optional number and one name with its derivative marks (`sin 2θ'` is
//! sin(2θ′)); what comes after multiplies (`sin θ x` is sin(θ)·x). Where that factor is
//! followed by something that could belong to it — an exponent (`sin θ²`), a `/` written
//! against it (`sin θ/2`; `sin θ / k` with a space divides the product), or a name or
//! bracket written against it (`sin ωt`) — the input is refused with both readings proposed,
//! since readers disagree.

use num_bigint::BigInt;
use num_traits::Signed;

use super::Parser;
use crate::expr::ast::{Ast, AstKind};
use crate::expr::context::{Call, Resolved, call_named};
use crate::expr::error::{ParseError, ParseErrorKind};
use crate::expr::lexer::{Span, Tok, Token};

impl Parser<'_> {
    /// `sin(…)`, `sin θ`, `sin^2(θ)`, `sin²θ`: `span` is the function name's.
    pub(super) fn function_call(&mut self, call: Call, span: Span) -> Result<Ast, ParseError> {
        let power = self.function_power(&span)?;
        let arg = if self.peek() == Some(&Tok::LParen) {
            self.parenthesized()?
        } else {
            self.bare_argument(&span)?
        };
        let end = self.prev_end();
        let mut a = Ast {
            kind: AstKind::Call(call, Box::new(arg)),
            span: span.start..end,
        };
        if let Some((n, sp)) = power {
            let exp = Ast {
                kind: AstKind::Num(num_rational::BigRational::from_integer(n)),
                span: sp,
            };
            a = Ast {
                span: a.span.clone(),
                kind: AstKind::Pow(Box::new(a), Box::new(exp)),
            };
        }
        Ok(a)
    }

    /// The power written on a function name (`sin²`, `sin^2`): a positive integer. `sin⁻¹`
    /// and `sin^-1` are refused: some mean arcsin by them, others 1/sin.
    fn function_power(&mut self, name: &Span) -> Result<Option<(BigInt, Span)>, ParseError> {
        let (n, len) = match (self.peek(), self.peek_at(1)) {
            (Some(Tok::Super(n)), _) => (n.clone(), 1),
            (Some(Tok::Caret), Some(Tok::Num(v))) if v.is_integer() => (v.to_integer(), 2),
            (Some(Tok::Caret), Some(Tok::Minus)) => (BigInt::from(-1), 2),
            _ => return Ok(None),
        };
        let sp = self.here();
        if !n.is_positive() || n > BigInt::from(64) {
            let text = self.src.get(name.clone()).unwrap_or("f").to_string();
            return Err(ParseError::new(
                ParseErrorKind::InversePower { name: text },
                name.start..sp.end,
            ));
        }
        self.pos += len;
        let end = self.prev_end();
        Ok(Some((n, sp.start..end)))
    }

    /// `( … )` (or `[ … ]`) after a function name: the argument, its span the brackets'.
    pub(super) fn parenthesized(&mut self) -> Result<Ast, ParseError> {
        let open = self.here();
        self.pos += 1;
        self.enter(&open)?;
        let arg = self.sum();
        self.leave();
        let arg = arg?;
        if !self.eat(&Tok::RParen) {
            return Err(ParseError::new(ParseErrorKind::UnclosedParen, open));
        }
        Ok(arg)
    }

    /// The argument of a function written without `(`: an optional number and one name with
    /// its derivative marks (see the module's rule).
    fn bare_argument(&mut self, name: &Span) -> Result<Ast, ParseError> {
        let without = || {
            ParseError::new(
                ParseErrorKind::FunctionWithoutArgs {
                    name: self.src.get(name.clone()).unwrap_or("f").to_string(),
                },
                name.clone(),
            )
        };
        let mut factors = Vec::new();
        if let Some(Token {
            tok: Tok::Num(v),
            span,
        }) = self.peek_token().cloned()
        {
            self.pos += 1;
            factors.push((
                false,
                Ast {
                    kind: AstKind::Num(v),
                    span,
                },
            ));
        }
        if let Some(Tok::Name { text, .. }) = self.peek()
            && !is_function_name(text)
        {
            let a = self.primary()?;
            factors.push((false, self.primes(a)?));
        }
        let (Some((_, first)), Some((_, last))) = (factors.first(), factors.last()) else {
            return Err(without());
        };
        let arg_span = first.span.start..last.span.end;
        self.refuse_ambiguous(name, &arg_span)?;
        Ok(if factors.len() == 1 {
            factors.pop().map(|(_, a)| a).ok_or_else(without)?
        } else {
            Ast {
                kind: AstKind::Product(factors),
                span: arg_span,
            }
        })
    }

    /// Refuses `sin θ²`, `sin θ^2`, `sin θ/2` and `sin ωt`, proposing both readings.
    fn refuse_ambiguous(&self, name: &Span, arg: &Span) -> Result<(), ParseError> {
        let Some(next) = self.peek_token() else {
            return Ok(());
        };
        let (op, operand) = match next.tok {
            Tok::Super(_) => ("", next.span.clone()),
            // `sin θ / k` (a space before `/`) divides the product; `sin θ/k` is refused.
            Tok::Slash if next.span.start > arg.end => return Ok(()),
            Tok::Caret | Tok::Slash => match self.tokens.get(self.pos + 1) {
                Some(t) => (self.text(&next.span), t.span.clone()),
                None => return Ok(()),
            },
            Tok::Name { .. } | Tok::LParen | Tok::Root | Tok::Num(_)
                if next.span.start == arg.end =>
            {
                ("", next.span.clone())
            }
            _ => return Ok(()),
        };
        let f = self.text(name);
        let a = self.text(arg);
        let n = match self.text(&operand) {
            "(" | "[" => "(…)",
            t => t,
        };
        Err(ParseError::new(
            ParseErrorKind::AmbiguousArgument {
                one: format!("{f}({a}{op}{n})"),
                other: format!("{f}({a}){op}{n}"),
            },
            name.start..operand.end,
        ))
    }

    fn text(&self, span: &Span) -> &str {
        self.src.get(span.clone()).unwrap_or("")
    }

    /// Whether `/ dt (` follows (after a `d` that is not a declared name).
    pub(super) fn at_time_derivative(&self) -> bool {
        self.peek() == Some(&Tok::Slash)
            && matches!(self.peek_at(1), Some(Tok::Name { text, dots: 0 }) if text == "dt")
            && !self.ctx.is_declared("dt")
            && self.peek_at(2) == Some(&Tok::LParen)
    }

    /// Leibniz notation for a coordinate's derivative: `dθ/dt` (also `dx/dt`, one name
    /// `dx`), `d²θ/dt²` and `d^2θ/dt^2` are θ' and θ'' (`text` is the name just read, a `d`
    /// that no symbol of the problem is called). `None` when what follows is not that form,
    /// so the name is read as before (a parameter's `dm/dt` stays an unknown name).
    pub(super) fn leibniz(&mut self, text: &str, span: &Span) -> Option<Ast> {
        if self.ctx.is_declared("dt") {
            return None;
        }
        // The order written after the `d` (`²`, `^2`), and how many tokens it takes.
        let order_at = |p: &Self, k: usize| -> Option<(u32, usize)> {
            let small =
                |n: &num_bigint::BigInt| u32::try_from(n).ok().filter(|&o| (1..=4).contains(&o));
            match (p.peek_at(k), p.peek_at(k + 1)) {
                (Some(Tok::Super(n)), _) => Some((small(n)?, 1)),
                (Some(Tok::Caret), Some(Tok::Num(r))) if r.is_integer() => {
                    Some((small(r.numer())?, 2))
                }
                _ => None,
            }
        };
        // `d` then the coordinate as its own token, or `dx` as one name.
        let (order, name, mut k) = if text == "d" {
            let (order, used) = order_at(self, 0).unwrap_or((1, 0));
            match self.peek_at(used) {
                Some(Tok::Name { text: q, dots: 0 }) => (order, q.clone(), used + 1),
                _ => return None,
            }
        } else {
            (1, text.strip_prefix('d')?.to_string(), 0)
        };
        if !matches!(self.ctx.resolve(&name), Some(Resolved::Coordinate(_, 0))) {
            return None;
        }
        if self.peek_at(k) != Some(&Tok::Slash)
            || !matches!(self.peek_at(k + 1), Some(Tok::Name { text, dots: 0 }) if text == "dt")
        {
            return None;
        }
        k += 2;
        let below = match order_at(self, k) {
            Some((o, used)) => {
                k += used;
                o
            }
            None => 1,
        };
        if below != order {
            return None;
        }
        self.pos += k;
        let end = self.prev_end();
        let name = match self.ctx.resolve(&name) {
            Some(Resolved::Coordinate(n, _)) => n,
            _ => return None,
        };
        Some(Ast {
            kind: AstKind::Coordinate {
                name,
                order: u8::try_from(order).unwrap_or(1),
            },
            span: span.start..end,
        })
    }

    /// `d/dt(…)`: the total time derivative of the bracket (`span` is the `d`'s).
    pub(super) fn time_derivative(&mut self, span: Span) -> Result<Ast, ParseError> {
        self.pos += 2;
        let arg = self.parenthesized()?;
        Ok(Ast {
            kind: AstKind::Dt(Box::new(arg)),
            span: span.start..self.prev_end(),
        })
    }

    /// `sqrt2`, `sqrt3`: the lexer reads them as one name; they are √2, √3.
    pub(super) fn sqrt_of_digits(&self, text: &str, span: &Span) -> Option<Ast> {
        let digits = text.strip_prefix("sqrt")?;
        if digits.is_empty() || digits.len() > 6 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let n: BigInt = digits.parse().ok()?;
        let arg = Ast {
            kind: AstKind::Num(num_rational::BigRational::from_integer(n)),
            span: span.start + 4..span.end,
        };
        Some(Ast {
            kind: AstKind::Call(Call::Sqrt, Box::new(arg)),
            span: span.clone(),
        })
    }

    /// `dot(q)` and `ddot(q)`.
    pub(super) fn dot_call(&mut self, which: &str, span: Span) -> Result<Ast, ParseError> {
        let order = if which == "dot" { 1 } else { 2 };
        let bad = || {
            ParseError::new(
                ParseErrorKind::DotNeedsName {
                    name: which.to_string(),
                },
                span.clone(),
            )
        };
        if self.peek() != Some(&Tok::LParen) {
            return Err(ParseError::new(
                ParseErrorKind::FunctionWithoutArgs {
                    name: which.to_string(),
                },
                span,
            ));
        }
        let open = self.here();
        self.pos += 1;
        let Some(Token {
            tok: Tok::Name { text, dots },
            span: name_span,
        }) = self.next()
        else {
            return Err(bad());
        };
        // `dot(sqrt)`: a function's name is never a coordinate (it would print as `sqrt'`,
        // which reads as a function without its argument).
        if is_function_name(&text) {
            return Err(bad());
        }
        let mut primes = dots;
        while self.eat(&Tok::Prime) {
            primes = primes.saturating_add(1);
        }
        if !self.eat(&Tok::RParen) {
            return Err(ParseError::new(ParseErrorKind::UnclosedParen, open));
        }
        let end = self.prev_end();
        let inner = match self.ctx.resolve(&text) {
            Some(Resolved::Coordinate(name, o)) => Ast {
                kind: AstKind::Coordinate { name, order: o },
                span: name_span,
            },
            Some(Resolved::Parameter(name)) => Ast {
                kind: AstKind::Parameter(name),
                span: name_span,
            },
            Some(_) => return Err(bad()),
            None => {
                return Err(ParseError::new(
                    ParseErrorKind::UnknownName {
                        suggestion: self.ctx.suggest(&text),
                        split: None,
                        name: text,
                    },
                    name_span,
                ));
            }
        };
        self.differentiate(inner, primes.saturating_add(order), end)
            .map(|a| Ast {
                span: span.start..end,
                ..a
            })
    }
}

/// Names that are functions (or `dot`/`ddot`), which cannot be a bare argument.
fn is_function_name(text: &str) -> bool {
    text == "dot" || text == "ddot" || call_named(text).is_some()
}
