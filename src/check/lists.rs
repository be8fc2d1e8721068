//! Unordered lists — equilibria, frequencies, values — matched item by item across every
//! sample point, with partial credit; why an unmatched item is wrong is `items.rs`'s business.

use super::common::{invalid_reading, verdict};
use super::compare::values;
use super::error::CheckError;
use super::items::{ItemFinding, Lists, classify_unmatched, same_item, what_of};
use super::prepare::{Prepared, read_frequency, read_one, read_point};
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, Style};
use crate::problem::{Part, PartKind, Problem};

use super::freq_label;
use super::item_reading::{ItemLabel, read_stated_items};

fn reference_items(part: &Part, p: &mut Prepared) -> Result<Vec<Vec<Id>>, CheckError> {
    part.answers
        .iter()
        .map(|a| match part.kind {
            PartKind::Equilibria => read_point(p, a),
            PartKind::Frequencies => read_frequency(p, a).map(|x| vec![x]),
            _ => read_one(p, a).map(|x| vec![x]),
        })
        .collect()
}

/// Values of each item's components at every point (None where undefined).
fn item_values(p: &Prepared, items: &[Vec<Id>]) -> Vec<Vec<Option<Vec<f64>>>> {
    items
        .iter()
        .map(|it| {
            values(&p.system, it, &p.points).unwrap_or_else(|_| vec![None; p.points.points.len()])
        })
        .collect()
}

/// An item as text: `θ = π` for an equilibrium, the value otherwise.
fn show_item(part: &Part, p: &Prepared, coords: &[Id], it: &[Id], style: Style) -> String {
    if part.kind == PartKind::Equilibria {
        let pool = &p.system.pool;
        it.iter()
            .zip(coords)
            .map(|(x, c)| format!("{} = {}", pool.display(*c, style), pool.display(*x, style)))
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        p.system.pool.display(it[0], style)
    }
}

/// Matches student items to reference items one to one: (matched reference, matched student).
/// A `blocked` item (labelled as another quantity) matches nothing.
fn match_items(
    part: &Part,
    p: &Prepared,
    lists: &Lists,
    blocked: &[bool],
) -> (Vec<bool>, Vec<bool>) {
    let mut matched_ref = vec![false; lists.reference.len()];
    let mut matched_stu = blocked.to_vec();
    for (i, s) in lists.student.iter().enumerate() {
        if blocked[i] {
            continue;
        }
        if let Some(j) = (0..lists.reference.len()).find(|&j| {
            !matched_ref[j] && same_item(part, p, s, &lists.reference[j], part.tolerance)
        }) {
            matched_ref[j] = true;
            matched_stu[i] = true;
        }
    }
    if part.kind == PartKind::Frequencies {
        match_zero_frequencies(part, lists, &mut matched_ref, &mut matched_stu);
    }
    // Blocked items were marked only to keep them out of the matching.
    for (m, b) in matched_stu.iter_mut().zip(blocked) {
        *m &= !b;
    }
    (matched_ref, matched_stu)
}

/// A free mode's ω = 0 written as an expression that vanishes only up to rounding
/// (√((M + m)²·g²) − (M + m)·g) matches a reference 0, measured against the largest frequency
/// of the list at each sample rather than against itself.
fn match_zero_frequencies(
    part: &Part,
    lists: &Lists,
    matched_ref: &mut [bool],
    matched_stu: &mut [bool],
) {
    let value = |item: &[Option<Vec<f64>>], k: usize| {
        item.get(k)
            .and_then(Option::as_ref)
            .and_then(|v| v.first().copied())
    };
    let samples = lists.reference.first().map_or(0, Vec::len);
    let scale = |k: usize| {
        lists
            .reference
            .iter()
            .filter_map(|r| value(r, k))
            .fold(0.0f64, |a, x| a.max(x.abs()))
    };
    let is_zero =
        |r: &[Option<Vec<f64>>]| (0..samples).all(|k| value(r, k).is_none_or(|x| x == 0.0));
    // Where the student's item is undefined the reference must be too.
    let near_zero = |s: &[Option<Vec<f64>>]| {
        (0..samples).all(|k| match value(s, k) {
            Some(u) => u.abs() <= part.tolerance * scale(k),
            None => value(&lists.reference[0], k).is_none(),
        })
    };
    for (j, r) in lists.reference.iter().enumerate() {
        if matched_ref[j] || !is_zero(r) {
            continue;
        }
        if let Some(i) =
            (0..lists.student.len()).find(|&i| !matched_stu[i] && near_zero(&lists.student[i]))
        {
            matched_ref[j] = true;
            matched_stu[i] = true;
        }
    }
}

