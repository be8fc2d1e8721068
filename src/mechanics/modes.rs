//! Small oscillations about an equilibrium: the linearized equations M δq̈ + C δq̇ + K δq = 0
//! (see [`linearize`](super::linearize), on the constraint manifold when there are
//! constraints). Without velocity terms and with a symmetric K, the generalized symmetric
//! eigenproblem K v = ω² M v gives frequencies, mode shapes and growth rates; otherwise the
//! quadratic eigenproblem (see [`quadratic`](super::quadratic)) gives frequencies, damping and
//! growth. ω² = 0 (a free direction: a cart, a translating chain) is decided relative to the
//! matrices' scale, never by the sign of rounding. Symbolically: det(K − ω² M₀) and, for one
//! or two coordinates, its roots in closed form.

use nalgebra::DMatrix;
use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::equilibria::{EIGENVALUE_ZERO, Stability, Statics};
use super::error::MechError;
use super::linalg::{det, generalized_eigen};
use super::linearize::Linear;
use super::quadratic::{self, Damped};
use super::system::System;
use crate::expr::{Factored, Id, Sym};

/// Closed forms (a cofactor expansion has n! terms) are given for at most this many
/// coordinates.
const MAX_CLOSED_FORM_COORDINATES: usize = 3;

/// One normal mode.
#[derive(Clone, Debug)]
pub struct Mode {
    /// The eigenvalue ω² (negative for an unstable direction; exactly 0 for a free motion).
    pub omega_squared: f64,
    /// Shape, normalized so that the largest component is 1, rounding set to 0 (empty when
    /// not available).
    pub shape: Vec<f64>,
}

/// The small-oscillation analysis at one point.
#[derive(Clone, Debug)]
pub struct Modes {
    /// The point analysed, one value per coordinate.
    pub point: Vec<f64>,
    /// Unstable if anything grows, marginal with a zero mode, otherwise stable.
    pub stability: Stability,
    /// Angular frequencies ω of the undamped modes, ascending, with 0 for each free motion.
    pub frequencies: Vec<f64>,
    /// Growth rates of the unstable modes, ascending.
    pub growth_rates: Vec<f64>,
    /// The normal modes (only without velocity terms, where shapes are real).
    pub modes: Vec<Mode>,
    /// Antisymmetric velocity terms (rotating frames, magnetic fields) survive.
    pub gyroscopic: bool,
    /// Symmetric velocity terms (friction, drag) survive.
    pub damping: bool,
    /// Damped oscillations: frequency, decay rate, damping ratio.
    pub damped: Vec<Damped>,
    /// Decay rates of modes that decay without oscillating.
    pub decay_rates: Vec<f64>,
    /// Directions along which a displacement is not restored (ω = 0), largest component 1.
    pub free_directions: Vec<Vec<f64>>,
}

impl Modes {
    /// What each mode's shape means, where it means something: "only x moves" when one
    /// coordinate moves; in phase / antiphase with the ratio when exactly two move; a free
    /// motion for ω = 0; nothing otherwise.
    pub fn describe(&self, names: &[String]) -> Vec<String> {
        self.modes
            .iter()
            .map(|m| {
                let moving: Vec<usize> =
                    (0..m.shape.len()).filter(|&i| m.shape[i] != 0.0).collect();
                let name = |i: usize| names.get(i).map_or("?", String::as_str);
                let w2 = m.omega_squared;
                let degenerate = self
                    .modes
                    .iter()
                    .filter(|o| (o.omega_squared - w2).abs() <= 1e-9 * w2.abs())
                    .count()
                    > 1;
                match moving[..] {
                    _ if w2 == 0.0 => "free motion (ω = 0)".into(),
                    // Any combination of modes with one ω² is a mode: no shape is special.
                    _ if degenerate => {
                        "degenerate: any combination of the modes with this ω² is a mode".into()
                    }
                    // With one coordinate there is nothing to compare.
                    [_] if m.shape.len() == 1 => String::new(),
                    [i] => format!("only {} moves", name(i)),
                    [i, j] => {
                        let r = m.shape[j] / m.shape[i];
                        let kind = if r > 0.0 { "in phase" } else { "antiphase" };
                        format!("{kind}, {}/{} = {:.6}", name(j), name(i), r)
                    }
                    _ => String::new(),
                }
            })
            .collect()
    }
}

