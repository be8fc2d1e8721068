//! The student's own text for the terms a diagnosis names: every node of the answer as typed
//! (and every term of a sum with the sign it was typed with) is lowered once, and the
//! expression it lowers to is remembered with the node printed as the student built it —
//! their grouping, order, signs and fractions, in Unicode (`-(m2 - m1)*g` as `−(m₂ − m₁) g`,
//! `theta'^2` as `θ̇²`) — so that "your term …" quotes what the student wrote, not the
//! canonical form the pool keeps (`(m₁ − m₂)·g`).
//!
//! The print depends on the syntax tree only, not on spacing or spelling (`m*g`, `m g`; `θ''`,
//! `theta''`), so that answers with one [`canonical`](super::fingerprint::canonical) form —
//! which includes it — still get one verdict. Numbers are shown as typed (`0.5` is not `1/2`:
//! a decimal can be the mistake).
//!
//! The table is made only when a diagnosis asks for it (wrong answers), once per answer. An
//! expression is quoted only when it is exactly the expression of a typed node, so a quote
//! always has the value of the term it names; anything else is printed as before.

use rustc_hash::FxHashMap;

use super::prepare::{Prepared, Quotes};
use crate::expr::Id;
use crate::expr::ast::{Ast, AstKind, Statement};
use crate::expr::context::Call;
use crate::expr::lower::lower;
use crate::expr::names;
use crate::expr::parser::parse;

/// Makes the table of quotes for the answer being checked, if not made yet.
pub(super) fn ensure(p: &mut Prepared) {
    if p.quotes.table.is_some() {
        return;
    }
    let source = std::mem::take(&mut p.quotes.source);
    let mut table = FxHashMap::default();
    for (piece, _) in pieces(&source) {
        add_piece(p, piece, &mut table);
    }
    p.quotes = Quotes {
        source,
        table: Some(table),
    };
}

/// The student's own text for `id`, when it is the expression of something they typed
/// (after [`ensure`]).
pub(super) fn lookup(p: &Prepared, id: Id) -> Option<&str> {
    p.quotes.table.as_ref()?.get(&id).map(String::as_str)
}

/// The student's text for `id` if they typed it, else its Unicode print.
pub(super) fn shown(p: &Prepared, id: Id) -> String {
    lookup(p, id).map_or_else(|| p.system.pool.unicode(id), str::to_string)
}

/// The whole answer, or, when it does not read as a whole (a list with stability words or
/// `±`), its top-level items separated by `,` and `;`, each with its byte offset.
fn pieces(source: &str) -> Vec<(&str, usize)> {
    let mut out = vec![(source, 0)];
    let mut depth = 0usize;
    let mut start = 0;
    for (i, c) in source.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth = depth.saturating_sub(1),
            ',' | ';' if depth == 0 => {
                out.push((&source[start..i], start));
                start = i + 1;
            }
            _ => {}
        }
    }
    if start > 0 {
        out.push((&source[start..], start));
    }
    out
}

/// Adds the quotes of one piece of the answer; a piece that does not read adds its value
/// after the last `=` (a labelled item, `ω = …`) if that reads, else nothing.
fn add_piece(p: &mut Prepared, piece: &str, table: &mut FxHashMap<Id, String>) {
    let parsed = match parse(piece, &p.context) {
        Ok(parsed) => parsed,
        Err(_) => {
            // An equilibrium with its stability (`x = −a (stable)`): the point without it.
            if let Some(point) = without_stability(piece) {
                add_piece(p, point, table);
                return;
            }
            if let Some(k) = piece.rfind('=')
                && k + 1 < piece.len()
            {
                add_piece(p, &piece[k + 1..], table);
            }
            return;
        }
    };
    let mut walk = Walk {
        p,
        src: piece,
        table,
    };
    walk.statement(&parsed.statement);
}

/// `piece` without a stability stated after it (`(stable)`, `unstable`), if it has one.
fn without_stability(piece: &str) -> Option<&str> {
    let t = piece.trim_end();
    let word = |w: &str| !w.is_empty() && w.chars().all(|c| c.is_alphabetic() || c == ' ');
    if let Some(inner) = t.strip_suffix(')')
        && let Some(open) = inner.rfind('(')
        && word(&inner[open + 1..])
    {
        return Some(&t[..open]);
    }
    let (head, last) = t.rsplit_once(char::is_whitespace)?;
    // ASCII case is enough: only ASCII capitals lowercase to exactly these words.
    ["stable", "unstable", "marginal", "neutral"]
        .iter()
        .any(|w| w.eq_ignore_ascii_case(last))
        .then_some(head)
}

