//! The printer: one layout for all three styles (signed terms, coefficient, numerator and
//! denominator factors), with the spelling of atoms, operators and fractions by style.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive};

use super::Style;
use crate::expr::names;
use crate::expr::node::{Func, Id, Node};
use crate::expr::pool::Pool;

const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 4;
const ATOM: u8 = 5;

/// An integer in superscript digits, exactly, however large (`⁻¹²`): it must read back.
fn superscript(n: &BigInt) -> String {
    n.to_string()
        .chars()
        .map(|c| match c.to_digit(10) {
            Some(d) => names::superscript(i64::from(d)),
            None => "⁻".to_string(),
        })
        .collect()
}

/// An exponent being printed: an exact number or an expression.
#[derive(Clone)]
enum Exp {
    Num(BigRational),
    Expr(Id),
}

pub(super) struct Printer<'a> {
    pub(super) pool: &'a Pool,
    pub(super) style: Style,
}

impl Printer<'_> {
    pub(super) fn minus(&self) -> &'static str {
        if self.style == Style::Unicode {
            "−"
        } else {
            "-"
        }
    }

    fn times(&self) -> &'static str {
        match self.style {
            Style::Plain => "*",
            Style::Unicode => "·",
            Style::Latex => " ",
        }
    }

    /// A whole expression, as at the top level.
    pub(super) fn sum(&self, id: Id) -> String {
        self.expr(id).0
    }

    /// Text and precedence.
    fn expr(&self, id: Id) -> (String, u8) {
        if self.pool.is_undefined(id) {
            // Undefined is stored as 0^(−1); shown as 0/0, which reads back as undefined and
            // does not suggest a division of something non-zero.
            let text = match self.style {
                Style::Latex => "\\frac{0}{0}",
                _ => "0/0",
            };
            return (
                text.into(),
                if self.style == Style::Latex {
                    ATOM
                } else {
                    PRODUCT
                },
            );
        }
        match self.pool.node(id) {
            Node::Add(ch) => {
                let mut terms = ch.to_vec();
                self.pool.display_sort_terms(&mut terms);
                let mut out = String::new();
                for (i, &t) in terms.iter().enumerate() {
                    let (neg, mag, _) = self.term(t);
                    if i == 0 {
                        if neg {
                            out.push_str(self.minus());
                        }
                    } else {
                        out.push_str(if neg {
                            if self.style == Style::Unicode {
                                " − "
                            } else {
                                " - "
                            }
                        } else {
                            " + "
                        });
                    }
                    out.push_str(&mag);
                }
                (out, SUM)
            }
            _ => {
                let (neg, mag, prec) = self.term_with(id, true);
                if neg {
                    (format!("{}{mag}", self.minus()), PRODUCT.min(prec))
                } else {
                    (mag, prec)
                }
            }
        }
    }

    fn wrap(&self, (text, prec): (String, u8), min: u8) -> String {
        if prec >= min {
            text
        } else if self.style == Style::Latex {
            format!("\\left({text}\\right)")
        } else {
            format!("({text})")
        }
    }

    /// A term of a sum as (negative?, magnitude text, precedence of the magnitude).
    fn term(&self, id: Id) -> (bool, String, u8) {
        self.term_with(id, false)
    }

    /// A term; `alone` when it is not inside a sum, where a difference among its factors
    /// may take its sign (see [`Self::product_term`]).
    fn term_with(&self, id: Id, alone: bool) -> (bool, String, u8) {
        let pool = self.pool;
        let (coeff, factors): (BigRational, Vec<Id>) = match pool.node(id) {
            Node::Num(v) => (v.clone(), Vec::new()),
            Node::Mul(ch) => match pool.as_num(ch[0]) {
                Some(c) => (c.clone(), ch[1..].to_vec()),
                None => (BigRational::one(), ch.to_vec()),
            },
            _ => (BigRational::one(), vec![id]),
        };
        self.product_term(&coeff, factors, alone)
    }

    /// The product `coeff · factors` as a term: (negative?, magnitude text, precedence).
    /// `alone`: the product stands by itself (a side, a quoted term, an argument), not as a
    /// term of a sum, whose sign the sum's text already shows as the student's `−`.
    pub(super) fn product_term(
        &self,
        coeff: &BigRational,
        factors: Vec<Id>,
        alone: bool,
    ) -> (bool, String, u8) {
        let pool = self.pool;
        let neg = coeff.is_negative();
        let coeff = coeff.abs();
        let mut num: Vec<Id> = Vec::new();
        let mut den: Vec<(Id, Exp)> = Vec::new();
        for f in factors {
            if let Node::Pow(b, e) = pool.node(f)
                && let Some(ev) = pool.as_num(*e)
                && ev.is_negative()
            {
                den.push((*b, Exp::Num(-ev)));
                continue;
            }
            num.push(f);
        }
        crate::sort::sort_by(&mut num, |&a, &b| pool.display_cmp_factors(a, b));
        crate::sort::sort_by(&mut den, |a, b| pool.display_cmp_factors(a.0, b.0));
        let (mut num_items, den_from_coeff) = self.numerator_items(&coeff, &num, den.is_empty());
        // −m g l (cos θ − 1) is shown m g l (1 − cos θ), −(m₁ − m₂) g as (m₂ − m₁) g: a
        // negative product standing alone with one difference among its factors takes the
        // sign into it, as a student writes it.
        let mut neg = neg;
        if neg
            && alone
            && let Some((k, flipped)) = self.flipped_difference(&num)
        {
            let at = num_items.len() - num.len() + k;
            num_items[at] = (flipped, ATOM);
            neg = false;
        }
        let mut den_items: Vec<(String, u8)> = Vec::new();
        if den_from_coeff {
            den_items.push((coeff.denom().to_string(), ATOM));
        }
        for (b, e) in &den {
            den_items.push(self.power(*b, e.clone()));
        }
        let (text, prec) = self.fraction(&num_items, &den_items, &den);
        (neg, text, prec)
    }

    /// The one factor of `num` that is a difference `a − b` (two terms, one negative), as
    /// `(b − a)`, and its index; `None` when there is no such factor or more than one (which
    /// one would take the sign is then a matter of taste), and in LaTeX.
    fn flipped_difference(&self, num: &[Id]) -> Option<(usize, String)> {
        if self.style == Style::Latex {
            return None;
        }
        let mut found = None;
        for (k, &f) in num.iter().enumerate() {
            let Node::Add(ch) = self.pool.node(f) else {
                continue;
            };
            let [x, y] = ch[..] else {
                continue;
            };
            let (tx, ty) = (self.term(x), self.term(y));
            let (pos, negative) = match (tx.0, ty.0) {
                (false, true) => (tx, ty),
                (true, false) => (ty, tx),
                _ => continue,
            };
            if found.is_some() {
                return None;
            }
            let minus = if self.style == Style::Unicode {
                " − "
            } else {
                " - "
            };
            found = Some((k, format!("({}{minus}{})", negative.1, pos.1)));
        }
        found
    }

    /// The numerator's items (the coefficient's numerator, or the whole coefficient as a
    /// vulgar fraction or `\frac`, then the factors), and whether the coefficient's
    /// denominator still has to go below the line.
    fn numerator_items(
        &self,
        coeff: &BigRational,
        num: &[Id],
        no_den: bool,
    ) -> (Vec<(String, u8)>, bool) {
        let p = BigRational::from_integer(coeff.numer().clone());
        let q = coeff.denom().clone();
        let mut items: Vec<(String, u8)> = Vec::new();
        let vulgar = (self.style == Style::Unicode && no_den && !q.is_one())
            .then(|| {
                let (n, d) = (coeff.numer().to_i64()?, q.to_i64()?);
                names::fraction_char(n, d)
            })
            .flatten();
        let mut den_from_coeff = !q.is_one();
        if let Some(v) = vulgar {
            items.push((v.to_string(), ATOM));
            den_from_coeff = false;
        } else if self.style == Style::Latex && no_den && !q.is_one() && !num.is_empty() {
            items.push((format!("\\frac{{{}}}{{{}}}", p, q), ATOM));
            den_from_coeff = false;
        } else if !p.is_one() || num.is_empty() {
            items.push((p.to_string(), ATOM));
        }
        for &f in num {
            items.push(self.factor(f));
        }
        (items, den_from_coeff)
    }

    /// Numerator over denominator (or the numerator alone), with its precedence. `den` is
    /// the denominator's factors, for the lone-sum case of LaTeX.
    fn fraction(
        &self,
        num_items: &[(String, u8)],
        den_items: &[(String, u8)],
        den: &[(Id, Exp)],
    ) -> (String, u8) {
        let numerator = self.join(num_items);
        if den_items.is_empty() {
            let prec = if num_items.len() == 1 {
                num_items[0].1
            } else {
                PRODUCT
            };
            return (numerator, prec);
        }
        let lone_den = den_items.len() == 1 && den.len() == 1;
        let denominator = match den {
            // \frac needs no parentheses around a lone sum: \frac{g}{m_{1} + m_{2}}.
            // The base is already printed in `den_items`: printing it again doubled the work
            // at each level of a nested fraction (exponential time on `1/(1+1/(1+…))`).
            [(_, Exp::Num(v))] if lone_den && v.is_one() && self.style == Style::Latex => {
                let t = &den_items[0].0;
                let bare = t
                    .strip_prefix("\\left(")
                    .and_then(|t| t.strip_suffix("\\right)"));
                bare.map_or_else(|| t.clone(), str::to_string)
            }
            _ => self.join(den_items),
        };
        if self.style == Style::Latex {
            return (format!("\\frac{{{numerator}}}{{{denominator}}}"), ATOM);
        }
        let n = if num_items.len() == 1 {
            self.wrap(num_items[0].clone(), PRODUCT)
        } else {
            numerator
        };
        let d = if den_items.len() == 1 {
            self.wrap(den_items[0].clone(), POWER)
        } else {
            format!("({denominator})")
        };
        (format!("{n}/{d}"), PRODUCT)
    }

    fn join(&self, items: &[(String, u8)]) -> String {
        if items.len() == 1 {
            return items[0].0.clone();
        }
        items
            .iter()
            .map(|it| self.wrap(it.clone(), PRODUCT + 1))
            .collect::<Vec<_>>()
            .join(self.times())
    }

    /// A factor of a product (never negative, never a product).
    fn factor(&self, f: Id) -> (String, u8) {
        match self.pool.node(f) {
            Node::Pow(b, e) => {
                let e = match self.pool.as_num(*e) {
                    Some(v) => Exp::Num(v.clone()),
                    None => Exp::Expr(*e),
                };
                self.power(*b, e)
            }
            Node::Add(_) => (self.wrap(self.expr(f), ATOM), ATOM),
            _ => self.atom(f),
        }
    }

    /// `b ^ e` for a positive exponent (or a symbolic one).
    fn power(&self, b: Id, e: Exp) -> (String, u8) {
        if let Exp::Num(v) = &e {
            if v.is_one() {
                return self.factor(b);
            }
            if *v == BigRational::new(BigInt::from(1), BigInt::from(2)) {
                return (self.sqrt(b), ATOM);
            }
        }
        if self.style == Style::Latex
            && let Node::Func(f, a) = self.pool.node(b)
            && let Exp::Num(v) = &e
            && v.is_integer()
            && !matches!(f, Func::Exp | Func::Abs)
        {
            let (name, arg) = self.latex_func(*f, *a);
            return (format!("{name}^{{{v}}}{arg}"), ATOM);
        }
        let base = self.expr(b);
        let base_is_atom = base.1 >= ATOM
            && !matches!(self.pool.node(b), Node::Num(v) if !v.is_integer() || v.is_negative())
            && !(self.style == Style::Latex
                && matches!(self.pool.node(b), Node::Func(Func::Exp, _)));
        let base = if base_is_atom {
            base.0
        } else {
            self.wrap((base.0, 0), ATOM)
        };
        let exp = match (&e, self.style) {
            (Exp::Num(v), Style::Unicode) if v.is_integer() => superscript(&v.to_integer()),
            (Exp::Num(v), Style::Latex) => format!("^{{{v}}}"),
            (Exp::Num(v), _) if v.is_integer() && !v.is_negative() => format!("^{v}"),
            (Exp::Num(v), _) => format!("^({v})"),
            (Exp::Expr(x), Style::Latex) => format!("^{{{}}}", self.sum(*x)),
            (Exp::Expr(x), _) => {
                // `^` is right associative, so a power needs no parentheses as an exponent.
                let t = self.expr(*x);
                let atomic = t.1 >= POWER && !self.pool.is_negative_form(*x);
                format!("^{}", if atomic { t.0 } else { format!("({})", t.0) })
            }
        };
        (format!("{base}{exp}"), POWER)
    }

    fn sqrt(&self, b: Id) -> String {
        match self.style {
            Style::Plain => format!("sqrt({})", self.sum(b)),
            Style::Unicode => {
                let inner = self.expr(b);
                if inner.1 >= ATOM && !matches!(self.pool.node(b), Node::Num(v) if !v.is_integer())
                {
                    format!("√{}", inner.0)
                } else {
                    format!("√({})", inner.0)
                }
            }
            Style::Latex => format!("\\sqrt{{{}}}", self.sum(b)),
        }
    }

    fn latex_func(&self, f: Func, a: Id) -> (String, String) {
        let name = match f {
            Func::Asin => "\\arcsin".to_string(),
            Func::Acos => "\\arccos".to_string(),
            Func::Atan => "\\arctan".to_string(),
            Func::Log => "\\ln".to_string(),
            _ => format!("\\{}", f.name()),
        };
        let arg = self.expr(a);
        let arg = if arg.1 >= ATOM && matches!(self.pool.node(a), Node::Var(..) | Node::Pi) {
            format!("{{{}}}", arg.0)
        } else {
            format!("\\left({}\\right)", arg.0)
        };
        (name, arg)
    }

    fn atom(&self, id: Id) -> (String, u8) {
        let pool = self.pool;
        match pool.node(id) {
            Node::Num(v) => {
                let text = match self.style {
                    Style::Latex if !v.is_integer() => {
                        format!("\\frac{{{}}}{{{}}}", v.numer(), v.denom())
                    }
                    Style::Unicode if !v.is_integer() => v
                        .numer()
                        .to_i64()
                        .zip(v.denom().to_i64())
                        .and_then(|(n, d)| names::fraction_char(n, d))
                        .map_or_else(|| v.to_string(), |c| c.to_string()),
                    _ => v.to_string(),
                };
                let prec = if v.is_integer() && !v.is_negative() || text.chars().count() == 1 {
                    ATOM
                } else {
                    PRODUCT
                };
                (text, prec)
            }
            Node::Pi => (
                match self.style {
                    Style::Plain => "pi",
                    Style::Unicode => "π",
                    Style::Latex => "\\pi",
                }
                .into(),
                ATOM,
            ),
            Node::Var(s, o) => (self.var(pool.name(*s), *o), ATOM),
            Node::Func(f, a) => (self.func(*f, *a), ATOM),
            Node::Add(_) | Node::Mul(_) | Node::Pow(..) => self.expr(id),
        }
    }

    fn func(&self, f: Func, a: Id) -> String {
        match self.style {
            Style::Latex => match f {
                Func::Exp => format!("e^{{{}}}", self.sum(a)),
                Func::Abs => format!("\\left|{}\\right|", self.sum(a)),
                _ => {
                    let (name, arg) = self.latex_func(f, a);
                    format!("{name}{arg}")
                }
            },
            _ => format!("{}({})", f.name(), self.sum(a)),
        }
    }

    pub(super) fn var(&self, name: &str, order: u8) -> String {
        let (letters, digits) = names::split_digits(name);
        match self.style {
            Style::Plain => format!("{name}{}", "'".repeat(order as usize)),
            Style::Unicode => {
                let base: String = match names::greek_letter(letters) {
                    Some(g) => g.to_string(),
                    None => letters.to_string(),
                };
                let sub = names::subscript(digits);
                let mark = match order {
                    1 => Some('\u{0307}'),
                    2 => Some('\u{0308}'),
                    3 => Some('\u{20DB}'),
                    _ => None,
                };
                match mark {
                    Some(m) if base.chars().count() == 1 => format!("{base}{m}{sub}"),
                    _ => format!("{base}{sub}{}", "'".repeat(order as usize)),
                }
            }
            Style::Latex => {
                let base = match names::greek_letter(letters) {
                    Some(_) => format!("\\{letters}"),
                    None if letters.chars().count() == 1 => letters.to_string(),
                    None => format!("\\mathrm{{{}}}", letters.replace('_', "\\_")),
                };
                let marked = match order {
                    0 => base,
                    1 => format!("\\dot{{{base}}}"),
                    2 => format!("\\ddot{{{base}}}"),
                    3 => format!("\\dddot{{{base}}}"),
                    n => format!("{base}^{{({n})}}"),
                };
                if digits.is_empty() {
                    marked
                } else {
                    format!("{marked}_{{{digits}}}")
                }
            }
        }
    }
}
