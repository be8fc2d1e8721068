//! Equilibria for given parameter values: every solution of f(q, q' = 0, t) = 0 inside the
//! coordinate ranges (periodic coordinates modulo 2π), by multi-start Newton with
//! deduplication; stability from the stiffness matrix K = −∂f/∂q. Also the check of a
//! symbolic candidate (x₀ = m g sin α / k) by substitution at random parameter values.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::generalized_eigen;
use super::magnitude::{Magnitudes, Sized};
use super::state::Layout;
use super::system::System;
use crate::expr::{Id, Program};

mod blocks;
mod families;
mod newton;

pub use blocks::Coverage;
pub use families::Shape;

pub(crate) use newton::wrap_angle;
use newton::{force_scale, is_continuum, range_widths, start_points};

/// An eigenvalue ω² (or a growth rate, or a frequency) counts as zero below this fraction of
/// the largest one: linear analysis cannot tell the sign of what rounding leaves.
pub(crate) const EIGENVALUE_ZERO: f64 = 1e-9;

/// A point given by hand is an equilibrium when each force is within this fraction of the
/// size of its terms (looser than the search's acceptance: values such as l₀ + m g/k are
/// evaluated with rounding).
const AT_ACCEPT: f64 = 1e-8;

/// Stability of an equilibrium.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    /// Every ω² > 0.
    Stable,
    /// Some ω² < 0.
    Unstable,
    /// No ω² < 0 but some ω² = 0 (linear analysis cannot decide).
    Marginal,
}

impl Stability {
    /// "stable", "unstable" or "marginal".
    pub fn name(self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::Marginal => "marginal",
        }
    }
}

/// The equilibria found.
#[derive(Clone, Debug)]
pub struct Equilibria {
    /// Isolated equilibria with their stability, sorted.
    pub points: Vec<(Vec<f64>, Stability)>,
    /// What each point is beyond a point (aligned with `points`): one of a continuum along
    /// its free directions, or degenerate (not harmonic).
    pub(crate) shapes: Vec<Shape>,
    /// What the search covered (blocks searched on their own, starts in each).
    pub(crate) coverage: Coverage,
    /// f vanishes on a whole region: equilibria are not isolated (e.g. the bead on the
    /// parabola at ω² = 2ga).
    pub continuum: bool,
}

/// Programs for the static problem: G(q) = f(q, 0, t = 0), J = ∂G/∂q, and M(q, 0); and G
/// and J with the sizes of their terms, which every zero test here is relative to.
pub struct Statics {
    program: Program,
    sizes: Magnitudes,
    layout: Layout,
    base: Vec<f64>,
    /// The entries of J = ∂G/∂q, row-major: which coordinates' forces depend on which.
    jacobian: Vec<Id>,
}

impl Statics {
    /// Compiles G, J and M with the parameter values `params` (in the system's order).
    /// Refused with [`MechError::ExplicitTime`] when the equations depend on t explicitly:
    /// the system frozen at t = 0 has no bearing on the driven motion.
    pub fn new(sys: &mut System, d: &Derivation, params: &[f64]) -> Result<Statics, MechError> {
        explicit_time(sys, d)?;
        let coords = sys.coordinate_syms();
        let zero = sys.pool.zero();
        let at_rest: FxHashMap<_, _> = coords
            .iter()
            .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
            .collect();
        let g: Vec<Id> = d
            .forcing
            .iter()
            .map(|&f| sys.pool.substitute(f, &at_rest))
            .collect();
        let mut roots = g.clone();
        for &gi in &g {
            for &c in &coords {
                roots.push(sys.pool.diff(gi, c, 0));
            }
        }
        for row in &d.mass {
            for &m in row {
                roots.push(sys.pool.substitute(m, &at_rest));
            }
        }
        let program = sys.compile(&roots)?;
        let sizes = sys.magnitudes(&roots)?;
        if params.len() != sys.parameters.len() {
            return Err(MechError::ParameterCount {
                expected: sys.parameters.len(),
                given: params.len(),
            });
        }
        let layout = sys.state_layout();
        let base = layout.at_rest(&[], params);
        let n = coords.len();
        Ok(Statics {
            program,
            sizes,
            layout,
            base,
            jacobian: roots[n..n + n * n].to_vec(),
        })
    }

