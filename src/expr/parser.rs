//! The parser: tokens to a span-carrying [`Statement`], resolving names against a
//! [`Context`].
//!
//! Precedence, loosest first: `;`, `,`, `=`, `+ -`, `* /` and juxtaposition (one level, left
//! associative, so `1/2 m v^2` is ½·m·v²), unary `-`, `^` (right associative, so `-x^2` is
//! −(x²)), postfix `'` and superscripts. Nesting is limited to [`MAX_DEPTH`], so no input can
//! overflow the stack.

use std::collections::BTreeSet;

use super::ast::{Ast, AstKind, Statement};
use super::context::{Call, Context, Resolved, call_named};
use super::error::{MAX_DEPTH, MAX_INPUT_BYTES, ParseError, ParseErrorKind};
use super::lexer::{Span, Tok, Token, lex};

/// The result of parsing: the statement and any coordinates implied by a derivative mark in
/// an open context (`x'` makes `x` a coordinate).
#[derive(Clone, Debug, PartialEq)]
pub struct Parsed {
    pub statement: Statement,
    pub implied_coordinates: BTreeSet<String>,
}

/// Parses a whole input.
pub fn parse(src: &str, ctx: &Context) -> Result<Parsed, ParseError> {
    if src.len() > MAX_INPUT_BYTES {
        let mut cut = MAX_INPUT_BYTES;
        while !src.is_char_boundary(cut) {
            cut -= 1;
        }
        return Err(ParseError::new(
            ParseErrorKind::TooLong {
                len: src.len(),
                max: MAX_INPUT_BYTES,
            },
            cut..src.len(),
        ));
    }
    let tokens = lex(src)?;
    if tokens.is_empty() {
        return Err(ParseError::new(ParseErrorKind::Empty, 0..src.len()));
    }
    let mut p = Parser {
        tokens,
        pos: 0,
        depth: 0,
        ctx,
        end: src.len(),
        implied: BTreeSet::new(),
    };
    let statement = p.system()?;
    if let Some(t) = p.peek_token() {
        let span = t.span.clone();
        return Err(match t.tok {
            Tok::RParen => ParseError::new(ParseErrorKind::UnmatchedParen, span),
            _ => ParseError::new(ParseErrorKind::UnexpectedChar(first_char(src, &span)), span),
        });
    }
    Ok(Parsed {
        statement,
        implied_coordinates: p.implied,
    })
}

fn first_char(src: &str, span: &Span) -> char {
    src[span.clone()].chars().next().unwrap_or(' ')
}

struct Parser<'c> {
    tokens: Vec<Token>,
    pos: usize,
    depth: usize,
    ctx: &'c Context,
    end: usize,
    implied: BTreeSet<String>,
}

impl Parser<'_> {
    fn peek(&self) -> Option<&Tok> {
        self.tokens.get(self.pos).map(|t| &t.tok)
    }

    fn peek_token(&self) -> Option<&Token> {
        self.tokens.get(self.pos)
    }

    fn peek_at(&self, k: usize) -> Option<&Tok> {
        self.tokens.get(self.pos + k).map(|t| &t.tok)
    }

    fn next(&mut self) -> Option<Token> {
        let t = self.tokens.get(self.pos).cloned();
        self.pos += 1;
        t
    }

    fn eat(&mut self, tok: &Tok) -> bool {
        if self.peek() == Some(tok) {
            self.pos += 1;
            true
        } else {
            false
        }
    }

    /// Span of the next token, or an empty span at the end of input.
    fn here(&self) -> Span {
        self.peek_token()
            .map(|t| t.span.clone())
            .unwrap_or(self.end..self.end)
    }

    fn prev_end(&self) -> usize {
        self.pos
            .checked_sub(1)
            .and_then(|i| self.tokens.get(i))
            .map_or(0, |t| t.span.end)
    }

    fn enter(&mut self, span: &Span) -> Result<(), ParseError> {
        self.depth += 1;
        if self.depth > MAX_DEPTH {
            return Err(ParseError::new(
                ParseErrorKind::TooDeep { max: MAX_DEPTH },
                span.clone(),
            ));
        }
        Ok(())
    }

    fn leave(&mut self) {
        self.depth -= 1;
    }

    fn system(&mut self) -> Result<Statement, ParseError> {
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

    fn sum(&mut self) -> Result<Ast, ParseError> {
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

    fn postfix(&mut self) -> Result<Ast, ParseError> {
        let mut a = self.primary()?;
        let mut primes = 0u8;
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

    /// Whether the next tokens are `(t)`.
    fn at_time_argument(&self) -> bool {
        self.peek() == Some(&Tok::LParen)
            && matches!(self.peek_at(1), Some(Tok::Name { text, dots: 0 }) if text == "t")
            && self.peek_at(2) == Some(&Tok::RParen)
    }

    /// Applies `order` derivative marks to a name read as `a`.
    fn differentiate(&mut self, a: Ast, order: u8, end: usize) -> Result<Ast, ParseError> {
        let span = a.span.start..end;
        match a.kind {
            AstKind::Coordinate { name, order: o } => Ok(Ast {
                kind: AstKind::Coordinate {
                    name,
                    order: o.saturating_add(order),
                },
                span,
            }),
            AstKind::Parameter(name) if self.ctx.is_open() && !self.ctx.is_parameter(&name) => {
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

    fn primary(&mut self) -> Result<Ast, ParseError> {
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

    fn name(&mut self, text: String, dots: u8, span: Span) -> Result<Ast, ParseError> {
        if text == "dot" || text == "ddot" {
            return self.dot_call(&text, span);
        }
        if let Some(call) = call_named(&text) {
            return self.function_call(call, text, span);
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

    /// `a` differentiated `dots` times (combining dots over a name), or `a` itself.
    fn with_dots(&mut self, a: Ast, dots: u8, end: usize) -> Result<Ast, ParseError> {
        if dots > 0 {
            self.differentiate(a, dots, end)
        } else {
            Ok(a)
        }
    }

    /// `sin(…)` and the other named functions: the name must be followed by `(`.
    fn function_call(&mut self, call: Call, text: String, span: Span) -> Result<Ast, ParseError> {
        if self.peek() != Some(&Tok::LParen) {
            return Err(ParseError::new(
                ParseErrorKind::FunctionWithoutArgs { name: text },
                span,
            ));
        }
        let open = self.here();
        self.pos += 1;
        self.enter(&open)?;
        let arg = self.sum();
        self.leave();
        let arg = arg?;
        if !self.eat(&Tok::RParen) {
            return Err(ParseError::new(ParseErrorKind::UnclosedParen, open));
        }
        let end = self.prev_end();
        Ok(Ast {
            kind: AstKind::Call(call, Box::new(arg)),
            span: span.start..end,
        })
    }

    /// A name that is not a function but is followed by `(`: an unknown function (with a
    /// suggestion when it looks like a misspelt one) unless it is a declared name, which
    /// then multiplies the parenthesis.
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

    /// `dot(q)` and `ddot(q)`.
    fn dot_call(&mut self, which: &str, span: Span) -> Result<Ast, ParseError> {
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
        self.differentiate(inner, order + primes, end).map(|a| Ast {
            span: span.start..end,
            ..a
        })
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
