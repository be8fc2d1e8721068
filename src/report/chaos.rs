//! [`ChaosReport`]: what `lagrange chaos` shows — the largest Lyapunov exponent by Benettin's
//! method with its running estimate (convergence) and what it suggests, the separation of two
//! trajectories started δ apart, and optionally a Poincaré section at the initial state's
//! energy. The numerics are in [`crate::simulate::chaos`]; the face draws the pictures.

use serde::Serialize;

use super::simulation::{initial_state, motion_parameters, state_names};
use super::{Paint, SimulationError, text};
use crate::mechanics::System;
use crate::progress::{Progress, Silent, Stage};
use crate::simulate::chaos::{LyapunovOptions, SectionOptions, energy_state, lyapunov_with};
use crate::simulate::chaos::{section_with, separation};
use crate::simulate::{Rhs, SimError, Tolerances};

mod render;

/// The default end time: the shortest for which the double pendulum's estimate at 2 rad
/// agrees to ±0.02 s⁻¹ across delta 1e-8…1e-10 and tolerance 1e-9…1e-11 (t = 30 gives
/// 1.08…1.46).
pub const DEFAULT_T_END: f64 = 4000.0;
/// The most section crossings in all (orbits × crossings per orbit).
pub const MAX_SECTION_POINTS: usize = 100_000;
/// The most orbits of a section.
pub const MAX_ORBITS: usize = 1_000;
/// The most separation samples.
pub const MAX_SAMPLES: usize = 100_000;

/// What to compute.
#[derive(Clone, Debug)]
pub struct ChaosOptions {
    /// Every parameter's value.
    pub params: Vec<(String, f64)>,
    /// Initial values by name (`theta1`, `theta1'`); the rest start at 0.
    pub init: Vec<(String, f64)>,
    /// The initial separation, in (0, 1).
    pub delta: f64,
    /// The end time of the exponent's estimate.
    pub t_end: f64,
    /// The renormalisation interval τ.
    pub tau: f64,
    /// DOP853's tolerances.
    pub rtol: f64,
    pub atol: f64,
    /// The separation (never renormalised) is followed to min(this, t_end).
    pub separation_t_end: f64,
    /// Even samples of the separation.
    pub samples: usize,
    /// A Poincaré section, if asked.
    pub section: Option<SectionSpec>,
}

/// The family of a Poincaré section: `orbits` values of the second coordinate evenly in
/// `range`, each followed for `crossings` crossings or `t_max`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SectionSpec {
    pub orbits: usize,
    pub range: (f64, f64),
    pub crossings: usize,
    pub t_max: f64,
}

/// Why `chaos` could not be done.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ChaosError {
    /// The separation is not in (0, 1).
    #[error("--delta must be in (0, 1), not {0}")]
    Delta(f64),
    /// The end time, τ or the separation's end is not positive.
    #[error("{what} must be a finite positive number, not {value}")]
    NotPositive { what: &'static str, value: f64 },
    /// Too many points asked.
    #[error("{what} asks for {got}, over the limit of {max}")]
    TooMany {
        what: &'static str,
        got: usize,
        max: usize,
    },
    /// Constraints: the perturbation along (1, …, 1) and the section's starting velocities
    /// would leave them.
    #[error(
        "the system has {0} constraint(s): the perturbed motion and the section's starts would leave them; describe it by independent coordinates"
    )]
    Constraints(usize),
    /// A setting that cannot give a meaningful estimate.
    #[error("{0}")]
    Invalid(String),
    /// A section needs two coordinates.
    #[error("a Poincaré section needs at least two coordinates (the system has {0})")]
    SectionDimension(usize),
    /// No state of the family exists at the energy.
    #[error("no state on the section q₁ = 0 at h = {energy} in the range asked: {reason}")]
    NoSectionState { energy: f64, reason: String },
    /// The shared setup errors (coordinates, parameters) and the numerics.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
}

impl ChaosError {
    /// Whether the progress callback stopped the run.
    pub fn interrupted(&self) -> bool {
        matches!(
            self,
            ChaosError::Simulation(SimulationError::Sim(SimError::Interrupted))
        )
    }
}

impl From<SimError> for ChaosError {
    fn from(e: SimError) -> Self {
        ChaosError::Simulation(SimulationError::Sim(e))
    }
}

