//! `swarmplan node-time`.

use crate::error::{Error, Result};

/// Node time.
#[derive(Debug, clap::Args)]
pub struct NodeTimeArgs {}

/// Runs the subcommand.
pub fn run(_args: NodeTimeArgs) -> Result<i32> {
    Err(Error::invalid(
        "E0000",
        "node_time",
        "not available yet",
        "wait",
    ))
}
