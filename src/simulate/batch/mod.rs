//! Many trajectories of one system: fixed-step classical RK4 from a batch of starts, run to
//! the time an angle first goes over the top (the flip-time map of the double pendulum).
//!
//! "Over the top" is defined precisely: a watched angle θ (a periodic coordinate, measured
//! from the hanging position) flips when its continuous value — never wrapped — leaves the
//! open interval (−π, π). The flip time is the step's end points' linear interpolation of
//! the crossing of ±π, so it is accurate to the integration error plus O(dt²). A start with
//! |θ| ≥ π is already over: its outcome says so instead of a made-up time.
//!
//! The vectorized path runs `K` trajectories in lockstep over lanes ([`Program::run_lanes`]
//! via [`Dynamics::mass_and_forcing_lanes`]): one instruction stream for `K` states. A lane
//! whose trajectory ended (flipped, reached t_end, failed) is refilled at once with the
//! next start, so the batch stays full until the starts run out. The scalar path (`lanes`
//! = 1) is the reference. No threads here: a face splits the starts among its workers.
//!
//! [`Program::run_lanes`]: crate::expr::Program::run_lanes
//! [`Dynamics::mass_and_forcing_lanes`]: crate::mechanics::accel::Dynamics::mass_and_forcing_lanes

use std::f64::consts::PI;

use super::{Ode, Rhs, SimError};
use crate::mechanics::Layout;
use crate::mechanics::singular::{is_singular_2x2, solve_in_place};
use crate::progress::{Interrupted, Progress, Silent, tick};

/// The step used for flip maps when none is given: RK4's error at 1e-3 is far below the
/// resolution of a map, and the double pendulum's chaos makes any finer step no more true.
pub const DEFAULT_FLIP_DT: f64 = 1e-3;

/// The lane widths [`flip_times`] accepts (1 is the scalar path).
pub const LANE_WIDTHS: [usize; 5] = [1, 4, 8, 16, 32];

/// Most steps one trajectory may take.
const MAX_STEPS: f64 = 1e9;
/// Lockstep steps between two progress reports of the lanes.
const REPORT_EVERY: usize = 1024;

/// What happened to one start.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Outcome {
    /// Watched coordinate `coordinate` left (−π, π) at time `t`.
    Flipped { t: f64, coordinate: usize },
    /// No watched angle left (−π, π) before t_end.
    Stayed,
    /// The start already has |θ| ≥ π for watched coordinate `coordinate` (flip time 0).
    StartsOver { coordinate: usize },
    /// The mass matrix became singular at time `t`.
    Singular { t: f64 },
    /// The state or the equations stopped being finite at time `t`.
    Diverged { t: f64 },
}

impl Outcome {
    /// The flip time, if the start flipped (0 for a start already over the top).
    pub fn flip_time(&self) -> Option<f64> {
        match *self {
            Outcome::Flipped { t, .. } => Some(t),
            Outcome::StartsOver { .. } => Some(0.0),
            _ => None,
        }
    }
}

/// How to run a batch.
#[derive(Clone, Debug, PartialEq)]
pub struct FlipSettings {
    /// Each trajectory runs from t = 0 to at most this time.
    pub t_end: f64,
    /// The fixed step (shrunk so that a whole number of steps ends at t_end).
    pub dt: f64,
    /// The coordinates (indices) whose angle is watched.
    pub watch: Vec<usize>,
    /// Trajectories per lockstep batch: one of [`LANE_WIDTHS`].
    pub lanes: usize,
}

/// The outcomes of a batch, one per start, and the work done.
#[derive(Clone, Debug, PartialEq)]
pub struct FlipRun {
    /// One per start, in the order of the starts.
    pub outcomes: Vec<Outcome>,
    /// RK4 steps taken, summed over the trajectories.
    pub(crate) steps: u64,
}

