//! No sharing: the baseline. Every drone flies on its own battery.

use super::{HopProblem, Transfer};

/// The empty schedule.
pub(super) fn plan(_problem: &HopProblem) -> Vec<Transfer> {
    Vec::new()
}
