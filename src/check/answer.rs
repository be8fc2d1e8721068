//! `check(problem, part, input)`: read the answer, compare it with the reference by the
//! part's kind, and judge an expression against its reference (equations are `equations.rs`,
//! unordered lists `lists.rs`, the search for an expression's mistake
//! `expression_diagnosis.rs`).

use rustc_hash::FxHashMap;

use super::common::{invalid_reading, point_text, undefined_everywhere, verdict};
use super::compare::{Relation, fmt_value, relate, values};
use super::diagnose::{bare_numbers_for, how_far_off, nice_fraction, rounded};
use super::error::CheckError;
use super::expression_diagnosis::diagnose_expression;
use super::lagrangian::{self, Motion};
use super::prepare::{Prepared, prepare};
use super::tolerance;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use super::{equations, lists, named};
use crate::expr::{Id, Reading, read, read_expr};
use crate::problem::{Part, PartKind, Problem, Quantity};

mod adjust;

use adjust::{
    drop_superseded, fold_definitions, never_correct_with_unlike_dimensions, numbers_for_symbols,
};

/// Checks answers to one problem, preparing each part once.
pub struct Checker<'a> {
    problem: &'a Problem,
    prepared: FxHashMap<String, Prepared>,
}

impl<'a> Checker<'a> {
    /// A checker for `problem`.
    pub fn new(problem: &'a Problem) -> Self {
        Checker {
            problem,
            prepared: FxHashMap::default(),
        }
    }

    /// Checks `input` against part `part_id`. Errors are usage errors (no such part, a part
    /// that cannot be prepared), never a judgement of the input.
    pub fn check(&mut self, part_id: &str, input: &str) -> Result<Verdict, CheckError> {
        let problem = self.problem;
        let (part, p) = self.prepared(part_id)?;
        Ok(check_prepared(problem, part, p, input))
    }

    /// The canonical form of `input` as part `part_id` reads it (list items sorted): answers
    /// with one canonical form get one verdict, so a caller checking many answers may check
    /// one of them and reuse the verdict. `None` when the input cannot be read.
    pub fn canonical(&mut self, part_id: &str, input: &str) -> Result<Option<String>, CheckError> {
        let (part, p) = self.prepared(part_id)?;
        let Some(input) = in_si(part, input) else {
            return Ok(None);
        };
        Ok(super::fingerprint::canonical(part, p, &input))
    }

    /// A fingerprint of `input` for part `part_id`: equal for answers equal at the sample
    /// points (equations up to scaling, lists in any order), so wrong answers can be grouped
    /// by what they mean rather than how they were typed. `None` when the input cannot be read
    /// or evaluated.
    pub fn fingerprint(
        &mut self,
        part_id: &str,
        input: &str,
    ) -> Result<Option<String>, CheckError> {
        let (part, p) = self.prepared(part_id)?;
        let Some(input) = in_si(part, input) else {
            return Ok(None);
        };
        Ok(super::fingerprint::fingerprint(part, p, &input))
    }

    /// The part `part_id` and its preparation (made on first use).
    fn prepared(&mut self, part_id: &str) -> Result<(&'a Part, &mut Prepared), CheckError> {
        let problem = self.problem;
        let part = problem
            .part(part_id)
            .ok_or_else(|| CheckError::UnknownPart {
                problem: problem.id.clone(),
                part: part_id.to_string(),
            })?;
        let p = match self.prepared.entry(part_id.to_string()) {
            std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(prepare(problem, part)?),
        };
        Ok((part, p))
    }
}

/// The input as the checker reads it: a numeric part's units converted to SI (`5 [cm]` and
/// `5 cm` must not share a key: in the second, `cm` would be symbols). `None` where the
/// units cannot be read.
fn in_si(part: &Part, input: &str) -> Option<String> {
    match part.units {
        Some(want) => super::units::convert(input, want).ok().map(|c| c.text),
        None => Some(input.to_string()),
    }
}

/// Checks one answer (preparing the part afresh; use [`Checker`] for many answers).
pub fn check(problem: &Problem, part: &Part, input: &str) -> Result<Verdict, CheckError> {
    let mut p = prepare(problem, part)?;
    Ok(check_prepared(problem, part, &mut p, input))
}

