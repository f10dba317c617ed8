//! The numbers of a plan that only the method's run defines, its **search report**: the hop
//! solves' statuses, bounds and certified distances (`hops[].sharing_solve`), the node-time
//! solves' statuses, the counts of `hop_solves` and `route_optimality`, what a failed plan's
//! `outcome` says of the flight that failed, and the optimum of `route_gap`. Two checks (see `models/plan_file.md`):
//!
//! * **Consistency** (P5047), from the document alone: a stop hop's `objective` is its stop's
//!   `nt_min`, a `bound` is at most the objective and equals it when `optimal`, an
//!   `optimal_within` objective is within `epsilon` of its bound, both hop models are continuous
//!   in time (`grid_step_min` 0), the solve counts add up and cover the hops flown, the route's
//!   `epsilon_min` is the sum of its hops' `epsilon`, and the route gap is
//!   `(dt - optimal_dt) / optimal_dt`.
//! * **Re-run** (P5048): the request planned again with the document's method combination and
//!   settings (`settings`, recorded by this version) gives every number of the search report
//!   again. Only a plan made without a wall-clock limit can be re-run (every limit then counts
//!   work, so the re-run is the same on any machine); [`why_not_rerun`] says when a plan is not.
//!   This is the one check that uses the planner: nothing else can say what its search did.

use super::{close, RELATIVE_TOLERANCE};
use crate::compose::{Context, Hop, Plan, RequestReport, RouteGap, SwarmsCompared};
use crate::eaas::exact::ExactStatus;
use crate::eaas::exact_hop::{HopGoal, HopSolve, HopSolveCounts};
use crate::error::Violation;
use crate::problem::io::json_name;
use crate::problem::{Network, Profile, Request, SkywayGraph};
use serde_json::Value;

fn consistency(field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        "P5047",
        field,
        cause,
        "the search report contradicts the plan it comes with: plan the request again",
    )
}

/// P5047: the search report agrees with the plan it comes with (see the module's notes).
///
/// # Complexity
/// O(hops).
pub fn check_consistency(report: &RequestReport) -> Vec<Violation> {
    let plan = &report.plan;
    let mut out = Vec::new();
    let mut epsilon_sum = 0.0;
    for (k, hop) in plan.hops.iter().enumerate() {
        let Some(solve) = &hop.sharing_solve else {
            continue;
        };
        let f = format!("plan.hops[{k}].sharing_solve");
        check_hop_solve(&f, hop, solve, &mut out);
        if let Some(e) = hop_epsilon(&f, solve, &mut out) {
            epsilon_sum += e;
        }
    }
    if let Some(counts) = &plan.hop_solves {
        check_hop_solve_counts(plan, counts, &mut out);
    }
    if let Some(route) = &plan.route_optimality {
        if !close(route.epsilon_min, epsilon_sum) {
            out.push(consistency(
                "plan.route_optimality.epsilon_min",
                format!(
                    "states {}, the hops flown sum to {epsilon_sum}",
                    route.epsilon_min
                ),
            ));
        }
    }
    if let Some(gap) = &report.route_gap {
        check_route_gap(plan, gap, &mut out);
    }
    if let Some(c) = &report.swarms_compared {
        out.extend(swarms_compared_consistency(report, c));
    }
    out
}

/// A hop's solve, `f` its field: both hop models continuous in time, a node-time objective the
/// stop's `nt_min`, the bound at most the objective (equal when `optimal`, within `epsilon`
/// when `optimal_within`).
fn check_hop_solve(f: &str, hop: &Hop, solve: &HopSolve, out: &mut Vec<Violation>) {
    if solve.grid_step_min != 0.0 {
        out.push(consistency(
            format!("{f}.grid_step_min"),
            format!(
                "states {}, both hop models of a plan are continuous in time: 0",
                solve.grid_step_min
            ),
        ));
    }
    if let (HopGoal::NodeTimeMin, Some(objective), Some(stop)) =
        (solve.goal, solve.objective, &hop.stop)
    {
        if !close(objective, stop.nt_min) {
            out.push(consistency(
                format!("{f}.objective"),
                format!(
                    "states {objective}, the node time of the stop the hop flies into is {}",
                    stop.nt_min
                ),
            ));
        }
    }
    if let (Some(bound), Some(objective)) = (solve.bound, solve.objective) {
        let slack = RELATIVE_TOLERANCE * objective.abs().max(1.0);
        let epsilon = solve.epsilon.unwrap_or(0.0);
        let (lowest, highest) = match solve.status {
            Some(ExactStatus::Optimal) => (objective - slack, objective + slack),
            Some(ExactStatus::OptimalWithin) => (objective - epsilon - slack, objective + slack),
            _ => (f64::NEG_INFINITY, objective + slack),
        };
        if !(lowest..=highest).contains(&bound) {
            out.push(consistency(
                format!("{f}.bound"),
                format!(
                    "states {bound}, a lower bound of objective {objective} (status {}, \
                     epsilon {epsilon}) lies in [{lowest}, {highest}]",
                    json_name(&solve.status)
                ),
            ));
        }
    }
}

