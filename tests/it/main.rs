//! The integration-test binary: every test of the public library and the CLI, grouped by
//! concept, sharing the helpers in `helpers.rs`.

mod bank;
mod cli;
mod corpus;
mod diagnostics;
mod dimensions;
mod energy13;
mod equilibria13;
mod follow;
mod fuzz_replay;
mod grade;
mod grid14;
mod helpers;
mod hostile;
mod ladder;
mod literature;
mod mechanics;
mod modes13;
mod notation;
mod notation_lists;
mod plot;
mod props;
mod pty;
mod repl;
mod resources;
mod rigid13;
mod scale;
mod session;
mod simulate14;
mod simulate_cli;
mod soundness;
mod steady13;
mod symbolic;
mod sympy13;
mod syntax;
mod tutor_session;
