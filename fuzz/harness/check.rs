//! Target `check`: answers to every part of every problem of the embedded bank — generated
//! from the part's symbols, mutated from the reference and the `wrong` examples, random, and
//! constructed to be wrong (the reference times a factor that vanishes somewhere, with one
//! coefficient perturbed, plus a term that is small or zero only on the sampled box, with
//! unlike dimensions, times 0·log(−1)) or constructed to be right (the reference, scaled,
//! reordered). Oracle: a constructed-wrong answer is never `correct`; a constructed-right
//! one always is (a false reject is a finding too, of a lesser kind).

use serde::{Deserialize, Serialize};

use lagrange::bank::{Bank, Part, PartKind, Problem, embedded};
use lagrange::check::{Checker, Status};
use lagrange::diagnostic::{Diagnostic, render_parse_error, render_plain};

use super::inputs::{self, Rng, Vocab, below, chance, pick};
use super::text::{is_zero, scale, split_eq, strip_sign, terms};

/// What the oracle expects of an answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Expect {
    /// Anything but a panic or a slow answer.
    Any,
    /// Never `correct`.
    Wrong,
    /// Always `correct`.
    Right,
}

/// One input of the target: an answer to a part, and what it must get.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Case {
    pub problem: String,
    pub part: String,
    pub answer: String,
    pub expect: Expect,
    /// How the answer was made, for the report.
    pub how: String,
}

thread_local! {
    /// The embedded bank, built once per thread (leaked: it lives as long as the run).
    static BANK: &'static Bank = Box::leak(Box::new(embedded::bank()));
}

/// The embedded bank.
pub fn bank() -> &'static Bank {
    BANK.with(|b| *b)
}

/// One input: constructed wrong (30%), constructed right (5%), grammar (30%), mutation of the
/// reference or of a `wrong` example (25%), soup or bytes (5%), blow-up (5%).
pub fn generate(r: &mut Rng) -> Vec<u8> {
    let bank = bank();
    let p = pick(r, &bank.problems);
    let part = pick(r, &p.parts);
    let v = vocab(p);
    let made = match below(r, 20) {
        0..=5 => wrong(r, p, part),
        6 => right(r, p, part),
        _ => None,
    };
    let (answer, expect, how) = made.unwrap_or_else(|| {
        let reference = part.reference_text(p.system.coordinates.len());
        let any = |a: String, how: &str| (a, Expect::Any, how.to_string());
        match below(r, 13) {
            0..=5 => any(grammar(r, &v, part), "grammar"),
            6..=9 => {
                let mut seeds = part.wrong.clone();
                seeds.push(reference);
                let s = pick(r, &seeds).clone();
                let m = inputs::mutate(r, s.as_bytes());
                any(String::from_utf8_lossy(&m).into_owned(), "mutation")
            }
            10 => {
                let n = 1 + below(r, 30);
                any(inputs::soup(r, n), "soup")
            }
            11 => {
                let n = below(r, 40);
                let b = inputs::bytes(r, n);
                any(String::from_utf8_lossy(&b).into_owned(), "bytes")
            }
            _ => any(inputs::blowup(r, &v), "blowup"),
        }
    });
    let case = Case {
        problem: p.id.clone(),
        part: part.id.clone(),
        answer,
        expect,
        how,
    };
    serde_json::to_vec_pretty(&case).expect("a case serializes")
}

/// The names of a problem, for generated answers.
fn vocab(p: &Problem) -> Vocab {
    let ctx = p.context();
    Vocab {
        coords: ctx.coordinates().to_vec(),
        params: ctx.parameters().to_vec(),
    }
}