/// Integrates every start (phase points y = (q, q'), concatenated in `starts`) with RK4 at
/// `settings.dt` until a watched angle flips or t_end. Errors only for settings that cannot
/// work; what happens to each trajectory is its [`Outcome`].
pub fn flip_times(rhs: &Rhs, starts: &[f64], settings: &FlipSettings) -> Result<FlipRun, SimError> {
    flip_times_with(rhs, starts, settings, &mut Silent)
}

/// [`flip_times`] that reports the trajectories finished out of all; a `Break` ends it with
/// [`SimError::Interrupted`].
pub fn flip_times_with(
    rhs: &Rhs,
    starts: &[f64],
    settings: &FlipSettings,
    progress: &mut dyn Progress,
) -> Result<FlipRun, SimError> {
    let layout = rhs.layout();
    let dim = layout.phase_len();
    let steps = step_count(settings)?;
    if !starts.len().is_multiple_of(dim) {
        return Err(SimError::StateLength {
            got: starts.len() % dim,
            want: dim,
        });
    }
    if let Some(&i) = settings.watch.iter().find(|&&i| i >= layout.coordinates()) {
        return Err(SimError::Invalid(format!(
            "no coordinate number {i} to watch"
        )));
    }
    let h = settings.t_end / steps as f64;
    let job = Job {
        starts,
        dim,
        steps,
        h,
        watch: &settings.watch,
    };
    // The lanes evaluate M and f only; constraints need the augmented solve of the scalar
    // right-hand side, so a constrained system takes the scalar path.
    let lanes = if rhs.dynamics().constraints() > 0 {
        1
    } else {
        settings.lanes
    };
    Ok(match lanes {
        1 => scalar(rhs, &job, progress)?,
        4 => Lanes::<4>::new(rhs, &job).run(progress)?,
        8 => Lanes::<8>::new(rhs, &job).run(progress)?,
        16 => Lanes::<16>::new(rhs, &job).run(progress)?,
        32 => Lanes::<32>::new(rhs, &job).run(progress)?,
        k => {
            return Err(SimError::Invalid(format!(
                "{k} lanes; the lane widths are {LANE_WIDTHS:?}"
            )));
        }
    })
}

/// The number of steps: t_end / dt rounded up, at least 1.
fn step_count(s: &FlipSettings) -> Result<usize, SimError> {
    if !(s.t_end.is_finite() && s.t_end > 0.0) {
        return Err(SimError::Invalid(format!(
            "the end time {} must be finite and positive",
            s.t_end
        )));
    }
    if !(s.dt > 0.0 && s.dt.is_finite()) || s.t_end / s.dt > MAX_STEPS {
        return Err(SimError::Invalid(format!(
            "the step {} must be positive and give at most 1e9 steps",
            s.dt
        )));
    }
    Ok(((s.t_end / s.dt) - 1e-9).ceil().max(1.0) as usize)
}

/// The shared description of a batch.
struct Job<'a> {
    starts: &'a [f64],
    dim: usize,
    steps: usize,
    h: f64,
    watch: &'a [usize],
}

impl Job<'_> {
    fn count(&self) -> usize {
        self.starts.len() / self.dim
    }

    fn start(&self, c: usize) -> &[f64] {
        &self.starts[c * self.dim..(c + 1) * self.dim]
    }

    /// The outcome of a start that cannot begin: not finite, or already over the top.
    fn refused(&self, y: &[f64]) -> Option<Outcome> {
        if !y.iter().all(|v| v.is_finite()) {
            return Some(Outcome::Diverged { t: 0.0 });
        }
        self.watch
            .iter()
            .find(|&&i| y[i].abs() >= PI)
            .map(|&coordinate| Outcome::StartsOver { coordinate })
    }

    /// The earliest watched crossing of ±π in a step from `old` to `new` (angles of the
    /// phase points given by `at`), as (fraction of the step, coordinate).
    fn crossing(&self, at: impl Fn(usize) -> (f64, f64)) -> Option<(f64, usize)> {
        let mut first: Option<(f64, usize)> = None;
        for &i in self.watch {
            let (old, new) = at(i);
            if new.abs() < PI {
                continue;
            }
            let edge = if new >= PI { PI } else { -PI };
            let frac = ((edge - old) / (new - old)).clamp(0.0, 1.0);
            if first.is_none_or(|(f, _)| frac < f) {
                first = Some((frac, i));
            }
        }
        first
    }
}