/// Checks against a prepared part.
pub(crate) fn check_prepared(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    input: &str,
) -> Verdict {
    // A numeric part reads units in brackets (`4.43 [rad/s]`), converted to SI first.
    let converted = match part.units {
        Some(want) => match super::units::convert(input, want) {
            Ok(c) => Some(c),
            Err(e) => return super::units::unit_verdict(problem, part, input, &e),
        },
        None => None,
    };
    let typed = input;
    let input = converted.as_ref().map_or(input, |c| c.text.as_str());
    // `T = …` for a part asking for T: the value after the name is the answer.
    let label = named::label(part, p, input);
    let input = label.as_ref().map_or(input, |l| &input[l.offset..]);
    p.quotes = super::prepare::Quotes::of(input);
    let mut v = match part.kind {
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values => {
            lists::check_list(problem, part, p, input)
        }
        _ => match read(input, &p.context, &mut p.system.pool) {
            Err(e) => invalid_reading(problem, part, e),
            Ok(r) => match part.kind {
                PartKind::Equation | PartKind::Equations => {
                    equations::check_equations(problem, part, p, r)
                }
                _ => check_expression(problem, part, p, r),
            },
        },
    };
    if let Some(l) = &label {
        named::finish(p, part, l, &mut v);
    }
    super::linearize::diagnose(part, p, input, &mut v);
    if let Some(c) = &converted {
        super::units::finish(part, typed, c, &mut v);
    }
    never_correct_with_unlike_dimensions(&mut v);
    numbers_for_symbols(part, p, input, &mut v);
    drop_superseded(&mut v);
    fold_definitions(p, input, &mut v);
    v.sort();
    v
}

/// What the comparison of an expression answer with its reference found, before it is put
/// into words.
enum Judgement {
    /// Equal at every point.
    Equal,
    /// Off by a constant, which this part allows.
    AllowedConstant,
    /// A Lagrangian with the reference's motion, accepted (a total time derivative; any
    /// factor on a part that accepts the same motion).
    SameMotion(Motion),
    /// A Lagrangian with the reference's motion at another scale (2L, V − T): not the
    /// Lagrangian asked for.
    OtherScale(Motion),
    /// Constants rounded (the diagnosis is the search's).
    Rounded(Diagnosis),
    /// The negative of the reference.
    Negated,
    /// `f` times the reference.
    Factor(f64),
    /// Bare numbers `f` times a reference with parameters: a wrong value, not a factor (any
    /// two numbers have a ratio).
    WrongValue(f64),
    /// Undefined at sample `point`, where the reference is defined.
    Undefined { point: usize },
    /// Nothing that simple: search for the mistake.
    Unexplained,
}

impl Judgement {
    /// Whether the answer is accepted.
    fn accepts(&self) -> bool {
        matches!(
            self,
            Judgement::Equal | Judgement::AllowedConstant | Judgement::SameMotion(_)
        )
    }

    /// The sentence for a judgement (none for a plain equality or an unexplained difference).
    fn details(self, p: &Prepared) -> Option<Diagnosis> {
        Some(match self {
            Judgement::Equal | Judgement::Unexplained => return None,
            Judgement::AllowedConstant => Diagnosis::new(
                Code::UpToConstant,
                "your answer differs from the reference by a constant; that is allowed here (the zero of potential energy is a free choice)",
            ),
            Judgement::SameMotion(m) => lagrangian::accepted(m),
            Judgement::OtherScale(m) => lagrangian::refused(m)?,
            Judgement::Rounded(d) => d,
            Judgement::Negated => Diagnosis::new(
                Code::SignError,
                "sign error: your answer is the negative of the right one",
            ),
            Judgement::Factor(f) => Diagnosis::new(
                Code::ConstantFactor,
                match nice_fraction(f) {
                    Some(n) => format!(
                        "your answer is {n} times the right one: check the numerical factors (a ½, a 2)"
                    ),
                    None => format!(
                        "your answer is off by a constant factor of about {}",
                        fmt_value(f)
                    ),
                },
            ),
            Judgement::WrongValue(f) => Diagnosis::new(
                Code::NotEqual,
                format!("your value is wrong: it is {}", how_far_off(f)),
            ),
            Judgement::Undefined { point } => Diagnosis::new(
                Code::Undefined,
                format!(
                    "your answer is undefined at {}, where the correct one is defined",
                    point_text(p, point)
                ),
            ),
        })
    }
}

/// The expression of a reading, or why a reading is of the wrong kind.
fn expression_of(r: Reading) -> Result<Id, &'static str> {
    match r {
        Reading::Expr(e, _) => Ok(e),
        Reading::Equation { .. } => Err("this part asks for an expression, not an equation"),
        Reading::List(..) | Reading::System(..) => {
            Err("this part asks for one expression, not a list")
        }
    }
}

