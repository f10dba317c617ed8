//! `swarmplan generate network|requests`.

use crate::error::{Error, Result};

/// What to generate.
#[derive(Debug, clap::Subcommand)]
pub enum GenerateCommand {
    /// A seeded synthetic rooftop network.
    Network,
}

/// Runs the subcommand.
pub fn run(_cmd: GenerateCommand) -> Result<i32> {
    Err(Error::invalid(
        "E0000",
        "generate",
        "not available yet",
        "wait",
    ))
}