impl System {
    /// Normal modes about `q0` with parameter values `params`.
    pub fn modes_at(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
    ) -> Result<Modes, MechError> {
        // The static analysis refuses what it cannot analyse; its refusals hold here too.
        Statics::new(self, d, params)?;
        let lin = self.linearize(d, params, q0)?;
        if lin.conservative() {
            symmetric_modes(&lin, q0)
        } else {
            quadratic_modes(&lin, q0)
        }
    }
}

/// K v = ω² M v, with ω² = 0 decided relative to the scale of K's terms and eigenvalues.
fn symmetric_modes(lin: &Linear, q0: &[f64]) -> Result<Modes, MechError> {
    let k = (&lin.k + lin.k.transpose()) * 0.5;
    let (vals, vecs) = generalized_eigen(&k, &lin.m)?;
    let scale = vals.iter().fold(lin.k_size, |a, v| a.max(v.abs()));
    let tol = EIGENVALUE_ZERO * scale;
    let full = &lin.tangent * vecs;
    let mut out = empty(q0);
    for (col, &w2) in vals.iter().enumerate() {
        let w2 = if w2.abs() <= tol { 0.0 } else { w2 };
        let shape = shape_of(&full.column(col).iter().copied().collect::<Vec<_>>());
        if w2 > 0.0 {
            out.frequencies.push(w2.sqrt());
        } else if w2 < 0.0 {
            out.growth_rates.push((-w2).sqrt());
        } else {
            out.frequencies.push(0.0);
            out.free_directions.push(shape.clone());
        }
        out.modes.push(Mode {
            omega_squared: w2,
            shape,
        });
    }
    out.frequencies.sort_by(f64::total_cmp);
    out.growth_rates.sort_by(f64::total_cmp);
    out.stability = if !out.growth_rates.is_empty() {
        Stability::Unstable
    } else if out.free_directions.is_empty() {
        Stability::Stable
    } else {
        Stability::Marginal
    };
    Ok(out)
}

/// λ² M + λ C + K = 0 through the companion form.
fn quadratic_modes(lin: &Linear, q0: &[f64]) -> Result<Modes, MechError> {
    let floor = lin.k_size.sqrt().max(lin.c_size);
    let s = quadratic::solve(&lin.m, &lin.c, &lin.k, floor)?;
    let gyro = &lin.c - lin.c.transpose();
    let damp = &lin.c + lin.c.transpose();
    let mut out = empty(q0);
    out.stability = s.stability;
    out.frequencies = s.frequencies;
    out.growth_rates = s.growth_rates;
    out.gyroscopic = gyro.iter().any(|x| *x != 0.0);
    out.damping = damp.iter().any(|x| *x != 0.0);
    if out.damping {
        out.damped = s.damped;
        out.decay_rates = s.decay_rates;
    }
    // Without damping the spectrum is symmetric under λ → −λ: a decaying λ is only the
    // time-reversed partner of a growing one, not a mode of its own.
    out.free_directions = s
        .free_directions
        .iter()
        .map(|v| {
            let full = &lin.tangent * DMatrix::from_column_slice(v.len(), 1, v);
            shape_of(full.as_slice())
        })
        .collect();
    Ok(out)
}

fn empty(q0: &[f64]) -> Modes {
    Modes {
        point: q0.to_vec(),
        stability: Stability::Marginal,
        frequencies: Vec::new(),
        growth_rates: Vec::new(),
        modes: Vec::new(),
        gyroscopic: false,
        damping: false,
        damped: Vec::new(),
        decay_rates: Vec::new(),
        free_directions: Vec::new(),
    }
}

/// Largest component 1, first nonzero positive, and components that are rounding relative
/// to the largest set to exactly 0 (so that "θ/x = 0.000000" is never shown as a ratio).
fn shape_of(v: &[f64]) -> Vec<f64> {
    quadratic::normalize(&nalgebra::DVector::from_column_slice(v))
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
