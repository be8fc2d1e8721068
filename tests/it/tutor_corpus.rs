//! The tutor's diagnosis rate (issue 21 §1): every labelled wrong step answer of
//! `tests/corpus-tutor/steps.tsv` is rejected, at least 90% get a named reason (a code other
//! than `not-equal`, and no sample-point dump), and none is named misleadingly (a named code
//! that is not among the line's labels). The figures are printed (`--nocapture`).

use std::collections::{BTreeMap, BTreeSet};

use lagrange::bank::embedded;
use lagrange::check::{Code, Status};
use lagrange::tutor::ladder::{StepChecker, ladder};

const CORPUS: &str = include_str!("../corpus-tutor/steps.tsv");

#[test]
fn the_tutor_names_the_mistake_in_wrong_steps() {
    let mut checkers = BTreeMap::new();
    let (mut total, mut named) = (0usize, 0usize);
    let mut misleading = Vec::new();
    let mut unnamed = Vec::new();
    let mut accepted = Vec::new();
    let mut kinds = BTreeSet::new();
    for line in CORPUS
        .lines()
        .filter(|l| !l.starts_with('#') && !l.is_empty())
    {
        let f: Vec<&str> = line.splitn(4, '\t').collect();
        let [pid, step_id, labels, answer] = f[..] else {
            panic!("bad corpus line: {line}");
        };
        let (steps, checker) = checkers.entry(pid.to_string()).or_insert_with(|| {
            let p = embedded::problem(pid).unwrap();
            (ladder(&p).unwrap(), StepChecker::owned(p))
        });
        let step = steps
            .iter()
            .find(|s| s.id == step_id)
            .unwrap_or_else(|| panic!("{pid}: no step {step_id}"));
        kinds.insert(step_id.split(':').next().unwrap_or_default().to_string());
        let v = checker.check(step, answer).unwrap();
        total += 1;
        if v.status == Status::Correct {
            accepted.push(line.to_string());
            continue;
        }
        let dump = v.diagnoses.iter().any(|d| d.message.contains("yours is"));
        let first = v.diagnoses.first().map(|d| d.code);
        if first.is_none_or(|c| c == Code::NotEqual) || dump {
            unnamed.push(format!("{line}\n    {:?}", v.diagnoses));
            continue;
        }
        named += 1;
        let codes: Vec<String> = v.diagnoses.iter().map(|d| kebab(d.code)).collect();
        if !labels.split('|').any(|l| codes.iter().any(|c| c == l)) {
            misleading.push(format!("{line}\n    {codes:?} {:?}", v.diagnoses));
        }
    }
    let rate = named as f64 / total as f64;
    println!(
        "tutor corpus: {total} wrong step answers, {named} named ({:.1}%), {} misleading, {} accepted, step kinds: {kinds:?}",
        100.0 * rate,
        misleading.len(),
        accepted.len()
    );
    assert!(total >= 150, "only {total} answers");
    for k in [
        "position",
        "speed-squared",
        "kinetic",
        "potential",
        "lagrangian",
        "momentum",
        "momentum-rate",
        "generalized-force",
        "eom",
        "equilibria",
        "linearized",
        "characteristic",
        "frequencies",
    ] {
        assert!(kinds.contains(k), "no answer to a `{k}` step");
    }
    assert!(accepted.is_empty(), "accepted:\n{}", accepted.join("\n"));
    assert!(
        misleading.is_empty(),
        "misleading:\n{}",
        misleading.join("\n")
    );
    assert!(
        rate >= 0.9,
        "named {rate:.3}; unnamed:\n{}",
        unnamed.join("\n")
    );
}

/// A code as the corpus writes it (`derivative-rule`).
fn kebab(c: Code) -> String {
    serde_json::to_value(c)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

#[test]
fn the_speed_for_its_square_and_l_for_the_momentum_are_named() {
    // Issue 21: these got a sample-point dump or a vague "wrong factor" before.
    let p = embedded::problem("simple-pendulum").unwrap();
    let steps = ladder(&p).unwrap();
    let mut checker = StepChecker::owned(p);
    let step = |id: &str| steps.iter().find(|s| s.id == id).unwrap().clone();
    let v = checker.check(&step("speed-squared:1"), "l*theta'").unwrap();
    assert_eq!(v.status, Status::Incorrect);
    assert_eq!(
        v.diagnoses[0].message,
        "that is the speed; this step asks for its square"
    );
    let v = checker
        .check(
            &step("momentum:theta"),
            "m*l^2*theta'^2/2 + m*g*l*cos(theta)",
        )
        .unwrap();
    assert_eq!(v.diagnoses[0].code, Code::GaveLagrangian);
    assert!(
        v.diagnoses[0].message.contains("p = ∂L/∂θ̇"),
        "{:?}",
        v.diagnoses
    );
    // The right answers are still right.
    let v = checker
        .check(&step("speed-squared:1"), "l^2*theta'^2")
        .unwrap();
    assert_eq!(v.status, Status::Correct);
    let v = checker
        .check(&step("momentum:theta"), "m l^2 theta'")
        .unwrap();
    assert_eq!(v.status, Status::Correct);
}
