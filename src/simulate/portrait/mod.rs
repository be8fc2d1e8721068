//! A phase-portrait family of a conservative system with one degree of freedom: trajectories
//! at a grid of energies, all started at the minimum of the potential V(q) = h(q, 0) on the
//! coordinate's range, each with the velocity that gives it its energy, so that one picture
//! shows the librations, the separatrix and (for an angle) the rotations both ways.
//!
//! Choices (documented in `lagrange simulate --help` and docs/simulation.md):
//! - the start is the lowest point q* of V over the coordinate's range (one period [a, a + 2π)
//!   for an angle), found on a grid and refined by golden-section search — not `--init`,
//!   because from q* every energy above V(q*) is reachable;
//! - the energies lie evenly above V(q*) below the highest barrier (a local maximum of V in
//!   the range), at it (the separatrix, exactly) and above it up to 1.8 × its height;
//!   without a barrier they run up to 90 % of the lower end of the range's V (the curves stay
//!   inside the range); a flat V, or one without a minimum inside the range, is refused;
//! - the separatrix and the rotations are drawn both ways (q̇ > 0 and q̇ < 0), a libration once;
//! - each curve is integrated for one period (at most `t_end`; the span starts at the small
//!   oscillations' period and doubles until a period is seen): a libration until it comes
//!   back through q*, a rotation when it has advanced 2π, the separatrix when it has
//!   nearly stopped at the saddle (the separatrix also backward in time, to the saddle it
//!   came from, so each direction draws one whole branch); a curve whose period is longer
//!   than `t_end` is what `t_end` gives.
//!
//! More than one degree of freedom is refused: there the energy does not select one curve in
//! one coordinate's phase plane (the other coordinates exchange energy with it).

mod shape;

use super::{Ode, Rhs, SimError, Tolerances, dop853};
use shape::Shape;

/// The most energies in a family.
pub const MAX_PORTRAIT: usize = 200;
/// Grid points of the search for V's extrema.
const GRID: usize = 720;
/// The highest energy of the family, in units of the highest barrier above the minimum.
const TOP: f64 = 1.8;
/// The most points kept per curve.
const MAX_POINTS: usize = 2000;
/// Points of the scan of each integration for the end of its first period.
const SCAN: usize = 8000;

/// Why a family cannot be drawn.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PortraitError {
    /// N = 0 or over the limit.
    #[error("--portrait asks for {got} energies; give 1 to {max}")]
    Count { got: usize, max: usize },
    /// More than one degree of freedom.
    #[error(
        "a portrait family needs one degree of freedom, and this system has {n}: with several, the energy does not select one curve in a coordinate's phase plane"
    )]
    Dimension { n: usize },
    /// h is not conserved.
    #[error(
        "a portrait family needs a conserved energy, and h is not conserved here (explicit time or forces doing work)"
    )]
    NotConserved,
    /// V is constant.
    #[error(
        "the potential V(q) = h(q, 0) is constant over {name}'s range [{lo}, {hi}], so it sets no energy scale for the family"
    )]
    Flat { name: String, lo: f64, hi: f64 },
    /// V has its lowest value at an end of a range that is not periodic.
    #[error(
        "the potential V(q) = h(q, 0) has no minimum inside {name}'s range [{lo}, {hi}] (its lowest value is at an end), so there is no bottom to start the family from"
    )]
    NoMinimum { name: String, lo: f64, hi: f64 },
    /// h does not grow with |q̇| at the start.
    #[error(
        "h does not grow with |{name}'| at {name} = {q}, so an energy does not fix the starting velocity"
    )]
    NotPositive { name: String, q: f64 },
    /// The integration failed.
    #[error(transparent)]
    Sim(#[from] SimError),
}

/// What a curve of the family is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum CurveKind {
    /// Below the highest barrier: a closed curve (about the minimum, or about several).
    Libration,
    /// At the highest barrier's energy.
    Separatrix,
    /// Above the barrier of an angle: q advances by a full period.
    Rotation,
}

/// One trajectory of the family.
#[derive(Clone, Debug, PartialEq)]
pub struct PortraitCurve {
    /// Its energy h.
    pub energy: f64,
    pub kind: CurveKind,
    /// The sign of the starting velocity.
    pub forward: bool,
    /// (q, q̇) in time order, q not wrapped.
    pub points: Vec<(f64, f64)>,
}

/// The family of one coordinate.
#[derive(Clone, Debug, PartialEq)]
pub struct Portrait {
    /// The coordinate's name.
    pub name: String,
    /// The start q*, V's lowest point.
    pub q_min: f64,
    /// V(q*) = h at rest at the start.
    pub h_min: f64,
    /// The highest barrier's energy, when V has one in the range.
    pub separatrix: Option<f64>,
    /// For an angle: the window [q* − π, q* + π) to wrap q into.
    pub window: Option<(f64, f64)>,
    pub curves: Vec<PortraitCurve>,
}

