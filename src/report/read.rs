//! [`ReadReport`]: what `read` shows — how an input is understood in every notation, its kind,
//! which names are coordinates and which parameters, its dimension, and optionally a partial
//! and the time derivative — built by [`reading`], rendered by [`ReadReport::render`].

use std::fmt::{self, Write as _};

use serde::Serialize;

use super::{Formula, Paint, text};
use crate::expr::{
    self, Context, DimError, Dimension, Dimensions, Id, Node, ParseError, Pool, Style,
};

/// How to read an input.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ReadOptions {
    /// Coordinates: their `dot`, `'` and combining-dot forms are time derivatives.
    pub coords: Vec<String>,
    /// Dimensions of symbols; when there are any, the dimension is checked.
    pub dims: Vec<(String, Dimension)>,
    /// Only the coordinates and the symbols given dimensions are allowed.
    pub strict: bool,
    /// Also the partial derivative with respect to this variable (e.g. `theta'`).
    pub diff: Option<String>,
    /// Also the total time derivative.
    pub dt: bool,
}

/// How an input was understood.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct ReadReport {
    /// The input in plain syntax, Unicode and LaTeX.
    pub forms: Formula,
    /// `expression`, `equation`, `list of n` or `system of n`.
    pub kind: String,
    /// Names read as coordinates, sorted.
    pub(crate) coordinates: Vec<String>,
    /// Names read as parameters, sorted.
    pub(crate) parameters: Vec<String>,
    /// The dimension, when dimensions were given.
    pub dimension: Option<DimensionFinding>,
    /// The partial derivatives of each expression, when asked for.
    pub partial: Option<Partial>,
    /// The time derivatives of each expression, when asked for.
    pub(crate) time_derivatives: Option<Vec<Formula>>,
}

/// The dimension of an input.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DimensionFinding {
    /// Consistent, with this dimension.
    Known(String),
    /// Some symbol has no dimension.
    Unknown,
    /// Every symbol has a dimension, but a power with a symbolic exponent (`r^n`) has one
    /// that depends on the exponent's value: it cannot be decided.
    Undecided,
    /// Terms of different dimensions are added or equated.
    Inconsistent(String),
}

/// A partial derivative that was asked for.
#[derive(Clone, Debug, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Partial {
    /// ∂/∂`variable` of each expression of the input.
    Taken {
        /// The variable, in Unicode.
        variable: String,
        /// One derivative per expression.
        derivatives: Vec<Formula>,
    },
    /// What was given is not one variable.
    NotAVariable,
}

/// Reads `input` and works out everything `read` shows. A parse error is returned as is,
/// for the face to render against the input.
pub fn reading(input: &str, opts: &ReadOptions) -> Result<ReadReport, ParseError> {
    let mut dims = Dimensions::new();
    let declared: Vec<String> = opts
        .dims
        .iter()
        .map(|(n, _)| n.trim().to_string())
        .collect();
    for (name, d) in &opts.dims {
        if opts.coords.iter().any(|c| c == name.trim()) {
            dims.set_coordinate(name.trim(), *d);
        } else {
            dims.set(name.trim(), *d);
        }
    }
    let base = if opts.strict {
        Context::new()
    } else {
        Context::open()
    };
    let ctx = base.with_coordinates(&opts.coords).with_parameters(
        declared
            .iter()
            .filter(|n| !opts.coords.contains(n))
            .cloned()
            .collect::<Vec<_>>(),
    );
    let mut pool = Pool::new();
    for c in ctx.coordinates().iter().chain(ctx.parameters()) {
        pool.symbol(c);
    }
    let parsed = expr::read(input, &ctx, &mut pool)?;
    let mut roots = Vec::new();
    collect(&parsed, &mut roots);
    let (coordinates, parameters) = names(&pool, &roots, &ctx);
    let dimension = (!declared.is_empty()).then(|| match dimension_of(&pool, &parsed, &dims) {
        Ok(Some(d)) => DimensionFinding::Known(d.to_string()),
        Ok(None)
            if coordinates
                .iter()
                .chain(&parameters)
                .all(|n| declared.contains(n)) =>
        {
            DimensionFinding::Undecided
        }
        Ok(None) => DimensionFinding::Unknown,
        Err(e) => DimensionFinding::Inconsistent(e.to_string()),
    });
    let forms = Formula {
        plain: show(&pool, &parsed, Style::Plain),
        unicode: show(&pool, &parsed, Style::Unicode),
        latex: show(&pool, &parsed, Style::Latex),
    };
    let positive: Vec<_> = parameters.iter().map(|p| pool.symbol(p)).collect();
    let partial = opts
        .diff
        .as_deref()
        .map(|v| partial(&mut pool, v, &coordinates, &roots, &positive));
    let stopped = matches!(partial, Some(Partial::NotAVariable));
    let time_derivatives = (opts.dt && !stopped).then(|| {
        let coord_syms: Vec<_> = coordinates.iter().map(|c| pool.symbol(c)).collect();
        roots
            .iter()
            .map(|&r| {
                let d = pool.dt(r, &coord_syms);
                let d = pool.simplify(d, &positive);
                Formula::new(&pool, d)
            })
            .collect()
    });
    Ok(ReadReport {
        forms,
        kind: kind(&parsed),
        coordinates,
        parameters,
        dimension,
        partial,
        time_derivatives,
    })
}

