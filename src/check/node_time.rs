//! Re-verifies a node-time result (`swarmplan node-time --json`, a [`NodeTimeReport`]) from the
//! instance it records, without the node-time solvers: the assignment is a partition of the
//! drones over at most `k` pads (P5501), the makespan is its largest pad load (P5502), the lower
//! bound lies in `[0, makespan]` and equals the makespan when `optimal` (P5503); with at most [`OPTIMALITY_CHECK_DRONES`] drones the optimum found by
//! exhaustive search bounds both (P5504); the gap is the makespan's against the optimum or the
//! bound as the status says (P5505); and, when an instance is given, the recorded one is it
//! (P5506). `solve_ms` is a measurement and `method` a choice: neither is checked.

use super::plan::{optimal_makespan_min, OPTIMALITY_CHECK_DRONES};
use super::{close, RELATIVE_TOLERANCE};
use crate::error::show;
use crate::error::Violation;
use crate::node_time::NodeTimeReport;
use crate::problem::io::json_name;
use crate::solver::{Gap, ReferenceKind, SolveStatus};

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "solve the instance again with `swarmplan node-time --json`",
    )
}

/// Checks a node-time result.
///
/// # Arguments
/// * `report` - the result as read.
/// * `instance` - the instance it should answer (`pads`, charge times), when given.
///
/// # Returns
/// Every broken rule (codes `P5501`-`P5506`); empty when the result passes.
///
/// # Complexity
/// `O(n)` for `n` drones, plus the exhaustive search (at most `k^n / k!` assignments) when
/// `n <= OPTIMALITY_CHECK_DRONES`.
pub fn check_node_time(
    report: &NodeTimeReport,
    instance: Option<(usize, &[f64])>,
) -> Vec<Violation> {
    let mut out = Vec::new();
    if let Some((pads, times)) = instance {
        check_instance(report, pads, times, &mut out);
    }
    if !check_partition(report, &mut out) {
        return out;
    }
    let makespan = check_makespan(report, &mut out);
    check_bound(report, makespan, &mut out);
    check_optimum(report, makespan, &mut out);
    check_gap(report, &mut out);
    out
}

/// P5506: the result's instance is the one given, `pads` pads and charge times `times`.
fn check_instance(report: &NodeTimeReport, pads: usize, times: &[f64], out: &mut Vec<Violation>) {
    if pads != report.pads {
        out.push(violation(
            "P5506",
            "pads",
            format!("states {} pads, the instance has {pads}", report.pads),
        ));
    }
    if times.len() != report.charge_times_min.len() {
        out.push(violation(
            "P5506",
            "charge_times_min",
            format!(
                "states {} charge times, the instance has {}",
                report.charge_times_min.len(),
                times.len()
            ),
        ));
    } else {
        for (j, (&stated, &given)) in report.charge_times_min.iter().zip(times).enumerate() {
            if stated != given {
                out.push(violation(
                    "P5506",
                    format!("charge_times_min[{j}]"),
                    format!("states {stated} min, the instance has {given} min"),
                ));
            }
        }
    }
}

/// P5501: the assignment is a partition of the drones over at most `k` pads. Whether it is: the
/// other rules need one.
fn check_partition(report: &NodeTimeReport, out: &mut Vec<Violation>) -> bool {
    let s = &report.solution;
    let n = report.charge_times_min.len();
    let mut seen = vec![0usize; n];
    for (p, pad) in s.assignment.iter().enumerate() {
        for (i, &j) in pad.iter().enumerate() {
            match seen.get_mut(j) {
                Some(count) => *count += 1,
                None => out.push(violation(
                    "P5501",
                    format!("assignment[{p}][{i}]"),
                    format!("drone {j}, the instance has {n} drones"),
                )),
            }
        }
    }
    if s.assignment.len() > report.pads {
        out.push(violation(
            "P5501",
            "assignment",
            format!(
                "{} pads used, the node has {}",
                s.assignment.len(),
                report.pads
            ),
        ));
    }
    let unassigned: Vec<usize> = (0..n).filter(|&j| seen[j] != 1).collect();
    let partition = out.iter().all(|x| x.code != "P5501") && unassigned.is_empty();
    if !unassigned.is_empty() && s.status != SolveStatus::Infeasible {
        out.push(violation(
            "P5501",
            "assignment",
            format!("drones {unassigned:?} are not charged exactly once"),
        ));
    }
    partition
}

