//! Re-verifies a hop schedule ([`crate::eaas::HopOutcome`]) from the raw
//! [`HopProblem`], re-integrating every battery itself. It calls nothing in `crate::eaas` but
//! the types.
//!
//! One function per rule, named after its code. Rules (see `models/eaas.md`): transfers name a
//! support drone giving to a delivery drone within `[0, tt]`, move `rho * duration`, put the
//! consumer within `range_m` of the (never moving) support drone, swap only with a delivery
//! drone (C3001-C3007); a support drone gives to one consumer at a time, a consumer takes from
//! one support drone at a time, and overlapping transfers involve distinct drones
//! (C3008-C3010); no battery above capacity (C3011); a support drone is at or above `delta`
//! whenever it shares (C3012) and shares at most its battery at `tt` without sharing minus
//! `delta` (C3013); the outcome's feasibility, first failure, final and lowest batteries and
//! shared total match the re-integration (C3014-C3018).

use crate::eaas::{FailureReason, HopFailure, HopOutcome, HopProblem, Transfer};
use crate::error::Violation;
use crate::problem::Role;

pub(super) const T_TOL: f64 = 1e-7;

pub(super) fn e_tol(x: f64) -> f64 {
    super::INTEGRATION_TOLERANCE * (1.0 + x.abs())
}

pub(super) fn violation(code: &'static str, field: String, cause: String) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "the schedule breaks the hop model: it was changed after it was made, or made for \
         another hop; make it again (`swarmplan solve ... --json` for a plan's hops, `swarmplan \
         eaas` for one hop) on the instance it is checked with",
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
    let hop = HopView::new(problem);
    let ts = &outcome.transfers;
    let mut out = Vec::new();

    // Per-transfer rules.
    for (i, x) in ts.iter().enumerate() {
        let f = format!("transfers[{i}]");
        if let Some(bad) = c3001_transfer_names_existing_drones(&hop, &f, x) {
            out.push(bad);
            return out;
        }
        out.extend(c3002_giver_is_a_support_drone(&hop, &f, x));
        out.extend(c3003_consumer_is_a_delivery_drone(&hop, &f, x));
        out.extend(c3004_transfer_lies_within_the_hop(&hop, &f, x));
        out.extend(c3005_energy_is_rho_times_duration(&hop, &f, x));
        out.extend(c3006_consumer_within_range(&hop, &f, x));
        out.extend(c3007_swap_only_with_a_delivery_drone(&hop, &f, x));
    }

    // Pairwise rules for overlapping transfers.
    for i in 0..ts.len() {
        for j in i + 1..ts.len() {
            let (a, b) = (&ts[i], &ts[j]);
            let overlap = a.start_min < b.end_min - T_TOL && b.start_min < a.end_min - T_TOL;
            if !overlap {
                continue;
            }
            let f = format!("transfers[{i}], transfers[{j}]");
            out.extend(c3008_one_consumer_per_support_at_a_time(&f, a, b));
            out.extend(c3009_one_support_per_consumer_at_a_time(&f, a, b));
            out.extend(c3010_overlapping_transfers_move_distinct_drones(
                &hop, &f, a, b,
            ));
        }
    }

    let run = integrate(&hop, ts);
    out.extend(c3011_no_battery_above_capacity(&run));
    out.extend(c3012_support_shares_above_its_reserve(&run));
    out.extend(c3013_support_shares_only_its_spare(&hop, &run));
    out.extend(c3014_feasibility_matches(outcome, &run));
    out.extend(c3015_first_failure_matches(outcome, &run));
    out.extend(c3016_final_batteries_match(outcome, &run));
    out.extend(c3017_lowest_batteries_match(outcome, &run));
    out.extend(c3018_shared_total_matches(outcome));
    out
}

