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
    (
        "cart-pendulum.toml",
        include_str!("../../problems/cart-pendulum.toml"),
    ),
    (
        "cart-pendulum-small.toml",
        include_str!("../../problems/cart-pendulum-small.toml"),
    ),
    (
        "central-force.toml",
        include_str!("../../problems/central-force.toml"),
    ),
    (
        "conical-pendulum.toml",
        include_str!("../../problems/conical-pendulum.toml"),
    ),
    (
        "charge-magnetic.toml",
        include_str!("../../problems/charge-magnetic.toml"),
    ),
    (
        "spring-cart.toml",
        include_str!("../../problems/spring-cart.toml"),
    ),
    (
        "rotating-trap.toml",
        include_str!("../../problems/rotating-trap.toml"),
    ),
    (
        "rotating-trap-fast.toml",
        include_str!("../../problems/rotating-trap-fast.toml"),
    ),
    (
        "pendulum-numbers.toml",
        include_str!("../../problems/pendulum-numbers.toml"),
    ),
];

/// Loads one embedded problem by id: files are named after their id, so only that file is
/// built (a full scan is the fallback if a name and an id ever disagree). An id two files
/// declare is refused, as in a folder ([`Bank::add`]).
pub fn problem(id: &str) -> Option<crate::problem::Problem> {
    let declaring = FILES
        .iter()
        .filter(|(_, text)| super::load::declared_id(text).is_none_or(|d| d == id))
        .count();
    if declaring > 1 {
        return bank().problems.into_iter().find(|p| p.id == id);
    }
    let by_name = FILES
        .iter()
        .find(|(name, _)| name.strip_suffix(".toml") == Some(id))
        .and_then(|(name, text)| load_str(&format!("problems/{name}"), text).ok())
        .filter(|p| p.id == id);
    by_name.or_else(|| bank().problems.into_iter().find(|p| p.id == id))
}

/// Whether a built-in problem has the id `id`, told from the files' `id` lines without
/// building any problem.
pub fn is_built_in(id: &str) -> bool {
    FILES
        .iter()
        .any(|(name, text)| match super::load::declared_id(text) {
            Some(d) => d == id,
            None => name.strip_suffix(".toml") == Some(id),
        })
}

/// Loads the embedded bank.
pub fn bank() -> Bank {
    let mut b = Bank::default();
    for (name, text) in FILES {
        match load_str(&format!("problems/{name}"), text) {
            Ok(p) => b.add(p, format!("problems/{name}")),
            Err(f) => b.failures.push(f),
        }
    }
    b
}
