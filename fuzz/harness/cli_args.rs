//! Target `cli-args`: the values of the command-line arguments (`read`'s input, `--coords`,
//! `--dims`, `--diff`; `derive`'s and `modes`' `--lagrangian`, `--kinetic`/`--potential`,
//! `--force`, `--constraint`, `--params`, `--at`, `--range`, `--symbolic`, a problem id;
//! `simulate`'s `--init`, `--t-end`, `--method`, `--dt`, `--rtol`)
//! through the library calls `src/cli/*.rs` makes, in process, with every report and error
//! rendered as the CLI renders it. Oracle: no panic, no slow input, no raw control
//! character in what is shown.

use serde::{Deserialize, Serialize};

use lagrange::bank::embedded;
use lagrange::diagnostic::{Diagnostic, render, render_parse_error, render_plain};
use lagrange::expr::{Dimension, Style};
use lagrange::mechanics::{MechError, System};
use lagrange::report::modes::assignments;
use lagrange::report::{
    ModesOptions, Plain, ReadOptions, SimulationOptions, derivation, modes, reading, simulation,
};
use lagrange::simulate::Method;

use super::inputs::{self, Rng, Vocab, below, chance, pick};
use super::no_raw_controls;

/// One command line's values.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
#[serde(default)]
pub struct Args {
    /// `read`, `derive` or `modes`.
    pub command: String,
    /// `read`'s input.
    pub input: String,
    pub problem: Option<String>,
    pub lagrangian: Option<String>,
    pub kinetic: Option<String>,
    pub potential: Option<String>,
    pub coords: String,
    pub force: Option<String>,
    pub constraint: Vec<String>,
    pub dims: String,
    pub strict: bool,
    pub diff: Option<String>,
    pub dt: bool,
    pub params: String,
    pub at: Option<String>,
    pub range: Vec<String>,
    pub symbolic: bool,
    /// `simulate`'s initial values, end time, method (`dop853`, `rk4`, `gauss`), step and
    /// tolerance.
    pub init: String,
    pub t_end: f64,
    pub method: String,
    pub step: Option<f64>,
    pub rtol: f64,
}

/// Lagrangians people type, and ones that blew up before.
const LAGRANGIANS: &[&str] = &[
    "1/2 m l^2 theta'^2 + m g l cos(theta)",
    "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)",
    "1/2 m x'^2 - 1/2 k x^2",
    "1/2*1e-9*x'^2 - 1/2*x^2",
    "1/2 m x'^2 + 1/2 m y'^2 - m g y",
    "1/2*(m1+m2)*x'^2 + (m1-m2)*g*x",
    "1/2 m (r'^2 + r^2 theta'^2) + k/r",
    "1/2 m x'^2 - exp(1000) x^2",
];

/// Systems with matching coordinates and parameter values.
const COHERENT: &[(&str, &str, &str)] = &[
    (
        "1/2 m l^2 theta'^2 + m g l cos(theta)",
        "theta",
        "m=1, l=1, g=9.81",
    ),
    (
        "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)",
        "theta1,theta2",
        "m1=1, m2=1, l1=1, l2=1, g=9.81",
    ),
    ("1/2 m x'^2 - 1/2 k x^2", "x", "k=1, m=1"),
    ("1/2 m (r'^2 + r^2 theta'^2) + k/r", "r,theta", "k=1, m=1"),
    ("1/2 m x'^2 - exp(x)", "x", "m=1"),
];

/// Coordinate lists, sensible and not.
const COORDS: &[&str] = &[
    "theta",
    "x",
    "theta1,theta2",
    "x,y",
    "r,theta",
    "x,x",
    "t",
    "sin",
    "",
    "θ",
    "x,,y",
    "theta1,theta2,theta3",
];

/// `--params` values.
const PARAMS: &[&str] = &[
    "m=1, l=1, g=9.81",
    "m1=1, m2=1, l1=1, l2=1, g=9.81",
    "m1=m, m2=m, l1=l, l2=l",
    "g=0/0",
    "m=1e300, l=1, g=9.81",
    "m=9.1e-31, k=1e-12",
    "k=1, m=1",
    "m=1, g=1e-10, l=1",
    "m",
    "",
];

