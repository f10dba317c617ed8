//! Re-verifies a hop schedule ([`crate::eaas::HopOutcome`]) from the raw
//! [`HopProblem`], re-integrating every battery itself. It calls nothing in `crate::eaas` but
//! the types.
//!
//! Rules (see `models/eaas.md`): transfers name a support drone giving to a delivery drone within
//! `[0, tt]`, move `rho * duration`, put the consumer within `range_m` of the (never moving) support
//! drone, swap only with a delivery drone; a support drone gives to one consumer at a time, a
//! consumer takes from one support drone at a time, and overlapping transfers involve distinct
//! drones; no battery above capacity; a support drone shares at most its battery at `tt` without
//! sharing minus `delta`, and is at or above `delta` whenever it shares; the outcome's feasibility,
//! first failure, final and lowest batteries and shared total match the re-integration.

use crate::eaas::{HopOutcome, HopProblem, Transfer};
use crate::error::Violation;
use crate::problem::Role;

const T_TOL: f64 = 1e-7;

fn e_tol(x: f64) -> f64 {
    1e-6 * (1.0 + x.abs())
}

fn v(code: &'static str, field: String, cause: String) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "the schedule breaks the hop model; report it with the instance",
    )
}

/// Checks `outcome` against `problem`.
///
/// # Arguments
/// * `problem` - the raw hop problem (assumed valid, see [`crate::eaas::validate`]).
/// * `outcome` - a schedule and its reported batteries.
///
/// # Returns
/// Every broken rule (codes `C3001`-`C3018`); empty when the schedule passes.
///
/// # Complexity
/// `O(T^2 + P * (D + T))` for `T` transfers, `P` pieces and `D` drones.
pub fn check_hop(problem: &HopProblem, outcome: &HopOutcome) -> Vec<Violation> {
    let mut out = Vec::new();
    let n = problem.drones.len();
    let rho = problem.rho_mah_per_min;
    let tt: f64 = problem.legs.iter().map(|l| l.duration_min).sum();
    let ts = &outcome.transfers;
    let holder = |q: usize| problem.initial_slot.iter().position(|&x| x == q);

    // Per-transfer rules.
    for (i, x) in ts.iter().enumerate() {
        let f = format!("transfers[{i}]");
        if x.support >= n || x.consumer >= n || x.consumer_slot >= n {
            out.push(v(
                "C3001",
                f,
                format!("drone or slot index out of range 0..{n}"),
            ));
            return out;
        }
        if problem.drones[x.support].role != Role::Support {
            out.push(v(
                "C3002",
                f.clone(),
                format!("giver {} is not a support drone", x.support),
            ));
        }
        if problem.drones[x.consumer].role != Role::Delivery {
            out.push(v(
                "C3003",
                f.clone(),
                format!("consumer {} is not a delivery drone", x.consumer),
            ));
        }
        if !(x.start_min >= -T_TOL && x.end_min > x.start_min && x.end_min <= tt + T_TOL) {
            out.push(v(
                "C3004",
                f.clone(),
                format!(
                    "interval [{}, {}] not a positive span within [0, {tt}]",
                    x.start_min, x.end_min
                ),
            ));
        }
        let expect = rho * (x.end_min - x.start_min);
        if (x.energy_mah - expect).abs() > e_tol(expect) {
            out.push(v(
                "C3005",
                f.clone(),
                format!(
                    "energy {} mAh but rho x duration = {expect} mAh",
                    x.energy_mah
                ),
            ));
        }
        let ps = problem.slots_m[problem.initial_slot[x.support]];
        let pc = problem.slots_m[x.consumer_slot];
        let dist = ((ps.x - pc.x).powi(2) + (ps.y - pc.y).powi(2)).sqrt();
        if dist > problem.range_m + 1e-9 {
            out.push(v(
                "C3006",
                f.clone(),
                format!(
                    "consumer slot {} is {dist} m from the support drone, range {}",
                    x.consumer_slot, problem.range_m
                ),
            ));
        }
        if x.consumer_slot != problem.initial_slot[x.consumer] {
            match holder(x.consumer_slot) {
                Some(p) if problem.drones[p].role == Role::Delivery && p != x.consumer => {}
                _ => out.push(v(
                    "C3007",
                    f.clone(),
                    format!(
                        "slot {} is not held by another delivery drone to swap with",
                        x.consumer_slot
                    ),
                )),
            }
        }
    }
    let partner = |x: &Transfer| -> Option<usize> {
        if x.consumer_slot == problem.initial_slot[x.consumer] {
            None
        } else {
            holder(x.consumer_slot)
        }
    };

    // Pairwise rules for overlapping transfers.
    for i in 0..ts.len() {
        for j in i + 1..ts.len() {
            let (a, b) = (&ts[i], &ts[j]);
            let overlap = a.start_min < b.end_min - T_TOL && b.start_min < a.end_min - T_TOL;
            if !overlap {
                continue;
            }
            let f = format!("transfers[{i}], transfers[{j}]");
            if a.support == b.support {
                out.push(v(
                    "C3008",
                    f.clone(),
                    format!("support drone {} gives to two consumers at once", a.support),
                ));
            }
            if a.consumer == b.consumer {
                out.push(v(
                    "C3009",
                    f.clone(),
                    format!(
                        "consumer {} takes from two support drones at once",
                        a.consumer
                    ),
                ));
            }
            let da = [Some(a.consumer), partner(a)];
            let db = [Some(b.consumer), partner(b)];
            let clash = da
                .iter()
                .flatten()
                .any(|d| db.iter().flatten().any(|e| d == e));
            if clash && a.consumer != b.consumer {
                out.push(v(
                    "C3010",
                    f,
                    "overlapping transfers move the same drone".to_string(),
                ));
            }
        }
    }

    // Re-integrate the batteries.
    let mut cuts: Vec<f64> = vec![0.0, tt];
    let mut acc = 0.0;
    for l in &problem.legs {
        acc += l.duration_min;
        cuts.push(acc);
    }
    for x in ts {
        cuts.push(x.start_min.clamp(0.0, tt));
        cuts.push(x.end_min.clamp(0.0, tt));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup_by(|a, b| (*a - *b).abs() <= 1e-12);

    let mut bat: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
    let mut low = bat.clone();
    let mut given = vec![0.0; n];
    let mut first_below: Option<(usize, f64)> = None;
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let h = b - a;
        if h <= 0.0 {
            continue;
        }
        let mid = 0.5 * (a + b);
        let mut acc = 0.0;
        let mut leg = problem.legs.len().saturating_sub(1);
        for (l, lg) in problem.legs.iter().enumerate() {
            acc += lg.duration_min;
            if mid < acc {
                leg = l;
                break;
            }
        }
        let mut slot = problem.initial_slot.clone();
        let on: Vec<&Transfer> = ts
            .iter()
            .filter(|x| x.start_min < mid && mid < x.end_min)
            .collect();
        for x in &on {
            if let Some(p) = partner(x) {
                slot[p] = problem.initial_slot[x.consumer];
                slot[x.consumer] = x.consumer_slot;
            }
        }
        let mut draw: Vec<f64> = (0..n)
            .map(|d| problem.legs[leg].rate_mah_per_min[d][slot[d]])
            .collect();
        for x in &on {
            draw[x.support] += rho;
            draw[x.consumer] -= rho;
            given[x.support] += rho * h;
        }
        for d in 0..n {
            let nb = bat[d] - draw[d] * h;
            if nb < -e_tol(0.0) && draw[d] > 0.0 {
                let t = a + bat[d].max(0.0) / draw[d];
                if first_below.is_none_or(|(fd, ft)| t < ft - T_TOL || (t <= ft + T_TOL && d < fd))
                {
                    first_below = Some((d, t));
                }
            }
            bat[d] = nb;
            low[d] = low[d].min(nb);
            if nb > problem.drones[d].capacity_mah + e_tol(nb) {
                out.push(v(
                    "C3011",
                    format!("drones[{d}]"),
                    format!(
                        "battery {nb} mAh above capacity {} at t = {b} min",
                        problem.drones[d].capacity_mah
                    ),
                ));
            }
        }
        for x in &on {
            if bat[x.support] < problem.delta_mah - e_tol(problem.delta_mah) {
                out.push(v(
                    "C3012",
                    format!("drones[{}]", x.support),
                    format!(
                        "shares at {} mAh, below the reserve delta = {}",
                        bat[x.support], problem.delta_mah
                    ),
                ));
            }
        }
    }
    for (d, &given_d) in given.iter().enumerate() {
        if problem.drones[d].role != Role::Support {
            continue;
        }
        let q = problem.initial_slot[d];
        let own: f64 = problem
            .legs
            .iter()
            .map(|l| l.rate_mah_per_min[d][q] * l.duration_min)
            .sum();
        let spare = (problem.drones[d].battery_mah - own - problem.delta_mah).max(0.0);
        if given_d > spare + e_tol(spare) {
            out.push(v(
                "C3013",
                format!("drones[{d}]"),
                format!(
                    "shares {} mAh, more than its spare {spare} mAh above delta at tt",
                    given_d
                ),
            ));
        }
    }

    // The outcome's own figures.
    let below = first_below.is_some();
    if outcome.feasible == below {
        out.push(v(
            "C3014",
            "feasible".into(),
            match first_below {
                Some((d, t)) => {
                    format!("reported feasible, but drone {d} is below zero from t = {t} min")
                }
                None => "reported infeasible, but no battery goes below zero".into(),
            },
        ));
    }
    if let (Some((d, t)), Some(f)) = (first_below, outcome.failure) {
        if f.drone != d || (f.time_min - t).abs() > 1e-6 * (1.0 + t) {
            out.push(v(
                "C3015",
                "failure".into(),
                format!(
                    "reported drone {} at {} min, re-integration gives drone {d} at {t} min",
                    f.drone, f.time_min
                ),
            ));
        }
    }
    if outcome.failure.is_some() == outcome.feasible {
        out.push(v(
            "C3015",
            "failure".into(),
            "failure present iff infeasible".into(),
        ));
    }
    let same = |a: &[f64], b: &[f64]| {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= e_tol(*y))
    };
    if !same(&outcome.final_battery_mah, &bat) {
        out.push(v(
            "C3016",
            "final_battery_mah".into(),
            format!(
                "reported {:?}, re-integration gives {bat:?}",
                outcome.final_battery_mah
            ),
        ));
    }
    if !same(&outcome.min_battery_mah, &low) {
        out.push(v(
            "C3017",
            "min_battery_mah".into(),
            format!(
                "reported {:?}, re-integration gives {low:?}",
                outcome.min_battery_mah
            ),
        ));
    }
    let total: f64 = ts.iter().map(|x| x.energy_mah).sum();
    if (outcome.shared_mah - total).abs() > e_tol(total) {
        out.push(v(
            "C3018",
            "shared_mah".into(),
            format!(
                "reported {} mAh, transfers sum to {total} mAh",
                outcome.shared_mah
            ),
        ));
    }
    out
}
