//! Printing in three styles: plain (parses back to the same expression), Unicode (θ̈, l², ·,
//! √, ½ — also parses back) and LaTeX.
//!
//! One layout serves all three: a sum is a list of signed terms, highest time derivative
//! first; a term is a coefficient, numerator factors and denominator factors. Only the
//! spelling of atoms, operators and fractions differs by style.
//!
//! Here: the style and the public printing entry points. The display order of terms and
//! factors lives in `ordering`, the layout and spelling in `printer`.

mod ordering;
mod printer;

use num_rational::BigRational;
use num_traits::One;

use super::node::{Id, Sym};
use super::pool::Pool;
use super::simplify::Factored;
use printer::Printer;

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
        let (neg, mag, _) = printer.product_term(&coeff, factors, true);
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
}
