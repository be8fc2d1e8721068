//! The progress callback of the long calls: it hears the run advance, and a `Break` ends the
//! run early with [`SimError::Interrupted`] (no trajectory, no panic).

use std::ops::ControlFlow;

use super::*;
use crate::mechanics::fixtures;
use crate::progress::PARTS;

fn double_pendulum() -> Rhs {
    let mut sys = fixtures::double_pendulum();
    Rhs::new(&mut sys, &fixtures::DOUBLE_PENDULUM_ANCHOR).unwrap()
}

#[test]
fn a_break_stops_a_long_simulation_early() {
    let mut rhs = double_pendulum();
    let mut calls = 0u64;
    let mut last = 0;
    let mut stop_after_ten = |done: u64, total: u64| {
        assert_eq!(total, PARTS);
        assert!(done >= last, "progress goes forward");
        last = done;
        calls += 1;
        if calls == 10 {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    };
    let y0 = [2.0, 2.0, 0.0, 0.0];
    let tol = Tolerances::default();
    let got = dop853_with(&mut rhs, (0.0, &y0, 1000.0), &tol, &mut stop_after_ten);
    assert_eq!(got.err(), Some(SimError::Interrupted));
    assert_eq!(calls, 10, "no step after the break");
    assert!(last < PARTS / 100, "stopped early: {last}");
    for method in [rk4_with, gauss_with] {
        let mut n = 0;
        let mut stop = |_: u64, _: u64| {
            n += 1;
            ControlFlow::Break(())
        };
        let got = method(&mut rhs, (0.0, &y0, 1000.0), 1e-3, &mut stop);
        assert_eq!(got.err(), Some(SimError::Interrupted));
        assert_eq!(n, 1);
    }
}

#[test]
fn a_run_reports_its_end_and_a_break_stops_flip_times() {
    let mut rhs = double_pendulum();
    let mut last = 0;
    let mut rec = |done: u64, _: u64| {
        last = done;
        ControlFlow::Continue(())
    };
    let y0 = [0.1, 0.0, 0.0, 0.0];
    dop853_with(&mut rhs, (0.0, &y0, 5.0), &Tolerances::default(), &mut rec).unwrap();
    assert_eq!(last, PARTS);
    let settings = FlipSettings {
        t_end: 100.0,
        dt: 1e-3,
        watch: vec![0],
        lanes: 4,
    };
    let starts: Vec<f64> = (0..64)
        .flat_map(|i| [0.01 * i as f64, 0.0, 0.0, 0.0])
        .collect();
    let mut stop = |_: u64, _: u64| ControlFlow::Break(());
    let got = flip_times_with(&rhs, &starts, &settings, &mut stop);
    assert_eq!(got.err(), Some(SimError::Interrupted));
}