/// How the items were read, joined as a student would type them (with the label of a
/// frequency that names its quantity, `ω² = g/l`).
fn list_reading(
    part: &Part,
    p: &Prepared,
    coords: &[Id],
    items: &[Vec<Id>],
    labels: &[Option<ItemLabel>],
) -> ReadAs {
    let sep = if part.kind == PartKind::Equilibria && p.system.n() > 1 {
        "; "
    } else {
        ", "
    };
    let shown = |style: Style| -> String {
        items
            .iter()
            .zip(labels)
            .map(|(i, l)| {
                let value = show_item(part, p, coords, i, style);
                match l {
                    Some(l) => format!("{} = {value}", l.said.label(style)),
                    None => value,
                }
            })
            .collect::<Vec<_>>()
            .join(sep)
    };
    ReadAs {
        plain: shown(Style::Plain),
        unicode: shown(Style::Unicode),
        note: None,
    }
}

/// The reference items, read once.
fn cached_reference(part: &Part, p: &mut Prepared) -> Result<Vec<Vec<Id>>, CheckError> {
    if let Some(r) = p.reference.get() {
        return Ok(r.clone());
    }
    let r = reference_items(part, p)?;
    Ok(p.reference.get_or_init(|| r).clone())
}

/// Checks a list answer.
pub fn check_list(problem: &Problem, part: &Part, p: &mut Prepared, input: &str) -> Verdict {
    let mut v = verdict(problem, part, Status::Incorrect);
    let (items, stated, labels) = match read_stated_items(part, p, input) {
        Ok(r) => (r.items, r.stated, r.labels),
        Err(e) => return invalid_reading(problem, part, e),
    };
    // An item labelled as another quantity than the part asks for is never the answer.
    let blocked: Vec<bool> = labels
        .iter()
        .map(|l| !freq_label::fits(part, l.as_ref().map(|l| l.said)))
        .collect();
    // The coordinates as expressions, interned once, to show equilibria as `θ = π`.
    let names: Vec<String> = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.clone())
        .collect();
    let coords: Vec<Id> = names.iter().map(|n| p.system.pool.sym(n)).collect();
    v.reading = list_reading(part, p, &coords, &items, &labels);
    v.reading.note = stability_note(part, p, &coords, (&items, &stated));
    let refs = match cached_reference(part, p) {
        Ok(r) => r,
        Err(m) => {
            v.status = Status::Invalid;
            v.diagnoses.push(Diagnosis::new(
                Code::Syntax,
                format!("the reference answer cannot be read: {m}"),
            ));
            return v;
        }
    };
    for &x in items.iter().flatten() {
        if let Err(e) = p.system.pool.dimension(x, &problem.dims) {
            v.diagnoses
                .push(Diagnosis::new(Code::Dimension, e.to_string()));
        }
    }
    let (sv, rv) = (item_values(p, &items), item_values(p, &refs));
    let lists = Lists {
        student: &sv,
        reference: &rv,
        reference_ids: &refs,
        student_ids: &items,
    };
    let (matched_ref, mut matched_stu) = match_items(part, p, &lists, &blocked);
    // An angle the part's range leaves out is the right position written outside the range
    // asked for: said so, and not credited.
    let outside: Vec<usize> = outside_stated_range(part, p, &sv)
        .into_iter()
        .filter(|&i| matched_stu[i])
        .collect();
    for &i in &outside {
        {
            matched_stu[i] = false;
            let shown = show_item(part, p, &coords, &items[i], Style::Unicode);
            v.diagnoses.push(Diagnosis::new(
                Code::WrongItem,
                format!(
                    "item {} ({shown}) is an equilibrium, but this part asks for the angles in (−π, π]: give each angle in that range (add or subtract 2π)",
                    i + 1
                ),
            ));
        }
    }
    let matched = matched_stu.iter().filter(|m| **m).count();
    let mut free: Vec<usize> = (0..refs.len()).filter(|&j| !matched_ref[j]).collect();
    for i in (0..items.len()).filter(|&i| !matched_stu[i] && !outside.contains(&i)) {
        if let Some(l) = labels[i].as_ref().filter(|_| blocked[i]) {
            let value = show_item(part, p, &coords, &items[i], Style::Unicode);
            let shown = format!("{} = {value}", l.said.symbol());
            let d = freq_label::mislabelled(part, p, &lists, (i, l.said, &shown), &mut free);
            v.diagnoses.push(d);
            continue;
        }
        let label = format!(
            "item {} ({})",
            i + 1,
            show_item(part, p, &coords, &items[i], Style::Unicode)
        );
        // A zero mode given where the part omits them; a frequency given for a growth rate.
        if let Some(d) = super::modes_lists::zero_item(part, &lists, i, &label)
            .or_else(|| super::modes_lists::oscillating_item(part, p, &lists, i, &label))
        {
            v.diagnoses.push(d);
            continue;
        }
        let item = (i, items[i][0], label);
        let finding = classify_unmatched(problem, part, p, &lists, item, &mut free);
        v.diagnoses.push(finding.details());
    }
    if let Some(d) = super::modes_lists::missing_zero_modes(part, &lists, &mut free) {
        v.diagnoses.push(d);
    }
    if !free.is_empty() {
        let missing = ItemFinding::Missing {
            count: free.len(),
            what: what_of(part),
        };
        v.diagnoses.push(missing.details());
    }
    // Stated stability, judged on the items that matched (each wrong one loses its credit).
    let wrong_stability = stated_stability(part, p, &lists, &coords, (&items, &stated));
    let wrong = wrong_stability.len();
    v.diagnoses.extend(wrong_stability);
    // Stability the part asks for and the answer does not state: half of each such point's
    // credit, once the points themselves are right (until then, they are the mistake).
    let all_points = matched == refs.len() && items.len() == refs.len();
    let unstated = if all_points {
        unstated_stability(part, &matched_stu, &stated)
    } else {
        0
    };
    let total = refs.len().max(items.len()).max(1);
    v.score = (matched.saturating_sub(wrong) as f64 - 0.5 * unstated as f64) / total as f64;
    if unstated > 0 {
        v.diagnoses.push(Diagnosis::new(
            Code::MissingStability,
            format!(
                "this part asks for the stability of each equilibrium, and {} of your points {} none: write stable or unstable after each point, as in `{} = … (stable)`",
                unstated,
                if unstated == 1 { "states" } else { "state" },
                p.system.coordinates.first().map_or("q", |c| c.name.as_str())
            ),
        ));
    }
    if all_points
        && v.diagnoses.iter().all(|d| {
            d.code != Code::Dimension
                && d.code != Code::WrongStability
                && d.code != Code::MissingStability
        })
    {
        v.status = Status::Correct;
        v.score = 1.0;
        v.diagnoses.clear();
    }
    super::misconception::list(problem, part, p, &items, &mut v);
    super::modes_lists::growth_wording(part, &mut v);
    show_any(part, input, &mut v);
    v
}

