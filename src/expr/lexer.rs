//! The lexer: turns input text into tokens, each with its byte span.
//!
//! Besides ASCII it reads what the Unicode printer writes (Greek letters, combining dots for
//! time derivatives, superscript exponents, subscript digits, `·`, `−`, `√`, `½`), so a
//! student can paste lagrange's own output back in.

use std::ops::Range;

use num_bigint::BigInt;
use num_rational::BigRational;

use super::error::{ParseError, ParseErrorKind};
use super::names;

/// Byte range in the input.
pub type Span = Range<usize>;

/// Largest decimal exponent accepted in a number literal (`1e400` is refused, not infinite).
const MAX_DECIMAL_EXPONENT: i64 = 300;
/// Most digits read in one number literal (and in one superscript exponent).
const MAX_DIGITS: usize = 1000;

/// A token kind.
#[derive(Clone, Debug, PartialEq)]
pub enum Tok {
    /// An exact number.
    Num(BigRational),
    /// A name (Greek spelled out, subscripts as digits) and how many combining dots follow it.
    Name {
        text: String,
        dots: u32,
    },
    /// `'` after a name: one time derivative.
    Prime,
    /// A superscript integer exponent (`²`, `⁻¹`), of any size: the printer writes every
    /// integer exponent this way, so every one must read back.
    Super(BigInt),
    Plus,
    Minus,
    Star,
    Slash,
    Caret,
    LParen,
    RParen,
    Comma,
    Semi,
    Eq,
    /// `√`
    Root,
}

impl Tok {
    /// A short description for messages.
    pub fn describe(&self) -> String {
        match self {
            Tok::Num(_) => "a number".into(),
            Tok::Name { text, .. } => format!("`{text}`"),
            Tok::Prime => "`'`".into(),
            Tok::Super(_) => "an exponent".into(),
            Tok::Plus => "`+`".into(),
            Tok::Minus => "`-`".into(),
            Tok::Star => "`*`".into(),
            Tok::Slash => "`/`".into(),
            Tok::Caret => "`^`".into(),
            Tok::LParen => "`(`".into(),
            Tok::RParen => "`)`".into(),
            Tok::Comma => "`,`".into(),
            Tok::Semi => "`;`".into(),
            Tok::Eq => "`=`".into(),
            Tok::Root => "`√`".into(),
        }
    }
}

/// A token and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Token {
    pub(crate) tok: Tok,
    pub(crate) span: Span,
}

/// Splits `src` into tokens.
pub(crate) fn lex(src: &str) -> Result<Vec<Token>, ParseError> {
    // About a token per two bytes: growing one at a time reallocates several times.
    let mut out = Vec::with_capacity(src.len() / 2 + 4);
    let mut chars = src.char_indices().peekable();
    while let Some(&(i, c)) = chars.peek() {
        if c.is_whitespace() {
            chars.next();
            continue;
        }
        if names::subscript_digit(c).is_some() && subscript_after_primes(&mut out, src, i) {
            // `θ'₁` is θ₁': the subscript belongs to the name before the primes.
            while chars
                .peek()
                .is_some_and(|&(_, d)| names::subscript_digit(d).is_some())
            {
                chars.next();
            }
            continue;
        }
        let (tok, end) = if is_number_start(src, i, c) {
            let (value, end) = number(src, i)?;
            (Tok::Num(value), end)
        } else if is_name_start(c) {
            name(src, i)
        } else if is_superscript_start(c) {
            superscript(src, i)?
        } else {
            symbol(src, i, c)?
        };
        if c == '″' {
            // A double prime is two derivatives, both pointing at the one character.
            out.push(Token {
                tok: Tok::Prime,
                span: i..end,
            });
        }
        out.push(Token { tok, span: i..end });
        while chars.peek().is_some_and(|&(j, _)| j < end) {
            chars.next();
        }
    }
    Ok(out)
}

