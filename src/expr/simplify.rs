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

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};
use rustc_hash::{FxHashMap, FxHashSet};

use super::node::{Func, Id, Node, Sym};
use super::pool::Pool;

/// Largest number of terms a single expansion may produce; beyond it the product is kept.
const MAX_EXPANDED_TERMS: usize = 4096;

impl Pool {
    /// Simplifies for display. `positive` lists symbols known to be positive (parameters).
    pub fn simplify(&mut self, e: Id, positive: &[Sym]) -> Id {
        let positive: FxHashSet<Sym> = positive.iter().copied().collect();
        let mut cur = e;
        for _ in 0..4 {
            let x = self.expand(cur);
            let x = self.rewrite(x, &mut |pool, n| pool.positive_roots(n, &positive));
            let x = self.rewrite(x, &mut |pool, n| pool.trig_identities(n));
            if x == cur {
                break;
            }
            cur = x;
        }
        cur
    }

    /// Rebuilds `e` bottom-up, applying `rule` to every rebuilt node.
    pub fn rewrite(&mut self, e: Id, rule: &mut dyn FnMut(&mut Pool, Id) -> Id) -> Id {
        let mut reach: Vec<Id> = Vec::new();
        let mut seen = FxHashSet::default();
        let mut stack = vec![e];
        while let Some(n) = stack.pop() {
            if seen.insert(n) {
                reach.push(n);
                stack.extend(self.children(n));
            }
        }
        reach.sort_unstable();
        let mut new: FxHashMap<Id, Id> = FxHashMap::default();
        for n in reach {
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
        }
        new[&e]
    }

    /// Multiplies out products of sums and small powers of sums (rule `expand`).
    pub fn expand(&mut self, e: Id) -> Id {
        self.rewrite(e, &mut |pool, n| pool.expand_node(n))
    }

    fn expand_node(&mut self, n: Id) -> Id {
        match self.node(n).clone() {
            Node::Mul(ch) => {
                let mut acc: Vec<Id> = vec![self.one()];
                for f in ch.iter() {
                    let terms: Vec<Id> = match self.node(*f) {
                        Node::Add(t) => t.to_vec(),
                        _ => vec![*f],
                    };
                    if acc.len() * terms.len() > MAX_EXPANDED_TERMS {
                        return n;
                    }
                    let mut next = Vec::with_capacity(acc.len() * terms.len());
                    for &a in &acc {
                        for &t in &terms {
                            next.push(self.mul(a, t));
                        }
                    }
                    acc = next;
                }
                self.sum(acc)
            }
            Node::Pow(b, e) => {
                let k = self.as_num(e).and_then(|v| {
                    (v.is_integer()
                        && v.is_positive()
                        && *v <= BigRational::from_integer(BigInt::from(8)))
                    .then(|| v.to_integer())
                });
                match (k, self.node(b)) {
                    (Some(k), Node::Add(t)) => {
                        let len = t.len();
                        let k: u32 = k.try_into().unwrap_or(1);
                        if len.saturating_pow(k) > MAX_EXPANDED_TERMS {
                            return n;
                        }
                        // Term by term: `acc·b` would fold straight back into a power of b.
                        let mut acc = self.one();
                        for _ in 0..k {
                            acc = self.multiply_out(acc, b);
                        }
                        acc
                    }
                    _ => n,
                }
            }
            _ => n,
        }
    }

    /// The product of two expressions with both multiplied out into terms.
    fn multiply_out(&mut self, a: Id, b: Id) -> Id {
        let terms = |pool: &Pool, x: Id| match pool.node(x) {
            Node::Add(t) => t.to_vec(),
            _ => vec![x],
        };
        let (ta, tb) = (terms(self, a), terms(self, b));
        let mut out = Vec::with_capacity(ta.len() * tb.len());
        for &x in &ta {
            for &y in &tb {
                out.push(self.mul(x, y));
            }
        }
        self.sum(out)
    }