/// A grammar-generated answer of the part's shape (equation, system, list).
fn grammar(r: &mut Rng, v: &Vocab, part: &Part) -> String {
    let d = 1 + below(r, 4) as u32;
    let items = 1 + below(r, 3);
    let one = |r: &mut Rng| match part.kind {
        PartKind::Equation | PartKind::Equations => {
            format!("{} = {}", inputs::expr(r, v, d), inputs::expr(r, v, d))
        }
        PartKind::Equilibria => v
            .coords
            .iter()
            .map(|q| format!("{q} = {}", inputs::expr(r, v, d)))
            .collect::<Vec<_>>()
            .join(", "),
        _ => inputs::expr(r, v, d),
    };
    let all: Vec<String> = (0..items).map(|_| one(r)).collect();
    match part.kind {
        PartKind::Equations | PartKind::Equilibria => all.join("; "),
        PartKind::Frequencies | PartKind::Values => all.join(", "),
        _ => all[0].clone(),
    }
}

/// Factors that vanish somewhere in the domain: each velocity, each coordinate, its sine,
/// and (with `params`) a difference of two parameters of one dimension. Not a coordinate the
/// `reference` divides by (`k/r^2`): where it vanishes the reference is not finite, so the
/// product is still right wherever the physics is defined (principle 6).
fn vanishing(p: &Problem, params: bool, reference: &str) -> Vec<String> {
    let mut f = Vec::new();
    for c in &p.system.coordinates {
        let q = &c.name;
        f.extend([format!("{q}'"), format!("sin({q})")]);
        if !reference.contains(&format!("/{q}")) {
            f.push(q.clone());
        }
    }
    if params {
        let ps = &p.system.parameters;
        for (i, a) in ps.iter().enumerate() {
            for b in &ps[i + 1..] {
                if a.dimension.is_some() && a.dimension == b.dimension {
                    f.push(format!("({} - {})", a.name, b.name));
                }
            }
        }
    }
    f
}

/// A parameter with a dimension, for `(P + 1)·answer`.
fn dimensioned(p: &Problem) -> Option<String> {
    let ps: Vec<&String> = p
        .system
        .parameters
        .iter()
        .filter(|x| x.dimension.is_some_and(|d| !d.is_none()))
        .map(|x| &x.name)
        .collect();
    ps.first().map(|s| (*s).clone())
}

/// A term that is zero for |q| ≤ c only: wrong outside the nominal range of q.
fn outside_box(r: &mut Rng, p: &Problem) -> String {
    let c = pick(r, &p.system.coordinates);
    let half = if c.periodic {
        "pi".to_string()
    } else {
        format!("{}", c.range.0.abs().max(c.range.1.abs()))
    };
    let q = &c.name;
    format!("(abs({q} - {half}) + abs({q} + {half}) - 2*{half})")
}

/// A constructed wrong answer, if the part allows one: (answer, expectation, how).
fn wrong(r: &mut Rng, p: &Problem, part: &Part) -> Option<(String, Expect, String)> {
    let made = match part.kind {
        PartKind::Equation => wrong_equation(r, p, &part.answers[0]),
        PartKind::Equations => wrong_system(r, p, &part.answers),
        PartKind::Expression
        | PartKind::ConstraintForce
        | PartKind::Lagrangian
        | PartKind::SteadyMotion => wrong_expression(r, p, part),
        PartKind::Equilibria => wrong_equilibria(r, &part.answers),
        PartKind::Frequencies | PartKind::Values => wrong_values(r, part),
    }?;
    // Within a part's own tolerance (a numeric part states one) a perturbed answer is the
    // same answer by design: only a change of 100 tolerances or more is wrong.
    let factor = (made.1.starts_with("perturbed"))
        .then(|| made.1.rsplit("times ").next()?.parse::<f64>().ok())
        .flatten();
    if factor.is_some_and(|d| (d - 1.0).abs() < 100.0 * part.tolerance) {
        return None;
    }
    Some((made.0, Expect::Wrong, made.1))
}

/// A small relative change, well above the documented tolerance (1e-9).
fn delta(r: &mut Rng) -> &'static str {
    const DELTAS: [&str; 6] = ["1.000001", "0.9999", "1.01", "1.5", "-1", "1.0000001"];
    DELTAS[below(r, DELTAS.len())]
}

