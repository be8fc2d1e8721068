//! The expression language: reading what students type, canonical expressions in an arena,
//! evaluation, differentiation, simplification for people, printing and dimensions.
//!
//! This layer knows no physics beyond "a coordinate q has time derivatives q', q''".

pub(crate) mod ast;
pub(crate) mod build;
pub(crate) mod context;
pub(crate) mod diff;
pub(crate) mod dimension;
pub mod error;
pub mod eval;
pub(crate) mod exact;
pub(crate) mod lexer;
pub(crate) mod lower;
pub(crate) mod names;
pub(crate) mod node;
pub(crate) mod order;
pub mod parser;
pub mod pool;
pub(crate) mod print;
pub(crate) mod simplify;

pub use context::Context;
pub use dimension::{DimError, Dimension, DimensionSyntax, Dimensions};
pub use error::{ParseError, ParseErrorKind};
pub use eval::{Program, Undefined};
pub use lower::{Reading, read, read_equation, read_expr};
pub use names::spelled;
pub use node::{Func, Id, Node, Sym};
pub use pool::Pool;
pub use print::Style;
pub use simplify::Factored;
