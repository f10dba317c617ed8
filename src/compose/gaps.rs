//! Optimality gaps of heuristics against the exact results recorded in plans.

use super::Stop;
use crate::error::Result;
use crate::node_time;
use crate::solver::{Gap, ReferenceKind, SolveStatus};
use serde::Serialize;

/// How far the LPT rule is from the exact node time over a set of stops. Gaps are
/// `(lpt - exact) / exact` against proven optima; stops whose exact solve was stopped by a limit are
/// counted apart (their gap would be against an incumbent) and left out of the gap figures.
#[derive(Debug, Clone, Serialize)]
pub struct LptGapSummary {
    /// Stops compared against a proven optimum.
    pub stops: usize,
    /// Stops whose exact node time is only an incumbent (left out of the gaps).
    pub stops_with_incumbent_only: usize,
    /// Stops where LPT's makespan equals the optimum (within 1e-9 relative).
    pub lpt_optimal: usize,
    /// Mean relative gap of LPT over the compared stops.
    pub mean_gap: f64,
    /// Largest relative gap of LPT.
    pub max_gap: f64,
    /// What the gaps are measured against: always `optimal`.
    pub reference: ReferenceKind,
}

/// LPT against the exact node time at every stop given.
///
/// # Errors
/// Only for a stop whose charge times are not valid node-time input.
pub fn lpt_node_time_gaps<'a>(stops: impl IntoIterator<Item = &'a Stop>) -> Result<LptGapSummary> {
    let gaps = stops.into_iter().map(lpt_gap).collect::<Result<Vec<_>>>()?;
    Ok(LptGapSummary::of(gaps))
}

/// LPT's relative gap at one stop against its proven optimum, `None` when the stop's exact node
/// time is only an incumbent.
///
/// # Errors
/// Only for a stop whose charge times are not valid node-time input.
pub fn lpt_gap(stop: &Stop) -> Result<Option<f64>> {
    if stop.status != SolveStatus::Optimal {
        return Ok(None);
    }
    let lpt = node_time::lpt(stop.pads as usize, &stop.charge_times_min)?;
    Ok(Some(
        Gap::new(lpt.makespan_min, stop.nt_min, ReferenceKind::Optimal)
            .relative
            .unwrap_or(0.0),
    ))
}

impl LptGapSummary {
    /// The summary of per-stop gaps from [`lpt_gap`], summed in the order given.
    pub fn of(gaps: impl IntoIterator<Item = Option<f64>>) -> LptGapSummary {
        let mut summary = LptGapSummary {
            stops: 0,
            stops_with_incumbent_only: 0,
            lpt_optimal: 0,
            mean_gap: 0.0,
            max_gap: 0.0,
            reference: ReferenceKind::Optimal,
        };
        let mut sum = 0.0;
        for gap in gaps {
            let Some(gap) = gap else {
                summary.stops_with_incumbent_only += 1;
                continue;
            };
            summary.stops += 1;
            if gap <= 1e-9 {
                summary.lpt_optimal += 1;
            }
            sum += gap;
            summary.max_gap = summary.max_gap.max(gap);
        }
        summary.mean_gap = sum / summary.stops.max(1) as f64;
        summary
    }
}
