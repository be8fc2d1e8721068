//! The problem bank: the TOML format, loading it into problems whose system the mechanics
//! engine can analyse, verifying every stated answer against the physics, and the default
//! bank embedded in the binary.

pub(crate) mod build;
mod build_definitions;
mod build_domain;
mod build_linearized;
mod build_numeric;
mod build_part;
mod build_reader;
mod build_rigid;
mod build_simulation;
pub mod embedded;
pub mod finding;
pub mod load;
pub mod schema;
pub mod verify;
mod verify_equilibria;
mod verify_expression;
mod verify_failed;
mod verify_frequencies;
mod verify_steady;

pub use crate::problem::{Part, PartKind, Problem, Quantity};
pub use finding::Finding;
pub use load::{Bank, load_dir, load_str};
