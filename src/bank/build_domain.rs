//! The declared domains of coordinates and parameters: where each can physically be (r > 0,
//! a half-angle in (0, π/2)), read from `domain = …` with the default that a parameter with a
//! physical dimension is positive. A sampling range must lie inside its domain.

use crate::expr::{Context, Dimension, Id, Pool, read_expr};
use crate::mechanics::system::{Coordinate, Domain, Parameter};

use super::build_reader::Builder;
use super::finding::Finding;
use super::schema::{BoundSpec, DomainSpec, ProblemFile};

/// Fills in every coordinate's and parameter's domain from the file.
pub(super) fn domains(
    b: &Builder<'_>,
    pf: &ProblemFile,
    pool: &mut Pool,
    coordinates: &mut [Coordinate],
    parameters: &mut [Parameter],
) -> Result<(), Finding> {
    // Ends are expressions of the parameters (and numbers, π), never of a coordinate.
    let ctx = Context::new().with_parameters(parameters.iter().map(|p| p.name.as_str()));
    for (c, spec) in coordinates.iter_mut().zip(&pf.coordinates) {
        if let Some(d) = &spec.domain {
            c.domain = read_domain(b, &ctx, pool, &c.name, d)?;
            inside(b, pool, &c.name, c.range, c.domain, "coordinate")?;
        }
    }
    for p in parameters.iter_mut() {
        let spec = pf
            .parameters
            .iter()
            .find(|(n, _)| crate::expr::names::normalize(n) == p.name)
            .and_then(|(_, s)| s.domain.as_ref());
        p.domain = match spec {
            Some(d) => read_domain(b, &ctx, pool, &p.name, d)?,
            None if p.dimension.is_some_and(|d| d != Dimension::NONE) => Domain {
                lower: Some(pool.zero()),
                upper: None,
            },
            None => Domain::ANY,
        };
        inside(b, pool, &p.name, p.range, p.domain, "parameter")?;
    }
    Ok(())
}

fn read_domain(
    b: &Builder<'_>,
    ctx: &Context,
    pool: &mut Pool,
    name: &str,
    spec: &DomainSpec,
) -> Result<Domain, Finding> {
    let bad = |why: String| {
        b.fail(
            b.id_line,
            "bad-domain",
            format!("the domain of `{name}` {why}"),
        )
    };
    match spec {
        DomainSpec::Word(w) => match w.trim() {
            "positive" => Ok(Domain {
                lower: Some(pool.zero()),
                upper: None,
            }),
            "negative" => Ok(Domain {
                lower: None,
                upper: Some(pool.zero()),
            }),
            "any" | "real" => Ok(Domain::ANY),
            other => Err(bad(format!(
                "is `{other}`; write \"positive\", \"negative\", \"any\" or an interval [low, high]"
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
                read_expr(&text, ctx, pool).map_err(|e| {
                    bad(format!(
                        "has the end `{text}`: {e} ({}); an end is a number or an expression of the parameters",
                        e.help()
                    ))
                })
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
    b: &Builder<'_>,
    pool: &Pool,
    name: &str,
    range: (f64, f64),
    d: Domain,
    what: &str,
) -> Result<(), Finding> {
    let below = d
        .lower
        .and_then(|l| constant(pool, l))
        .is_some_and(|l| range.0 < l);
    let above = d
        .upper
        .and_then(|u| constant(pool, u))
        .is_some_and(|u| range.1 > u);
    if below || above {
        return Err(b.fail(
            b.id_line,
            "bad-domain",
            format!(
                "{what} `{name}` is sampled over [{}, {}], outside its domain; make the range lie inside it",
                range.0, range.1
            ),
        ));
    }
    Ok(())
}