/// Whether an equation's reference has both an acceleration term and another nonzero term,
/// so that scaling one term changes the accelerations it implies.
fn mixed(ts: &[String]) -> bool {
    ts.iter().any(|t| t.contains("''")) && ts.iter().any(|t| !t.contains("''") && !is_zero(t))
}

/// A wrong single equation (only for an equation of motion, with accelerations).
fn wrong_equation(r: &mut Rng, p: &Problem, reference: &str) -> Option<(String, String)> {
    let (lhs, rhs) = split_eq(reference);
    let mut ts = terms(&lhs);
    ts.extend(terms(&rhs));
    if !mixed(&ts) {
        return None;
    }
    Some(match below(r, 6) {
        0 | 1 => {
            let f = pick(r, &vanishing(p, true, reference)).clone();
            (
                format!("({lhs})*{f} = ({rhs})*{f}"),
                format!("vanishing-factor: times {f}"),
            )
        }
        2 => {
            // A term of either side, never a bare 0 (scaling it changes nothing).
            let nonzero: Vec<usize> = (0..ts.len()).filter(|&i| !is_zero(&ts[i])).collect();
            let k = *pick(r, &nonzero);
            let d = delta(r);
            let side_l = terms(&lhs).len();
            let (l, rr) = if k < side_l {
                (scale(&lhs, k, d), rhs.clone())
            } else {
                (lhs.clone(), scale(&rhs, k - side_l, d))
            };
            (
                format!("{l} = {rr}"),
                format!("perturbed: term {k} times {d}"),
            )
        }
        3 => {
            let f = dimensioned(p)?;
            (
                format!("({lhs})*({f} + 1) = ({rhs})*({f} + 1)"),
                "dimension: (P + 1) times".into(),
            )
        }
        4 => (
            format!("{lhs} + 0*log(-1) = {rhs}"),
            "undefined: plus 0·log(−1)".into(),
        ),
        _ => {
            let t = ts.iter().find(|t| !t.contains("''"))?;
            let bump = outside_box(r, p);
            (
                format!("{lhs} + ({})*{bump} = {rhs}", strip_sign(t)),
                "outside-box: plus a term zero only on the box".into(),
            )
        }
    })
}

/// A wrong system: one equation times a vanishing factor, replaced by the energy law
/// Σ q̇ᵢ·eqᵢ, by a coordinate times another equation, or with a forcing term scaled.
fn wrong_system(r: &mut Rng, p: &Problem, eqs: &[String]) -> Option<(String, String)> {
    let k = below(r, eqs.len());
    let sides: Vec<(String, String)> = eqs.iter().map(|e| split_eq(e)).collect();
    let zero_form = |i: usize| format!("({}) - ({})", sides[i].0, sides[i].1);
    let coords: Vec<String> = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.clone())
        .collect();
    let mut out: Vec<String> = eqs.to_vec();
    let how = match below(r, 4) {
        0 => {
            let f = pick(r, &vanishing(p, true, &eqs[k])).clone();
            out[k] = format!("({})*{f} = ({})*{f}", sides[k].0, sides[k].1);
            format!("vanishing-factor: equation {k} times {f}")
        }
        1 if coords.len() == eqs.len() => {
            let sum: Vec<String> = (0..eqs.len())
                .map(|i| format!("{}'*({})", coords[i], zero_form(i)))
                .collect();
            out[k] = format!("{} = 0", sum.join(" + "));
            format!("energy-law: equation {k} replaced by Σ q̇ᵢ·eqᵢ")
        }
        2 if eqs.len() > 1 => {
            let other = (k + 1 + below(r, eqs.len() - 1)) % eqs.len();
            let q = pick(r, &coords);
            out[k] = format!("{q}*({}) = 0", zero_form(other));
            format!("dependent: equation {k} replaced by {q} times equation {other}")
        }
        _ => {
            let ts = terms(&sides[k].0);
            let j = ts.iter().position(|t| !t.contains("''"))?;
            let d = delta(r);
            out[k] = format!("{} = {}", scale(&sides[k].0, j, d), sides[k].1);
            format!("perturbed: equation {k}, forcing term {j} times {d}")
        }
    };
    Some((out.join("; "), how))
}

