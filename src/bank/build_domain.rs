//! The declared domains of coordinates and parameters: where each can physically be (r > 0,
//! a half-angle in (0, π/2)), read from `domain = …` with the default that a parameter with a
//! physical dimension is positive. A sampling range must lie inside its domain.

use crate::expr::{Context, Dimension, Dimensions, Id, Pool, read_expr};
use crate::mechanics::system::{Coordinate, Domain, Parameter};

use super::FindingCode;
use super::build_reader::Builder;
use super::finding::Finding;
use super::schema::{BoundSpec, DomainSpec, ProblemFile};

/// Fills in every coordinate's and parameter's domain from the file.
pub(super) fn domains(
    b: &Builder<'_>,
    pf: &ProblemFile,
    pool: &mut Pool,
    dims: &Dimensions,
    coordinates: &mut [Coordinate],
    parameters: &mut [Parameter],
) -> Result<(), Finding> {
    // Ends are expressions of the parameters (and numbers, π), never of a coordinate.
    let ctx = Context::new().with_parameters(parameters.iter().map(|p| p.name.as_str()));
    for (c, spec) in coordinates.iter_mut().zip(&pf.coordinates) {
        if let Some(d) = &spec.domain {
            let at = Place {
                b,
                name: &c.name,
                line: line_naming(b, |l| l.contains(&format!("name = \"{}\"", spec.name))),
                dimension: dims.get(&c.name),
            };
            c.domain = read_domain(&at, &ctx, pool, dims, d)?;
            inside(&at, pool, c.range, c.domain, "coordinate")?;
        }
    }
    for p in parameters.iter_mut() {
        let spec = pf
            .parameters
            .iter()
            .find(|(n, _)| crate::expr::names::normalize(n) == p.name)
            .and_then(|(_, s)| s.domain.as_ref());
        let at = Place {
            b,
            name: &p.name,
            line: line_naming(b, |l| {
                let l = l.trim_start().trim_start_matches('"');
                l.strip_prefix(p.name.as_str())
                    .is_some_and(|rest| rest.trim_start_matches('"').trim_start().starts_with('='))
            }),
            dimension: p.dimension,
        };
        p.domain = match spec {
            Some(d) => read_domain(&at, &ctx, pool, dims, d)?,
            None if p.dimension.is_some_and(|d| d != Dimension::NONE) => Domain {
                lower: Some(pool.zero()),
                upper: None,
            },
            None => Domain::ANY,
        };
        inside(&at, pool, p.range, p.domain, "parameter")?;
    }
    Ok(())
}

/// What a domain belongs to: its name, the line to report, and its dimension.
struct Place<'a> {
    b: &'a Builder<'a>,
    name: &'a str,
    line: usize,
    dimension: Option<Dimension>,
}

/// The first line of the file that `is_it` picks (the declaration of a coordinate or
/// parameter), else the id's line.
fn line_naming(b: &Builder<'_>, is_it: impl Fn(&str) -> bool) -> usize {
    b.text.lines().position(is_it).map_or(b.id_line, |i| i + 1)
}

fn read_domain(
    at: &Place<'_>,
    ctx: &Context,
    pool: &mut Pool,
    dims: &Dimensions,
    spec: &DomainSpec,
) -> Result<Domain, Finding> {
    let name = at.name;
    let bad = |why: String| {
        at.b.fail(
            at.line,
            FindingCode::BadDomain,
            format!("the domain of `{name}` {why}"),
        )
    };
    match spec {
        // ASCII case is enough: only ASCII capitals lowercase to exactly these words.
        DomainSpec::Word(w) => match w.trim().to_ascii_lowercase().as_str() {
            "positive" => Ok(Domain {
                lower: Some(pool.zero()),
                upper: None,
            }),
            "negative" => Ok(Domain {
                lower: None,
                upper: Some(pool.zero()),
            }),
            "any" | "real" => Ok(Domain::ANY),
            _ => Err(bad(format!(
                "is `{}`; write \"positive\", \"negative\", \"any\" or an interval [low, high]",
                w.trim()
            ))),
        },
        DomainSpec::Interval(ends) => {
            let [lo, hi] = &ends[..] else {
                return Err(bad(format!(
                    "has {} ends; an interval is [low, high]",
                    ends.len()
                )));
            };
            let mut end = |e: &BoundSpec| -> Result<Id, Finding> {
                let text = match e {
                    BoundSpec::Number(v) if v.is_finite() => format!("{v:e}"),
                    BoundSpec::Number(v) => return Err(bad(format!("has the end {v}"))),
                    BoundSpec::Text(t) => t.clone(),
                };
                let end = read_expr(&text, ctx, pool).map_err(|e| {
                    bad(format!(
                        "has the end `{text}`: {e} ({}); an end is a number or an expression of the parameters",
                        e.help()
                    ))
                })?;
                // A number is 0 or a bound of any dimension; an expression must have the
                // dimension of what it bounds (θ < l is a slip).
                if let (Some(want), Ok(Some(got))) = (at.dimension, pool.dimension(end, dims))
                    && pool.number_value(end).is_none()
                    && got != want
                {
                    return Err(bad(format!(
                        "has the end `{text}` of dimension {}, but `{name}` has dimension {}",
                        got.plain(),
                        want.plain()
                    )));
                }
                Ok(end)
            };
            let (lower, upper) = (end(lo)?, end(hi)?);
            if let (Some(l), Some(h)) = (constant(pool, lower), constant(pool, upper))
                && l >= h
            {
                return Err(bad(format!("[{l}, {h}] is empty: it needs low < high")));
            }
            Ok(Domain {
                lower: Some(lower),
                upper: Some(upper),
            })
        }
    }
}

/// The value of an expression without symbols (None when it has one or no value).
fn constant(pool: &Pool, e: Id) -> Option<f64> {
    let program = crate::expr::Program::compile(pool, &[e], &[]).ok()?;
    program.eval(&[]).ok()?.first().copied()
}

/// The sampling range must lie inside the domain where the domain's ends are numbers (ends
/// with parameters are met by redrawing samples).
fn inside(
    at: &Place<'_>,
    pool: &Pool,
    range: (f64, f64),
    d: Domain,
    what: &str,
) -> Result<(), Finding> {
    let name = at.name;
    let below = d
        .lower
        .and_then(|l| constant(pool, l))
        .is_some_and(|l| range.0 < l);
    let above = d
        .upper
        .and_then(|u| constant(pool, u))
        .is_some_and(|u| range.1 > u);
    if below || above {
        return Err(at.b.fail(
            at.line,
            FindingCode::BadDomain,
            format!(
                "{what} `{name}` is sampled over [{}, {}], outside its domain; make the range lie inside it",
                range.0, range.1
            ),
        ));
    }
    Ok(())
}
