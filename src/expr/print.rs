//! Printing in three styles: plain (parses back to the same expression), Unicode (θ̈, l², ·,
//! √, ½ — also parses back) and LaTeX.
//!
//! One layout serves all three: a sum is a list of signed terms, highest time derivative
//! first; a term is a coefficient, numerator factors and denominator factors. Only the
//! spelling of atoms, operators and fractions differs by style.

use std::cmp::{Ordering, Reverse};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive};

use super::names;
use super::node::{Func, Id, Node, Sym};
use super::order::{self, natural_cmp};
use super::pool::Pool;
use super::simplify::Factored;

/// An output style.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Style {
    /// ASCII that parses back to an equal expression.
    #[default]
    Plain,
    /// Unicode for people (θ̈, l², ·, √, ½); also parses back.
    Unicode,
    /// LaTeX math.
    Latex,
}

const SUM: u8 = 1;
const PRODUCT: u8 = 2;
const POWER: u8 = 4;
const ATOM: u8 = 5;

impl Pool {
    /// Prints `id` in `style`.
    pub fn display(&self, id: Id, style: Style) -> String {
        Printer { pool: self, style }.sum(id)
    }

    /// A variable (symbol `s` with `order` time derivatives) in `style`, as it prints
    /// inside an expression: `θ̇`, `theta'`, `\dot{\theta}`.
    pub fn var_name(&self, s: Sym, order: u8, style: Style) -> String {
        Printer { pool: self, style }.var(self.name(s), order)
    }

    /// Plain syntax.
    pub fn plain(&self, id: Id) -> String {
        self.display(id, Style::Plain)
    }

    /// Unicode.
    pub fn unicode(&self, id: Id) -> String {
        self.display(id, Style::Unicode)
    }

    /// LaTeX.
    pub fn latex(&self, id: Id) -> String {
        self.display(id, Style::Latex)
    }

    /// Prints a factored form (see [`Pool::factored`]) in `style`, as the product node it
    /// stands for would print.
    pub fn display_factored(&self, f: &Factored, style: Style) -> String {
        let parts = match f {
            Factored::Plain(id) => return self.display(*id, style),
            Factored::Product(parts) => parts,
        };
        let printer = Printer { pool: self, style };
        let (coeff, factors) = match parts.split_first() {
            Some((&c, rest)) if self.as_num(c).is_some() => (
                self.as_num(c).cloned().unwrap_or_else(BigRational::one),
                rest.to_vec(),
            ),
            _ => (BigRational::one(), parts.clone()),
        };
        let (neg, mag, _) = printer.product_term(&coeff, factors);
        if neg {
            format!("{}{mag}", printer.minus())
        } else {
            mag
        }
    }

    /// Prints `lhs = rhs`.
    pub fn display_equation(&self, lhs: Id, rhs: Id, style: Style) -> String {
        format!(
            "{} = {}",
            self.display(lhs, style),
            self.display(rhs, style)
        )
    }