/// The coordinate's range and whether it is an angle.
#[derive(Clone, Debug, PartialEq)]
pub struct Coordinate1 {
    pub(crate) name: String,
    pub(crate) range: (f64, f64),
    pub(crate) periodic: bool,
}

/// How to integrate each curve.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FamilySpec {
    /// Energies (≤ [`MAX_PORTRAIT`]).
    pub(crate) count: usize,
    /// The longest integration of one curve.
    pub(crate) t_end: f64,
    pub(crate) rtol: f64,
    pub(crate) atol: f64,
    /// Points per curve, over its one period (capped at 2000).
    pub(crate) samples: usize,
}

/// The family of `rhs` (one coordinate) described in the module header.
pub fn portrait(
    rhs: &mut Rhs,
    coordinate: &Coordinate1,
    spec: &FamilySpec,
) -> Result<Portrait, PortraitError> {
    if spec.count == 0 || spec.count > MAX_PORTRAIT {
        return Err(PortraitError::Count {
            got: spec.count,
            max: MAX_PORTRAIT,
        });
    }
    let n = rhs.layout().coordinates();
    if n != 1 {
        return Err(PortraitError::Dimension { n });
    }
    if !rhs.energy_conserved() {
        return Err(PortraitError::NotConserved);
    }
    let shape = Shape::of(rhs, coordinate)?;
    // The first try at one period: the small oscillations' (else a small part of t_end).
    let first = shape
        .small_period(rhs)?
        .unwrap_or(spec.t_end / 4096.0)
        .min(spec.t_end);
    let energies = energies(&shape, spec.count, coordinate)?;
    let mut curves = Vec::new();
    for (energy, kind) in energies {
        let both = kind != CurveKind::Libration;
        for forward in [true, false].into_iter().take(if both { 2 } else { 1 }) {
            let v0 = start_velocity(rhs, shape.q_min, energy, forward, coordinate)?;
            let points = trace(rhs, [shape.q_min, v0], kind, first, spec)?;
            curves.push(PortraitCurve {
                energy,
                kind,
                forward,
                points,
            });
        }
    }
    let pi = std::f64::consts::PI;
    Ok(Portrait {
        name: coordinate.name.clone(),
        q_min: shape.q_min,
        h_min: shape.v_min,
        separatrix: shape.barrier,
        window: coordinate
            .periodic
            .then_some((shape.q_min - pi, shape.q_min + pi)),
        curves,
    })
}

/// The family's energies and kinds: without a barrier `count` energies up to 90 % of the way
/// to the range's ends; with one, the separatrix, then librations below and rotations (or, for
/// a coordinate that is not an angle, curves round several minima) above, about half each.
fn energies(
    s: &Shape,
    count: usize,
    c: &Coordinate1,
) -> Result<Vec<(f64, CurveKind)>, PortraitError> {
    let Some(barrier) = s.barrier.filter(|&b| b > s.v_min) else {
        let top = 0.9 * (s.v_ends - s.v_min);
        if top.is_nan() || top <= 0.0 {
            return Err(PortraitError::Flat {
                name: c.name.clone(),
                lo: c.range.0,
                hi: c.range.1,
            });
        }
        return Ok((1..=count)
            .map(|i| {
                (
                    s.v_min + top * i as f64 / count as f64,
                    CurveKind::Libration,
                )
            })
            .collect());
    };
    let height = barrier - s.v_min;
    let below = (count - 1) / 2;
    let above = count - 1 - below;
    let over = if c.periodic {
        CurveKind::Rotation
    } else {
        CurveKind::Libration
    };
    let mut out: Vec<(f64, CurveKind)> = (1..=below)
        .map(|i| {
            let f = i as f64 / (below + 1) as f64;
            (s.v_min + height * f, CurveKind::Libration)
        })
        .collect();
    out.push((barrier, CurveKind::Separatrix));
    out.extend((1..=above).map(|i| {
        let f = 1.0 + (TOP - 1.0) * i as f64 / above as f64;
        (s.v_min + height * f, over)
    }));
    Ok(out)
}

