//! Named answers: `T = …`, `V = …`, `L = …`, `p = …`, `p_θ = …`, `h = …`, `E = …`, `θ'' = …`
//! (`a = …`, `λ = …`)
//! given for a part asking for that quantity are the quantity, not an equation. The name is
//! read off the text before the first `=`; what follows is checked as the answer, and a name
//! of another quantity is told (`wrong-name`), the value still checked.
//!
//! Equation parts are left alone (`θ'' = …` is an equation there), and so is a name that is a
//! declared symbol of the problem.

use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis, Status, Verdict};
use crate::expr::lexer::{Tok, lex};
use crate::expr::{Context, ParseError};
use crate::mechanics::System;
use crate::problem::{Part, PartKind, Problem, Quantity};

/// A quantity a student can name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Named {
    Kinetic,
    Potential,
    Lagrangian,
    /// The momentum of coordinate i, or `p` alone.
    Momentum(Option<usize>),
    Energy,
    /// The acceleration of coordinate i (`θ'' = …`), or `a` alone.
    Acceleration(Option<usize>),
    /// A constraint's multiplier (`λ = …`), never judged: a tension may be called `T`.
    Multiplier,
}

/// A name found before the answer's `=`.
pub(super) struct Label {
    /// The name as typed.
    text: String,
    named: Named,
    /// Where the value starts in the input.
    pub(super) offset: usize,
}

/// The label of `input` when it names a quantity and the part asks for one expression.
pub(super) fn label(part: &Part, p: &Prepared, input: &str) -> Option<Label> {
    if !matches!(
        part.kind,
        PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce
    ) {
        return None;
    }
    let k = input.find('=')?;
    let text = input[..k].trim();
    let named = classify(&p.system, &p.context, text)?;
    Some(Label {
        text: text.to_string(),
        named,
        offset: k + 1,
    })
}

/// The answer `input` to `part` without a name that fits the quantity the part asks for
/// (`L = …` for a Lagrangian, `p_θ = …` for that momentum): what the checker judges, and what
/// follow-through reads as the student's quantity. Anything else is returned whole.
pub fn unlabelled<'i>(problem: &Problem, part: &Part, input: &'i str) -> &'i str {
    if !matches!(
        part.kind,
        PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce
    ) {
        return input;
    }
    let Some(k) = input.find('=') else {
        return input;
    };
    let ctx = problem.context();
    match classify(&problem.system, &ctx, input[..k].trim()) {
        Some(named) if asked(part).is_none_or(|a| fits(named, a)) => &input[k + 1..],
        _ => input,
    }
}

/// What the name `text` stands for, if it is a quantity's name and no symbol of the problem.
fn classify(sys: &System, ctx: &Context, text: &str) -> Option<Named> {
    let toks: Vec<Tok> = lex(text).ok()?.into_iter().map(|t| t.tok).collect();
    let coordinate = |name: &str| {
        let name = crate::expr::names::normalize(name);
        sys.coordinates.iter().position(|c| c.name == name)
    };
    let named = match toks.as_slice() {
        [Tok::Name { text: n, dots: 2 }] => Named::Acceleration(Some(coordinate(n)?)),
        [Tok::Name { text: n, dots: 0 }, Tok::Prime, Tok::Prime] => {
            Named::Acceleration(Some(coordinate(n)?))
        }
        [
            Tok::Name { text: p_, dots: 0 },
            Tok::Name { text: q, dots: 0 },
        ] if p_ == "p" || p_ == "p_" => Named::Momentum(Some(coordinate(q)?)),
        [Tok::Name { text: n, dots: 0 }] if !ctx.is_declared(n) => match n.as_str() {
            "T" => Named::Kinetic,
            "V" | "U" => Named::Potential,
            "L" => Named::Lagrangian,
            "h" | "H" | "E" => Named::Energy,
            "p" => Named::Momentum(None),
            "a" => Named::Acceleration(None),
            "lambda" | "lambda1" | "lambda2" | "lambda3" => Named::Multiplier,
            _ => {
                let rest = n.strip_prefix('p')?;
                Named::Momentum(Some(coordinate(rest.strip_prefix('_').unwrap_or(rest))?))
            }
        },
        _ => return None,
    };
    Some(named)
}

/// The quantity part asks for, if it is one a student can name.
fn asked(part: &Part) -> Option<Named> {
    Some(match part.quantity {
        Quantity::Kinetic => Named::Kinetic,
        Quantity::Potential => Named::Potential,
        Quantity::Lagrangian => Named::Lagrangian,
        Quantity::Momentum(i) => Named::Momentum(Some(i)),
        Quantity::EnergyFunction => Named::Energy,
        Quantity::Acceleration(i) => Named::Acceleration(Some(i)),
        Quantity::Multiplier(_) | Quantity::Cyclic | Quantity::None => return None,
    })
}

/// Whether the name said fits the quantity asked.
/// Whether `label` names what `part` asks for (or the part asks for nothing nameable).
pub(super) fn fits_part(part: &Part, label: &Label) -> bool {
    asked(part).is_none_or(|a| fits(label.named, a))
}

fn fits(said: Named, asked: Named) -> bool {
    said == asked
        || (said == Named::Momentum(None) && matches!(asked, Named::Momentum(_)))
        || (said == Named::Acceleration(None) && matches!(asked, Named::Acceleration(_)))
}

/// The quantity in words, with its symbol.
fn describe(p: &mut Prepared, q: Named) -> String {
    let coord = |p: &mut Prepared, i: usize, order: u8| {
        p.system.coordinates.get(i).map_or_else(String::new, |c| {
            let v = p.system.pool.var(c.sym, order);
            p.system.pool.unicode(v)
        })
    };
    match q {
        Named::Kinetic => "the kinetic energy T".into(),
        Named::Potential => "the potential energy V".into(),
        Named::Lagrangian => "the Lagrangian L".into(),
        Named::Energy => "the energy function h".into(),
        Named::Momentum(None) => "a momentum".into(),
        Named::Momentum(Some(i)) => format!("the momentum conjugate to {}", coord(p, i, 0)),
        Named::Acceleration(Some(i)) => format!("the acceleration {}", coord(p, i, 2)),
        Named::Acceleration(None) => "an acceleration".into(),
        Named::Multiplier => "a multiplier".into(),
    }
}

/// Completes the verdict on the value after `label`: spans point into the whole input, and a
/// name of another quantity makes the answer incorrect with `wrong-name`.
pub(super) fn finish(p: &mut Prepared, part: &Part, label: &Label, v: &mut Verdict) {
    if let Some(e) = v.parse_error.take() {
        v.parse_error = Some(ParseError::new(
            e.kind,
            e.span.start + label.offset..e.span.end + label.offset,
        ));
    }
    let Some(asked) = asked(part) else {
        return;
    };
    if fits(label.named, asked) || v.status == Status::Invalid {
        return;
    }
    let right = v.status == Status::Correct;
    let mut message = format!(
        "you wrote {} = …, but this part asks for {}",
        label.text,
        describe(p, asked)
    );
    // A right expression under the wrong name is a slip of the label, not a wrong attempt:
    // unreadable as an answer to this part (invalid) until the name is fixed.
    if right {
        message.push_str(": the expression itself is right for it, so fix the name");
        v.diagnoses.clear();
    }
    v.status = if right {
        Status::Invalid
    } else {
        Status::Incorrect
    };
    v.score = 0.0;
    v.diagnoses.push(Diagnosis::new(Code::WrongName, message));
}
