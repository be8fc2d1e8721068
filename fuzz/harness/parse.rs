//! Target `parse`: bytes, token soups and grammar-generated expressions into the reader in
//! three contexts (open; closed with coordinates x, θ and parameters m, g, l, k; open with a
//! coordinate), every error rendered with its caret, and every expression or equation that
//! reads printed in plain and Unicode form and read back: the round trip must give the same
//! canonical node.

use lagrange::diagnostic::render_parse_error;
use lagrange::expr::{Context, Pool, Reading, Style, read};

use super::inputs::{self, Rng, Vocab, below};

/// The vocabulary of generated expressions (the closed context's names, and two it lacks).
fn vocab() -> Vocab {
    Vocab {
        coords: vec!["x".into(), "theta".into(), "θ".into()],
        params: ["m", "g", "l", "k", "m1", "omega", "y"]
            .map(String::from)
            .to_vec(),
    }
}

/// Seeds for mutation: inputs that read, and the hostile ones.
const SEEDS: &[&str] = &[
    "1/2 m l^2 theta'^2 + m g l cos(theta)",
    "m*l^2*theta'' + m*g*l*sin(theta) = 0",
    "theta'' = -g/l sin(θ)",
    "½·m·l²·θ̇² + m·g·l·cos(θ)",
    "x'' + k/m x = 0; theta'' = 0",
    "0*log(-1)",
    "0/0",
    "m^100000",
    "1e301",
    "x^(1/3) + sqrt(x) - abs(x)",
    "dot(theta) + ddot(x) + thetadot",
    "\u{1b}]0;pwned\u{7}x",
];

/// One input: grammar (40%), token soup (20%), mutation of a seed (25%), bytes (10%) or a
/// blow-up (5%).
pub fn generate(r: &mut Rng) -> Vec<u8> {
    let v = vocab();
    match below(r, 20) {
        0..=7 => {
            let d = 1 + below(r, 6) as u32;
            let e = inputs::expr(r, &v, d);
            if inputs::chance(r, 0.3) {
                format!("{e} = {}", inputs::expr(r, &v, d)).into_bytes()
            } else {
                e.into_bytes()
            }
        }
        8..=11 => {
            let n = 1 + below(r, 40);
            inputs::soup(r, n).into_bytes()
        }
        12..=16 => {
            let s = inputs::pick(r, SEEDS).as_bytes();
            inputs::mutate(r, s)
        }
        17 | 18 => {
            let n = below(r, 64);
            inputs::bytes(r, n)
        }
        _ => inputs::blowup(r, &v).into_bytes(),
    }
}

/// The reading contexts every input is read in.
fn contexts() -> [Context; 3] {
    [
        Context::open(),
        Context::new()
            .with_coordinates(["x", "theta"])
            .with_parameters(["m", "g", "l", "k"]),
        Context::open().with_coordinates(["x"]),
    ]
}

/// Reads the input in every context; an error is rendered, a reading is printed and read
/// back.
pub fn execute(input: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    for ctx in contexts() {
        let mut pool = Pool::new();
        match read(&text, &ctx, &mut pool) {
            Err(e) => {
                // The renderer must cope with every error on every input, and show it safely.
                let shown = render_parse_error("input", &text, &e, false);
                super::no_raw_controls(&shown, "parse error")?;
            }
            Ok(reading) => round_trip(&reading, &ctx, &mut pool)?,
        }
    }
    Ok(())
}

/// Whether a reading error is one of the reader's size limits (length, depth, digits,
/// magnitude), which a printed form of a huge value may exceed.
fn beyond_limits(e: &lagrange::ParseError) -> bool {
    matches!(
        e.kind.code(),
        "too-long" | "too-deep" | "number-too-large" | "too-many-digits"
    )
}

/// Every expression and equation of a reading, printed and read back, is the same node.
fn round_trip(reading: &Reading, ctx: &Context, pool: &mut Pool) -> Result<(), String> {
    match reading {
        Reading::Expr(id, _) => {
            for style in [Style::Plain, Style::Unicode] {
                let printed = pool.display(*id, style);
                match read(&printed, ctx, pool) {
                    Ok(Reading::Expr(back, _)) if back == *id => {}
                    Ok(other) => {
                        return Err(format!(
                            "roundtrip: {style:?} form `{printed}` reads back as a different \
                             node ({})",
                            describe(&other, pool)
                        ));
                    }
                    // A printed form beyond the reader's documented limits (a 1001-digit
                    // integer from 10^1000) is refused with the limit named: not a failure.
                    Err(e) if beyond_limits(&e) => {}
                    Err(e) => {
                        return Err(format!(
                            "roundtrip: {style:?} form `{printed}` does not read back: {e}"
                        ));
                    }
                }
            }
            Ok(())
        }
        Reading::Equation { lhs, rhs, .. } => {
            let printed = pool.display_equation(*lhs, *rhs, Style::Unicode);
            match read(&printed, ctx, pool) {
                Ok(Reading::Equation { lhs: l, rhs: r, .. }) if l == *lhs && r == *rhs => Ok(()),
                Ok(other) => Err(format!(
                    "roundtrip: equation `{printed}` reads back as {}",
                    describe(&other, pool)
                )),
                Err(e) if beyond_limits(&e) => Ok(()),
                Err(e) => Err(format!(
                    "roundtrip: equation `{printed}` does not read back: {e}"
                )),
            }
        }
        Reading::List(items, _) | Reading::System(items, _) => items
            .iter()
            .try_for_each(|item| round_trip(item, ctx, pool)),
    }
}

/// A reading, printed, for a finding.
fn describe(r: &Reading, pool: &Pool) -> String {
    match r {
        Reading::Expr(id, _) => format!("`{}`", pool.display(*id, Style::Plain)),
        Reading::Equation { lhs, rhs, .. } => {
            format!("`{}`", pool.display_equation(*lhs, *rhs, Style::Plain))
        }
        Reading::List(..) => "a list".into(),
        Reading::System(..) => "a system".into(),
    }
}