/// The student items (equilibria) with a periodic coordinate outside (−π, π] at some
/// sample point, where the part's prompt states that range; none otherwise. −π itself is
/// let pass: it is π, and which end a range keeps is notation, not physics.
fn outside_stated_range(part: &Part, p: &Prepared, values: &[Vec<Option<Vec<f64>>>]) -> Vec<usize> {
    let stated = ["(−π, π]", "(-π, π]", "(-pi, pi]"]
        .iter()
        .any(|r| part.prompt.contains(r));
    if part.kind != PartKind::Equilibria || !stated {
        return Vec::new();
    }
    let periodic: Vec<usize> = (0..p.system.n())
        .filter(|&c| p.system.coordinates[c].periodic)
        .collect();
    let beyond = |x: f64| x.abs() > std::f64::consts::PI * (1.0 + 1e-9);
    (0..values.len())
        .filter(|&i| {
            values[i].iter().flatten().any(|at| {
                periodic
                    .iter()
                    .any(|&c| at.get(c).is_some_and(|&x| beyond(x)))
            })
        })
        .collect()
}

/// A coordinate left arbitrary is shown as `any` (it is read as a marker value), and a
/// student who gave one point of a continuum is told which coordinate is free.
fn show_any(part: &Part, input: &str, v: &mut Verdict) {
    if part.kind != PartKind::Equilibria {
        return;
    }
    for (marker, word) in [("√3·π", "any"), ("sqrt(3)*pi", "any")] {
        v.reading.plain = v.reading.plain.replace(marker, word);
        v.reading.unicode = v.reading.unicode.replace(marker, word);
        if let Some(n) = &mut v.reading.note {
            *n = n.replace(marker, word);
        }
        for d in &mut v.diagnoses {
            d.message = d.message.replace(marker, word);
        }
    }
    let free: Vec<&str> = part
        .answers
        .iter()
        .flat_map(|a| a.split(','))
        .filter_map(|it| it.split_once('='))
        .filter(|(_, r)| r.trim() == "any")
        .map(|(l, _)| l.trim())
        .collect();
    if v.status != Status::Correct
        && !free.is_empty()
        && !input.contains("any")
        && !input.contains("arbitrary")
    {
        v.diagnoses.push(Diagnosis::new(
            Code::WrongItem,
            format!(
                "{} is arbitrary at the equilibria asked for (a continuum: every value is one), so give it as `{} = any` rather than a value",
                free[0], free[0]
            ),
        ));
    }
}

