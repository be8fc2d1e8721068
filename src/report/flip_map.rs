//! [`FlipMap`]: the flip-time map every face draws — one trajectory per cell of a grid over one
//! or two initial values (the others shared), each run with the batch RK4 until a watched
//! angle goes over the top. Here: reading the grid (`name=start:end:count`), the checked plan
//! (cells, step and work within limits), the cells' outcomes chunk by chunk (a face may run
//! the chunks on several threads; the library runs none), the summary with its text, and the
//! CSV. The numerics are in [`crate::simulate::flip_times_with`].

use serde::Serialize;

use super::simulation::{initial_state, motion_parameters, state_names};
use crate::diagnostic::did_you_mean;
use crate::mechanics::System;
use crate::progress::Progress;
use crate::simulate::flip_times_with;
use crate::simulate::{DEFAULT_FLIP_DT, FlipRun, FlipSettings, Outcome, Rhs, SimError};

/// The most cells a grid may have.
pub const MAX_CELLS: usize = 1_000_000;
/// The most RK4 steps a whole map may take (cells × steps).
pub const MAX_WORK: f64 = 2e10;
/// Trajectories per lockstep batch (the fastest width measured by benches/flip.rs).
const LANES: usize = 16;
/// Cells per chunk (a multiple of the lanes; small enough to balance two cores).
pub const CHUNK: usize = 512;

/// Why a flip-time map cannot be planned; the text is what every face shows.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum FlipMapError {
    /// The grid text, with the column (1-based, in characters) where it goes wrong.
    #[error("--grid: {0}")]
    Grid(String),
    /// A grid axis that names no coordinate or velocity.
    #[error("--grid: `{name}` is not a coordinate or velocity of the system{hint}")]
    UnknownAxis { name: String, hint: String },
    /// An axis also given a fixed initial value.
    #[error("`{name}` is given by both --grid and --init")]
    AlsoInit { name: String },
    /// No coordinate is an angle, so nothing can flip.
    #[error("--until-flip watches angles, and none of the coordinates ({coordinates}) is an angle")]
    NoAngles { coordinates: String },
    /// More cells than [`MAX_CELLS`].
    #[error("--grid asks for {cells} cells, over the limit of {MAX_CELLS}")]
    TooManyCells { cells: usize },
    /// A non-positive or non-finite end time or step.
    #[error("--t-end {t_end} and --dt {dt} must be positive numbers")]
    Times { t_end: f64, dt: f64 },
    /// More steps than [`MAX_WORK`].
    #[error(
        "{cells} cells of {steps} steps each is {work:.2e} steps, over the limit of {MAX_WORK:.0e}: coarsen the grid, shorten --t-end or enlarge --dt"
    )]
    TooMuchWork { cells: usize, steps: f64, work: f64 },
    /// The initial values.
    #[error("{0}")]
    Init(String),
    /// The equations at the given parameters (a missing parameter names `--params`).
    #[error("{0}")]
    Equations(String),
}

/// One axis of the grid: `name=start:end:count`, ends included.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Axis {
    pub name: String,
    pub(crate) start: f64,
    pub(crate) end: f64,
    pub(crate) count: usize,
}

impl Axis {
    /// The values, evenly spaced from start to end inclusive.
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.start];
        }
        let step = (self.end - self.start) / (self.count - 1) as f64;
        (0..self.count)
            .map(|k| self.start + step * k as f64)
            .collect()
    }
}

/// Reads `name=start:end:count` items separated by commas (Greek names as in expressions);
/// errors name the column.
pub fn parse_grid(spec: &str) -> Result<Vec<Axis>, FlipMapError> {
    let grid = |m: String| FlipMapError::Grid(m);
    let mut axes = Vec::new();
    let mut column = 1;
    for item in spec.split(',') {
        let at = column + item.len() - item.trim_start().len();
        column += item.chars().count() + 1;
        let item = item.trim();
        if item.is_empty() {
            return Err(grid(format!(
                "column {at}: an empty item (write name=start:end:count)"
            )));
        }
        axes.push(parse_axis(item, at)?);
    }
    if axes.len() > 2 {
        return Err(grid(format!("{} axes; a map has one or two", axes.len())));
    }
    if axes.len() == 2 && axes[0].name == axes[1].name {
        return Err(grid(format!("`{}` is given twice", axes[0].name)));
    }
    Ok(axes)
}