/// If `out` ends in a name and its primes, appends the subscript digits at byte `i` to the
/// name and says so.
fn subscript_after_primes(out: &mut [Token], src: &str, i: usize) -> bool {
    let primes = out.iter().rev().take_while(|t| t.tok == Tok::Prime).count();
    let Some(k) = out.len().checked_sub(primes + 1) else {
        return false;
    };
    let Some(Token {
        tok: Tok::Name { text, .. },
        ..
    }) = out.get_mut(k)
    else {
        return false;
    };
    if primes == 0 {
        return false;
    }
    for d in src[i..].chars().map_while(names::subscript_digit) {
        text.push(char::from_digit(d, 10).unwrap_or('0'));
    }
    true
}

fn is_number_start(src: &str, i: usize, c: char) -> bool {
    c.is_ascii_digit() || (c == '.' && src[i + 1..].starts_with(|d: char| d.is_ascii_digit()))
}

fn is_superscript_start(c: char) -> bool {
    names::superscript_digit(c).is_some() || c == '⁻' || c == '⁺'
}

/// Reads a superscript integer (`²`, `⁻¹`) starting at byte `start`; a sign only first.
fn superscript(src: &str, start: usize) -> Result<(Tok, usize), ParseError> {
    let mut end = start;
    let mut text = String::new();
    for (j, d) in src[start..].char_indices() {
        if let Some(v) = names::superscript_digit(d) {
            text.push(char::from_digit(v, 10).unwrap_or('0'));
        } else if (d == '⁻' || d == '⁺') && j == 0 {
            if d == '⁻' {
                text.push('-');
            }
        } else {
            break;
        }
        end = start + j + d.len_utf8();
    }
    if text.len() > MAX_DIGITS {
        return Err(ParseError::new(
            ParseErrorKind::TooManyDigits { max: MAX_DIGITS },
            start..end,
        ));
    }
    let n: BigInt = text
        .parse()
        .map_err(|_| ParseError::new(ParseErrorKind::BadNumber, start..end))?;
    Ok((Tok::Super(n), end))
}

/// Reads an operator, bracket or other one-character token at byte `i` (`**` is two bytes;
/// a `″` is returned as one prime, and the caller adds the other).
fn symbol(src: &str, i: usize, c: char) -> Result<(Tok, usize), ParseError> {
    let end = i + c.len_utf8();
    let tok = match c {
        '+' => Tok::Plus,
        '-' | '−' | '–' => Tok::Minus,
        '*' if src[i + 1..].starts_with('*') => return Ok((Tok::Caret, i + 2)),
        '*' | '·' | '×' | '⋅' => Tok::Star,
        '/' | '÷' => Tok::Slash,
        '^' => Tok::Caret,
        '(' | '[' => Tok::LParen,
        ')' | ']' => Tok::RParen,
        ',' => Tok::Comma,
        ';' => Tok::Semi,
        '=' => Tok::Eq,
        '\'' | '′' | '″' | '’' => Tok::Prime,
        '√' => Tok::Root,
        'π' => Tok::Name {
            text: "pi".into(),
            dots: 0,
        },
        _ => match names::fraction_value(c) {
            Some((n, d)) => Tok::Num(BigRational::new(BigInt::from(n), BigInt::from(d))),
            None => {
                return Err(ParseError::new(ParseErrorKind::UnexpectedChar(c), i..end));
            }
        },
    };
    Ok((tok, end))
}

fn is_name_start(c: char) -> bool {
    c.is_ascii_alphabetic()
        || c == '_'
        || names::greek_name(c).is_some()
        || names::precomposed(c).is_some()
}

