//! Issue 14, item 4 (rest): `simulate --portrait N --phase FILE` draws a family of
//! trajectories at a grid of energies; axes carry SI units for bank problems and none for a
//! typed Lagrangian; the REPL's `:simulate` draws a terminal chart. The physics is checked
//! against closed forms of the pendulum, h = ½ m l² θ̇² − m g l cos θ.

use std::path::Path;

use crate::helpers::lagrange;
use lagrange::report::SimulationOptions;
use lagrange::report::portrait::portrait_family;
use lagrange::simulate::Method;
use lagrange::simulate::portrait::CurveKind;

const PI: f64 = std::f64::consts::PI;
const M: f64 = 1.3;
const L: f64 = 0.8;
const G: f64 = 9.81;

fn dir(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("portrait-{name}"))
}

fn options(t_end: f64) -> SimulationOptions {
    SimulationOptions {
        params: vec![("m".into(), M), ("l".into(), L), ("g".into(), G)],
        init: vec![],
        t_end,
        method: Method::Dop853,
        rtol: 1e-9,
        atol: 1e-9,
        dt: None,
        report_at: vec![],
        samples: 1500,
    }
}

#[test]
fn the_pendulum_family_has_librations_the_separatrix_and_rotations_both_ways() {
    let mut sys = lagrange::bank::embedded::problem("simple-pendulum")
        .unwrap()
        .system;
    let p = portrait_family(&mut sys, &options(8.0), 9).unwrap();
    let mgl = M * G * L;
    // V = −m g l cos θ: the bottom is h = −m g l, the separatrix 2 m g l above it.
    assert!(p.q_min.abs() < 1e-6);
    assert!((p.h_min + mgl).abs() < 1e-9 * mgl, "{}", p.h_min);
    let sep = p.separatrix.unwrap();
    assert!((sep - p.h_min - 2.0 * mgl).abs() < 1e-9 * mgl, "{sep}");
    assert_eq!(p.window, Some((p.q_min - PI, p.q_min + PI)));
    let count = |k: CurveKind| p.curves.iter().filter(|c| c.kind == k).count();
    assert_eq!(count(CurveKind::Libration), 4);
    assert_eq!(count(CurveKind::Separatrix), 2);
    assert_eq!(count(CurveKind::Rotation), 8);
    for c in &p.curves {
        let (lo, hi) = c
            .points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), q| {
                (a.min(q.0), b.max(q.0))
            });
        match c.kind {
            CurveKind::Libration => {
                // Closed inside (−π, π), turning at cos θ_max = −E/(m g l).
                let amp = (-c.energy / mgl).acos();
                assert!(lo > -PI && hi < PI, "{lo} {hi}");
                assert!((hi - amp).abs() < 1e-2 && (lo + amp).abs() < 1e-2, "{amp}");
                let last = c.points.last().unwrap();
                assert!(last.0.abs() < 0.05 * amp && last.1 > 0.0, "{last:?}");
            }
            CurveKind::Rotation => {
                // A full period, in the direction it started, never stopping: at the top
                // ½ m l² θ̇² = E − m g l.
                assert!(hi - lo >= 2.0 * PI, "{lo} {hi}");
                let v_top = (2.0 * (c.energy - mgl) / (M * L * L)).sqrt();
                let v_min = c.points.iter().fold(f64::INFINITY, |a, q| a.min(q.1.abs()));
                assert!((v_min - v_top).abs() < 0.02 * v_top, "{v_min} {v_top}");
                assert!(c.points.iter().all(|q| (q.1 > 0.0) == c.forward));
            }
            CurveKind::Separatrix => {
                // One branch from the saddle at −π to the one at +π, slowing to a near stop at
                // both, with ½ m l² θ̇² = m g l (1 + cos θ) all along.
                assert!(hi > PI - 0.05 && hi < PI + 1e-6, "{hi}");
                assert!(lo < -PI + 0.05 && lo > -PI - 1e-6, "{lo}");
                for &(q, v) in &c.points {
                    let want = (2.0 * G / L * (1.0 + q.cos())).sqrt();
                    assert!((v.abs() - want).abs() < 1e-4 * (G / L).sqrt(), "{q} {v}");
                    assert_eq!(v > 0.0, c.forward);
                }
            }
        }
    }
}