/// How many matched items state no stability where the part requires it.
fn unstated_stability(
    part: &Part,
    matched_stu: &[bool],
    stated: &[Option<super::stability::Stated>],
) -> usize {
    if !part.require_stability {
        return 0;
    }
    matched_stu
        .iter()
        .zip(stated)
        .filter(|(m, s)| **m && s.is_none())
        .count()
}

/// `wrong-stability` for each matched item whose stated stability the part contradicts.
fn stated_stability(
    part: &Part,
    p: &mut Prepared,
    lists: &Lists,
    coords: &[Id],
    (items, stated): (&[Vec<Id>], &[Option<super::stability::Stated>]),
) -> Vec<Diagnosis> {
    let mut out = Vec::new();
    let gyroscopic = stated.iter().any(Option::is_some) && velocity_linear(p);
    for (i, said) in stated.iter().enumerate() {
        let Some(said) = *said else { continue };
        let matched = (0..lists.reference.len()).find(|&j| {
            same_item(
                part,
                p,
                &lists.student[i],
                &lists.reference[j],
                part.tolerance,
            )
        });
        if let Some(j) = matched {
            let label = show_item(part, p, coords, &items[i], Style::Unicode);
            let engine =
                |p: &mut Prepared| super::stability::engine_stability(p, &lists.student[i]);
            let said = (said, gyroscopic);
            out.extend(super::stability::judge(part, &label, said, j, || engine(p)));
        }
    }
    out
}

/// Whether L has terms linear in the velocities (Coriolis, gyroscopic): L(q, q̇) and
/// L(q, −q̇) differ. Stability is then not read off the potential alone.
fn velocity_linear(p: &mut Prepared) -> bool {
    let l = p.system.lagrangian;
    let mut map = rustc_hash::FxHashMap::default();
    for c in p.system.coordinate_syms() {
        let v = p.system.pool.var(c, 1);
        map.insert((c, 1), p.system.pool.neg(v));
    }
    let reversed = p.system.pool.substitute(l, &map);
    let odd = p.system.pool.sub(l, reversed);
    !p.system.is_zero(odd)
}

/// The stability the student stated, as read (`stated: θ = 0 stable, θ = π unstable`).
fn stability_note(
    part: &Part,
    p: &Prepared,
    coords: &[Id],
    (items, stated): (&[Vec<Id>], &[Option<super::stability::Stated>]),
) -> Option<String> {
    let said: Vec<String> = items
        .iter()
        .zip(stated)
        .filter_map(|(it, s)| {
            let s = (*s)?;
            Some(format!(
                "{} {}",
                show_item(part, p, coords, it, Style::Unicode),
                s.word()
            ))
        })
        .collect();
    (!said.is_empty()).then(|| format!("stated: {}", said.join(", ")))
}
