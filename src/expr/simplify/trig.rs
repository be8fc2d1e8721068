//! Rules `pythagoras` and `angle-difference`: trig partners found by lookup among the terms
//! of a sum, skipping terms of more than [`MAX_TRIG_FACTORS`] factors.

use num_rational::BigRational;
use num_traits::Signed;
use rustc_hash::FxHashMap;

use super::MAX_TRIG_FACTORS;
use crate::expr::node::{Func, Id, Node};
use crate::expr::pool::Pool;

impl Pool {
    /// Rules `pythagoras` and `angle-difference`, applied to one sum. Terms are indexed by
    /// their factors, so each term finds its partner by lookup rather than by a pairwise
    /// search (sums in an n-link pendulum have hundreds of terms).
    pub(super) fn trig_identities(&mut self, n: Id) -> Id {
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
    crate::sort::sort_unstable(&mut v);
    v
}