/// One command line: `read` (30%), `derive` (35%) or `modes` (35%).
pub fn generate(r: &mut Rng) -> Vec<u8> {
    let coords = pick(r, COORDS).to_string();
    let v = Vocab {
        coords: coords.split(',').map(String::from).collect(),
        params: ["m", "g", "l", "k", "m1", "R"].map(String::from).to_vec(),
    };
    let mut a = Args {
        coords,
        ..Args::default()
    };
    match below(r, 20) {
        0..=5 => {
            a.command = "read".into();
            a.input = text(r, &v);
            a.dims = pick(
                r,
                &["", "m=M, l=L, g=L T^-2", "m=M", "x=L", "m=M^1e9", "g=L T^"],
            )
            .to_string();
            a.strict = chance(r, 0.3);
            a.diff = chance(r, 0.4).then(|| text(r, &v));
            a.dt = chance(r, 0.5);
        }
        17..=19 => simulation_args(r, &v, &mut a),
        k => {
            a.command = if k < 13 { "derive" } else { "modes" }.into();
            system(r, &v, &mut a);
            a.params = if chance(r, 0.7) {
                pick(r, PARAMS).to_string()
            } else {
                format!("{}={}", pick(r, &v.params), text(r, &v))
            };
            a.at = chance(r, 0.3).then(|| {
                let q = v.coords.first().cloned().unwrap_or_default();
                format!("{q}={}", pick(r, &["0", "pi", "1e308", "0/0", "x'", "m"]))
            });
            if chance(r, 0.3) {
                let q = v.coords.first().cloned().unwrap_or_default();
                let span = pick(
                    r,
                    &[
                        "-5:5",
                        "-1e308:1e308",
                        "-inf:inf",
                        "5:-5",
                        "nan:1",
                        "0:1e-300",
                    ],
                );
                a.range.push(format!("{q}={span}"));
            }
            a.symbolic = chance(r, 0.3);
        }
    }
    serde_json::to_vec_pretty(&a).expect("arguments serialize")
}

/// `simulate`: a system, parameters, a start, an end time and a method, sensible and not.
fn simulation_args(r: &mut Rng, v: &Vocab, a: &mut Args) {
    a.command = "simulate".into();
    system(r, v, a);
    a.params = pick(r, PARAMS).to_string();
    if chance(r, 0.5) {
        // A coherent system, so that the integration itself runs.
        let (l, q, p) = *pick(r, COHERENT);
        (a.problem, a.kinetic, a.potential) = (None, None, None);
        a.lagrangian = Some(l.to_string());
        a.coords = q.to_string();
        a.params = p.to_string();
    }
    let q = v.coords.first().cloned().unwrap_or_default();
    a.init = pick(
        r,
        &[
            String::new(),
            format!("{q}=1"),
            format!("{q}=3.1, {q}'=2"),
            format!("{q}=1e300"),
            format!("{q}'=1e10"),
            format!("{q}=1, {q}=2"),
            "nope=1".to_string(),
        ],
    )
    .clone();
    a.t_end = *pick(r, &[1.0, 0.1, 5.0, 0.0, -1.0, 1e9, 1e-300]);
    a.method = pick(r, &["dop853", "rk4", "gauss"]).to_string();
    a.step = Some(*pick(r, &[1e-2, 1e-3, 0.0, -1.0, 1e-12, 2.0]));
    a.rtol = *pick(r, &[1e-10, 1e-6, 0.0, 1e-20, 1.0]);
}

/// An input text: grammar, a known Lagrangian mutated, a soup or a blow-up.
fn text(r: &mut Rng, v: &Vocab) -> String {
    match below(r, 10) {
        0..=3 => {
            let d = 1 + below(r, 5) as u32;
            inputs::expr(r, v, d)
        }
        4..=6 => {
            let l = *pick(r, LAGRANGIANS);
            let m = inputs::mutate(r, l.as_bytes());
            String::from_utf8_lossy(&m).into_owned()
        }
        7 | 8 => {
            let n = 1 + below(r, 30);
            inputs::soup(r, n)
        }
        _ => inputs::blowup(r, v),
    }
}

