//! Fairness-based sharing (FB, the paper's Algorithm 3).
//!
//! Each support drone serves its delivery drones (see [`super::responsible_support`]) round robin
//! in id order, `lambda` per round, i.e. `lambda / rho` minutes at `rho`, from `ct = 0`, while
//! `ct < tt` and it has sharing budget left (energy above `delta` at the hop end; the paper's
//! `SD.ae > delta`). The last round is clipped at `tt`; a round also ends early when the consumer
//! fills up or the budget runs out, and the next round starts at once. A drone that is full (at
//! capacity, consuming less than `rho` in its transfer slot) is skipped at no cost; with
//! [`PolicyOptions::fb_charge_skipped`] it still costs the support drone one round of time and
//! `lambda` of its budget, as the paper's pseudo-code does. When a whole pass serves nobody
//! (everyone full, or blocked by other transfers' re-ordering), the support drone waits until the
//! first blocking transfer ends, or one round when nothing blocks.

use super::reorder::{busy_drones, choose_consumer_slot};
use super::simulate::{evaluate, leg_at};
use super::{
    responsible_support, sharing_budget_mah, travel_time_min, HopProblem, PolicyOptions, Role,
    Transfer, ENERGY_TOL_MAH, MAX_PLANNING_STEPS, TIME_TOL_MIN,
};

/// FB's schedule.
pub(super) fn plan(problem: &HopProblem, options: &PolicyOptions) -> Vec<Transfer> {
    let n = problem.drones.len();
    let owner = responsible_support(problem);
    let tt = travel_time_min(problem);
    let rho = problem.rho_mah_per_min;
    let round_min = problem.lambda_mah / rho;
    let supports: Vec<usize> = (0..n)
        .filter(|&s| problem.drones[s].role == Role::Support)
        .collect();
    let subset: Vec<Vec<usize>> = (0..n)
        .map(|s| (0..n).filter(|&d| owner[d] == Some(s)).collect())
        .collect();
    let budget: Vec<f64> = (0..n)
        .map(|s| match problem.drones[s].role {
            Role::Support => sharing_budget_mah(problem, s),
            Role::Delivery => 0.0,
        })
        .collect();
    let mut ct = vec![0.0_f64; n];
    let mut pos = vec![0usize; n];
    let mut forfeited = vec![0.0_f64; n];
    let mut done: Vec<bool> = (0..n).map(|s| subset[s].is_empty()).collect();
    let mut run = evaluate(problem, &[]);
    let mut plan = run.transfers.clone();

    for _ in 0..MAX_PLANNING_STEPS {
        let Some(&s) = supports
            .iter()
            .filter(|&&s| !done[s])
            .min_by(|&&a, &&b| ct[a].total_cmp(&ct[b]).then(a.cmp(&b)))
        else {
            break;
        };
        let available = budget[s] - run.shared_by_support[s] - forfeited[s];
        let Some(leg) = leg_at(problem, ct[s]) else {
            done[s] = true;
            continue;
        };
        if ct[s] >= tt - TIME_TOL_MIN || available <= ENERGY_TOL_MAH {
            done[s] = true;
            continue;
        }
        let start = ct[s];
        let end = (start + round_min).min(tt);
        let busy = busy_drones(problem, &plan, start, end);
        let m = subset[s].len();
        let mut acted = false;
        let mut blocked = false;
        for k in 0..m {
            let i = (pos[s] + k) % m;
            let d = subset[s][i];
            let Some(slot) = choose_consumer_slot(problem, s, d, &busy) else {
                blocked = true;
                continue;
            };
            let full = run.battery_at(d, start) >= problem.drones[d].capacity_mah - ENERGY_TOL_MAH
                && problem.legs[leg].rate_mah_per_min[d][slot] < rho;
            if full {
                if options.fb_charge_skipped {
                    ct[s] = start + round_min;
                    forfeited[s] += problem.lambda_mah;
                    pos[s] = (i + 1) % m;
                    acted = true;
                    break;
                }
                continue;
            }
            let x = Transfer {
                support: s,
                consumer: d,
                start_min: start,
                end_min: end,
                energy_mah: rho * (end - start),
                consumer_slot: slot,
            };
            let mut trial = plan.clone();
            trial.push(x);
            let r = evaluate(problem, &trial);
            if r.harms(&run) {
                // The round (or its swap) would take some drone below zero: not made; the next
                // drone in turn is tried, as for a drone blocked by re-ordering.
                blocked = true;
                continue;
            }
            let realised = r.transfers.iter().find(|y| {
                y.support == s && y.consumer == d && (y.start_min - start).abs() <= TIME_TOL_MIN
            });
            match realised {
                Some(y) => {
                    ct[s] = y.end_min;
                    run = r;
                    plan = run.transfers.clone();
                }
                None => ct[s] = end,
            }
            pos[s] = (i + 1) % m;
            acted = true;
            break;
        }
        if !acted {
            let first_free = plan
                .iter()
                .filter(|x| x.start_min < end && start < x.end_min)
                .map(|x| x.end_min)
                .fold(f64::INFINITY, f64::min);
            ct[s] = if blocked && first_free.is_finite() {
                first_free
            } else {
                start + round_min
            };
        }
    }
    plan
}
