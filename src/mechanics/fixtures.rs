//! Standard systems for benchmarks, examples and tests, built the way the bank builds its
//! problems (from bodies and potentials), so that they exercise the whole engine.

use super::bodies::{Body, Potential};
use super::coordinate::Coordinate;
use super::system::System;
use crate::expr::{Func, Pool};

/// The double pendulum as the course notes and the SciPy anchor write it: masses m1, m2,
/// lengths l1, l2, gravity g, angles from the downward vertical.
pub const DOUBLE_PENDULUM: &str = "(m1 + m2)/2*l1^2*theta1'^2 + m2/2*l2^2*theta2'^2 \
    + m2*l1*l2*theta1'*theta2'*cos(theta1 - theta2) + (m1 + m2)*g*l1*cos(theta1) \
    + m2*g*l2*cos(theta2)";

/// The anchor's values of its parameters: m = l = 1, g = 9.81.
pub const DOUBLE_PENDULUM_ANCHOR: [(&str, f64); 5] = [
    ("m1", 1.0),
    ("m2", 1.0),
    ("l1", 1.0),
    ("l2", 1.0),
    ("g", 9.81),
];

/// [`DOUBLE_PENDULUM`] as a system in θ₁, θ₂.
pub fn double_pendulum() -> System {
    // The text is this file's own: it reads.
    System::from_lagrangian(DOUBLE_PENDULUM, &["theta1", "theta2"])
        .unwrap_or_else(|e| unreachable!("the double pendulum reads: {e}"))
}

/// The planar n-link pendulum (equal masses m, equal lengths l, angles q1…qn from the
/// downward vertical, gravity g), built from its bodies' positions — the benchmark system.
pub fn n_link_pendulum(n: usize) -> System {
    let mut pool = Pool::new();
    let coordinates: Vec<Coordinate> = (1..=n)
        .map(|i| {
            let name = format!("q{i}");
            Coordinate {
                sym: pool.symbol(&name),
                name,
                periodic: true,
                range: (-std::f64::consts::PI, std::f64::consts::PI),
                domain: crate::mechanics::system::Domain::ANY,
            }
        })
        .collect();
    let (m, l, g) = (pool.sym("m"), pool.sym("l"), pool.sym("g"));
    let mut bodies = Vec::with_capacity(n);
    let (mut x, mut y) = (pool.zero(), pool.zero());
    for c in &coordinates {
        let q = pool.var(c.sym, 0);
        let (s, co) = (pool.func(Func::Sin, q), pool.func(Func::Cos, q));
        let dx = pool.mul(l, s);
        let dy = pool.mul(l, co);
        x = pool.add(x, dx);
        y = pool.sub(y, dy);
        bodies.push(Body::Point {
            mass: m,
            position: vec![x, y],
        });
    }
    System::from_bodies(
        pool,
        coordinates,
        &bodies,
        &[Potential::Gravity { g, axis: 1 }],
    )
}
