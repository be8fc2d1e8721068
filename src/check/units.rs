//! Numbers with units, read only in numeric parts (a part whose `values` give every
//! parameter a number): a unit is written in square brackets after the number,
//! `9.8 [m/s^2]`, `50 [cm]`, `4.43 [rad/s]`, so that it cannot be read as the problem's
//! symbols (`m` is a mass elsewhere, `g` the gravity). Each item is converted to SI before it
//! is checked; a unit of another dimension than the answer's is a `dimension` finding.

use std::f64::consts::PI;

use super::common::verdict;
use super::prepare::top_level_items;
use super::verdict::{Code, Diagnosis, Status, Verdict};
use crate::expr::Dimension;
use crate::problem::{Part, Problem};

/// The units understood, each with its factor to SI and its dimension (M, L, T exponents;
/// charge separately).
const UNITS: &[(&str, f64, (i32, i32, i32))] = &[
    ("m", 1.0, (0, 1, 0)),
    ("cm", 1e-2, (0, 1, 0)),
    ("mm", 1e-3, (0, 1, 0)),
    ("km", 1e3, (0, 1, 0)),
    ("kg", 1.0, (1, 0, 0)),
    ("g", 1e-3, (1, 0, 0)),
    ("s", 1.0, (0, 0, 1)),
    ("ms", 1e-3, (0, 0, 1)),
    ("min", 60.0, (0, 0, 1)),
    ("h", 3600.0, (0, 0, 1)),
    ("Hz", 1.0, (0, 0, -1)),
    ("N", 1.0, (1, 1, -2)),
    ("J", 1.0, (1, 2, -2)),
    ("W", 1.0, (1, 2, -3)),
    ("rad", 1.0, (0, 0, 0)),
    ("deg", PI / 180.0, (0, 0, 0)),
];

/// The names of the known units, for a help line.
pub fn known() -> String {
    let mut names: Vec<&str> = UNITS.iter().map(|u| u.0).collect();
    names.push("C");
    names.join(", ")
}

/// Reads a unit, `m/s^2`, `kg*m^2/s^2`, `kg m² s⁻²`, `1/s`: its factor to SI and dimension.
/// Each `/` divides by the one unit after it.
pub fn parse_unit(text: &str) -> Result<(f64, Dimension), String> {
    let normal: String = text
        .chars()
        .map(|c| match c {
            '·' | '*' => ' ',
            '²' => '2',
            '³' => '3',
            '⁻' => '-',
            '¹' => '1',
            c => c,
        })
        .collect();
    let mut factor = 1.0;
    let mut dim = Dimension::NONE;
    let mut divide = false;
    let mut any = false;
    let mut rest = normal.trim();
    while !rest.is_empty() {
        if let Some(r) = rest.strip_prefix('/') {
            divide = true;
            rest = r.trim_start();
            continue;
        }
        let end = if rest.starts_with('1') {
            1
        } else {
            rest.find(|c: char| !c.is_ascii_alphabetic())
                .unwrap_or(rest.len())
        };
        let name = &rest[..end];
        if name.is_empty() {
            return Err(format!(
                "`{text}` is not a unit: write e.g. [m/s^2] (known units: {})",
                known()
            ));
        }
        rest = &rest[end..];
        // Exponent: `^-2`, `^2`, or digits right after the name (`m2`, from `m²`).
        let mut exp = 1i32;
        let tail = rest.strip_prefix('^').unwrap_or(rest);
        let digits_end = tail
            .char_indices()
            .find(|&(i, c)| !(c.is_ascii_digit() || (i == 0 && c == '-')))
            .map_or(tail.len(), |(i, _)| i);
        if digits_end > 0 {
            exp = tail[..digits_end]
                .parse()
                .map_err(|_| format!("bad exponent in the unit `{text}`"))?;
            rest = &tail[digits_end..];
        } else if tail.len() != rest.len() {
            return Err(format!("missing exponent after `^` in the unit `{text}`"));
        }
        rest = rest.trim_start();
        if divide {
            exp = -exp;
            divide = false;
        }
        let (f, d) = match name {
            "1" => (1.0, Dimension::NONE),
            "C" => (1.0, Dimension::charge()),
            _ => match UNITS.iter().find(|u| u.0 == name) {
                Some(&(_, f, (m, l, t))) => (f, Dimension::new(m, l, t)),
                None => {
                    return Err(format!("unknown unit `{name}` (known units: {})", known()));
                }
            },
        };
        factor *= f.powi(exp);
        dim = dim * d.pow(exp.into());
        any = true;
    }
    if !any {
        return Err(format!(
            "empty unit `[{text}]`: write the unit inside the brackets, e.g. [m]"
        ));
    }
    Ok((factor, dim))
}

/// What went wrong reading the units of an answer.
#[derive(Clone, Debug, PartialEq)]
pub enum UnitError {
    /// A unit that cannot be read (unknown, malformed, a bracket left open).
    Unreadable(String),
    /// A unit of another dimension than the answer's.
    Dimension {
        item: String,
        unit: String,
        have: Dimension,
        want: Dimension,
    },
}

