//! Benchmarks of the simulation numerics (issue 14): the double pendulum (m = l = 1,
//! g = 9.81, θ₁ = θ₂ = 2 rad at rest) over 20 s with DOP853 at rtol = atol = 1e-10, through
//! the compiled right-hand side and through a hand-coded one (the yardstick: the compiled
//! M and f should cost at most 2× the hand-written Cramer's rule); one right-hand-side call
//! of each; and Gauss and RK4 at dt = 1e-3 over the same 20 s.

use divan::{Bencher, black_box};
use lagrange::mechanics::fixtures;
use lagrange::simulate::{FnOde, Ode, Rhs, Tolerances, dop853, gauss, rk4};

const Y0: [f64; 4] = [2.0, 2.0, 0.0, 0.0];

fn compiled() -> Rhs {
    let mut sys = fixtures::double_pendulum();
    Rhs::new(&mut sys, &fixtures::DOUBLE_PENDULUM_ANCHOR).expect("rhs")
}

/// The anchor's right-hand side, by hand (Cramer's rule on the 2 × 2 mass matrix).
fn hand(_t: f64, y: &[f64], dy: &mut [f64]) {
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

fn main() {
    divan::main();
}

#[divan::bench]
fn rhs_call_compiled(b: Bencher) {
    let mut rhs = compiled();
    let mut dy = [0.0; 4];
    b.bench_local(|| rhs.eval(0.0, black_box(&[0.3, -1.2, 2.5, -0.7]), &mut dy));
}

#[divan::bench]
fn rhs_call_hand(b: Bencher) {
    let mut ode = FnOde::new(4, hand);
    let mut dy = [0.0; 4];
    b.bench_local(|| ode.eval(0.0, black_box(&[0.3, -1.2, 2.5, -0.7]), &mut dy));
}

#[divan::bench(args = [true, false])]
fn dop853_20s_compiled(b: Bencher, dense: bool) {
    let mut rhs = compiled();
    let mut tol = Tolerances::new(1e-10, 1e-10);
    tol.dense = dense;
    b.bench_local(|| dop853(&mut rhs, 0.0, black_box(&Y0), 20.0, &tol));
}

#[divan::bench(args = [true, false])]
fn dop853_20s_hand(b: Bencher, dense: bool) {
    let mut ode = FnOde::new(4, hand);
    let mut tol = Tolerances::new(1e-10, 1e-10);
    tol.dense = dense;
    b.bench_local(|| dop853(&mut ode, 0.0, black_box(&Y0), 20.0, &tol));
}

#[divan::bench]
fn rk4_20s_dt_1e3_compiled(b: Bencher) {
    let mut rhs = compiled();
    b.bench_local(|| rk4(&mut rhs, 0.0, black_box(&Y0), 20.0, 1e-3));
}

#[divan::bench]
fn gauss_20s_dt_1e3_compiled(b: Bencher) {
    let mut rhs = compiled();
    b.bench_local(|| gauss(&mut rhs, 0.0, black_box(&Y0), 20.0, 1e-3));
}