/// One trajectory at a time through the scalar right-hand side (the reference path).
fn scalar(rhs: &Rhs, job: &Job, progress: &mut dyn Progress) -> Result<FlipRun, Interrupted> {
    let mut ode = rhs.clone();
    let dim = job.dim;
    let mut k = [
        vec![0.0; dim],
        vec![0.0; dim],
        vec![0.0; dim],
        vec![0.0; dim],
    ];
    let (mut y, mut tmp) = (vec![0.0; dim], vec![0.0; dim]);
    let mut run = FlipRun {
        outcomes: Vec::with_capacity(job.count()),
        steps: 0,
    };
    for c in 0..job.count() {
        y.copy_from_slice(job.start(c));
        let outcome = job.refused(&y).unwrap_or_else(|| {
            scalar_one(&mut ode, job, (&mut y, &mut tmp, &mut k), &mut run.steps)
        });
        run.outcomes.push(outcome);
        tick(progress, (c + 1) as u64, job.count() as u64)?;
    }
    Ok(run)
}

type Buffers<'a> = (&'a mut Vec<f64>, &'a mut Vec<f64>, &'a mut [Vec<f64>; 4]);

/// Integrates the trajectory from `y` (in place) to its outcome.
fn scalar_one(ode: &mut Rhs, job: &Job, (y, tmp, k): Buffers, steps: &mut u64) -> Outcome {
    let h = job.h;
    let fail = |e: SimError, t: f64| match e {
        SimError::Singular { .. } => Outcome::Singular { t },
        _ => Outcome::Diverged { t },
    };
    for s in 0..job.steps {
        let t = h * s as f64;
        let stages = [(0.0, 0.0), (0.5, 0.5), (0.5, 0.5), (1.0, 1.0)];
        for (j, &(c, a)) in stages.iter().enumerate() {
            for i in 0..y.len() {
                tmp[i] = if j == 0 {
                    y[i]
                } else {
                    y[i] + h * a * k[j - 1][i]
                };
            }
            if let Err(e) = ode.eval(t + c * h, tmp, &mut k[j]) {
                return fail(e, t);
            }
        }
        for i in 0..y.len() {
            tmp[i] = y[i] + h / 6.0 * (k[0][i] + 2.0 * k[1][i] + 2.0 * k[2][i] + k[3][i]);
        }
        *steps += 1;
        if !tmp.iter().all(|v| v.is_finite()) {
            return Outcome::Diverged { t: t + h };
        }
        if let Some((frac, coordinate)) = job.crossing(|i| (y[i], tmp[i])) {
            return Outcome::Flipped {
                t: t + frac * h,
                coordinate,
            };
        }
        y.copy_from_slice(tmp);
    }
    Outcome::Stayed
}

/// `K` trajectories in lockstep, structure-of-arrays: `y[i][l]` is component i of lane l.
struct Lanes<'a, const K: usize> {
    rhs: &'a Rhs,
    job: &'a Job<'a>,
    layout: Layout,
    y: Vec<[f64; K]>,
    tmp: Vec<[f64; K]>,
    k: [Vec<[f64; K]>; 4],
    points: Vec<[f64; K]>,
    scratch: Vec<[f64; K]>,
    m: Vec<[f64; K]>,
    f: Vec<[f64; K]>,
    /// One lane's M and f, gathered for the general solve.
    mm: Vec<f64>,
    ff: Vec<f64>,
    /// The start each lane is integrating, `None` when idle.
    cell: [Option<usize>; K],
    /// Steps taken by each lane's trajectory.
    step: [usize; K],
    next: usize,
    run: FlipRun,
}