/// Flies a schedule exactly as written (by hand, or by another program): the batteries come
/// from this checker's own re-integration, and every rule the schedule breaks is listed.
///
/// # Returns
/// The outcome (`None` when a transfer names a drone or slot that does not exist, or has a
/// time that is not a finite number, so that nothing can be integrated) and every broken rule
/// (codes `C3001`-`C3013`; the outcome's own figures match by construction).
///
/// # Complexity
/// That of [`check_hop`].
pub fn fly_as_written(
    problem: &HopProblem,
    transfers: &[Transfer],
) -> (Option<HopOutcome>, Vec<Violation>) {
    let hop = HopView::new(problem);
    let mut out = Vec::new();
    for (i, x) in transfers.iter().enumerate() {
        let f = format!("transfers[{i}]");
        out.extend(c3001_transfer_names_existing_drones(&hop, &f, x));
        if !(x.start_min.is_finite() && x.end_min.is_finite() && x.energy_mah.is_finite()) {
            out.push(violation(
                "C3004",
                f,
                format!(
                    "start {}, end {} or energy {} is not a finite number",
                    x.start_min, x.end_min, x.energy_mah
                ),
            ));
        }
    }
    if !out.is_empty() {
        return (None, out);
    }
    let run = integrate(&hop, transfers);
    let outcome = HopOutcome {
        feasible: run.first_below.is_none(),
        failure: run.first_below.map(|(drone, time_min)| HopFailure {
            drone,
            time_min,
            reason: FailureReason::BatteryDepleted,
        }),
        transfers: transfers.to_vec(),
        final_battery_mah: run.battery,
        min_battery_mah: run.lowest,
        shared_mah: transfers.iter().fold(0.0, |a, t| a + t.energy_mah),
    };
    let violations = check_hop(problem, &outcome);
    (Some(outcome), violations)
}

/// Every drone's battery over the hop when `transfers` are flown as written: this checker's own
/// re-integration, sampled where it cuts the hop (leg ends, transfer starts and ends).
///
/// # Returns
/// `(t, every drone's battery)`, min and mAh, at `t = 0` and at the end of every piece, in order
/// of `t` up to `tt`; every battery is linear between two points. `None` when a transfer names a
/// drone or slot that does not exist or has a time that is not a finite number (see
/// [`fly_as_written`]).
///
/// # Complexity
/// `O(P * (D + T))` for `P` pieces, `D` drones and `T` transfers.
pub fn battery_trajectory(
    problem: &HopProblem,
    transfers: &[Transfer],
) -> Option<Vec<(f64, Vec<f64>)>> {
    let hop = HopView::new(problem);
    let malformed = transfers.iter().any(|x| {
        c3001_transfer_names_existing_drones(&hop, "", x).is_some()
            || !(x.start_min.is_finite() && x.end_min.is_finite())
    });
    (!malformed).then(|| integrate(&hop, transfers).points)
}

/// The hop problem with what every rule needs of it.
struct HopView<'a> {
    problem: &'a HopProblem,
    /// Drones.
    n: usize,
    /// Sharing rate `rho`, mAh/min.
    rho: f64,
    /// Travel time `tt`, min.
    tt: f64,
}

