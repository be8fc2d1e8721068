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
//! [`MAX_EXPANDED_TERMS`] terms or [`MAX_TREE_SIZE`] nodes is not done, the trig rules skip
//! terms of more than [`MAX_TRIG_FACTORS`] factors, and a simplification that adds more than
//! [`MAX_NEW_NODES`] nodes gives up and returns its input unchanged.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed};
use rustc_hash::{FxHashMap, FxHashSet};

use super::node::{Func, Id, Node, Sym};
use super::pool::{MAX_NEW_NODES, MAX_TREE_SIZE, Pool};

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
        sorted_positive.sort_unstable();
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
        reach.sort_unstable();
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

    /// Multiplies out products of sums and small powers of sums (rule `expand`), within
    /// the limits (see the module header).
    pub fn expand(&mut self, e: Id) -> Id {
        self.within_budget(e, |pool| {
            let mut cache = std::mem::take(&mut pool.caches.expand);
            let r = pool.rewrite_cached(e, &mut cache, true, &mut |pool, n| pool.expand_node(n));
            pool.caches.expand = cache;
            r
        })
    }

    /// One node multiplied out, or `n` itself when the result would pass a limit.
    fn expand_node(&mut self, n: Id) -> Id {
        if self.over_budget() {
            return n;
        }
        let r = self.expand_node_unbounded(n);
        if r != n && self.tree_size(r) > MAX_TREE_SIZE.max(self.tree_size(n)) {
            return n;
        }
        r
    }

    fn expand_node_unbounded(&mut self, n: Id) -> Id {
        match self.node(n).clone() {
            Node::Mul(ch) => {
                // The number of terms is known before any is built: the product of the
                // factors' term counts (products past the limit are kept as they are).
                let count = ch.iter().try_fold(1usize, |acc, f| {
                    let k = match self.node(*f) {
                        Node::Add(t) => t.len(),
                        _ => 1,
                    };
                    acc.checked_mul(k).filter(|&c| c <= MAX_EXPANDED_TERMS)
                });
                if count.is_none() {
                    return n;
                }
                let mut acc: Vec<Id> = vec![self.one()];
                for f in ch.iter() {
                    let terms: Vec<Id> = match self.node(*f) {
                        Node::Add(t) => t.to_vec(),
                        _ => vec![*f],
                    };
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

    /// Replaces variables by expressions (`theta'' → 0`, `m1 → m`).
    pub(crate) fn substitute(&mut self, e: Id, map: &FxHashMap<(Sym, u8), Id>) -> Id {
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

    /// Rules `pythagoras` and `angle-difference`, applied to one sum. Terms are indexed by
    /// their factors, so each term finds its partner by lookup rather than by a pairwise
    /// search (sums in an n-link pendulum have hundreds of terms).
    fn trig_identities(&mut self, n: Id) -> Id {
        let Node::Add(terms) = self.node(n).clone() else {
            return n;
        };
        let mut terms: Vec<Id> = terms.to_vec();
        for _ in 0..8 {
            if self.over_budget() {
                return n;
            }
            let parts: Vec<(BigRational, Vec<Id>)> =
                terms.iter().map(|&t| self.term_factors(t)).collect();
            let mut index: FxHashMap<Vec<Id>, usize> = FxHashMap::default();
            for (i, (_, f)) in parts.iter().enumerate() {
                index.insert(sorted(f.clone()), i);
            }
            let mut used = vec![false; terms.len()];
            let mut out: Vec<Id> = Vec::new();
            let mut changed = false;
            for i in 0..terms.len() {
                if used[i] {
                    continue;
                }
                if let Some((j, replacement)) = self.find_partner(i, &parts, &index, &used) {
                    used[i] = true;
                    used[j] = true;
                    out.extend(replacement);
                    changed = true;
                }
            }
            if !changed {
                break;
            }
            for (i, &t) in terms.iter().enumerate() {
                if !used[i] {
                    out.push(t);
                }
            }
            terms = out;
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

    /// Looks up a partner of term `i` for a trig identity; returns it and the replacement.
    fn find_partner(
        &mut self,
        i: usize,
        parts: &[(BigRational, Vec<Id>)],
        index: &FxHashMap<Vec<Id>, usize>,
        used: &[bool],
    ) -> Option<(usize, Vec<Id>)> {
        let lookup = |want: Vec<Id>| -> Option<usize> {
            index
                .get(&sorted(want))
                .copied()
                .filter(|&j| j != i && !used[j])
        };
        self.pythagoras_partner(i, parts, &lookup)
            .or_else(|| self.angle_partner(i, parts, &lookup))
    }

    /// Rule `pythagoras` for term `i`: R·sin²a with R·cos²a.
    fn pythagoras_partner(
        &mut self,
        i: usize,
        parts: &[(BigRational, Vec<Id>)],
        lookup: &dyn Fn(Vec<Id>) -> Option<usize>,
    ) -> Option<(usize, Vec<Id>)> {
        let (cx, fx) = parts[i].clone();
        if fx.len() > MAX_TRIG_FACTORS {
            return None;
        }
        for (k, &f) in fx.iter().enumerate() {
            let Some(a) = self.trig_square(f, Func::Sin) else {
                continue;
            };
            let c = self.func(Func::Cos, a);
            let cos2 = self.powi(c, 2);
            let rest = without(&fx, k);
            let mut want = rest.clone();
            want.push(cos2);
            let Some(j) = lookup(want) else { continue };
            let cy = parts[j].0.clone();
            // cx·R·sin² + cy·R·cos²: keep whichever square has the larger coefficient.
            let (keep, square, other) = if cx.abs() >= cy.abs() {
                (cy.clone(), f, cx.clone())
            } else {
                (cx.clone(), cos2, cy.clone())
            };
            let r = self.product(rest.clone());
            let t1 = self.scale(&keep, r);
            let mut sq = rest;
            sq.push(square);
            let base = self.product(sq);
            let diff = &other - &keep;
            let t2 = self.scale(&diff, base);
            return Some((j, vec![t1, t2]));
        }
        None
    }

    /// Rule `angle-difference` for term `i`.
    fn angle_partner(
        &mut self,
        i: usize,
        parts: &[(BigRational, Vec<Id>)],
        lookup: &dyn Fn(Vec<Id>) -> Option<usize>,
    ) -> Option<(usize, Vec<Id>)> {
        let (cx, fx) = parts[i].clone();
        if fx.len() > MAX_TRIG_FACTORS {
            return None;
        }
        // cos a cos b ± sin a sin b = cos(a ∓ b); sin a cos b ± cos a sin b = sin(a ± b).
        for (k, &p) in fx.iter().enumerate() {
            for (l, &q) in fx.iter().enumerate() {
                if k == l {
                    continue;
                }
                let (Node::Func(g1, a), Node::Func(g2, b)) =
                    (self.node(p).clone(), self.node(q).clone())
                else {
                    continue;
                };
                if a == b || g2 != Func::Cos || !matches!(g1, Func::Cos | Func::Sin) {
                    continue;
                }
                if g1 == Func::Cos && k > l {
                    continue; // each unordered pair of cosines once
                }
                let rest = without(&without(&fx, k.max(l)), k.min(l));
                let (pa, pb) = if g1 == Func::Cos {
                    (self.func(Func::Sin, a), self.func(Func::Sin, b))
                } else {
                    (self.func(Func::Cos, a), self.func(Func::Sin, b))
                };
                let mut want = rest.clone();
                want.push(pa);
                want.push(pb);
                if pa == pb {
                    continue;
                }
                let Some(j) = lookup(want) else { continue };
                let cy = &parts[j].0;
                let same = *cy == cx;
                if !same && *cy != -cx.clone() {
                    continue;
                }
                let arg = match (g1, same) {
                    (Func::Cos, true) | (Func::Sin, false) => self.sub(a, b),
                    _ => self.add(a, b),
                };
                let g = if g1 == Func::Cos {
                    Func::Cos
                } else {
                    Func::Sin
                };
                let t = self.func(g, arg);
                let mut f = rest;
                f.push(t);
                let prod = self.product(f);
                return Some((j, vec![self.scale(&cx, prod)]));
            }
        }
        None
    }

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
        rest.sort_unstable();
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

fn sorted(mut v: Vec<Id>) -> Vec<Id> {
    v.sort_unstable();
    v
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
