//! Re-verifies a composed [`Plan`] from the raw instance ([`Network`], [`Profile`], [`Request`],
//! [`Swarm`]), without the composition code paths: edges are looked up in `network.edges`,
//! lengths and headings recomputed from the node coordinates, the rate matrices taken from the
//! energy model (the physics, [`energy::rate_matrix_mah_per_min`]), every hop's sharing schedule
//! re-integrated by [`check_hop`] and every stop's pad assignment re-added.
//!
//! Rules (see `models/compose.md`), codes `P5001`-`P5034`:
//! * the plan answers the request; a failed plan gives a reason (P5001-P5003); under the
//!   paper's baseline `none` the swarm has no support drone (P5034);
//! * hops chain from the source, and, when the plan succeeds, end at the destination; a hop that
//!   ends anywhere but the destination of a successful plan stops there (P5004-P5008);
//! * every consecutive pair of path nodes is an edge of the network, the hop's length is the sum
//!   of the edge lengths (the file's `distance_m`, else Euclidean) and `tt = distance / v_g`
//!   (P5009-P5013), and the hop's per-leg list follows the path and adds up to `tt` (P5033);
//! * every hop departs with every battery full (at the source and after every stop) (P5014);
//! * every hop's schedule is feasible and valid for the hop problem rebuilt from the raw data
//!   (P5015 wraps each `C3xxx` of [`check_hop`]; P5016 for transfers without a sharing policy);
//! * every stop is at a node with pads: `ct_d = (C_d - b_d) / q_v`, the assignment is a partition
//!   of every drone over at most `k_v` pads whose makespan equals `nt`, and
//!   `nt >= max(max ct, sum ct / k_v)` (P5020-P5027); with at most [`OPTIMALITY_CHECK_DRONES`]
//!   drones, `nt` is also compared with the optimal makespan found by exhaustive search (P5028);
//! * totals: `tt = sum tt`, `nt = sum nt`, `dt = tt + nt`, shared energy = sum of the transfers
//!   (P5030-P5032).

use super::check_hop;
use crate::compose::{Hop, Plan, Stop};
use crate::eaas::{self, HopOutcome, HopProblem, SharingPolicy};
use crate::energy;
use crate::error::Violation;
use crate::problem::Wind;
use crate::problem::{Network, Profile, Request};
use crate::problem::{Role, Swarm};
use std::collections::HashMap;

/// Largest swarm whose node time is re-proved optimal by exhaustive search (at most
/// `k^n / k!` assignments, about 10^4 for 10 drones on 4 pads with the symmetry cut).
pub const OPTIMALITY_CHECK_DRONES: usize = 10;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

fn v(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "the plan breaks the composition model; report it with the instance and the request",
    )
}

/// One directed leg rebuilt from the raw network.
struct RawLeg {
    distance_m: f64,
    heading_deg: f64,
    wind: Wind,
}

