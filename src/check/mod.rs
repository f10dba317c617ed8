//! Independent checkers: re-verify a plan from the raw problem, without the planners' code paths
//! (only the input and output types are shared).
//!
//! Codes `C3xxx` concern hop schedules ([`hop`]), codes `P5xxx` whole plans ([`plan`]).

pub mod hop;
pub mod plan;

pub use hop::check_hop;
pub use plan::check_plan;