/// An answer with its units converted: the text to check (each item in SI) and what was
/// converted, for the reading (`50 cm = 0.5 m`).
#[derive(Clone, Debug, PartialEq)]
pub struct Converted {
    pub(crate) text: String,
    pub(crate) notes: Vec<String>,
}

/// Converts each item of `input` (split at top-level commas) that ends in a bracketed unit
/// to SI: `v [u]` becomes `(v)*factor`. An item without a unit is taken as SI.
pub fn convert(input: &str, want: Dimension) -> Result<Converted, UnitError> {
    let mut items = Vec::new();
    let mut notes = Vec::new();
    for item in top_level_items(input) {
        let trimmed = item.trim_end();
        let Some(body) = trimmed.strip_suffix(']') else {
            if trimmed.contains('[') {
                return Err(UnitError::Unreadable(format!(
                    "`{}`: a unit goes in square brackets at the end of the number, e.g. `4.4 [rad/s]`",
                    item.trim()
                )));
            }
            items.push(item.to_string());
            continue;
        };
        let Some(open) = body.rfind('[') else {
            return Err(UnitError::Unreadable(format!(
                "`{}`: a `]` without its `[`",
                item.trim()
            )));
        };
        let (value, unit) = (&body[..open], &body[open + 1..]);
        let (factor, have) = parse_unit(unit).map_err(UnitError::Unreadable)?;
        if have != want {
            return Err(UnitError::Dimension {
                item: item.trim().to_string(),
                unit: unit.trim().to_string(),
                have,
                want,
            });
        }
        if value.trim().is_empty() {
            return Err(UnitError::Unreadable(format!(
                "`{}`: a unit needs a number before it",
                item.trim()
            )));
        }
        if factor != 1.0 {
            let number = value.split_once('=').map_or(value, |(_, v)| v);
            let shown = match numbers(number).first().copied().flatten() {
                Some(x) => format!("{}", x * factor),
                None => format!("({})·{factor}", number.trim()),
            };
            notes.push(format!("{} [{}] = {shown}", number.trim(), unit.trim()));
        }
        // A label (`ω = 4.4 [rad/s]`) stays in front of the converted value.
        match value.split_once('=') {
            Some((label, v)) => items.push(format!("{label}= ({})*{factor:e}", v.trim())),
            None => items.push(format!("({})*{factor:e}", value.trim())),
        }
    }
    Ok(Converted {
        text: items.join(","),
        notes,
    })
}

/// The verdict on an answer whose units are wrong: another dimension (incorrect, said
/// as a dimension), or a unit that cannot be read (invalid).
pub(super) fn unit_verdict(problem: &Problem, part: &Part, input: &str, e: &UnitError) -> Verdict {
    let mut v = match e {
        UnitError::Unreadable(m) => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(Code::Syntax, m.clone()));
            v
        }
        UnitError::Dimension {
            item,
            unit,
            have,
            want,
        } => {
            let mut v = verdict(problem, part, Status::Incorrect);
            v.diagnoses.push(Diagnosis::new(
                Code::Dimension,
                format!(
                    "`{item}`: the unit {unit} has dimension {have}, but this answer is {want} (e.g. {})",
                    example(*want)
                ),
            ));
            v
        }
    };
    v.reading.plain = input.to_string();
    v.reading.unicode = input.to_string();
    v
}

/// How a part's answer is written, where it is not plain: a numeric part's units in
/// brackets (`units in brackets, e.g. 1.23 [rad/s]`), a growth-rates part's λ. Shown with the
/// prompt in the REPL and on the problem sheet.
pub fn answer_form(part: &Part) -> Option<String> {
    let mut notes = Vec::new();
    if let Some(d) = part.units {
        notes.push(format!(
            "a number with its unit in square brackets, e.g. 1.23 {}",
            example(d)
        ));
    }
    if part.growth {
        notes.push("the growth rates λ > 0 (q ~ e^(λt)) of the modes that grow".to_string());
    }
    if part.omit_zero_modes {
        notes.push("the nonzero frequencies only".to_string());
    }
    (!notes.is_empty()).then(|| format!("answer: {}", notes.join("; ")))
}

/// A unit of dimension `d` to suggest.
fn example(d: Dimension) -> &'static str {
    const EXAMPLES: &[((i32, i32, i32), &str)] = &[
        ((0, 0, -1), "[rad/s] or [1/s]"),
        ((0, 0, -2), "[1/s^2]"),
        ((0, 0, 1), "[s]"),
        ((0, 1, 0), "[m]"),
        ((0, 1, -1), "[m/s]"),
        ((0, 1, -2), "[m/s^2]"),
        ((1, 0, 0), "[kg]"),
        ((1, 1, -2), "[N]"),
        ((1, 2, -2), "[J]"),
        ((1, 1, -1), "[kg m/s]"),
        ((1, 2, -1), "[J s]"),
        ((0, 0, 0), "no unit, or [rad]"),
    ];
    EXAMPLES
        .iter()
        .find(|((m, l, t), _)| Dimension::new(*m, *l, *t) == d)
        .map_or("SI units", |e| e.1)
}

