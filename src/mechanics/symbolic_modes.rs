//! Symbolic small oscillations about an equilibrium given in closed form: M₀ and K as
//! expressions, det(K − ω² M₀) and, for one or two coordinates, its roots in closed form.

use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::det;
use super::system::System;
use crate::expr::{Factored, Id, Sym};

/// Closed forms (a cofactor expansion has n! terms) are given for at most this many
/// coordinates.
const MAX_CLOSED_FORM_COORDINATES: usize = 3;

impl System {
    /// Symbolic small oscillations about `at` (one expression per coordinate).
    pub fn symbolic_modes(
        &mut self,
        d: &Derivation,
        at: &[Id],
    ) -> Result<SymbolicModes, MechError> {
        let n = self.n();
        // A cofactor expansion has n! terms: closed forms are for small systems only.
        if n > MAX_CLOSED_FORM_COORDINATES {
            return Err(MechError::ClosedFormTooLarge {
                n,
                max: MAX_CLOSED_FORM_COORDINATES,
            });
        }
        let coords = self.coordinate_syms();
        let zero = self.pool.zero();
        let mut map: FxHashMap<_, _> = FxHashMap::default();
        for (&c, &v) in coords.iter().zip(at) {
            map.insert((c, 0), v);
            map.insert((c, 1), zero);
            map.insert((c, 2), zero);
        }
        let mut mass = vec![vec![zero; n]; n];
        let mut stiffness = vec![vec![zero; n]; n];
        for i in 0..n {
            for j in 0..n {
                let m = self.pool.substitute(d.mass[i][j], &map);
                mass[i][j] = self.simplify(m);
                let dfdq = self.pool.diff(d.forcing[i], coords[j], 0);
                let k = self.pool.neg(dfdq);
                let k = self.pool.substitute(k, &map);
                stiffness[i][j] = self.simplify(k);
            }
        }
        let omega = self.omega_symbol();
        let x = self.pool.symbol("__omega_squared");
        let xv = self.pool.var(x, 0);
        let kmx: Vec<Vec<Id>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        let t = self.pool.mul(xv, mass[i][j]);
                        self.pool.sub(stiffness[i][j], t)
                    })
                    .collect()
            })
            .collect();
        let p = det(&mut self.pool, &kmx);
        let p = self.simplify(p);
        let ov = self.pool.var(omega, 0);
        let w2 = self.pool.powi(ov, 2);
        let display_map: FxHashMap<_, _> = [((x, 0), w2)].into_iter().collect();
        let shown = self.pool.substitute(p, &display_map);
        let characteristic_shown = self.pool.factored(shown);
        let roots = match n {
            1 | 2 => self.quadratic_roots(p, x),
            _ => Vec::new(),
        };
        let (omega_squared, omega_squared_shown) = roots.into_iter().unzip();
        Ok(SymbolicModes {
            mass,
            stiffness,
            characteristic: shown,
            characteristic_shown,
            omega,
            omega_squared,
            omega_squared_shown,
        })
    }

    /// A symbol for ω that is not a parameter of the system.
    fn omega_symbol(&mut self) -> Sym {
        let name = if self.parameters.iter().any(|p| p.name == "omega") {
            "Omega"
        } else {
            "omega"
        };
        self.pool.symbol(name)
    }

    /// Roots in x of the polynomial p (degree 1 or 2), simplified, each with its display form.
    fn quadratic_roots(&mut self, p: Id, x: Sym) -> Vec<(Id, Factored)> {
        let zero = self.pool.zero();
        let at0: FxHashMap<_, _> = [((x, 0), zero)].into_iter().collect();
        let c = self.pool.substitute(p, &at0);
        let p1 = self.pool.diff(p, x, 0);
        let b = self.pool.substitute(p1, &at0);
        let p2 = self.pool.diff(p1, x, 0);
        let a2 = self.pool.substitute(p2, &at0);
        let half = self.pool.ratio(1, 2);
        let a = self.pool.mul(half, a2);
        let (a, b, c) = (self.simplify(a), self.simplify(b), self.simplify(c));
        let mut out = Vec::new();
        if self.pool.is_zero(a) {
            if !self.pool.is_zero(b) {
                let nc = self.pool.neg(c);
                let r = self.pool.div(nc, b);
                out.push(self.tidy(r));
            }
            return out;
        }
        // (−b ± √(b² − 4ac)) / 2a
        let b2 = self.pool.powi(b, 2);
        let four = self.pool.int(4);
        let ac4 = self.pool.product([four, a, c]);
        let disc = self.pool.sub(b2, ac4);
        let disc = self.simplify(disc);
        let root = self.pool.sqrt(disc);
        let root = self.simplify(root);
        let two = self.pool.int(2);
        let den = self.pool.mul(two, a);
        let nb = self.pool.neg(b);
        for sign in [-1, 1] {
            let s = self.pool.int(sign);
            let sr = self.pool.mul(s, root);
            let num = self.pool.add(nb, sr);
            let r = self.pool.div(num, den);
            out.push(self.tidy(r));
        }
        out
    }

    /// Simplified, and with common factors pulled out for display: (2 + √2)·g/l. Each root
    /// is factored right after it is simplified, so that the pool grows in the order the
    /// printed forms have always been built in.
    fn tidy(&mut self, e: Id) -> (Id, Factored) {
        let s = self.simplify(e);
        (s, self.pool.factored(s))
    }
}

/// The symbolic small-oscillation results.
#[derive(Clone, Debug)]
pub struct SymbolicModes {
    pub mass: Vec<Vec<Id>>,
    pub stiffness: Vec<Vec<Id>>,
    /// det(K − ω² M₀), in the symbol `omega`.
    pub characteristic: Id,
    /// The characteristic polynomial as shown, common factors pulled out
    /// (print it with [`Pool::display_factored`](crate::expr::Pool::display_factored)).
    pub characteristic_shown: Factored,
    /// The symbol used for ω.
    pub omega: Sym,
    /// ω² in closed form (for one or two coordinates), ascending where comparable.
    pub omega_squared: Vec<Id>,
    /// Each ω² as shown, common factors pulled out: (2 + √2)·g/l.
    pub omega_squared_shown: Vec<Factored>,
}