/// The velocity at q with h(q, v) = E and the sign asked, by bracketing and bisection.
fn start_velocity(
    rhs: &mut Rhs,
    q: f64,
    energy: f64,
    forward: bool,
    c: &Coordinate1,
) -> Result<f64, PortraitError> {
    let sign = if forward { 1.0 } else { -1.0 };
    let h0 = rhs.energy(0.0, &[q, 0.0])?;
    let not_positive = || PortraitError::NotPositive {
        name: c.name.clone(),
        q,
    };
    let h1 = rhs.energy(0.0, &[q, sign])?;
    if h1.is_nan() || h1 <= h0 {
        return Err(not_positive());
    }
    let mut hi = 1.0;
    let mut doublings = 0;
    while rhs.energy(0.0, &[q, sign * hi])? < energy {
        hi *= 2.0;
        doublings += 1;
        if doublings > 200 {
            return Err(not_positive());
        }
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if rhs.energy(0.0, &[q, sign * mid])? < energy {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Ok(sign * 0.5 * (lo + hi))
}

/// The curve through y0: one period of its kind forward in time; for the separatrix also its
/// past (the branch that comes out of the other saddle), so that it joins saddle to saddle.
fn trace(
    rhs: &mut Rhs,
    y0: [f64; 2],
    kind: CurveKind,
    first: f64,
    spec: &FamilySpec,
) -> Result<Vec<(f64, f64)>, SimError> {
    let ahead = trace_one(rhs, y0, kind, first, spec)?;
    if kind != CurveKind::Separatrix {
        return Ok(ahead);
    }
    let mut past = trace_one(&mut Backward(rhs), y0, kind, first, spec)?;
    past.reverse();
    past.pop();
    past.extend(ahead);
    Ok(past)
}

/// The motion backward in time: y'(s) = −F(y) for s = −t (the system is autonomous, as h is
/// conserved).
struct Backward<'a>(&'a mut Rhs);

impl Ode for Backward<'_> {
    fn dim(&self) -> usize {
        self.0.dim()
    }

    fn eval(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError> {
        self.0.eval(-t, y, dy)?;
        dy.iter_mut().for_each(|v| *v = -*v);
        Ok(())
    }
}

/// Integrates from y0 for one period of its kind, at most `t_end`, and samples it. The
/// integration runs over `first`, doubled until a period is seen (so a long `t_end` costs
/// about twice one period, not all of `t_end`).
fn trace_one(
    ode: &mut dyn Ode,
    y0: [f64; 2],
    kind: CurveKind,
    first: f64,
    spec: &FamilySpec,
) -> Result<Vec<(f64, f64)>, SimError> {
    let tol = Tolerances::new(spec.rtol, spec.atol);
    let mut span = first;
    let (traj, t_cut) = loop {
        let traj = dop853(ode, 0.0, &y0, span, &tol)?;
        // Find the period on a fine scan, then draw the curve with its own points over it.
        let scan = traj.sample_even(SCAN);
        let scan_points: Vec<(f64, f64)> = scan.iter().map(|(_, y)| (y[0], y[1])).collect();
        match one_period(&scan_points, y0, kind) {
            Some(end) => break (traj, scan[end.clamp(1, scan.len()) - 1].0),
            None if span >= spec.t_end => break (traj, span),
            None => span = (2.0 * span).min(spec.t_end),
        }
    };
    let n = spec.samples.clamp(2, MAX_POINTS);
    let mut y = [0.0; 2];
    Ok((0..n)
        .map(|k| {
            traj.at_into(t_cut * k as f64 / (n - 1) as f64, &mut y);
            (y[0], y[1])
        })
        .collect())
}

/// How many samples make one period: a libration returns through q0 the way it left, a
/// rotation advances 2π, the separatrix slows below 10⁻³ of its start speed (at the saddle).
fn one_period(points: &[(f64, f64)], y0: [f64; 2], kind: CurveKind) -> Option<usize> {
    let (q0, v0) = (y0[0], y0[1]);
    let ahead = |q: f64| (q - q0) * v0.signum();
    match kind {
        CurveKind::Rotation => points
            .iter()
            .position(|p| ahead(p.0) >= std::f64::consts::TAU)
            .map(|k| k + 1),
        CurveKind::Separatrix => points
            .iter()
            .position(|p| p.1.abs() < 1e-3 * v0.abs())
            .map(|k| k + 1),
        CurveKind::Libration => {
            let behind = points.iter().position(|p| ahead(p.0) < 0.0)?;
            (behind..points.len())
                .find(|&k| ahead(points[k].0) >= 0.0)
                .map(|k| k + 1)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::System;

    fn pendulum() -> Rhs {
        let mut sys =
            System::from_lagrangian("m*l^2*theta'^2/2 + m*g*l*cos(theta)", &["theta"]).unwrap();
        Rhs::new(&mut sys, &[("m", 2.0), ("l", 1.5), ("g", 9.81)]).unwrap()
    }

    fn angle() -> Coordinate1 {
        Coordinate1 {
            name: "theta".into(),
            range: (-std::f64::consts::PI, std::f64::consts::PI),
            periodic: true,
        }
    }

    fn spec(count: usize) -> FamilySpec {
        FamilySpec {
            count,
            t_end: 8.0,
            rtol: 1e-8,
            atol: 1e-8,
            samples: 600,
        }
    }

    #[test]
    fn the_pendulum_separatrix_is_two_m_g_l_above_the_bottom() {
        let p = portrait(&mut pendulum(), &angle(), &spec(5)).unwrap();
        let mgl = 2.0 * 1.5 * 9.81;
        assert!(p.q_min.abs() < 1e-6, "{}", p.q_min);
        assert!((p.h_min + mgl).abs() < 1e-9 * mgl);
        let sep = p.separatrix.unwrap();
        assert!((sep - p.h_min - 2.0 * mgl).abs() < 1e-9 * mgl, "{sep}");
        // 2 librations, the separatrix and 2 rotations, the last two both ways.
        let kinds: Vec<_> = p.curves.iter().map(|c| c.kind).collect();
        assert_eq!(kinds.len(), 2 + 2 + 4);
        assert_eq!(
            kinds.iter().filter(|k| **k == CurveKind::Rotation).count(),
            4
        );
    }

    #[test]
    fn the_harmonic_oscillator_has_no_barrier_and_closed_curves() {
        let mut sys = System::from_lagrangian("x'^2/2 - x^2/2", &["x"]).unwrap();
        let mut rhs = Rhs::new::<&str>(&mut sys, &[]).unwrap();
        let c = Coordinate1 {
            name: "x".into(),
            range: (-2.0, 2.0),
            periodic: false,
        };
        let p = portrait(&mut rhs, &c, &spec(3)).unwrap();
        assert_eq!(p.separatrix, None);
        assert_eq!(p.curves.len(), 3);
        // E = 0.9·2·i/3: amplitude √(2E) reached, curves closed (cut after one period 2π).
        for curve in &p.curves {
            let amp = curve.points.iter().fold(0.0f64, |a, p| a.max(p.0.abs()));
            assert!((amp - (2.0 * curve.energy).sqrt()).abs() < 0.02, "{amp}");
            // Cut after one period 2π < t_end: back at the start, (0, √(2E)).
            let (x, v) = curve.points[curve.points.len() - 1];
            assert!(x.abs() < 0.01 && (v - (2.0 * curve.energy).sqrt()).abs() < 1e-3);
            assert!(
                curve.points.iter().any(|q| q.0 < -0.9 * amp),
                "a whole turn"
            );
        }
    }

    #[test]
    fn a_double_well_has_its_separatrix_at_the_hump_and_curves_round_both_wells_above() {
        // V = −x²/2 + x⁴/4: minima at ±1 (V = −¼), the hump at 0 (V = 0).
        let mut sys = System::from_lagrangian("x'^2/2 + x^2/2 - x^4/4", &["x"]).unwrap();
        let mut rhs = Rhs::new::<&str>(&mut sys, &[]).unwrap();
        let c = Coordinate1 {
            name: "x".into(),
            range: (-2.0, 2.0),
            periodic: false,
        };
        let p = portrait(&mut rhs, &c, &spec(5)).unwrap();
        assert!((p.q_min.abs() - 1.0).abs() < 1e-6 && (p.h_min + 0.25).abs() < 1e-12);
        assert!(p.separatrix.unwrap().abs() < 1e-12);
        assert_eq!(p.window, None);
        for curve in &p.curves {
            let h = |&(x, v): &(f64, f64)| v * v / 2.0 - x * x / 2.0 + x.powi(4) / 4.0;
            assert!(
                curve
                    .points
                    .iter()
                    .all(|q| (h(q) - curve.energy).abs() < 1e-6)
            );
            if curve.kind != CurveKind::Separatrix {
                let crosses = curve.points.iter().any(|q| q.0 * p.q_min < 0.0);
                assert_eq!(crosses, curve.energy > 0.0, "{}", curve.energy);
            }
        }
    }

    #[test]
    fn refusals_say_why() {
        let e = portrait(&mut pendulum(), &angle(), &spec(0)).unwrap_err();
        assert!(matches!(e, PortraitError::Count { got: 0, .. }));
        let mut sys = System::from_lagrangian("x'^2/2 - x", &["x"]).unwrap();
        let mut rhs = Rhs::new::<&str>(&mut sys, &[]).unwrap();
        let c = Coordinate1 {
            name: "x".into(),
            range: (-2.0, 2.0),
            periodic: false,
        };
        let e = portrait(&mut rhs, &c, &spec(3)).unwrap_err();
        assert!(matches!(e, PortraitError::NoMinimum { .. }), "{e}");
        let mut sys = System::from_lagrangian("x'^2/2 + y'^2/2 - x^2 - y^2", &["x", "y"]).unwrap();
        let mut rhs = Rhs::new::<&str>(&mut sys, &[]).unwrap();
        let e = portrait(&mut rhs, &c, &spec(3)).unwrap_err();
        assert_eq!(e, PortraitError::Dimension { n: 2 });
    }
}