/// A numeric part's verdict: what was converted is shown with the reading, and a value off
/// by more than the tolerance is told so in numbers (not "write exact constants").
pub(super) fn finish(part: &Part, input: &str, c: &Converted, v: &mut Verdict) {
    // The numbers as typed, with their units (read exactly, they would show as fractions).
    let typed = input.split_whitespace().collect::<Vec<_>>().join(" ");
    v.reading.plain = typed.clone();
    v.reading.unicode = typed;
    if !c.notes.is_empty() {
        let note = format!("converted to SI: {}", c.notes.join(", "));
        v.reading.note = Some(match v.reading.note.take() {
            Some(n) => format!("{n}; {note}"),
            None => note,
        });
    }
    // An item that is a number within 1 % of a reference number, but outside the tolerance:
    // close, not wrong (said in numbers below).
    let student = numbers(&c.text);
    let reference: Vec<Option<f64>> = part.answers.iter().flat_map(|a| numbers(a)).collect();
    let close = |x: f64| {
        reference.iter().flatten().any(|r| {
            let e = (x - r).abs() / r.abs().max(f64::MIN_POSITIVE);
            e > part.tolerance && e < 1e-2
        })
    };
    for d in &mut v.diagnoses {
        let item = match d.code {
            Code::NotEqual if student.len() == 1 => Some(0),
            Code::WrongItem => d
                .message
                .strip_prefix("item ")
                .and_then(|r| r.split(' ').next())
                .and_then(|k| k.parse::<usize>().ok())
                .and_then(|k| k.checked_sub(1)),
            _ => None,
        };
        if item
            .and_then(|k| student.get(k).copied().flatten())
            .is_some_and(close)
        {
            d.code = Code::RoundedConstant;
        }
    }
    for d in &mut v.diagnoses {
        if d.code == Code::RoundedConstant {
            d.message = format!(
                "your number is close but outside the accepted relative error ({:e}): give more significant digits, or recompute",
                part.tolerance
            );
        }
    }
}

/// The value of each item of a converted answer that is a plain number (a label before `=`
/// dropped); `None` for an item that is not.
fn numbers(text: &str) -> Vec<Option<f64>> {
    top_level_items(text)
        .into_iter()
        .map(|item| {
            let value = item.split_once('=').map_or(item, |(_, v)| v);
            let mut pool = crate::expr::Pool::new();
            let id = crate::expr::read_expr(value, &crate::expr::Context::new(), &mut pool).ok()?;
            pool.number_value(id)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn units_convert_to_si_with_their_dimension() {
        let (f, d) = parse_unit("m/s^2").unwrap();
        assert_eq!((f, d), (1.0, Dimension::new(0, 1, -2)));
        let (f, d) = parse_unit("cm").unwrap();
        assert!((f - 0.01).abs() < 1e-15);
        assert_eq!(d, Dimension::new(0, 1, 0));
        let (f, d) = parse_unit("kg m² s⁻²").unwrap();
        assert_eq!((f, d), (1.0, Dimension::energy()));
        let (f, d) = parse_unit("g*cm^2").unwrap();
        assert!((f - 1e-7).abs() < 1e-20);
        assert_eq!(d, Dimension::new(1, 2, 0));
        assert_eq!(parse_unit("1/s").unwrap().1, Dimension::new(0, 0, -1));
        assert_eq!(parse_unit("rad/s").unwrap().1, Dimension::new(0, 0, -1));
        assert!((parse_unit("deg").unwrap().0 - PI / 180.0).abs() < 1e-15);
        assert!(parse_unit("furlong").unwrap_err().contains("unknown unit"));
        assert!(parse_unit("").is_err());
        assert!(parse_unit("m^").is_err());
    }

    #[test]
    fn items_are_converted_and_dimensions_checked() {
        let per_time = Dimension::new(0, 0, -1);
        let c = convert("4.43 [rad/s]", per_time).unwrap();
        assert_eq!(c.text, "(4.43)*1e0");
        let c = convert("0, 265.8 [1/min]", per_time).unwrap();
        assert_eq!(c.text, "0,(265.8)*1.6666666666666666e-2");
        let c = convert("omega = 4.43 [rad/s]", per_time).unwrap();
        assert_eq!(c.text, "omega = (4.43)*1e0");
        assert!(matches!(
            convert("4.43 [m/s]", per_time),
            Err(UnitError::Dimension { .. })
        ));
        assert!(matches!(
            convert("4.43 [rad/s", per_time),
            Err(UnitError::Unreadable(_))
        ));
        assert!(matches!(
            convert("[rad/s]", per_time),
            Err(UnitError::Unreadable(_))
        ));
        // No unit: the number is read in SI.
        assert_eq!(convert("4.43", per_time).unwrap().text, "4.43");
    }
}