/// A hop's `epsilon`, `f` its solve's field: a distance >= 0 under `optimal_within`, absent
/// under any other status. The epsilon the route's sum counts, if any.
fn hop_epsilon(f: &str, solve: &HopSolve, out: &mut Vec<Violation>) -> Option<f64> {
    match (solve.status, solve.epsilon) {
        (Some(ExactStatus::OptimalWithin), Some(e)) if e >= 0.0 => return Some(e),
        (Some(ExactStatus::OptimalWithin), e) => out.push(consistency(
            format!("{f}.epsilon"),
            format!(
                "status optimal_within states epsilon {}, a distance >= 0",
                json_name(&e)
            ),
        )),
        (_, None) => {}
        (status, Some(e)) => out.push(consistency(
            format!("{f}.epsilon"),
            format!(
                "states epsilon {e} with status {}: only optimal_within has one",
                json_name(&status)
            ),
        )),
    }
    None
}

/// `hop_solves`: the counts by status add up to the solves, and each count lies between the
/// hops flown and the solves.
fn check_hop_solve_counts(plan: &Plan, counts: &HopSolveCounts, out: &mut Vec<Violation>) {
    let f = "plan.hop_solves";
    let by_status = counts.optimal
        + counts.optimal_within
        + counts.time_limit_incumbent
        + counts.infeasible
        + counts.time_limit_no_solution
        + counts.no_schedule_found
        + counts.backend_errors;
    if by_status != counts.solves {
        out.push(consistency(
            format!("{f}.solves"),
            format!(
                "states {} solves, its counts by status add up to {by_status}",
                counts.solves
            ),
        ));
    }
    let flown = plan.hops.iter().filter_map(|h| h.sharing_solve.as_ref());
    let (mut fallbacks, mut solved) = (0, 0);
    for solve in flown {
        solved += 1;
        fallbacks += usize::from(solve.fallback.is_some());
    }
    for (name, stated, least) in [
        ("solves", counts.solves, solved),
        ("fallbacks", counts.fallbacks, fallbacks),
        ("schedule_does_not_fly", counts.schedule_does_not_fly, 0),
    ] {
        if stated < least || stated > counts.solves {
            out.push(consistency(
                format!("{f}.{name}"),
                format!(
                    "states {stated}, between the {least} of the hops flown and the {} \
                     solves",
                    counts.solves
                ),
            ));
        }
    }
}

/// `route_gap.gap` is `(dt - optimal_dt) / optimal_dt` of the plan's delivery time.
fn check_route_gap(plan: &Plan, gap: &RouteGap, out: &mut Vec<Violation>) {
    let expected = match (plan.delivered(), gap.optimal_dt_min) {
        (true, Some(best)) if best > 0.0 => Some((plan.dt_min - best) / best),
        (true, Some(_)) => Some(0.0),
        _ => None,
    };
    let agrees = match (gap.gap, expected) {
        (Some(a), Some(b)) => close(a, b),
        (a, b) => a.is_none() && b.is_none(),
    };
    if !agrees {
        out.push(consistency(
            "route_gap.gap",
            format!(
                "states {}, (dt - optimal_dt_min) / optimal_dt_min is {}",
                json_name(&gap.gap),
                json_name(&expected)
            ),
        ));
    }
}

/// P5047: `swarms_compared` (`solve --swarm best`) names as best the least delivery time
/// among its swarms, and the plan is that swarm's: its positioning, support drones and `dt`.
fn swarms_compared_consistency(report: &RequestReport, c: &SwarmsCompared) -> Vec<Violation> {
    let mut out = Vec::new();
    let least = c
        .swarms
        .iter()
        .enumerate()
        .filter_map(|(i, s)| s.dt_min.map(|t| (i, t)))
        .fold(None, |acc: Option<(usize, f64)>, (i, t)| match acc {
            Some((_, u)) if u <= t => acc,
            _ => Some((i, t)),
        });
    let best_dt = |b: usize| c.swarms.get(b).and_then(|s| s.dt_min);
    let names_least = match (c.best, least) {
        (Some(b), Some((_, t))) => best_dt(b).is_some_and(|u| close(u, t)),
        (None, None) => true,
        _ => false,
    };
    if !names_least {
        out.push(consistency(
            "swarms_compared.best",
            format!(
                "states {}, the least delivery time among the swarms is swarm {}",
                json_name(&c.best),
                json_name(&least.map(|l| l.0))
            ),
        ));
        return out;
    }
    if let Some(s) = c.best.and_then(|b| c.swarms.get(b)) {
        let o = report.options;
        let same_swarm = report.support_drones == s.support_drones
            && (s.support_drones == 0 || o.positioning == s.positioning);
        let same_dt =
            report.plan.delivered() && s.dt_min.is_some_and(|t| close(t, report.plan.dt_min));
        if !same_swarm || !same_dt {
            out.push(consistency(
                "swarms_compared",
                format!(
                    "the best swarm ({}, {} support drone(s), dt {}) is not the plan's ({}, {} \
                     support drone(s), dt {})",
                    json_name(&s.positioning),
                    s.support_drones,
                    json_name(&s.dt_min),
                    json_name(&o.positioning),
                    report.support_drones,
                    report.plan.dt_min
                ),
            ));
        }
    }
    out
}

