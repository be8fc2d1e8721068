//! Simplification for people. Verdicts never depend on it: it exists so that derivations
//! print the way a tutor would write them.
//!
//! Named rules, each a pass over the expression (children first):
//! - `expand`: distribute products over sums and multiply out small integer powers of sums;
//! - `positive-roots`: `√(l²) → l`, `√(m² g²) → m g` for symbols known to be positive, and
//!   `√(x²) → |x|` otherwise;
//! - `pythagoras`: `a·sin²x + b·cos²x → b + (a − b)·sin²x` (so sin²x + cos²x → 1);
//! - `angle-difference`: `cos a cos b + sin a sin b → cos(a − b)`,
//!   `sin a cos b − cos a sin b → sin(a − b)`, and the sums likewise.
//!
//! Canonical construction already collects like terms, folds numbers and applies parity.
//!
//! Every pass is bounded, since only presentation is at stake: an expansion that would pass
//! [`MAX_EXPANDED_TERMS`] terms or [`MAX_TREE_SIZE`](super::pool::MAX_TREE_SIZE) nodes is not
//! done, the trig rules skip terms of more than [`MAX_TRIG_FACTORS`] factors, and a
//! simplification that adds more than [`MAX_NEW_NODES`] nodes gives up and returns its input
//! unchanged.
//!
//! Here: the driver ([`Pool::simplify`]), the budget and the memoised rewriting, substitution
//! and the `positive-roots` rule. Expansion lives in `expand`, the trig rules in `trig`,
//! collecting and factoring (with [`Factored`]) in `factor`.

mod expand;
mod factor;
mod trig;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};
use rustc_hash::{FxHashMap, FxHashSet};

use super::node::{Func, Id, Node, Sym};
use super::pool::{MAX_NEW_NODES, Pool};

pub use factor::Factored;

/// Largest number of terms a single expansion may produce; beyond it the product is kept.
const MAX_EXPANDED_TERMS: usize = 4096;

/// Most factors in a term searched for trig partners: the search is cubic in the number of
/// factors, and tutors' terms have a handful (the 20-link pendulum's have at most 6).
const MAX_TRIG_FACTORS: usize = 16;

impl Pool {
    /// Simplifies for display. `positive` lists symbols known to be positive (parameters).
    /// Past [`MAX_NEW_NODES`] new nodes it gives up and returns `e` as it was.
    pub fn simplify(&mut self, e: Id, positive: &[Sym]) -> Id {
        self.within_budget(e, |pool| pool.simplify_unbounded(e, positive))
    }

    /// Runs a display pass with a budget of [`MAX_NEW_NODES`] new nodes (unless one already
    /// runs, as when `simplify` expands); past it, `e` is returned as it was. The memo
    /// tables are cleared then, since they may hold the half-done pass's results.
    fn within_budget(&mut self, e: Id, pass: impl FnOnce(&mut Pool) -> Id) -> Id {
        if self.budget_end.is_some() {
            return pass(self);
        }
        self.budget_end = Some(self.len() + MAX_NEW_NODES);
        let r = pass(self);
        let over = self.over_budget();
        self.budget_end = None;
        if over {
            self.caches.expand.clear();
            self.caches.trig.clear();
            self.caches.roots.clear();
            return e;
        }
        r
    }

    fn simplify_unbounded(&mut self, e: Id, positive: &[Sym]) -> Id {
        let mut sorted_positive = positive.to_vec();
        crate::sort::sort_unstable(&mut sorted_positive);
        if self.caches.roots_positive != sorted_positive {
            self.caches.roots.clear();
            self.caches.roots_positive = sorted_positive;
        }
        let positive: FxHashSet<Sym> = positive.iter().copied().collect();
        let mut cur = e;
        for _ in 0..4 {
            if self.over_budget() {
                break;
            }
            let x = self.expand(cur);
            let mut roots = std::mem::take(&mut self.caches.roots);
            let x = self.rewrite_cached(x, &mut roots, true, &mut |pool, n| {
                pool.positive_roots(n, &positive)
            });
            self.caches.roots = roots;
            let mut trig = std::mem::take(&mut self.caches.trig);
            let x = self.rewrite_cached(x, &mut trig, true, &mut |pool, n| pool.trig_identities(n));
            self.caches.trig = trig;
            if x == cur {
                break;
            }
            cur = x;
        }
        cur
    }

    /// Rebuilds `e` bottom-up, applying `rule` to every rebuilt node.
    pub(crate) fn rewrite(&mut self, e: Id, rule: &mut dyn FnMut(&mut Pool, Id) -> Id) -> Id {
        let mut cache = FxHashMap::default();
        self.rewrite_cached(e, &mut cache, false, rule)
    }