/// A wrong expression or Lagrangian.
fn wrong_expression(r: &mut Rng, p: &Problem, part: &Part) -> Option<(String, String)> {
    let reference = &part.answers[0];
    // Any multiple of a reference of 0 is the reference.
    if reference.trim() == "0" {
        return None;
    }
    let lagrangian = part.kind == PartKind::Lagrangian;
    let has_coordinate = p
        .system
        .coordinates
        .iter()
        .any(|c| reference.contains(c.name.as_str()));
    Some(match below(r, 5) {
        0 | 1 => {
            // A constant multiple of L is an equivalent Lagrangian: only state factors.
            let f = pick(r, &vanishing(p, !lagrangian, reference)).clone();
            (
                format!("({reference})*{f}"),
                format!("vanishing-factor: times {f}"),
            )
        }
        2 if lagrangian => {
            let ts = terms(reference);
            let k = ts
                .iter()
                .position(|t| !t.contains('\'') && has_name(t, p))?;
            let d = delta(r);
            (
                scale(reference, k, d),
                format!("perturbed: potential term {k} times {d}"),
            )
        }
        2 if part.up_to_constant && !has_coordinate => return None,
        2 => {
            let d = delta(r);
            (
                format!("{d}*({reference})"),
                format!("perturbed: times {d}"),
            )
        }
        3 => {
            let f = dimensioned(p)?;
            (
                format!("({reference})*({f} + 1)"),
                "dimension: (P + 1) times".into(),
            )
        }
        _ => (
            format!("{reference} + 0*log(-1)"),
            "undefined: plus 0·log(−1)".into(),
        ),
    })
}

/// Whether a term names a coordinate.
fn has_name(t: &str, p: &Problem) -> bool {
    p.system
        .coordinates
        .iter()
        .any(|c| t.contains(c.name.as_str()))
}

/// A wrong list of equilibria: one item dropped, or one value moved a little (π rounded).
fn wrong_equilibria(r: &mut Rng, items: &[String]) -> Option<(String, String)> {
    let mut out = items.to_vec();
    let k = below(r, items.len());
    let how = if items.len() > 1 && chance(r, 0.25) {
        out.remove(k);
        format!("dropped: item {k}")
    } else {
        // A multi-coordinate item ("θ₁ = 0, θ₂ = 0") moves its last value only.
        let (head, last) = match items[k].rsplit_once(',') {
            Some((h, l)) => (format!("{h}, "), l.to_string()),
            None => (String::new(), items[k].clone()),
        };
        let (q, v) = split_eq(&last);
        let moved = if v.trim() == "pi" {
            pick(r, &["3.14159", "355/113", "pi + 1e-6", "3.1416"]).to_string()
        } else {
            format!("({v}) + {}", pick(r, &["1e-6", "1e-3", "0.1"]))
        };
        out[k] = format!("{head}{} = {moved}", q.trim());
        format!("moved: item {k} to {moved}")
    };
    Some((out.join("; "), how))
}

/// A wrong list of values: one item scaled, or squared when ω is asked.
fn wrong_values(r: &mut Rng, part: &Part) -> Option<(String, String)> {
    let mut out = part.answers.clone();
    // Scaling or squaring a 0 (a free motion's ω = 0) leaves it right: only a nonzero item
    // can be made wrong this way.
    let nonzero: Vec<usize> = (0..out.len()).filter(|&i| out[i].trim() != "0").collect();
    if nonzero.is_empty() {
        return None;
    }
    let k = nonzero[below(r, nonzero.len())];
    let how = if !part.squared && chance(r, 0.3) {
        out[k] = format!("({})^2", out[k]);
        format!("squared: item {k}")
    } else {
        let d = delta(r);
        out[k] = format!("{d}*({})", out[k]);
        format!("perturbed: item {k} times {d}")
    };
    Some((out.join(", "), how))
}