/// Checks `plan` against the raw instance.
///
/// # Arguments
/// * `network` - the network as read (assumed valid).
/// * `profile` - the profile the plan was made with.
/// * `request` - the request planned.
/// * `swarm` - the swarm that flew it (drones, slots, initial positions).
/// * `sharing` - the sharing policy the plan claims; with a policy that does not share ([`SharingPolicy::shares`]) no hop may share.
/// * `plan` - the plan to verify.
///
/// # Returns
/// Every broken rule (codes `P5xxx`); empty when the plan passes.
///
/// # Complexity
/// `O(N + S)` to index the network, then per hop the schedule check of [`check_hop`] plus
/// `O(D)` per stop for `D` drones.
pub fn check_plan(
    network: &Network,
    profile: &Profile,
    request: &Request,
    swarm: &Swarm,
    sharing: SharingPolicy,
    plan: &Plan,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let index: HashMap<&str, usize> = network
        .nodes
        .iter()
        .enumerate()
        .map(|(i, n)| (n.id.as_str(), i))
        .collect();
    let speed_m_per_min = profile.drone.speed_kmh * 1000.0 / 60.0;
    let full: Vec<f64> = swarm.drones.iter().map(|d| d.capacity_mah).collect();

    if plan.source != request.source || plan.destination != request.destination {
        out.push(v(
            "P5001",
            "source, destination",
            format!(
                "plan goes {} -> {}, the request {} -> {}",
                plan.source, plan.destination, request.source, request.destination
            ),
        ));
    }
    let supports = swarm
        .drones
        .iter()
        .filter(|d| d.role == Role::Support)
        .count();
    if !sharing.flies_support() && supports > 0 {
        out.push(v(
            "P5034",
            "swarm",
            format!(
                "{supports} support drone(s) under sharing policy none, the paper's baseline \
                 without support drones"
            ),
        ));
    }
    if !plan.success && plan.failure.is_none() {
        out.push(v("P5002", "failure", "a failed plan gives no reason"));
    }
    if plan.success && plan.failure.is_some() {
        out.push(v("P5003", "failure", "a successful plan gives a failure"));
    }

    // The chain of hops.
    let mut at = request.source.as_str();
    for (k, hop) in plan.hops.iter().enumerate() {
        let f = format!("hops[{k}]");
        if hop.from != at {
            out.push(v(
                "P5004",
                format!("{f}.from"),
                format!("hop starts at {}, the swarm is at {at}", hop.from),
            ));
        }
        let last = k + 1 == plan.hops.len();
        let ends_plan = plan.success && last;
        if ends_plan && hop.to != request.destination {
            out.push(v(
                "P5005",
                format!("{f}.to"),
                format!(
                    "the last hop ends at {}, not at the destination {}",
                    hop.to, request.destination
                ),
            ));
        }
        if ends_plan && hop.stop.is_some() {
            out.push(v(
                "P5006",
                format!("{f}.stop"),
                "the destination is not a recharging stop",
            ));
        }
        if !ends_plan && hop.stop.is_none() {
            out.push(v(
                "P5007",
                format!("{f}.stop"),
                format!("the swarm ends a hop at {} without recharging", hop.to),
            ));
        }
        at = hop.to.as_str();
        check_plan_hop(
            &mut out,
            &f,
            hop,
            &index,
            network,
            profile,
            swarm,
            sharing,
            speed_m_per_min,
            &full,
        );
        if let Some(stop) = &hop.stop {
            check_stop(&mut out, &f, hop, stop, &index, network, profile, swarm);
        }
    }
    if plan.success && plan.hops.is_empty() && request.source != request.destination {
        out.push(v(
            "P5008",
            "hops",
            "a successful plan between two different nodes flies no hop",
        ));
    }

    // Totals.
    let tt: f64 = plan.hops.iter().map(|h| h.tt_min).sum();
    let nt: f64 = plan
        .hops
        .iter()
        .filter_map(|h| h.stop.as_ref().map(|s| s.nt_min))
        .sum();
    let shared: f64 = plan
        .hops
        .iter()
        .flat_map(|h| h.transfers.iter().map(|x| x.energy_mah))
        .sum();
    if !close(plan.tt_min, tt) || !close(plan.nt_min, nt) {
        out.push(v(
            "P5030",
            "tt_min, nt_min",
            format!(
                "reported tt {} and nt {}, the hops sum to tt {tt} and nt {nt}",
                plan.tt_min, plan.nt_min
            ),
        ));
    }
    if !close(plan.dt_min, tt + nt) {
        out.push(v(
            "P5031",
            "dt_min",
            format!(
                "reported dt {}, but sum tt + sum nt = {}",
                plan.dt_min,
                tt + nt
            ),
        ));
    }
    if !close(plan.shared_mah, shared) {
        out.push(v(
            "P5032",
            "shared_mah",
            format!(
                "reported {} mAh, the transfers sum to {shared} mAh",
                plan.shared_mah
            ),
        ));
    }
    out
}

