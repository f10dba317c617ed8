//! `swarmplan solve`.

use crate::error::{Error, Result};

/// Plan one request.
#[derive(Debug, clap::Args)]
pub struct SolveArgs {}

/// Runs the subcommand.
pub fn run(_args: SolveArgs) -> Result<i32> {
    Err(Error::invalid(
        "E0000",
        "solve",
        "not available yet",
        "wait",
    ))
}
