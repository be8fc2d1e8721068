//! `lagrange read`: how an input is understood.

use std::fmt::Write as _;
use std::process::ExitCode;

use anyhow::{Context as _, bail};
use clap::Args;
use colored::Colorize;

use lagrange::diagnostic::render_parse_error;
use lagrange::expr::{Context, Dimension, Dimensions, Id, Pool, Reading, Style, read};

#[derive(Args, Debug)]
pub struct ReadArgs {
    /// The input, e.g. "m*l^2*theta'' + m*g*l*sin(theta) = 0".
    input: String,
    /// Coordinates, comma-separated (their `dot`, `'` and combining-dot forms are then read
    /// as time derivatives).
    #[arg(long, default_value = "")]
    coords: String,
    /// Dimensions of symbols, e.g. "m=M, l=L, g=L T^-2"; enables the dimension check.
    #[arg(long, default_value = "")]
    dims: String,
    /// Only the coordinates and the symbols named in --dims are allowed.
    #[arg(long)]
    strict: bool,
    /// Also print the partial derivative with respect to this variable (e.g. theta').
    #[arg(long)]
    diff: Option<String>,
    /// Also print the total time derivative.
    #[arg(long)]
    dt: bool,
}

fn split_list(s: &str) -> Vec<String> {
    s.split(',')
        .map(|x| x.trim().to_string())
        .filter(|x| !x.is_empty())
        .collect()
}

pub fn run(args: &ReadArgs, color: bool, out: &mut String) -> anyhow::Result<ExitCode> {
    let coords = split_list(&args.coords);
    let mut dims = Dimensions::new();
    let mut declared = Vec::new();
    for item in split_list(&args.dims) {
        let (name, d) = item
            .split_once('=')
            .with_context(|| format!("--dims item `{item}` should look like `g=L T^-2`"))?;
        let d = Dimension::parse(d).map_err(anyhow::Error::msg)?;
        dims.set(name.trim(), d);
        declared.push(name.trim().to_string());
    }
    let base = if args.strict {
        Context::new()
    } else {
        Context::open()
    };
    let ctx = base.with_coordinates(&coords).with_parameters(
        declared
            .iter()
            .filter(|n| !coords.contains(n))
            .cloned()
            .collect::<Vec<_>>(),
    );
    let mut pool = Pool::new();
    for c in ctx.coordinates().iter().chain(ctx.parameters()) {
        pool.symbol(c);
    }
    let reading = match read(&args.input, &ctx, &mut pool) {
        Ok(r) => r,
        Err(e) => {
            eprint!("{}", render_parse_error("input", &args.input, &e, color));
            return Ok(ExitCode::from(1));
        }
    };
    let mut roots = Vec::new();
    collect(&reading, &mut roots);
    writeln!(
        out,
        "{} {}",
        "read as:".bold(),
        show(&pool, &reading, Style::Plain)
    )?;
    writeln!(
        out,
        "{} {}",
        "unicode:".bold(),
        show(&pool, &reading, Style::Unicode)
    )?;
    writeln!(
        out,
        "{} {}",
        "latex:  ".bold(),
        show(&pool, &reading, Style::Latex)
    )?;
    writeln!(out, "{} {}", "kind:   ".bold(), kind(&reading))?;
    let mut coordinate_names: Vec<String> = Vec::new();
    let mut parameter_names: Vec<String> = Vec::new();
    for &r in &roots {
        for (s, o) in pool.variables(r) {
            let name = pool.name(s).to_string();
            if s == pool.time() {
                continue;
            }
            let list = if o > 0 || ctx.is_coordinate(&name) {
                &mut coordinate_names
            } else {
                &mut parameter_names
            };
            if !list.contains(&name) {
                list.push(name);
            }
        }
    }
    parameter_names.retain(|p| !coordinate_names.contains(p));
    coordinate_names.sort();
    parameter_names.sort();
    writeln!(
        out,
        "{} {}",
        "coordinates:".bold(),
        join_or_none(&coordinate_names)
    )?;
    writeln!(
        out,
        "{} {}",
        "parameters: ".bold(),
        join_or_none(&parameter_names)
    )?;
    let mut failed = false;
    if !declared.is_empty() {
        match dimension_of(&pool, &reading, &dims) {
            Ok(Some(d)) => writeln!(out, "{} {d}", "dimension:  ".bold())?,
            Ok(None) => writeln!(
                out,
                "{} unknown (give every symbol a dimension with --dims)",
                "dimension:  ".bold()
            )?,
            Err(e) => {
                writeln!(out, "{} {}", "dimension:  ".bold(), e.to_string().red())?;
                failed = true;
            }
        }
    }
    let coord_syms: Vec<_> = coordinate_names.iter().map(|c| pool.symbol(c)).collect();
    let positive: Vec<_> = parameter_names.iter().map(|p| pool.symbol(p)).collect();
    if let Some(v) = &args.diff {
        let vctx = Context::open().with_coordinates(&coordinate_names);
        let var = match read(v, &vctx, &mut pool) {
            Ok(Reading::Expr(id, _)) => id,
            _ => bail!("--diff takes one variable, e.g. theta or theta'"),
        };
        let lagrange::expr::Node::Var(s, o) = *pool.node(var) else {
            bail!("--diff takes one variable, e.g. theta or theta'");
        };
        for &r in &roots {
            let d = pool.diff(r, s, o);
            let d = pool.simplify(d, &positive);
            writeln!(
                out,
                "{} {}",
                format!("∂/∂{}:", pool.unicode(var)).bold(),
                pool.unicode(d)
            )?;
        }
    }
    if args.dt {
        for &r in &roots {
            let d = pool.dt(r, &coord_syms);
            let d = pool.simplify(d, &positive);
            writeln!(out, "{} {}", "d/dt:".bold(), pool.unicode(d))?;
        }
    }
    Ok(ExitCode::from(u8::from(failed)))
}

