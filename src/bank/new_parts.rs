//! The candidate parts of a drafted problem (`problems new`), each answer derived by the
//! engine from the loaded system: T and V (bodies only), L, the momenta, the cyclic
//! coordinates, the equations of motion, the energy function, and — where a closed form is
//! found — the equilibria with their stability and the frequencies about a stable one. A part
//! with no closed form is left out here with the reason; verification (in `new.rs`) proves the
//! rest and removes what it cannot prove.

use super::new_types::{Candidate, Field, LeftOut, Widened};
use crate::expr::Id;
use crate::mechanics::System;
use crate::problem::Problem;

/// The candidate parts of `problem`, the parts left out with why, and the coordinate ranges
/// the stated equilibria need.
pub(super) fn candidates(problem: &Problem) -> (Vec<Candidate>, Vec<LeftOut>, Vec<Widened>) {
    let mut sys = problem.system.clone();
    let mut parts = Vec::new();
    let mut left = Vec::new();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let from_bodies = !sys.bodies.is_empty();
    let plain = |sys: &mut System, e: Id| {
        let s = sys.simplify(e);
        sys.pool.plain(s)
    };
    if let (true, Some(t), Some(v)) = (from_bodies, sys.kinetic, sys.potential) {
        parts.push(Candidate::one(
            "kinetic",
            "expression",
            "Write the kinetic energy T.",
            plain(&mut sys, t),
            &[
                "Differentiate each body's position with respect to t to get its velocity.",
                "Add ½ m v² for each mass (and ½ I ω² for each rotation).",
            ],
        ));
        parts.push(
            Candidate::one(
                "potential",
                "expression",
                "Write the potential energy V (any zero level).",
                plain(&mut sys, v),
                &[
                    "Gravity contributes m g times each body's height; a spring ½ k (stretch)².",
                    "Only differences of V matter: any constant may be added.",
                ],
            )
            .with("up_to", Field::Str("constant".into())),
        );
    } else {
        for part in ["kinetic", "potential"] {
            left.push(LeftOut {
                part: part.into(),
                reason: "the system is given by its Lagrangian, which does not fix T and V apart (give bodies to state them)".into(),
            });
        }
    }
    let l = sys.lagrangian;
    parts.push(Candidate::one(
        "lagrangian",
        "lagrangian",
        "Write the Lagrangian.",
        plain(&mut sys, l),
        &["L = T − V.", "Write T and V in the coordinates first."],
    ));
    let d = match sys.derive() {
        Ok(d) => d,
        Err(e) => {
            for part in [
                "momentum",
                "eom",
                "energy-function",
                "equilibria",
                "frequencies",
            ] {
                left.push(LeftOut {
                    part: part.into(),
                    reason: format!("the equations of motion cannot be derived: {e}"),
                });
            }
            return (parts, left, Vec::new());
        }
    };
    let energy = sys.energy(&d);
    for (i, name) in names.iter().enumerate() {
        let id = if names.len() == 1 {
            "momentum".to_string()
        } else {
            format!("momentum-{name}")
        };
        let conserved = if energy.cyclic.contains(&i) {
            " (it is conserved)"
        } else {
            ""
        };
        let p = d.steps[i].momentum;
        parts.push(
            Candidate::one(
                &id,
                "expression",
                &format!("Find the momentum conjugate to {name}{conserved}."),
                plain(&mut sys, p),
                &[&format!(
                    "Differentiate L with respect to {name}', the other coordinates and velocities held fixed."
                )],
            )
            .with("quantity", Field::Str("momentum".into()))
            .with("coordinate", Field::Str(name.clone())),
        );
    }
    let cyclic: Vec<String> = energy.cyclic.iter().map(|&i| names[i].clone()).collect();
    let mut c = Candidate::one(
        "cyclic",
        "values",
        "Which coordinates are cyclic? (Answer `none` if there is none.)",
        "none".into(),
        &["A coordinate is cyclic when L does not depend on it (its velocity may appear)."],
    )
    .with("quantity", Field::Str("cyclic".into()));
    if !cyclic.is_empty() {
        c.answer = cyclic;
        c.many = true;
    }
    parts.push(c);
    let equations: Vec<String> = d
        .steps
        .iter()
        .map(|s| format!("{} = 0", sys.pool.plain(s.equation)))
        .collect();
    let eom_hints = [
        "Compute ∂L/∂q' for each coordinate q and its time derivative d/dt(∂L/∂q').",
        "Compute ∂L/∂q.",
        "Write d/dt(∂L/∂q') − ∂L/∂q = 0 for each coordinate.",
    ];
    let mut eom = Candidate::one(
        "eom",
        if names.len() == 1 {
            "equation"
        } else {
            "equations"
        },
        if names.len() == 1 {
            "Derive the equation of motion."
        } else {
            "Derive the equations of motion, one for each coordinate."
        },
        String::new(),
        &eom_hints,
    );
    eom.many = names.len() > 1;
    eom.answer = equations;
    parts.push(eom);
    let h = energy.function;
    let mut hints = vec!["h = Σ q' ∂L/∂q' − L."];
    if energy.is_total == Some(true) {
        hints.push("T is quadratic in the velocities here, so h = T + V.");
    }
    parts.push(Candidate::one(
        "energy-function",
        "expression",
        "Write the energy function h.",
        plain(&mut sys, h),
        &hints,
    ));
    let widened = super::new_statics::statics(&mut sys, &d, &mut parts, &mut left);
    (parts, left, widened)
}