impl<'a> HopView<'a> {
    fn new(problem: &'a HopProblem) -> HopView<'a> {
        HopView {
            problem,
            n: problem.drones.len(),
            rho: problem.rho_mah_per_min,
            tt: problem.legs.iter().map(|l| l.duration_min).sum(),
        }
    }

    /// The drone holding slot `q` outside transfers.
    fn holder(&self, q: usize) -> Option<usize> {
        self.problem.initial_slot.iter().position(|&x| x == q)
    }

    /// The drone a transfer's consumer swaps slots with, if it moves.
    fn partner(&self, x: &Transfer) -> Option<usize> {
        if x.consumer_slot == self.problem.initial_slot[x.consumer] {
            None
        } else {
            self.holder(x.consumer_slot)
        }
    }
}

// ---- Each transfer.

/// C3001: the transfer names drones and a slot that exist. The other rules need them: the check
/// stops at the first transfer that breaks it.
fn c3001_transfer_names_existing_drones(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    let n = hop.n;
    (x.support >= n || x.consumer >= n || x.consumer_slot >= n).then(|| {
        violation(
            "C3001",
            f.to_string(),
            format!("drone or slot index out of range 0..{n}"),
        )
    })
}

/// C3002: the giver is a support drone.
fn c3002_giver_is_a_support_drone(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    (hop.problem.drones[x.support].role != Role::Support).then(|| {
        violation(
            "C3002",
            f.to_string(),
            format!("giver {} is not a support drone", x.support),
        )
    })
}

/// C3003: the consumer is a delivery drone.
fn c3003_consumer_is_a_delivery_drone(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    (hop.problem.drones[x.consumer].role != Role::Delivery).then(|| {
        violation(
            "C3003",
            f.to_string(),
            format!("consumer {} is not a delivery drone", x.consumer),
        )
    })
}

/// C3004: the transfer is a positive span within `[0, tt]`.
fn c3004_transfer_lies_within_the_hop(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    let tt = hop.tt;
    let ok = x.start_min >= -T_TOL && x.end_min > x.start_min && x.end_min <= tt + T_TOL;
    (!ok).then(|| {
        violation(
            "C3004",
            f.to_string(),
            format!(
                "interval [{}, {}] not a positive span within [0, {tt}]",
                x.start_min, x.end_min
            ),
        )
    })
}

/// C3005: the energy moved is `rho x duration`.
fn c3005_energy_is_rho_times_duration(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    let expect = hop.rho * (x.end_min - x.start_min);
    ((x.energy_mah - expect).abs() > e_tol(expect)).then(|| {
        violation(
            "C3005",
            f.to_string(),
            format!(
                "energy {} mAh but rho x duration = {expect} mAh",
                x.energy_mah
            ),
        )
    })
}

/// C3006: the consumer's slot is within `range_m` of the support drone's.
fn c3006_consumer_within_range(hop: &HopView, f: &str, x: &Transfer) -> Option<Violation> {
    let p = hop.problem;
    let ps = p.slots_m[p.initial_slot[x.support]];
    let pc = p.slots_m[x.consumer_slot];
    let dist = ((ps.x - pc.x).powi(2) + (ps.y - pc.y).powi(2)).sqrt();
    (dist > p.range_m + 1e-9).then(|| {
        violation(
            "C3006",
            f.to_string(),
            format!(
                "consumer slot {} is {dist} m from the support drone, range {}",
                x.consumer_slot, p.range_m
            ),
        )
    })
}

/// C3007: a consumer that moves swaps with another delivery drone.
fn c3007_swap_only_with_a_delivery_drone(
    hop: &HopView,
    f: &str,
    x: &Transfer,
) -> Option<Violation> {
    let p = hop.problem;
    if x.consumer_slot == p.initial_slot[x.consumer] {
        return None;
    }
    match hop.holder(x.consumer_slot) {
        Some(q) if p.drones[q].role == Role::Delivery && q != x.consumer => None,
        _ => Some(violation(
            "C3007",
            f.to_string(),
            format!(
                "slot {} is not held by another delivery drone to swap with",
                x.consumer_slot
            ),
        )),
    }
}

// ---- Overlapping transfers.

/// C3008: a support drone gives to one consumer at a time.
fn c3008_one_consumer_per_support_at_a_time(
    f: &str,
    a: &Transfer,
    b: &Transfer,
) -> Option<Violation> {
    (a.support == b.support).then(|| {
        violation(
            "C3008",
            f.to_string(),
            format!("support drone {} gives to two consumers at once", a.support),
        )
    })
}

/// C3009: a consumer takes from one support drone at a time.
fn c3009_one_support_per_consumer_at_a_time(
    f: &str,
    a: &Transfer,
    b: &Transfer,
) -> Option<Violation> {
    (a.consumer == b.consumer).then(|| {
        violation(
            "C3009",
            f.to_string(),
            format!(
                "consumer {} takes from two support drones at once",
                a.consumer
            ),
        )
    })
}

/// C3010: overlapping transfers of different consumers move distinct drones (a consumer and
/// the drone it swaps with).
fn c3010_overlapping_transfers_move_distinct_drones(
    hop: &HopView,
    f: &str,
    a: &Transfer,
    b: &Transfer,
) -> Option<Violation> {
    let da = [Some(a.consumer), hop.partner(a)];
    let db = [Some(b.consumer), hop.partner(b)];
    let clash = da
        .iter()
        .flatten()
        .any(|d| db.iter().flatten().any(|e| d == e));
    (clash && a.consumer != b.consumer).then(|| {
        violation(
            "C3010",
            f.to_string(),
            "overlapping transfers move the same drone".to_string(),
        )
    })
}

// ---- The re-integration.

/// Every battery re-integrated over the schedule, piece by piece.
struct Integration {
    /// Every drone's battery at `tt`, mAh.
    battery: Vec<f64>,
    /// Every drone's lowest battery, mAh.
    lowest: Vec<f64>,
    /// Energy each drone gave, mAh.
    given: Vec<f64>,
    /// The first drone below zero and when: earliest, then lowest id.
    first_below: Option<(usize, f64)>,
    /// `(drone, battery, capacity, t)` at the end of every piece where a battery is above its
    /// capacity.
    above_capacity: Vec<(usize, f64, f64, f64)>,
    /// `(support drone, battery, delta)` at the end of every piece where a sharing support
    /// drone is below its reserve.
    below_reserve: Vec<(usize, f64, f64)>,
    /// `(t, every drone's battery)` at 0 and at the end of every piece: the batteries are linear
    /// in between.
    points: Vec<(f64, Vec<f64>)>,
}

/// Integrates every battery over the pieces cut by leg ends and transfer starts and ends: on
/// each, a drone draws its rate in the slot it holds (swapped during a transfer), a giving
/// support drone `rho` more, a receiving consumer `rho` less.
fn integrate(hop: &HopView, ts: &[Transfer]) -> Integration {
    let (problem, n, tt, rho) = (hop.problem, hop.n, hop.tt, hop.rho);
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
    let mut run = Integration {
        lowest: bat.clone(),
        battery: Vec::new(),
        given: vec![0.0; n],
        first_below: None,
        above_capacity: Vec::new(),
        below_reserve: Vec::new(),
        points: vec![(0.0, bat.clone())],
    };
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
            if let Some(p) = hop.partner(x) {
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
            run.given[x.support] += rho * h;
        }
        for d in 0..n {
            let nb = bat[d] - draw[d] * h;
            if nb < -e_tol(0.0) && draw[d] > 0.0 {
                let t = a + bat[d].max(0.0) / draw[d];
                if run
                    .first_below
                    .is_none_or(|(fd, ft)| t < ft - T_TOL || (t <= ft + T_TOL && d < fd))
                {
                    run.first_below = Some((d, t));
                }
            }
            bat[d] = nb;
            run.lowest[d] = run.lowest[d].min(nb);
            let capacity = problem.drones[d].capacity_mah;
            if nb > capacity + e_tol(nb) {
                run.above_capacity.push((d, nb, capacity, b));
            }
        }
        for x in &on {
            if bat[x.support] < problem.delta_mah - e_tol(problem.delta_mah) {
                run.below_reserve
                    .push((x.support, bat[x.support], problem.delta_mah));
            }
        }
        run.points.push((b, bat.clone()));
    }
    run.battery = bat;
    run
}