/// Reads a name starting at byte `start`. An ASCII name runs over letters, digits and `_`; a
/// Greek letter is a name of its own, continued only by digits, subscripts and `_`. Combining
/// dots (U+0307, U+0308) count derivatives; subscript digits become digits.
fn name(src: &str, start: usize) -> (Tok, usize) {
    let mut text = String::new();
    let mut dots = 0u32;
    let mut end = start;
    let mut first = true;
    let mut greek = false;
    // After a subscript (`m₂`), a letter starts a new name: `m₂l₂` is m₂·l₂.
    let mut subscripted = false;
    for (j, c) in src[start..].char_indices() {
        let j = start + j;
        let accepted = if first {
            if let Some((b, d)) = names::precomposed(c) {
                // A dotted letter is a name of its own: `ẋ` then digits or subscripts.
                greek = true;
                text.push(b);
                dots = dots.saturating_add(u32::from(d));
            } else if let Some(g) = names::greek_name(c) {
                greek = true;
                text.push_str(g);
            } else {
                text.push(c);
            }
            true
        } else if c == '\u{0307}' {
            dots = dots.saturating_add(1);
            true
        } else if c == '\u{0308}' {
            dots = dots.saturating_add(2);
            true
        } else if c == '\u{20DB}' {
            dots = dots.saturating_add(3);
            true
        } else if let Some(d) = names::subscript_digit(c) {
            text.push(char::from_digit(d, 10).unwrap_or('0'));
            subscripted = true;
            true
        } else if c.is_ascii_digit()
            || c == '_'
            || (!greek && !subscripted && c.is_ascii_alphabetic())
        {
            text.push(c);
            true
        } else {
            false
        };
        if !accepted {
            break;
        }
        first = false;
        end = j + c.len_utf8();
    }
    (Tok::Name { text, dots }, end)
}

/// Reads a decimal number exactly: `0.1` is 1/10, `1e-3` is 1/1000.
fn number(src: &str, start: usize) -> Result<(BigRational, usize), ParseError> {
    let bytes = src.as_bytes();
    let mut i = start;
    let mut digits = String::with_capacity(24);
    let mut frac_len: i64 = 0;
    while i < bytes.len() && bytes[i].is_ascii_digit() {
        digits.push(bytes[i] as char);
        i += 1;
    }
    if i < bytes.len() && bytes[i] == b'.' {
        i += 1;
        while i < bytes.len() && bytes[i].is_ascii_digit() {
            digits.push(bytes[i] as char);
            frac_len += 1;
            i += 1;
        }
    }
    let mut exp: i64 = 0;
    if i < bytes.len() && (bytes[i] == b'e' || bytes[i] == b'E') {
        let mut j = i + 1;
        let neg = j < bytes.len() && bytes[j] == b'-';
        if j < bytes.len() && (bytes[j] == b'-' || bytes[j] == b'+') {
            j += 1;
        }
        if j < bytes.len() && bytes[j].is_ascii_digit() {
            let k = j;
            while j < bytes.len() && bytes[j].is_ascii_digit() {
                j += 1;
            }
            let e: i64 = src[k..j].parse().unwrap_or(i64::MAX);
            if e > MAX_DECIMAL_EXPONENT {
                return Err(ParseError::new(
                    ParseErrorKind::ExponentTooLarge {
                        max: MAX_DECIMAL_EXPONENT,
                    },
                    start..j,
                ));
            }
            exp = if neg { -e } else { e };
            i = j;
        }
    }
    if digits.len() > MAX_DIGITS {
        return Err(ParseError::new(
            ParseErrorKind::TooManyDigits { max: MAX_DIGITS },
            start..i,
        ));
    }
    let shift = exp - frac_len;
    if let Some(value) = small_decimal(&digits, shift) {
        return Ok((value, i));
    }
    let mantissa: BigInt = digits.parse().unwrap_or_default();
    // One reduction (a single gcd), not a power of a ratio times a ratio.
    let scale = num_traits::Pow::pow(BigInt::from(10), shift.unsigned_abs());
    let value = if shift >= 0 {
        BigRational::from_integer(mantissa * scale)
    } else {
        BigRational::new(mantissa, scale)
    };
    Ok((value, i))
}