    /// [`rewrite`](Self::rewrite) with a memo table: a node already in `cache` is neither
    /// visited nor rebuilt again (the rule must depend on the node only). For an
    /// `idempotent` pass every result is also recorded as its own fixed point, so running
    /// the pass again on its output costs one lookup.
    fn rewrite_cached(
        &mut self,
        e: Id,
        cache: &mut FxHashMap<Id, Id>,
        idempotent: bool,
        rule: &mut dyn FnMut(&mut Pool, Id) -> Id,
    ) -> Id {
        if let Some(&r) = cache.get(&e) {
            return r;
        }
        let mut reach: Vec<Id> = Vec::new();
        let mut seen = FxHashSet::default();
        let mut stack = vec![e];
        while let Some(n) = stack.pop() {
            if seen.insert(n) {
                reach.push(n);
                if !cache.contains_key(&n) {
                    self.push_children(n, &mut stack);
                }
            }
        }
        crate::sort::sort_unstable(&mut reach);
        let new = cache;
        for n in reach {
            if new.contains_key(&n) {
                continue;
            }
            let rebuilt = match self.node(n).clone() {
                Node::Num(_) | Node::Var(..) | Node::Pi => n,
                Node::Add(ch) => {
                    let c: Vec<Id> = ch.iter().map(|x| new[x]).collect();
                    self.sum(c)
                }
                Node::Mul(ch) => {
                    let c: Vec<Id> = ch.iter().map(|x| new[x]).collect();
                    self.product(c)
                }
                Node::Pow(b, x) => self.pow(new[&b], new[&x]),
                Node::Func(f, a) => self.func(f, new[&a]),
            };
            let r = rule(self, rebuilt);
            new.insert(n, r);
            if idempotent {
                new.insert(r, r);
            }
        }
        new[&e]
    }
    /// Replaces variables by expressions (`theta'' → 0`, `m1 → m`).
    pub fn substitute(&mut self, e: Id, map: &FxHashMap<(Sym, u8), Id>) -> Id {
        if map.is_empty() {
            return e;
        }
        self.rewrite(e, &mut |pool, n| match pool.node(n) {
            Node::Var(s, o) => map.get(&(*s, *o)).copied().unwrap_or(n),
            _ => n,
        })
    }

    /// Whether `e` is positive wherever it is defined, given positive symbols.
    pub(crate) fn is_positive(&self, e: Id, positive: &FxHashSet<Sym>) -> bool {
        match self.node(e) {
            Node::Num(v) => v.is_positive(),
            Node::Pi => true,
            Node::Var(s, 0) => positive.contains(s),
            Node::Mul(ch) => ch.iter().all(|&c| self.is_positive(c, positive)),
            Node::Add(ch) => ch.iter().all(|&c| self.is_positive(c, positive)),
            Node::Pow(b, _) => self.is_positive(*b, positive),
            Node::Func(Func::Exp | Func::Cosh, _) => true,
            _ => false,
        }
    }

    /// Rule `positive-roots`.
    pub(super) fn positive_roots(&mut self, n: Id, positive: &FxHashSet<Sym>) -> Id {
        let Node::Pow(b, e) = self.node(n).clone() else {
            return n;
        };
        let Some(ev) = self.as_num(e).cloned() else {
            return n;
        };
        if ev.is_integer() {
            return n;
        }
        match self.node(b).clone() {
            Node::Pow(bb, be) => {
                if self.is_positive(bb, positive) {
                    let ne = self.mul(be, e);
                    return self.pow(bb, ne);
                }
                // (x^(2k))^(1/(2k)) = |x|
                if let Some(bev) = self.as_num(be)
                    && bev.is_integer()
                    && (bev * &ev).is_one()
                    && bev.to_integer() % 2 == BigInt::from(0)
                {
                    return self.func(Func::Abs, bb);
                }
                n
            }
            Node::Mul(ch) if ch.iter().all(|&c| self.is_positive(c, positive)) => {
                let parts: Vec<Id> = ch.iter().map(|&c| self.pow(c, e)).collect();
                let parts: Vec<Id> = parts
                    .into_iter()
                    .map(|p| self.positive_roots(p, positive))
                    .collect();
                self.product(parts)
            }
            _ => n,
        }
    }

    /// A term as (coefficient, factors without coefficient).
    fn term_factors(&mut self, t: Id) -> (BigRational, Vec<Id>) {
        let (c, k) = self.split_coeff(t);
        let f = match self.node(k) {
            Node::Mul(ch) => ch.to_vec(),
            _ if k == self.one() => Vec::new(),
            _ => vec![k],
        };
        (c, f)
    }
}

#[cfg(test)]
mod tests {
    use crate::expr::node::Node;
    use crate::expr::{Context, Factored, Pool, Style, read_expr};

    #[test]
    fn an_expansion_past_the_limit_is_not_started() {
        // 2^60 terms: known to be too many before any is built, so the product is kept.
        let ctx = Context::open().with_coordinates(["x"]);
        let mut pool = Pool::new();
        let factors: Vec<String> = (1..=60).map(|k| format!("(1 + cos({k}x))")).collect();
        let e = read_expr(&factors.join("*"), &ctx, &mut pool).unwrap();
        let before = pool.len();
        assert_eq!(pool.expand(e), e);
        assert!(
            pool.len() - before < 10,
            "{} nodes built",
            pool.len() - before
        );
    }

    #[test]
    fn factored_forms_print_as_their_product_node_did() {
        let ctx = Context::open().with_coordinates(["theta", "x"]);
        for text in [
            "2*m*l^2*theta'' + 2*m*g*l*sin(theta)",
            "-2*g/l - sqrt(2)*g/l",
            "3*x + 6",
            "-m*x - m",
            "1/2*k*x^2 + 1/4*k*x",
            "x + theta",
        ] {
            let mut pool = Pool::new();
            let e = read_expr(text, &ctx, &mut pool).unwrap();
            let f = pool.factored(e);
            let value = f.value(&mut pool);
            // The product node the factored form once was (interned here only, for the
            // comparison: it is not canonical).
            let node = match f.clone() {
                Factored::Plain(id) => id,
                Factored::Product(parts) => pool.intern(Node::Mul(parts.into_boxed_slice())),
            };
            for style in [Style::Plain, Style::Unicode, Style::Latex] {
                assert_eq!(pool.display_factored(&f, style), pool.display(node, style));
            }
            assert_eq!(f.count_ops(&pool), pool.count_ops(node), "{text}");
            let back = pool.sub(value, e);
            assert!(pool.expand(back) == pool.zero(), "{text}");
        }
    }
}
