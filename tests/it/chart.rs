//! The simulation's pictures drawn once for every face (`lagrange::chart`): a small chart's
//! SVG text pinned by a snapshot, the axes of a real motion covering what the physics says it
//! reaches, and the CLI's `--plot`/`--phase` files being the very text the page is given for
//! the same run (the browser face adds the library's `qt`/`phase` SVG to its `:simulate`
//! reply; `web/tests/cli_agrees.rs` compares that reply with the CLI's files directly).

use lagrange::chart::{self, Chart, Figure, Series};
use lagrange::report::SimulationReport;
use lagrange::tutor::response::AnalysisReport;
use lagrange::tutor::{Progress, Response, Session};

use crate::helpers::lagrange;

/// The report of the page's `:simulate` line on a bank problem.
fn session_run(problem: &str, line: &str) -> SimulationReport {
    let mut s = Session::new(lagrange::embedded::bank(), Progress::new());
    s.handle(&format!(":open {problem}"));
    for r in s.handle(line) {
        if let Response::Analysis(a) = r
            && let AnalysisReport::Simulate(report) = a.report
        {
            return *report;
        }
    }
    panic!("{line}: no simulation");
}

#[test]
fn a_small_chart_is_one_stable_self_contained_svg() {
    // Two curves (a legend), a gap where a value is not finite, and names that need escaping.
    let t = [0.0, 0.5, 1.0, 1.5, 2.0];
    let a = Series::new("a<b", t.iter().map(|&t| (t, t * t)).collect());
    let b = Series::new(
        "\"b\" & c",
        t.iter()
            .map(|&t| (t, if t == 1.0 { f64::NAN } else { 4.0 - t }))
            .collect(),
    );
    let chart = Chart::new("x & y", "t / s", "x < 5 / m", vec![a, b]);
    let svg = Figure::new("Two <curves>", vec![chart]).to_svg();
    for forbidden in ["<script", "style", "href", "http://www.w3.org/1999", "url("] {
        assert!(!svg.contains(forbidden), "{forbidden}");
    }
    assert!(svg.contains(">a&lt;b</text>") && svg.contains(">&quot;b&quot; &amp; c</text>"));
    insta::assert_snapshot!(svg);
}

#[test]
fn the_pendulums_axes_cover_its_swing_and_no_more_than_a_tick_beyond() {
    // Released at rest from θ = 1 rad (l = 1 m, g = 9.81 m/s²): θ swings within ±1 and
    // |θ̇| reaches √(2 g/l (1 − cos 1)) = 3.0032 rad/s at the bottom.
    let report = session_run("simple-pendulum", ":simulate --t-end 3");
    let phase = chart::phase(&report);
    let c = &phase.charts[0];
    assert_eq!((c.x.lo, c.x.hi), (-1.0, 1.0), "{:?}", c.x.texts);
    let w_max = (2.0 * 9.81 * (1.0 - 1.0_f64.cos())).sqrt();
    assert!((w_max - 3.0032).abs() < 1e-4);
    let step = c.y.values[1] - c.y.values[0];
    assert!(c.y.hi >= w_max && c.y.hi - w_max < step, "{:?}", c.y.texts);
    assert!(
        -c.y.lo >= w_max && -c.y.lo - w_max < step,
        "{:?}",
        c.y.texts
    );
    assert_eq!(
        (c.x_label.as_str(), c.y_label.as_str()),
        ("θ / rad", "θ\u{307} / rad s⁻¹")
    );
    let qt = chart::qt(&report);
    assert_eq!((qt.charts[0].x.lo, qt.charts[0].x.hi), (0.0, 3.0));
    assert_eq!(
        qt.charts[0].x.texts,
        ["0", "0.5", "1", "1.5", "2", "2.5", "3"]
    );
}

#[test]
fn the_clis_picture_files_are_the_pages_charts_byte_for_byte() {
    // The page's `:simulate --t-end 2` on the double pendulum: its suggested start and
    // parameters, 400 samples; the CLI told the same.
    let report = session_run("double-pendulum", ":simulate --t-end 2");
    let d = crate::helpers::scratch("chart-same");
    let (q, p) = (d.join("q.svg"), d.join("p.svg"));
    let pairs = |s: &lagrange::report::simulation::State| -> String {
        let each: Vec<String> = s.0.iter().map(|(n, v)| format!("{n}={v}")).collect();
        each.join(", ")
    };
    let (init, params) = (pairs(&report.start), pairs(&report.params));
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--t-end",
        "2",
        "--samples",
        "400",
        "--init",
        &init,
        "--params",
        &params,
        "--plot",
        q.to_str().unwrap(),
        "--phase",
        p.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let read = |path: &std::path::Path| std::fs::read_to_string(path).unwrap();
    assert_eq!(read(&q), chart::qt(&report).to_svg());
    assert_eq!(read(&p), chart::phase(&report).to_svg());
    assert!(read(&q).contains(">θ₁, θ₂ / rad</text>"));
}