impl ChaosError {
    /// Whether the input was fine but the motion could not be followed.
    pub fn along_the_way(&self) -> bool {
        matches!(self, ChaosError::Simulation(e) if e.along_the_way())
    }
}

/// One orbit of the section: q₂ at its start and its crossings (q₂, q̇₂).
#[derive(Clone, Debug, Serialize)]
pub struct SectionOrbitReport {
    pub(crate) q2_start: f64,
    pub points: Vec<(f64, f64)>,
    pub(crate) t: f64,
}

/// The Poincaré section q₁ = 0, q̇₁ > 0 at the initial energy.
#[derive(Clone, Debug, Serialize)]
pub struct SectionReport {
    pub energy: f64,
    /// The names of q₁ and q₂.
    pub q1: String,
    pub q2: String,
    pub orbits: Vec<SectionOrbitReport>,
    /// Values of q₂ refused, with why.
    pub(crate) refused: Vec<(f64, String)>,
}

/// Everything `chaos` shows.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct ChaosReport {
    /// The estimate at t_end.
    pub(crate) exponent: f64,
    pub(crate) delta: f64,
    pub(crate) tau: f64,
    pub(crate) t_end: f64,
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
    /// The unit of t when the system declares one (a face sets it): λ is then in its inverse.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub time_unit: Option<String>,
    /// The running estimate at a few times (t, λ).
    pub(crate) checkpoints: Vec<(f64, f64)>,
    /// Smallest and largest running estimate over the last third of the run.
    pub(crate) last_third: (f64, f64),
    /// λ(t_end) / λ(t_end / 3): about 1 when the estimate has settled, about 0.4 when it
    /// falls like ln(t)/t.
    pub(crate) ratio_to_a_third: f64,
    /// The running estimate after every renormalisation (t, λ).
    pub running: Vec<(f64, f64)>,
    /// The separation of the two trajectories never renormalised (t, |Δy|).
    pub separation: Vec<(f64, f64)>,
    /// Accepted steps of the pair (the estimate's segments and the separation's run).
    pub(crate) steps: usize,
    /// Evaluations of the system's F (two per evaluation of the pair).
    pub(crate) rhs_evals: usize,
    /// The names of y's entries.
    pub(crate) names: Vec<String>,
    pub section: Option<SectionReport>,
    /// What the estimate suggests.
    pub(crate) verdict: Verdict,
}

/// The checks that need no system.
fn check(opts: &ChaosOptions) -> Result<(), ChaosError> {
    if !(opts.delta > 0.0 && opts.delta < 1.0) {
        return Err(ChaosError::Delta(opts.delta));
    }
    for (what, value) in [
        ("--t-end", opts.t_end),
        ("--tau", opts.tau),
        ("--separation-t-end", opts.separation_t_end),
    ] {
        if !(value.is_finite() && value > 0.0) {
            return Err(ChaosError::NotPositive { what, value });
        }
    }
    if opts.tau * 10.0 > opts.t_end {
        return Err(ChaosError::Invalid(format!(
            "--tau {} is more than a tenth of --t-end {}: the estimate averages over renormalisations, and fewer than ten say nothing",
            opts.tau, opts.t_end
        )));
    }
    let segments = (opts.t_end / opts.tau).ceil();
    let max = crate::simulate::chaos::MAX_SEGMENTS;
    if segments > max as f64 {
        let got = segments.min(usize::MAX as f64) as usize;
        let what = "--t-end / --tau (renormalisations)";
        return Err(ChaosError::TooMany { what, got, max });
    }
    if opts.samples > MAX_SAMPLES {
        let (what, got, max) = ("--samples", opts.samples, MAX_SAMPLES);
        return Err(ChaosError::TooMany { what, got, max });
    }
    if let Some(s) = &opts.section {
        check_section(s)?;
    }
    Ok(())
}

fn check_section(s: &SectionSpec) -> Result<(), ChaosError> {
    for (what, n) in [("--orbits", s.orbits), ("--crossings", s.crossings)] {
        if n == 0 {
            return Err(ChaosError::NotPositive { what, value: 0.0 });
        }
    }
    if s.orbits > MAX_ORBITS {
        let (what, got, max) = ("--orbits", s.orbits, MAX_ORBITS);
        return Err(ChaosError::TooMany { what, got, max });
    }
    let total = s.orbits.saturating_mul(s.crossings);
    if total > MAX_SECTION_POINTS {
        let what = "--orbits × --crossings (section points)";
        return Err(ChaosError::TooMany {
            what,
            got: total,
            max: MAX_SECTION_POINTS,
        });
    }
    if !(s.t_max.is_finite() && s.t_max > 0.0) {
        let what = "--section-t-end";
        return Err(ChaosError::NotPositive {
            what,
            value: s.t_max,
        });
    }
    if !(s.range.0.is_finite() && s.range.1.is_finite() && s.range.0 <= s.range.1) {
        return Err(ChaosError::NotPositive {
            what: "the width of --section-range",
            value: s.range.1 - s.range.0,
        });
    }
    Ok(())
}