#[test]
fn the_cli_draws_the_family_with_units_on_a_bank_problem() {
    let d = dir("bank");
    let phase = d.join("portrait.svg");
    let (code, _, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--t-end",
        "6",
        "--samples",
        "300",
        "--portrait",
        "5",
        "--phase",
        phase.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let svg = std::fs::read_to_string(&phase).unwrap();
    assert!(
        svg.contains("θ / rad") && svg.contains("θ\u{307} / rad s⁻¹"),
        "{svg}"
    );
    // h = −m g l cos θ, separatrix at +m g l = 9.81 J.
    assert!(svg.contains("separatrix, h = 9.81 J"), "{svg}");
}

#[test]
fn a_typed_lagrangian_has_no_units_on_any_axis() {
    let d = dir("typed");
    let (phase, q) = (d.join("phase.svg"), d.join("q.svg"));
    let (code, _, err) = lagrange(&[
        "simulate",
        "-L",
        "theta'^2/2 + 9.81*cos(theta)",
        "--coords",
        "theta",
        "--t-end",
        "3",
        "--samples",
        "200",
        "--portrait",
        "3",
        "--phase",
        phase.to_str().unwrap(),
        "--plot",
        q.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    for path in [&phase, &q] {
        let svg = std::fs::read_to_string(path).unwrap();
        assert!(!svg.contains(" / "), "{svg}");
        assert!(!svg.contains(" J"), "{svg}");
    }
}

#[test]
fn bad_portrait_requests_exit_2_with_the_reason() {
    let d = dir("bad");
    let phase = d.join("p.svg");
    let base = [
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--t-end",
        "1",
    ];
    let run = |extra: &[&str]| {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        lagrange(&args)
    };
    let p = phase.to_str().unwrap();
    for (extra, want) in [
        (vec!["--portrait", "0", "--phase", p], "give 1 to 200"),
        (vec!["--portrait", "201", "--phase", p], "give 1 to 200"),
        (vec!["--portrait", "5"], "give --phase"),
    ] {
        let (code, _, err) = run(&extra);
        assert_eq!(code, 2, "{extra:?}: {err}");
        assert!(err.contains(want) && !err.contains("panicked"), "{err}");
    }
    assert!(!phase.exists());
    // Two degrees of freedom are refused with the reason.
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        "m1=1, m2=1, l1=1, l2=1, g=9.81",
        "--t-end",
        "1",
        "--portrait",
        "3",
        "--phase",
        p,
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("one degree of freedom"), "{err}");
}

/// The documented command draws the committed `docs/pendulum-portrait.svg`: every element in
/// place to a pixel.
#[test]
fn the_readme_portrait_is_what_its_command_draws() {
    let d = dir("readme");
    let fresh = d.join("pendulum-portrait.svg");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let page = std::fs::read_to_string(root.join("docs/simulation.md")).unwrap();
    let cmd = "--t-end 10 --samples 300 --portrait 15 --phase docs/pendulum-portrait.svg";
    assert!(page.contains(cmd), "docs/simulation.md lost its command");
    let (code, _, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--t-end",
        "10",
        "--samples",
        "300",
        "--portrait",
        "15",
        "--phase",
        fresh.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let committed = std::fs::read_to_string(root.join("docs/pendulum-portrait.svg")).unwrap();
    let fresh = std::fs::read_to_string(&fresh).unwrap();
    crate::helpers::assert_svg_agrees(&fresh, &committed, "docs/pendulum-portrait.svg");
}

/// Runs the REPL with `input` piped in, without a progress file: (exit code, stdout).
fn repl(input: &str) -> (i32, String) {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(["repl", "--no-save"])
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// The complete elliptic integral K(k) by the arithmetic–geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-15 {
        (a, b) = ((a + b) / 2.0, (a * b).sqrt());
    }
    PI / (2.0 * a)
}

#[test]
fn repl_simulate_draws_the_chart_and_comes_back_after_one_period() {
    // θ(0) = 1 at rest: the period is 4 K(sin ½) / √(g/l), after which θ is 1 again.
    let period = 4.0 * elliptic_k(0.5f64.sin()) / 9.81f64.sqrt();
    let input = format!(
        ":open simple-pendulum\n:simulate --init theta=1\n\
         :simulate --init theta=1 --t-end {period} --params m=1, l=1, g=9.81\n\
         :help simulate\n:simulate --t-end -1\n"
    );
    let (code, out) = repl(&input);
    assert_eq!(code, 0, "{out}");
    // The first run takes the problem's suggested values (m = l = 1, g = 9.81).
    assert_eq!(out.matches("Final: θ = ").count(), 2, "{out}");
    assert!(out.contains("θ(t) (θ / rad against t / s)"), "{out}");
    assert!(
        out.contains('⠀') || out.contains('⡀'),
        "a braille chart: {out}"
    );
    let last = out
        .lines()
        .filter_map(|l| l.strip_prefix("Final: θ = "))
        .next_back()
        .unwrap();
    let theta: f64 = last.split(',').next().unwrap().trim().parse().unwrap();
    assert!((theta - 1.0).abs() < 1e-6, "{theta}");
    assert!(out.contains(":simulate [--init …]"), "{out}");
    assert!(out.contains("error[bad-simulate]: --t-end"), "{out}");
}
