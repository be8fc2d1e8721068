//! Conserved quantities: the energy function h = Σ qᵢ' ∂L/∂qᵢ' − L, whether it is conserved
//! (∂L/∂t ≡ 0 and no non-conservative forces), whether it equals T + V, the conjugate
//! momenta and the cyclic coordinates.

use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::system::System;
use crate::expr::Id;

/// What the energy analysis finds.
#[derive(Clone, Debug)]
pub struct Energy {
    /// h, simplified.
    pub function: Id,
    /// ∂L/∂t ≡ 0 and every Qᵢ ≡ 0.
    pub conserved: bool,
    /// h ≡ T + V. With only L given, T is taken as the velocity-dependent part of L.
    pub is_total: bool,
    /// T + V as compared.
    pub total: Id,
    /// Indices of cyclic coordinates (∂L/∂qᵢ ≡ 0); their momenta are conserved.
    pub cyclic: Vec<usize>,
}

impl System {
    /// The energy function and the conserved quantities.
    pub fn energy(&mut self, d: &Derivation) -> Energy {
        let l = self.lagrangian;
        let mut terms = Vec::new();
        for (c, s) in self.coordinates.clone().iter().zip(&d.steps) {
            let v = self.pool.var(c.sym, 1);
            terms.push(self.pool.mul(v, s.momentum));
        }
        let sum = self.pool.sum(terms);
        let h = self.pool.sub(sum, l);
        let h = self.simplify(h);
        let time = self.pool.time();
        let dldt = self.pool.diff(l, time, 0);
        let conserved = self.is_zero(dldt) && self.forces.iter().all(|&q| self.is_zero(q));
        let (t, v) = match (self.kinetic, self.potential) {
            (Some(t), Some(v)) => (t, v),
            _ => {
                let zero = self.pool.zero();
                let still: FxHashMap<_, _> = self
                    .coordinate_syms()
                    .into_iter()
                    .map(|c| ((c, 1), zero))
                    .collect();
                let l0 = self.pool.substitute(l, &still);
                (self.pool.sub(l, l0), self.pool.neg(l0))
            }
        };
        let total = self.pool.add(t, v);
        let total = self.simplify(total);
        let diff = self.pool.sub(h, total);
        let is_total = self.is_zero(diff);
        let cyclic = d
            .steps
            .iter()
            .enumerate()
            .filter(|(_, s)| self.is_zero(s.force))
            .map(|(i, _)| i)
            .collect();
        Energy {
            function: h,
            conserved,
            is_total,
            total,
            cyclic,
        }
    }
}
