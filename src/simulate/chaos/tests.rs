//! Physics of the double pendulum (m = l = 1, g = 9.81): Benettin's estimate at 2 rad, at
//! 0.2 rad, and the cost of restarting DOP853 per segment.

use super::*;
use crate::mechanics::fixtures;
use crate::simulate::Rhs;

pub(super) fn double_pendulum() -> Rhs {
    let mut sys = fixtures::double_pendulum();
    Rhs::new(&mut sys, &fixtures::DOUBLE_PENDULUM_ANCHOR).unwrap()
}

fn estimate(angle: f64, delta: f64, tol: f64, t_end: f64, tau: f64) -> Lyapunov {
    let mut rhs = double_pendulum();
    let opts = LyapunovOptions {
        delta,
        t_end,
        tau,
        tol: Tolerances::new(tol, tol),
    };
    lyapunov(&mut rhs, &[angle, angle, 0.0, 0.0], &opts).unwrap()
}

/// At θ₁ = θ₂ = 2 rad at rest the estimate at t = 4000 agrees to ±0.025 across delta
/// 1e-8…1e-10 and tolerance 1e-9…1e-11 (measured 1.334…1.363; an independent estimate in the
/// literature gives about 1.3 s⁻¹). Slow (about 10 s per run in debug, run side by side):
/// 4000 is the shortest run that holds two digits (at 1000 the runs spread over 1.29…1.37,
/// at 30 over 1.08…1.46); the corners of the ranges only.
#[test]
fn slow_benettin_at_two_radians_is_stable_to_two_digits() {
    let runs = [(1e-8, 1e-9), (1e-10, 1e-9), (1e-9, 1e-11)];
    let found: Vec<f64> = std::thread::scope(|s| {
        let handles: Vec<_> = runs
            .iter()
            .map(|&(delta, tol)| s.spawn(move || estimate(2.0, delta, tol, 4000.0, 1.0).exponent))
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let lo = found.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = found.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    assert!(hi - lo < 0.05, "{found:?}");
    assert!(lo > 1.25 && hi < 1.45, "{found:?}");
}

/// At 0.2 rad the motion is regular: separations grow like a power of t, so the estimate
/// falls like ln(t)/t — λ(t)·t stays below ln(t) + 1 (growth at most linear in t) and λ
/// keeps falling.
#[test]
fn at_point_two_radians_the_estimate_falls_like_log_t_over_t() {
    let l = estimate(0.2, 1e-9, 1e-10, 300.0, 1.0);
    let at = |t: f64| l.running.iter().find(|r| r.0 >= t - 1e-9).unwrap().1;
    let (a, b, c) = (at(30.0), at(100.0), at(300.0));
    assert!(a > b && b > c && c > 0.0, "{a} {b} {c}");
    for t in [30.0, 100.0, 300.0] {
        assert!(at(t) * t < t.ln() + 1.0, "λ({t}) = {}", at(t));
    }
    assert!(c < 0.01, "{c}");
}

/// Restarting DOP853 at every renormalisation (τ = 1) costs little: the pair's evaluations
/// over 100 s against one uninterrupted run of the reference trajectory alone under the same
/// tolerances (the pair stays within delta, so it needs the same steps).
#[test]
fn restarting_per_segment_is_cheap() {
    let l = estimate(2.0, 1e-9, 1e-10, 100.0, 1.0);
    let mut rhs = double_pendulum();
    let tol = Tolerances {
        dense: false,
        ..Tolerances::new(1e-10, 1e-10)
    };
    let whole = crate::simulate::dop853(&mut rhs, 0.0, &[2.0, 2.0, 0.0, 0.0], 100.0, &tol).unwrap();
    let ratio = l.stats.rhs_evals as f64 / whole.stats.rhs_evals as f64;
    eprintln!(
        "segments {} vs whole {}: {ratio}",
        l.stats.rhs_evals, whole.stats.rhs_evals
    );
    assert!(ratio < 1.15, "{ratio}");
}

#[test]
fn bad_settings_are_refused() {
    let mut rhs = double_pendulum();
    let y0 = [2.0, 2.0, 0.0, 0.0];
    let tol = Tolerances::new(1e-8, 1e-8);
    for (delta, t_end, tau) in [
        (0.0, 1.0, 1.0),
        (1.0, 1.0, 1.0),
        (1e-9, 0.0, 1.0),
        (1e-9, 1e7, 1e-3),
    ] {
        let opts = LyapunovOptions {
            delta,
            t_end,
            tau,
            tol,
        };
        assert!(matches!(
            lyapunov(&mut rhs, &y0, &opts),
            Err(SimError::Invalid(_))
        ));
    }
}

/// The section's family sits at the asked energy with q̇₁ > 0; its crossings keep it
/// (energy conserved) and lie on q₁ = 0 with q̇₁ > 0; below the potential a start is refused.
#[test]
fn section_states_and_crossings_are_on_the_section_at_the_energy() {
    let mut rhs = double_pendulum();
    let base = [1.0, 1.0, 0.0, 0.0];
    let e = rhs.energy(0.0, &base).unwrap();
    let y = energy_state(&mut rhs, &base, 0.5, e).unwrap();
    assert!((rhs.energy(0.0, &y).unwrap() - e).abs() < 1e-10 * e.abs());
    assert!(y[0] == 0.0 && y[1] == 0.5 && y[2] > 0.0 && y[3] == 0.0);
    let refused = energy_state(&mut rhs, &base, 2.0, e).unwrap_err();
    assert!(refused.contains("below"), "{refused}");
    let opts = SectionOptions {
        crossings: 10,
        t_max: 100.0,
        tol: Tolerances::new(1e-10, 1e-10),
    };
    let o = section(&mut rhs, &y, &opts).unwrap();
    assert_eq!(o.points.len(), 10);
    for p in &o.points {
        assert!(p[0].abs() < 1e-10 && p[2] > 0.0, "{p:?}");
        assert!((rhs.energy(0.0, p).unwrap() - e).abs() < 1e-7 * e.abs());
    }
}
