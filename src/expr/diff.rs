//! Differentiation: the partial derivative with respect to any variable (a symbol or one of
//! its time derivatives, so ∂/∂q' is as easy as ∂/∂q) and the total time derivative d/dt.
//!
//! Both are one chain-rule engine with a different rule for leaves. Nodes are visited in
//! ascending id order (children first), so no recursion is needed.

use rustc_hash::FxHashMap;

use super::node::{Func, Id, Node, Sym};
use super::pool::Pool;

impl Pool {
    /// ∂e/∂v where v is `s` differentiated `order` times in time.
    pub fn diff(&mut self, e: Id, s: Sym, order: u8) -> Id {
        self.derive(e, &mut |pool, x, o| {
            if x == s && o == order {
                pool.one()
            } else {
                pool.zero()
            }
        })
    }

    /// The total time derivative de/dt: each coordinate in `coordinates` (and anything
    /// already differentiated in time) moves up one order, `t` gives 1, parameters 0.
    pub fn dt(&mut self, e: Id, coordinates: &[Sym]) -> Id {
        let time = self.time();
        self.derive(e, &mut |pool, x, o| {
            if x == time && o == 0 {
                pool.one()
            } else if o > 0 || coordinates.contains(&x) {
                pool.var(x, o.saturating_add(1))
            } else {
                pool.zero()
            }
        })
    }

    /// The chain rule, with `leaf` giving the derivative of each variable.
    pub fn derive(&mut self, e: Id, leaf: &mut dyn FnMut(&mut Pool, Sym, u8) -> Id) -> Id {
        let mut reach: Vec<Id> = Vec::new();
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![e];
        while let Some(n) = stack.pop() {
            if seen.insert(n) {
                reach.push(n);
                self.push_children(n, &mut stack);
            }
        }
        reach.sort_unstable();
        let mut d: FxHashMap<Id, Id> = FxHashMap::default();
        for n in reach {
            let dn = self.derive_node(n, &d, leaf);
            d.insert(n, dn);
        }
        d[&e]
    }

    fn derive_node(
        &mut self,
        n: Id,
        d: &FxHashMap<Id, Id>,
        leaf: &mut dyn FnMut(&mut Pool, Sym, u8) -> Id,
    ) -> Id {
        let zero = self.zero();
        match self.node(n).clone() {
            Node::Num(_) | Node::Pi => zero,
            Node::Var(s, o) => leaf(self, s, o),
            Node::Add(ch) => {
                let terms: Vec<Id> = ch.iter().map(|c| d[c]).filter(|&x| x != zero).collect();
                self.sum(terms)
            }
            Node::Mul(ch) => {
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
                        return zero;
                    }
                    // e · b^(e−1) · b'
                    let m1 = self.minus_one();
                    let e1 = self.add(e, m1);
                    let p = self.pow(b, e1);
                    return self.product([e, p, db]);
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
                    return zero;
                }
                let outer = self.func_derivative(f, a);
                self.mul(outer, da)
            }
        }
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