    /// Whether `e` is positive wherever it is defined, given positive symbols.
    pub fn is_positive(&self, e: Id, positive: &FxHashSet<Sym>) -> bool {
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
    fn positive_roots(&mut self, n: Id, positive: &FxHashSet<Sym>) -> Id {
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

    /// Rules `pythagoras` and `angle-difference`, applied to one sum.
    fn trig_identities(&mut self, n: Id) -> Id {
        let Node::Add(terms) = self.node(n).clone() else {
            return n;
        };
        let mut terms: Vec<Id> = terms.to_vec();
        let mut changed = true;
        let mut rounds = 0;
        while changed && rounds < 64 {
            changed = false;
            rounds += 1;
            'outer: for i in 0..terms.len() {
                for j in 0..terms.len() {
                    if i == j {
                        continue;
                    }
                    if let Some(r) = self.combine_pair(terms[i], terms[j]) {
                        let (a, b) = (i.max(j), i.min(j));
                        terms.remove(a);
                        terms.remove(b);
                        terms.extend(r);
                        changed = true;
                        break 'outer;
                    }
                }
            }
        }
        self.sum(terms)
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

    /// Tries to merge two terms by a trig identity; returns the replacement terms.
    fn combine_pair(&mut self, x: Id, y: Id) -> Option<Vec<Id>> {
        let (cx, fx) = self.term_factors(x);
        let (cy, fy) = self.term_factors(y);
        // pythagoras: R·sin²a (coefficient cx) and R·cos²a (coefficient cy).
        for (i, &f) in fx.iter().enumerate() {
            let Some(a) = self.trig_square(f, Func::Sin) else {
                continue;
            };
            let cos2 = {
                let c = self.func(Func::Cos, a);
                self.powi(c, 2)
            };
            let rest_x: Vec<Id> = without(&fx, i);
            if let Some(k) = fy.iter().position(|&g| g == cos2)
                && same_factors(&rest_x, &without(&fy, k))
            {
                // cx·R·sin² + cy·R·cos²: keep whichever square has the larger coefficient.
                let r = self.product(rest_x.clone());
                let (keep, square, other) = if cx.abs() >= cy.abs() {
                    (cy.clone(), f, cx.clone())
                } else {
                    (cx.clone(), cos2, cy.clone())
                };
                let t1 = self.scale(&keep, r);
                let mut sq = rest_x;
                sq.push(square);
                let base = self.product(sq);
                let diff = &other - &keep;
                let t2 = self.scale(&diff, base);
                return Some(vec![t1, t2]);
            }
        }
        // angle-difference and angle-sum.
        let trig_pair =
            |pool: &Pool, fs: &[Id], f1: Func, f2: Func| -> Vec<(usize, usize, Id, Id)> {
                let mut out = Vec::new();
                for (i, &p) in fs.iter().enumerate() {
                    for (j, &q) in fs.iter().enumerate() {
                        if i == j {
                            continue;
                        }
                        if let (Node::Func(g1, a), Node::Func(g2, b)) = (pool.node(p), pool.node(q))
                            && *g1 == f1
                            && *g2 == f2
                            && a != b
                        {
                            out.push((i, j, *a, *b));
                        }
                    }
                }
                out
            };
        // cos a cos b ± sin a sin b
        for (i, j, a, b) in trig_pair(self, &fx, Func::Cos, Func::Cos) {
            let rest_x = without(&without(&fx, i.max(j)), i.min(j));
            let sa = self.func(Func::Sin, a);
            let sb = self.func(Func::Sin, b);
            if let (Some(k), Some(l)) = (
                fy.iter().position(|&g| g == sa),
                fy.iter().position(|&g| g == sb),
            ) && k != l
                && same_factors(&rest_x, &without(&without(&fy, k.max(l)), k.min(l)))
                && (cx == cy || cx == -cy.clone())
            {
                let arg = if cx == cy {
                    self.sub(a, b)
                } else {
                    self.add(a, b)
                };
                let c = self.func(Func::Cos, arg);
                let mut f = rest_x;
                f.push(c);
                let p = self.product(f);
                return Some(vec![self.scale(&cx, p)]);
            }
        }
        // sin a cos b ± cos a sin b
        for (i, j, a, b) in trig_pair(self, &fx, Func::Sin, Func::Cos) {
            let rest_x = without(&without(&fx, i.max(j)), i.min(j));
            let ca = self.func(Func::Cos, a);
            let sb = self.func(Func::Sin, b);
            if let (Some(k), Some(l)) = (
                fy.iter().position(|&g| g == ca),
                fy.iter().position(|&g| g == sb),
            ) && k != l
                && same_factors(&rest_x, &without(&without(&fy, k.max(l)), k.min(l)))
                && (cx == cy || cx == -cy.clone())
            {
                let arg = if cx == cy {
                    self.add(a, b)
                } else {
                    self.sub(a, b)
                };
                let s = self.func(Func::Sin, arg);
                let mut f = rest_x;
                f.push(s);
                let p = self.product(f);
                return Some(vec![self.scale(&cx, p)]);
            }
        }
        None
    }

    /// `Some(a)` when `f` is `g(a)²`.
    fn trig_square(&self, f: Id, g: Func) -> Option<Id> {
        if let Node::Pow(b, e) = self.node(f)
            && self
                .as_num(*e)
                .is_some_and(|v| *v == BigRational::from_integer(2.into()))
            && let Node::Func(h, a) = self.node(*b)
            && *h == g
        {
            return Some(*a);
        }
        None
    }
}

fn without(v: &[Id], i: usize) -> Vec<Id> {
    let mut w = v.to_vec();
    w.remove(i);
    w
}

fn same_factors(a: &[Id], b: &[Id]) -> bool {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    a.sort_unstable();
    b.sort_unstable();
    a == b
}