/// P5502: the makespan is the largest pad load; returns that load.
fn check_makespan(report: &NodeTimeReport, out: &mut Vec<Violation>) -> f64 {
    let s = &report.solution;
    let times = &report.charge_times_min;
    let makespan = s
        .assignment
        .iter()
        .map(|pad| pad.iter().map(|&j| times[j]).sum::<f64>())
        .fold(0.0, f64::max);
    if !close(s.makespan_min, makespan) {
        out.push(violation(
            "P5502",
            "makespan_min",
            format!(
                "states {}, the assignment's largest pad load is {makespan}",
                s.makespan_min
            ),
        ));
    }
    makespan
}

/// P5503: the lower bound lies in `[0, makespan]`, equal to it when `optimal`.
fn check_bound(report: &NodeTimeReport, makespan: f64, out: &mut Vec<Violation>) {
    let s = &report.solution;
    let slack = RELATIVE_TOLERANCE * makespan.max(1.0);
    let bound_ok = match s.status {
        SolveStatus::Optimal => close(s.lower_bound_min, makespan),
        _ => s.lower_bound_min >= 0.0 && s.lower_bound_min <= makespan + slack,
    };
    if !bound_ok {
        out.push(violation(
            "P5503",
            "lower_bound_min",
            format!(
                "states {} with status {}: a lower bound lies in [0, {}], equal to the \
                 makespan when optimal",
                show(s.lower_bound_min),
                json_name(&s.status),
                show(makespan)
            ),
        ));
    }
}

/// P5504: with few drones, the optimum found by exhaustive search bounds the lower bound from
/// above and, when `optimal`, the makespan from below.
fn check_optimum(report: &NodeTimeReport, makespan: f64, out: &mut Vec<Violation>) {
    let s = &report.solution;
    let times = &report.charge_times_min;
    if times.len() > OPTIMALITY_CHECK_DRONES || report.pads == 0 {
        return;
    }
    let best = optimal_makespan_min(times, report.pads);
    let slack = super::INTEGRATION_TOLERANCE * (1.0 + best);
    if s.lower_bound_min > best + slack {
        out.push(violation(
            "P5504",
            "lower_bound_min",
            format!(
                "states {}, above the optimum {best} found by exhaustive search",
                s.lower_bound_min
            ),
        ));
    }
    if s.status == SolveStatus::Optimal && makespan > best + slack {
        out.push(violation(
            "P5504",
            "makespan_min",
            format!("optimal {makespan}, but an assignment with makespan {best} exists"),
        ));
    }
}

/// P5505: the gap is the makespan's against the optimum or the bound, as the status says.
fn check_gap(report: &NodeTimeReport, out: &mut Vec<Violation>) {
    let s = &report.solution;
    let expected = s.gap();
    let gap_ok = match (&report.gap, &expected) {
        (Some(a), Some(b)) => {
            a.reference == b.reference
                && match (a.relative, b.relative) {
                    (Some(x), Some(y)) => close(x, y),
                    (x, y) => x.is_none() && y.is_none(),
                }
        }
        (a, b) => a.is_none() && b.is_none(),
    };
    if !gap_ok {
        let field = match (&report.gap, &expected) {
            (Some(a), Some(b)) if a.reference != b.reference => "gap.reference",
            (Some(_), Some(_)) => "gap.relative",
            _ => "gap",
        };
        out.push(violation(
            "P5505",
            field,
            format!(
                "states {}; status {} gives {}",
                gap_words(report.gap),
                json_name(&s.status),
                gap_words(expected)
            ),
        ));
    }
}

/// A gap in words, its relative value as the document writes it: `relative gap 0.5 against the
/// lower bound`, `no gap` (`null`).
fn gap_words(gap: Option<Gap>) -> String {
    let Some(g) = gap else {
        return "no gap (null)".to_string();
    };
    let against = match g.reference {
        ReferenceKind::Optimal => "the optimum",
        ReferenceKind::Incumbent => "an incumbent",
        ReferenceKind::Bound => "the lower bound",
        ReferenceKind::Infimum => "the infimum",
    };
    match g.relative {
        Some(r) => format!("relative gap {} against {against}", show(r)),
        None => format!("no relative gap (null: a reference of 0) against {against}"),
    }
}
