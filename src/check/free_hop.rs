//! Re-verifies a `free` hop schedule given as slot intervals ([`SlotInterval`]) from the raw
//! [`HopProblem`], re-integrating every battery itself. It calls nothing in `crate::eaas` but the
//! types.
//!
//! One function per rule, named after its code (see `models/eaas_config.md`): the intervals
//! cover `[0, tt]` back to back without crossing a leg end (C3019); each interval's slots are a
//! permutation with every support drone in its own slot (C3020); a support drone gives to a
//! delivery drone (C3021), to one consumer at a time and a consumer takes from one support drone
//! (C3022), within `range_m` in the interval's slots (C3023); no battery above capacity
//! (C3024); a support drone shares at most its spare energy `B_s` (C3025); no battery below
//! zero (C3026); the stated final batteries match the re-integration (C3027). Within an interval
//! every rate is constant, so the bounds at its ends are the bounds throughout.

use super::hop::{e_tol, violation, T_TOL};
use crate::eaas::{HopProblem, SlotInterval};
use crate::error::Violation;
use crate::problem::Role;

/// Checks a `free` schedule against `problem`.
///
/// # Arguments
/// * `problem` - the raw hop problem (assumed valid, see [`crate::eaas::validate`]).
/// * `intervals` - the schedule.
/// * `final_battery_mah` - every drone's battery at `tt` as the schedule states it.
///
/// # Returns
/// Every broken rule (codes `C3019`-`C3027`); empty when the schedule passes.
///
/// # Complexity
/// `O(I (D + S))` for `I` intervals, `D` drones and `S` pairs served per interval.
pub fn check_free_hop(
    problem: &HopProblem,
    intervals: &[SlotInterval],
    final_battery_mah: &[f64],
) -> Vec<Violation> {
    let mut out = c3019_intervals_cover_the_hop(problem, intervals);
    for (i, x) in intervals.iter().enumerate() {
        let f = format!("intervals[{i}]");
        let slots = c3020_slots_are_a_permutation(problem, &f, x);
        let slots_ok = slots.is_empty();
        out.extend(slots);
        let pairs = c3021_support_gives_to_delivery(problem, &f, x);
        let pairs_ok = pairs.is_empty();
        out.extend(pairs);
        if pairs_ok {
            out.extend(c3022_one_partner_at_a_time(&f, x));
            if slots_ok {
                out.extend(c3023_consumer_within_range(problem, &f, x));
            }
        }
        if !(slots_ok && pairs_ok) {
            return out;
        }
    }
    if !out.is_empty() {
        return out;
    }
    let run = integrate(problem, intervals);
    out.extend(c3024_no_battery_above_capacity(problem, &run));
    out.extend(c3025_support_shares_only_its_spare(problem, &run));
    out.extend(c3026_no_battery_below_zero(&run));
    out.extend(c3027_final_batteries_match(&run, final_battery_mah));
    out
}

/// C3019: the intervals run back to back from 0 to `tt`, each positive and within one leg.
fn c3019_intervals_cover_the_hop(problem: &HopProblem, xs: &[SlotInterval]) -> Vec<Violation> {
    let tt: f64 = problem.legs.iter().map(|l| l.duration_min).sum();
    let mut ends = vec![0.0];
    for l in &problem.legs {
        ends.push(ends.last().copied().unwrap_or(0.0) + l.duration_min);
    }
    let mut out = Vec::new();
    let mut at = 0.0;
    for (i, x) in xs.iter().enumerate() {
        let f = format!("intervals[{i}]");
        if (x.start_min - at).abs() > T_TOL || x.end_min <= x.start_min {
            out.push(violation(
                "C3019",
                f.clone(),
                format!(
                    "[{}, {}) does not follow the previous end {at} with a positive length",
                    x.start_min, x.end_min
                ),
            ));
        }
        if ends
            .iter()
            .any(|&e| e > x.start_min + T_TOL && e < x.end_min - T_TOL)
        {
            out.push(violation(
                "C3019",
                f,
                format!("[{}, {}) crosses a leg end", x.start_min, x.end_min),
            ));
        }
        at = x.end_min;
    }
    if (at - tt).abs() > T_TOL {
        out.push(violation(
            "C3019",
            "intervals".into(),
            format!("the intervals end at {at}, the hop at {tt}"),
        ));
    }
    out
}

/// C3020: the slots are a permutation of the formation's, support drones in their own.
fn c3020_slots_are_a_permutation(
    problem: &HopProblem,
    f: &str,
    x: &SlotInterval,
) -> Vec<Violation> {
    let n = problem.drones.len();
    let mut seen = vec![false; n];
    let permutation = x.slot.len() == n
        && x.slot.iter().all(|&q| {
            let fresh = q < n && !seen[q];
            if fresh {
                seen[q] = true;
            }
            fresh
        });
    if !permutation {
        return vec![violation(
            "C3020",
            format!("{f}.slot"),
            format!("{:?} is not a permutation of the {n} slots", x.slot),
        )];
    }
    (0..n)
        .filter(|&d| {
            problem.drones[d].role == Role::Support && x.slot[d] != problem.initial_slot[d]
        })
        .map(|d| {
            violation(
                "C3020",
                format!("{f}.slot[{d}]"),
                format!(
                    "support drone {d} flies in slot {} instead of its own {}",
                    x.slot[d], problem.initial_slot[d]
                ),
            )
        })
        .collect()
}