/// C3011: no battery above its capacity.
fn c3011_no_battery_above_capacity(run: &Integration) -> Vec<Violation> {
    run.above_capacity
        .iter()
        .map(|&(d, battery, capacity, t)| {
            violation(
                "C3011",
                format!("drones[{d}]"),
                format!("battery {battery} mAh above capacity {capacity} at t = {t} min"),
            )
        })
        .collect()
}

/// C3012: a support drone shares only while at or above its reserve `delta`.
fn c3012_support_shares_above_its_reserve(run: &Integration) -> Vec<Violation> {
    run.below_reserve
        .iter()
        .map(|&(s, battery, delta)| {
            violation(
                "C3012",
                format!("drones[{s}]"),
                format!("shares at {battery} mAh, below the reserve delta = {delta}"),
            )
        })
        .collect()
}

/// C3013: a support drone shares at most its battery at `tt` without sharing minus `delta`.
fn c3013_support_shares_only_its_spare(hop: &HopView, run: &Integration) -> Vec<Violation> {
    let problem = hop.problem;
    let mut out = Vec::new();
    for (d, &given_d) in run.given.iter().enumerate() {
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
            out.push(violation(
                "C3013",
                format!("drones[{d}]"),
                format!(
                    "shares {} mAh, more than its spare {spare} mAh above delta at tt",
                    given_d
                ),
            ));
        }
    }
    out
}

