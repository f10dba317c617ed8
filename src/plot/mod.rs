//! The figure of one plan, or of two plans of the same request side by side (`swarmplan plot`):
//! the route on the network, every drone's battery against time with the in-flight transfers,
//! and the pad schedule of every stop.
//! User guide: the command `plot` (`docs/src/commands/plot.md`).
//!
//! [`data`] computes what is drawn from the plan documents and the raw instance (the planning
//! core's types and the independent checker's re-integration, no plotting crate); [`draw`]
//! places it in an SVG with plotters (feature `plot`, which `cli` includes: the command line's
//! `swarmplan plot` and the Python package's `swarmplan.plot` draw the same bytes).

pub mod data;
/// Drawn with plotters (feature `plot`).
#[cfg(feature = "plot")]
pub mod draw;
pub mod hop;