/// The system arguments: a problem id, a Lagrangian, or T and V; forces and constraints.
fn system(r: &mut Rng, v: &Vocab, a: &mut Args) {
    match below(r, 10) {
        0 => {
            let ids: Vec<&str> = embedded::FILES
                .iter()
                .map(|(n, _)| n.trim_end_matches(".toml"))
                .collect();
            a.problem = Some(pick(r, &ids).to_string());
        }
        1..=4 => a.lagrangian = Some(pick(r, LAGRANGIANS).to_string()),
        5 => {
            a.kinetic = Some(text(r, v));
            a.potential = Some(text(r, v));
        }
        _ => a.lagrangian = Some(text(r, v)),
    }
    if chance(r, 0.15) {
        a.force = Some(pick(r, &["-b*x'", "-b*theta'", "0; 0", "x'''", "1/0"]).to_string());
    }
    if chance(r, 0.15) {
        let c = pick(
            r,
            &[
                "x^2 + y^2 = l^2",
                "x' - R*theta' = 0",
                "x = x",
                "0 = 0",
                "1/0",
            ],
        );
        a.constraint.push(c.to_string());
    }
}

/// Runs the command's library calls and renders what the CLI would print.
pub fn execute(input: &[u8]) -> Result<(), String> {
    let a: Args =
        serde_json::from_slice(input).map_err(|e| format!("corpus: unreadable args: {e}"))?;
    match a.command.as_str() {
        "read" => read(&a),
        "derive" | "modes" => match build(&a) {
            Err(e) => no_raw_controls(&e, "error"),
            Ok(sys) if a.command == "derive" => match derivation(&sys) {
                Ok(rep) => {
                    no_raw_controls(&rep.render(Style::Unicode, &Plain), "derivation")?;
                    let _latex = rep.render(Style::Latex, &Plain);
                    serde_json::to_string(&rep)
                        .map(drop)
                        .map_err(|e| format!("json: {e}"))
                }
                Err(e) => no_raw_controls(&mech(&e), "error"),
            },
            Ok(sys) => modes_of(&a, &sys),
        },
        "simulate" => match build(&a) {
            Err(e) => no_raw_controls(&e, "error"),
            Ok(mut sys) => simulate(&a, &mut sys),
        },
        other => Err(format!("corpus: no command `{other}`")),
    }
}

/// `lagrange simulate`, as `src/cli/simulate.rs` does it (numbers that do not parse are
/// usage errors there, skipped here).
fn simulate(a: &Args, sys: &mut System) -> Result<(), String> {
    let numbers = |text: &str| -> Option<Vec<(String, f64)>> {
        let pairs = assignments(text).ok()?;
        pairs
            .into_iter()
            .map(|(n, v)| {
                v.parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .map(|v| (n, v))
            })
            .collect()
    };
    let (Some(params), Some(init)) = (numbers(&a.params), numbers(&a.init)) else {
        return Ok(());
    };
    let method = match a.method.as_str() {
        "rk4" => Method::Rk4,
        "gauss" => Method::Gauss,
        _ => Method::Dop853,
    };
    let opts = SimulationOptions {
        params,
        init,
        t_end: a.t_end,
        method,
        rtol: a.rtol,
        atol: a.rtol,
        dt: a.step,
        report_at: vec![a.t_end / 2.0],
        samples: 200,
    };
    match simulation(sys, &opts) {
        Ok(rep) => {
            no_raw_controls(&rep.render(&Plain), "simulation")?;
            let _ = rep.csv();
            serde_json::to_string(&rep)
                .map(drop)
                .map_err(|e| format!("json: {e}"))
        }
        Err(e) => no_raw_controls(&format!("{e} / {}", e.help()), "error"),
    }
}

