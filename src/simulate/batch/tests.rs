//! The batch against the scalar path, its physics (small swings never flip, a constrained
//! system) and the settings it refuses.

use super::*;
use crate::mechanics::System;
use crate::mechanics::fixtures::n_link_pendulum;

fn double_pendulum() -> Rhs {
    let mut sys = n_link_pendulum(2);
    Rhs::new(&mut sys, &[("m", 1.0), ("l", 1.0), ("g", 9.81)]).unwrap()
}

#[test]
fn a_constrained_system_flips_as_its_scalar_right_hand_side_says() {
    // θ tied to x = θ: the effective inertia is m l² + m, not m l² (the lanes alone
    // would ignore the constraint and flip sooner).
    let l = "m*l^2*theta'^2/2 + m*x'^2/2 + m*g*l*cos(theta)";
    let mut sys = System::from_lagrangian(l, &["theta", "x"]).unwrap();
    sys.coordinates[0].periodic = true;
    sys.add_constraint("x - theta").unwrap();
    let rhs = Rhs::new(&mut sys, &[("m", 1.0), ("l", 1.0), ("g", 9.81)]).unwrap();
    let starts = [0.0, 0.0, 7.0, 7.0, 0.0, 0.0, 8.0, 8.0];
    let mut s = FlipSettings {
        t_end: 3.0,
        dt: 1e-3,
        watch: vec![0],
        lanes: 1,
    };
    let scalar = flip_times(&rhs, &starts, &s).unwrap();
    s.lanes = 16;
    assert_eq!(flip_times(&rhs, &starts, &s).unwrap(), scalar);
    // Energy: (m l² + m) θ'²/2 = 2 m g l at the top needs θ'(0)² ≥ 4 g l/(l² + 1) = 19.6:
    // 7 and 8 rad/s both flip; without the constraint's mass the time would be shorter.
    assert!(
        scalar.outcomes.iter().all(|o| o.flip_time().is_some()),
        "{scalar:?}"
    );
}

fn settings(lanes: usize) -> FlipSettings {
    FlipSettings {
        t_end: 2.0,
        dt: 1e-2,
        watch: vec![0, 1],
        lanes,
    }
}

/// Starts of every kind: small swings, flips, one over the top, one not finite.
fn starts() -> Vec<f64> {
    let mut s = Vec::new();
    for a in [-3.0, -2.5, -0.1, 0.0, 0.05, 2.0, 2.9, 3.1] {
        for b in [-3.0, 0.0, 3.05] {
            s.extend_from_slice(&[a, b, 0.0, 0.0]);
        }
    }
    s.extend_from_slice(&[3.5, 0.0, 0.0, 0.0, f64::NAN, 0.0, 0.0, 0.0]);
    s
}

#[test]
fn lanes_agree_with_the_scalar_path() {
    let rhs = double_pendulum();
    let starts = starts();
    let reference = flip_times(&rhs, &starts, &settings(1)).unwrap();
    assert!(
        reference
            .outcomes
            .iter()
            .any(|o| matches!(o, Outcome::Flipped { .. }))
    );
    assert_eq!(
        reference.outcomes[24],
        Outcome::StartsOver { coordinate: 0 }
    );
    assert_eq!(reference.outcomes[25], Outcome::Diverged { t: 0.0 });
    for k in [4, 8, 16, 32] {
        // The lanes' sine and cosine are libm's to a few ulp, so times agree closely.
        let got = flip_times(&rhs, &starts, &settings(k)).unwrap();
        assert_eq!(got.steps, reference.steps, "{k} lanes");
        for (a, b) in got.outcomes.iter().zip(&reference.outcomes) {
            assert_eq!(
                std::mem::discriminant(a),
                std::mem::discriminant(b),
                "{k} lanes"
            );
            let (ta, tb) = (a.flip_time().unwrap_or(0.0), b.flip_time().unwrap_or(0.0));
            assert!((ta - tb).abs() < 1e-9, "{k} lanes: {a:?} against {b:?}");
        }
    }
}

#[test]
fn small_swings_at_rest_never_flip() {
    // Energy conservation forbids it: at rest at 0.1 rad neither bob can reach the top.
    let rhs = double_pendulum();
    let run = flip_times(&rhs, &[0.1, -0.1, 0.0, 0.0], &settings(4)).unwrap();
    assert_eq!(run.outcomes, vec![Outcome::Stayed]);
    assert_eq!(run.steps, 200);
}

#[test]
fn settings_that_cannot_work_are_refused() {
    let rhs = double_pendulum();
    for s in [
        FlipSettings {
            lanes: 3,
            ..settings(1)
        },
        FlipSettings {
            dt: 0.0,
            ..settings(1)
        },
        FlipSettings {
            t_end: -1.0,
            ..settings(1)
        },
        FlipSettings {
            watch: vec![2],
            ..settings(1)
        },
    ] {
        assert!(matches!(
            flip_times(&rhs, &[0.0; 4], &s),
            Err(SimError::Invalid(_))
        ));
    }
    assert!(flip_times(&rhs, &[0.0; 3], &settings(1)).is_err());
}
