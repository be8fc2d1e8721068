//! `:read`, `:derive` and `:modes`: reading an expression and analysing the open problem's
//! system or a typed Lagrangian, as analysis responses.

use super::Session;
use super::replies::{no_problem, visible};
use crate::report::{self, ModesOptions, ReadOptions, reading};
use crate::tutor::response::{AnalysisReply, AnalysisReport, Response};

impl Session {
    /// `:read EXPR`: read with the open problem's coordinates and parameter dimensions (or
    /// with every name open when no problem is).
    pub(super) fn read(&self, expr: &str) -> Response {
        let mut opts = ReadOptions::default();
        if let Some(p) = self.problem() {
            opts.coords = p
                .system
                .coordinates
                .iter()
                .map(|c| c.name.clone())
                .collect();
            // Every symbol's dimension as the problem declares it (angles: none).
            let names = p.system.coordinates.iter().map(|c| &c.name);
            let names = names.chain(p.system.parameters.iter().map(|q| &q.name));
            opts.dims = names
                .filter_map(|n| Some((n.clone(), p.dims.get(n)?)))
                .collect();
        }
        match reading(expr, &opts) {
            Ok(r) => Response::Analysis(AnalysisReply {
                of: "read".to_string(),
                report: AnalysisReport::Read(Box::new(r)),
                note: None,
            }),
            Err(e) => Response::error("syntax", format!("`{}`: {e}", visible(expr)), None),
        }
    }

    /// `:derive` or `:modes` on the open problem, marking the unsolved parts whose answers it
    /// shows revealed (as `:solution` does), and saying so in the note.
    pub(super) fn analyse_and_reveal(&mut self, modes: bool) -> Response {
        let mut r = self.analyse(modes);
        let (Response::Analysis(a), Some(p)) = (&mut r, self.problem()) else {
            return r;
        };
        let pid = p.id.clone();
        let shown: Vec<String> = p
            .parts
            .iter()
            .filter(|q| reveals(q, modes) && !self.progress.is_solved(&pid, &q.id))
            .map(|q| q.id.clone())
            .collect();
        if shown.is_empty() {
            return r;
        }
        for id in &shown {
            self.progress.part_mut(&pid, id).revealed = true;
        }
        let said = format!(
            "this shows the answer to {} (marked revealed, as `:solution` does)",
            shown.join(", ")
        );
        a.note = Some(match a.note.take() {
            Some(n) => format!("{n}\n{said}"),
            None => said,
        });
        r
    }

    /// `:derive` or `:modes` on the open problem's system.
    fn analyse(&self, modes: bool) -> Response {
        let Some(p) = self.problem() else {
            return no_problem();
        };
        // Numeric modes need numbers: each parameter at the middle of its sampling range.
        let params: Vec<(String, String)> = p
            .system
            .parameters
            .iter()
            .map(|q| (q.name.clone(), format!("{}", (q.range.0 + q.range.1) / 2.0)))
            .collect();
        let note = (modes && !params.is_empty()).then(|| {
            let shown: Vec<String> = params.iter().map(|(n, v)| format!("{n} = {v}")).collect();
            format!(
                "parameters at the middle of their ranges: {}",
                shown.join(", ")
            )
        });
        let opts = ModesOptions {
            params,
            ..ModesOptions::default()
        };
        analysis_response(&p.system, modes, &opts, note)
    }
}

/// Whether `:derive` (or, with `modes`, `:modes`) prints the answer to `part`: the
/// Lagrangian, momenta, equations of motion, energy function and cyclic coordinates; the
/// equilibria, frequencies and steady motions.
fn reveals(part: &crate::problem::Part, modes: bool) -> bool {
    use crate::problem::{PartKind as K, Quantity as Q};
    if modes {
        matches!(part.kind, K::Equilibria | K::Frequencies | K::SteadyMotion)
    } else {
        matches!(part.kind, K::Lagrangian | K::Equation | K::Equations)
            || matches!(
                part.quantity,
                Q::Lagrangian | Q::Momentum(_) | Q::EnergyFunction | Q::Cyclic
            )
    }
}

/// `:derive L` / `:modes L` on a typed Lagrangian, with optional `--coords q1,q2` (else the
/// names that appear with a time derivative) and, for modes, `--params m=1,k=2`.
pub(super) fn analyse_typed(text: &str, modes: bool) -> Response {
    let (l, coords, params) = split_flags(text);
    let coords: Vec<String> = match coords {
        Some(c) => c
            .split(',')
            .filter(|x| !x.trim().is_empty())
            .map(crate::expr::spelled)
            .collect(),
        None => moving_names(l),
    };
    if coords.is_empty() {
        return Response::error(
            "no-coordinates",
            "no coordinate: write the velocities with a prime (x') or add --coords x,y",
            None,
        );
    }
    let names: Vec<&str> = coords.iter().map(String::as_str).collect();
    let sys = match crate::mechanics::System::from_lagrangian(l, &names) {
        Ok(sys) => sys,
        Err(e) => return Response::error(e.code(), e.to_string(), None),
    };
    let mut opts = ModesOptions {
        default_range: Some((-10.0, 10.0)),
        ..ModesOptions::default()
    };
    if modes {
        match params.map(report::modes::assignments).transpose() {
            Ok(p) => opts.params = p.unwrap_or_default(),
            Err(e) => return Response::error("bad-params", e.to_string(), None),
        }
    }
    analysis_response(&sys, modes, &opts, None)
}

/// The derivation or the modes of `sys` as an analysis response (or why not).
fn analysis_response(
    sys: &crate::mechanics::System,
    modes: bool,
    opts: &ModesOptions,
    note: Option<String>,
) -> Response {
    let report = if modes {
        report::modes(sys, opts)
            .map(|r| AnalysisReport::Modes(Box::new(r)))
            .map_err(|e| e.to_string())
    } else {
        report::derivation(sys)
            .map(|r| AnalysisReport::Derive(Box::new(r)))
            .map_err(|e| e.to_string())
    };
    match report {
        Ok(report) => Response::Analysis(AnalysisReply {
            of: if modes { "modes" } else { "derive" }.to_string(),
            report,
            note,
        }),
        Err(e) => Response::error("analysis", e, None),
    }
}

/// The Lagrangian and the values of `--coords` and `--params` in `:derive L --coords x`.
fn split_flags(text: &str) -> (&str, Option<&str>, Option<&str>) {
    let mut l = text;
    let mut coords = None;
    let mut params = None;
    // Flags come after the Lagrangian, in any order.
    while let Some(i) = l.rfind(" --") {
        let (head, flag) = (&l[..i], &l[i + 3..]);
        match flag.split_once(char::is_whitespace) {
            Some(("coords", v)) => coords = Some(v.trim()),
            Some(("params", v)) => params = Some(v.trim()),
            _ => break,
        }
        l = head;
    }
    (l.trim(), coords, params)
}

/// The names that appear with a time derivative in `l` (its coordinates, by the notation).
fn moving_names(l: &str) -> Vec<String> {
    let mut pool = crate::expr::Pool::new();
    let Ok(e) = crate::expr::read_expr(l, &crate::expr::Context::open(), &mut pool) else {
        return Vec::new();
    };
    let mut names: Vec<String> = pool
        .variables(e)
        .into_iter()
        .filter(|v| v.1 >= 1)
        .map(|v| pool.name(v.0).to_string())
        .collect();
    crate::sort::sort(&mut names);
    names.dedup();
    names
}
