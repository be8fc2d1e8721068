//! Taylor polynomials of a system about a point, for linearized parts (`about`): T, V and L
//! to second order in the displacements q − q₀ and the velocities, the generalized forces to
//! first. A leaf of the checker (the preparation of a part uses it; the diagnosis of a
//! linearized answer is `linearize.rs`).

use rustc_hash::FxHashMap;

use super::error::CheckError;
use crate::expr::{Id, Sym, read_expr};
use crate::mechanics::System;

/// The order a linearized energy is expanded to (equations then come out linear).
pub const ORDER: u32 = 2;

/// Where a linearized part's system was expanded: the point, one value per coordinate.
#[derive(Clone, Debug)]
pub struct Expansion {
    pub(crate) point: Vec<Id>,
}

/// The expansion point of `about` (coordinates not named expand about 0).
fn point_of(sys: &mut System, about: &[(String, String)]) -> Result<Vec<Id>, CheckError> {
    let ctx = sys.context();
    let mut point = vec![sys.pool.zero(); sys.n()];
    for (name, text) in about {
        let i = sys
            .coordinates
            .iter()
            .position(|c| c.name == crate::expr::names::normalize(name))
            .ok_or_else(|| CheckError::BadAt { name: name.clone() })?;
        point[i] =
            read_expr(text, &ctx, &mut sys.pool).map_err(|e| CheckError::UnreadableItem {
                src: text.clone(),
                error: Box::new(e),
            })?;
    }
    Ok(point)
}

/// Replaces the system by its expansion about `about` (T, V, L to second order, the forces
/// to first); returns the point.
pub fn linearize(sys: &mut System, about: &[(String, String)]) -> Result<Expansion, CheckError> {
    let point = point_of(sys, about)?;
    sys.lagrangian = taylor(sys, sys.lagrangian, &point, ORDER);
    sys.kinetic = sys.kinetic.map(|t| taylor(sys, t, &point, ORDER));
    sys.potential = sys.potential.map(|v| taylor(sys, v, &point, ORDER));
    let forces = sys.forces.clone();
    sys.forces = forces
        .into_iter()
        .map(|f| taylor(sys, f, &point, ORDER - 1))
        .collect();
    Ok(Expansion { point })
}

/// The Taylor polynomial of `e` of total order `order` in q − q₀, q̇ and q̈ about (q₀, 0, 0):
/// with g(ε) = e(q₀ + ε(q − q₀), ε q̇, ε q̈), the sum of g⁽ᵏ⁾(0)/k! for k ≤ order. Time stays as it is.
pub fn taylor(sys: &mut System, e: Id, point: &[Id], order: u32) -> Id {
    let eps: Sym = sys.pool.symbol("ε·taylor");
    let eps_id = sys.pool.var(eps, 0);
    let coords = sys.coordinate_syms();
    let mut scale: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
    for (&c, &q0) in coords.iter().zip(point) {
        let q = sys.pool.var(c, 0);
        let d = sys.pool.sub(q, q0);
        let d = sys.pool.mul(eps_id, d);
        scale.insert((c, 0), sys.pool.add(q0, d));
        // Velocities and accelerations are small with the displacements.
        for order in [1, 2] {
            let v = sys.pool.var(c, order);
            scale.insert((c, order), sys.pool.mul(eps_id, v));
        }
    }
    let mut at_zero: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
    at_zero.insert((eps, 0), sys.pool.zero());
    let mut g = sys.pool.substitute(e, &scale);
    let mut sum = sys.pool.zero();
    let mut factorial: i64 = 1;
    for k in 0..=order {
        if k > 0 {
            g = sys.pool.diff(g, eps, 0);
            g = sys.simplify(g);
            factorial *= i64::from(k);
        }
        let term = sys.pool.substitute(g, &at_zero);
        let c = sys.pool.ratio(1, factorial);
        let term = sys.pool.mul(c, term);
        sum = sys.pool.add(sum, term);
    }
    sys.simplify(sum)
}

#[cfg(test)]
mod tests {
    use super::taylor;
    use crate::expr::{Program, read_expr};
    use crate::mechanics::System;

    #[test]
    fn taylor_polynomials_are_exact() {
        // cos about π to second order: −1 + (θ − π)²/2, compared with that polynomial written
        // out at points near and far from π (a polynomial identity holds everywhere).
        let mut sys = System::from_lagrangian("theta'^2/2 + cos(theta)", &["theta"]).unwrap();
        let ctx = sys.context();
        let cos = read_expr("cos(theta)", &ctx, &mut sys.pool).unwrap();
        let pi = sys.pool.pi();
        let t = taylor(&mut sys, cos, &[pi], 2);
        let want = read_expr("-1 + (theta - pi)^2/2", &ctx, &mut sys.pool).unwrap();
        let vars = sys.pool.variables(want);
        assert_eq!(vars, sys.pool.variables(t));
        let p = Program::compile(&sys.pool, &[t, want], &vars).unwrap();
        for th in [0.3, 1.0, 2.5, -0.7] {
            let v = p.eval(&[th]).unwrap();
            assert!(
                (v[0] - v[1]).abs() < 1e-12,
                "θ = {th}: {} vs {}",
                v[0],
                v[1]
            );
        }
    }
}