/// The edge joining `a` and `b` in either direction, rebuilt as the leg `a -> b`.
fn raw_leg(network: &Network, a: usize, b: usize) -> Option<RawLeg> {
    let (na, nb) = (&network.nodes[a], &network.nodes[b]);
    let seg = network
        .edges
        .iter()
        .find(|s| (s.from == na.id && s.to == nb.id) || (s.from == nb.id && s.to == na.id))?;
    let (dx, dy) = (nb.x_m - na.x_m, nb.y_m - na.y_m);
    let distance_m = seg.distance_m.unwrap_or_else(|| (dx * dx + dy * dy).sqrt());
    // Clockwise from north: east is 90 degrees.
    let heading_deg = if dx == 0.0 && dy == 0.0 {
        0.0
    } else {
        dx.atan2(dy).to_degrees().rem_euclid(360.0)
    };
    Some(RawLeg {
        distance_m,
        heading_deg,
        wind: Wind {
            speed_mps: seg.wind_speed_mps,
            from_deg: seg.wind_from_deg,
        },
    })
}

#[allow(clippy::too_many_arguments)]
fn check_plan_hop(
    out: &mut Vec<Violation>,
    f: &str,
    hop: &Hop,
    index: &HashMap<&str, usize>,
    network: &Network,
    profile: &Profile,
    swarm: &Swarm,
    sharing: SharingPolicy,
    speed_m_per_min: f64,
    full: &[f64],
) {
    if hop.path.first() != Some(&hop.from) || hop.path.last() != Some(&hop.to) || hop.path.len() < 2
    {
        out.push(v(
            "P5009",
            format!("{f}.path"),
            format!(
                "path {:?} does not run from {} to {} over at least one edge",
                hop.path, hop.from, hop.to
            ),
        ));
        return;
    }
    let mut nodes = Vec::with_capacity(hop.path.len());
    for (i, id) in hop.path.iter().enumerate() {
        match index.get(id.as_str()) {
            Some(&n) => nodes.push(n),
            None => {
                out.push(v(
                    "P5010",
                    format!("{f}.path[{i}]"),
                    format!("`{id}` is not a node of the network"),
                ));
                return;
            }
        }
    }
    let mut legs = Vec::with_capacity(nodes.len() - 1);
    for (i, w) in nodes.windows(2).enumerate() {
        match raw_leg(network, w[0], w[1]) {
            Some(l) => legs.push(l),
            None => out.push(v(
                "P5011",
                format!("{f}.path[{i}..={}]", i + 1),
                format!(
                    "no edge joins {} and {} in the network",
                    hop.path[i],
                    hop.path[i + 1]
                ),
            )),
        }
    }
    if legs.len() + 1 != nodes.len() {
        return;
    }
    let distance_m: f64 = legs.iter().map(|l| l.distance_m).sum();
    if !close(hop.distance_m, distance_m) {
        out.push(v(
            "P5012",
            format!("{f}.distance_m"),
            format!(
                "reported {} m, the edges sum to {distance_m} m",
                hop.distance_m
            ),
        ));
    }
    let tt = distance_m / speed_m_per_min;
    if !close(hop.tt_min, tt) {
        out.push(v(
            "P5013",
            format!("{f}.tt_min"),
            format!(
                "reported {} min, distance / speed = {distance_m} / {speed_m_per_min} = {tt} min",
                hop.tt_min
            ),
        ));
    }
    // The per-leg breakdown follows the path and adds up to the hop.
    let pairs_match = hop.legs.len() + 1 == hop.path.len()
        && hop
            .legs
            .iter()
            .zip(hop.path.windows(2))
            .all(|(s, w)| s.from == w[0] && s.to == w[1]);
    let legs_tt: f64 = hop.legs.iter().map(|s| s.tt_min).sum();
    if !pairs_match || !close(legs_tt, tt) {
        out.push(v(
            "P5033",
            format!("{f}.legs"),
            format!(
                "the {} legs listed do not follow the path or their tt sum to {legs_tt} min, not {tt} min",
                hop.legs.len()
            ),
        ));
    }
    let n = swarm.drones.len();
    let sizes_ok = hop.departure_battery_mah.len() == n && hop.arrival_battery_mah.len() == n;
    if !sizes_ok
        || !hop
            .departure_battery_mah
            .iter()
            .zip(full)
            .all(|(&b, &c)| close(b, c))
    {
        out.push(v(
            "P5014",
            format!("{f}.departure_battery_mah"),
            format!(
                "departs with {:?} mAh, not every battery full ({full:?} mAh)",
                hop.departure_battery_mah
            ),
        ));
    }
    if !sizes_ok {
        return;
    }
    if !sharing.shares() && !hop.transfers.is_empty() {
        out.push(v(
            "P5016",
            format!("{f}.transfers"),
            format!(
                "{} transfer(s) under sharing policy {sharing:?}, which does not share",
                hop.transfers.len()
            ),
        ));
    }
    let s = &profile.sharing;
    let problem = HopProblem {
        legs: legs
            .iter()
            .map(|l| eaas::LegRates {
                duration_min: l.distance_m / speed_m_per_min,
                rate_mah_per_min: energy::rate_matrix_mah_per_min(
                    profile,
                    swarm,
                    l.heading_deg,
                    &l.wind,
                ),
            })
            .collect(),
        drones: swarm
            .drones
            .iter()
            .zip(&hop.departure_battery_mah)
            .map(|(d, &b)| eaas::DroneState {
                role: d.role,
                capacity_mah: d.capacity_mah,
                battery_mah: b,
            })
            .collect(),
        slots_m: swarm.slots_m.clone(),
        initial_slot: swarm.initial_slot.clone(),
        rho_mah_per_min: s.rate_mah_per_min,
        range_m: s.range_m,
        gamma_mah: s.gamma_mah,
        lambda_mah: s.lambda_mah,
        delta_mah: s.delta_mah,
    };
    // A plan records arrival batteries, not the lowest ones: the lowest are left to the
    // re-integration, whose below-zero test (C3014) is what feasibility means.
    let outcome = HopOutcome {
        feasible: true,
        failure: None,
        transfers: hop.transfers.clone(),
        final_battery_mah: hop.arrival_battery_mah.clone(),
        min_battery_mah: hop.arrival_battery_mah.clone(),
        shared_mah: hop.shared_mah,
    };
    for x in check_hop(&problem, &outcome) {
        if x.code == "C3017" {
            continue;
        }
        out.push(v(
            "P5015",
            format!("{f}: {}", x.field),
            format!("[{}] {}", x.code, x.cause),
        ));
    }
}

