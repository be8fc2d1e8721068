//! The problem bank: the TOML format, loading it into problems whose system the mechanics
//! engine can analyse, verifying every stated answer against the physics, and the default
//! bank embedded in the binary.
// A `Finding` (file, problem, part, message and code: 128 bytes) is the bank's error value,
// made once per failing file and never on a path that is timed; boxing it would change every
// caller for no measurable gain.
#![allow(clippy::result_large_err)]

pub(crate) mod build;
mod build_definitions;
mod build_domain;
mod build_linearized;
mod build_numeric;
mod build_part;
mod build_reader;
mod build_rigid;
mod build_simulation;
mod build_variants;
pub mod embedded;
pub mod export;
pub(crate) mod finding;
mod finding_code;
pub mod load;
pub mod new;
mod new_parts;
mod new_statics;
mod new_toml;
mod new_types;
pub mod schema;
pub(crate) mod schema_read;
pub mod verify;
mod verify_equilibria;
mod verify_expression;
mod verify_failed;
mod verify_frequencies;
mod verify_steady;
pub mod verify_variants;

pub use crate::problem::{Part, PartKind, Problem, Quantity};
pub use finding::Finding;
pub use finding_code::FindingCode;
pub use load::{Bank, BankError, load_dir, load_str};
