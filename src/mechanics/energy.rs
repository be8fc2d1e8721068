//! Conserved quantities: the energy function h = Σ qᵢ' ∂L/∂qᵢ' − L, its parts by degree in
//! the velocities (h = L₂ − L₀), whether it is conserved, whether it equals T + V (only
//! decidable when T and V are known), the conjugate momenta and the cyclic coordinates.

use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::system::{ConstraintKind, System};
use crate::expr::Id;

/// L split by degree in the velocities: L = L₂ + L₁ + L₀.
#[derive(Clone, Copy, Debug)]
pub struct VelocityParts {
    /// The part quadratic in the velocities.
    pub(crate) l2: Id,
    /// The part linear in the velocities (moving frames, magnetic fields); it drops out of h.
    pub(crate) l1: Id,
    /// The velocity-free part.
    pub l0: Id,
}

/// Why h is or is not conserved.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conservation {
    /// ∂L/∂t ≡ 0, no generalized forces, no time-dependent constraint.
    Conserved,
    /// ∂L/∂t ≡ 0 and the generalized forces do no work (Σ Qᵢ qᵢ' ≡ 0: gyroscopic, magnetic).
    ConservedPowerlessForces,
    /// L depends explicitly on time.
    ExplicitTime,
    /// The generalized forces do work.
    ForcesDoWork,
    /// A constraint depends explicitly on time, so its force does work.
    MovingConstraint,
}

impl Conservation {
    /// Whether h is conserved.
    pub fn holds(self) -> bool {
        matches!(
            self,
            Conservation::Conserved | Conservation::ConservedPowerlessForces
        )
    }
}

