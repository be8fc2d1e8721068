//! Simulation: the equations of motion of a [`System`](crate::mechanics::System) as a
//! first-order system y' = F(t, y), y = (q, q'), and the integrators that advance it.
//!
//! - [`Rhs`]: M and f compiled once; each call solves M q'' = f in reused buffers;
//! - [`dop853`]: adaptive Dormand–Prince 8(5,3) (Hairer's DOP853 error control, dense output);
//! - [`rk4`]: the classical fixed-step Runge–Kutta method;
//! - [`flip_times`]: many trajectories in lockstep over lanes, to the time an angle flips;
//! - [`gauss`]: the 2-stage Gauss–Legendre method (order 4, implicit, symplectic);
//! - [`portrait`]: a family of trajectories at a grid of energies (one degree of freedom);
//! - [`chaos`]: separation of nearby trajectories, the largest Lyapunov exponent (Benettin),
//!   the Poincaré section; [`events`]: zero crossings located on dense output.
//!
//! Every integrator returns a [`Trajectory`]: step counts, the final state and a continuous
//! solution that can be sampled anywhere in the interval. No printing, files or threads.
//! The methods are written here (no ODE crate: none of them shares the project's nalgebra
//! 0.35 without a second copy, and these need no linear algebra beyond n × n solves).

mod batch;
pub mod chaos;
mod dop853;
mod dop853_tableau;
pub mod events;
mod fixed;
pub mod portrait;
mod rhs;
mod trajectory;

pub use batch::{
    DEFAULT_FLIP_DT, FlipRun, FlipSettings, LANE_WIDTHS, Outcome, flip_times, flip_times_with,
};
pub use dop853::{dop853, dop853_with};
pub use fixed::{gauss, gauss_with, rk4, rk4_with};
pub use rhs::{Rhs, parameter_values};
pub use trajectory::{Method, Stats, Trajectory};

use crate::mechanics::MechError;
use crate::progress::Interrupted;

impl From<Interrupted> for SimError {
    fn from(_: Interrupted) -> Self {
        SimError::Interrupted
    }
}

/// What can go wrong setting up or running a simulation.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimError {
    /// A parameter of the system has no value.
    #[error("no value was given for {}", list_names(names))]
    MissingParameters { names: Vec<String> },
    /// A value was given for something that is not a parameter.
    #[error("`{name}` is not a parameter of the system (its parameters: {known})")]
    UnknownParameter { name: String, known: String },
    /// The initial state has the wrong length.
    #[error("the initial state has {got} values where {want} were expected (q then q')")]
    StateLength { got: usize, want: usize },
    /// A tolerance, step or interval that cannot work.
    #[error("invalid setting: {0}")]
    Invalid(String),
    /// M became singular along the motion, at the state `y` = (q, q').
    #[error("the mass matrix became singular at t = {}", time(*t))]
    Singular { t: f64, y: Vec<f64> },
    /// The solution or the right-hand side stopped being finite.
    #[error("{}", diverged_at(*t))]
    Diverges { t: f64 },
    /// The adaptive step fell below rounding of t.
    #[error(
        "the step size underflowed at t = {}: the solution may blow up there (reach infinity in finite time), or the equations are too stiff or singular", time(*t)
    )]
    StepUnderflow { t: f64 },
    /// More steps than allowed.
    #[error("more than {max} steps were needed before t = {}", time(*t))]
    TooManySteps { max: usize, t: f64 },
    /// The implicit stage equations did not converge.
    #[error("the implicit Gauss step did not converge at t = {} (try a smaller step)", time(*t))]
    NoConvergence { t: f64 },
    /// The progress callback asked the run to stop.
    #[error("interrupted")]
    Interrupted,
    /// Building the equations failed.
    #[error(transparent)]
    Mechanics(#[from] MechError),
}

/// A time for a message: as is where that is short, else in scientific notation (`4.49e307`,
/// never 308 digits).
pub fn time(t: f64) -> String {
    if t == 0.0 || (1e-6..1e9).contains(&t.abs()) {
        format!("{t}")
    } else {
        format!("{t:e}")
    }
}

/// What happened when the motion stopped being finite: where, or — when time itself ran past
/// the largest number (t = ∞) — that, in words.
fn diverged_at(t: f64) -> String {
    if t.is_finite() {
        format!("the solution diverges near t = {}", time(t))
    } else {
        "the time itself overflowed: the steps carried t past the largest number a computer \
         holds (about 1.8e308) before the motion ended, so the solution could not be followed \
         to the end"
            .into()
    }
}

/// "the parameter `g`" or "the parameters `g`, `l`".
fn list_names(names: &[String]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    let s = if names.len() == 1 { "" } else { "s" };
    format!("the parameter{s} {}", quoted.join(", "))
}

/// A first-order system y' = F(t, y) of fixed dimension.
pub trait Ode {
    /// The dimension of y.
    fn dim(&self) -> usize;
    /// Writes F(t, y) into `dy`.
    fn eval(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError>;
}

/// A closure as an [`Ode`] (tests, hand-coded right-hand sides).
pub struct FnOde<F> {
    dim: usize,
    f: F,
}

impl<F: FnMut(f64, &[f64], &mut [f64])> FnOde<F> {
    /// The system of dimension `dim` whose F is `f`.
    pub fn new(dim: usize, f: F) -> Self {
        FnOde { dim, f }
    }
}

impl<F: FnMut(f64, &[f64], &mut [f64])> Ode for FnOde<F> {
    fn dim(&self) -> usize {
        self.dim
    }

    fn eval(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError> {
        (self.f)(t, y, dy);
        if dy.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(SimError::Diverges { t })
        }
    }
}

/// Error control and limits of [`dop853`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance.
    pub(crate) rtol: f64,
    /// Absolute tolerance.
    pub(crate) atol: f64,
    /// The largest step (∞ for none).
    pub(crate) max_step: f64,
    /// The largest number of steps (accepted and rejected).
    pub(crate) max_steps: usize,
    /// DOP853's 7th-degree dense output (3 more evaluations per step); without it the
    /// trajectory interpolates each step by a cubic Hermite polynomial (as SciPy without
    /// `dense_output`: 12 evaluations per step).
    pub dense: bool,
}

impl Tolerances {
    /// rtol and atol, no step limit, at most a million steps, dense output.
    pub fn new(rtol: f64, atol: f64) -> Self {
        Tolerances {
            rtol,
            atol,
            max_step: f64::INFINITY,
            max_steps: 500_000,
            dense: true,
        }
    }
}

impl Default for Tolerances {
    /// rtol = 1e-8, atol = 1e-10.
    fn default() -> Self {
        Tolerances::new(1e-8, 1e-10)
    }
}

/// Checks the interval and initial state shared by every method.
fn check_start(ode: &dyn Ode, t0: f64, y0: &[f64], t_end: f64) -> Result<(), SimError> {
    if y0.len() != ode.dim() {
        return Err(SimError::StateLength {
            got: y0.len(),
            want: ode.dim(),
        });
    }
    if !(t0.is_finite() && t_end.is_finite() && t_end > t0) {
        return Err(SimError::Invalid(format!(
            "the end time {t_end} must be finite and after the start {t0}"
        )));
    }
    if !y0.iter().all(|v| v.is_finite()) {
        return Err(SimError::Invalid("the initial state is not finite".into()));
    }
    Ok(())
}

#[cfg(test)]
mod progress_tests;
