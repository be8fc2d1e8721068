//! Issue 14, item 4: `lagrange simulate --plot/--phase/--energy` write SVG files with the
//! coordinates' Unicode names on the axes and one polyline of `--samples` points per curve;
//! `--plot -` prints a terminal chart.

use std::path::Path;

use crate::helpers::lagrange;

const DP_PARAMS: &str = "m1=1, m2=1, l1=1, l2=1, g=9.81";

/// A fresh directory for this test's files.
fn dir(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("plot-{name}"))
}

fn svg(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(
        text.starts_with("<svg") || text.starts_with("<?xml"),
        "{}",
        &text[..text.len().min(100)]
    );
    assert!(text.trim_end().ends_with("</svg>"));
    text
}

/// The number of points of each data curve (`<path class="curve" d="M…L…L…">`).
fn curves(svg: &str) -> Vec<usize> {
    svg.lines()
        .filter(|l| l.starts_with("<path class=\"curve\""))
        .map(|l| {
            let d = l.split(" d=\"").nth(1).unwrap().split('"').next().unwrap();
            d.matches(['M', 'L']).count()
        })
        .collect()
}

#[test]
fn the_double_pendulum_draws_q_of_t_its_phase_portrait_and_its_energy_error() {
    let d = dir("dp");
    let (q, p, e) = (d.join("q.svg"), d.join("phase.svg"), d.join("energy.svg"));
    let (code, out, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--init",
        "theta1=2, theta2=2",
        "--t-end",
        "5",
        "--samples",
        "300",
        "--plot",
        q.to_str().unwrap(),
        "--phase",
        p.to_str().unwrap(),
        "--energy",
        e.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Final:"), "{out}");
    let q = svg(&q);
    // One chart: both coordinates share the axis and its unit, a legend names each curve.
    assert!(q.contains(">θ₁, θ₂ / rad</text>"), "{q}");
    assert!(q.contains(">θ₁</text>") && q.contains(">θ₂</text>"), "{q}");
    assert!(q.contains(">t / s</text>"));
    assert_eq!(curves(&q), vec![300, 300]);
    let p = svg(&p);
    for label in [
        "θ₁ / rad",
        "θ\u{307}₁ / rad s⁻¹",
        "θ₂ / rad",
        "θ\u{307}₂ / rad s⁻¹",
    ] {
        assert!(p.contains(&format!(">{label}</text>")), "{label}");
    }
    assert_eq!(curves(&p), vec![300, 300]);
    let e = svg(&e);
    assert!(e.contains("(h − h₀)/|h₀|"));
    assert_eq!(curves(&e), vec![300]);
}

#[test]
fn plot_dash_prints_a_terminal_chart() {
    let (code, out, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--init",
        "theta=1",
        "--t-end",
        "5",
        "--plot",
        "-",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("Final:"), "{out}");
    assert!(out.contains("θ(t)"), "{out}");
    let braille = out
        .chars()
        .filter(|c| ('\u{2801}'..='\u{28ff}').contains(c))
        .count();
    assert!(braille > 50, "{out}");
}

#[test]
fn plot_dash_with_json_is_a_usage_error() {
    let (code, out, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--init",
        "theta=1",
        "--t-end",
        "1",
        "--plot",
        "-",
        "--json",
    ]);
    assert_eq!(code, 2, "{out}");
    assert!(err.contains("--plot -"), "{err}");
}

#[test]
fn an_unwritable_picture_is_a_usage_error() {
    let (code, _, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--init",
        "theta=1",
        "--t-end",
        "1",
        "--phase",
        "/nonexistent-dir/x/phase.svg",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("--phase") && !err.contains("panicked"),
        "{err}"
    );
}

/// The documented command draws the committed `docs/pendulum-phase.svg`: every element in
/// place to a pixel (a regular motion, so rounding moves no curve further).
#[test]
fn the_readme_phase_portrait_is_what_its_command_draws() {
    let d = dir("readme");
    let fresh = d.join("pendulum-phase.svg");
    let (code, _, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--init",
        "theta=2.5",
        "--t-end",
        "10",
        "--samples",
        "500",
        "--phase",
        fresh.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let committed = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/pendulum-phase.svg");
    let readme =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/simulation.md"));
    assert!(
        readme
            .unwrap()
            .contains("--t-end 10 --samples 500 --phase docs/pendulum-phase.svg")
    );
    crate::helpers::assert_svg_agrees(&svg(&fresh), &svg(&committed), "docs/pendulum-phase.svg");
    assert_eq!(curves(&svg(&committed)), vec![500]);
}
