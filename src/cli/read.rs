//! `lagrange read`: how an input is understood.

use std::process::ExitCode;

use anyhow::{Context as _, bail};
use clap::Args;

use super::system_args::Terminal;
use lagrange::diagnostic::render_parse_error;
use lagrange::expr::Dimension;
use lagrange::report::read::Partial;
use lagrange::report::{ReadOptions, reading};

#[derive(Args, Debug)]
pub struct ReadArgs {
    /// The input, e.g. "m*l^2*theta'' + m*g*l*sin(theta) = 0".
    #[arg(allow_hyphen_values = true)]
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
    #[arg(long, allow_hyphen_values = true)]
    diff: Option<String>,
    /// Also print the total time derivative.
    #[arg(long)]
    dt: bool,
}

/// How a user of `read` gives symbols dimensions, shown after an unknown dimension.
const GIVE_DIMENSIONS: &str = "give every symbol a dimension with --dims";

fn split_list(s: &str) -> Vec<String> {
    s.split(',')
        .map(|x| x.trim().to_string())
        .filter(|x| !x.is_empty())
        .collect()
}

pub fn run(args: &ReadArgs, color: bool, out: &mut String) -> anyhow::Result<ExitCode> {
    let mut dims = Vec::new();
    for item in split_list(&args.dims) {
        let (name, d) = item
            .split_once('=')
            .with_context(|| format!("--dims item `{item}` should look like `g=L T^-2`"))?;
        let d = Dimension::parse(d).map_err(anyhow::Error::msg)?;
        dims.push((lagrange::expr::spelled(name), d));
    }
    let opts = ReadOptions {
        coords: split_list(&args.coords)
            .iter()
            .map(|c| lagrange::expr::spelled(c))
            .collect(),
        dims,
        strict: args.strict,
        diff: args.diff.clone(),
        dt: args.dt,
    };
    let r = match reading(&args.input, &opts) {
        Ok(r) => r,
        Err(e) => {
            eprint!("{}", render_parse_error("input", &args.input, &e, color));
            return Ok(ExitCode::from(1));
        }
    };
    out.push_str(&r.render(&Terminal, GIVE_DIMENSIONS));
    if matches!(r.partial, Some(Partial::NotAVariable)) {
        bail!("--diff takes one variable, e.g. theta or theta'");
    }
    Ok(ExitCode::from(u8::from(r.failed())))
}