fn parse_axis(item: &str, at: usize) -> Result<Axis, FlipMapError> {
    let grid = |m: String| Err(FlipMapError::Grid(m));
    let Some((name, range)) = item.split_once('=') else {
        return grid(format!(
            "column {at}: `{item}` has no `=` (write name=start:end:count)"
        ));
    };
    let name = crate::expr::spelled(name);
    let name = name.as_str();
    let at_range = at + item.find('=').unwrap_or(0) + 1;
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return grid(format!(
            "column {at_range}: `{}` should be start:end:count",
            range.trim()
        ));
    }
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let (Some(start), Some(end)) = (number(parts[0]), number(parts[1])) else {
        return grid(format!(
            "column {at_range}: the start and end of `{name}` must be finite numbers"
        ));
    };
    let count = parts[2].trim().parse::<usize>().ok().filter(|&c| c >= 1);
    let Some(count) = count else {
        return grid(format!(
            "column {at_range}: the count of `{name}` must be a whole number ≥ 1, not `{}`",
            parts[2].trim()
        ));
    };
    if count == 1 && start != end {
        return grid(format!("`{name}` has one point but two different ends"));
    }
    Ok(Axis {
        name: name.to_string(),
        start,
        end,
        count,
    })
}

/// What the map starts from, besides the grid.
#[derive(Clone, Debug)]
pub struct FlipMapOptions {
    /// Every parameter's value (those the motion does not use may be missing).
    pub params: Vec<(String, f64)>,
    /// Initial values by name; the rest start at 0.
    pub init: Vec<(String, f64)>,
    /// Whether `init` was typed by the user: a problem's suggested start gives way to the
    /// grid's axes; a typed one is an error when it names an axis.
    pub init_typed: bool,
    /// Each trajectory's end time.
    pub t_end: f64,
    /// The RK4 step ([`DEFAULT_FLIP_DT`] when `None`).
    pub dt: Option<f64>,
}

/// A checked plan: the equations, the grid, the shared start and the limits.
#[derive(Clone, Debug)]
pub struct FlipMap {
    rhs: Rhs,
    axes: Vec<Axis>,
    /// The axes' indices in y = (q, q') and their values.
    index: Vec<usize>,
    values: Vec<Vec<f64>>,
    /// y at every cell before the grid values are set.
    base: Vec<f64>,
    names: Vec<String>,
    settings: FlipSettings,
    cells: usize,
}