/// The part's reference expression, read once.
fn reference_of(part: &Part, p: &mut Prepared) -> Option<Id> {
    if let Some(r) = p.reference.get() {
        return r.first().and_then(|x| x.first()).copied();
    }
    let id = read_expr(&part.answers[0], &p.context, &mut p.system.pool).ok()?;
    p.reference.get_or_init(|| vec![vec![id]]);
    Some(id)
}

/// A sum of unlike terms, or a different dimension from the reference.
fn dimension_check(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    s: Id,
    reference: Id,
) -> Option<Diagnosis> {
    // A number carries no unit: an answer judged with the student's numbers (the problem
    // pinned to them, without dimensions) has no dimension to check.
    if part.numbers && problem.dims.is_empty() {
        return None;
    }
    let ds = match p.system.pool.dimension(s, &problem.dims) {
        Err(e) => return Some(Diagnosis::new(Code::Dimension, e.to_string())),
        Ok(Some(ds)) => ds,
        Ok(None) => return None,
    };
    // A reference of 0 (the bead on a horizontal wire has V = 0) has every dimension: only a
    // dimension the part states can be asked for.
    let dr = if p.system.pool.is_zero(reference) {
        part.dimension?
    } else {
        p.system.pool.dimension(reference, &problem.dims).ok()??
    };
    (ds != dr && !p.system.pool.is_zero(s)).then(|| {
        Diagnosis::new(
            Code::Dimension,
            format!("your answer has dimension {ds}, but the answer must be {dr}"),
        )
    })
}

/// Classifies how the answer `s` relates to the reference. V, L and h are each defined up
/// to an added constant; L also up to a total time derivative.
fn judge(part: &Part, p: &mut Prepared, s: Id, reference: Id, rel: &Relation) -> Judgement {
    let lagrangian = lagrangian::asks_lagrangian(part);
    let free_constant =
        part.up_to_constant || lagrangian || part.quantity == Quantity::EnergyFunction;
    let by_motion = |m: Motion| {
        if m == Motion::Gauge || part.same_motion {
            Judgement::SameMotion(m)
        } else {
            Judgement::OtherScale(m)
        }
    };
    match *rel {
        Relation::Equal => Judgement::Equal,
        Relation::UpToConstant(_) if free_constant => Judgement::AllowedConstant,
        Relation::Factor(f) if lagrangian && (f - 1.0).abs() >= tolerance::ROUNDED => {
            match lagrangian::motion(p, s, reference, Some(f)) {
                Some(m) => by_motion(m),
                None => Judgement::Factor(f),
            }
        }
        Relation::Factor(f) if (f - 1.0).abs() < tolerance::ROUNDED => {
            match rounded(p, s, reference) {
                Some(d) => Judgement::Rounded(d),
                None if bare_numbers_for(p, s, reference) => Judgement::WrongValue(f),
                None => Judgement::Factor(f),
            }
        }
        Relation::Factor(f) if (f + 1.0).abs() < tolerance::NUMBER => Judgement::Negated,
        Relation::Factor(f) if bare_numbers_for(p, s, reference) => Judgement::WrongValue(f),
        Relation::Factor(f) => Judgement::Factor(f),
        Relation::Undefined { point } => Judgement::Undefined { point },
        Relation::UpToConstant(_) | Relation::Different { .. } => {
            match lagrangian
                .then(|| lagrangian::motion(p, s, reference, None))
                .flatten()
            {
                Some(m) => by_motion(m),
                None => Judgement::Unexplained,
            }
        }
    }
}

