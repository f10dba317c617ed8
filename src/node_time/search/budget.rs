//! Node and time budget shared by every search of one solve.

use crate::node_time::Limits;
use std::time::Instant;

/// How often (in nodes) the search reads the clock.
pub(crate) const CLOCK_EVERY_NODES: u64 = 1024;

/// Node and time budget shared by every search of one solve.
pub(crate) struct Budget<'l> {
    /// Nodes counted so far (all phases).
    pub nodes: u64,
    /// Start of the solve.
    pub start: Instant,
    /// The caller's limits.
    pub limits: &'l Limits,
}

impl<'l> Budget<'l> {
    /// A budget starting now with no node counted, under `limits`.
    pub(crate) fn new(limits: &'l Limits) -> Self {
        Budget {
            nodes: 0,
            start: Instant::now(),
            limits,
        }
    }

    /// The caller's limits with at most `extra` nodes beyond those spent so far: the budget of a
    /// sub-search that may stop early and hand back.
    pub(crate) fn limits_for(&self, extra: u64) -> Limits {
        Limits {
            time_limit_s: self.limits.time_limit_s,
            node_limit: Some(
                self.limits
                    .node_limit
                    .unwrap_or(u64::MAX)
                    .min(self.nodes.saturating_add(extra)),
            ),
        }
    }

    /// Runs `search` on a share of this budget: at most `share` nodes beyond those spent so far
    /// ([`Budget::limits_for`]), under the same clock; the nodes it spends count here too.
    pub(crate) fn within<T>(&mut self, share: u64, search: impl FnOnce(&mut Budget<'_>) -> T) -> T {
        let limits = self.limits_for(share);
        let mut sub = Budget {
            nodes: self.nodes,
            start: self.start,
            limits: &limits,
        };
        let found = search(&mut sub);
        self.nodes = sub.nodes;
        found
    }

    /// Whether the caller's node or time limit is reached (the clock read every time).
    pub(crate) fn spent(&self) -> bool {
        self.limits.node_limit.is_some_and(|max| self.nodes >= max)
            || self
                .limits
                .time_limit_s
                .is_some_and(|t| self.start.elapsed().as_secs_f64() >= t)
    }

    /// Counts one placement; true when a limit is reached.
    pub(crate) fn tick(&mut self) -> bool {
        self.nodes += 1;
        if let Some(max_nodes) = self.limits.node_limit {
            if self.nodes >= max_nodes {
                return true;
            }
        }
        if let Some(t) = self.limits.time_limit_s {
            if self.nodes.is_multiple_of(CLOCK_EVERY_NODES)
                && self.start.elapsed().as_secs_f64() >= t
            {
                return true;
            }
        }
        false
    }
}
