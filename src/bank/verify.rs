//! Verification: every stated answer of a problem is proved against the physics before a
//! student sees it — dimensions, the Lagrangian from bodies against the stated one, equations
//! of motion through their accelerations, equilibria (none missing, none spurious, stated
//! stability), frequencies from the eigen-solver, and the energy function, momenta, T, V and
//! constraint forces; and every `wrong` example must indeed be wrong.

use super::finding::Finding;
use crate::check::CheckError;
use crate::check::compare::{Relation, close, fmt_value, parameter_text, relate, values};
use crate::check::equations::equations_hold;
use crate::check::points::PointSet;
use crate::check::prepare::{
    Prepared, equilibrium_of, prepare, read_frequency, read_one, read_point, residuals,
    same_coordinate,
};
use crate::check::tolerance;
use crate::expr::{Dimension, Id, Style, read_expr};
use crate::mechanics::accel::Dynamics;
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, PartKind, Problem, Quantity};

use crate::check::prepare::POINTS;
/// Parameter samples for equilibria (each runs a multi-start search).
const EQUILIBRIUM_SAMPLES: usize = 6;
/// Parameter samples for frequencies.
const FREQUENCY_SAMPLES: usize = 20;

/// Verifies a problem; an empty list means every stated answer holds.
pub fn verify(problem: &Problem) -> Vec<Finding> {
    let mut out = Vec::new();
    let whole = |line: usize, code: &'static str, message: String| Finding {
        file: problem.file.clone(),
        problem: Some(problem.id.clone()),
        part: None,
        line,
        code,
        message,
    };
    let sys = &problem.system;
    let energy = Dimension::energy();
    for (what, e) in [
        ("L", Some(sys.lagrangian)),
        ("T", sys.kinetic),
        ("V", sys.potential),
    ] {
        let Some(e) = e else { continue };
        match sys.pool.dimension(e, &problem.dims) {
            Ok(Some(d)) if d != energy && !sys.pool.is_zero(e) => out.push(whole(
                problem.lagrangian_line,
                "dimension",
                format!(
                    "{what} = {} has dimension {d}, not an energy (M L² T⁻²)",
                    sys.pool.unicode(e)
                ),
            )),
            Err(err) => out.push(whole(
                problem.lagrangian_line,
                "dimension",
                format!("{what}: {err}"),
            )),
            _ => {}
        }
    }
    if let Some(stated) = problem.stated_lagrangian
        && stated != sys.lagrangian
    {
        let mut s = sys.clone();
        match PointSet::draw(
            &s,
            &problem.assumptions,
            seed_from(&[&problem.id, "lagrangian"]),
            POINTS,
        )
        .and_then(|pts| relate(&s, stated, s.lagrangian, &pts, tolerance::SAME))
        {
            Ok(Relation::Equal | Relation::UpToConstant(_)) => {}
            Ok(_) => {
                let derived = s.simplify(s.lagrangian);
                out.push(whole(
                    problem.lagrangian_line,
                    "lagrangian-mismatch",
                    format!(
                        "the stated L = {} is not the L of the bodies, {}",
                        s.pool.unicode(stated),
                        s.pool.unicode(derived)
                    ),
                ));
            }
            Err(e) => out.push(whole(problem.lagrangian_line, "sampling", e.to_string())),
        }
    }
    for part in &problem.parts {
        if let Err(f) = verify_part(problem, part) {
            out.push(f);
        }
    }
    out
}

