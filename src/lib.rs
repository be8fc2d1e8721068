//! lagrange: check, derive and explain analytical mechanics.
//!
//! Layers, lowest first (a layer never imports a higher one):
//! - [`expr`]: the expression language — parse, canonical arena, evaluate, differentiate,
//!   simplify, print, dimensions;
//! - [`mechanics`]: Euler–Lagrange equations, accelerations, conserved quantities,
//!   constraint forces, equilibria and normal modes;
//! - [`diagnostic`]: rendering of positioned errors, shared by every face.
//!
//! `src/main.rs` is a thin command-line face over this library.

pub mod diagnostic;
pub mod expr;
pub mod mechanics;
