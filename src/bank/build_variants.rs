//! The `[variants]` table of a problem file: how each varied parameter's values are declared
//! (`values = [1.5, 2, 2.5]`, or `range = [0.5, 2.0]` with `step = 0.1` or `digits = 2`, and a
//! `unit` to show), read into [`Varied`] declarations. A name that is not a parameter, a
//! declaration with both or neither of `values` and `range`, a value outside the parameter's
//! domain, a grid too large, or a `{{name}}` in the statement or a prompt that names no varied
//! parameter is a `bad-variant` finding at its line.

use super::FindingCode;
use crate::mechanics::System;
use crate::problem::variant::{MAX_VALUES, Varied, digits_grid, placeholders, step_grid};

use super::build_reader::Builder;
use super::finding::{Finding, line_of};
use super::schema::{ProblemFile, VariantSpec};

/// The longest unit text (`kg m^2`, `N/m`): a unit is a label, not prose.
const MAX_UNIT: usize = 24;

impl Builder<'_> {
    /// The file's variant declarations, in the order of their names.
    pub(super) fn variants(
        &self,
        pf: &ProblemFile,
        system: &System,
    ) -> Result<Vec<Varied>, Finding> {
        let mut out: Vec<Varied> = Vec::new();
        for (raw, spec) in &pf.variants {
            let line = line_of(self.text, spec.span().start);
            let bad = |why: String| self.fail(line, FindingCode::BadVariant, why);
            let name = crate::expr::names::normalize(raw.trim());
            let Some(param) = system.parameters.iter().find(|p| p.name == name) else {
                return Err(bad(format!(
                    "`[variants.{raw}]`: `{name}` is not a parameter; declare it under [parameters] first"
                )));
            };
            let values = values_of(&name, spec.get_ref()).map_err(bad)?;
            let pool = &system.pool;
            let lower = param.domain.lower.and_then(|e| pool.number_value(e));
            let upper = param.domain.upper.and_then(|e| pool.number_value(e));
            if let Some(v) = values
                .iter()
                .find(|&&v| lower.is_some_and(|lo| v <= lo) || upper.is_some_and(|hi| v >= hi))
            {
                return Err(bad(format!(
                    "`{name}` may take {v}, outside its domain ({}): every variant must be a possible value",
                    domain_text(lower, upper)
                )));
            }
            let unit = spec.get_ref().unit.trim().to_string();
            if unit.chars().count() > MAX_UNIT || unit.chars().any(char::is_control) {
                return Err(bad(format!(
                    "`{name}`: the unit is a short label such as \"kg\" or \"m/s^2\" (at most {MAX_UNIT} characters, one line)"
                )));
            }
            out.push(Varied {
                name,
                values,
                unit,
                line,
            });
        }
        self.check_placeholders(pf, &out)?;
        Ok(out)
    }

    /// Every `{{name}}` of the statement and the prompts names a varied parameter.
    fn check_placeholders(&self, pf: &ProblemFile, varied: &[Varied]) -> Result<(), Finding> {
        let known = |n: &str| {
            let n = crate::expr::names::normalize(n);
            varied.iter().any(|v| v.name == n)
        };
        let names: Vec<&str> = varied.iter().map(|v| v.name.as_str()).collect();
        let listed = if names.is_empty() {
            "none is declared".to_string()
        } else {
            format!("the varied ones are {}", names.join(", "))
        };
        if let Some(n) = placeholders(&pf.statement).into_iter().find(|n| !known(n)) {
            let line = self
                .text
                .lines()
                .position(|l| l.contains(&format!("{{{{{n}")))
                .map_or(self.id_line, |i| i + 1);
            return Err(self.fail(
                line,
                FindingCode::BadVariant,
                format!("the statement shows `{{{{{n}}}}}`, which is no varied parameter ({listed}); declare `[variants.{n}]`"),
            ));
        }
        for sp in &pf.parts {
            if let Some(n) = placeholders(&sp.get_ref().prompt)
                .into_iter()
                .find(|n| !known(n))
            {
                return Err(Finding {
                    part: Some(sp.get_ref().id.clone()),
                    ..self.fail(
                        line_of(self.text, sp.span().start),
                        FindingCode::BadVariant,
                        format!("the prompt shows `{{{{{n}}}}}`, which is no varied parameter ({listed}); declare `[variants.{n}]`"),
                    )
                });
            }
        }
        Ok(())
    }
}

/// The values one declaration allows, or why it allows none.
fn values_of(name: &str, spec: &VariantSpec) -> Result<Vec<f64>, String> {
    match (&spec.values, &spec.range) {
        (Some(values), None) => {
            if spec.step.is_some() || spec.digits.is_some() {
                return Err(format!(
                    "`{name}`: `step` and `digits` go with `range`, not with a list of `values`"
                ));
            }
            if values.is_empty() || values.len() > MAX_VALUES {
                return Err(format!(
                    "`{name}`: `values` lists 1 to {MAX_VALUES} numbers"
                ));
            }
            if let Some(v) = values.iter().find(|v| !v.is_finite()) {
                return Err(format!("`{name}`: the value {v} is not a finite number"));
            }
            for (i, v) in values.iter().enumerate() {
                if values[..i].contains(v) {
                    return Err(format!("`{name}`: the value {v} is listed twice"));
                }
            }
            Ok(values.clone())
        }
        (None, Some(range)) => {
            let &[lo, hi] = range.as_slice() else {
                return Err(format!("`{name}`: `range` is [low, high], two numbers"));
            };
            if !(lo.is_finite() && hi.is_finite() && lo < hi) {
                return Err(format!(
                    "`{name}`: range [{lo}, {hi}] needs finite low < high"
                ));
            }
            match (spec.step, spec.digits) {
                (Some(step), None) => step_grid(lo, hi, step).ok_or_else(|| {
                    format!(
                        "`{name}`: step {step} over [{lo}, {hi}] is not a grid of 1 to {MAX_VALUES} values (a positive step of at most 9 decimals)"
                    )
                }),
                (None, Some(d)) => digits_grid(lo, hi, d).ok_or_else(|| {
                    format!(
                        "`{name}`: {d} significant digits over [{lo}, {hi}] is not a grid of 1 to {MAX_VALUES} values (a positive range, 1 to 9 digits)"
                    )
                }),
                _ => Err(format!(
                    "`{name}`: a range needs exactly one of `step` (a grid, `step = 0.1`) or `digits` (rounded to significant digits, `digits = 2`)"
                )),
            }
        }
        _ => Err(format!(
            "`{name}`: give either `values = [...]` or `range = [low, high]` with `step` or `digits`"
        )),
    }
}

/// `> 0`, `< 1`, `between 0 and 1`.
fn domain_text(lower: Option<f64>, upper: Option<f64>) -> String {
    match (lower, upper) {
        (Some(a), Some(b)) => format!("between {a} and {b}"),
        (Some(a), None) => format!("> {a}"),
        (None, Some(b)) => format!("< {b}"),
        (None, None) => "any".into(),
    }
}
