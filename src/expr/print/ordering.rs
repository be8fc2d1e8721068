//! Display order: the order in which the terms of a sum and the factors of a product are
//! printed (highest time derivative first, then like a polynomial, masses first).

use std::cmp::{Ordering, Reverse};

use num_traits::ToPrimitive;

use crate::expr::names;
use crate::expr::node::{Id, Node};
use crate::expr::order::{self, natural_cmp};
use crate::expr::pool::Pool;

impl Pool {
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
        crate::sort::sort_by(&mut keyed, |(a, ka), (b, kb)| {
            self.display_cmp_keyed(*a, ka, *b, kb)
        });
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

    pub(super) fn display_cmp_factors(&self, a: Id, b: Id) -> Ordering {
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