/// One walk over a parsed piece.
struct Walk<'a> {
    p: &'a mut Prepared,
    src: &'a str,
    table: &'a mut FxHashMap<Id, String>,
}

impl Walk<'_> {
    fn statement(&mut self, st: &Statement) {
        match st {
            Statement::Expr(a) => self.node(a, Place::Whole),
            Statement::Equation { lhs, rhs, .. } => {
                self.node(lhs, Place::Whole);
                self.node(rhs, Place::Whole);
            }
            Statement::List(items, _) | Statement::System(items, _) => {
                items.iter().for_each(|s| self.statement(s));
            }
        }
    }

    /// Remembers `a` and everything in it; a subtracted term of a sum also with its `−`.
    /// Recursion follows the syntax tree, whose depth the parser limits.
    fn node(&mut self, a: &Ast, place: Place) {
        let id = lower(&mut self.p.system.pool, a);
        let text = print(self.src, a, place);
        self.table.entry(id).or_insert(text);
        match &a.kind {
            AstKind::Sum(terms) => {
                for (k, (negated, t)) in terms.iter().enumerate() {
                    if *negated {
                        let x = lower(&mut self.p.system.pool, t);
                        let n = self.p.system.pool.neg(x);
                        let text = format!("−{}", print(self.src, t, Place::Term));
                        self.table.entry(n).or_insert(text);
                    }
                    self.node(t, term_place(k, t));
                }
            }
            AstKind::Product(factors) => factors
                .iter()
                .for_each(|(_, f)| self.node(f, Place::Factor)),
            AstKind::Neg(x) => self.node(x, Place::Factor),
            AstKind::Call(_, x) | AstKind::Dt(x) => self.node(x, Place::Whole),
            AstKind::Pow(b, e) => {
                self.node(b, Place::Factor);
                self.node(e, Place::Whole);
            }
            AstKind::Num(_)
            | AstKind::Pi
            | AstKind::Time
            | AstKind::Coordinate { .. }
            | AstKind::Parameter(_) => {}
        }
    }
}

/// Where a node is printed, which decides whether it needs brackets.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Place {
    /// Alone: a side, an argument, an exponent.
    Whole,
    /// A term of a sum: a sum here was bracketed by the student.
    Term,
    /// A factor (or what a `−` applies to): a sum or a negation is bracketed, and so is a
    /// product, which can only have been bracketed to be one factor.
    Factor,
    /// The base of a power: anything but a name, a number or a call is bracketed.
    Base,
}

/// Where the `k`-th term of a sum is printed: a leading `−a` is the sum's first sign, as
/// typed (`−a + b`), not a bracketed negation.
fn term_place(k: usize, t: &Ast) -> Place {
    if k == 0 && matches!(t.kind, AstKind::Neg(_)) {
        Place::Whole
    } else {
        Place::Term
    }
}

/// `a` as the student built it, in Unicode: factors separated by a space, names in Greek with
/// subscripts and dots (`θ̈₁`), integer powers as superscripts, numbers as typed (`src` holds
/// them). Recursion follows the syntax tree, whose depth the parser limits.
fn print(src: &str, a: &Ast, place: Place) -> String {
    let bracket = |s: String| format!("({s})");
    match &a.kind {
        AstKind::Num(v) => {
            let typed = src.get(a.span.clone()).unwrap_or_default().trim();
            let text = match typed {
                "" => v.to_string(),
                // A superscript exponent's span is the superscript itself.
                t if t.chars().any(|c| names::superscript_digit(c).is_some()) => v.to_string(),
                t => t.to_string(),
            };
            if place == Place::Base && !v.is_integer() {
                bracket(text)
            } else {
                text
            }
        }
        AstKind::Pi => "π".to_string(),
        AstKind::Time => "t".to_string(),
        AstKind::Coordinate { name, order } => {
            names::unicode_state_name(&format!("{name}{}", "'".repeat(usize::from(*order))))
        }
        AstKind::Parameter(name) => names::unicode_state_name(name),
        AstKind::Neg(x) => {
            let text = format!("−{}", print(src, x, Place::Factor));
            if matches!(place, Place::Term | Place::Factor | Place::Base) {
                bracket(text)
            } else {
                text
            }
        }
        AstKind::Sum(terms) => {
            let mut text = String::new();
            for (k, (negated, t)) in terms.iter().enumerate() {
                let shown = print(src, t, term_place(k, t));
                match (k, negated) {
                    (0, false) => text.push_str(&shown),
                    (0, true) => text.push_str(&format!("−{shown}")),
                    (_, false) => text.push_str(&format!(" + {shown}")),
                    (_, true) => text.push_str(&format!(" − {shown}")),
                }
            }
            if place == Place::Whole {
                text
            } else {
                bracket(text)
            }
        }
        AstKind::Product(factors) => {
            let mut text = String::new();
            for (k, (divided, f)) in factors.iter().enumerate() {
                let lead = k == 0;
                // A leading `−m` is the product's sign, as typed; elsewhere it is bracketed.
                let shown = match &f.kind {
                    AstKind::Neg(_) if lead => print(src, f, Place::Whole),
                    _ => print(src, f, Place::Factor),
                };
                if *divided {
                    text.push('/');
                } else if !lead {
                    text.push(' ');
                }
                text.push_str(&shown);
            }
            if matches!(place, Place::Factor | Place::Base) {
                bracket(text)
            } else {
                text
            }
        }
        AstKind::Pow(b, e) => {
            let base = print(src, b, Place::Base);
            let exponent = match &e.kind {
                AstKind::Num(v) if v.is_integer() => {
                    i64::try_from(v.numer()).ok().map(names::superscript)
                }
                AstKind::Neg(x) => match &x.kind {
                    AstKind::Num(v) if v.is_integer() => i64::try_from(v.numer())
                        .ok()
                        .map(|n| names::superscript(-n)),
                    _ => None,
                },
                _ => None,
            };
            let text = match exponent {
                Some(sup) => format!("{base}{sup}"),
                None => format!("{base}^{}", print(src, e, Place::Base)),
            };
            if place == Place::Base {
                bracket(text)
            } else {
                text
            }
        }
        AstKind::Call(call, x) => {
            let arg = print(src, x, Place::Whole);
            match call {
                Call::F(f) => format!("{}({arg})", f.name()),
                Call::Sqrt => format!("√({arg})"),
                Call::Sec => format!("sec({arg})"),
                Call::Csc => format!("csc({arg})"),
                Call::Cot => format!("cot({arg})"),
            }
        }
        AstKind::Dt(x) => format!("d/dt({})", print(src, x, Place::Whole)),
    }
}

