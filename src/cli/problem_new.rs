//! `lagrange problems new`: a proved problem file drafted from a system given as `derive` and
//! `modes` take it (a Lagrangian, or bodies with gravity, springs and a potential). The flags
//! are checked by building the system as those commands do (same errors), turned into the
//! file format's tables here, and drafted by the library (`bank::new`); this face writes the
//! file.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Args;

use super::system_args::body_args::split_top;
use super::system_args::{SystemArgs, report};
use lagrange::bank::new::{Spec, Table, Value, draft};
use lagrange::diagnostic::{Diagnostic, render_plain};

/// `problems new --id ID --coords Q (--lagrangian L | --point … [--gravity …] …)`.
#[derive(Args, Debug)]
pub struct NewArgs {
    /// The new problem's id: letters, digits, `-`, `_` and `.`.
    #[arg(long)]
    pub id: String,
    /// Its title (a placeholder to edit otherwise).
    #[arg(long)]
    pub title: Option<String>,
    /// The Lagrangian (T and V are then not stated: L alone does not fix them).
    #[arg(long, short = 'L', allow_hyphen_values = true)]
    pub lagrangian: Option<String>,
    /// A point body, "mass=m; position=x, y", as for `derive`; repeat for several.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "lagrangian")]
    pub point: Vec<String>,
    /// A rigid body, as for `derive` ("mass=M; position=…; inertia=I; angle=theta", …).
    #[arg(long, allow_hyphen_values = true, conflicts_with = "lagrangian")]
    pub rigid: Vec<String>,
    /// Uniform gravity on the bodies, "g" (down the y axis) or "g, z".
    #[arg(long, allow_hyphen_values = true, conflicts_with = "lagrangian")]
    pub gravity: Option<String>,
    /// A spring, "k=k; from=1; to=0, 0; natural=l0"; repeat for several.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "lagrangian")]
    pub spring: Vec<String>,
    /// A further potential energy of the bodies.
    #[arg(
        long,
        short = 'V',
        allow_hyphen_values = true,
        conflicts_with = "lagrangian"
    )]
    pub potential: Option<String>,
    /// The generalized coordinates, comma-separated (angle names such as theta are periodic).
    #[arg(long, short = 'q')]
    pub coords: String,
    /// A parameter's dimension, "NAME=DIM" (e.g. "k=M T^-2"), where its name does not tell it;
    /// repeat for several.
    #[arg(long, allow_hyphen_values = true)]
    pub param: Vec<String>,
    /// Write the file here (standard output otherwise).
    #[arg(long, short = 'o')]
    pub out: Option<PathBuf>,
    /// Replace an existing file at --out.
    #[arg(long)]
    pub force: bool,
}

/// Drafts the file and writes it; notes on standard error say what was left out.
pub fn run(args: &NewArgs, color: bool, out: &mut String) -> anyhow::Result<ExitCode> {
    // The system is built first, as `derive` builds it, so a typo gets the same message.
    let sys = SystemArgs {
        problem: None,
        lagrangian: args.lagrangian.clone(),
        kinetic: None,
        potential: args.potential.clone(),
        point: args.point.clone(),
        rigid: args.rigid.clone(),
        gravity: args.gravity.clone(),
        spring: args.spring.clone(),
        coords: args.coords.clone(),
        force: None,
        force_at: Vec::new(),
        constraint: Vec::new(),
    };
    if let Err(e) = sys.build(None) {
        return Ok(report(&e, color));
    }
    let spec = match spec(args) {
        Ok(s) => s,
        Err(d) => return Ok(fail(&d)),
    };
    let drafted = match draft(&spec) {
        Ok(d) => d,
        Err(d) => return Ok(fail(&d)),
    };
    match &args.out {
        None => out.push_str(&drafted.text),
        Some(path) => {
            if !args.force && std::fs::symlink_metadata(path).is_ok() {
                return Ok(fail(&Diagnostic::new(
                    "exists",
                    format!("{} already exists", path.display()),
                    "choose another name, or give --force to replace it",
                )));
            }
            crate::face::outfile::write_named(path, drafted.text.as_bytes())
                .map_err(anyhow::Error::msg)?;
            out.push_str(&format!(
                "wrote {}\n  next: `lagrange problems verify {}` proves it again after your edits\n",
                path.display(),
                path.display()
            ));
        }
    }
    eprintln!(
        "note: {} parts stated ({})",
        drafted.stated.len(),
        drafted.stated.join(", ")
    );
    for l in &drafted.left_out {
        eprintln!("note: {} left out: {}", l.part, l.reason);
    }
    Ok(ExitCode::SUCCESS)
}