fn check_expression(problem: &Problem, part: &Part, p: &mut Prepared, r: Reading) -> Verdict {
    // `φ̇² = g/(l cos α)` for a part asking φ̇²: the value after the asked quantity.
    let r = match r {
        Reading::Equation { lhs, rhs, span } if names_the_rate(part, p, lhs) => {
            Reading::Expr(rhs, span)
        }
        r => r,
    };
    let s = match expression_of(r) {
        Ok(s) => s,
        Err(why) => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(Code::WrongKind, why));
            return v;
        }
    };
    let mut v = verdict(problem, part, Status::Incorrect);
    v.reading = ReadAs {
        plain: p.system.pool.plain(s),
        unicode: p.system.pool.unicode(s),
        note: None,
    };
    let Some(reference) = reference_of(part, p) else {
        v.status = Status::Invalid;
        v.diagnoses.push(Diagnosis::new(
            Code::Syntax,
            "the reference answer of this part cannot be read",
        ));
        return v;
    };
    if p.system.pool.is_undefined(s) {
        v.diagnoses.push(undefined_everywhere());
        return v;
    }
    v.diagnoses
        .extend(dimension_check(problem, part, p, s, reference));
    if let Some(d) = rate_for_its_square(part, p, s, reference) {
        v.diagnoses.push(d);
        return v;
    }
    let rel = match relate(&p.system, s, reference, &p.points, part.tolerance) {
        Ok(r) => r,
        Err(e) => {
            v.diagnoses
                .push(Diagnosis::new(Code::NotEqual, e.to_string()));
            return v;
        }
    };
    let judgement = match judge(part, p, s, reference, &rel) {
        Judgement::Factor(f) if bare_numbers_for(p, s, reference) => Judgement::WrongValue(f),
        j => j,
    };
    let unlike = v.diagnoses.iter().any(|d| d.code == Code::Dimension);
    match judgement {
        // Numbers that agree do not make an answer with unlike terms right: the dimension
        // diagnosis is the reason, and nothing else is said.
        j if j.accepts() && unlike => {}
        j if j.accepts() => {
            v.status = Status::Correct;
            v.diagnoses.extend(j.details(p));
        }
        Judgement::Unexplained if negated_up_to_constant(part, p, s, reference) => v
            .diagnoses
            .push(Diagnosis::new(
                Code::SignError,
                "sign error: your answer is the negative of the right one (up to a constant, which is free here)",
            )),
        Judgement::Unexplained => diagnose_expression(part, p, s, reference, rel, &mut v),
        j => v.diagnoses.extend(j.details(p)),
    }
    if v.status == Status::Correct {
        v.score = 1.0;
        v.diagnoses.retain(|d| {
            matches!(
                d.code,
                Code::UpToConstant | Code::EquivalentLagrangian | Code::TotalDerivative
            )
        });
    }
    v
}

/// Whether `s` is −`reference` plus a constant on a part that allows a constant (V, h):
/// `−m g l (1 − cos θ)` for V = −m g l cos θ is the sign, not a factor, that is wrong.
fn negated_up_to_constant(part: &Part, p: &mut Prepared, s: Id, reference: Id) -> bool {
    let free = part.up_to_constant || part.quantity == Quantity::EnergyFunction;
    if !free {
        return false;
    }
    let minus = p.system.pool.neg(reference);
    matches!(
        relate(&p.system, s, minus, &p.points, part.tolerance),
        Ok(Relation::Equal | Relation::UpToConstant(_))
    )
}

/// Whether `lhs` is what a steady-motion part asks for, the moving coordinate's rate (or
/// its square, where the part asks for that): `φ̇² = …` then states the answer. The rate
/// itself on a part asking its square is taken too, so the value is told to be squared.
fn names_the_rate(part: &Part, p: &mut Prepared, lhs: Id) -> bool {
    if part.kind != PartKind::SteadyMotion {
        return false;
    }
    let stays = |name: &str| {
        part.at
            .iter()
            .any(|(k, _)| crate::expr::names::normalize(k.trim()) == name)
    };
    let moving: Vec<_> = p
        .system
        .coordinates
        .iter()
        .filter(|c| !stays(&c.name))
        .map(|c| c.sym)
        .collect();
    let [sym] = moving[..] else {
        return false;
    };
    let rate = p.system.pool.var(sym, 1);
    let square = p.system.pool.powi(rate, 2);
    let asked = if part.squared { square } else { rate };
    lhs == asked || lhs == rate
}

/// A steady-motion part asking for the rate squared (φ'²) answered with the rate: the
/// answer's square is the reference wherever the answer is defined (where the reference is
/// negative, outside the physical range, the root is undefined, which is not the mistake).
fn rate_for_its_square(part: &Part, p: &mut Prepared, s: Id, reference: Id) -> Option<Diagnosis> {
    if part.kind != PartKind::SteadyMotion || !part.squared {
        return None;
    }
    let square = p.system.pool.powi(s, 2);
    let vals = values(&p.system, &[square, reference], &p.points).ok()?;
    let mut agree = 0;
    for v in vals.iter().flatten() {
        if !v[0].is_finite() {
            continue;
        }
        if !super::compare::close(v[0], v[1], 0.0, part.tolerance) {
            return None;
        }
        agree += 1;
    }
    (agree > 0 && agree >= vals.len() / 2).then(|| {
        Diagnosis::new(
            Code::OmegaRoot,
            "that is the rate, but this part asks for its square: square it",
        )
    })
}
