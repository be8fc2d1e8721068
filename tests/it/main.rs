//! The integration-test binary: every test of the public library and the CLI, grouped by
//! concept, sharing the helpers in `helpers.rs`.

mod bank;
mod cli;
mod corpus;
mod diagnostics;
mod dimensions;
mod helpers;
mod mechanics;
mod props;
mod resources;
mod symbolic;
mod syntax;