/// A whole statement printed as the student built it (items joined by `, `, equations by
/// `; `): what the quotes of its terms are made of.
pub(super) fn statement_text(src: &str, st: &Statement) -> String {
    let join = |items: &[Statement], sep: &str| {
        items
            .iter()
            .map(|s| statement_text(src, s))
            .collect::<Vec<_>>()
            .join(sep)
    };
    match st {
        Statement::Expr(a) => print(src, a, Place::Whole),
        Statement::Equation { lhs, rhs, .. } => format!(
            "{} = {}",
            print(src, lhs, Place::Whole),
            print(src, rhs, Place::Whole)
        ),
        Statement::List(items, _) => join(items, ", "),
        Statement::System(items, _) => join(items, "; "),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn typed(src: &str) -> String {
        let ctx = crate::expr::Context::open();
        let parsed = parse(src, &ctx).expect("reads");
        statement_text(src, &parsed.statement)
    }

    #[test]
    fn printed_as_built() {
        for (src, want) in [
            ("-(m2 - m1) g", "−(m₂ − m₁) g"),
            ("(m1+m2) x''", "(m₁ + m₂) x\u{308}"),
            ("m*l^2*theta''", "m l² θ̈"),
            ("m l² θ̈", "m l² θ̈"),
            ("1/2 m_1 x'^2", "1/2 m₁ x\u{307}²"),
            ("0.5 k x²", "0.5 k x²"),
            ("g/l*sin(theta)", "g/l sin(θ)"),
            ("g/(l m)", "g/(l m)"),
            ("sqrt(g/l)", "√(g/l)"),
            ("x^(1/2) + y^-1", "x^(1/2) + y⁻¹"),
            ("θ̇₁^2 cos(θ₁ − θ₂)", "θ̇₁² cos(θ₁ − θ₂)"),
            ("-m g l sin θ", "−m g l sin(θ)"),
            ("a*(-b)", "a (−b)"),
            ("(a + b) + c", "(a + b) + c"),
            ("(a b)^2 + sin(x)^2", "(a b)² + sin(x)²"),
            ("a = b; c, d", "a = b; c, d"),
            ("-a + b - (c + d)", "−a + b − (c + d)"),
        ] {
            assert_eq!(typed(src), want, "{src}");
        }
        // Spacing and spelling do not change it.
        assert_eq!(typed("m*g*l*sin(theta)"), typed("m g l sin(θ)"));
    }

    #[test]
    fn pieces_of_a_list() {
        let p = pieces("theta = 0 (stable), f(a, b); x");
        let texts: Vec<&str> = p.iter().map(|x| x.0).collect();
        assert_eq!(
            texts,
            [
                "theta = 0 (stable), f(a, b); x",
                "theta = 0 (stable)",
                " f(a, b)",
                " x"
            ]
        );
    }
}