#[allow(clippy::too_many_arguments)]
fn check_stop(
    out: &mut Vec<Violation>,
    f: &str,
    hop: &Hop,
    stop: &Stop,
    index: &HashMap<&str, usize>,
    network: &Network,
    profile: &Profile,
    swarm: &Swarm,
) {
    let f = format!("{f}.stop");
    if stop.node != hop.to {
        out.push(v(
            "P5020",
            format!("{f}.node"),
            format!("stop at {} but the hop ends at {}", stop.node, hop.to),
        ));
    }
    let Some(&node) = index.get(stop.node.as_str()) else {
        out.push(v(
            "P5020",
            format!("{f}.node"),
            format!("`{}` is not a node of the network", stop.node),
        ));
        return;
    };
    let raw = &network.nodes[node];
    if raw.pads == 0 || stop.pads != raw.pads {
        out.push(v(
            "P5021",
            format!("{f}.pads"),
            format!(
                "node {} has {} pad(s), the stop says {}",
                raw.id, raw.pads, stop.pads
            ),
        ));
    }
    if raw.pads == 0 {
        return;
    }
    let n = swarm.drones.len();
    if hop.arrival_battery_mah.len() != n {
        out.push(v(
            "P5022",
            format!("{f}.charge_times_min"),
            format!(
                "{} arrival batteries for {n} drones: charge times undefined",
                hop.arrival_battery_mah.len()
            ),
        ));
        return;
    }
    let rate = raw
        .pad_charge_rate_mah_per_min
        .unwrap_or(profile.pads.charge_rate_mah_per_min);
    let ct: Vec<f64> = swarm
        .drones
        .iter()
        .zip(&hop.arrival_battery_mah)
        .map(|(d, &b)| (d.capacity_mah - b).max(0.0) / rate)
        .collect();
    if stop.charge_times_min.len() != n
        || !stop
            .charge_times_min
            .iter()
            .zip(&ct)
            .all(|(&a, &b)| close(a, b))
    {
        out.push(v(
            "P5022",
            format!("{f}.charge_times_min"),
            format!(
                "reported {:?} min, (capacity - arrival) / {rate} gives {ct:?} min",
                stop.charge_times_min
            ),
        ));
    }
    if stop.assignment.len() > raw.pads as usize {
        out.push(v(
            "P5023",
            format!("{f}.assignment"),
            format!(
                "{} pads used, the node has {}",
                stop.assignment.len(),
                raw.pads
            ),
        ));
    }
    let mut seen = vec![0usize; n];
    for pad in &stop.assignment {
        for &d in pad {
            if d < n {
                seen[d] += 1;
            } else {
                out.push(v(
                    "P5024",
                    format!("{f}.assignment"),
                    format!("drone {d} does not exist (swarm of {n})"),
                ));
            }
        }
    }
    if let Some(d) = seen.iter().position(|&c| c != 1) {
        out.push(v(
            "P5025",
            format!("{f}.assignment"),
            format!(
                "drone {d} charged {} time(s): not a partition of the drones",
                seen[d]
            ),
        ));
    }
    let makespan = stop
        .assignment
        .iter()
        .map(|pad| pad.iter().filter(|&&d| d < n).map(|&d| ct[d]).sum::<f64>())
        .fold(0.0, f64::max);
    if !close(makespan, stop.nt_min) {
        out.push(v(
            "P5026",
            format!("{f}.nt_min"),
            format!(
                "nt {} min, but the assignment's makespan is {makespan} min",
                stop.nt_min
            ),
        ));
    }
    if n <= OPTIMALITY_CHECK_DRONES {
        let best = optimal_makespan_min(&ct, raw.pads as usize);
        if stop.nt_min > best + 1e-6 * (1.0 + best) {
            out.push(v(
                "P5028",
                format!("{f}.nt_min"),
                format!(
                    "nt {} min, but an assignment with makespan {best} min exists",
                    stop.nt_min
                ),
            ));
        }
    }
    let max_ct = ct.iter().copied().fold(0.0, f64::max);
    let bound = max_ct.max(ct.iter().sum::<f64>() / raw.pads as f64);
    if stop.nt_min < bound - 1e-6 * (1.0 + bound) {
        out.push(v(
            "P5027",
            format!("{f}.nt_min"),
            format!(
                "nt {} min below the lower bound max(max ct, sum ct / pads) = {bound} min",
                stop.nt_min
            ),
        ));
    }
}

/// Optimal makespan of `ct` on `pads` identical pads by exhaustive search: each drone in turn goes
/// on a pad already used or on the first empty one (pads are interchangeable), cut when the
/// partial makespan reaches the best found.
fn optimal_makespan_min(ct: &[f64], pads: usize) -> f64 {
    fn go(i: usize, ct: &[f64], load: &mut Vec<f64>, pads: usize, best: &mut f64) {
        let makespan = load.iter().copied().fold(0.0, f64::max);
        if makespan >= *best {
            return;
        }
        if i == ct.len() {
            *best = makespan;
            return;
        }
        for p in 0..load.len() {
            load[p] += ct[i];
            go(i + 1, ct, load, pads, best);
            load[p] -= ct[i];
        }
        if load.len() < pads {
            load.push(ct[i]);
            go(i + 1, ct, load, pads, best);
            load.pop();
        }
    }
    let mut best = f64::INFINITY;
    go(0, ct, &mut Vec::with_capacity(pads), pads, &mut best);
    if best.is_finite() {
        best
    } else {
        0.0
    }
}