/// The coordinates (names with a derivative, or declared) and the parameters, each sorted.
fn names(pool: &Pool, roots: &[Id], ctx: &Context) -> (Vec<String>, Vec<String>) {
    let mut coordinates: Vec<String> = Vec::new();
    let mut parameters: Vec<String> = Vec::new();
    for &r in roots {
        for (s, o) in pool.variables(r) {
            let name = pool.name(s).to_string();
            if s == pool.time() {
                continue;
            }
            let list = if o > 0 || ctx.is_coordinate(&name) {
                &mut coordinates
            } else {
                &mut parameters
            };
            if !list.contains(&name) {
                list.push(name);
            }
        }
    }
    parameters.retain(|p| !coordinates.contains(p));
    crate::sort::sort(&mut coordinates);
    crate::sort::sort(&mut parameters);
    (coordinates, parameters)
}

/// ∂/∂`v` of every root, when `v` reads as one variable.
fn partial(
    pool: &mut Pool,
    v: &str,
    coordinates: &[String],
    roots: &[Id],
    positive: &[expr::Sym],
) -> Partial {
    let vctx = Context::open().with_coordinates(coordinates);
    let Ok(expr::Reading::Expr(var, _)) = expr::read(v, &vctx, pool) else {
        return Partial::NotAVariable;
    };
    let Node::Var(s, o) = *pool.node(var) else {
        return Partial::NotAVariable;
    };
    let derivatives = roots
        .iter()
        .map(|&r| {
            let d = pool.diff(r, s, o);
            let d = pool.simplify(d, positive);
            Formula::new(pool, d)
        })
        .collect();
    Partial::Taken {
        variable: pool.unicode(var),
        derivatives,
    }
}

impl ReadReport {
    /// Whether the input is inconsistent (its dimensions do not agree).
    pub fn failed(&self) -> bool {
        matches!(self.dimension, Some(DimensionFinding::Inconsistent(_)))
    }

    /// The report as text, derivatives in Unicode, marked up by `paint`. When the partial
    /// derivative's variable is not one variable the text stops before it: the face says why.
    ///
    /// `give_dimensions` follows an unknown dimension, in parentheses: how the face's user
    /// gives symbols their dimensions (the command line names its flag); empty, nothing does.
    pub fn render(&self, paint: &dyn Paint, give_dimensions: &str) -> String {
        text(|o| self.write_text(paint, give_dimensions, o))
    }