/// `lagrange read`, as `src/cli/read.rs` does it.
fn read(a: &Args) -> Result<(), String> {
    let mut dims = Vec::new();
    for item in list(&a.dims) {
        let Some((name, d)) = item.split_once('=') else {
            return Ok(());
        };
        match Dimension::parse(d) {
            Ok(d) => dims.push((name.trim().to_string(), d)),
            Err(_) => return Ok(()),
        }
    }
    let opts = ReadOptions {
        coords: list(&a.coords),
        dims,
        strict: a.strict,
        diff: a.diff.clone(),
        dt: a.dt,
    };
    match reading(&a.input, &opts) {
        Ok(rep) => {
            no_raw_controls(&rep.render(&Plain, "give dimensions"), "reading")?;
            let _failed = rep.failed();
            serde_json::to_string(&rep)
                .map(drop)
                .map_err(|e| format!("json: {e}"))
        }
        Err(e) => no_raw_controls(&render_parse_error("input", &a.input, &e, false), "error"),
    }
}

/// A comma-separated list, trimmed, without empty items (the CLI's `split_list`).
fn list(s: &str) -> Vec<String> {
    s.split(',')
        .map(|x| x.trim().to_string())
        .filter(|x| !x.is_empty())
        .collect()
}

/// The system, as `SystemArgs::build` makes it; an error is returned rendered.
fn build(a: &Args) -> Result<System, String> {
    if let Some(id) = &a.problem {
        return embedded::problem(id)
            .map(|p| p.system)
            .ok_or_else(|| format!("no problem `{id}`"));
    }
    let coords: Vec<&str> = a
        .coords
        .split(',')
        .map(str::trim)
        .filter(|c| !c.is_empty())
        .collect();
    if coords.is_empty() {
        return Err("--coords names no coordinate".into());
    }
    let mut sys = match (&a.lagrangian, &a.kinetic, &a.potential) {
        (Some(l), _, _) => System::from_lagrangian(l, &coords),
        (None, Some(t), Some(v)) => System::from_energies(t, v, &coords),
        _ => return Err("give --lagrangian".into()),
    }
    .map_err(|e| mech(&e))?;
    if let Some(f) = &a.force {
        sys.set_forces(f).map_err(|e| mech(&e))?;
    }
    for c in &a.constraint {
        sys.add_constraint(c).map_err(|e| mech(&e))?;
    }
    Ok(sys)
}

/// A mechanics error rendered as the CLI renders it.
fn mech(e: &MechError) -> String {
    match e {
        MechError::Parse {
            what, source_text, ..
        } => render(what, source_text, &Diagnostic::from(e), false),
        other => render_plain(&Diagnostic::from(other)),
    }
}

/// `lagrange modes`, as `src/cli/modes.rs` does it (its `--range` parser copied: it lives in
/// the binary).
fn modes_of(a: &Args, sys: &System) -> Result<(), String> {
    let Ok(params) = assignments(&a.params) else {
        return Ok(());
    };
    let at = match a.at.as_deref().map(assignments).transpose() {
        Ok(at) => at,
        Err(_) => return Ok(()),
    };
    let mut ranges = Vec::new();
    for r in &a.range {
        let parsed = r.split_once('=').and_then(|(name, span)| {
            let (lo, hi) = span.split_once(':')?;
            let (lo, hi) = (
                lo.trim().parse::<f64>().ok()?,
                hi.trim().parse::<f64>().ok()?,
            );
            (lo < hi).then(|| (name.trim().to_string(), lo, hi))
        });
        match parsed {
            Some(x) => ranges.push(x),
            None => return Ok(()),
        }
    }
    let opts = ModesOptions {
        default_range: a.problem.is_none().then_some((-10.0, 10.0)),
        ranges,
        params,
        at,
        symbolic: a.symbolic,
        steady: Vec::new(),
    };
    match modes(sys, &opts) {
        Ok(rep) => {
            no_raw_controls(&rep.render(Style::Unicode, &Plain), "modes")?;
            serde_json::to_string(&rep)
                .map(drop)
                .map_err(|e| format!("json: {e}"))
        }
        Err(e) => no_raw_controls(&e.to_string(), "error"),
    }
}