/// Prints a diagnostic and returns the usage exit code.
fn fail(d: &Diagnostic) -> ExitCode {
    eprint!("{}", render_plain(d));
    ExitCode::from(2)
}

/// The flags as the library's spec: each body and potential as the file's table.
fn spec(args: &NewArgs) -> Result<Spec, Diagnostic> {
    let coordinates: Vec<String> = args
        .coords
        .split(',')
        .map(str::trim)
        .filter(|c| !c.is_empty())
        .map(lagrange::expr::spelled)
        .collect();
    let mut bodies = Vec::new();
    for p in &args.point {
        bodies.push(table("point", p, &["position"])?);
    }
    for r in &args.rigid {
        let mut t = table(
            "rigid",
            r,
            &["position", "moments", "omega_body", "euler", "tensor"],
        )?;
        // The command line gives a tensor's nine entries row by row; the file, three rows.
        for (k, v) in &mut t.fields {
            if let (true, Value::List(items)) = (k == "tensor", &*v) {
                *v = Value::Rows(items.chunks(3).map(<[String]>::to_vec).collect());
            }
        }
        bodies.push(t);
    }
    let mut potentials = Vec::new();
    if let Some(g) = &args.gravity {
        let parts = split_top(g, ',');
        let mut fields = vec![("g".to_string(), Value::Text(parts[0].to_string()))];
        fields.push((
            "axis".to_string(),
            Value::Text(parts.get(1).copied().unwrap_or("y").to_string()),
        ));
        potentials.push(Table {
            kind: "gravity".into(),
            fields,
        });
    }
    for s in &args.spring {
        let mut t = table("spring", s, &[])?;
        for (k, v) in &mut t.fields {
            if let (true, Value::Text(text)) = (k == "from" || k == "to", &*v) {
                *v = match text.parse::<usize>() {
                    Ok(n) => Value::Body(n),
                    Err(_) => {
                        Value::List(split_top(text, ',').iter().map(|s| s.to_string()).collect())
                    }
                };
            }
        }
        if !t.fields.iter().any(|(k, _)| k == "k") {
            t.fields.insert(0, ("k".into(), Value::Text("k".into())));
        }
        potentials.push(t);
    }
    if let Some(v) = &args.potential {
        potentials.push(Table {
            kind: "explicit".into(),
            fields: vec![("V".into(), Value::Text(v.clone()))],
        });
    }
    let mut dimensions = Vec::new();
    for p in &args.param {
        let Some((name, dim)) = p.split_once('=') else {
            return Err(Diagnostic::new(
                "usage",
                format!("--param `{p}` is not NAME=DIM"),
                "e.g. --param \"k=M T^-2\"",
            ));
        };
        dimensions.push((name.trim().to_string(), dim.trim().to_string()));
    }
    Ok(Spec {
        id: args.id.clone(),
        title: args.title.clone(),
        coordinates,
        lagrangian: args.lagrangian.clone(),
        bodies,
        potentials,
        dimensions,
    })
}

/// "key=value; key=value" as a table of `kind`; the keys in `lists` hold comma-separated
/// lists. The system was built from the same text, so every key is known and given once.
fn table(kind: &str, text: &str, lists: &[&str]) -> Result<Table, Diagnostic> {
    let mut fields = Vec::new();
    for item in split_top(text, ';').into_iter().filter(|s| !s.is_empty()) {
        let Some((k, v)) = item.split_once('=') else {
            return Err(Diagnostic::new(
                "usage",
                format!("`{item}` is not key=value"),
                "write each field as key=value, separated by `;`",
            ));
        };
        let (k, v) = (k.trim(), v.trim());
        let value = if lists.contains(&k) {
            Value::List(split_top(v, ',').iter().map(|s| s.to_string()).collect())
        } else {
            Value::Text(v.to_string())
        };
        fields.push((k.to_string(), value));
    }
    Ok(Table {
        kind: kind.to_string(),
        fields,
    })
}
