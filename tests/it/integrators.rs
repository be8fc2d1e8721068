//! Issue 14, items 1–2: the simulation numerics checked against physics — the harmonic
//! oscillator's closed form, measured orders of convergence, the pendulum's period from the
//! complete elliptic integral, energy conservation of the double pendulum, and the symplectic
//! Gauss method's bounded energy error against RK4's drift.

use lagrange::System;
use lagrange::mechanics::fixtures;
use lagrange::simulate::{FnOde, Ode, Rhs, SimError, Tolerances, Trajectory, dop853, gauss, rk4};

fn double_pendulum() -> Rhs {
    let mut sys = fixtures::double_pendulum();
    Rhs::new(&mut sys, &fixtures::DOUBLE_PENDULUM_ANCHOR).unwrap()
}

fn oscillator() -> Rhs {
    let mut sys = System::from_lagrangian("m*x'^2/2 - k*x^2/2", &["x"]).unwrap();
    Rhs::new(&mut sys, &[("m", 1.0), ("k", 4.0)]).unwrap()
}

/// x(t) of the oscillator with ω = 2, x(0) = 1, x'(0) = 0.5.
fn oscillator_exact(t: f64) -> [f64; 2] {
    let w = 2.0;
    [
        (w * t).cos() + 0.5 / w * (w * t).sin(),
        -w * (w * t).sin() + 0.5 * (w * t).cos(),
    ]
}

fn max_error(traj: &Trajectory, t: f64) -> f64 {
    let y = traj.at(t).unwrap();
    let e = oscillator_exact(t);
    (y[0] - e[0]).abs().max((y[1] - e[1]).abs())
}

/// The largest relative change of h over the integrator's own step times.
fn max_rel_energy_error(rhs: &mut Rhs, traj: &Trajectory, from: f64) -> f64 {
    let h0 = rhs.energy(traj.t0, &traj.y0).unwrap();
    traj.step_times()
        .into_iter()
        .filter(|&t| t >= from)
        .map(|t| {
            let y = traj.at(t).unwrap();
            ((rhs.energy(t, &y).unwrap() - h0) / h0).abs()
        })
        .fold(0.0, f64::max)
}

#[test]
fn dop853_follows_the_harmonic_oscillator_to_1e_9() {
    let mut rhs = oscillator();
    let traj = dop853(
        &mut rhs,
        0.0,
        &[1.0, 0.5],
        10.0,
        &Tolerances::new(1e-12, 1e-12),
    )
    .unwrap();
    let end = oscillator_exact(10.0);
    let final_err = (traj.y_final[0] - end[0])
        .abs()
        .max((traj.y_final[1] - end[1]).abs());
    // Dense output between the steps, on an even grid and at chosen times.
    let dense_err = traj
        .sample_even(1001)
        .iter()
        .map(|(t, _)| max_error(&traj, *t))
        .fold(0.0, f64::max);
    eprintln!(
        "oscillator dop853: final error {final_err:.2e}, dense error {dense_err:.2e}, {:?}",
        traj.stats
    );
    assert!(final_err < 1e-9 && dense_err < 1e-9);
    assert_eq!(traj.sample_at(&[0.0, 10.0]).unwrap()[1], traj.y_final);
    assert!(traj.at(10.5).is_err());
}

/// A fixed-step integrator.
type Integrator = fn(&mut dyn Ode, f64, &[f64], f64, f64) -> Result<Trajectory, SimError>;

/// The order measured from errors at t = 10 with the step halved twice.
fn measured_order(method: Integrator) -> (f64, f64, Vec<f64>) {
    let errors: Vec<f64> = [0.1, 0.05, 0.025]
        .iter()
        .map(|&dt| {
            let traj = method(&mut oscillator(), 0.0, &[1.0, 0.5], 10.0, dt).unwrap();
            let e = oscillator_exact(10.0);
            (traj.y_final[0] - e[0])
                .abs()
                .max((traj.y_final[1] - e[1]).abs())
        })
        .collect();
    let p1 = (errors[0] / errors[1]).log2();
    let p2 = (errors[1] / errors[2]).log2();
    (p1, p2, errors)
}

