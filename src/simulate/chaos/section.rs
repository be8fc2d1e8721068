//! The Poincaré section q₁ = 0, q̇₁ > 0 at one energy: a family of initial states on the
//! section at that energy, and the section's points of each one's motion, located on DOP853's
//! dense output ([`crossings`](crate::simulate::events::crossings)).
//!
//! **The family.** Each state is the given state with q₁ = 0, q₂ set to a value s, every
//! velocity 0 except q̇₁, which is solved from h(q, q̇) = E with q̇₁ > 0: h is a quadratic
//! a v² + b v + c in v = q̇₁ (checked at a fourth point); an s where no positive root exists
//! (the energy below the potential there) is refused, with the reason, not moved.
//! q₁ = 0 is taken literally (not modulo 2π): a motion whose q₁ rotates away leaves only the
//! crossings it made before.

use crate::progress::{PARTS, Progress, Silent, fraction, tick};
use crate::simulate::events::{Direction, crossings};
use crate::simulate::{Rhs, SimError, Stats, Tolerances, dop853};

/// How long each integration chunk is, in units of the section's time budget per crossing.
const CHUNK: f64 = 20.0;

/// The state on the section q₁ = 0 with q₂ = `s` (the rest of `base`, velocities 0) at
/// energy `energy`, q̇₁ > 0 solved; `Err` says why there is none.
pub(crate) fn energy_state(
    rhs: &mut Rhs,
    base: &[f64],
    s: f64,
    energy: f64,
) -> Result<Vec<f64>, String> {
    let layout = rhs.layout();
    if layout.coordinates() < 2 {
        return Err("a section needs at least two coordinates".into());
    }
    let mut y = base.to_vec();
    for i in 0..layout.coordinates() {
        y[layout.phase_qdot(i)] = 0.0;
    }
    y[layout.phase_q(0)] = 0.0;
    y[layout.phase_q(1)] = s;
    let v = layout.phase_qdot(0);
    let mut h = |x: f64| {
        y[v] = x;
        rhs.energy(0.0, &y).map_err(|e| e.to_string())
    };
    let (c, h1, hm1, h2) = (h(0.0)?, h(1.0)?, h(-1.0)?, h(2.0)?);
    let a = (h1 + hm1) / 2.0 - c;
    let b = (h1 - hm1) / 2.0;
    let scale = c.abs().max(a.abs()).max(b.abs()).max(1.0);
    if (4.0 * a + 2.0 * b + c - h2).abs() > 1e-9 * scale {
        return Err("h is not quadratic in the velocity".into());
    }
    if a.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return Err("the kinetic energy is not positive in this velocity".into());
    }
    let disc = b * b - 4.0 * a * (c - energy);
    let root = (-b + disc.sqrt()) / (2.0 * a);
    if !(disc >= 0.0 && root > 0.0) {
        return Err(format!(
            "the energy {energy} is below what the position allows (h = {c} at rest there)"
        ));
    }
    y[v] = root;
    Ok(y)
}

/// What [`section`] collects per orbit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionOptions {
    /// Crossings wanted per orbit.
    pub(crate) crossings: usize,
    /// The longest time an orbit is followed.
    pub(crate) t_max: f64,
    /// DOP853's tolerances.
    pub(crate) tol: Tolerances,
}

/// One orbit's crossings of q₁ = 0 with q̇₁ > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionOrbit {
    /// The starting state (on the section).
    pub(crate) start: Vec<f64>,
    /// The states at the crossings.
    pub(crate) points: Vec<Vec<f64>>,
    /// The time followed.
    pub(crate) t: f64,
    /// The work.
    pub(crate) stats: Stats,
}

/// Follows the motion from `y0` in chunks until `opts.crossings` crossings of q₁ = 0 upwards
/// or `opts.t_max`, collecting the states there.
pub fn section(rhs: &mut Rhs, y0: &[f64], opts: &SectionOptions) -> Result<SectionOrbit, SimError> {
    section_with(rhs, y0, opts, &mut Silent)
}

/// [`section`] that reports how far the time followed is through `opts.t_max` after each
/// chunk; a `Break` ends it with [`SimError::Interrupted`].
pub fn section_with(
    rhs: &mut Rhs,
    y0: &[f64],
    opts: &SectionOptions,
    progress: &mut dyn Progress,
) -> Result<SectionOrbit, SimError> {
    if !(opts.t_max.is_finite() && opts.t_max > 0.0) {
        return Err(SimError::Invalid(format!(
            "t_max = {} must be positive",
            opts.t_max
        )));
    }
    let q1 = rhs.layout().phase_q(0);
    let g = move |y: &[f64]| y[q1];
    let chunk = (CHUNK * opts.t_max / opts.crossings.max(1) as f64).min(opts.t_max);
    let mut orbit = SectionOrbit {
        start: y0.to_vec(),
        points: Vec::new(),
        t: 0.0,
        stats: Stats::default(),
    };
    let mut y = y0.to_vec();
    while orbit.points.len() < opts.crossings && orbit.t < opts.t_max {
        let t_b = (orbit.t + chunk).min(opts.t_max);
        let traj = dop853(rhs, orbit.t, &y, t_b, &opts.tol)?;
        let want = opts.crossings - orbit.points.len();
        let found = crossings(&traj, &g, Direction::Rising, want);
        orbit.points.extend(found.into_iter().map(|c| c.y));
        orbit.stats += traj.stats;
        y.copy_from_slice(&traj.y_final);
        orbit.t = t_b;
        tick(progress, fraction(orbit.t, 0.0, opts.t_max), PARTS)?;
    }
    Ok(orbit)
}
