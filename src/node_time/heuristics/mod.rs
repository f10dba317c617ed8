//! Heuristics for the node time: upper bounds and starting incumbents of the exact search.
//! LPT (`lpt.rs`, also a public method), largest differencing (`ldm.rs`), the move/swap local
//! search (`local_search.rs`) and the perfect-partition search aimed at the lower bound
//! (`perfect.rs`).

mod ldm;
mod local_search;
mod lpt;
mod perfect;

pub(crate) use ldm::ldm_sorted;
pub(crate) use local_search::local_search;
pub use lpt::lpt;
pub(crate) use lpt::lpt_sorted;
pub(crate) use perfect::aim_at;
#[cfg(test)]
pub(crate) use perfect::cases;