/// Why the search report of `report` cannot be re-run, if it cannot: a plan of an earlier
/// version (no `settings`), or one made with a wall-clock limit.
pub fn why_not_rerun(report: &RequestReport) -> Option<&'static str> {
    match &report.settings {
        None => Some("the plan records no settings (an earlier version's plan)"),
        Some(s) if !s.deterministic() => Some(
            "the plan was made with a wall-clock limit on its hop solves (--hop-time-limit), so \
             its search depends on the machine",
        ),
        Some(_) => None,
    }
}

/// P5048: the request planned again with the document's combination and settings gives every
/// number of its search report again. Nothing when [`why_not_rerun`] says why not, or when the
/// re-run itself cannot be made here (a backend this build lacks).
///
/// # Complexity
/// That of planning the request again (and its optimal route for a `route_gap`).
pub fn check_rerun(
    network: &Network,
    profile: &Profile,
    request: &Request,
    report: &RequestReport,
) -> Vec<Violation> {
    let (None, Some(settings)) = (why_not_rerun(report), &report.settings) else {
        return Vec::new();
    };
    let Ok(graph) = SkywayGraph::new(network) else {
        return Vec::new();
    };
    let context = Context::new(network, &graph, profile).with_settings(settings);
    let Ok(mut again) = context.plan(request, &report.options) else {
        return Vec::new();
    };
    if report.route_gap.is_some() {
        let Ok(gap) = context.route_gap(request, &again) else {
            return Vec::new();
        };
        again.route_gap = Some(gap);
    }
    if let Some(c) = &report.swarms_compared {
        let Ok(joint) = context.joint_optimum(request, c.support) else {
            return Vec::new();
        };
        again.swarms_compared = Some(SwarmsCompared::new(&joint, c.support));
    }
    let stated = serde_json::to_value(report).expect("plain data");
    let rerun = serde_json::to_value(&again).expect("plain data");
    let mut out = Vec::new();
    let at = |v: &Value, path: &[&str]| path.iter().fold(v.clone(), |v, k| v[*k].clone());
    for path in [
        &["plan", "hop_solves"][..],
        &["plan", "route_optimality"],
        &["plan", "outcome"],
        &["route_gap"],
        &["swarms_compared"],
    ] {
        compare(
            &path.join("."),
            &at(&stated, path),
            &at(&rerun, path),
            &mut out,
        );
    }
    for k in 0..report.plan.hops.len() {
        let hop = |v: &Value| v["plan"]["hops"][k].clone();
        for part in ["sharing_solve", "stop"] {
            let (a, b) = (hop(&stated)[part].clone(), hop(&rerun)[part].clone());
            let f = format!("plan.hops[{k}].{part}");
            if part == "stop" {
                compare(&format!("{f}.status"), &a["status"], &b["status"], &mut out);
            } else {
                compare(&f, &a, &b, &mut out);
            }
        }
    }
    out
}

/// Compares `stated` with `rerun` leaf by leaf under `field`, one P5048 per leaf that differs.
fn compare(field: &str, stated: &Value, rerun: &Value, out: &mut Vec<Violation>) {
    match (stated, rerun) {
        (Value::Object(a), Value::Object(b)) => {
            let keys: std::collections::BTreeSet<&String> = a.keys().chain(b.keys()).collect();
            for key in keys {
                let (x, y) = (&a.get(key), &b.get(key));
                compare(
                    &format!("{field}.{key}"),
                    x.unwrap_or(&Value::Null),
                    y.unwrap_or(&Value::Null),
                    out,
                );
            }
        }
        (Value::Array(a), Value::Array(b)) if a.len() == b.len() => {
            for (i, (x, y)) in a.iter().zip(b).enumerate() {
                compare(&format!("{field}[{i}]"), x, y, out);
            }
        }
        (Value::Number(a), Value::Number(b)) => {
            let (x, y) = (
                a.as_f64().unwrap_or(f64::NAN),
                b.as_f64().unwrap_or(f64::NAN),
            );
            if !close(x, y) {
                out.push(rerun_differs(field, stated, rerun));
            }
        }
        (a, b) if a != b => out.push(rerun_differs(field, stated, rerun)),
        _ => {}
    }
}

fn rerun_differs(field: &str, stated: &Value, rerun: &Value) -> Violation {
    Violation::new(
        "P5048",
        field,
        format!(
            "states {stated}, the method run again with the plan's combination and settings \
             gives {rerun}"
        ),
        "the search report is not the method's: plan the request again with the settings the \
         plan records",
    )
}