    /// The term printed first in a sum (each term's key computed once).
    pub(crate) fn display_first_term(&self, terms: &[Id]) -> Option<Id> {
        let keyed: Vec<(Id, TermKey<'_>)> = terms.iter().map(|&t| (t, self.term_key(t))).collect();
        keyed
            .iter()
            .min_by(|(a, ka), (b, kb)| self.display_cmp_keyed(*a, ka, *b, kb))
            .map(|(t, _)| *t)
    }

    /// Sorts the terms of a sum into display order: highest time derivative first, then like a
    /// polynomial (higher degree first, then by variable name and its degree), constants
    /// last. So `m·l²·θ̈ + m·g·l·sin θ`, `a² + 2·a·b + b²`, `l²·ω⁴ − 4·g·l·ω² + 2·g²`.
    /// Each term's key is computed once.
    pub(crate) fn display_sort_terms(&self, terms: &mut [Id]) {
        let mut keyed: Vec<(Id, TermKey<'_>)> =
            terms.iter().map(|&t| (t, self.term_key(t))).collect();
        keyed.sort_by(|(a, ka), (b, kb)| self.display_cmp_keyed(*a, ka, *b, kb));
        for (slot, (t, _)) in terms.iter_mut().zip(keyed) {
            *slot = t;
        }
    }

    fn display_cmp_keyed(&self, a: Id, ka: &TermKey<'_>, b: Id, kb: &TermKey<'_>) -> Ordering {
        let ((ka, na), (kb, nb)) = (ka, kb);
        ka.0.cmp(&kb.0)
            .then(ka.1.cmp(&kb.1))
            .then(ka.2.cmp(&kb.2))
            .then_with(|| match (na, nb) {
                (Some(x), Some(y)) => natural_cmp(x, y),
                _ => Ordering::Equal,
            })
            .then(ka.3.cmp(&kb.3))
            .then_with(|| self.cmp_terms(a, b))
    }

    /// (highest derivative order ↓, constant?, total degree in variables of that order ↓,
    /// degree in the lead variable ↓) and the lead variable's name.
    fn term_key(&self, t: Id) -> TermKey<'_> {
        let vars = self.variables(t);
        let max = vars.iter().map(|v| v.1).max().unwrap_or(0);
        let lead = vars
            .iter()
            .filter(|v| v.1 == max)
            .min_by(|a, b| natural_cmp(self.name(a.0), self.name(b.0)))
            .copied();
        let degree_of = |pred: &dyn Fn(u32, u8) -> bool| -> i64 {
            self.factors_without_coeff(t)
                .iter()
                .map(|&f| match self.node(f) {
                    Node::Var(x, p) if pred(x.0, *p) => 1,
                    Node::Pow(b, e) => match self.node(*b) {
                        Node::Var(x, p) if pred(x.0, *p) => self
                            .as_num(*e)
                            .and_then(|v| v.to_integer().to_i64())
                            .unwrap_or(1),
                        _ => 0,
                    },
                    _ => 0,
                })
                .sum()
        };
        let total = degree_of(&|_, p| p == max);
        let lead_degree = lead.map_or(0, |(s, o)| degree_of(&|x, p| x == s.0 && p == o));
        (
            (
                Reverse(max),
                vars.is_empty(),
                Reverse(total),
                Reverse(lead_degree),
            ),
            lead.map(|(s, _)| self.name(s)),
        )
    }

    fn is_constant_sum(&self, s: Id) -> bool {
        let mut stack = vec![s];
        while let Some(n) = stack.pop() {
            match self.node(n) {
                Node::Func(..) | Node::Var(_, 1..) => return false,
                _ => self.push_children(n, &mut stack),
            }
        }
        true
    }

    fn display_cmp_factors(&self, a: Id, b: Id) -> Ordering {
        let class = |f: Id| -> (u8, Option<Id>) {
            let base = match self.node(f) {
                Node::Pow(b, _) => *b,
                _ => f,
            };
            let c = match self.node(base) {
                Node::Num(_) => 0,
                Node::Pi => 1,
                // A sum of constants leads ((m₁ + m₂)·g); one involving functions or
                // velocities follows the other factors (m·g·l·(cos θ − 1)).
                Node::Add(_) if self.is_constant_sum(base) => 2,
                Node::Add(_) => 5,
                Node::Var(_, 0) => 3,
                Node::Var(..) => 4,
                Node::Func(..) => 6,
                _ => 7,
            };
            (c, Some(base))
        };
        let (ca, ba) = class(a);
        let (cb, bb) = class(b);
        ca.cmp(&cb)
            .then_with(
                || match (ba.map(|x| self.node(x)), bb.map(|x| self.node(x))) {
                    (Some(Node::Var(s, o)), Some(Node::Var(t, p))) => {
                        let (x, y) = (self.name(*s), self.name(*t));
                        mass_first(x)
                            .cmp(&mass_first(y))
                            .then_with(|| natural_cmp(x, y))
                            .then_with(|| o.cmp(p))
                    }
                    _ => Ordering::Equal,
                },
            )
            .then_with(|| order::cmp(self, a, b))
    }
}

/// The sort key of a term in a sum, and the name of its lead variable.
type TermKey<'a> = (
    (Reverse<u8>, bool, Reverse<i64>, Reverse<i64>),
    Option<&'a str>,
);

/// Masses come first in a product (`m g l`, not `g l m`), as physicists write them.
fn mass_first(name: &str) -> u8 {
    let (letters, _) = names::split_digits(name);
    u8::from(letters != "m" && letters != "M")
}

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

struct Printer<'a> {
    pool: &'a Pool,
    style: Style,
}

impl Printer<'_> {
    fn minus(&self) -> &'static str {
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
    fn sum(&self, id: Id) -> String {
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
                let (neg, mag, prec) = self.term(id);
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

    /// A term as (negative?, magnitude text, precedence of the magnitude).
    fn term(&self, id: Id) -> (bool, String, u8) {
        let pool = self.pool;
        let (coeff, factors): (BigRational, Vec<Id>) = match pool.node(id) {
            Node::Num(v) => (v.clone(), Vec::new()),
            Node::Mul(ch) => match pool.as_num(ch[0]) {
                Some(c) => (c.clone(), ch[1..].to_vec()),
                None => (BigRational::one(), ch.to_vec()),
            },
            _ => (BigRational::one(), vec![id]),
        };
        self.product_term(&coeff, factors)
    }

    /// The product `coeff · factors` as a term: (negative?, magnitude text, precedence).
    fn product_term(&self, coeff: &BigRational, factors: Vec<Id>) -> (bool, String, u8) {
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
        num.sort_by(|&a, &b| pool.display_cmp_factors(a, b));
        den.sort_by(|a, b| pool.display_cmp_factors(a.0, b.0));
        let (num_items, den_from_coeff) = self.numerator_items(&coeff, &num, den.is_empty());
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

    fn var(&self, name: &str, order: u8) -> String {
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