    /// The sample point at rest at `q`.
    fn point(&self, q: &[f64]) -> Vec<f64> {
        let mut x = self.base.clone();
        for (i, &v) in q.iter().enumerate() {
            x[self.layout.q(i)] = v;
        }
        x
    }

    /// G, J and M at `q` with the sizes of their terms (G first, then J and M row-major).
    fn sizes(&self, q: &[f64]) -> Option<Vec<Sized>> {
        self.sizes.eval(&self.point(q))
    }

    /// The size of the generalized forces at `q`: the largest term magnitude among the Gᵢ.
    /// (The largest among the forces of the coordinates `active`.)
    fn force_size(&self, q: &[f64], active: &[usize]) -> Option<f64> {
        let s = self.sizes(q)?;
        Some(active.iter().fold(0.0, |a, &i| a.max(s[i].magnitude)))
    }

    fn eval(
        &self,
        q: &[f64],
        scratch: &mut [f64],
    ) -> Option<(DVector<f64>, DMatrix<f64>, DMatrix<f64>)> {
        let x = self.point(q);
        self.program.run(&x, scratch).ok()?;
        let n = self.layout.coordinates();
        let g = DVector::from_fn(n, |i, _| self.program.output(i, scratch));
        let j = DMatrix::from_fn(n, n, |r, c| self.program.output(n + r * n + c, scratch));
        let m = DMatrix::from_fn(n, n, |r, c| {
            self.program.output(n + n * n + r * n + c, scratch)
        });
        Some((g, j, m))
    }

    /// Stability and the generalized eigenvalues ω² (ascending) at `q`.
    pub fn stability(&self, q: &[f64]) -> Result<(Stability, Vec<f64>, DMatrix<f64>), MechError> {
        let mut scratch = self.program.scratch();
        let (_, j, m) = self.eval(q, &mut scratch).ok_or(MechError::Undefined {
            what: "the equations at the equilibrium".into(),
        })?;
        let k = -&j;
        let k = (&k + k.transpose()) * 0.5;
        let (vals, vecs) = generalized_eigen(&k, &m)?;
        // Each ω² is zero relative to the size of the terms of K along its own mode (per
        // unit mass): a stiffness that is rounding left over from cancelling terms is zero
        // however the eigenvalues compare with each other, and a weak but real one
        // (k = 1e-12, even beside a stiff k = 1) is not.
        let sizes = self.sizes(q);
        let n = vals.len();
        let tol: Vec<f64> = (0..n)
            .map(|k| {
                let u = vecs.column(k);
                let mass = (u.transpose() * &m * u)[(0, 0)].abs();
                let terms: f64 = sizes.as_ref().map_or(0.0, |s| {
                    (0..n)
                        .flat_map(|i| (0..n).map(move |j| (i, j)))
                        .map(|(i, j)| s[n + i * n + j].magnitude * (u[i] * u[j]).abs())
                        .sum()
                });
                let scale = (terms / mass).max(vals[k].abs());
                EIGENVALUE_ZERO * if scale.is_finite() { scale } else { 0.0 }
            })
            .collect();
        let st = if (0..n).any(|k| vals[k] < -tol[k]) {
            Stability::Unstable
        } else if (0..n).any(|k| vals[k].abs() <= tol[k]) {
            Stability::Marginal
        } else {
            Stability::Stable
        };
        Ok((st, vals.iter().copied().collect(), vecs))
    }
}

