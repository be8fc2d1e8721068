//! `lagrange derive`: the Euler–Lagrange equations with every step, M and f, the energy
//! function and the conserved quantities, and the multipliers of constraints.

use std::fmt::Write as _;
use std::process::ExitCode;

use clap::{Args, ValueEnum};
use colored::Colorize;
use serde_json::{Value, json};

use super::system_args::{SystemArgs, report};
use lagrange::expr::{Id, Style};
use lagrange::mechanics::System;

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Text,
    Latex,
    Json,
}

#[derive(Args, Debug)]
pub struct DeriveArgs {
    #[command(flatten)]
    system: SystemArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Same as --format json.
    #[arg(long)]
    json: bool,
}

pub fn run(
    args: &DeriveArgs,
    problems: Option<&std::path::Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    let mut sys = match args.system.build(problems) {
        Ok(s) => s,
        Err(e) => return Ok(report(&e, color)),
    };
    let format = if args.json { Format::Json } else { args.format };
    match derive_report(&mut sys, format) {
        Ok(text) => {
            out.push_str(&text);
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => Ok(report(&e, color)),
    }
}

/// Everything `derive` prints, in `format`.
pub fn derive_report(
    sys: &mut System,
    format: Format,
) -> Result<String, lagrange::mechanics::MechError> {
    let d = sys.derive()?;
    let energy = sys.energy(&d);
    let rows = (!sys.constraints.is_empty()).then(|| sys.constraint_rows());
    let augmented = rows.as_ref().map(|r| sys.augmented_equations(&d, r));
    let multipliers = rows.as_ref().and_then(|r| sys.multipliers_symbolic(&d, r));
    let shown: Vec<Id> = d
        .steps
        .iter()
        .map(|s| sys.pool.factor_common(s.equation))
        .collect();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let style = if format == Format::Latex {
        Style::Latex
    } else {
        Style::Unicode
    };
    let labels: Vec<(String, String)> = sys
        .coordinates
        .clone()
        .iter()
        .map(|c| {
            let q = sys.pool.var(c.sym, 0);
            let qd = sys.pool.var(c.sym, 1);
            (sys.pool.display(q, style), sys.pool.display(qd, style))
        })
        .collect();
    let param_labels: Vec<String> = sys
        .parameters
        .clone()
        .iter()
        .map(|p| {
            let v = sys.pool.var(p.sym, 0);
            sys.pool.display(v, style)
        })
        .collect();
    let pool = &sys.pool;
    if format == Format::Json {
        let plain = |e: Id| Value::String(pool.plain(e));
        let v = json!({
            "coordinates": names,
            "parameters": sys.parameters.iter().map(|p| p.name.clone()).collect::<Vec<_>>(),
            "lagrangian": plain(sys.lagrangian),
            "momenta": d.steps.iter().map(|s| plain(s.momentum)).collect::<Vec<_>>(),
            "momenta_dt": d.steps.iter().map(|s| plain(s.momentum_dt)).collect::<Vec<_>>(),
            "generalized_forces": d.steps.iter().map(|s| plain(s.force)).collect::<Vec<_>>(),
            "equations": d.steps.iter().map(|s| plain(s.equation)).collect::<Vec<_>>(),
            "mass_matrix": d.mass.iter().map(|r| r.iter().map(|&m| plain(m)).collect::<Vec<_>>()).collect::<Vec<_>>(),
            "forcing": d.forcing.iter().map(|&f| plain(f)).collect::<Vec<_>>(),
            "energy_function": plain(energy.function),
            "energy_conserved": energy.conserved,
            "energy_is_total": energy.is_total,
            "cyclic": energy.cyclic.iter().map(|&i| names[i].clone()).collect::<Vec<_>>(),
            "conserved_momenta": energy.cyclic.iter().map(|&i| json!({"coordinate": names[i], "momentum": plain(d.steps[i].momentum)})).collect::<Vec<_>>(),
            "constraints": sys.constraints.iter().map(|c| json!({"constraint": plain(c.expr), "kind": format!("{:?}", c.kind).to_lowercase()})).collect::<Vec<_>>(),
            "augmented_equations": augmented.as_ref().map(|a| a.iter().map(|&e| plain(e)).collect::<Vec<_>>()),
            "multipliers": multipliers.as_ref().map(|m| m.iter().map(|&e| plain(e)).collect::<Vec<_>>()),
        });
        return Ok(format!(
            "{}\n",
            serde_json::to_string_pretty(&v).unwrap_or_default()
        ));
    }
    let show = |e: Id| pool.display(e, style);
    let var = |i: usize, o: u8| {
        if o == 0 {
            labels[i].0.clone()
        } else {
            labels[i].1.clone()
        }
    };
    let mut o = String::new();
    if style == Style::Latex {
        let _ = writeln!(o, "\\begin{{align*}}");
        let _ = writeln!(o, "L &= {} \\\\", show(sys.lagrangian));
        for (i, s) in d.steps.iter().enumerate() {
            let (q, qd) = (var(i, 0), var(i, 1));
            let _ = writeln!(
                o,
                "p_{{{q}}} = \\frac{{\\partial L}}{{\\partial {qd}}} &= {} \\\\",
                show(s.momentum)
            );
            let _ = writeln!(
                o,
                "\\frac{{d}}{{dt}} p_{{{q}}} &= {} \\\\",
                show(s.momentum_dt)
            );
            let _ = writeln!(
                o,
                "\\frac{{\\partial L}}{{\\partial {q}}} &= {} \\\\",
                show(s.force)
            );
            let _ = writeln!(o, "{} &= 0 \\\\", show(shown[i]));
        }
        let _ = writeln!(o, "h &= {}", show(energy.function));
        let _ = writeln!(o, "\\end{{align*}}");
        return Ok(o);
    }
    let head = |t: &str| t.bold().to_string();
    let _ = writeln!(o, "{} L = {}", head("Lagrangian:"), show(sys.lagrangian));
    let _ = writeln!(
        o,
        "{} {}    {} {}",
        head("coordinates:"),
        (0..names.len())
            .map(|i| var(i, 0))
            .collect::<Vec<_>>()
            .join(", "),
        head("parameters:"),
        if param_labels.is_empty() {
            "none".to_string()
        } else {
            param_labels.join(", ")
        }
    );
    for (i, s) in d.steps.iter().enumerate() {
        let (q, qd) = (var(i, 0), var(i, 1));
        let _ = writeln!(o, "\n{} {q}", head("Coordinate"));
        let _ = writeln!(o, "  p = ∂L/∂{qd} = {}", show(s.momentum));
        let _ = writeln!(o, "  d/dt p = {}", show(s.momentum_dt));
        let _ = writeln!(o, "  ∂L/∂{q} = {}", show(s.force));
        if !pool.is_zero(s.generalized_force) {
            let _ = writeln!(o, "  Q = {}", show(s.generalized_force));
        }
        let _ = writeln!(
            o,
            "  {} {} = 0",
            if pool.is_zero(s.generalized_force) {
                "d/dt p − ∂L/∂q:"
            } else {
                "d/dt p − ∂L/∂q − Q:"
            },
            show(shown[i]).green()
        );
    }
    let _ = writeln!(o, "\n{} (M q̈ = f)", head("Mass matrix M and forcing f"));
    for (row, &f) in d.mass.iter().zip(&d.forcing) {
        let cells: Vec<String> = row.iter().map(|&m| show(m)).collect();
        let _ = writeln!(o, "  [ {} ]   [ {} ]", cells.join(", "), show(f));
    }
    let _ = writeln!(
        o,
        "\n{} h = Σ q̇ ∂L/∂q̇ − L = {}",
        head("Energy function:"),
        show(energy.function)
    );
    let _ = writeln!(
        o,
        "  conserved: {}",
        if energy.conserved {
            "yes (∂L/∂t = 0 and no non-conservative forces)"
        } else {
            "no"
        }
    );
    let _ = writeln!(
        o,
        "  h = T + V: {}",
        if energy.is_total {
            "yes".to_string()
        } else {
            format!("no (T + V = {})", show(energy.total))
        }
    );
    if energy.cyclic.is_empty() {
        let _ = writeln!(o, "{} none", head("Cyclic coordinates:"));
    } else {
        for &i in &energy.cyclic {
            let _ = writeln!(
                o,
                "{} {} — conserved momentum {}",
                head("Cyclic coordinate:"),
                var(i, 0),
                show(d.steps[i].momentum)
            );
        }
    }
    if let Some(aug) = &augmented {
        let _ = writeln!(o, "\n{}", head("Constraints"));
        for c in &sys.constraints {
            let _ = writeln!(o, "  {} = 0 ({:?})", show(c.expr), c.kind);
        }
        let _ = writeln!(o, "  with multipliers λ:");
        for &e in aug {
            let _ = writeln!(o, "  {} = 0", show(e));
        }
        match &multipliers {
            Some(ms) => {
                for (j, &m) in ms.iter().enumerate() {
                    let _ = writeln!(o, "  λ{} = {}", j + 1, show(m));
                }
            }
            None => {
                let _ = writeln!(
                    o,
                    "  (the multipliers are solved numerically at a state; the system is too large for a closed form)"
                );
            }
        }
    }
    Ok(o)
}