    fn write_text(&self, paint: &dyn Paint, give_dimensions: &str, o: &mut String) -> fmt::Result {
        let h = |t: &str| paint.heading(t);
        writeln!(o, "{} {}", h("read as:"), self.forms.plain)?;
        writeln!(o, "{} {}", h("unicode:"), self.forms.unicode)?;
        writeln!(o, "{} {}", h("latex:  "), self.forms.latex)?;
        writeln!(o, "{} {}", h("kind:   "), self.kind)?;
        writeln!(
            o,
            "{} {}",
            h("coordinates:"),
            join_or_none(&self.coordinates)
        )?;
        writeln!(
            o,
            "{} {}",
            h("parameters: "),
            join_or_none(&self.parameters)
        )?;
        match &self.dimension {
            None => {}
            Some(DimensionFinding::Known(d)) => {
                writeln!(o, "{} {d}", h("dimension:  "))?;
            }
            Some(DimensionFinding::Unknown) if give_dimensions.is_empty() => {
                writeln!(o, "{} unknown", h("dimension:  "))?;
            }
            Some(DimensionFinding::Unknown) => {
                writeln!(o, "{} unknown ({give_dimensions})", h("dimension:  "))?;
            }
            Some(DimensionFinding::Undecided) => {
                writeln!(
                    o,
                    "{} cannot be decided: a power with a symbolic exponent has a dimension that depends on the exponent's value",
                    h("dimension:  ")
                )?;
            }
            Some(DimensionFinding::Inconsistent(e)) => {
                writeln!(o, "{} {}", h("dimension:  "), paint.bad(e))?;
            }
        }
        match &self.partial {
            None => {}
            Some(Partial::NotAVariable) => return Ok(()),
            Some(Partial::Taken {
                variable,
                derivatives,
            }) => {
                for d in derivatives {
                    writeln!(o, "{} {}", h(&format!("∂/∂{variable}:")), d.unicode)?;
                }
            }
        }
        for d in self.time_derivatives.iter().flatten() {
            writeln!(o, "{} {}", h("d/dt:"), d.unicode)?;
        }
        Ok(())
    }
}

fn join_or_none(v: &[String]) -> String {
    if v.is_empty() {
        "none".into()
    } else {
        v.join(", ")
    }
}

fn collect(r: &expr::Reading, out: &mut Vec<Id>) {
    match r {
        expr::Reading::Expr(id, _) => out.push(*id),
        expr::Reading::Equation { lhs, rhs, .. } => {
            out.push(*lhs);
            out.push(*rhs);
        }
        expr::Reading::List(items, _) | expr::Reading::System(items, _) => {
            items.iter().for_each(|i| collect(i, out));
        }
    }
}

fn show(pool: &Pool, r: &expr::Reading, style: Style) -> String {
    let join = |items: &[expr::Reading], sep: &str| {
        items
            .iter()
            .map(|i| show(pool, i, style))
            .collect::<Vec<_>>()
            .join(sep)
    };
    match r {
        expr::Reading::Expr(id, _) => pool.display(*id, style),
        expr::Reading::Equation { lhs, rhs, .. } => pool.display_equation(*lhs, *rhs, style),
        expr::Reading::List(items, _) => join(items, ", "),
        expr::Reading::System(items, _) => join(items, "; "),
    }
}

fn kind(r: &expr::Reading) -> String {
    match r {
        expr::Reading::Expr(..) => "expression".into(),
        expr::Reading::Equation { .. } => "equation".into(),
        expr::Reading::List(items, _) => format!("list of {}", items.len()),
        expr::Reading::System(items, _) => format!("system of {}", items.len()),
    }
}

fn dimension_of(
    pool: &Pool,
    r: &expr::Reading,
    dims: &Dimensions,
) -> Result<Option<Dimension>, DimError> {
    match r {
        expr::Reading::Expr(id, _) => pool.dimension(*id, dims),
        expr::Reading::Equation { lhs, rhs, .. } => pool.check_equation_dimension(*lhs, *rhs, dims),
        expr::Reading::List(items, _) | expr::Reading::System(items, _) => {
            let mut last = None;
            for i in items {
                last = dimension_of(pool, i, dims)?;
            }
            Ok(last)
        }
    }
}