/// The exponent, its convergence, the separation and the asked section of `sys`.
pub fn chaos(sys: &mut System, opts: &ChaosOptions) -> Result<ChaosReport, ChaosError> {
    chaos_with(sys, opts, &mut Silent)
}

/// [`chaos`] that reports its work to `progress` (the exponent, the separation, then each
/// orbit of the section, as equal stages); a `Break` ends it with the interrupted error
/// ([`ChaosError::interrupted`]).
pub fn chaos_with(
    sys: &mut System,
    opts: &ChaosOptions,
    progress: &mut dyn Progress,
) -> Result<ChaosReport, ChaosError> {
    check(opts)?;
    if !sys.constraints.is_empty() {
        return Err(ChaosError::Constraints(sys.constraints.len()));
    }
    let params = motion_parameters(sys, &opts.params);
    let mut rhs = Rhs::new(sys, &params).map_err(SimulationError::Sim)?;
    let names = state_names(rhs.names());
    let y0 = initial_state(&names, &opts.init)?;
    let tol = Tolerances::new(opts.rtol, opts.atol);
    let l_opts = LyapunovOptions {
        delta: opts.delta,
        t_end: opts.t_end,
        tau: opts.tau,
        tol,
    };
    let stages = 2 + opts.section.as_ref().map_or(0, |s| s.orbits as u64);
    let l = lyapunov_with(&mut rhs, &y0, &l_opts, &mut Stage::new(progress, 0, stages))?;
    let sep_end = opts.separation_t_end.min(opts.t_end);
    let (separation, sep_stats) = separation(
        &mut rhs,
        &y0,
        (opts.delta, sep_end),
        &tol,
        opts.samples,
        &mut Stage::new(progress, 1, stages),
    )?;
    let section = match &opts.section {
        Some(spec) => {
            let along = (progress, stages);
            Some(poincare(&mut rhs, (&y0, spec, tol), &names, along)?)
        }
        None => None,
    };
    let (checkpoints, last_third, ratio_to_a_third) = convergence(&l.running, opts.t_end);
    let verdict = match verdict(l.exponent, last_third, ratio_to_a_third) {
        Verdict::Regular => Verdict::Regular,
        // A positive exponent is chaos only where chaos can be: not in one autonomous degree of
        // freedom, not at rest on an unstable equilibrium, not in a motion running away.
        positive => {
            let spread = separation.iter().map(|p| p.1).fold(0.0, f64::max);
            not_chaos(
                rhs.names().len(),
                rhs.energy_conserved(),
                &l.reference,
                spread,
            )
            .unwrap_or(positive)
        }
    };
    Ok(ChaosReport {
        exponent: l.exponent,
        delta: opts.delta,
        tau: opts.tau,
        t_end: opts.t_end,
        rtol: opts.rtol,
        atol: opts.atol,
        time_unit: None,
        checkpoints,
        last_third,
        ratio_to_a_third,
        running: l.running,
        separation,
        steps: l.stats.accepted + sep_stats.accepted,
        rhs_evals: 2 * (l.stats.rhs_evals + sep_stats.rhs_evals),
        names,
        section,
        verdict,
    })
}

/// The running estimate at t_end / 10ᵏ and t_end / 3, the spread over the last third and
/// the ratio λ(t_end) / λ(t_end / 3).
type Convergence = (Vec<(f64, f64)>, (f64, f64), f64);