// ---- The outcome's own figures.

/// C3014: the outcome is feasible iff no battery goes below zero.
fn c3014_feasibility_matches(outcome: &HopOutcome, run: &Integration) -> Option<Violation> {
    (outcome.feasible == run.first_below.is_some()).then(|| {
        violation(
            "C3014",
            "feasible".into(),
            match run.first_below {
                Some((d, t)) => {
                    format!("reported feasible, but drone {d} is below zero from t = {t} min")
                }
                None => "reported infeasible, but no battery goes below zero".into(),
            },
        )
    })
}

/// C3015: the reported first failure is the re-integration's, and is present iff the outcome
/// is infeasible.
fn c3015_first_failure_matches(outcome: &HopOutcome, run: &Integration) -> Vec<Violation> {
    let mut out = Vec::new();
    if let (Some((d, t)), Some(f)) = (run.first_below, outcome.failure) {
        if f.drone != d || (f.time_min - t).abs() > super::INTEGRATION_TOLERANCE * (1.0 + t) {
            out.push(violation(
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
        out.push(violation(
            "C3015",
            "failure".into(),
            "failure present iff infeasible".into(),
        ));
    }
    out
}

fn same_batteries(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= e_tol(*y))
}

/// C3016: the reported final batteries are the re-integration's.
fn c3016_final_batteries_match(outcome: &HopOutcome, run: &Integration) -> Option<Violation> {
    (!same_batteries(&outcome.final_battery_mah, &run.battery)).then(|| {
        violation(
            "C3016",
            "final_battery_mah".into(),
            format!(
                "reported {:?}, re-integration gives {:?}",
                outcome.final_battery_mah, run.battery
            ),
        )
    })
}

/// C3017: the reported lowest batteries are the re-integration's.
fn c3017_lowest_batteries_match(outcome: &HopOutcome, run: &Integration) -> Option<Violation> {
    (!same_batteries(&outcome.min_battery_mah, &run.lowest)).then(|| {
        violation(
            "C3017",
            "min_battery_mah".into(),
            format!(
                "reported {:?}, re-integration gives {:?}",
                outcome.min_battery_mah, run.lowest
            ),
        )
    })
}

/// C3018: the reported shared total is the sum of the transfers.
fn c3018_shared_total_matches(outcome: &HopOutcome) -> Option<Violation> {
    let total: f64 = outcome.transfers.iter().map(|x| x.energy_mah).sum();
    ((outcome.shared_mah - total).abs() > e_tol(total)).then(|| {
        violation(
            "C3018",
            "shared_mah".into(),
            format!(
                "reported {} mAh, transfers sum to {total} mAh",
                outcome.shared_mah
            ),
        )
    })
}
