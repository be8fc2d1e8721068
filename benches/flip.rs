//! Benchmark of the batch RK4 behind the flip-time map (issue 14, item 6): the double
//! pendulum (m = l = 1, g = 9.81) from 1000 starts at rest with angles spread over
//! [−2.5, 2.5]² — the workload of the numpy anchor's batch row (K = 1000, 2 s, dt = 1e-3,
//! 2 M trajectory-steps) — single-thread, scalar (one trajectory at a time) against lanes of
//! K = 4, 8, 16, 32. No angle is watched, so every trajectory runs its 2000 steps; the
//! counter is trajectory-steps.

use divan::counter::ItemsCount;
use divan::{Bencher, black_box};
use lagrange::mechanics::fixtures::n_link_pendulum;
use lagrange::simulate::{FlipSettings, Rhs, flip_times};

fn main() {
    divan::main();
}

fn rhs() -> Rhs {
    let mut sys = n_link_pendulum(2);
    Rhs::new(&mut sys, &[("m", 1.0), ("l", 1.0), ("g", 9.81)]).expect("rhs")
}

/// 1000 starts at rest on a deterministic 40 × 25 spread over [−2.5, 2.5]².
fn starts() -> Vec<f64> {
    let mut s = Vec::with_capacity(4000);
    for i in 0..40 {
        for j in 0..25 {
            let a = -2.5 + 5.0 * f64::from(i) / 39.0;
            let b = -2.5 + 5.0 * f64::from(j) / 24.0;
            s.extend_from_slice(&[a, b, 0.0, 0.0]);
        }
    }
    s
}

#[divan::bench(args = [1, 4, 8, 16, 32], sample_count = 5, sample_size = 1)]
fn batch_rk4_2s(bencher: Bencher, lanes: usize) {
    let (rhs, starts) = (rhs(), starts());
    let settings = FlipSettings {
        t_end: 2.0,
        dt: 1e-3,
        watch: Vec::new(),
        lanes,
    };
    bencher
        .counter(ItemsCount::new(2000usize * 1000))
        .bench(|| flip_times(black_box(&rhs), black_box(&starts), &settings).expect("run"));
}
