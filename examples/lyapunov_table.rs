//! The measurement behind `lagrange chaos`'s default end time: Benettin's estimate for the
//! double pendulum (m = l = 1, g = 9.81) at θ₁ = θ₂ = 2 rad across delta × tolerance × t_end,
//! and at 0.2 rad over t_end. A table to read, not a test:
//! `cargo run --release --example lyapunov_table [T1,T2,…]` (default 30,100,200,400).

use lagrange::mechanics::fixtures;
use lagrange::simulate::chaos::{LyapunovOptions, lyapunov};
use lagrange::simulate::{Rhs, Tolerances};

fn estimate(angle: f64, delta: f64, tol: f64, t_end: f64) -> Result<f64, String> {
    let mut sys = fixtures::double_pendulum();
    let mut rhs =
        Rhs::new(&mut sys, &fixtures::DOUBLE_PENDULUM_ANCHOR).map_err(|e| e.to_string())?;
    let opts = LyapunovOptions {
        delta,
        t_end,
        tau: 1.0,
        tol: Tolerances::new(tol, tol),
    };
    let l = lyapunov(&mut rhs, &[angle, angle, 0.0, 0.0], &opts).map_err(|e| e.to_string())?;
    Ok(l.exponent)
}

fn main() -> Result<(), String> {
    let t_ends: Vec<f64> = match std::env::args().nth(1) {
        Some(list) => list
            .split(',')
            .map(|x| x.trim().parse().map_err(|_| format!("`{x}` is not a time")))
            .collect::<Result<_, _>>()?,
        None => vec![30.0, 100.0, 200.0, 400.0],
    };
    for &t_end in &t_ends {
        for delta in [1e-8, 1e-9, 1e-10] {
            for tol in [1e-9, 1e-10, 1e-11] {
                let l = estimate(2.0, delta, tol, t_end)?;
                println!("2 rad, t_end {t_end}, delta {delta:e}, tol {tol:e}: {l:.4}");
            }
        }
    }
    for t_end in [10.0, 30.0, 100.0, 300.0, 1000.0] {
        println!(
            "0.2 rad, t_end {t_end}: {:.5}",
            estimate(0.2, 1e-9, 1e-10, t_end)?
        );
    }
    Ok(())
}