#[test]
fn rk4_and_gauss_converge_with_order_four() {
    for (name, method) in [("rk4", rk4 as Integrator), ("gauss", gauss as Integrator)] {
        let (p1, p2, errors) = measured_order(method);
        eprintln!("{name}: errors {errors:?}, orders {p1:.3} {p2:.3}");
        assert!(
            (3.8..4.2).contains(&p1) && (3.8..4.2).contains(&p2),
            "{name}"
        );
    }
}

/// The complete elliptic integral of the first kind K(k) = π / (2 AGM(1, √(1 − k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// The times where the first component of the solution changes sign, by bisection on the
/// dense output between the step times.
fn zero_crossings(traj: &Trajectory) -> Vec<f64> {
    let times = traj.step_times();
    let q = |t: f64| traj.at(t).unwrap()[0];
    let mut out = Vec::new();
    for w in times.windows(2) {
        let (mut a, mut b) = (w[0], w[1]);
        if q(a).signum() == q(b).signum() || q(b) == 0.0 {
            continue;
        }
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if q(m).signum() == q(a).signum() {
                a = m;
            } else {
                b = m;
            }
        }
        out.push(0.5 * (a + b));
    }
    out
}

#[test]
fn pendulum_period_is_four_k_over_omega() {
    let (g, l, theta0) = (9.81, 1.5, 2.0f64);
    let mut sys =
        System::from_lagrangian("m*l^2*theta'^2/2 + m*g*l*cos(theta)", &["theta"]).unwrap();
    let mut rhs = Rhs::new(&mut sys, &[("m", 0.7), ("l", l), ("g", g)]).unwrap();
    let exact = 4.0 * elliptic_k((theta0 / 2.0).sin()) * (l / g).sqrt();
    let tol = Tolerances::new(1e-12, 1e-12);
    let traj = dop853(&mut rhs, 0.0, &[theta0, 0.0], 3.2 * exact, &tol).unwrap();
    let z = zero_crossings(&traj);
    assert!(z.len() >= 6, "{z:?}");
    // Consecutive crossings of θ = 0 are half a period apart.
    let measured = (z[5] - z[1]) / 2.0;
    let rel = (measured - exact).abs() / exact;
    eprintln!("pendulum: period {measured:.14} vs 4K/ω {exact:.14}, rel {rel:.1e}");
    assert!(rel < 1e-10);
}

#[test]
fn double_pendulum_conserves_energy_with_sane_step_counts() {
    let mut rhs = double_pendulum();
    let y0 = [2.0, 2.0, 0.0, 0.0];
    let tol = Tolerances::new(1e-10, 1e-10);
    let traj = dop853(&mut rhs, 0.0, &y0, 20.0, &tol).unwrap();
    let h0 = rhs.energy(0.0, &y0).unwrap();
    let end = ((rhs.energy(20.0, &traj.y_final).unwrap() - h0) / h0).abs();
    let max = max_rel_energy_error(&mut rhs, &traj, 0.0);
    eprintln!(
        "double pendulum dop853: {:?}, energy error end {end:.1e}, max {max:.1e}",
        traj.stats
    );
    // SciPy 1.17's DOP853 on the same problem (the anchor's right-hand side): 842 steps,
    // 13502 evaluations (so 283 rejected), relative energy error 2.2e-9 at 20 s. The same
    // algorithm lands at the same figures here; 1e-9 needs a tighter tolerance (below).
    let s = traj.stats;
    assert!(
        (800..900).contains(&s.accepted) && (250..320).contains(&s.rejected),
        "{s:?}"
    );
    assert!(end <= 4e-9 && max <= 4e-9);
    let tight = dop853(&mut rhs, 0.0, &y0, 20.0, &Tolerances::new(2e-11, 2e-11)).unwrap();
    let tight_err = max_rel_energy_error(&mut rhs, &tight, 0.0);
    eprintln!(
        "at 2e-11: {:?}, max energy error {tight_err:.1e}",
        tight.stats
    );
    assert!(tight_err <= 1e-9);
    // The state at 10 s against the anchor's SciPy DOP853 at 3e-14 (printed to 8 decimals)
    // and a run of our own at 1e-14 (the motion is chaotic, so 10 s, not 20).
    let scipy = [-0.60216261, -10.50147452, -6.2421671, -4.89796966];
    let reference = dop853(&mut rhs, 0.0, &y0, 10.0, &Tolerances::new(1e-14, 1e-14)).unwrap();
    for (a, b) in reference.y_final.iter().zip(&scipy) {
        assert!((a - b).abs() < 1e-7, "{:?}", reference.y_final);
    }
    let at10 = traj.at(10.0).unwrap();
    let dist = at10
        .iter()
        .zip(&scipy)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!("double pendulum at 10 s: {at10:?}, distance to the reference {dist:.1e}");
    assert!(dist < 1e-5);
}

