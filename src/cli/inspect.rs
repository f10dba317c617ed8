//! `swarmplan inspect`.

use crate::error::{Error, Result};

/// Describe a network.
#[derive(Debug, clap::Args)]
pub struct InspectArgs {}

/// Runs the subcommand.
pub fn run(_args: InspectArgs) -> Result<i32> {
    Err(Error::invalid(
        "E0000",
        "inspect",
        "not available yet",
        "wait",
    ))
}