/// C3021: every pair names a support drone giving to a delivery drone.
fn c3021_support_gives_to_delivery(
    problem: &HopProblem,
    f: &str,
    x: &SlotInterval,
) -> Vec<Violation> {
    let role = |d: usize| problem.drones.get(d).map(|d| d.role);
    x.serves
        .iter()
        .enumerate()
        .filter(|(_, &(s, c))| role(s) != Some(Role::Support) || role(c) != Some(Role::Delivery))
        .map(|(k, &(s, c))| {
            violation(
                "C3021",
                format!("{f}.serves[{k}]"),
                format!("({s}, {c}) is not a support drone giving to a delivery drone"),
            )
        })
        .collect()
}

/// C3022: a support drone gives to one consumer, a consumer takes from one support drone.
fn c3022_one_partner_at_a_time(f: &str, x: &SlotInterval) -> Vec<Violation> {
    let mut out = Vec::new();
    for (k, &(s, c)) in x.serves.iter().enumerate() {
        let earlier = &x.serves[..k];
        if earlier.iter().any(|&(s2, c2)| s2 == s || c2 == c) {
            out.push(violation(
                "C3022",
                format!("{f}.serves[{k}]"),
                format!("support {s} or consumer {c} is already in a pair of this interval"),
            ));
        }
    }
    out
}

/// C3023: the consumer's slot is within `range_m` of its support drone's.
fn c3023_consumer_within_range(problem: &HopProblem, f: &str, x: &SlotInterval) -> Vec<Violation> {
    x.serves
        .iter()
        .enumerate()
        .filter_map(|(k, &(s, c))| {
            let d = (problem.slots_m[x.slot[s]] - problem.slots_m[x.slot[c]]).norm();
            (d > problem.range_m + 1e-9).then(|| {
                violation(
                    "C3023",
                    format!("{f}.serves[{k}]"),
                    format!(
                        "consumer {c} in slot {} is {d} m from support {s}, beyond {} m",
                        x.slot[c], problem.range_m
                    ),
                )
            })
        })
        .collect()
}

/// Batteries at every interval end, the lowest and highest over the hop, and the energy given.
struct Run {
    highest: Vec<f64>,
    lowest: Vec<f64>,
    last: Vec<f64>,
    given: Vec<f64>,
}

fn integrate(problem: &HopProblem, xs: &[SlotInterval]) -> Run {
    let rho = problem.rho_mah_per_min;
    let mut b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
    let (mut highest, mut lowest) = (b.clone(), b.clone());
    let mut given = vec![0.0; b.len()];
    let mut leg_start = 0.0;
    let mut leg = 0;
    for x in xs {
        // The leg holding the interval (C3019 keeps it within one).
        while leg + 1 < problem.legs.len()
            && x.start_min >= leg_start + problem.legs[leg].duration_min - T_TOL
        {
            leg_start += problem.legs[leg].duration_min;
            leg += 1;
        }
        let dur = x.end_min - x.start_min;
        let rates = &problem.legs[leg].rate_mah_per_min;
        for (d, bd) in b.iter_mut().enumerate() {
            *bd -= dur * rates[d][x.slot[d]];
        }
        for &(s, c) in &x.serves {
            b[s] -= rho * dur;
            b[c] += rho * dur;
            given[s] += rho * dur;
        }
        for d in 0..b.len() {
            highest[d] = highest[d].max(b[d]);
            lowest[d] = lowest[d].min(b[d]);
        }
    }
    Run {
        highest,
        lowest,
        last: b,
        given,
    }
}

/// C3024: no battery above its capacity.
fn c3024_no_battery_above_capacity(problem: &HopProblem, run: &Run) -> Vec<Violation> {
    (0..run.highest.len())
        .filter(|&d| {
            let cap = problem.drones[d].capacity_mah;
            run.highest[d] > cap + e_tol(cap)
        })
        .map(|d| {
            violation(
                "C3024",
                format!("drones[{d}]"),
                format!(
                    "battery reaches {} mAh, above its capacity {}",
                    run.highest[d], problem.drones[d].capacity_mah
                ),
            )
        })
        .collect()
}

/// C3025: a support drone gives at most `B_s = max(0, b_s(0) - Σ_l τ_l r[l][s][π(s)] - delta)`.
fn c3025_support_shares_only_its_spare(problem: &HopProblem, run: &Run) -> Vec<Violation> {
    (0..run.given.len())
        .filter(|&s| problem.drones[s].role == Role::Support)
        .filter_map(|s| {
            let own: f64 = problem
                .legs
                .iter()
                .map(|l| l.duration_min * l.rate_mah_per_min[s][problem.initial_slot[s]])
                .sum();
            let spare = (problem.drones[s].battery_mah - own - problem.delta_mah).max(0.0);
            (run.given[s] > spare + e_tol(spare)).then(|| {
                violation(
                    "C3025",
                    format!("drones[{s}]"),
                    format!(
                        "support drone gives {} mAh, more than its spare {spare}",
                        run.given[s]
                    ),
                )
            })
        })
        .collect()
}

/// C3026: no battery below zero (the schedule flies).
fn c3026_no_battery_below_zero(run: &Run) -> Vec<Violation> {
    (0..run.lowest.len())
        .filter(|&d| run.lowest[d] < -e_tol(0.0))
        .map(|d| {
            violation(
                "C3026",
                format!("drones[{d}]"),
                format!("battery falls to {} mAh", run.lowest[d]),
            )
        })
        .collect()
}

/// C3027: the stated final batteries are the re-integrated ones.
fn c3027_final_batteries_match(run: &Run, stated: &[f64]) -> Vec<Violation> {
    let same = stated.len() == run.last.len()
        && stated
            .iter()
            .zip(&run.last)
            .all(|(a, b)| (a - b).abs() <= e_tol(*b));
    if same {
        Vec::new()
    } else {
        vec![violation(
            "C3027",
            "final_battery_mah".into(),
            format!("stated {stated:?}, re-integrated {:?}", run.last),
        )]
    }
}