impl FlipMap {
    /// Checks the grid against the system and the limits, and compiles the equations.
    pub fn plan(
        sys: &mut System,
        opts: &FlipMapOptions,
        axes: Vec<Axis>,
    ) -> Result<FlipMap, FlipMapError> {
        let init: Vec<(String, f64)> = (opts.init.iter())
            .filter(|(n, _)| opts.init_typed || !axes.iter().any(|a| a.name == *n))
            .cloned()
            .collect();
        // A bank problem declares parameters for all its parts; those the motion does not
        // use take any value, as in a single run.
        let params = motion_parameters(sys, &opts.params);
        let rhs = Rhs::new(sys, &params).map_err(|e| match e {
            SimError::MissingParameters { .. } => {
                FlipMapError::Equations(format!("{e}: add them to --params"))
            }
            e => FlipMapError::Equations(e.to_string()),
        })?;
        let coords = rhs.names().to_vec();
        let names = state_names(&coords);
        let base = initial_state(&names, &init).map_err(|e| FlipMapError::Init(e.to_string()))?;
        let index = (axes.iter())
            .map(|a| {
                names.iter().position(|n| *n == a.name).ok_or_else(|| {
                    let hint = did_you_mean(&a.name, names.iter().map(String::as_str))
                        .map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
                    FlipMapError::UnknownAxis {
                        name: a.name.clone(),
                        hint,
                    }
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(a) = axes.iter().find(|a| init.iter().any(|(n, _)| *n == a.name)) {
            return Err(FlipMapError::AlsoInit {
                name: a.name.clone(),
            });
        }
        let watch: Vec<usize> = (0..coords.len())
            .filter(|&i| sys.coordinates[i].periodic)
            .collect();
        if watch.is_empty() {
            return Err(FlipMapError::NoAngles {
                coordinates: coords.join(", "),
            });
        }
        let (cells, dt) = limits(opts, &axes)?;
        let settings = FlipSettings {
            t_end: opts.t_end,
            dt,
            watch,
            lanes: LANES,
        };
        let values = axes.iter().map(Axis::values).collect();
        Ok(FlipMap {
            rhs,
            axes,
            index,
            values,
            base,
            names,
            settings,
            cells,
        })
    }

    /// The number of cells.
    pub fn cells(&self) -> usize {
        self.cells
    }

    /// The number of chunks of [`CHUNK`] cells (the last may be shorter).
    pub fn chunks(&self) -> usize {
        self.cells.div_ceil(CHUNK)
    }

    /// The grid's axes and their values.
    pub fn axes(&self) -> impl Iterator<Item = (&Axis, &[f64])> {
        self.axes.iter().zip(self.values.iter().map(Vec::as_slice))
    }

    /// Where axis `k` sits in y = (q, q') (below the number of coordinates: a coordinate).
    pub fn axis_index(&self, k: usize) -> usize {
        self.index[k]
    }

    /// The number of coordinates.
    pub fn coordinates(&self) -> usize {
        self.names.len() / 2
    }

    /// The run's settings (end time, step, watched angles).
    pub fn settings(&self) -> &FlipSettings {
        &self.settings
    }

    /// The start of cell `c` (row-major, the last axis fastest).
    fn start(&self, c: usize, y: &mut [f64]) {
        y.copy_from_slice(&self.base);
        let mut rest = c;
        for (k, values) in self.values.iter().enumerate().rev() {
            y[self.index[k]] = values[rest % values.len()];
            rest /= values.len();
        }
    }

    /// The outcomes of chunk `k`'s cells; `progress` hears cells done out of the chunk's.
    pub fn run_chunk(&self, k: usize, progress: &mut dyn Progress) -> FlipRun {
        let dim = self.base.len();
        let cells = k * CHUNK..((k + 1) * CHUNK).min(self.cells);
        let mut starts = vec![0.0; cells.len() * dim];
        for (c, y) in cells.clone().zip(starts.chunks_mut(dim)) {
            self.start(c, y);
        }
        // The settings were checked by the plan, so a refusal cannot happen; if it did, the
        // cells are marked as not followed rather than invented.
        flip_times_with(&self.rhs, &starts, &self.settings, progress).unwrap_or_else(|_| FlipRun {
            outcomes: vec![Outcome::Diverged { t: 0.0 }; cells.len()],
            steps: 0,
        })
    }

    /// The chunks' runs, in chunk order, as one run.
    pub fn join(&self, chunks: impl IntoIterator<Item = FlipRun>) -> FlipRun {
        let start = FlipRun {
            outcomes: Vec::with_capacity(self.cells),
            steps: 0,
        };
        chunks.into_iter().fold(start, |mut all, r| {
            all.outcomes.extend(r.outcomes);
            all.steps += r.steps;
            all
        })
    }

    /// The whole map, chunk after chunk (a face with threads runs [`run_chunk`](Self::run_chunk)
    /// itself).
    pub fn run(&self, progress: &mut dyn Progress) -> FlipRun {
        let runs: Vec<FlipRun> = (0..self.chunks())
            .map(|k| {
                let mut stage =
                    crate::progress::Stage::new(progress, k as u64, self.chunks() as u64);
                self.run_chunk(k, &mut stage)
            })
            .collect();
        self.join(runs)
    }

    /// What the map found.
    pub fn summary(&self, run: &FlipRun) -> FlipSummary {
        let count = |f: fn(&Outcome) -> bool| run.outcomes.iter().filter(|o| f(o)).count();
        let flipped = count(|o| o.flip_time().is_some());
        FlipSummary {
            axes: self.axes.clone(),
            others: (self.names.iter().zip(&self.base).enumerate())
                .filter(|(i, _)| !self.index.contains(i))
                .map(|(_, (n, v))| (n.clone(), *v))
                .collect(),
            cells: self.cells,
            t_end: self.settings.t_end,
            dt: self.settings.dt,
            watched: (self.settings.watch.iter())
                .map(|&i| self.names[i].clone())
                .collect(),
            flipped,
            starts_over: count(|o| matches!(o, Outcome::StartsOver { .. })),
            did_not_flip: count(|o| matches!(o, Outcome::Stayed)),
            singular: count(|o| matches!(o, Outcome::Singular { .. })),
            diverged: count(|o| matches!(o, Outcome::Diverged { .. })),
            flipped_fraction: flipped as f64 / self.cells.max(1) as f64,
            trajectory_steps: run.steps,
        }
    }

    /// One row per cell: the grid values, the flip time (empty when none) and what happened.
    pub fn csv(&self, run: &FlipRun) -> String {
        let mut o: String = self.axes.iter().map(|a| format!("{},", a.name)).collect();
        o += "flip_time,outcome\n";
        let mut y = vec![0.0; self.base.len()];
        for (c, outcome) in run.outcomes.iter().enumerate() {
            self.start(c, &mut y);
            for &i in &self.index {
                o += &format!("{},", y[i]);
            }
            let time = outcome.flip_time().map_or(String::new(), |t| t.to_string());
            let kind = match outcome {
                Outcome::Flipped { .. } => "flipped",
                Outcome::StartsOver { .. } => "starts_over",
                Outcome::Stayed => "did_not_flip",
                Outcome::Singular { .. } => "singular",
                Outcome::Diverged { .. } => "diverged",
            };
            o += &format!("{time},{kind}\n");
        }
        o
    }
}

/// The number of cells and the step, within the limits of work.
fn limits(opts: &FlipMapOptions, axes: &[Axis]) -> Result<(usize, f64), FlipMapError> {
    let cells = (axes.iter())
        .try_fold(1usize, |acc, a| acc.checked_mul(a.count))
        .unwrap_or(usize::MAX);
    if cells > MAX_CELLS {
        return Err(FlipMapError::TooManyCells { cells });
    }
    let (t_end, dt) = (opts.t_end, opts.dt.unwrap_or(DEFAULT_FLIP_DT));
    if !(t_end.is_finite() && t_end > 0.0 && dt > 0.0 && dt.is_finite()) {
        return Err(FlipMapError::Times { t_end, dt });
    }
    let steps = (t_end / dt).ceil();
    let work = cells as f64 * steps;
    if work > MAX_WORK {
        return Err(FlipMapError::TooMuchWork { cells, steps, work });
    }
    Ok((cells, dt))
}

/// What the map found, as printed and as JSON (no wall time: that is the face's).
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct FlipSummary {
    pub(crate) axes: Vec<Axis>,
    /// The values every cell shares (the coordinates and velocities not on an axis).
    pub(crate) others: Vec<(String, f64)>,
    pub(crate) cells: usize,
    pub(crate) t_end: f64,
    pub(crate) dt: f64,
    pub(crate) watched: Vec<String>,
    pub(crate) flipped: usize,
    pub(crate) starts_over: usize,
    pub(crate) did_not_flip: usize,
    pub(crate) singular: usize,
    pub(crate) diverged: usize,
    pub(crate) flipped_fraction: f64,
    pub trajectory_steps: u64,
}

impl FlipSummary {
    /// The summary as text, one fact per line.
    pub fn render(&self) -> String {
        let s = self;
        let axes: Vec<String> = (s.axes.iter())
            .map(|a| format!("{} = {} … {} ({})", a.name, a.start, a.end, a.count))
            .collect();
        let mut o = format!(
            "Flip-time map: {}; {} cells, RK4 at dt = {} to t = {}\n",
            axes.join(" × "),
            s.cells,
            s.dt,
            s.t_end
        );
        let others: Vec<String> = (s.others.iter())
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        o += &format!("Every cell starts with: {}\n", others.join(", "));
        o += &format!(
            "Watched angles: {} (a flip: the continuous angle leaves (−π, π))\n",
            s.watched.join(", ")
        );
        o += &format!(
            "Flipped: {} of {} ({:.1} %)",
            s.flipped,
            s.cells,
            100.0 * s.flipped_fraction
        );
        if s.starts_over > 0 {
            o += &format!(
                ", of which {} start over the top already (flip time 0)",
                s.starts_over
            );
        }
        o += &format!("\nDid not flip by t = {}: {}\n", s.t_end, s.did_not_flip);
        if s.singular + s.diverged > 0 {
            o += &format!(
                "Not followed to the end: {} (mass matrix singular: {}, diverged: {})\n",
                s.singular + s.diverged,
                s.singular,
                s.diverged
            );
        }
        o += &format!("Trajectory-steps: {}\n", s.trajectory_steps);
        o
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grids_read_and_refuse_with_columns() {
        let axes = parse_grid("theta1=-3:3:7, θ₂=0:1:2").unwrap();
        assert_eq!(axes.len(), 2);
        assert_eq!(axes[1].name, "theta2");
        assert_eq!(axes[0].values(), vec![-3.0, -2.0, -1.0, 0.0, 1.0, 2.0, 3.0]);
        for (spec, want) in [
            ("", "column 1: an empty item"),
            ("x", "column 1: `x` has no `=`"),
            ("x=1:2", "column 3: `1:2` should be start:end:count"),
            (
                "x=0:1:0",
                "the count of `x` must be a whole number ≥ 1, not `0`",
            ),
            ("x=0:1:1", "`x` has one point but two different ends"),
            ("x=0:1:2, x=0:1:2", "`x` is given twice"),
            ("a=0:1:2, b=0:1:2, c=0:1:2", "3 axes"),
        ] {
            let e = parse_grid(spec).unwrap_err().to_string();
            assert!(e.contains(want), "{spec}: {e}");
        }
    }

    #[test]
    fn a_pendulum_released_near_the_top_flips_and_one_near_the_bottom_does_not() {
        let mut sys =
            System::from_lagrangian("theta'^2/2 + cos(theta)", &["theta"]).expect("system");
        sys.coordinates[0].periodic = true;
        let opts = FlipMapOptions {
            params: vec![],
            init: vec![("theta'".into(), 0.0)],
            init_typed: false,
            t_end: 20.0,
            dt: None,
        };
        // E = θ̇²/2 − cos θ: starting at rest never flips; θ̇₀ = 2.5 > 2 goes over the top.
        let axes = parse_grid("theta'=0:2.5:2").unwrap();
        let map = FlipMap::plan(&mut sys, &opts, axes).expect("plan");
        let run = map.run(&mut crate::progress::Silent);
        let s = map.summary(&run);
        assert_eq!((s.cells, s.flipped, s.did_not_flip), (2, 1, 1));
        assert!(
            map.csv(&run)
                .starts_with("theta',flip_time,outcome\n0,,did_not_flip\n")
        );
        let e = FlipMap::plan(&mut sys, &opts, parse_grid("phi=0:1:2").unwrap());
        assert!(matches!(e, Err(FlipMapError::UnknownAxis { .. })), "{e:?}");
    }
}
