//! Optimality gaps of heuristics against the exact results recorded in plans.

use super::Stop;
use crate::error::Result;
use crate::node_time;
use crate::solver::{Gap, ReferenceKind, Sense, SolveStatus};
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
        Gap::new(
            lpt.makespan_min,
            stop.nt_min,
            ReferenceKind::Optimal,
            Sense::Minimise,
        )
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

/// How far a heuristic route method is from the optimal route (`--route optimal`, same sharing
/// policy, positioning and support drones) over a request set: gaps `(dt - dt_opt) / dt_opt` on
/// the requests both deliver, summed in request order. The optimum is over stop sequences with
/// hops along the shortest path between stops; Dijkstra's and Floyd–Warshall's hops follow their
/// fixed route instead, so their gap can be negative (shown, never clipped).
#[derive(Debug, Clone, Serialize)]
pub struct RouteGapSummary {
    /// What the gaps are measured against: `optimal` (over stop sequences).
    pub reference: ReferenceKind,
    /// The hop paths of the reference: `shortest-between-stops` (`--hop-paths rule`) or
    /// `any-flyable-path` (`--hop-paths any`).
    pub reference_hop_paths: &'static str,
    /// Requests both delivered (the gaps' denominator).
    pub compared: usize,
    /// Of those, requests at gap 0 (within 1e-9 relative).
    pub at_zero: usize,
    /// Mean gap over the compared requests.
    pub mean_gap: f64,
    /// Largest gap.
    pub max_gap: f64,
    /// Smallest gap (negative only for a method whose hops follow another path rule).
    pub min_gap: f64,
    /// Requests the heuristic fails and the optimum delivers.
    pub heuristic_fails_optimum_delivers: usize,
    /// Requests the optimum fails and the heuristic delivers (0 for Algorithm 1 and A*, whose
    /// hops follow the same rule).
    pub optimum_fails_heuristic_delivers: usize,
    /// Compared requests whose optimum is proven only for the node times found (a stop of its
    /// search stopped by the node limit).
    pub unproven_references: usize,
}

/// One request for [`RouteGapSummary::of`]: the heuristic's and the optimum's delivery times
/// (`None` when not delivered), and whether the optimum is proven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoutePair {
    /// The heuristic's delivery time, min.
    pub heuristic_dt_min: Option<f64>,
    /// The optimum's delivery time, min.
    pub optimal_dt_min: Option<f64>,
    /// Whether the optimum's node times were all proven.
    pub optimal_proven: bool,
}

impl RoutePair {
    /// The relative gap when both delivered (0 when both delivery times are 0).
    pub fn gap(&self) -> Option<f64> {
        let (h, o) = (self.heuristic_dt_min?, self.optimal_dt_min?);
        Some(if o > 0.0 { (h - o) / o } else { 0.0 })
    }
}

impl RouteGapSummary {
    /// The reference's name in `batch`'s CSV: `optimal` (hops along the shortest path between
    /// stops) or `optimal-any-path`.
    pub fn reference_name(&self) -> &'static str {
        match (self.reference, self.reference_hop_paths) {
            (ReferenceKind::Optimal, "any-flyable-path") => "optimal-any-path",
            (ReferenceKind::Optimal, _) => "optimal",
            (ReferenceKind::Incumbent, _) => "incumbent",
            (ReferenceKind::Bound, _) => "bound",
            (ReferenceKind::Infimum, _) => "infimum",
        }
    }

    /// The same summary, its reference planned with the hop paths `hop_paths`.
    pub fn with_hop_paths(mut self, hop_paths: super::HopPaths) -> RouteGapSummary {
        self.reference_hop_paths = match hop_paths {
            super::HopPaths::Rule => "shortest-between-stops",
            super::HopPaths::Any => "any-flyable-path",
        };
        self
    }

    /// The summary of the requests `pairs`, in the order given.
    pub fn of(pairs: impl IntoIterator<Item = RoutePair>) -> RouteGapSummary {
        let mut s = RouteGapSummary {
            reference: ReferenceKind::Optimal,
            reference_hop_paths: "shortest-between-stops",
            compared: 0,
            at_zero: 0,
            mean_gap: 0.0,
            max_gap: f64::NEG_INFINITY,
            min_gap: f64::INFINITY,
            heuristic_fails_optimum_delivers: 0,
            optimum_fails_heuristic_delivers: 0,
            unproven_references: 0,
        };
        let mut sum = 0.0;
        for pair in pairs {
            match (pair.heuristic_dt_min, pair.optimal_dt_min) {
                (None, Some(_)) => s.heuristic_fails_optimum_delivers += 1,
                (Some(_), None) => s.optimum_fails_heuristic_delivers += 1,
                _ => {}
            }
            let Some(gap) = pair.gap() else { continue };
            s.compared += 1;
            if !pair.optimal_proven {
                s.unproven_references += 1;
            }
            if gap.abs() <= 1e-9 {
                s.at_zero += 1;
            }
            sum += gap;
            s.max_gap = s.max_gap.max(gap);
            s.min_gap = s.min_gap.min(gap);
        }
        if s.compared == 0 {
            (s.max_gap, s.min_gap) = (0.0, 0.0);
        }
        s.mean_gap = sum / s.compared.max(1) as f64;
        s
    }
}
