//! `lagrange modes`: equilibria, their stability, frequencies and mode shapes; with
//! `--symbolic`, the characteristic polynomial and ω² in closed form.

use std::fmt::Write as _;
use std::process::ExitCode;

use clap::Args;
use colored::Colorize;
use serde_json::{Value, json};

use super::system_args::{SystemArgs, report};
use lagrange::expr::{Id, Program};
use lagrange::mechanics::equilibria::Stability;
use lagrange::mechanics::modes::Modes;
use lagrange::mechanics::{MechError, System};

#[derive(Args, Debug)]
pub struct ModesArgs {
    #[command(flatten)]
    system: SystemArgs,
    /// Parameter values, e.g. "m=1, l=2, g=9.81"; a value may be an expression in other
    /// parameters ("m1=m, l2=l"), which then stay symbolic.
    #[arg(long, default_value = "")]
    params: String,
    /// Only this equilibrium, e.g. "theta1=0, theta2=0" (values may be expressions).
    #[arg(long)]
    at: Option<String>,
    /// Search range of non-periodic coordinates, e.g. "x=-50:50" (default −10:10).
    #[arg(long)]
    range: Vec<String>,
    /// Also the characteristic polynomial and ω² in closed form (needs --at).
    #[arg(long)]
    symbolic: bool,
    /// JSON output.
    #[arg(long)]
    json: bool,
}

fn pairs(s: &str) -> Result<Vec<(String, String)>, MechError> {
    s.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .map(|item| {
            item.split_once('=')
                .map(|(a, b)| (a.trim().to_string(), b.trim().to_string()))
                .ok_or_else(|| MechError::Invalid(format!("`{item}` should look like name=value")))
        })
        .collect()
}

