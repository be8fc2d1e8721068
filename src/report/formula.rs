//! [`Formula`]: one expression printed in every notation a report may be rendered in.
//!
//! A report is built once and then rendered as plain text, Unicode, LaTeX or JSON, so each
//! expression is printed up front in all three notations; serialization uses the plain
//! syntax, which lagrange reads back.

use serde::{Serialize, Serializer};

use crate::expr::{Factored, Id, Pool, Style};

/// An expression in plain syntax, Unicode and LaTeX.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Formula {
    /// Plain syntax, e.g. `m*l^2*theta'`.
    pub plain: String,
    /// Unicode, e.g. `m·l²·θ̇`.
    pub unicode: String,
    /// LaTeX, e.g. `m l^{2} \dot{\theta}`.
    pub latex: String,
}

impl Formula {
    /// The expression `e` of `pool` in every notation.
    pub fn new(pool: &Pool, e: Id) -> Formula {
        Formula {
            plain: pool.display(e, Style::Plain),
            unicode: pool.display(e, Style::Unicode),
            latex: pool.display(e, Style::Latex),
        }
    }

    /// A factored form of `pool` (see [`Pool::factored`]) in every notation.
    pub fn factored(pool: &Pool, f: &Factored) -> Formula {
        Formula {
            plain: pool.display_factored(f, Style::Plain),
            unicode: pool.display_factored(f, Style::Unicode),
            latex: pool.display_factored(f, Style::Latex),
        }
    }

    /// The form for `style`.
    pub fn get(&self, style: Style) -> &str {
        match style {
            Style::Plain => &self.plain,
            Style::Unicode => &self.unicode,
            Style::Latex => &self.latex,
        }
    }
}

/// Serialized as the plain syntax, so that JSON can be fed back to lagrange.
impl Serialize for Formula {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.plain)
    }
}
