//! Mechanics: from a Lagrangian (or from bodies and potentials) to equations of motion,
//! accelerations, conserved quantities, constraint forces, equilibria and normal modes.
//!
//! This layer knows no students and no terminal; it builds on [`crate::expr`] only.

pub mod accel;
pub mod bodies;
pub(crate) mod constraint_check;
pub(crate) mod constraints;
pub(crate) mod coordinate;
pub mod derive;
pub(crate) mod energy;
pub mod equilibria;
pub mod error;
pub mod fixtures;
pub(crate) mod linalg;
pub(crate) mod linearize;
pub(crate) mod magnitude;
pub mod modes;
pub mod naming;
pub mod point_force;
pub mod quadratic;
pub mod rigid;
pub(crate) mod sample;
pub(crate) mod singular;
pub mod state;
pub mod steady;
pub mod symbolic_modes;
pub mod system;

pub use bodies::{Body, Potential};
pub use derive::{CoordinateSteps, Derivation};
pub use energy::{Conservation, Energy, VelocityParts};
pub use error::MechError;
pub use point_force::PointForce;
pub use rigid::{Inertia, Orientation, Rigid, RigidError, RigidSpec};
pub use state::Layout;
pub use system::{Constraint, ConstraintKind, Coordinate, Domain, Parameter, System};