fn convergence(running: &[(f64, f64)], t_end: f64) -> Convergence {
    let at = |t: f64| {
        let k = running.partition_point(|r| r.0 < t * (1.0 - 1e-12));
        running.get(k).copied().unwrap_or((t_end, 0.0))
    };
    let mut checkpoints: Vec<(f64, f64)> = [1000.0, 100.0, 10.0, 3.0, 1.0]
        .iter()
        .map(|d| at(t_end / d))
        .filter(|r| r.0 >= running.first().map_or(0.0, |f| f.0))
        .collect();
    checkpoints.dedup_by(|a, b| a.0 == b.0);
    let tail = running.iter().filter(|r| r.0 >= 2.0 * t_end / 3.0);
    let last_third = tail.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), r| {
        (a.min(r.1), b.max(r.1))
    });
    let end = running.last().map_or(0.0, |r| r.1);
    let third = at(t_end / 3.0).1;
    let ratio = if third != 0.0 { end / third } else { f64::NAN };
    (checkpoints, last_third, ratio)
}

/// The section's family at the initial energy, and each orbit's crossings.
fn poincare(
    rhs: &mut Rhs,
    (y0, spec, tol): (&[f64], &SectionSpec, Tolerances),
    names: &[String],
    (progress, stages): (&mut dyn Progress, u64),
) -> Result<SectionReport, ChaosError> {
    let n = rhs.layout().coordinates();
    if n < 2 {
        return Err(ChaosError::SectionDimension(n));
    }
    let energy = rhs.energy(0.0, y0)?;
    let (mut orbits, mut refused) = (Vec::new(), Vec::new());
    let opts = SectionOptions {
        crossings: spec.crossings,
        t_max: spec.t_max,
        tol,
    };
    let (q2, q2dot) = (rhs.layout().phase_q(1), rhs.layout().phase_qdot(1));
    for k in 0..spec.orbits {
        let s = if spec.orbits == 1 {
            (spec.range.0 + spec.range.1) / 2.0
        } else {
            spec.range.0 + (spec.range.1 - spec.range.0) * k as f64 / (spec.orbits - 1) as f64
        };
        match energy_state(rhs, y0, s, energy) {
            Err(reason) => refused.push((s, reason)),
            Ok(start) => {
                let mut stage = Stage::new(progress, 2 + k as u64, stages);
                let o = section_with(rhs, &start, &opts, &mut stage)?;
                let points = o.points.iter().map(|y| (y[q2], y[q2dot])).collect();
                orbits.push(SectionOrbitReport {
                    q2_start: s,
                    points,
                    t: o.t,
                });
            }
        }
    }
    if orbits.is_empty() {
        let reason = refused.first().map_or_else(String::new, |r| r.1.clone());
        return Err(ChaosError::NoSectionState { energy, reason });
    }
    Ok(SectionReport {
        energy,
        q1: names[0].clone(),
        q2: names[1].clone(),
        orbits,
        refused,
    })
}

impl ChaosReport {
    /// The summary as text.
    pub fn render(&self, paint: &dyn Paint) -> String {
        text(|o| render::summary(self, paint, o))
    }
}

/// What the estimate suggests: regular when it is not positive or falls by more than 40 %
/// from t_end/3 to t_end (ln(t)/t falls by about 60 %), chaotic when it holds within 15 % and
/// varies by at most a tenth of itself over the last third, else unsettled.
fn verdict(exponent: f64, (lo, hi): (f64, f64), ratio: f64) -> Verdict {
    if exponent <= 0.0 || ratio < 0.6 {
        Verdict::Regular
    } else if ratio > 0.85 && hi - lo <= 0.1 * exponent {
        Verdict::Chaotic
    } else {
        Verdict::Unsettled
    }
}

/// Why a positive exponent is not chaos, when it is not: one degree of freedom with a
/// conserved h (its phase plane has no room for chaos), a reference motion that never moves
/// (λ is then the equilibrium's instability rate), or one whose size keeps growing tenfold
/// and more between the first and the last third of the run (separation of a runaway), or
/// neighbours whose never-renormalised separation grows a hundredfold beyond the motion's own
/// size (an unstable orbit they leave for good; chaos keeps them within the motion's range).
fn not_chaos(
    coordinates: usize,
    autonomous: bool,
    reference: &[(f64, f64, f64)],
    spread: f64,
) -> Option<Verdict> {
    if coordinates == 1 && autonomous {
        return Some(Verdict::OneDegree);
    }
    let size = reference.iter().map(|r| r.1).fold(0.0, f64::max);
    let speed = reference.iter().map(|r| r.2).fold(0.0, f64::max);
    if speed <= 1e-9 * size.max(1.0) {
        return Some(Verdict::AtEquilibrium);
    }
    let t_end = reference.last().map_or(0.0, |r| r.0);
    let largest = |keep: &dyn Fn(f64) -> bool| {
        (reference.iter())
            .filter(|r| keep(r.0))
            .map(|r| r.1)
            .fold(0.0, f64::max)
    };
    let first = largest(&|t| t <= t_end / 3.0);
    let last = largest(&|t| t >= 2.0 * t_end / 3.0);
    if last > 10.0 * first.max(1e-300) {
        return Some(Verdict::Runaway);
    }
    (spread > 100.0 * size.max(1e-300)).then_some(Verdict::Unstable)
}

