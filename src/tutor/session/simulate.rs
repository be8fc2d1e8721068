//! `:simulate [--init …] [--t-end T] [--params …]`: the open problem's motion integrated
//! with DOP853 (as `lagrange simulate` does), as an analysis response whose face draws q(t)
//! as a terminal chart under the summary. It starts from the problem's suggested numbers
//! (parameter values, start, end time) where the user gives none; a parameter still without
//! a value is named in the reply. The axes carry the problem's SI units.

use super::Session;
use super::replies::no_problem;
use crate::problem::SimulationDefaults;
use crate::report::SimulationOptions;
use crate::report::simulation::numbers;
use crate::report::simulation::{missing_parameters, simulation};
use crate::report::units::AxisUnits;
use crate::simulate::Method;
use crate::tutor::response::{AnalysisReply, AnalysisReport, Response};

/// The end time when `--t-end` is not given.
const DEFAULT_T_END: f64 = 10.0;
/// The longest end time `:simulate` accepts (the REPL waits for the answer).
const MAX_T_END: f64 = 1000.0;
/// Points of the chart.
const SAMPLES: usize = 400;

impl Session {
    /// `:simulate` on the open problem.
    pub(super) fn simulate(&self, args: &str) -> Response {
        let Some(p) = self.problem() else {
            return no_problem();
        };
        let opts = match options(args, &p.simulation) {
            Ok(o) => o,
            Err(message) => {
                // The usage goes with the message (the did-you-mean slot holds names only).
                let message = if message.contains(USAGE) {
                    message
                } else {
                    format!("{message}; usage: {USAGE}")
                };
                return Response::error("bad-simulate", message, None);
            }
        };
        let missing = missing_parameters(&p.system, &opts.params);
        if !missing.is_empty() {
            let example: Vec<String> = missing.iter().map(|n| format!("{n}=…")).collect();
            let message = format!(
                "`{}` suggests no value for some parameters: give {} with --params \"{}\"",
                p.id,
                missing
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", "),
                example.join(", ")
            );
            return Response::error("missing-parameters", message, None);
        }
        let mut sys = p.system.clone();
        match simulation(&mut sys, &opts) {
            Ok(mut report) => {
                report.units = AxisUnits::of(p);
                Response::Analysis(AnalysisReply {
                    of: "simulate".to_string(),
                    report: AnalysisReport::Simulate(Box::new(report)),
                    note: None,
                })
            }
            // The did-you-mean slot holds a name only; the help goes with the message.
            Err(e) => Response::error(e.code(), format!("{e}: {}", e.help()), None),
        }
    }
}

/// The options from `--init`, `--t-end` and `--params` (values may be quoted), over the
/// problem's suggestions.
fn options(args: &str, defaults: &SimulationDefaults) -> Result<SimulationOptions, String> {
    let (mut params, mut init, mut t_end) = (Vec::new(), None, None);
    let mut opts = SimulationOptions {
        params: Vec::new(),
        init: Vec::new(),
        t_end: DEFAULT_T_END,
        method: Method::Dop853,
        rtol: 1e-10,
        atol: 1e-10,
        dt: None,
        report_at: Vec::new(),
        samples: SAMPLES,
    };
    let text = format!(" {args}");
    let mut pieces = text.split(" --");
    if let Some(head) = pieces.next().map(str::trim)
        && !head.is_empty()
    {
        return Err(format!("`{head}` is not a flag: {USAGE}"));
    }
    for piece in pieces {
        // The command line's grammar (clap's): `--flag value` or `--flag=value`, the value
        // optionally quoted.
        let (flag, value) = piece
            .split_once(|c: char| c.is_whitespace() || c == '=')
            .unwrap_or((piece, ""));
        let value = value.trim();
        let value = (value.strip_prefix('"').and_then(|v| v.strip_suffix('"')))
            .or_else(|| value.strip_prefix('\'').and_then(|v| v.strip_suffix('\'')))
            .unwrap_or(value)
            .trim();
        match flag {
            "init" => init = Some(numbers("--init", value).map_err(|e| e.to_string())?),
            "params" => params = numbers("--params", value).map_err(|e| e.to_string())?,
            "t-end" => {
                t_end = value
                    .parse::<f64>()
                    .ok()
                    .filter(|t| t.is_finite() && *t > 0.0 && *t <= MAX_T_END)
                    .map(Some)
                    .ok_or_else(|| {
                        format!("--t-end must be a number in (0, {MAX_T_END}], not `{value}`")
                    })?;
            }
            other => return Err(format!("there is no flag `--{other}` here: {USAGE}")),
        }
    }
    let chosen = defaults.complete(params, init, t_end);
    opts.params = chosen.params;
    opts.init = chosen.init;
    opts.t_end = chosen.t_end.unwrap_or(DEFAULT_T_END).min(MAX_T_END);
    Ok(opts)
}

const USAGE: &str = ":simulate [--init theta=1, theta'=0] [--t-end 10] [--params m=1, g=9.81]";

#[cfg(test)]
mod tests {
    use crate::problem::SimulationDefaults;

    fn options(args: &str) -> Result<crate::report::SimulationOptions, String> {
        super::options(args, &SimulationDefaults::default())
    }

    #[test]
    fn the_problem_suggests_what_is_not_given() {
        let d = SimulationDefaults {
            params: vec![("g".into(), 9.81), ("m".into(), 1.0)],
            init: vec![("theta".into(), 1.0)],
            t_end: Some(5.0),
        };
        let o = super::options("--params m=2", &d).unwrap();
        assert_eq!(o.params, vec![("m".into(), 2.0), ("g".into(), 9.81)]);
        assert_eq!(
            (o.init.clone(), o.t_end),
            (vec![("theta".into(), 1.0)], 5.0)
        );
        let o = super::options("--init theta'=1 --t-end 2", &d).unwrap();
        assert_eq!((o.init, o.t_end), (vec![("theta'".into(), 1.0)], 2.0));
    }

    #[test]
    fn flags_take_the_command_lines_grammar() {
        // `--flag=value` as clap reads it, and single or double quotes.
        let a = options("--t-end=5 --init=theta=1, theta'=0 --params 'm=2, g=9.81'").unwrap();
        let b = options("--t-end 5 --init \"theta=1, theta'=0\" --params m=2, g=9.81").unwrap();
        assert_eq!((a.t_end, &a.init, &a.params), (5.0, &b.init, &b.params));
        assert_eq!(a.init[0], ("theta".to_string(), 1.0));
        assert!(options("--t-end=-1").is_err());
    }

    #[test]
    fn flags_are_read_in_any_order() {
        let o = options("--t-end 3 --init theta=1, theta'=-0.5 --params \"m=1, g=9.81\"").unwrap();
        assert_eq!(o.t_end, 3.0);
        assert_eq!(o.init, vec![("theta".into(), 1.0), ("theta'".into(), -0.5)]);
        assert_eq!(o.params.len(), 2);
        assert!(options("--t-end 0").is_err());
        assert!(options("--t-end 1e9").is_err());
        assert!(options("--dt 1").unwrap_err().contains("no flag `--dt`"));
        assert!(options("theta=1").is_err());
        assert_eq!(options("").unwrap().t_end, 10.0);
    }
}
