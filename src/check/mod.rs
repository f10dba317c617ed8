//! Independent checkers: re-verify a plan from the raw problem, without the planners' code paths
//! (only the input and output types are shared).
//! User guide: "Checking plans" (`docs/src/checking.md`), with every rule code.
//!
//! Codes `C3xxx` concern hop schedules ([`check_hop`]), codes `P5xxx` whole plans ([`check_plan`]) and plan
//! documents read from a file ([`check_report`], read by [`plan_file`], whose errors are `E6xxx`),
//! `P55xx` node-time results ([`node_time`]), `P56xx` hop files ([`hop_file`]) and `P57xx` the
//! rows of a bench run ([`bench_rows`]).

pub mod bench_rows;
pub mod decision;
mod free_hop;
mod hop;
pub mod hop_file;
pub mod node_time;
mod plan;
pub mod plan_file;
mod report;
pub mod search;

pub use free_hop::check_free_hop;
pub use hop::{battery_trajectory, check_hop, fly_as_written};
pub use plan::{check_plan, optimal_makespan_min, rebuilt_hop_problem, OPTIMALITY_CHECK_DRONES};
pub use report::{check_report, fingerprint_mismatch, made_on_another_instance};

/// Relative tolerance of a number the checkers recompute and compare with the stated one (a few
/// sums and products of the same inputs; a JSON or CSV round trip keeps every digit).
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// Tolerance of a quantity the checkers integrate again over time (a battery, a charge time, a
/// node time built from them), relative above 1 and absolute below: the replay sums many legs
/// and transfers in another order than the planner, so it agrees to about `1e-12` per step, and
/// `1e-6` leaves room for thousands of steps while catching any change a user makes by hand.
pub const INTEGRATION_TOLERANCE: f64 = 1e-6;

/// Whether `a` and `b` agree within [`RELATIVE_TOLERANCE`] (absolute below 1).
pub(crate) fn close(a: f64, b: f64) -> bool {
    a == b || (a - b).abs() <= RELATIVE_TOLERANCE * a.abs().max(b.abs()).max(1.0)
}

/// Node id -> index in `network.nodes`.
pub(crate) fn node_index(
    network: &crate::problem::Network,
) -> std::collections::HashMap<&str, usize> {
    network
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id.as_str(), i))
        .collect()
}
