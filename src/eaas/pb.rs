//! Priority-based sharing (PB, the paper's Algorithm 2).
//!
//! Requests: delivery drone `d` requests energy when its battery, under the schedule built so far,
//! falls below `gamma`: `st` = the first time at or after the end of `d`'s last transfer at which
//! `b_d(t) < gamma` (the crossing time, or that end itself when already below), and `re` is what
//! the drone needs to end the hop at `gamma`, `min(gamma - b_d(tt), capacity_d - b_d(st))`
//! ([`PbRequest::ToHopEnd`], default) or a full battery, `capacity_d - b_d(st)`
//! ([`PbRequest::Fill`]). Requests are sorted by `st` ascending, then `re` descending, then drone id. The first
//! request its support drone (see [`super::responsible_support`]) can serve is served in full: at
//! `rho` from `max(st, free)` (`free` = the support drone's last transfer end) for `re / rho`
//! minutes, clipped at `tt`, provided the energy it will move (`re`, or less when clipped) fits the
//! support drone's remaining sharing budget (energy above `delta` at the hop end) and a
//! re-ordering slot is available. Then the schedule is
//! re-evaluated and the requests regenerated (re-ordering changes rates), until no request can be
//! served. With [`PolicyOptions::pb_wait_for_support`] off, a request with `st < free` is skipped
//! (the paper's literal `er.st >= SD.st`). A transfer whose trial schedule would take some drone
//! below zero (a swap partner moved into a costlier slot, say) is not made.

use super::reorder::{busy_drones, choose_consumer_slot};
use super::simulate::{evaluate, Run};
use super::{
    responsible_support, sharing_budget_mah, travel_time_min, HopProblem, PbRequest, PolicyOptions,
    Role, Transfer, ENERGY_TOL_MAH, MAX_PLANNING_STEPS, TIME_TOL_MIN,
};

/// An energy request `er = (drone, st, re)`.
#[derive(Debug, Clone, Copy)]
struct Request {
    drone: usize,
    st_min: f64,
    re_mah: f64,
}

/// PB's schedule, with its realisation when the schedule is empty (the hop without sharing, which
/// PB evaluates first anyway).
pub(super) fn plan(problem: &HopProblem, options: &PolicyOptions) -> (Vec<Transfer>, Option<Run>) {
    let owner = responsible_support(problem);
    let tt = travel_time_min(problem);
    let rho = problem.rho_mah_per_min;
    let budget: Vec<f64> = (0..problem.drones.len())
        .map(|d| match problem.drones[d].role {
            Role::Support => sharing_budget_mah(problem, d),
            Role::Delivery => 0.0,
        })
        .collect();
    let mut run = evaluate(problem, &[]);
    let mut plan = run.transfers.clone();
    let mut rejected: Vec<(usize, f64)> = Vec::new();
    for _ in 0..MAX_PLANNING_STEPS {
        let mut reqs = requests(problem, &run, &owner, tt, options.pb_request);
        reqs.sort_by(|a, b| {
            a.st_min
                .total_cmp(&b.st_min)
                .then(b.re_mah.total_cmp(&a.re_mah))
                .then(a.drone.cmp(&b.drone))
        });
        let mut chosen: Option<(Request, Transfer)> = None;
        for er in reqs {
            if rejected
                .iter()
                .any(|&(d, st)| d == er.drone && (st - er.st_min).abs() <= TIME_TOL_MIN)
            {
                continue;
            }
            let Some(s) = owner[er.drone] else { continue };
            let free = plan
                .iter()
                .filter(|x| x.support == s)
                .map(|x| x.end_min)
                .fold(0.0, f64::max);
            let start = if er.st_min + TIME_TOL_MIN >= free {
                er.st_min
            } else if options.pb_wait_for_support {
                free
            } else {
                continue;
            };
            if start >= tt - TIME_TOL_MIN {
                continue;
            }
            let end = (start + er.re_mah / rho).min(tt);
            let deliverable = rho * (end - start);
            let available = budget[s] - run.shared_by_support[s];
            if deliverable > available + ENERGY_TOL_MAH {
                continue;
            }
            let busy = busy_drones(problem, &plan, start, end);
            let Some(slot) = choose_consumer_slot(problem, s, er.drone, &busy) else {
                continue;
            };
            chosen = Some((
                er,
                Transfer {
                    support: s,
                    consumer: er.drone,
                    start_min: start,
                    end_min: end,
                    energy_mah: rho * (end - start),
                    consumer_slot: slot,
                },
            ));
            break;
        }
        let Some((er, x)) = chosen else { break };
        let mut trial = plan.clone();
        trial.push(x);
        let r = evaluate(problem, &trial);
        let realised = r.transfers.iter().any(|y| {
            y.support == x.support
                && y.consumer == x.consumer
                && (y.start_min - x.start_min).abs() <= TIME_TOL_MIN
        });
        if realised && !r.harms(&run) {
            run = r;
            plan = run.transfers.clone();
        } else {
            rejected.push((er.drone, er.st_min));
        }
    }
    let empty = plan.is_empty().then_some(run);
    (plan, empty)
}

/// Current requests of every delivery drone that has a responsible support drone.
fn requests(
    problem: &HopProblem,
    run: &Run,
    owner: &[Option<usize>],
    tt: f64,
    size: PbRequest,
) -> Vec<Request> {
    let gamma = problem.gamma_mah;
    let mut out = Vec::new();
    for (d, who) in owner.iter().enumerate() {
        if who.is_none() {
            continue;
        }
        let t0 = run
            .transfers
            .iter()
            .filter(|x| x.consumer == d)
            .map(|x| x.end_min)
            .fold(0.0, f64::max);
        if t0 >= tt - TIME_TOL_MIN {
            continue;
        }
        let b0 = run.battery_at(d, t0);
        let mut found: Option<(f64, f64)> = None;
        if b0 < gamma {
            found = Some((t0, b0));
        } else {
            for k in 1..run.times_min.len() {
                let (t1, b1) = (run.times_min[k], run.breakpoint(k)[d]);
                if t1 <= t0 {
                    continue;
                }
                let (ta, ba) = if run.times_min[k - 1] < t0 {
                    (t0, b0)
                } else {
                    (run.times_min[k - 1], run.breakpoint(k - 1)[d])
                };
                if ba >= gamma && b1 < gamma {
                    let st = ta + (ba - gamma) / (ba - b1) * (t1 - ta);
                    found = Some((st, gamma));
                    break;
                }
            }
        }
        let Some((st, b_st)) = found else { continue };
        if st >= tt - TIME_TOL_MIN {
            continue;
        }
        let fill = problem.drones[d].capacity_mah - b_st;
        let re = match size {
            PbRequest::Fill => fill,
            // The drone receives nothing after `st` under the schedule so far and rates are
            // >= 0, so its battery at `tt` is at most `b_st <= gamma`.
            PbRequest::ToHopEnd => (gamma - run.final_battery(d)).min(fill),
        };
        if re > ENERGY_TOL_MAH {
            out.push(Request {
                drone: d,
                st_min: st,
                re_mah: re,
            });
        }
    }
    out
}
