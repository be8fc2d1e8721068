//! Issue 14, items 6 and 4-PNG: `simulate --grid … --until-flip`, the flip-time map. Flip
//! times are checked against an independent single-trajectory DOP853 run at tight
//! tolerance; the lane evaluator against the scalar one on every bank system; PNG files by
//! their signature and size; the errors by exit code and message.

use crate::helpers::lagrange;
use lagrange::mechanics::System;
use lagrange::mechanics::accel::Dynamics;
use lagrange::simulate::{Rhs, Tolerances, dop853};

const DP_PARAMS: &str = "m1=1, m2=1, l1=1, l2=1, g=9.81";
use lagrange::mechanics::fixtures::{DOUBLE_PENDULUM as DP, DOUBLE_PENDULUM_ANCHOR};

fn dir(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("grid-{name}"))
}

/// The first time |θ₁| or |θ₂| reaches π, from a DOP853 run at rtol = atol = 1e-12: the
/// dense output scanned every 1e-3 s, then the crossing bisected.
fn reference_flip(theta1: f64, theta2: f64, t_end: f64) -> Option<f64> {
    let mut sys = System::from_lagrangian(DP, &["theta1", "theta2"]).unwrap();
    let mut rhs = Rhs::new(&mut sys, &DOUBLE_PENDULUM_ANCHOR).unwrap();
    let traj = dop853(
        &mut rhs,
        0.0,
        &[theta1, theta2, 0.0, 0.0],
        t_end,
        &Tolerances::new(1e-12, 1e-12),
    )
    .unwrap();
    let over = |t: f64| {
        let y = traj.at(t).unwrap();
        y[0].abs().max(y[1].abs()) >= std::f64::consts::PI
    };
    let steps = (t_end / 1e-3) as usize;
    let k = (1..=steps).find(|&k| over(k as f64 * 1e-3))?;
    let (mut a, mut b) = ((k - 1) as f64 * 1e-3, k as f64 * 1e-3);
    for _ in 0..40 {
        let m = 0.5 * (a + b);
        if over(m) { b = m } else { a = m }
    }
    Some(b)
}

#[test]
fn flip_times_of_a_small_grid_match_single_tight_runs() {
    let d = dir("small");
    let csv = d.join("map.csv");
    let (code, out, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "2",
        "--grid",
        "theta1=-2.9:2.9:3, theta2=-2.9:2.9:3",
        "--until-flip",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("9 cells"), "{out}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("theta1,theta2,flip_time,outcome"));
    let mut flipped = 0;
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let (a, b): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
        let want = reference_flip(a, b, 2.0);
        match want {
            Some(t) => {
                flipped += 1;
                let got: f64 = f[2].parse().unwrap();
                // RK4 at dt = 1e-3 plus the linear interpolation inside a step.
                assert!((got - t).abs() < 1e-4, "({a}, {b}): {got} against {t}");
                assert_eq!(f[3], "flipped");
            }
            None => assert_eq!((f[2], f[3]), ("", "did_not_flip"), "({a}, {b})"),
        }
    }
    assert!(flipped >= 2, "the corners go over the top: {text}");
}

#[test]
fn small_angles_at_rest_never_flip_and_starts_over_the_top_are_said() {
    // At rest within 0.3 rad the energy is far below what either bob needs to reach the top.
    let (code, out, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "3",
        "--dt",
        "0.01",
        "--grid",
        "theta1=-0.3:0.3:3, theta2=-0.3:0.3:3",
        "--until-flip",
        "--json",
    ]);
    assert_eq!(code, 0, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(
        (v["cells"].as_u64(), v["did_not_flip"].as_u64()),
        (Some(9), Some(9))
    );
    assert_eq!(v["trajectory_steps"].as_u64(), Some(9 * 300));
    let (code, out, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "1",
        "--grid",
        "theta1=3.2:3.2:1",
        "--until-flip",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("1 start over the top already (flip time 0)"),
        "{out}"
    );
}

#[test]
fn cells_whose_energy_cannot_reach_the_top_never_flip() {
    // At rest, h = −g(2 cos θ₁ + cos θ₂) (m = l = 1); θ₂ = π needs h ≥ −g at the least
    // (θ₁ = 0), θ₁ = π needs h ≥ g: so no flip ever where 2 cos θ₁ + cos θ₂ > 1.
    let d = dir("energy");
    let csv = d.join("map.csv");
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "3",
        "--dt",
        "0.01",
        "--grid",
        "theta1=-3:3:9, theta2=-3:3:9",
        "--until-flip",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&csv).unwrap();
    let (mut forbidden, mut flipped) = (0, 0);
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let (a, b): (f64, f64) = (f[0].parse().unwrap(), f[1].parse().unwrap());
        if 2.0 * a.cos() + b.cos() > 1.0 {
            forbidden += 1;
            assert_eq!(f[3], "did_not_flip", "({a}, {b})");
        } else if f[3] == "flipped" {
            flipped += 1;
        }
    }
    assert!(
        forbidden >= 9 && flipped >= 9,
        "{forbidden} forbidden, {flipped} flipped"
    );
}

/// Width and height from a PNG's IHDR chunk, after checking the signature.
fn png_size(path: &std::path::Path) -> (u32, u32) {
    let bytes = std::fs::read(path).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |s: &[u8]| u32::from_be_bytes([s[0], s[1], s[2], s[3]]);
    (be(&bytes[16..20]), be(&bytes[20..24]))
}