/// The double pendulum's F written by hand (Cramer's rule on the 2 × 2 mass matrix).
fn hand_double_pendulum(_t: f64, y: &[f64], dy: &mut [f64]) {
    let (th1, th2, w1, w2) = (y[0], y[1], y[2], y[3]);
    let g = 9.81;
    let (c, s) = ((th1 - th2).cos(), (th1 - th2).sin());
    let (a11, a12, a22) = (2.0, c, 1.0);
    let f1 = -s * w2 * w2 - 2.0 * g * th1.sin();
    let f2 = s * w1 * w1 - g * th2.sin();
    let det = a11 * a22 - a12 * a12;
    dy[0] = w1;
    dy[1] = w2;
    dy[2] = (f1 * a22 - a12 * f2) / det;
    dy[3] = (a11 * f2 - a12 * f1) / det;
}

#[test]
fn compiled_right_hand_side_matches_the_hand_coded_one() {
    let mut rhs = double_pendulum();
    let mut hand = FnOde::new(4, hand_double_pendulum);
    let (mut a, mut b) = ([0.0; 4], [0.0; 4]);
    for y in [
        [2.0, 2.0, 0.0, 0.0],
        [0.3, -1.2, 2.5, -0.7],
        [3.0, 0.1, -4.0, 6.0],
    ] {
        rhs.eval(0.0, &y, &mut a).unwrap();
        hand.eval(0.0, &y, &mut b).unwrap();
        for (u, v) in a.iter().zip(&b) {
            assert!((u - v).abs() <= 1e-12 * (1.0 + v.abs()), "{a:?} vs {b:?}");
        }
    }
    let tol = Tolerances::new(1e-10, 1e-10);
    let y0 = [2.0, 2.0, 0.0, 0.0];
    let ta = dop853(&mut rhs, 0.0, &y0, 5.0, &tol).unwrap();
    let tb = dop853(&mut hand, 0.0, &y0, 5.0, &tol).unwrap();
    assert_eq!(ta.stats.accepted, tb.stats.accepted);
}

#[test]
fn gauss_keeps_energy_bounded_where_rk4_drifts() {
    let mut sys =
        System::from_lagrangian("m*l^2*theta'^2/2 + m*g*l*cos(theta)", &["theta"]).unwrap();
    let mut rhs = Rhs::new(&mut sys, &[("m", 1.0), ("l", 1.0), ("g", 9.81)]).unwrap();
    let (y0, dt, t_end) = ([2.5, 0.0], 0.1, 1000.0);
    let g = gauss(&mut rhs, 0.0, &y0, t_end, dt).unwrap();
    let r = rk4(&mut rhs, 0.0, &y0, t_end, dt).unwrap();
    let g_early = max_rel_energy_error(&mut rhs, &g, 0.0);
    let g_late = max_rel_energy_error(&mut rhs, &g, 0.9 * t_end);
    let h0 = rhs.energy(0.0, &y0).unwrap();
    let rel_end =
        |rhs: &mut Rhs, t: &Trajectory| ((rhs.energy(t_end, &t.y_final).unwrap() - h0) / h0).abs();
    let (g_end, r_end) = (rel_end(&mut rhs, &g), rel_end(&mut rhs, &r));
    let r_tenth = {
        let y = r.at(0.1 * t_end).unwrap();
        ((rhs.energy(0.1 * t_end, &y).unwrap() - h0) / h0).abs()
    };
    eprintln!(
        "pendulum dt = {dt}, {t_end} s: gauss max {g_early:.2e} (last tenth {g_late:.2e}, end {g_end:.2e}); \
         rk4 at 100 s {r_tenth:.2e}, end {r_end:.2e}; gauss {:?}",
        g.stats
    );
    // Bounded: the error of the last tenth is no larger than over the whole run (no drift),
    // and RK4 at the same step drifts far beyond it, growing with time.
    assert!(g_late <= g_early * 1.0001 && g_early < 1e-3);
    assert!(r_end > 10.0 * g_early && r_end > 5.0 * r_tenth);
}

