//! The cells of the summary table, as `swarmplan bench` prints it and `report.html` shows it:
//! one source, so the two never show different numbers.

use super::{GapSplitSummary, JointSummary, MethodSummary, Shard, Summary};
use crate::compose::PlanOptions;
use crate::human::round;

/// The columns of the summary table, one row per combination ([`method_row`]).
pub const METHOD_COLUMNS: [&str; 9] = [
    "combination",
    "delivered",
    "dt min",
    "nt min",
    "stops",
    "gap = 0",
    "gap mean",
    "gap max",
    "ms/request",
];

/// The columns of the gap split table (unless `--no-joint`), one row per combination
/// ([`split_row`]).
pub const SPLIT_COLUMNS: [&str; 7] = [
    "gap to the joint optimum, min (%)",
    "split",
    "only J",
    "total",
    "sharing",
    "route",
    "swarm",
];

/// A combination's name in the tables: `sharing/positioning/route`.
pub fn combination(o: &PlanOptions) -> String {
    format!("{}/{}/{}", o.sharing, o.positioning, o.route)
}

/// A fraction as a percentage with one decimal, without a `+` (the table's means and maxima);
/// `0%` within [`crate::solver::ZERO_GAP_TOL`] of zero or when it rounds to zero, never `-0.0%`.
pub fn percent(x: f64) -> String {
    let text = format!("{:.1}%", 100.0 * x);
    if x.abs() <= crate::solver::ZERO_GAP_TOL || text == "-0.0%" || text == "0.0%" {
        "0%".to_string()
    } else {
        text
    }
}

/// A combination's row of the summary table, in the order of [`METHOD_COLUMNS`].
pub fn method_row(m: &MethodSummary) -> [String; 9] {
    let (zero, mean, max) = match &m.route_gap {
        Some(g) if g.compared > 0 => (
            format!("{}/{}", g.at_zero, g.compared),
            percent(g.mean_gap),
            percent(g.max_gap),
        ),
        _ => ("-".into(), "-".into(), "-".into()),
    };
    [
        combination(&m.options),
        format!("{}/{}", m.delivered, m.requests),
        round(m.mean_dt_min, 1),
        round(m.mean_nt_min, 1),
        round(m.mean_stops, 2),
        zero,
        mean,
        max,
        round(m.exec_ms_median, 2),
    ]
}

/// A combination's row of the gap split table, in the order of [`SPLIT_COLUMNS`] (`None`
/// with `--no-joint`).
pub fn split_row(m: &MethodSummary) -> Option<[String; 7]> {
    let g: &GapSplitSummary = m.gap_split.as_ref()?;
    let cell = |min: f64, pct: f64| format!("{} ({})", round(min, 1), percent(pct));
    Some([
        combination(&m.options),
        g.split.to_string(),
        g.joint_only.to_string(),
        cell(g.mean_total_min, g.mean_total_pct),
        cell(g.mean_sharing_min, g.mean_sharing_pct),
        cell(g.mean_route_min, g.mean_route_pct),
        cell(g.mean_swarm_min, g.mean_swarm_pct),
    ])
}

/// The line above the table: what was planned, on what.
pub fn heading(s: &Summary) -> String {
    format!(
        "{} requests of {} on {} ({}), profile {}",
        s.requests_planned,
        s.config.requests,
        s.config.network,
        if s.config.shard == Shard::WHOLE {
            "whole run".to_string()
        } else {
            format!("shard {}", s.config.shard)
        },
        s.config.profile
    )
}

/// What the route gap columns measure (when the run measured them).
pub const ROUTE_GAP_NOTE: &str = "route gap: (dt - dt_opt) / dt_opt over the requests both \
     deliver, against the optimal route of the same sharing and positioning (hops along the \
     shortest path between stops; Dijkstra and Floyd-Warshall can be below it)";

/// The lines under the table: each sharing heuristic's hops and the stops of the exact subset.
pub fn exact_subset_lines(s: &Summary) -> Vec<String> {
    let mut lines: Vec<String> = s
        .hop_gaps
        .iter()
        .map(|h| {
            format!(
                "hops under {} (first {} requests): {} solved again; against the optimum over \
                 continuous-time schedules: {} (attained {}, approached {}), optimal {}, mean \
                 loss {}, max loss {}, below the optimum {}; against the fluid bound {}{}",
                h.sharing,
                s.config.exact_limit,
                h.hops,
                h.against_optimal + h.against_infimum,
                h.against_optimal,
                h.against_infimum,
                h.at_zero,
                percent(h.mean_loss),
                percent(h.max_loss),
                h.below_optimum,
                h.against_bound,
                if h.different_policy > 0 {
                    format!(
                        "; outside the re-ordering mode (no gap) {}",
                        h.different_policy
                    )
                } else {
                    String::new()
                }
            )
        })
        .collect();
    let st = &s.stop_gaps;
    if st.stops > 0 {
        lines.push(format!(
            "stops (first {} requests): {}, proven {}; LPT optimal at {}, mean gap {}, max gap {}",
            s.config.exact_limit,
            st.stops,
            st.proven,
            st.lpt_optimal,
            percent(st.mean_gap),
            percent(st.max_gap)
        ));
    }
    lines
}

/// The joint optimum over the requests (unless `--no-joint`), above the split table.
pub fn joint_line(j: &JointSummary) -> String {
    format!(
        "joint optimum (route, continuous-time sharing and pads, over the swarms of both \
         positionings and the swarm without support drones): delivers {}/{}, mean dt {} min; \
         proven {} ({} within a certified distance, largest {:.2e} min); arcs flown {} of {}; \
         ms/request median {}, p90 {}, max {}",
        j.delivered,
        j.requests,
        round(j.mean_dt_min, 1),
        j.proven,
        j.within,
        j.max_epsilon_min,
        j.arcs_flown,
        j.arcs_total,
        round(j.ms_median, 1),
        round(j.ms_p90, 1),
        round(j.ms_max, 1)
    )
}

/// What the split table holds, under it.
pub fn split_note(s: &Summary) -> String {
    format!(
        "split: dt - dt_joint = sharing (the plan's route flown with exact schedules and pads) + \
         route (that against its swarm's optimum) + swarm (that against the best swarm), means \
         over the requests split, % of dt_joint; `only J`: requests the joint optimum delivers \
         and the combination does not. Dijkstra and Floyd-Warshall routes off the hop-path rule \
         are not split (outside the reference): {}",
        s.methods
            .iter()
            .filter_map(|m| m.gap_split.as_ref().map(|g| g.outside_reference))
            .sum::<usize>()
    )
}
