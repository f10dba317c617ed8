//! What every search of one exact solve shares: the node and time [`Budget`] with its one limit
//! check, the [`Memo`] of failed bin-completion states, the [`Decision`] outcome of a capacity
//! query "do all drones fit on `k` pads with every load `<= C`?", and the [`SubsetSums`] table
//! of the searches that split or list drone sets by their sum.

mod budget;
mod memo;
mod subset_sums;

pub(crate) use budget::{Budget, CLOCK_EVERY_NODES};
pub(crate) use memo::{Memo, WordHasher, MEMO_MAX_STATES};
pub(crate) use subset_sums::{SubsetSums, TABLE_WORDS_PER_NODE};

/// Real-valued times are checked against `C (1 + CAP_SLACK)`: exact arithmetic would fill the
/// last pad to exactly its share of the waste, and rounding must not turn that into a failure.
/// A failure then proves `nt > C`; a success returns an assignment whose makespan is recomputed.
pub(crate) const CAP_SLACK: f64 = 1e-11;

/// Outcome of one exact search (the assignment branch and bound, sequential partitioning, the
/// search over capacities): whether it proved its incumbent optimal, the best lower bound it
/// proved and the incumbent's makespan (minutes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SearchOutcome {
    pub proven: bool,
    pub lower_bound_min: f64,
    pub incumbent_min: f64,
}

/// Outcome of a decision search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decision {
    /// Every drone fits; the pads are in the search's `pad_of`.
    Fits,
    /// Proven: no assignment has every load `<= C`.
    DoesNotFit,
    /// A node or time limit stopped the search.
    Stopped,
}
