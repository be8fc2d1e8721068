//! The parser: tokens to a span-carrying `Statement`, resolving names against a
//! [`Context`].
//!
//! Precedence, loosest first: `;`, `,`, `=`, `+ -`, `* /` and juxtaposition (one level, left
//! associative, so `1/2 m v^2` is ½·m·v²), unary `-`, `^` (right associative, so `-x^2` is
//! −(x²)), postfix `'` and superscripts. Nesting is limited to [`MAX_DEPTH`], so no input can
//! overflow the stack.
//!
//! A function name without `(` takes the shortest factor after it: an optional number and one
//! name with its primes (`sin 2θ` = sin(2θ), `sin θ x` = sin(θ)·x); what could also belong
//! to it (`sin θ²`, `sin θ/2`, `sin ωt`) is refused with both readings. A power may sit on
//! the name (`sin²θ`, `sin^2(θ)` = (sin θ)²). `d/dt(…)` is the total time derivative. See
//! `calls`.
//!
//! Here: the entry point [`parse`] and the parser's token cursor and depth guard. The
//! operator levels (`;` down to `'`) live in `operators`, the primaries (numbers, names,
//! calls, derivative marks) in `atoms`.

mod atoms;
mod calls;
mod lines;
mod operators;

use std::collections::BTreeSet;

use super::ast::Statement;
use super::context::Context;
use super::error::{MAX_DEPTH, ParseError, ParseErrorKind};
use super::lexer::{Span, Tok, Token, lex};

/// The result of parsing: the statement and any coordinates implied by a derivative mark in
/// an open context (`x'` makes `x` a coordinate).
#[derive(Clone, Debug, PartialEq)]
pub struct Parsed {
    pub(crate) statement: Statement,
    pub implied_coordinates: BTreeSet<String>,
}

/// Parses a whole input.
pub fn parse(src: &str, ctx: &Context) -> Result<Parsed, ParseError> {
    let max = ctx.max_input();
    if src.len() > max {
        let mut cut = max;
        while !src.is_char_boundary(cut) {
            cut -= 1;
        }
        return Err(ParseError::new(
            ParseErrorKind::TooLong {
                len: src.len(),
                max,
            },
            cut..src.len(),
        ));
    }
    // Equations one a line are separated as by `;` (same length: spans are unchanged).
    let lined = lines::separate_lines(src);
    let src = lined.as_ref();
    let tokens = lex(src)?;
    if tokens.is_empty() {
        return Err(ParseError::new(ParseErrorKind::Empty, 0..src.len()));
    }
    let mut p = Parser {
        tokens,
        pos: 0,
        depth: 0,
        ctx,
        src,
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
    /// The input, for quoting it in messages that propose readings.
    src: &'c str,
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
}