impl<'a, const K: usize> Lanes<'a, K> {
    fn new(rhs: &'a Rhs, job: &'a Job<'a>) -> Self {
        let layout = rhs.layout();
        let n = layout.coordinates();
        let lanes = |len: usize| vec![[0.0; K]; len];
        let points = rhs.sample_point().iter().map(|&v| [v; K]).collect();
        Lanes {
            rhs,
            job,
            layout,
            y: lanes(job.dim),
            tmp: lanes(job.dim),
            k: [
                lanes(job.dim),
                lanes(job.dim),
                lanes(job.dim),
                lanes(job.dim),
            ],
            points,
            scratch: rhs.dynamics().scratch_lanes(),
            m: lanes(n * n),
            f: lanes(n),
            mm: vec![0.0; n * n],
            ff: vec![0.0; n],
            cell: [None; K],
            step: [0; K],
            next: 0,
            run: FlipRun {
                outcomes: vec![Outcome::Stayed; job.count()],
                steps: 0,
            },
        }
    }

    /// Steps every busy lane until the starts run out and every lane is idle.
    fn run(mut self, progress: &mut dyn Progress) -> Result<FlipRun, Interrupted> {
        for l in 0..K {
            self.refill(l);
        }
        let total = self.job.count() as u64;
        let mut since = 0;
        while self.cell.iter().any(Option::is_some) {
            self.step();
            since += 1;
            if since == REPORT_EVERY {
                since = 0;
                let busy = self.cell.iter().filter(|c| c.is_some()).count();
                tick(progress, (self.next - busy) as u64, total)?;
            }
        }
        tick(progress, total, total)?;
        Ok(self.run)
    }

    /// Gives lane `l` the next start that can begin (recording those that cannot), or
    /// leaves it idle.
    fn refill(&mut self, l: usize) {
        self.cell[l] = None;
        while self.next < self.job.count() {
            let c = self.next;
            self.next += 1;
            let y = self.job.start(c);
            if let Some(o) = self.job.refused(y) {
                self.run.outcomes[c] = o;
                continue;
            }
            for (i, &v) in y.iter().enumerate() {
                self.y[i][l] = v;
            }
            self.cell[l] = Some(c);
            self.step[l] = 0;
            return;
        }
    }

    /// Ends lane `l`'s trajectory with `outcome` and refills the lane.
    fn finish(&mut self, l: usize, outcome: Outcome) {
        if let Some(c) = self.cell[l] {
            self.run.outcomes[c] = outcome;
        }
        self.refill(l);
    }

    /// One RK4 step of every lane, then each lane's flip, failure or end is settled.
    fn step(&mut self) {
        let h = self.job.h;
        let mut singular = 0u64;
        let mut undefined = 0u64;
        for (j, &(c, a)) in [(0.0, 0.0), (0.5, 0.5), (0.5, 0.5), (1.0, 1.0)]
            .iter()
            .enumerate()
        {
            for i in 0..self.job.dim {
                let (y, tmp) = (&self.y[i], &mut self.tmp[i]);
                if j == 0 {
                    *tmp = *y;
                } else {
                    let slope = &self.k[j - 1][i];
                    for ((t, y), k) in tmp.iter_mut().zip(y).zip(slope) {
                        *t = y + h * a * k;
                    }
                }
            }
            let (u, s) = self.eval(c, j);
            undefined |= u;
            singular |= s;
        }
        for i in 0..self.job.dim {
            let [k0, k1, k2, k3] = &self.k;
            let (k0, k1, k2, k3) = (&k0[i], &k1[i], &k2[i], &k3[i]);
            let (y, tmp) = (&self.y[i], &mut self.tmp[i]);
            for l in 0..K {
                tmp[l] = y[l] + h / 6.0 * (k0[l] + 2.0 * k1[l] + 2.0 * k2[l] + k3[l]);
            }
        }
        for l in 0..K {
            if self.cell[l].is_some() {
                self.settle(l, undefined >> l & 1 == 1, singular >> l & 1 == 1);
            }
        }
    }