/// A constructed right answer: the reference, scaled, sides swapped, reordered. (A Lagrangian
/// is not scaled: `k·L` gives the same equations but is `constant-factor`, not the L asked
/// for, and a bare number added to it has the wrong dimension; equilibria keep their stated stability where the part requires it.)
fn right(r: &mut Rng, p: &Problem, part: &Part) -> Option<(String, Expect, String)> {
    let reference = part.reference_text(p.system.coordinates.len());
    let k = pick(r, &["2", "-3", "1e-9", "1e9"]);
    let (answer, how) = match (part.kind, below(r, 3)) {
        (_, 0) => (reference, "reference: as stated".to_string()),
        (PartKind::Equation, 1) => {
            let (l, rr) = split_eq(&part.answers[0]);
            (
                format!("({l})*{k} = ({rr})*{k}"),
                format!("scaled: times {k}"),
            )
        }
        (PartKind::Equation, _) => {
            let (l, rr) = split_eq(&part.answers[0]);
            (format!("{rr} = {l}"), "swapped: sides".into())
        }
        (PartKind::Equations, 1) => {
            let mut eqs = part.answers.clone();
            let (l, rr) = split_eq(&eqs[0]);
            eqs[0] = format!("({l})*{k} = ({rr})*{k}");
            (eqs.join("; "), format!("scaled: equation 0 times {k}"))
        }
        (PartKind::Lagrangian, _) => (
            format!("{k}*({reference}) + ({reference}) - {k}*({reference})"),
            format!("restated: kL + L - kL with k = {k}"),
        ),
        (
            PartKind::Equilibria | PartKind::Frequencies | PartKind::Values | PartKind::Equations,
            _,
        ) => {
            let mut items = part.answers.clone();
            if part.kind == PartKind::Equilibria && part.require_stability {
                for (a, s) in items.iter_mut().zip(&part.stability) {
                    *a = format!("{a} ({s})");
                }
            }
            items.reverse();
            let sep = if part.kind == PartKind::Frequencies || part.kind == PartKind::Values {
                ", "
            } else {
                "; "
            };
            (items.join(sep), "reordered: items reversed".into())
        }
        _ => return None,
    };
    Some((answer, Expect::Right, how))
}

/// Checks one case as the CLI would (verdict, rendered diagnoses, JSON) and applies the
/// oracle.
pub fn execute(input: &[u8]) -> Result<(), String> {
    let case: Case =
        serde_json::from_slice(input).map_err(|e| format!("corpus: unreadable case: {e}"))?;
    let bank = bank();
    let p = bank
        .problem(&case.problem)
        .ok_or_else(|| format!("corpus: no problem `{}`", case.problem))?;
    let mut checker = Checker::new(p);
    let v = checker
        .check(&case.part, &case.answer)
        .map_err(|e| format!("check-error: {e}"))?;
    for d in &v.diagnoses {
        super::no_raw_controls(&render_plain(&Diagnostic::from(d)), "diagnosis")?;
    }
    if let Some(e) = &v.parse_error {
        let shown = render_parse_error("answer", &case.answer, e, false);
        super::no_raw_controls(&shown, "parse error")?;
    }
    let _json = serde_json::to_string(&v).map_err(|e| format!("json: {e}"))?;
    let what = format!(
        "`{}` ({}) for {}/{}",
        case.answer, case.how, case.problem, case.part
    );
    match case.expect {
        Expect::Wrong if v.status == Status::Correct => {
            let family = case.how.split(':').next().unwrap_or_default();
            Err(format!("false-accept[{family}]: {what} is graded correct"))
        }
        Expect::Right if v.status != Status::Correct => {
            let why: Vec<String> = v.diagnoses.iter().map(|d| d.code.to_string()).collect();
            let family = case.how.split(':').next().unwrap_or_default();
            Err(format!(
                "false-reject[{family}]: {what} is graded {:?} [{}]",
                v.status,
                why.join(", ")
            ))
        }
        _ => Ok(()),
    }
}
