//! No sharing: the baseline. Every drone flies on its own battery.

use super::{SegmentProblem, Transfer};

/// The empty schedule.
pub(super) fn plan(_problem: &SegmentProblem) -> Vec<Transfer> {
    Vec::new()
}