#[test]
fn bad_settings_and_divergence_are_typed_errors() {
    let mut rhs = oscillator();
    let e = dop853(&mut rhs, 0.0, &[1.0], 1.0, &Tolerances::default()).unwrap_err();
    assert!(matches!(e, SimError::StateLength { got: 1, want: 2 }));
    let e = rk4(&mut rhs, 0.0, &[1.0, 0.0], -1.0, 0.1).unwrap_err();
    assert!(matches!(e, SimError::Invalid(_)));
    // y' = y² blows up at t = 1.
    let mut blow = FnOde::new(1, |_t, y: &[f64], dy: &mut [f64]| dy[0] = y[0] * y[0]);
    let e = dop853(&mut blow, 0.0, &[1.0], 2.0, &Tolerances::default()).unwrap_err();
    let t = match e {
        SimError::Diverges { t } | SimError::StepUnderflow { t } => t,
        other => panic!("{other:?}"),
    };
    assert!((t - 1.0).abs() < 1e-3, "{t}");
    assert!(e.to_string().contains("t = "));
}

#[test]
fn a_mass_matrix_that_becomes_singular_is_reported_with_its_time() {
    // M = (t − 1)² vanishes at t = 1; at rest the motion stays put until then, and RK4's
    // grid of quarter steps evaluates F exactly there.
    let mut sys = System::from_lagrangian("(t - 1)^2*x'^2/2", &["x"]).unwrap();
    let mut rhs = Rhs::new::<&str>(&mut sys, &[]).unwrap();
    let e = rk4(&mut rhs, 0.0, &[1.0, 0.0], 2.0, 0.25).unwrap_err();
    assert!(
        matches!(e, SimError::Singular { t, .. } if (t - 1.0).abs() < 1e-9),
        "{e:?}"
    );
    assert!(
        e.to_string()
            .starts_with("the mass matrix became singular at t = 1")
    );
}

#[test]
fn without_dense_output_dop853_takes_the_same_steps_with_twelve_evaluations_each() {
    let mut rhs = double_pendulum();
    let y0 = [2.0, 2.0, 0.0, 0.0];
    let mut tol = Tolerances::new(1e-10, 1e-10);
    let dense = dop853(&mut rhs, 0.0, &y0, 20.0, &tol).unwrap();
    tol.dense = false;
    let lean = dop853(&mut rhs, 0.0, &y0, 20.0, &tol).unwrap();
    assert_eq!(lean.y_final, dense.y_final);
    let s = lean.stats;
    assert_eq!(s.rhs_evals, 2 + 12 * s.accepted + 11 * s.rejected);
    // The Hermite interpolant is cruder than the dense output, but continuous and close.
    let (a, b) = (lean.at(3.3).unwrap(), dense.at(3.3).unwrap());
    assert!((a[0] - b[0]).abs() < 1e-4, "{a:?} {b:?}");
}

#[test]
fn gauss_keeps_the_double_pendulum_energy_bounded() {
    let mut rhs = double_pendulum();
    let (y0, dt, t_end) = ([0.5, 0.5, 0.0, 0.0], 0.02, 200.0);
    let g = gauss(&mut rhs, 0.0, &y0, t_end, dt).unwrap();
    let r = rk4(&mut rhs, 0.0, &y0, t_end, dt).unwrap();
    let g_all = max_rel_energy_error(&mut rhs, &g, 0.0);
    let g_late = max_rel_energy_error(&mut rhs, &g, 0.8 * t_end);
    let r_all = max_rel_energy_error(&mut rhs, &r, 0.0);
    eprintln!(
        "double pendulum dt = {dt}, {t_end} s: gauss max {g_all:.2e} (last fifth {g_late:.2e}), \
         rk4 max {r_all:.2e}; gauss {:?}",
        g.stats
    );
    assert!(g_late <= g_all * 1.0001 && r_all > 5.0 * g_all);
}
