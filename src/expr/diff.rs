//! Differentiation: the partial derivative with respect to any variable (a symbol or one of
//! its time derivatives, so ∂/∂q' is as easy as ∂/∂q) and the total time derivative d/dt.
//!
//! Both are one chain-rule engine with a different rule for leaves. Nodes are visited in
//! ascending id order (children first), so no recursion is needed.
//!
//! Derivatives can grow much faster than what they differentiate (the product rule copies
//! every factor once per factor; a tower of powers doubles at each level), so each
//! derivative is bounded: past [`MAX_TREE_SIZE`] or [`MAX_NEW_NODES`] the `try_` forms
//! refuse with [`TooLarge`], and the plain forms give the undefined value.

use rustc_hash::FxHashMap;

use super::node::{Func, Id, Node, Sym};
use super::pool::{MAX_NEW_NODES, MAX_TREE_SIZE, Pool, TooLarge};

impl Pool {
    /// ∂e/∂v where v is `s` differentiated `order` times in time; undefined past the size
    /// limits (see [`try_diff`](Self::try_diff)).
    pub fn diff(&mut self, e: Id, s: Sym, order: u8) -> Id {
        self.try_diff(e, s, order)
            .unwrap_or_else(|_| self.undefined())
    }

    /// The total time derivative, undefined past the size limits (see
    /// [`try_dt`](Self::try_dt)).
    pub fn dt(&mut self, e: Id, coordinates: &[Sym]) -> Id {
        self.try_dt(e, coordinates)
            .unwrap_or_else(|_| self.undefined())
    }

    /// The chain rule, undefined past the size limits (see [`try_derive`](Self::try_derive)).
    pub fn derive(&mut self, e: Id, leaf: &mut dyn FnMut(&mut Pool, Sym, u8) -> Id) -> Id {
        self.try_derive(e, leaf)
            .unwrap_or_else(|_| self.undefined())
    }

    /// ∂e/∂v where v is `s` differentiated `order` times in time.
    pub fn try_diff(&mut self, e: Id, s: Sym, order: u8) -> Result<Id, TooLarge> {
        self.try_derive(e, &mut |pool, x, o| {
            if x == s && o == order {
                pool.one()
            } else {
                pool.zero()
            }
        })
    }

    /// The total time derivative de/dt: each coordinate in `coordinates` (and anything
    /// already differentiated in time) moves up one order, `t` gives 1, parameters 0.
    pub fn try_dt(&mut self, e: Id, coordinates: &[Sym]) -> Result<Id, TooLarge> {
        let time = self.time();
        self.try_derive(e, &mut |pool, x, o| {
            if x == time && o == 0 {
                pool.one()
            } else if o > 0 || coordinates.contains(&x) {
                pool.var(x, o.saturating_add(1))
            } else {
                pool.zero()
            }
        })
    }

    /// The chain rule, with `leaf` giving the derivative of each variable. Refuses a
    /// derivative whose tree grows past [`MAX_TREE_SIZE`] or that adds more than
    /// [`MAX_NEW_NODES`] nodes, before doing the work where it can be foreseen.
    pub fn try_derive(
        &mut self,
        e: Id,
        leaf: &mut dyn FnMut(&mut Pool, Sym, u8) -> Id,
    ) -> Result<Id, TooLarge> {
        let mut reach: Vec<Id> = Vec::new();
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![e];
        while let Some(n) = stack.pop() {
            if seen.insert(n) {
                reach.push(n);
                self.push_children(n, &mut stack);
            }
        }
        crate::sort::sort_unstable(&mut reach);
        let start = self.len();
        let mut d: FxHashMap<Id, Id> = FxHashMap::default();
        for n in reach {
            let dn = self.derive_node(n, &d, leaf)?;
            if self.tree_size(dn) > MAX_TREE_SIZE {
                return Err(TooLarge {
                    limit: MAX_TREE_SIZE,
                });
            }
            if self.len() - start > MAX_NEW_NODES {
                return Err(TooLarge {
                    limit: MAX_NEW_NODES,
                });
            }
            d.insert(n, dn);
        }
        Ok(d[&e])
    }