#[test]
fn pictures_ending_in_png_are_png_files_of_the_asked_size() {
    let d = dir("png");
    let map = d.join("map.png");
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "0.5",
        "--dt",
        "0.01",
        "--grid",
        "theta1=-3:3:4, theta2=-3:3:3",
        "--until-flip",
        "--plot",
        map.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(png_size(&map), (960, 800));
    let (q, p, e) = (d.join("q.png"), d.join("p.PNG"), d.join("e.png"));
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--init",
        "theta1=1",
        "--t-end",
        "1",
        "--samples",
        "50",
        "--plot",
        q.to_str().unwrap(),
        "--phase",
        p.to_str().unwrap(),
        "--energy",
        e.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    // Each PNG is the chart the SVG of the same run draws, at the SVG's size.
    let svgs = [d.join("q.svg"), d.join("p.svg"), d.join("e.svg")];
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--init",
        "theta1=1",
        "--t-end",
        "1",
        "--samples",
        "50",
        "--plot",
        svgs[0].to_str().unwrap(),
        "--phase",
        svgs[1].to_str().unwrap(),
        "--energy",
        svgs[2].to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let svg_size = |path: &std::path::Path| {
        let text = std::fs::read_to_string(path).expect("svg");
        let attr = |name: &str| -> u32 {
            let at = text.find(&format!(" {name}=\"")).expect("size attribute") + name.len() + 3;
            text[at..]
                .split('"')
                .next()
                .and_then(|v| v.parse().ok())
                .expect("a number")
        };
        (attr("width"), attr("height"))
    };
    for (png, svg) in [&q, &p, &e].into_iter().zip(&svgs) {
        let (w, h) = svg_size(svg);
        assert!(w >= 320 && h >= 200, "{svg:?} is {w}×{h}");
        assert_eq!(png_size(png), (w, h), "{png:?}");
    }
}

#[test]
fn grid_errors_exit_2_with_a_clear_message() {
    let cases: [(&str, &str); 5] = [
        (
            "theta1=-3:3, theta2=0:1:2",
            "column 8: `-3:3` should be start:end:count",
        ),
        (
            "theta1=-3:3:2, theta2=0:1:x",
            "column 23: the count of `theta2`",
        ),
        (
            "theta1=-3:3:2000, theta2=-3:3:2000",
            "4000000 cells, over the limit of 1000000",
        ),
        (
            "theta3=-3:3:2",
            "`theta3` is not a coordinate or velocity of the system (did you mean `theta1`?)",
        ),
        ("theta1=-3:3:2, theta2=0:1:2, theta1'=0:1:2", "3 axes"),
    ];
    for (spec, want) in cases {
        let (code, _, err) = lagrange(&[
            "simulate",
            "double-pendulum",
            "--params",
            DP_PARAMS,
            "--t-end",
            "1",
            "--grid",
            spec,
            "--until-flip",
        ]);
        assert_eq!(code, 2, "{spec}: {err}");
        assert!(err.contains(want), "{spec}: {err}");
    }
    let (code, _, err) = lagrange(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--t-end",
        "1",
        "--grid",
        "theta1=0:1:2",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("add --until-flip"), "{err}");
}

/// Equal to rounding: the lanes compute sin and cos in vector form, within a few ulp of libm.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-13 * a.abs().max(b.abs()).max(1.0)
}

#[test]
fn lanes_evaluate_every_bank_system_as_the_scalar_program_does() {
    let bank = lagrange::bank::embedded::bank();
    let mut checked = 0;
    for problem in &bank.problems {
        let mut sys = problem.system.clone();
        let Ok(d) = sys.derive() else { continue };
        let Ok(dynamics) = Dynamics::new(&sys, &d) else {
            continue;
        };
        let n = sys.n();
        let len = sys.state_layout().len(sys.parameters.len());
        let points: Vec<[f64; 4]> = (0..len)
            .map(|k| std::array::from_fn(|l| 0.3 + 0.7 * ((k * 7 + l * 3) % 11) as f64 / 11.0))
            .collect();
        let mut scratch = dynamics.scratch_lanes::<4>();
        let (mut m, mut f) = (vec![[0.0; 4]; n * n], vec![[0.0; 4]; n]);
        let bad = dynamics.mass_and_forcing_lanes(&points, &mut scratch, &mut m, &mut f);
        let mut s = dynamics.scratch();
        for l in 0..4 {
            let point: Vec<f64> = points.iter().map(|p| p[l]).collect();
            let (mut ms, mut fs) = (vec![0.0; n * n], vec![0.0; n]);
            match dynamics.mass_and_forcing_into(&point, &mut s, &mut ms, &mut fs) {
                Ok(()) => {
                    assert_eq!(bad >> l & 1, 0, "{}", problem.id);
                    assert!(
                        ms.iter().zip(&m).all(|(a, b)| close(*a, b[l])),
                        "{}",
                        problem.id
                    );
                    assert!(
                        fs.iter().zip(&f).all(|(a, b)| close(*a, b[l])),
                        "{}",
                        problem.id
                    );
                }
                Err(_) => assert_eq!(bad >> l & 1, 1, "{}", problem.id),
            }
        }
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} bank systems");
}