    /// After a step: lane `l` failed, flipped, reached t_end, or takes the new state.
    fn settle(&mut self, l: usize, undefined: bool, singular: bool) {
        let h = self.job.h;
        let t = h * self.step[l] as f64;
        if singular {
            return self.finish(l, Outcome::Singular { t });
        }
        let finite = (0..self.job.dim).all(|i| self.tmp[i][l].is_finite());
        if undefined || !finite {
            return self.finish(l, Outcome::Diverged { t });
        }
        self.step[l] += 1;
        self.run.steps += 1;
        let (y, tmp) = (&self.y, &self.tmp);
        if let Some((frac, coordinate)) = self.job.crossing(|i| (y[i][l], tmp[i][l])) {
            let t = t + frac * h;
            return self.finish(l, Outcome::Flipped { t, coordinate });
        }
        for i in 0..self.job.dim {
            self.y[i][l] = self.tmp[i][l];
        }
        if self.step[l] == self.job.steps {
            self.finish(l, Outcome::Stayed);
        }
    }

    /// k[j] = F(t + c·h, tmp) on every lane; returns the masks of the lanes where the
    /// equations are undefined and where M is singular.
    fn eval(&mut self, c: f64, j: usize) -> (u64, u64) {
        let (lay, n, h) = (self.layout, self.layout.coordinates(), self.job.h);
        for l in 0..K {
            self.points[lay.time()][l] = h * (self.step[l] as f64 + c);
        }
        for i in 0..n {
            self.points[lay.q(i)] = self.tmp[lay.phase_q(i)];
            self.points[lay.qdot(i)] = self.tmp[lay.phase_qdot(i)];
        }
        let dynamics = self.rhs.dynamics();
        let undefined = dynamics.mass_and_forcing_lanes(
            &self.points,
            &mut self.scratch,
            &mut self.m,
            &mut self.f,
        );
        let singular = if n == 2 {
            self.cramer(j)
        } else {
            self.eliminate(j)
        };
        for i in 0..n {
            self.k[j][lay.phase_q(i)] = self.tmp[lay.phase_qdot(i)];
        }
        (undefined, singular)
    }

    /// Two coordinates: Cramer's rule on every lane at once (the same test of singularity
    /// as the scalar solve); accelerations into k[j].
    fn cramer(&mut self, j: usize) -> u64 {
        let (m, f, lay) = (&self.m, &self.f, self.layout);
        let mut singular = 0u64;
        for l in 0..K {
            let (a, b, c, d) = (m[0][l], m[1][l], m[2][l], m[3][l]);
            let det = a * d - b * c;
            singular |= u64::from(is_singular_2x2(a, b, c, d)) << l;
            self.k[j][lay.phase_qdot(0)][l] = (f[0][l] * d - b * f[1][l]) / det;
            self.k[j][lay.phase_qdot(1)][l] = (a * f[1][l] - c * f[0][l]) / det;
        }
        singular
    }

    /// Any number of coordinates: each lane's M and f gathered and solved by elimination.
    fn eliminate(&mut self, j: usize) -> u64 {
        let lay = self.layout;
        let n = lay.coordinates();
        let mut singular = 0u64;
        for l in 0..K {
            for (to, from) in self.mm.iter_mut().zip(&self.m) {
                *to = from[l];
            }
            for (to, from) in self.ff.iter_mut().zip(&self.f) {
                *to = from[l];
            }
            singular |= u64::from(solve_in_place(n, &mut self.mm, &mut self.ff).is_none()) << l;
            for (i, &a) in self.ff.iter().enumerate() {
                self.k[j][lay.phase_qdot(i)][l] = a;
            }
        }
        singular
    }
}

#[cfg(test)]
mod tests;
