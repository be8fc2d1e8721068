//! Mechanics: from a Lagrangian (or from bodies and potentials) to equations of motion,
//! accelerations, conserved quantities, constraint forces, equilibria and normal modes.
//!
//! This layer knows no students and no terminal; it builds on [`crate::expr`] only.

pub mod accel;
pub mod bodies;
pub(crate) mod constraint_check;
pub(crate) mod constraints;
pub(crate) mod coordinate;
pub(crate) mod derive;
pub(crate) mod energy;
pub mod equilibria;
pub(crate) mod error;
// Standard systems for the benches, the fuzzer and the tests: public because they live outside
// the crate, hidden because they are not part of the API.
#[doc(hidden)]
pub mod fixtures;
pub(crate) mod linalg;
pub(crate) mod linearize;
pub(crate) mod magnitude;
pub mod modes;
pub mod naming;
pub(crate) mod point_force;
pub(crate) mod quadratic;
pub(crate) mod rigid;
pub(crate) mod sample;
pub(crate) mod singular;
pub(crate) mod state;
pub mod steady;
pub(crate) mod symbolic_modes;
pub mod system;

pub use bodies::{Body, Potential};
pub use derive::{CoordinateSteps, Derivation};
pub use energy::{Conservation, Energy, VelocityParts};
pub use error::MechError;
pub use point_force::PointForce;
pub use rigid::{Inertia, Orientation, Rigid, RigidError, RigidSpec};
pub use state::Layout;
pub use system::{Constraint, ConstraintKind, Coordinate, Domain, Parameter, System};
