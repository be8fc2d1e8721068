//! Symbolic small oscillations about an equilibrium given in closed form: M₀, K and the
//! velocity coupling C as expressions, the characteristic polynomial in ω² and its roots in
//! closed form where it factors into pieces of degree ≤ 2 in ω².
//!
//! With velocity-linear terms (rotating frames, magnetic fields) the linearized problem is
//! M δq'' − C δq' + K δq = 0; for a gyroscopic C (antisymmetric) and symmetric K, M the
//! matrix K − ω² M − iωC is Hermitian, so det is a real polynomial in ω² and its roots are
//! the true ω² (the rotating trap's (2 ∓ Ω)², not 4 − Ω² twice). Any other C (damping) or a
//! non-symmetric K (circulatory forces) is refused: no real polynomial in ω² describes it.

use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::det;
use super::system::System;
use crate::expr::{Factored, Id, Sym};

/// Closed forms (a cofactor expansion has n! terms) are given for at most this many
/// coordinates.
const MAX_CLOSED_FORM_COORDINATES: usize = 3;

/// M₀, K and C = ∂f/∂q' at the point, simplified.
struct Linearized {
    mass: Vec<Vec<Id>>,
    stiffness: Vec<Vec<Id>>,
    coupling: Vec<Vec<Id>>,
    /// Kᵢᵢ/Mᵢᵢ simplified before the point is substituted (g cos θ/r, not a ratio of
    /// expanded polynomials), then at the point: the roots of a coordinate that decouples.
    ratios: Vec<Id>,
}

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
        let lin = self.linearized(d, at);
        let gyroscopic = lin.coupling.iter().flatten().any(|&c| !self.is_zero(c));
        if gyroscopic {
            self.check_gyroscopic(&lin)?;
        }
        let omega = self.omega_symbol();
        let x = self.pool.symbol("__omega_squared");
        let p = self.characteristic(&lin, x, gyroscopic);
        let ov = self.pool.var(omega, 0);
        let w2 = self.pool.powi(ov, 2);
        let display_map: FxHashMap<_, _> = [((x, 0), w2)].into_iter().collect();
        let shown = self.pool.substitute(p, &display_map);
        let characteristic_shown = self.pool.factored(shown);
        let roots = self.closed_form_roots(p, x, &lin, gyroscopic);
        let (omega_squared, omega_squared_shown) = roots.into_iter().unzip();
        Ok(SymbolicModes {
            mass: lin.mass,
            stiffness: lin.stiffness,
            characteristic: shown,
            characteristic_shown,
            omega,
            omega_squared,
            omega_squared_shown,
            gyroscopic,
        })
    }

    /// M₀, K = −∂f/∂q and C = ∂f/∂q' at rest at `at`.
    fn linearized(&mut self, d: &Derivation, at: &[Id]) -> Linearized {
        let n = self.n();
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
        let mut coupling = vec![vec![zero; n]; n];
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
        // After M and K, so that their entries enter the pool in the order they always have.
        for (row, &f) in coupling.iter_mut().zip(&d.forcing) {
            for (entry, &q) in row.iter_mut().zip(&coords) {
                let c = self.pool.diff(f, q, 1);
                let c = self.pool.substitute(c, &map);
                *entry = self.simplify(c);
            }
        }
        let ratios = self.diagonal_ratios(d, &map);
        Linearized {
            mass,
            stiffness,
            coupling,
            ratios,
        }
    }

    /// Kᵢᵢ/Mᵢᵢ at rest, simplified with the coordinates still symbolic, then at the point
    /// (`map` sends each q to its value and each q', q'' to 0).
    fn diagonal_ratios(&mut self, d: &Derivation, map: &FxHashMap<(Sym, u8), Id>) -> Vec<Id> {
        let coords = self.coordinate_syms();
        let rest: FxHashMap<_, _> = map
            .iter()
            .filter(|(k, _)| k.1 > 0)
            .map(|(k, v)| (*k, *v))
            .collect();
        (0..self.n())
            .map(|i| {
                let dfdq = self.pool.diff(d.forcing[i], coords[i], 0);
                let k = self.pool.neg(dfdq);
                let r = self.pool.div(k, d.mass[i][i]);
                let r = self.pool.substitute(r, &rest);
                let r = self.simplify(r);
                let r = self.pool.substitute(r, map);
                self.simplify(r)
            })
            .collect()
    }

    /// C must be antisymmetric (gyroscopic) and K symmetric, or ω² is not the root of a
    /// real polynomial: refused with the reason rather than given a wrong closed form.
    fn check_gyroscopic(&mut self, lin: &Linearized) -> Result<(), MechError> {
        let n = lin.mass.len();
        for i in 0..n {
            for j in i..n {
                let c = self.pool.add(lin.coupling[i][j], lin.coupling[j][i]);
                if !self.is_zero(c) {
                    return Err(MechError::ClosedFormNotGyroscopic {
                        reason:
                            "the velocity terms damp (or pump) the motion: they are not gyroscopic"
                                .into(),
                    });
                }
                let k = self.pool.sub(lin.stiffness[i][j], lin.stiffness[j][i]);
                if !self.is_zero(k) {
                    return Err(MechError::ClosedFormNotGyroscopic {
                        reason: "the position forces are circulatory (K is not symmetric)".into(),
                    });
                }
            }
        }
        Ok(())
    }

    /// The characteristic polynomial in x = ω², simplified. With a gyroscopic C it is
    /// det(K − xM − sC) at s = iω: even in s, so Σₖ P₂ₖ(x)·(−x)ᵏ with P₂ₖ the s²ᵏ
    /// coefficient.
    fn characteristic(&mut self, lin: &Linearized, x: Sym, gyroscopic: bool) -> Id {
        let n = lin.mass.len();
        let xv = self.pool.var(x, 0);
        let s = self.pool.symbol("__s");
        let sv = self.pool.var(s, 0);
        let matrix: Vec<Vec<Id>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| {
                        let t = self.pool.mul(xv, lin.mass[i][j]);
                        let e = self.pool.sub(lin.stiffness[i][j], t);
                        if gyroscopic {
                            let c = self.pool.mul(sv, lin.coupling[i][j]);
                            self.pool.sub(e, c)
                        } else {
                            e
                        }
                    })
                    .collect()
            })
            .collect();
        let p = det(&mut self.pool, &matrix);
        if !gyroscopic {
            return self.simplify(p);
        }
        let coefficients = self.coefficients(p, s, n);
        let mut terms = Vec::new();
        let nx = self.pool.neg(xv);
        for (j, c) in coefficients.into_iter().enumerate().step_by(2) {
            let pw = self.pool.powi(nx, (j / 2) as i64);
            terms.push(self.pool.mul(c, pw));
        }
        let q = self.pool.sum(terms);
        let q = self.pool.expand(q);
        self.simplify(q)
    }

    /// The coefficients c₀ … c_deg of p as a polynomial in `s` (Taylor at s = 0).
    fn coefficients(&mut self, p: Id, s: Sym, deg: usize) -> Vec<Id> {
        let zero = self.pool.zero();
        let at0: FxHashMap<_, _> = [((s, 0), zero)].into_iter().collect();
        let mut out = Vec::with_capacity(deg + 1);
        let mut dp = p;
        let mut factorial = 1i64;
        for j in 0..=deg {
            if j > 0 {
                dp = self.pool.diff(dp, s, 0);
                factorial *= j as i64;
            }
            let c = self.pool.substitute(dp, &at0);
            let inv = self.pool.ratio(1, factorial);
            let c = self.pool.mul(inv, c);
            out.push(self.simplify(c));
        }
        out
    }

    /// The roots of p(x) in closed form: x = 0 where p(0) ≡ 0, the ratios Kᵢᵢ/Mᵢᵢ where they
    /// are roots (a coordinate that decouples at the point), each divided out; then a
    /// remaining factor of degree ≤ 2 by formula. Empty unless every root is found.
    fn closed_form_roots(
        &mut self,
        p: Id,
        x: Sym,
        lin: &Linearized,
        gyroscopic: bool,
    ) -> Vec<(Id, Factored)> {
        let n = lin.mass.len();
        let mut coeffs = self.coefficients(p, x, n);
        while coeffs.len() > 1 && coeffs.last().is_some_and(|&c| self.is_zero(c)) {
            coeffs.pop();
        }
        let mut found: Vec<Id> = Vec::new();
        while coeffs.len() > 1 && self.is_zero(coeffs[0]) {
            found.push(self.pool.zero());
            coeffs.remove(0);
        }
        for i in 0..n {
            if coeffs.len() <= 1 || self.is_zero(lin.mass[i][i]) {
                continue;
            }
            let c = lin.ratios[i];
            let value = self.horner(&coeffs, c);
            if self.is_zero(value) {
                coeffs = self.deflate(&coeffs, c);
                found.push(c);
            }
        }
        let degree = coeffs.len() - 1;
        if found.is_empty() && !gyroscopic && degree == n {
            // Nothing divides out: the formula on the whole polynomial, as always.
            return if n <= 2 {
                self.quadratic_roots(p, x)
            } else {
                Vec::new()
            };
        }
        if degree > 2 {
            return Vec::new();
        }
        let mut out: Vec<(Id, Factored)> = found.into_iter().map(|r| self.tidy(r)).collect();
        let two = coeffs.get(2).copied().unwrap_or_else(|| self.pool.zero());
        let (a, b, c) = (two, coeffs.get(1).copied(), coeffs[0]);
        if let Some(b) = b {
            out.extend(self.roots_of(a, b, c));
        }
        out
    }

    /// Σ cᵢ vⁱ.
    fn horner(&mut self, coeffs: &[Id], v: Id) -> Id {
        let mut acc = self.pool.zero();
        for &c in coeffs.iter().rev() {
            let t = self.pool.mul(acc, v);
            acc = self.pool.add(t, c);
        }
        let acc = self.pool.expand(acc);
        self.simplify(acc)
    }

    /// The coefficients of p(x)/(x − r), for a root r (synthetic division).
    fn deflate(&mut self, coeffs: &[Id], r: Id) -> Vec<Id> {
        let d = coeffs.len() - 1;
        let mut out = vec![self.pool.zero(); d];
        let mut carry = self.pool.zero();
        for k in (1..=d).rev() {
            let t = self.pool.mul(carry, r);
            let b = self.pool.add(coeffs[k], t);
            let b = self.simplify(b);
            out[k - 1] = b;
            carry = b;
        }
        out
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
        self.roots_of(a, b, c)
    }

    /// Roots of a x² + b x + c (a linear one when a is 0), simplified and shown.
    fn roots_of(&mut self, a: Id, b: Id, c: Id) -> Vec<(Id, Factored)> {
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
    /// det(K − ω² M₀) (with gyroscopic terms, det(K − ω² M₀ − iωC)), in the symbol `omega`.
    pub characteristic: Id,
    /// The characteristic polynomial as shown, common factors pulled out
    /// (print it with [`Pool::display_factored`](crate::expr::Pool::display_factored)).
    pub(crate) characteristic_shown: Factored,
    /// The symbol used for ω.
    pub omega: Sym,
    /// ω² in closed form where every root was found (the polynomial factors into pieces
    /// of degree ≤ 2 in ω²), ascending where comparable; empty otherwise.
    pub omega_squared: Vec<Id>,
    /// Each ω² as shown, common factors pulled out: (2 + √2)·g/l.
    pub(crate) omega_squared_shown: Vec<Factored>,
    /// Gyroscopic (antisymmetric velocity) terms entered the characteristic polynomial.
    pub(crate) gyroscopic: bool,
}
