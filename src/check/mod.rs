//! Independent checkers: re-verify a plan from the raw problem, without the planners' code paths
//! (only the input and output types are shared).
//!
//! Codes `C3xxx` concern hop schedules ([`hop`]), codes `P5xxx` whole plans ([`plan`]) and plan
//! documents read from a file ([`report`], read by [`plan_file`], whose errors are `E6xxx`).

pub mod free_hop;
pub mod hop;
pub mod plan;
pub mod plan_file;
pub mod report;

pub use free_hop::check_free_hop;
pub use hop::{check_hop, fly_as_written};
pub use plan::check_plan;
pub use report::check_report;