pub fn run(
    args: &ModesArgs,
    problems: Option<&std::path::Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    match modes_report(args, problems) {
        Ok(text) => {
            out.push_str(&text);
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => Ok(report(&e, color)),
    }
}

/// The value of a constant expression.
fn constant(sys: &System, e: Id) -> Option<f64> {
    if !sys.pool.variables(e).is_empty() {
        return None;
    }
    Program::compile(&sys.pool, &[e], &[])
        .ok()?
        .eval(&[])
        .ok()
        .map(|v| v[0])
}

fn modes_report(args: &ModesArgs, problems: Option<&std::path::Path>) -> Result<String, MechError> {
    let mut sys = args.system.build(problems)?;
    if args.system.problem.is_none() {
        // A typed Lagrangian has no ranges of its own; a problem's are kept.
        for c in sys.coordinates.iter_mut() {
            if !c.periodic {
                c.range = (-10.0, 10.0);
            }
        }
    }
    for r in &args.range {
        let (name, span) = r
            .split_once('=')
            .ok_or_else(|| MechError::Invalid(format!("--range `{r}` should look like x=-5:5")))?;
        let (lo, hi) = span
            .split_once(':')
            .and_then(|(a, b)| Some((a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?)))
            .filter(|(a, b)| a < b)
            .ok_or_else(|| MechError::Invalid(format!("--range `{r}` should look like x=-5:5")))?;
        let c = sys
            .coordinates
            .iter_mut()
            .find(|c| c.name == name.trim())
            .ok_or_else(|| MechError::UnknownCoordinate {
                name: name.trim().into(),
            })?;
        c.range = (lo, hi);
    }
    sys.substitute_parameters(&pairs(&args.params)?)?;
    let d = sys.derive()?;
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let labels: Vec<String> = sys
        .coordinates
        .clone()
        .iter()
        .map(|c| {
            let v = sys.pool.var(c.sym, 0);
            sys.pool.unicode(v)
        })
        .collect();
    // --at: one expression per coordinate.
    let at: Option<Vec<Id>> = match &args.at {
        None => None,
        Some(text) => {
            let given = pairs(text)?;
            let ctx = sys.open_context();
            let mut point = vec![None; names.len()];
            for (name, v) in given {
                let k = names
                    .iter()
                    .position(|n| *n == lagrange::expr::names::normalize(&name))
                    .ok_or(MechError::UnknownCoordinate { name: name.clone() })?;
                point[k] = Some(sys.read(&v, &format!("--at {name}"), &ctx)?);
            }
            let mut ids = Vec::with_capacity(names.len());
            for (k, p) in point.into_iter().enumerate() {
                ids.push(p.ok_or_else(|| {
                    MechError::Invalid(format!("--at gives no value for `{}`", names[k]))
                })?);
            }
            Some(ids)
        }
    };
    let symbolic_params: Vec<String> = sys.parameters.iter().map(|p| p.name.clone()).collect();
    let mut results: Vec<Modes> = Vec::new();
    let mut continuum = false;
    if symbolic_params.is_empty() {
        match &at {
            Some(ids) => {
                let q: Vec<f64> = ids
                    .iter()
                    .map(|&e| {
                        constant(&sys, e).ok_or(MechError::Invalid(
                            "--at values must be numbers here".into(),
                        ))
                    })
                    .collect::<Result<_, _>>()?;
                results.push(sys.modes_at(&d, &[], &q)?);
            }
            None => {
                let eq = sys.equilibria(&d, &[])?;
                continuum = eq.continuum;
                if !continuum && eq.points.is_empty() {
                    return Err(MechError::NoEquilibrium);
                }
                for (q, _) in eq.points {
                    results.push(sys.modes_at(&d, &[], &q)?);
                }
            }
        }
    } else if !args.symbolic {
        return Err(MechError::MissingValue {
            name: symbolic_params[0].clone(),
        });
    }
    let symbolic = match (&at, args.symbolic) {
        (Some(ids), true) => Some(sys.symbolic_modes(&d, ids)?),
        (None, true) => {
            return Err(MechError::Invalid(
                "--symbolic needs the equilibrium, given with --at".into(),
            ));
        }
        _ => None,
    };
    let pool = &sys.pool;
    if args.json {
        let eqs: Vec<Value> = results
            .iter()
            .map(|m| {
                let point: serde_json::Map<String, Value> = names
                    .iter()
                    .zip(&m.point)
                    .map(|(n, v)| (n.clone(), json!(v)))
                    .collect();
                json!({
                    "point": point,
                    "stable": m.stability == Stability::Stable,
                    "stability": m.stability.name(),
                    "frequencies": m.frequencies,
                    "growth_rates": m.growth_rates,
                    "omega_squared": m.modes.iter().map(|x| x.omega_squared).collect::<Vec<_>>(),
                    "modes": m.modes.iter().map(|x| x.shape.clone()).collect::<Vec<_>>(),
                    "gyroscopic": m.gyroscopic,
                })
            })
            .collect();
        let mut v = json!({ "equilibria": eqs, "continuum": continuum });
        if let Some(s) = &symbolic {
            v["characteristic_polynomial"] = json!(pool.plain(s.characteristic));
            v["omega_squared"] = json!(
                s.omega_squared
                    .iter()
                    .map(|&w| pool.plain(w))
                    .collect::<Vec<_>>()
            );
        }
        return Ok(format!(
            "{}\n",
            serde_json::to_string_pretty(&v).unwrap_or_default()
        ));
    }
    let mut o = String::new();
    if continuum {
        let _ = writeln!(
            o,
            "every point in the search range is an equilibrium: they are not isolated (neutral)"
        );
    }
    for m in &results {
        let point: Vec<String> = labels
            .iter()
            .zip(&m.point)
            .map(|(n, v)| format!("{n} = {}", fmt_num(*v)))
            .collect();
        let st = match m.stability {
            Stability::Stable => "stable".green(),
            Stability::Unstable => "unstable".red(),
            Stability::Marginal => "marginal".yellow(),
        };
        let _ = writeln!(o, "{} {}: {st}", "equilibrium".bold(), point.join(", "));
        if m.gyroscopic {
            let _ = writeln!(
                o,
                "  velocity-dependent terms survive here: solved as a first-order system"
            );
        }
        if !m.frequencies.is_empty() {
            let f: Vec<String> = m.frequencies.iter().map(|x| fmt_num(*x)).collect();
            let _ = writeln!(o, "  frequencies ω: {}", f.join(", "));
        }
        if !m.growth_rates.is_empty() {
            let f: Vec<String> = m.growth_rates.iter().map(|x| fmt_num(*x)).collect();
            let _ = writeln!(o, "  growth rates: {}", f.join(", "));
        }
        let desc = m.describe(&labels);
        for (k, mode) in m.modes.iter().enumerate() {
            let shape: Vec<String> = mode.shape.iter().map(|x| fmt_num(*x)).collect();
            let _ = writeln!(
                o,
                "  mode {}: ω² = {}, shape ({}){}",
                k + 1,
                fmt_num(mode.omega_squared),
                shape.join(", "),
                if desc[k].is_empty() {
                    String::new()
                } else {
                    format!(" — {}", desc[k])
                }
            );
        }
    }
    if let Some(s) = &symbolic {
        let _ = writeln!(
            o,
            "{} det(K − ω²M) = {}",
            "characteristic polynomial:".bold(),
            pool.unicode(s.characteristic)
        );
        for &w in &s.omega_squared {
            let _ = writeln!(o, "ω² = {}", pool.unicode(w).green());
        }
        if s.omega_squared.is_empty() {
            let _ = writeln!(
                o,
                "(closed-form roots are given for one or two coordinates)"
            );
        }
    }
    Ok(o)
}

fn fmt_num(x: f64) -> String {
    lagrange::check::compare::fmt_value(x)
}
