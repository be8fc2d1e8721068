//! Rule `expand`: products of sums and small integer powers of sums multiplied out, within
//! [`MAX_EXPANDED_TERMS`] terms and [`MAX_TREE_SIZE`] nodes.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;

use super::MAX_EXPANDED_TERMS;
use crate::expr::node::{Id, Node};
use crate::expr::pool::{MAX_TREE_SIZE, Pool};

impl Pool {
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
    pub(super) fn expand_node(&mut self, n: Id) -> Id {
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
}