fn join_or_none(v: &[String]) -> String {
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

fn collect(r: &Reading, out: &mut Vec<Id>) {
    match r {
        Reading::Expr(id, _) => out.push(*id),
        Reading::Equation { lhs, rhs, .. } => {
            out.push(*lhs);
            out.push(*rhs);
        }
        Reading::List(items, _) | Reading::System(items, _) => {
            items.iter().for_each(|i| collect(i, out));
        }
    }
}

fn show(pool: &Pool, r: &Reading, style: Style) -> String {
    match r {
        Reading::Expr(id, _) => pool.display(*id, style),
        Reading::Equation { lhs, rhs, .. } => pool.display_equation(*lhs, *rhs, style),
        Reading::List(items, _) => items
            .iter()
            .map(|i| show(pool, i, style))
            .collect::<Vec<_>>()
            .join(", "),
        Reading::System(items, _) => items
            .iter()
            .map(|i| show(pool, i, style))
            .collect::<Vec<_>>()
            .join("; "),
    }
}

fn kind(r: &Reading) -> String {
    match r {
        Reading::Expr(..) => "expression".into(),
        Reading::Equation { .. } => "equation".into(),
        Reading::List(items, _) => format!("list of {}", items.len()),
        Reading::System(items, _) => format!("system of {}", items.len()),
    }
}

fn dimension_of(
    pool: &Pool,
    r: &Reading,
    dims: &Dimensions,
) -> Result<Option<Dimension>, lagrange::expr::DimError> {
    match r {
        Reading::Expr(id, _) => pool.dimension(*id, dims),
        Reading::Equation { lhs, rhs, .. } => pool.check_equation_dimension(*lhs, *rhs, dims),
        Reading::List(items, _) | Reading::System(items, _) => {
            let mut last = None;
            for i in items {
                last = dimension_of(pool, i, dims)?;
            }
            Ok(last)
        }
    }
}
