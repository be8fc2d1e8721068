//! The default bank, compiled into the binary so that `lagrange` works from any directory.

use super::load::{Bank, load_str};

/// (file name, contents) of every problem in `problems/`.
pub const FILES: &[(&str, &str)] = &[
    (
        "simple-pendulum.toml",
        include_str!("../../problems/simple-pendulum.toml"),
    ),
    (
        "bead-wire.toml",
        include_str!("../../problems/bead-wire.toml"),
    ),
    (
        "double-pendulum.toml",
        include_str!("../../problems/double-pendulum.toml"),
    ),
    ("atwood.toml", include_str!("../../problems/atwood.toml")),
    (
        "bead-parabola.toml",
        include_str!("../../problems/bead-parabola.toml"),
    ),
    (
        "spring-incline.toml",
        include_str!("../../problems/spring-incline.toml"),
    ),
    (
        "atwood-tension.toml",
        include_str!("../../problems/atwood-tension.toml"),
    ),
    (
        "rolling-disk.toml",
        include_str!("../../problems/rolling-disk.toml"),
    ),
    (
        "rotating-hoop.toml",
        include_str!("../../problems/rotating-hoop.toml"),
    ),
];

/// Loads the embedded bank.
pub fn bank() -> Bank {
    let mut b = Bank::default();
    for (name, text) in FILES {
        match load_str(&format!("problems/{name}"), text) {
            Ok(p) => b.problems.push(p),
            Err(f) => b.failures.push(f),
        }
    }
    b
}