/// What the energy analysis finds.
#[derive(Clone, Debug)]
pub struct Energy {
    /// h, simplified.
    pub function: Id,
    /// L₂, L₁, L₀ when L is at most quadratic in the velocities (then h = L₂ − L₀).
    pub parts: Option<VelocityParts>,
    /// Whether h is conserved, and why.
    pub conservation: Conservation,
    /// Whether h is conserved (`conservation.holds()`).
    pub conserved: bool,
    /// h ≡ T + V; `None` when T and V are not known separately (only L was given): then it
    /// cannot be told from L alone.
    pub is_total: Option<bool>,
    /// T + V, when T and V are known.
    pub total: Option<Id>,
    /// T is known and is not a quadratic form in the velocities (it has parts of degree 0
    /// or 1 in them: a moving frame or support): the usual reason h ≠ T + V.
    pub kinetic_not_quadratic: bool,
    /// Indices of cyclic coordinates: ∂L/∂qᵢ ≡ 0, no generalized force on qᵢ and qᵢ in no
    /// constraint; their momenta are conserved.
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
        let parts = self.velocity_parts(self.lagrangian);
        let kinetic_not_quadratic = match self.kinetic {
            Some(t) => match self.velocity_parts(t) {
                Some(p) => !self.is_zero(p.l0) || !self.is_zero(p.l1),
                None => true,
            },
            None => false,
        };
        let conservation = self.conservation();
        let (is_total, total) = match (self.kinetic, self.potential) {
            (Some(t), Some(v)) => {
                let total = self.pool.add(t, v);
                let total = self.simplify(total);
                let diff = self.pool.sub(h, total);
                (Some(self.is_zero(diff)), Some(total))
            }
            _ => (None, None),
        };
        let cyclic = (0..self.n()).filter(|&i| self.is_cyclic(d, i)).collect();
        Energy {
            function: h,
            parts,
            conservation,
            conserved: conservation.holds(),
            is_total,
            total,
            kinetic_not_quadratic,
            cyclic,
        }
    }

    /// The parts of `l` (L, or T) of degree 2, 1, 0 in the velocities, or `None` when it is
    /// not a polynomial of degree ≤ 2 in them (then h has no such split). L₀ = L at rest,
    /// L₁ = Σ qᵢ' ∂L/∂qᵢ' at rest, L₂ the rest, which must be homogeneous of degree 2
    /// (Euler: Σ qᵢ' ∂L₂/∂qᵢ' = 2 L₂).
    fn velocity_parts(&mut self, l: Id) -> Option<VelocityParts> {
        let zero = self.pool.zero();
        let coords = self.coordinate_syms();
        let still: FxHashMap<_, _> = coords.iter().map(|&c| ((c, 1), zero)).collect();
        let l0 = self.pool.substitute(l, &still);
        let mut linear = Vec::new();
        for &c in &coords {
            let v = self.pool.var(c, 1);
            let p = self.pool.diff(l, c, 1);
            let p0 = self.pool.substitute(p, &still);
            linear.push(self.pool.mul(v, p0));
        }
        let l1 = self.pool.sum(linear);
        let rest = self.pool.sub(l, l0);
        let l2 = self.pool.sub(rest, l1);
        let mut euler = Vec::new();
        for &c in &coords {
            let v = self.pool.var(c, 1);
            let p = self.pool.diff(l2, c, 1);
            euler.push(self.pool.mul(v, p));
        }
        let e = self.pool.sum(euler);
        let two_l2 = self.pool.add(l2, l2);
        let check = self.pool.sub(e, two_l2);
        if !self.is_zero(check) {
            return None;
        }
        Some(VelocityParts {
            l2: self.simplify(l2),
            l1: self.simplify(l1),
            l0: self.simplify(l0),
        })
    }

    /// dh/dt = Σ Qᵢ qᵢ' − ∂L/∂t + (the power of the constraint forces, which vanishes unless
    /// a constraint depends on time).
    fn conservation(&mut self) -> Conservation {
        let time = self.pool.time();
        let dldt = self.pool.diff(self.lagrangian, time, 0);
        if !self.is_zero(dldt) {
            return Conservation::ExplicitTime;
        }
        if self
            .constraints
            .clone()
            .iter()
            .any(|c| self.moves(c.expr, c.kind))
        {
            return Conservation::MovingConstraint;
        }
        if self.forces.iter().all(|&q| self.pool.is_zero(q)) {
            return Conservation::Conserved;
        }
        let mut power = Vec::new();
        for (c, q) in self.coordinates.clone().iter().zip(self.forces.clone()) {
            let v = self.pool.var(c.sym, 1);
            power.push(self.pool.mul(q, v));
        }
        let p = self.pool.sum(power);
        if self.is_zero(p) {
            Conservation::ConservedPowerlessForces
        } else {
            Conservation::ForcesDoWork
        }
    }

    /// Whether a constraint's force can do work: a holonomic f(q, t) with ∂f/∂t ≢ 0, or a
    /// velocity constraint with a term free of velocities (a(q, t)·q' + b(q, t), b ≢ 0).
    fn moves(&mut self, e: Id, kind: ConstraintKind) -> bool {
        let free = match kind {
            ConstraintKind::Holonomic => {
                let time = self.pool.time();
                self.pool.diff(e, time, 0)
            }
            ConstraintKind::Nonholonomic => {
                let zero = self.pool.zero();
                let still: FxHashMap<_, _> = self
                    .coordinate_syms()
                    .into_iter()
                    .map(|c| ((c, 1), zero))
                    .collect();
                self.pool.substitute(e, &still)
            }
        };
        !self.is_zero(free)
    }

    /// ∂L/∂qᵢ ≡ 0, Qᵢ ≡ 0, and qᵢ appears in no constraint (a constraint's force acts on
    /// it: the Cartesian pendulum's x, a rolling disk's angle).
    fn is_cyclic(&self, d: &Derivation, i: usize) -> bool {
        let sym = self.coordinates[i].sym;
        self.is_zero(d.steps[i].force)
            && self.is_zero(self.forces[i])
            && !self
                .constraints
                .iter()
                .any(|c| self.pool.variables(c.expr).iter().any(|&(s, _)| s == sym))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn energy_of(l: &str, coords: &[&str]) -> (System, Energy) {
        let mut sys = System::from_lagrangian(l, coords).unwrap();
        let d = sys.derive().unwrap();
        let e = sys.energy(&d);
        (sys, e)
    }

    #[test]
    fn bead_on_a_rotating_wire_from_l_alone_cannot_tell_t_plus_v() {
        // L = ½m(r'² + ω²r²): h = ½mr'² − ½mω²r², and whether it is T + V depends on
        // whether ½mω²r² is kinetic (rotating wire) or −V (a repulsive spring): unknowable.
        let (mut sys, e) = energy_of("1/2*m*(r'^2 + omega^2*r^2)", &["r"]);
        assert_eq!(e.is_total, None);
        assert!(e.total.is_none());
        let p = e.parts.unwrap();
        let want = sys
            .read("-1/2*m*omega^2*r^2", "", &sys.open_context())
            .unwrap();
        let diff = sys.pool.add(p.l0, want);
        assert!(sys.is_zero(diff));
        assert!(e.conserved);
    }

    #[test]
    fn linear_velocity_part_is_split_out() {
        // A charge in a uniform field B along z: L₁ = ½qB(x y' − y x').
        let (sys, e) = energy_of("1/2*m*(x'^2 + y'^2) + 1/2*q*B*(x*y' - y*x')", &["x", "y"]);
        let p = e.parts.unwrap();
        assert!(!sys.is_zero(p.l1));
        assert!(sys.is_zero(p.l0));
        // L₁ makes ∂L/∂x ≢ 0: neither coordinate is cyclic.
        assert!(e.cyclic.is_empty());
    }

    #[test]
    fn non_quadratic_lagrangian_has_no_split() {
        let (_, e) = energy_of("-m*c^2*sqrt(1 - x'^2/c^2)", &["x"]);
        assert!(e.parts.is_none());
        assert_eq!(e.cyclic, vec![0]);
    }

    #[test]
    fn powerless_force_keeps_energy_conserved() {
        let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2)", &["x", "y"]).unwrap();
        sys.set_forces("q*B*y'; -q*B*x'").unwrap();
        let d = sys.derive().unwrap();
        let e = sys.energy(&d);
        assert_eq!(e.conservation, Conservation::ConservedPowerlessForces);
        // A generalized force acts on both: not cyclic.
        assert!(e.cyclic.is_empty());
    }

    #[test]
    fn working_force_breaks_conservation() {
        let mut sys = System::from_lagrangian("1/2*m*x'^2", &["x"]).unwrap();
        sys.set_forces("-b*x'").unwrap();
        let d = sys.derive().unwrap();
        assert_eq!(sys.energy(&d).conservation, Conservation::ForcesDoWork);
    }

    #[test]
    fn coordinate_in_a_constraint_is_not_cyclic() {
        // The Cartesian pendulum: L has no x, but the rod's force acts along x.
        let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) + m*g*y", &["x", "y"]).unwrap();
        sys.add_constraint("x^2 + y^2 = l^2").unwrap();
        let d = sys.derive().unwrap();
        assert!(sys.energy(&d).cyclic.is_empty());
    }

    #[test]
    fn moving_constraint_breaks_conservation() {
        let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
        sys.add_constraint("y = a*cos(w*t)").unwrap();
        let d = sys.derive().unwrap();
        assert_eq!(sys.energy(&d).conservation, Conservation::MovingConstraint);
    }
}