fn verify_part(problem: &Problem, part: &Part) -> Result<(), Finding> {
    let fail = |code: &'static str, message: String| Finding {
        file: problem.file.clone(),
        problem: Some(problem.id.clone()),
        part: Some(part.id.clone()),
        line: part.line,
        code,
        message,
    };
    // A part the engine derives nothing for would be "proved" without any check.
    if part.quantity == Quantity::None
        && matches!(
            part.kind,
            PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce
        )
    {
        return Err(fail(
            "unprovable",
            format!(
                "verification cannot prove this {} part: say what it is with `quantity` (kinetic, potential, lagrangian, momentum, energy-function, multiplier, acceleration)",
                part.kind.name()
            ),
        ));
    }
    let mut p = prepare(problem, part).map_err(|e| fail("unusable", e.to_string()))?;
    let physics = match part.kind {
        PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce => {
            verify_expression(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Equation | PartKind::Equations => {
            verify_equations(part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Equilibria => {
            verify_equilibria(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Frequencies => {
            verify_frequencies(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Values => Ok(()),
    };
    physics?;
    // The checker must accept the reference as written and reject every `wrong` example.
    let reference = part.reference_text(p.system.n());
    let v = crate::check::answer::check_prepared(problem, part, &mut p, &reference);
    if v.status != crate::check::Status::Correct {
        let why: Vec<String> = v.diagnoses.iter().map(|d| d.message.clone()).collect();
        return Err(fail(
            "reference-rejected",
            format!(
                "the checker does not accept the reference answer `{reference}`: {}",
                why.join("; ")
            ),
        ));
    }
    for w in &part.wrong {
        let v = crate::check::answer::check_prepared(problem, part, &mut p, w);
        // A `wrong` example that cannot be checked proves nothing: it is a typo in the file.
        if v.status == crate::check::Status::Invalid {
            let why: Vec<String> = v.diagnoses.iter().map(|d| d.message.clone()).collect();
            return Err(fail(
                "unreadable-wrong",
                format!(
                    "the `wrong` example `{w}` cannot be checked: {}",
                    why.join("; ")
                ),
            ));
        }
        if v.status == crate::check::Status::Correct {
            return Err(fail(
                "wrong-accepted",
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

/// A failed verification: the finding's code and message.
struct Failed {
    code: &'static str,
    message: String,
}

impl Failed {
    fn new(code: &'static str, message: String) -> Self {
        Failed { code, message }
    }
}

/// A checker error met while verifying keeps its own code (`unreadable`, `bad-at`, …).
impl From<CheckError> for Failed {
    fn from(e: CheckError) -> Self {
        Failed::new(e.code(), e.to_string())
    }
}

type Check = Result<(), Failed>;

/// The dimension an answer of this quantity must have.
fn expected_dimension(problem: &Problem, part: &Part) -> Option<Dimension> {
    if part.dimension.is_some() {
        return part.dimension;
    }
    let coord_dim = |i: usize| problem.dims.get(&problem.system.coordinates[i].name);
    let t = Dimension::new(0, 0, 1);
    match part.quantity {
        Quantity::Kinetic
        | Quantity::Potential
        | Quantity::Lagrangian
        | Quantity::EnergyFunction => Some(Dimension::energy()),
        Quantity::Momentum(i) => coord_dim(i).map(|d| Dimension::energy() * t / d),
        Quantity::Acceleration(i) => coord_dim(i).map(|d| d / (t * t)),
        _ => None,
    }
}

fn check_dimension(problem: &Problem, p: &Prepared, e: Id, want: Option<Dimension>) -> Check {
    match p.system.pool.dimension(e, &problem.dims) {
        Err(err) => Err(Failed::new(
            "dimension",
            format!("{}: {err}", p.system.pool.unicode(e)),
        )),
        Ok(Some(d)) if want.is_some_and(|w| w != d) && !p.system.pool.is_zero(e) => {
            Err(Failed::new(
                "dimension",
                format!(
                    "{} has dimension {d}, but this part asks for {}",
                    p.system.pool.unicode(e),
                    want.unwrap_or(Dimension::NONE)
                ),
            ))
        }
        _ => Ok(()),
    }
}

/// The truth of an expression part: a symbolic expression, or numbers per point.
enum Truth {
    Expr(Id),
    Numbers(Vec<Option<f64>>),
}

fn truth(part: &Part, p: &mut Prepared) -> Result<Option<Truth>, Failed> {
    let sys = &mut p.system;
    let d = &p.derivation;
    Ok(Some(match part.quantity {
        Quantity::Kinetic => Truth::Expr(sys.kinetic.ok_or(Failed::new(
            "no-truth",
            "a kinetic part needs bodies (or T and V) to check against".to_string(),
        ))?),
        Quantity::Potential => Truth::Expr(sys.potential.ok_or(Failed::new(
            "no-truth",
            "a potential part needs bodies (or T and V) to check against".to_string(),
        ))?),
        Quantity::Lagrangian => Truth::Expr(sys.lagrangian),
        Quantity::Momentum(i) => Truth::Expr(d.steps[i].momentum),
        Quantity::EnergyFunction => Truth::Expr(sys.energy(d).function),
        Quantity::Multiplier(j) | Quantity::Acceleration(j) => {
            let rows = sys.constraint_rows();
            let dynamics =
                Dynamics::new(sys, d).map_err(|e| Failed::new("unusable", e.to_string()))?;
            let mut scratch = dynamics.scratch();
            let nums = p
                .points
                .points
                .iter()
                .map(|x| {
                    if sys.constraints.is_empty() {
                        dynamics.accelerations(x, &mut scratch).ok().map(|a| a[j])
                    } else {
                        sys.multipliers_at(d, &rows, x).ok().map(|(a, l)| {
                            if matches!(part.quantity, Quantity::Multiplier(_)) {
                                l[j]
                            } else {
                                a[j]
                            }
                        })
                    }
                })
                .collect();
            Truth::Numbers(nums)
        }
        Quantity::None => return Ok(None),
    }))
}

/// Whether `answer` matches the truth (exactly, or up to a constant where allowed).
fn matches_truth(part: &Part, p: &mut Prepared, answer: Id, truth: &Truth) -> Result<bool, Failed> {
    match truth {
        Truth::Expr(t) => {
            let r = relate(&p.system, answer, *t, &p.points, part.tolerance)
                .map_err(|e| Failed::new("sampling", e.to_string()))?;
            Ok(match r {
                Relation::Equal => true,
                Relation::UpToConstant(_) => {
                    part.up_to_constant || part.kind == PartKind::Lagrangian
                }
                _ => false,
            })
        }
        Truth::Numbers(nums) => {
            let vals = values(&p.system, &[answer], &p.points)
                .map_err(|e| Failed::new("sampling", e.to_string()))?;
            let scale = nums.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
            Ok(nums.iter().zip(&vals).all(|(t, v)| match (t, v) {
                (Some(t), Some(v)) => close(v[0], *t, scale, part.tolerance),
                (None, _) => true,
                (Some(_), None) => false,
            }))
        }
    }
}

fn show_truth(p: &mut Prepared, t: &Truth) -> String {
    match t {
        Truth::Expr(e) => {
            let s = p.system.simplify(*e);
            p.system.pool.unicode(s)
        }
        Truth::Numbers(n) => format!(
            "{:.6} at the first sample",
            n.iter().flatten().next().copied().unwrap_or(f64::NAN)
        ),
    }
}

fn verify_expression(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let answer = read_one(p, &part.answers[0])?;
    check_dimension(problem, p, answer, expected_dimension(problem, part))?;
    let Some(t) = truth(part, p)? else {
        return Ok(());
    };
    if !matches_truth(part, p, answer, &t)? {
        return Err(Failed::new(
            "wrong-answer",
            format!(
                "the stated answer {} is not what the physics gives: {}",
                p.system.pool.unicode(answer),
                show_truth(p, &t)
            ),
        ));
    }
    for w in &part.wrong {
        let Ok(id) = read_expr(w, &p.context, &mut p.system.pool) else {
            continue;
        };
        if matches_truth(part, p, id, &t)? {
            return Err(Failed::new(
                "wrong-accepted",
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

fn verify_equations(part: &Part, p: &mut Prepared) -> Check {
    let res = residuals(p, &part.answers)?;
    // A condition without accelerations: proportional to a generalized force at rest.
    if part.kind == PartKind::Equation
        && res.len() == 1
        && !p.system.pool.variables(res[0]).iter().any(|v| v.1 == 2)
    {
        let coords = p.system.coordinate_syms();
        let zero = p.system.pool.zero();
        let rest: rustc_hash::FxHashMap<_, _> = coords
            .iter()
            .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
            .collect();
        for &f in &p.derivation.forcing.clone() {
            let f0 = p.system.pool.substitute(f, &rest);
            if crate::check::compare::proportional(
                &p.system,
                res[0],
                f0,
                &p.points,
                tolerance::SAME,
            ) {
                return Ok(());
            }
        }
        return Err(Failed::new(
            "wrong-condition",
            format!(
                "the stated condition {} = 0 is not a generalized force at rest set to zero",
                p.system.pool.unicode(res[0])
            ),
        ));
    }
    let system = part.kind == PartKind::Equations;
    if let Some(why) = equations_hold(p, &res, system)? {
        let shown: Vec<String> = res
            .iter()
            .map(|&r| format!("{} = 0", p.system.pool.unicode(r)))
            .collect();
        let derived: Vec<String> = p
            .derivation
            .steps
            .iter()
            .map(|s| {
                let f = p.system.pool.factored(s.equation);
                format!("{} = 0", p.system.pool.display_factored(&f, Style::Unicode))
            })
            .collect();
        return Err(Failed::new(
            "wrong-eom",
            format!(
                "the stated equations {} are not the equations of motion ({why}); the physics gives {}",
                shown.join("; "),
                derived.join("; ")
            ),
        ));
    }
    for w in &part.wrong {
        let Ok(r) = residuals(p, std::slice::from_ref(w)) else {
            continue;
        };
        if equations_hold(p, &r, system)?.is_none() {
            return Err(Failed::new(
                "wrong-accepted",
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

/// What comparing the stated equilibria with the engine's, for one parameter sample, found.
enum EquilibriumFinding {
    /// Every point is an equilibrium.
    Continuum,
    /// The engine finds an equilibrium at `at` that the answer lacks.
    Missing { at: String },
    /// Stated item `item` has stability `want` but is `is`.
    Stability {
        item: String,
        want: String,
        is: &'static str,
    },
    /// Stated item `item` is not among the engine's equilibria.
    Spurious { item: String },
}

impl EquilibriumFinding {
    /// The finding as a failed verification, for the parameters `pstr`.
    fn details(self, pstr: &str) -> Failed {
        match self {
            EquilibriumFinding::Continuum => Failed::new(
                "not-isolated",
                format!(
                    "for {pstr} every point is an equilibrium; restrict the parameters with `assume`"
                ),
            ),
            EquilibriumFinding::Missing { at } => Failed::new(
                "missing-equilibrium",
                format!(
                    "the physics also has an equilibrium at {at} (for {pstr}), which the answer does not list"
                ),
            ),
            EquilibriumFinding::Stability { item, want, is } => Failed::new(
                "wrong-stability",
                format!("`{item}` is stated {want}, but it is {is} (for {pstr})"),
            ),
            EquilibriumFinding::Spurious { item } => Failed::new(
                "spurious-equilibrium",
                format!("`{item}` is not among the equilibria the engine finds for {pstr}"),
            ),
        }
    }
}

/// Reads the stated equilibria and checks each one's dimensions, that the forces vanish
/// there, and that the stabilities are as many as the equilibria.
fn stated_equilibria(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
) -> Result<Vec<Vec<Id>>, Failed> {
    let stated: Vec<Vec<Id>> = part
        .answers
        .iter()
        .map(|a| read_point(p, a))
        .collect::<Result<_, _>>()?;
    for (item, point) in part.answers.iter().zip(&stated) {
        for (i, &v) in point.iter().enumerate() {
            let want = problem.dims.get(&p.system.coordinates[i].name);
            check_dimension(problem, p, v, want)?;
        }
        if !p
            .system
            .verify_equilibrium(&p.derivation, point)
            .map_err(|e| Failed::new("unusable", e.to_string()))?
        {
            return Err(Failed::new(
                "spurious-equilibrium",
                format!(
                    "`{item}` is not an equilibrium: the generalized forces do not vanish there"
                ),
            ));
        }
    }
    if !part.stability.is_empty() && part.stability.len() != stated.len() {
        return Err(Failed::new(
            "bad-stability",
            format!(
                "{} stabilities for {} equilibria",
                part.stability.len(),
                stated.len()
            ),
        ));
    }
    Ok(stated)
}

/// Compares the stated equilibria (values `stated_pts`) with those the engine finds for
/// `params`.
fn compare_equilibria(
    part: &Part,
    p: &mut Prepared,
    params: &[f64],
    stated_pts: &[&[f64]],
) -> Result<Option<EquilibriumFinding>, Failed> {
    let found = p
        .system
        .equilibria(&p.derivation, params)
        .map_err(|e| Failed::new("unusable", e.to_string()))?;
    if found.continuum {
        return Ok(Some(EquilibriumFinding::Continuum));
    }
    let coords = &p.system.coordinates;
    let same = |s: &[f64], q: &[f64]| {
        s.iter()
            .zip(q)
            .enumerate()
            .all(|(i, (a, b))| same_coordinate(coords[i].periodic, *a, *b))
    };
    for (q, st) in &found.points {
        match stated_pts.iter().position(|s| same(s, q)) {
            None => {
                let at = coords
                    .iter()
                    .zip(q)
                    .map(|(c, x)| format!("{} = {}", c.name, fmt_value(*x)))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Ok(Some(EquilibriumFinding::Missing { at }));
            }
            Some(j) => {
                if let Some(want) = part.stability.get(j)
                    && want != st.name()
                {
                    return Ok(Some(EquilibriumFinding::Stability {
                        item: part.answers[j].clone(),
                        want: want.clone(),
                        is: st.name(),
                    }));
                }
            }
        }
    }
    let in_range = |q: &[f64]| {
        q.iter().enumerate().all(|(i, x)| {
            coords[i].periodic
                || (coords[i].range.0 - tolerance::RANGE_SLACK
                    ..=coords[i].range.1 + tolerance::RANGE_SLACK)
                    .contains(x)
        })
    };
    Ok(stated_pts
        .iter()
        .position(|s| in_range(s) && !found.points.iter().any(|(q, _)| same(s, q)))
        .map(|j| EquilibriumFinding::Spurious {
            item: part.answers[j].clone(),
        }))
}

fn verify_equilibria(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let stated = stated_equilibria(problem, part, p)?;
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "equilibria"]),
        EQUILIBRIUM_SAMPLES,
    )
    .map_err(|e| Failed::new("sampling", e.to_string()))?;
    let flat: Vec<Id> = stated.iter().flatten().copied().collect();
    let vals =
        values(&p.system, &flat, &samples).map_err(|e| Failed::new("sampling", e.to_string()))?;
    let n = p.system.n();
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        let params = samples.params(&p.system, k).to_vec();
        let stated_pts: Vec<&[f64]> = v.chunks(n).collect();
        if let Some(f) = repeated_equilibrium(part, p, &stated_pts) {
            return Err(f);
        }
        if let Some(f) = compare_equilibria(part, p, &params, &stated_pts)? {
            return Err(f.details(&parameter_text(&p.system, &params)));
        }
    }
    Ok(())
}

/// Two stated equilibria that are the same point (θ = π and θ = −π for a periodic θ): a
/// student listing each point once would be graded as missing one.
fn repeated_equilibrium(part: &Part, p: &Prepared, stated_pts: &[&[f64]]) -> Option<Failed> {
    let coords = &p.system.coordinates;
    for (i, a) in stated_pts.iter().enumerate() {
        for (j, b) in stated_pts.iter().enumerate().skip(i + 1) {
            let same = a
                .iter()
                .zip(b.iter())
                .enumerate()
                .all(|(c, (x, y))| same_coordinate(coords[c].periodic, *x, *y));
            if same {
                return Some(Failed::new(
                    "duplicate-equilibrium",
                    format!(
                        "`{}` and `{}` are the same equilibrium (an angle is periodic): list each point once",
                        part.answers[i], part.answers[j]
                    ),
                ));
            }
        }
    }
    None
}

fn verify_frequencies(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let stated: Vec<Id> = part
        .answers
        .iter()
        .map(|a| read_frequency(p, a))
        .collect::<Result<_, _>>()?;
    let per_time = if part.squared {
        Dimension::new(0, 0, -2)
    } else {
        Dimension::new(0, 0, -1)
    };
    for &s in &stated {
        check_dimension(problem, p, s, Some(per_time))?;
    }
    let at = equilibrium_of(p, part)?;
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "frequencies"]),
        FREQUENCY_SAMPLES,
    )
    .map_err(|e| Failed::new("sampling", e.to_string()))?;
    let mut roots = stated.clone();
    roots.extend(at.iter().copied());
    let vals =
        values(&p.system, &roots, &samples).map_err(|e| Failed::new("sampling", e.to_string()))?;
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        let params = samples.params(&p.system, k).to_vec();
        let q0 = &v[stated.len()..];
        let modes = p
            .system
            .modes_at(&p.derivation, &params, q0)
            .map_err(|e| Failed::new("unusable", e.to_string()))?;
        let mut want: Vec<f64> = if part.squared {
            modes.frequencies.iter().map(|w| w * w).collect()
        } else {
            modes.frequencies.clone()
        };
        let mut got: Vec<f64> = v[..stated.len()].to_vec();
        want.sort_by(f64::total_cmp);
        got.sort_by(f64::total_cmp);
        let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if want.len() != got.len()
            || !want
                .iter()
                .zip(&got)
                .all(|(a, b)| close(*a, *b, scale, part.tolerance.max(tolerance::EIGEN)))
        {
            let pstr = parameter_text(&p.system, &params);
            return Err(Failed::new(
                "wrong-frequency",
                format!(
                    "for {pstr} the stated frequencies are {got:.6?}, the eigen-solver gives {want:.6?}"
                ),
            ));
        }
    }
    Ok(())
}
