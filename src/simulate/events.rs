//! Event location on dense output: the times where a function g(y) of the state crosses zero
//! in a chosen direction, found per accepted step from the sign of g at its ends and solved
//! on the step's interpolant by the Illinois variant of regula falsi (a bracket that always
//! shrinks, superlinear convergence) to about 1e-12 in t. Two crossings inside one step
//! (g back to its sign before the step ends) are not seen: steps are short against the
//! motion's oscillations at the tolerances used here.

use super::Trajectory;

/// The time tolerance of a located crossing.
const T_TOL: f64 = 1e-12;
/// Iterations after which the bracket's midpoint is taken (never reached in practice).
const MAX_ITER: usize = 200;

/// The direction of a crossing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// g goes from negative to non-negative.
    Rising,
    /// g goes from positive to non-positive.
    Falling,
}

/// One located crossing: its time and the state there.
#[derive(Clone, Debug, PartialEq)]
pub struct Crossing {
    pub(crate) t: f64,
    pub(crate) y: Vec<f64>,
}

/// Every crossing of g = 0 in `direction` along `traj`, at most `max` of them, in time order.
/// The start itself is not a crossing (g must change sign within a step).
pub fn crossings(
    traj: &Trajectory,
    g: &dyn Fn(&[f64]) -> f64,
    direction: Direction,
    max: usize,
) -> Vec<Crossing> {
    let sign = match direction {
        Direction::Rising => 1.0,
        Direction::Falling => -1.0,
    };
    let signed = |y: &[f64]| sign * g(y);
    let times = traj.step_times();
    let mut y = vec![0.0; traj.dim()];
    let mut found = Vec::new();
    let mut g_a = signed(&traj.y0);
    for w in times.windows(2) {
        if found.len() >= max {
            break;
        }
        let (t_a, t_b) = (w[0], w[1]);
        traj.at_into(t_b, &mut y);
        let g_b = signed(&y);
        if g_a < 0.0 && g_b >= 0.0 {
            let t = solve(traj, &signed, (t_a, g_a), (t_b, g_b), &mut y);
            traj.at_into(t, &mut y);
            found.push(Crossing { t, y: y.clone() });
            traj.at_into(t_b, &mut y);
        }
        g_a = g_b;
    }
    found
}

/// The root of the signed g between a (g < 0) and b (g ≥ 0) on the interpolant, by Illinois.
fn solve(
    traj: &Trajectory,
    g: &dyn Fn(&[f64]) -> f64,
    (mut a, mut ga): (f64, f64),
    (mut b, mut gb): (f64, f64),
    y: &mut [f64],
) -> f64 {
    if gb == 0.0 {
        return b;
    }
    // Which end was kept last time: halving its g when kept twice is the Illinois step.
    let mut kept = 0i8;
    for _ in 0..MAX_ITER {
        if b - a <= T_TOL * b.abs().max(1.0) {
            break;
        }
        let c = (a - ga * (b - a) / (gb - ga)).clamp(a, b);
        traj.at_into(c, y);
        let gc = g(y);
        if gc == 0.0 {
            return c;
        }
        if gc < 0.0 {
            (a, ga) = (c, gc);
            if kept == 1 {
                gb *= 0.5;
            }
            kept = 1;
        } else {
            (b, gb) = (c, gc);
            if kept == -1 {
                ga *= 0.5;
            }
            kept = -1;
        }
        if (b - a) <= T_TOL * b.abs().max(1.0) {
            break;
        }
    }
    if ga.abs() < gb.abs() { a } else { b }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{FnOde, Tolerances, dop853};

    /// x'' = −x from (x, x') = (0, −1): x = −sin t rises through 0 at t = π, 3π, 5π with
    /// x' = +1 there (and the start, x = 0, is not a crossing).
    #[test]
    fn the_oscillator_crosses_zero_upwards_at_odd_multiples_of_pi() {
        let mut ode = FnOde::new(2, |_t, y: &[f64], dy: &mut [f64]| {
            dy[0] = y[1];
            dy[1] = -y[0];
        });
        let traj = dop853(
            &mut ode,
            0.0,
            &[0.0, -1.0],
            17.0,
            &Tolerances::new(1e-12, 1e-12),
        )
        .unwrap();
        let up = crossings(&traj, &|y| y[0], Direction::Rising, 100);
        let pi = std::f64::consts::PI;
        let times: Vec<f64> = up.iter().map(|c| c.t).collect();
        assert_eq!(times.len(), 3, "{times:?}");
        for (c, k) in up.iter().zip([1.0, 3.0, 5.0]) {
            assert!((c.t - k * pi).abs() < 1e-10, "{} vs {}", c.t, k * pi);
            assert!(c.y[0].abs() < 1e-11 && (c.y[1] - 1.0).abs() < 1e-10);
        }
        let down = crossings(&traj, &|y| y[0], Direction::Falling, 100);
        let times: Vec<f64> = down.iter().map(|c| c.t).collect();
        assert_eq!(times.len(), 2, "{times:?}");
        assert!((times[0] - 2.0 * pi).abs() < 1e-10);
        assert_eq!(crossings(&traj, &|y| y[0], Direction::Rising, 2).len(), 2);
    }
}