/// The number `digits` × 10^`shift` when the digits and the power of ten fit in 64 bits
/// (every number a student types): reduced by a machine gcd, as `BigRational::new` would.
fn small_decimal(digits: &str, shift: i64) -> Option<BigRational> {
    use num_integer::Integer;
    let mantissa: u64 = digits.parse().ok()?;
    let scale = 10u64.checked_pow(u32::try_from(shift.unsigned_abs()).ok()?)?;
    if shift >= 0 {
        let n = mantissa.checked_mul(scale)?;
        return Some(BigRational::from_integer(BigInt::from(n)));
    }
    let g = mantissa.gcd(&scale);
    Some(BigRational::new_raw(
        BigInt::from(mantissa / g),
        BigInt::from(scale / g),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kinds(src: &str) -> Vec<Tok> {
        lex(src).unwrap().into_iter().map(|t| t.tok).collect()
    }

    fn name(t: &str, dots: u32) -> Tok {
        Tok::Name {
            text: t.into(),
            dots,
        }
    }

    fn num(n: i64, d: i64) -> Tok {
        Tok::Num(BigRational::new(BigInt::from(n), BigInt::from(d)))
    }

    #[test]
    fn short_decimals_reduce_as_big_ones_do() {
        for (digits, shift) in [
            ("1000003", -6i64),
            ("0", -3),
            ("120", 2),
            ("25", -1),
            ("4", -19),
        ] {
            let ten = num_traits::Pow::pow(BigInt::from(10), shift.unsigned_abs());
            let m: BigInt = digits.parse().unwrap();
            let want = if shift >= 0 {
                BigRational::from_integer(m * ten)
            } else {
                BigRational::new(m, ten)
            };
            let got = small_decimal(digits, shift).expect("fits in 64 bits");
            assert_eq!(
                (got.numer(), got.denom()),
                (want.numer(), want.denom()),
                "{digits}e{shift}"
            );
        }
        assert_eq!(small_decimal("18446744073709551616", 0), None);
        assert_eq!(small_decimal("1", -20), None);
    }

    #[test]
    fn tokens() {
        let cases: Vec<(&str, Vec<Tok>)> = vec![
            ("0.5", vec![num(1, 2)]),
            ("1e-3", vec![num(1, 1000)]),
            (".25", vec![num(1, 4)]),
            ("2m", vec![num(2, 1), name("m", 0)]),
            ("2e", vec![num(2, 1), name("e", 0)]),
            ("θ̇", vec![name("theta", 1)]),
            ("θ̈₁", vec![name("theta1", 2)]),
            ("θ₁̇", vec![name("theta1", 1)]),
            ("mθ", vec![name("m", 0), name("theta", 0)]),
            ("l²", vec![name("l", 0), Tok::Super(2.into())]),
            ("T⁻²", vec![name("T", 0), Tok::Super((-2).into())]),
            ("a·b", vec![name("a", 0), Tok::Star, name("b", 0)]),
            ("x**2", vec![name("x", 0), Tok::Caret, num(2, 1)]),
            ("a − b", vec![name("a", 0), Tok::Minus, name("b", 0)]),
            ("½", vec![num(1, 2)]),
            ("√2", vec![Tok::Root, num(2, 1)]),
            ("π", vec![name("pi", 0)]),
            ("q''", vec![name("q", 0), Tok::Prime, Tok::Prime]),
            ("ẍ", vec![name("x", 2)]),
            ("mẋ", vec![name("m", 0), name("x", 1)]),
            ("m₂l₂", vec![name("m2", 0), name("l2", 0)]),
        ];
        for (src, want) in cases {
            assert_eq!(kinds(src), want, "{src}");
        }
    }

    #[test]
    fn spans_are_bytes() {
        let toks = lex("θ + x").unwrap();
        assert_eq!(toks[0].span, 0..2);
        assert_eq!(toks[1].span, 3..4);
        assert_eq!(toks[2].span, 5..6);
    }

    #[test]
    fn bad_characters() {
        let e = lex("x $ y").unwrap_err();
        assert_eq!(e.kind, ParseErrorKind::UnexpectedChar('$'));
        assert_eq!(e.span, 2..3);
        assert_eq!(
            lex("1e999").unwrap_err().kind,
            ParseErrorKind::ExponentTooLarge { max: 300 }
        );
    }
}
