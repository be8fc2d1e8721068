//! Benchmarks of the mechanics engine (issue: mechanics engine):
//! - planar n-link pendulum (equal m, l; angles from the vertical), n = 1…10 and 20: build L
//!   from the bodies' positions, then derive the equations, M and f (all simplified), as
//!   SymPy's `LagrangesMethod` anchor does; and the size (operation count) of the printed
//!   equations, printed at start-up next to SymPy's simplified sizes;
//! - numeric normal modes of the 20-link pendulum (stiffness and mass evaluation, Cholesky
//!   reduction and symmetric eigen-decomposition);
//! - symbolic double-pendulum modes with m₁ = m₂ = m, l₁ = l₂ = l, from the Lagrangian text.

use divan::{Bencher, black_box};
use lagrange::mechanics::System;
use lagrange::mechanics::equilibria::Statics;

fn n_link(n: usize) -> System {
    lagrange::mechanics::fixtures::n_link_pendulum(n)
}

fn printed_ops(n: usize) -> (usize, f64) {
    let t0 = std::time::Instant::now();
    let mut sys = n_link(n);
    let d = sys.derive().expect("derives");
    let secs = t0.elapsed().as_secs_f64();
    let ops = d
        .steps
        .iter()
        .map(|s| {
            let f = sys.pool.factored(s.equation);
            f.count_ops(&sys.pool)
        })
        .sum();
    (ops, secs)
}

const DOUBLE_PENDULUM: &str = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)";

fn main() {
    println!("printed size of the n-link pendulum's equations (count_ops, summed over equations):");
    let sympy = [(2, 58), (3, 149), (4, 282)];
    for n in [1, 2, 3, 4, 6, 8, 10, 20] {
        let (ops, secs) = printed_ops(n);
        let s = sympy
            .iter()
            .find(|(k, _)| *k == n)
            .map_or(String::new(), |(_, o)| format!("  (SymPy simplified: {o})"));
        println!(
            "  n = {n:>2}: {ops:>6} ops{s}; one derivation {:.3} ms",
            secs * 1e3
        );
    }
    divan::main();
}

#[divan::bench(args = [1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 20], sample_count = 10)]
fn n_link_pendulum_derive(b: Bencher, n: usize) {
    b.bench_local(|| {
        let mut sys = n_link(n);
        black_box(sys.derive().expect("derives"))
    });
}

#[divan::bench(sample_count = 100)]
fn n_link_20_numeric_modes(b: Bencher) {
    let mut sys = n_link(20);
    let d = sys.derive().expect("derives");
    let params = vec![9.81, 1.0, 1.0]; // g, l, m
    let statics = Statics::new(&mut sys, &d, &params).expect("compiles");
    let q0 = vec![0.0; 20];
    b.bench_local(|| black_box(statics.stability(&q0).expect("modes")));
}

#[divan::bench(sample_count = 100)]
fn double_pendulum_symbolic_modes(b: Bencher) {
    b.bench_local(|| {
        let mut sys =
            System::from_lagrangian(DOUBLE_PENDULUM, &["theta1", "theta2"]).expect("reads");
        sys.substitute_parameters(&[
            ("m1".into(), "m".into()),
            ("m2".into(), "m".into()),
            ("l1".into(), "l".into()),
            ("l2".into(), "l".into()),
        ])
        .expect("substitutes");
        let d = sys.derive().expect("derives");
        let zero = sys.pool.zero();
        black_box(sys.symbolic_modes(&d, &[zero, zero]).expect("modes"))
    });
}