    /// The derivative of node `n`, given those of its children in `d`.
    fn derive_node(
        &mut self,
        n: Id,
        d: &FxHashMap<Id, Id>,
        leaf: &mut dyn FnMut(&mut Pool, Sym, u8) -> Id,
    ) -> Result<Id, TooLarge> {
        let zero = self.zero();
        Ok(match self.node(n).clone() {
            Node::Num(_) | Node::Pi => zero,
            Node::Var(s, o) => leaf(self, s, o),
            Node::Add(ch) => {
                let terms: Vec<Id> = ch.iter().map(|c| d[c]).filter(|&x| x != zero).collect();
                self.sum(terms)
            }
            Node::Mul(ch) => {
                // The product rule writes the other factors once per differentiated factor:
                // foresee the size, so that a product of thousands of factors is refused
                // before thousands of products of thousands of factors are built.
                let size = self.tree_size(n);
                let foreseen = ch
                    .iter()
                    .filter(|c| d[c] != zero)
                    .map(|c| size.saturating_add(self.tree_size(d[c])))
                    .fold(0usize, usize::saturating_add);
                if foreseen > MAX_TREE_SIZE {
                    return Err(TooLarge {
                        limit: MAX_TREE_SIZE,
                    });
                }
                let mut terms = Vec::new();
                for (i, c) in ch.iter().enumerate() {
                    let dc = d[c];
                    if dc == zero {
                        continue;
                    }
                    let mut f: Vec<Id> = Vec::with_capacity(ch.len());
                    f.extend(
                        ch.iter()
                            .enumerate()
                            .filter(|&(j, _)| j != i)
                            .map(|(_, &x)| x),
                    );
                    f.push(dc);
                    terms.push(self.product(f));
                }
                self.sum(terms)
            }
            Node::Pow(b, e) => {
                let (db, de) = (d[&b], d[&e]);
                if de == zero {
                    if db == zero {
                        return Ok(zero);
                    }
                    // e · b^(e−1) · b'
                    let m1 = self.minus_one();
                    let e1 = self.add(e, m1);
                    let p = self.pow(b, e1);
                    return Ok(self.product([e, p, db]));
                }
                // b^e · (e' ln b + e b'/b)
                let lb = self.func(Func::Log, b);
                let t1 = self.mul(de, lb);
                let rb = self.recip(b);
                let t2 = self.product([e, db, rb]);
                let s = self.add(t1, t2);
                self.mul(n, s)
            }
            Node::Func(f, a) => {
                let da = d[&a];
                if da == zero {
                    return Ok(zero);
                }
                let outer = self.func_derivative(f, a);
                self.mul(outer, da)
            }
        })
    }

    /// f'(a).
    fn func_derivative(&mut self, f: Func, a: Id) -> Id {
        match f {
            Func::Sin => self.func(Func::Cos, a),
            Func::Cos => {
                let s = self.func(Func::Sin, a);
                self.neg(s)
            }
            Func::Tan => {
                let c = self.func(Func::Cos, a);
                self.powi(c, -2)
            }
            Func::Asin | Func::Acos => {
                let a2 = self.powi(a, 2);
                let one = self.one();
                let r = self.sub(one, a2);
                let h = self.ratio(-1, 2);
                let p = self.pow(r, h);
                if f == Func::Acos { self.neg(p) } else { p }
            }
            Func::Atan => {
                let a2 = self.powi(a, 2);
                let one = self.one();
                let r = self.add(one, a2);
                self.recip(r)
            }
            Func::Sinh => self.func(Func::Cosh, a),
            Func::Cosh => self.func(Func::Sinh, a),
            Func::Tanh => {
                let t = self.func(Func::Tanh, a);
                let t2 = self.powi(t, 2);
                let one = self.one();
                self.sub(one, t2)
            }
            Func::Exp => self.func(Func::Exp, a),
            Func::Log => self.recip(a),
            Func::Abs => {
                let ab = self.func(Func::Abs, a);
                self.div(a, ab)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::expr::pool::{MAX_TREE_SIZE, TooLarge};
    use crate::expr::{Context, Pool, read_expr};

    #[test]
    fn a_derivative_past_the_size_limit_is_refused() {
        let ctx = Context::new().with_coordinates(["x"]);
        let mut pool = Pool::new();
        let tower = vec!["(x'+2)"; 20].join("^");
        let e = read_expr(&tower, &ctx, &mut pool).unwrap();
        let x = pool.symbol("x");
        let refused = Err(TooLarge {
            limit: MAX_TREE_SIZE,
        });
        // The momentum of a tower of powers, differentiated in time, as a derivation does.
        let p = pool.try_diff(e, x, 1).unwrap();
        assert_eq!(pool.try_dt(p, &[x]), refused);
        // The plain form gives the undefined value instead.
        let d = pool.dt(p, &[x]);
        assert!(pool.is_undefined(d));
        // Well within the limit, nothing changes.
        let small = read_expr("(x'+2)^(x'+2)", &ctx, &mut pool).unwrap();
        let d = pool.try_dt(small, &[x]).unwrap();
        assert!(!pool.is_undefined(d));
        assert!(pool.tree_size(d) < 100);
    }
}