impl System {
    /// All equilibria inside the coordinate ranges for parameter values `params`.
    pub fn equilibria(&mut self, d: &Derivation, params: &[f64]) -> Result<Equilibria, MechError> {
        let statics = Statics::new(self, d, params)?;
        let ranges = search_ranges(&self.coordinates);
        let periodic: Vec<bool> = self.coordinates.iter().map(|c| c.periodic).collect();
        let starts = start_points(&ranges);
        if let Some(q) = starts.first()
            && starts.iter().all(|q| statics.sizes(q).is_none())
        {
            // Undefined at every start: name what fails rather than find nothing.
            let what = "the equations at rest";
            return Err(self.undefined_at(&statics.sizes, &statics.point(q), what));
        }
        if is_continuum(&statics, &starts) {
            return Ok(Equilibria {
                points: Vec::new(),
                shapes: Vec::new(),
                coverage: Coverage::default(),
                continuum: true,
            });
        }
        let widths = range_widths(&ranges, &periodic);
        let blocks = self.decoupled_blocks(&statics);
        let rest: Vec<f64> = starts[0].clone();
        let search = blocks::Search {
            statics: &statics,
            ranges: &ranges,
            periodic: &periodic,
            widths: &widths,
        };
        let mut roots = Vec::with_capacity(blocks.len());
        let mut coverage = Coverage::default();
        let mut force = f64::MAX;
        for block in &blocks {
            let (r, count, f) = search.block_roots(block, &rest);
            roots.push(r);
            coverage.starts.push(count);
            if f > 0.0 {
                force = force.min(f);
            }
        }
        coverage.blocks = blocks.clone();
        if force == f64::MAX {
            force = 0.0;
        }
        let found = blocks::product(&blocks, &roots, &rest)?;
        let mut grouped = families::group(&statics, found, &periodic, &widths, force);
        crate::sort::sort_by(&mut grouped, |(a, _), (b, _)| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let mut points = Vec::with_capacity(grouped.len());
        let mut shapes = Vec::with_capacity(grouped.len());
        for (q, shape) in grouped {
            if !shape.singular_chart.is_empty() {
                // The chart fails here, so its linearization says nothing: undecided.
                points.push((q, Stability::Marginal));
                shapes.push(shape);
                continue;
            }
            let (st, _, _) = statics.stability(&q)?;
            points.push((q, across_family(st, &shape)));
            shapes.push(shape);
        }
        Ok(Equilibria {
            points,
            shapes,
            continuum: false,
            coverage,
        })
    }

    /// The shape of the equilibrium at `q` (parameter values `params`): whether it is one
    /// of a continuum (and along which directions), or degenerate.
    pub fn equilibrium_shape(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q: &[f64],
    ) -> Result<Shape, MechError> {
        // With constraints the unconstrained K says nothing about the shape (the Cartesian
        // pendulum's K is singular along the rod, which the constraint holds): the
        // linearization on the constraint manifold is the analysis there.
        if !self.constraints.is_empty() {
            return Ok(Shape::default());
        }
        let statics = Statics::new(self, d, params)?;
        let ranges = search_ranges(&self.coordinates);
        let periodic: Vec<bool> = self.coordinates.iter().map(|c| c.periodic).collect();
        let widths = range_widths(&ranges, &periodic);
        let all: Vec<usize> = (0..q.len()).collect();
        let block = newton::Block {
            statics: &statics,
            active: &all,
        };
        let force = force_scale(block, &start_points(&ranges));
        Ok(families::shape_at(&statics, q, &widths, force))
    }

    /// [`MechError::NotAnEquilibrium`] unless every generalized force vanishes at rest at
    /// `q` (parameter values `params`), each relative to the size of its own terms there: a
    /// point given by hand is analysed only when it is an equilibrium.
    pub fn check_equilibrium(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q: &[f64],
    ) -> Result<(), MechError> {
        // With constraints the forces need not vanish (the constraint balances them): the
        // linearization on the constraint manifold checks the point instead (`OffConstraint`,
        // `NotConstrainedEquilibrium`).
        if !self.constraints.is_empty() {
            return Ok(());
        }
        let statics = Statics::new(self, d, params)?;
        let mut scratch = statics.program.scratch();
        let undefined = || MechError::Undefined {
            what: "the equations at the point given".into(),
        };
        let (g, _, _) = statics.eval(q, &mut scratch).ok_or_else(undefined)?;
        let sizes = statics.sizes(q).ok_or_else(undefined)?;
        let off: Vec<usize> = (0..g.len())
            // A NaN force is off too.
            .filter(|&i| g[i].is_nan() || g[i].abs() > AT_ACCEPT * sizes[i].magnitude)
            .collect();
        if off.is_empty() {
            return Ok(());
        }
        let names: Vec<&str> = self.coordinates.iter().map(|c| c.name.as_str()).collect();
        let point = names
            .iter()
            .zip(q)
            .map(|(n, v)| format!("{n} = {}", short(*v)))
            .collect::<Vec<_>>()
            .join(", ");
        // At rest the force on qᵢ is −∂V/∂qᵢ (plus any generalized force given).
        let forces = off
            .iter()
            .map(|&i| format!("∂V/∂{} = {}", names[i], short(-g[i])))
            .collect::<Vec<_>>()
            .join(", ");
        Err(MechError::NotAnEquilibrium { point, forces })
    }

    /// Whether the candidate equilibrium `point` satisfies f(q₀, 0) = 0 at each of
    /// `samples` (state vectors in the system's layout, drawn by the caller so that they
    /// respect the problem's assumptions: the elastic pendulum's r₀ = l₀ + m g/k is an
    /// equilibrium where |r₀| = r₀), each force zero relative to its terms. `false` when
    /// no sample is defined.
    pub fn verify_equilibrium_at(
        &mut self,
        d: &Derivation,
        point: &[Id],
        samples: &[Vec<f64>],
    ) -> Result<bool, MechError> {
        let g = self.forces_at_rest(d, point);
        let sizes = self.magnitudes(&g)?;
        let mut defined = 0;
        for x in samples {
            let Some(v) = sizes.eval(x) else { continue };
            if v.iter().any(|s| !s.value.is_finite()) {
                continue;
            }
            defined += 1;
            if !v.iter().all(|s| s.negligible()) {
                return Ok(false);
            }
        }
        Ok(defined > 0)
    }

    /// The forces at rest at `point` (one expression per coordinate).
    fn forces_at_rest(&mut self, d: &Derivation, point: &[Id]) -> Vec<Id> {
        let coords = self.coordinate_syms();
        let zero = self.pool.zero();
        let mut map: FxHashMap<_, _> = FxHashMap::default();
        for (&c, &v) in coords.iter().zip(point) {
            map.insert((c, 0), v);
            map.insert((c, 1), zero);
            map.insert((c, 2), zero);
        }
        d.forcing
            .iter()
            .map(|&f| self.pool.substitute(f, &map))
            .collect()
    }

    /// Whether the candidate equilibrium `point` (one expression per coordinate, in the
    /// parameters) satisfies f(q₀, 0) = 0 at 20 random parameter samples.
    pub fn verify_equilibrium(&mut self, d: &Derivation, point: &[Id]) -> Result<bool, MechError> {
        let g = self.forces_at_rest(d, point);
        Ok(g.iter().all(|&gi| self.is_zero(gi)))
    }
}

/// The stability of an equilibrium that is one of a continuum, judged across it: when
/// every zero ω² is a free direction (not degenerate), moving along the continuum is
/// neutral and the other directions decide (the cart-pendulum's θ = 0 with x arbitrary is
/// stable). A degenerate point stays marginal: linear analysis cannot decide it.
pub fn across_family(st: Stability, shape: &Shape) -> Stability {
    if st == Stability::Marginal && !shape.free.is_empty() && !shape.degenerate {
        Stability::Stable
    } else {
        st
    }
}

impl System {
    /// [`MechError::ExplicitTime`] when the equations of motion depend on t explicitly:
    /// equilibria and small oscillations (numeric or in closed form) are then refused.
    pub fn refuse_explicit_time(&mut self, d: &Derivation) -> Result<(), MechError> {
        explicit_time(self, d)
    }
}

/// [`MechError::ExplicitTime`] when some equation of motion (or the mass matrix) changes
/// with t at fixed q, q': the terms named are the coordinates' equations that do.
fn explicit_time(sys: &mut System, d: &Derivation) -> Result<(), MechError> {
    let time = sys.pool.time();
    let mut driven = Vec::new();
    for (i, &f) in d.forcing.iter().enumerate() {
        let row = d.mass.get(i).map(Vec::as_slice).unwrap_or(&[]);
        let depends = std::iter::once(f).chain(row.iter().copied()).any(|e| {
            // t written but cancelling (sin(t)² + cos(t)²) is no dependence; a derivative
            // too large to form counts as one (refusing is the safe side).
            sys.pool.variables(e).contains(&(time, 0)) && {
                let dt = sys.pool.diff(e, time, 0);
                !sys.is_zero(dt)
            }
        });
        if depends {
            driven.push(format!("the equation of {}", sys.coordinates[i].name));
        }
    }
    if driven.is_empty() {
        return Ok(());
    }
    Err(MechError::ExplicitTime {
        terms: driven.join(", "),
    })
}

/// A value with six significant digits, trailing zeros dropped.
fn short(v: f64) -> String {
    let t = format!("{v:.6e}");
    match t.split_once('e') {
        Some((_, e)) if (-4..6).contains(&e.parse::<i32>().unwrap_or(99)) => {
            let digits = 5 - e.parse::<i32>().unwrap_or(0);
            let t = format!("{v:.*}", digits.max(0) as usize);
            if t.contains('.') {
                t.trim_end_matches('0').trim_end_matches('.').to_string()
            } else {
                t
            }
        }
        Some((m, e)) => {
            let m = if m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            format!("{m}e{e}")
        }
        None => t,
    }
}

/// Where equilibria are searched: a periodic coordinate over its whole period (−π, π], whatever
/// its sampling range (an equilibrium is a point of the configuration space, and an angle's
/// range only says where states are drawn); any other coordinate over its range.
fn search_ranges(coordinates: &[crate::mechanics::Coordinate]) -> Vec<(f64, f64)> {
    coordinates
        .iter()
        .map(|c| {
            if c.periodic {
                (-std::f64::consts::PI, std::f64::consts::PI)
            } else {
                c.range
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_shown_with_six_significant_digits() {
        assert_eq!(short(0.8414709848078965), "0.841471");
        assert_eq!(short(-16.49278), "-16.4928");
        assert_eq!(short(2.0), "2");
        assert_eq!(short(1.5e-9), "1.5e-9");
        assert_eq!(short(f64::NAN), "NaN");
    }

    #[test]
    fn time_that_cancels_is_no_explicit_dependence() {
        // sin²(t) + cos²(t) = 1: the oscillator is not driven.
        let l = "1/2*x'^2 - 1/2*(sin(t)^2 + cos(t)^2)*x^2";
        let mut sys = System::from_lagrangian(l, &["x"]).unwrap();
        let d = sys.derive().unwrap();
        assert!(sys.refuse_explicit_time(&d).is_ok());
        let driven = "1/2*x'^2 - 1/2*x^2 + x*cos(t)";
        let mut sys = System::from_lagrangian(driven, &["x"]).unwrap();
        let d = sys.derive().unwrap();
        assert_eq!(
            sys.refuse_explicit_time(&d).unwrap_err().code(),
            "explicit-time"
        );
    }

    #[test]
    fn a_point_that_is_not_an_equilibrium_names_its_force() {
        let mut sys = System::from_lagrangian("1/2*x'^2 - 1/2*x^2", &["x"]).unwrap();
        let d = sys.derive().unwrap();
        assert!(sys.check_equilibrium(&d, &[], &[0.0]).is_ok());
        let e = sys.check_equilibrium(&d, &[], &[2.0]).unwrap_err();
        assert_eq!(e.to_string(), "x = 2 is not an equilibrium: ∂V/∂x = 2");
    }
}