/// What a finite-time estimate suggests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Positive and steady over the last third.
    Chaotic,
    /// Falling towards 0 (like ln(t)/t) or not positive.
    Regular,
    /// Neither yet.
    Unsettled,
    /// Positive, but one autonomous degree of freedom cannot be chaotic: an unstable
    /// equilibrium or a separatrix.
    OneDegree,
    /// Positive, but the motion stays at rest: the instability rate of its equilibrium.
    AtEquilibrium,
    /// Positive, but the motion keeps growing: the separation of a runaway, not chaos.
    Runaway,
    /// Positive, but neighbours leave for good: an unstable orbit, not chaos.
    Unstable,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn judged(f: impl Fn(f64) -> f64, t_end: f64) -> (Convergence, Verdict) {
        let running: Vec<(f64, f64)> = (1..=t_end as usize)
            .map(|k| (k as f64, f(k as f64)))
            .collect();
        let c = convergence(&running, t_end);
        let v = verdict(running.last().unwrap().1, c.1, c.2);
        (c, v)
    }

    /// A steady positive estimate reads as chaotic, ln(t)/t as regular, a swinging one as
    /// neither; the checkpoints are the running estimate at t_end/10ᵏ and t_end/3.
    #[test]
    fn the_verdict_follows_the_shape_of_the_running_estimate() {
        let (c, v) = judged(|t| 1.3 + 0.05 / t.sqrt(), 1000.0);
        assert_eq!(v, Verdict::Chaotic);
        let times: Vec<f64> = c.0.iter().map(|p| p.0).collect();
        assert_eq!(times, [1.0, 10.0, 100.0, 334.0, 1000.0]);
        assert!((c.2 - 1.0).abs() < 0.01);
        assert_eq!(judged(|t| (t + 1.0).ln() / t, 1000.0).1, Verdict::Regular);
        assert_eq!(judged(|t| -0.01 / t, 1000.0).1, Verdict::Regular);
        assert_eq!(
            judged(|t| 0.5 + 0.3 * (t / 50.0).sin(), 1000.0).1,
            Verdict::Unsettled
        );
    }

    #[test]
    fn settings_are_checked_before_any_work() {
        let opts = ChaosOptions {
            params: vec![],
            init: vec![],
            delta: 1e-9,
            t_end: 10.0,
            tau: 1.0,
            rtol: 1e-8,
            atol: 1e-8,
            separation_t_end: 10.0,
            samples: 10,
            section: Some(SectionSpec {
                orbits: 10,
                range: (-1.0, 1.0),
                crossings: 10,
                t_max: 10.0,
            }),
        };
        assert_eq!(check(&opts), Ok(()));
        let bad = |f: &dyn Fn(&mut ChaosOptions)| {
            let mut o = opts.clone();
            f(&mut o);
            check(&o).unwrap_err()
        };
        assert_eq!(bad(&|o| o.delta = 1.0), ChaosError::Delta(1.0));
        assert!(matches!(
            bad(&|o| o.tau = 0.0),
            ChaosError::NotPositive { what: "--tau", .. }
        ));
        assert!(matches!(
            bad(&|o| o.t_end = 1e9),
            ChaosError::TooMany { .. }
        ));
        assert!(matches!(
            bad(&|o| o.samples = 1 << 20),
            ChaosError::TooMany { .. }
        ));
        let no_width = |o: &mut ChaosOptions| {
            if let Some(s) = &mut o.section {
                s.range = (1.0, -1.0);
            }
        };
        assert!(matches!(bad(&no_width), ChaosError::NotPositive { .. }));
        let no_orbits = |o: &mut ChaosOptions| {
            if let Some(s) = &mut o.section {
                s.orbits = 0;
            }
        };
        assert!(matches!(
            bad(&no_orbits),
            ChaosError::NotPositive {
                what: "--orbits",
                ..
            }
        ));
    }
}
