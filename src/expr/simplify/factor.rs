//! Rule `collect` (like terms with constant factors combined) and [`Pool::factored`], the
//! common factors of a sum pulled out for display as a [`Factored`].

use num_rational::BigRational;
use num_traits::{One, Signed};
use rustc_hash::FxHashMap;

use crate::expr::node::{Id, Node, Sym};
use crate::expr::pool::Pool;

impl Pool {
    /// Rule `collect`: terms that differ only in constant factors are combined, with the
    /// constants factored: `m₁·l₁²·θ̈₁ + m₂·l₁²·θ̈₁` → `(m₁ + m₂)·l₁²·θ̈₁`. `constant` says which
    /// symbols are constants (parameters). Applied to the top-level sum only.
    pub fn collect(&mut self, e: Id, constant: &[Sym]) -> Id {
        let Node::Add(terms) = self.node(e).clone() else {
            return e;
        };
        let is_constant = |pool: &Pool, f: Id| -> bool {
            let base = match pool.node(f) {
                Node::Pow(b, e) if pool.as_num(*e).is_some() => *b,
                _ => f,
            };
            match pool.node(base) {
                Node::Num(_) | Node::Pi => true,
                Node::Var(s, o) => *o == 0 && constant.contains(s),
                _ => pool
                    .variables(f)
                    .iter()
                    .all(|&(s, o)| o == 0 && constant.contains(&s)),
            }
        };
        let mut keys: Vec<Id> = Vec::new();
        let mut groups: FxHashMap<Id, Vec<Id>> = FxHashMap::default();
        for &t in terms.iter() {
            let (c, fs) = self.term_factors(t);
            let (consts, rest): (Vec<Id>, Vec<Id>) =
                fs.into_iter().partition(|&f| is_constant(self, f));
            let key = self.product(rest);
            let cn = self.num(c);
            let mut cf = consts;
            cf.push(cn);
            let coeff = self.product(cf);
            groups.entry(key).or_insert_with(|| {
                keys.push(key);
                Vec::new()
            });
            if let Some(g) = groups.get_mut(&key) {
                g.push(coeff);
            }
        }
        if keys.len() == terms.len() {
            return e;
        }
        let mut out = Vec::with_capacity(keys.len());
        for k in keys {
            let cs = groups.remove(&k).unwrap_or_default();
            let c = self.sum(cs);
            // The factored coefficient is only a way of building the product: its node is
            // never interned.
            let mut parts = self.factored(c).into_parts();
            parts.push(k);
            out.push(self.product(parts));
        }
        self.sum(out)
    }

    /// Pulls the factors common to every term of a sum out in front, for display:
    /// `2·m·l²·θ̈ + 2·m·g·l·sin θ` → `2·m·l·(l·θ̈ + g·sin θ)`. The result is not canonical, so
    /// it stays out of the pool: print it with [`display_factored`](Pool::display_factored),
    /// or take its canonical [`value`](Factored::value).
    pub fn factored(&mut self, e: Id) -> Factored {
        let Node::Add(terms) = self.node(e).clone() else {
            return Factored::Plain(e);
        };
        let common = self.common_factors(&terms);
        // The sign is chosen on the factored sum, so that it is the one that reads first.
        let (content, _) = self.content(e);
        let content = content.abs();
        if common.is_empty() && content.is_one() {
            return Factored::Plain(e);
        }
        let mut factors: Vec<Id> = common
            .iter()
            .map(|(b, x)| {
                let xe = self.num(x.clone());
                self.pow(*b, xe)
            })
            .collect();
        let c = self.num(content);
        factors.push(c);
        let divisor = self.product(factors.clone());
        let quotients: Vec<Id> = terms.iter().map(|&t| self.div(t, divisor)).collect();
        let mut inner = self.sum(quotients);
        let mut coeff = BigRational::one();
        if self.is_negative_form(inner) {
            inner = self.neg(inner);
            coeff = -coeff;
        }
        let (nums, rest): (Vec<Id>, Vec<Id>) =
            factors.into_iter().partition(|&f| self.as_num(f).is_some());
        for f in nums {
            if let Some(v) = self.as_num(f) {
                coeff *= v;
            }
        }
        // Laid out as the product node `product` would not build: it would distribute a
        // lone numeric factor over the sum.
        let mut rest: Vec<Id> = rest.into_iter().filter(|&f| f != self.one()).collect();
        rest.push(inner);
        crate::sort::sort_unstable(&mut rest);
        let mut parts = Vec::with_capacity(rest.len() + 1);
        if !coeff.is_one() {
            parts.push(self.num(coeff));
        }
        parts.extend(rest);
        if parts.len() == 1 {
            return Factored::Plain(parts[0]);
        }
        Factored::Product(parts)
    }

    /// The bases common to every term of a sum, each with the exponent to pull out.
    fn common_factors(&mut self, terms: &[Id]) -> Vec<(Id, BigRational)> {
        let mut common: Option<Vec<(Id, BigRational)>> = None;
        for &t in terms {
            let (_, fs) = self.term_factors(t);
            let mine: Vec<(Id, BigRational)> = fs
                .into_iter()
                .map(|f| match self.node(f) {
                    Node::Pow(b, x) => match self.as_num(*x) {
                        Some(v) => (*b, v.clone()),
                        None => (f, BigRational::one()),
                    },
                    _ => (f, BigRational::one()),
                })
                .collect();
            // A base is common when every term has it with exponents of one sign; it is
            // pulled out with the exponent nearest zero (g/l from 2g/l + √2 g/l).
            common = Some(match common {
                None => mine,
                Some(c) => c
                    .into_iter()
                    .filter_map(|(b, x)| {
                        let y = mine.iter().find(|(mb, _)| *mb == b)?.1.clone();
                        (y.is_positive() == x.is_positive())
                            .then(|| (b, if y.abs() < x.abs() { y } else { x }))
                    })
                    .collect(),
            });
        }
        common.unwrap_or_default()
    }
}

/// A sum with its common factors pulled out, for display only (`2·m·l·(l·θ̈ + g·sin θ)`).
/// Not a node of the pool: the pool holds canonical forms, and this one is not.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Factored {
    /// Nothing to pull out: the expression itself.
    Plain(Id),
    /// The factors of the product, laid out as a product node would be (a numeric
    /// coefficient first, then the rest by id); one of them is the remaining sum.
    Product(Vec<Id>),
}

impl Factored {
    /// The factors (one, for a plain expression).
    pub fn into_parts(self) -> Vec<Id> {
        match self {
            Factored::Plain(id) => vec![id],
            Factored::Product(parts) => parts,
        }
    }

    /// The size of the printed form, counted as [`Pool::count_ops`] counts the product node
    /// it prints as.
    pub fn count_ops(&self, pool: &Pool) -> usize {
        match self {
            Factored::Plain(id) => pool.count_ops(*id),
            Factored::Product(parts) => {
                parts.len().saturating_sub(1)
                    + parts.iter().map(|&p| pool.count_ops(p)).sum::<usize>()
            }
        }
    }

    /// The canonical expression this equals.
    pub fn value(&self, pool: &mut Pool) -> Id {
        match self {
            Factored::Plain(id) => *id,
            Factored::Product(parts) => pool.product(parts.iter().copied()),
        }
    }
}
