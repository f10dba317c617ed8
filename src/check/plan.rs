//! Re-verifies a composed [`Plan`] from the raw instance ([`Network`], [`Profile`], [`Request`],
//! [`Swarm`]), without the composition code paths: edges are looked up in `network.edges`,
//! lengths and headings recomputed from the node coordinates, the rate matrices taken from the
//! energy model (the physics, [`energy::rate_matrix_mah_per_min`]), every hop's sharing schedule
//! re-integrated by [`check_hop`] and every stop's pad assignment re-added.
//!
//! One function per rule, named after its code. Rules (see `models/compose.md`), codes
//! `P5001`-`P5040`:
//! * the plan answers the request (P5001); under the paper's baseline `none` the swarm has no
//!   support drone (P5034);
//! * the swarm is well formed (P5037), its delivery drones carry the request's packages (P5038),
//!   its drones are the profile's (P5039) and its slots the formation's (P5040);
//! * hops chain from the source, and, when the plan is delivered, end at the destination; a hop
//!   that ends anywhere but the destination of a delivered plan stops there (P5004-P5008);
//! * a failed plan's outcome names where the swarm is (P5035), and claims no route only between
//!   nodes the network does not connect (P5036);
//! * every consecutive pair of path nodes is an edge of the network, the hop's length is the sum
//!   of the edge lengths (the file's `distance_m`, else Euclidean) and `tt = distance / v_g`
//!   (P5009-P5013), and the hop's per-leg list follows the path and adds up to `tt` (P5033);
//! * every hop departs with every battery full (at the source and after every stop) (P5014);
//! * every hop's schedule is feasible and valid for the hop problem rebuilt from the raw data
//!   (P5015 wraps each `C3xxx` of [`check_hop`]; P5016 for transfers without a sharing policy);
//! * every stop is at a node with pads: `ct_d = (C_d - b_d) / q_v`, the assignment is a partition
//!   of every drone over at most `k_v` pads whose makespan equals `nt`, and
//!   `nt >= max(max ct, sum ct / k_v)` (P5020-P5027); with at most [`OPTIMALITY_CHECK_DRONES`]
//!   drones, the `nt` of a stop whose status is `optimal` is also compared with the optimal
//!   makespan found by exhaustive search (P5028; a node limit may leave a `feasible` incumbent);
//! * totals: `tt = sum tt`, `nt = sum nt`, `dt = tt + nt`, shared energy = sum of the transfers
//!   (P5030-P5032).
//!
//! Codes P5002 and P5003 (a failed plan without a reason, a delivered one with a failure) are
//! retired: a plan's [`PlanOutcome`] cannot say both.

use super::check_hop;
use crate::compose::{Hop, Plan, PlanOutcome, Stop};
use crate::eaas::{self, HopOutcome, HopProblem, SharingPolicy};
use crate::energy;
use crate::error::Violation;
use crate::formation;
use crate::problem::io::json_name;
use crate::problem::Candidates;
use crate::problem::{Network, Node, Profile, Request};
use crate::problem::{Role, Swarm, Wind};
use crate::solver::SolveStatus;
use std::collections::HashMap;

/// Largest swarm whose node time is re-proved optimal by exhaustive search (at most
/// `k^n / k!` assignments, about 10^4 for 10 drones on 4 pads with the symmetry cut).
pub const OPTIMALITY_CHECK_DRONES: usize = 10;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= super::INTEGRATION_TOLERANCE * (1.0 + a.abs().max(b.abs()))
}

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "the plan breaks the composition model: it was changed after it was made, or made on \
         another network or profile; make it again with `swarmplan solve ... --json` on the \
         instance it is checked with",
    )
}

/// The raw instance every rule reads, indexed once.
struct Raw<'a> {
    network: &'a Network,
    profile: &'a Profile,
    request: &'a Request,
    swarm: &'a Swarm,
    sharing: SharingPolicy,
    /// Node id -> index in `network.nodes`.
    index: HashMap<&'a str, usize>,
    /// Ground speed `v_g`, m/min.
    speed_m_per_min: f64,
    /// Every drone's capacity, mAh: its battery when full.
    full: Vec<f64>,
}

/// One directed leg rebuilt from the raw network.
pub(super) struct RawLeg {
    pub(super) distance_m: f64,
    pub(super) heading_deg: f64,
    pub(super) wind: Wind,
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
/// Every broken rule (codes `P5xxx`); empty when the plan passes. A malformed plan or swarm (a
/// plan read from a file) gives violations, never a panic.
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
    let raw = Raw {
        network,
        profile,
        request,
        swarm,
        sharing,
        index: super::node_index(network),
        speed_m_per_min: profile.drone.speed_kmh * 1000.0 / 60.0,
        full: swarm.drones.iter().map(|d| d.capacity_mah).collect(),
    };
    let mut out = Vec::new();
    out.extend(p5001_plan_answers_the_request(&raw, plan));
    out.extend(p5034_baseline_flies_no_support_drone(&raw));
    let shape = p5037_swarm_is_well_formed(swarm);
    let swarm_ok = shape.is_empty();
    out.extend(shape);
    out.extend(p5038_delivery_drones_carry_the_packages(&raw));
    out.extend(p5039_drones_are_the_profiles(&raw));
    if swarm_ok {
        out.extend(p5040_slots_are_the_formations(&raw));
    }

    // The chain of hops.
    let mut at = request.source.as_str();
    for (k, hop) in plan.hops.iter().enumerate() {
        let f = format!("hops[{k}]");
        let ends_plan = plan.delivered() && k + 1 == plan.hops.len();
        out.extend(p5004_hop_starts_where_the_swarm_is(&f, hop, at));
        out.extend(p5005_last_hop_ends_at_the_destination(
            &raw, &f, hop, ends_plan,
        ));
        out.extend(p5006_no_stop_at_the_destination(&f, hop, ends_plan));
        out.extend(p5007_other_hops_end_in_a_stop(&f, hop, ends_plan));
        at = hop.to.as_str();
        check_flight(&mut out, &raw, &f, hop, swarm_ok);
        if let Some(stop) = &hop.stop {
            check_stop(&mut out, &raw, &f, hop, stop);
        }
    }
    out.extend(p5008_a_delivery_flies(&raw, plan));
    out.extend(p5035_failure_names_where_the_swarm_is(&raw, plan));
    out.extend(p5036_no_route_only_between_unconnected_nodes(&raw, plan));

    // Totals.
    out.extend(p5030_totals_are_the_sums(plan));
    out.extend(p5031_dt_is_tt_plus_nt(plan));
    out.extend(p5032_shared_is_the_transfers(plan));
    out
}

// ---- The plan and the request.

/// P5001: the plan goes from the request's source to its destination.
fn p5001_plan_answers_the_request(raw: &Raw, plan: &Plan) -> Option<Violation> {
    let r = raw.request;
    (plan.source != r.source || plan.destination != r.destination).then(|| {
        violation(
            "P5001",
            "source, destination",
            format!(
                "plan goes {} -> {}, the request {} -> {}",
                plan.source, plan.destination, r.source, r.destination
            ),
        )
    })
}

/// P5034: under the paper's baseline `none` the swarm has no support drone.
fn p5034_baseline_flies_no_support_drone(raw: &Raw) -> Option<Violation> {
    let supports = raw.swarm.support_count();
    (!raw.sharing.flies_support() && supports > 0).then(|| {
        violation(
            "P5034",
            "swarm",
            format!(
                "{supports} support drone(s) under sharing policy none, the paper's baseline \
                 without support drones"
            ),
        )
    })
}

// ---- The swarm.

/// P5037: drone ids are their indices, there is one slot per drone and the initial slots are a
/// permutation of the slots. The hop schedules are re-checked only on a well-formed swarm.
fn p5037_swarm_is_well_formed(swarm: &Swarm) -> Vec<Violation> {
    let mut out = Vec::new();
    let n = swarm.drones.len();
    if let Some((i, d)) = swarm.drones.iter().enumerate().find(|(i, d)| d.id != *i) {
        out.push(violation(
            "P5037",
            format!("swarm.drones[{i}].id"),
            format!("drone {i} has id {}: ids must be the drones' indices", d.id),
        ));
    }
    if swarm.slots_m.len() != n {
        out.push(violation(
            "P5037",
            "swarm.slots_m",
            format!("{} slots for {n} drones", swarm.slots_m.len()),
        ));
    }
    let mut seen = vec![false; n];
    let permutation = swarm.initial_slot.len() == n
        && swarm
            .initial_slot
            .iter()
            .all(|&q| q < n && !std::mem::replace(&mut seen[q], true));
    if !permutation {
        out.push(violation(
            "P5037",
            "swarm.initial_slot",
            format!(
                "{:?} is not a permutation of the {n} slots",
                swarm.initial_slot
            ),
        ));
    }
    out
}

/// P5038: delivery drones come first, one per package of the request in its order, each
/// carrying its package; the other drones are support drones.
fn p5038_delivery_drones_carry_the_packages(raw: &Raw) -> Option<Violation> {
    let packages = &raw.request.packages_kg;
    let drones = &raw.swarm.drones;
    let delivery = drones
        .iter()
        .take_while(|d| d.role == Role::Delivery)
        .count();
    let rest_support = drones[delivery..].iter().all(|d| d.role == Role::Support);
    let carried = drones
        .iter()
        .zip(packages)
        .all(|(d, &p)| close(d.payload_kg, p));
    (delivery != packages.len() || !rest_support || !carried).then(|| {
        violation(
            "P5038",
            "swarm.drones",
            format!(
                "delivery drones carry {:?} kg, the request's packages are {packages:?} kg \
                 (delivery drones first, one per package in order, then support drones)",
                drones
                    .iter()
                    .filter(|d| d.role == Role::Delivery)
                    .map(|d| d.payload_kg)
                    .collect::<Vec<_>>()
            ),
        )
    })
}

/// P5039: every drone has the profile's capacity (one battery for a delivery drone,
/// `1 + extra_batteries` for a support drone), and a support drone carries the extra batteries.
fn p5039_drones_are_the_profiles(raw: &Raw) -> Vec<Violation> {
    let p = raw.profile;
    raw.swarm
        .drones
        .iter()
        .enumerate()
        .flat_map(|(i, d)| {
            let (capacity, payload) = match d.role {
                Role::Delivery => (p.drone.battery_mah, d.payload_kg),
                Role::Support => (p.support_capacity_mah(), p.support_payload_kg()),
            };
            let mut out = Vec::new();
            for (field, stated, expected, unit) in [
                ("capacity_mah", d.capacity_mah, capacity, "mAh"),
                ("payload_kg", d.payload_kg, payload, "kg"),
            ] {
                if !close(stated, expected) {
                    out.push(violation(
                        "P5039",
                        format!("swarm.drones[{i}].{field}"),
                        format!(
                            "{} drone with {stated} {unit}, the profile gives {expected} {unit}",
                            json_name(&d.role)
                        ),
                    ));
                }
            }
            out
        })
        .collect()
}

/// P5040: the slots are those of the swarm's formation at the profile's spacing.
fn p5040_slots_are_the_formations(raw: &Raw) -> Option<Violation> {
    let swarm = raw.swarm;
    let want = formation::slots_m(
        swarm.formation,
        swarm.drones.len(),
        raw.profile.formation.spacing_m,
    );
    let same = want
        .iter()
        .zip(&swarm.slots_m)
        .all(|(a, b)| close(a.x, b.x) && close(a.y, b.y));
    (!same).then(|| {
        violation(
            "P5040",
            "swarm.slots_m",
            format!(
                "not the slots of a {} formation of {} drones at {} m spacing",
                json_name(&swarm.formation),
                swarm.drones.len(),
                raw.profile.formation.spacing_m
            ),
        )
    })
}

// ---- The chain of hops.

/// P5004: a hop starts where the swarm is: the source, or where the previous hop ended.
fn p5004_hop_starts_where_the_swarm_is(f: &str, hop: &Hop, at: &str) -> Option<Violation> {
    (hop.from != at).then(|| {
        violation(
            "P5004",
            format!("{f}.from"),
            format!("hop starts at {}, the swarm is at {at}", hop.from),
        )
    })
}

/// P5005: the last hop of a delivered plan ends at the destination.
fn p5005_last_hop_ends_at_the_destination(
    raw: &Raw,
    f: &str,
    hop: &Hop,
    ends_plan: bool,
) -> Option<Violation> {
    let destination = &raw.request.destination;
    (ends_plan && hop.to != *destination).then(|| {
        violation(
            "P5005",
            format!("{f}.to"),
            format!(
                "the last hop ends at {}, not at the destination {destination}",
                hop.to
            ),
        )
    })
}

/// P5006: the swarm does not recharge at the destination.
fn p5006_no_stop_at_the_destination(f: &str, hop: &Hop, ends_plan: bool) -> Option<Violation> {
    (ends_plan && hop.stop.is_some()).then(|| {
        violation(
            "P5006",
            format!("{f}.stop"),
            "the destination is not a recharging stop",
        )
    })
}

/// P5007: every hop but the last of a delivered plan ends in a recharging stop.
fn p5007_other_hops_end_in_a_stop(f: &str, hop: &Hop, ends_plan: bool) -> Option<Violation> {
    (!ends_plan && hop.stop.is_none()).then(|| {
        violation(
            "P5007",
            format!("{f}.stop"),
            format!("the swarm ends a hop at {} without recharging", hop.to),
        )
    })
}

/// P5008: a delivered plan between two different nodes flies at least one hop.
fn p5008_a_delivery_flies(raw: &Raw, plan: &Plan) -> Option<Violation> {
    let r = raw.request;
    (plan.delivered() && plan.hops.is_empty() && r.source != r.destination).then(|| {
        violation(
            "P5008",
            "hops",
            "a successful plan between two different nodes flies no hop",
        )
    })
}

/// P5035: a failed plan's outcome names nodes of the network and where the swarm is: the end
/// of the last hop flown (or the source). Algorithm 1 over adjacent nodes may fail at a node it
/// passed without charging, after the last hop recorded; there only the node's existence is
/// checked. A plan that fails for want of a route names the destination.
fn p5035_failure_names_where_the_swarm_is(raw: &Raw, plan: &Plan) -> Option<Violation> {
    let at = plan
        .hops
        .last()
        .map_or(raw.request.source.as_str(), |h| h.to.as_str());
    let known = |id: &str| raw.index.contains_key(id);
    let cause = match &plan.outcome {
        PlanOutcome::Delivered => return None,
        PlanOutcome::NoRoute { from, to } => {
            if !known(from) || *to != raw.request.destination {
                format!(
                    "no route from {from} to {to}, but the swarm heads for {} from a node of \
                     the network",
                    raw.request.destination
                )
            } else {
                return None;
            }
        }
        PlanOutcome::DeadEnd {
            node, candidates, ..
        } => {
            let fine = match candidates {
                Candidates::PadNodes => node == at,
                Candidates::Adjacent => known(node),
            };
            if fine {
                return None;
            }
            format!("dead end at {node}, but the swarm is at {at}")
        }
        PlanOutcome::HopInfeasible { from, to, .. } => {
            if from == at && known(to) {
                return None;
            }
            format!("cannot reach {to} from {from}, but the swarm is at {at}")
        }
        PlanOutcome::NoStopSequence { from, to, .. } => {
            if from == at && *to == raw.request.destination {
                return None;
            }
            format!(
                "no sequence of stops from {from} to {to}, but the swarm is at {at} and heads \
                 for {}",
                raw.request.destination
            )
        }
    };
    Some(violation("P5035", "outcome", cause))
}

/// P5036: a plan fails for want of a route only between nodes no path of the network joins.
fn p5036_no_route_only_between_unconnected_nodes(raw: &Raw, plan: &Plan) -> Option<Violation> {
    let PlanOutcome::NoRoute { from, to } = &plan.outcome else {
        return None;
    };
    let (&a, &b) = (raw.index.get(from.as_str())?, raw.index.get(to.as_str())?);
    let n = raw.network.nodes.len();
    let mut adjacent = vec![Vec::new(); n];
    for e in &raw.network.edges {
        if let (Some(&x), Some(&y)) = (raw.index.get(e.from.as_str()), raw.index.get(e.to.as_str()))
        {
            adjacent[x].push(y);
            adjacent[y].push(x);
        }
    }
    let mut seen = vec![false; n];
    let mut stack = vec![a];
    seen[a] = true;
    while let Some(x) = stack.pop() {
        for &y in &adjacent[x] {
            if !std::mem::replace(&mut seen[y], true) {
                stack.push(y);
            }
        }
    }
    seen[b].then(|| {
        violation(
            "P5036",
            "outcome",
            format!("no route from {from} to {to}, but the network joins them"),
        )
    })
}

// ---- Totals.

/// P5030: the plan's `tt` and `nt` are the sums over its hops and stops.
fn p5030_totals_are_the_sums(plan: &Plan) -> Vec<Violation> {
    [
        ("tt_min", plan.tt_min, sum_tt(plan), "hops' travel times"),
        ("nt_min", plan.nt_min, sum_nt(plan), "stops' node times"),
    ]
    .into_iter()
    .filter(|(_, stated, sum, _)| !close(*stated, *sum))
    .map(|(field, stated, sum, what)| {
        violation(
            "P5030",
            field,
            format!("reported {stated}, the {what} sum to {sum}"),
        )
    })
    .collect()
}

/// P5031: `dt = sum tt + sum nt`.
fn p5031_dt_is_tt_plus_nt(plan: &Plan) -> Option<Violation> {
    let dt = sum_tt(plan) + sum_nt(plan);
    (!close(plan.dt_min, dt)).then(|| {
        violation(
            "P5031",
            "dt_min",
            format!("reported dt {}, but sum tt + sum nt = {dt}", plan.dt_min),
        )
    })
}

/// P5032: the energy shared is the sum of the transfers.
fn p5032_shared_is_the_transfers(plan: &Plan) -> Option<Violation> {
    let shared: f64 = plan
        .hops
        .iter()
        .flat_map(|h| h.transfers.iter().map(|x| x.energy_mah))
        .sum();
    (!close(plan.shared_mah, shared)).then(|| {
        violation(
            "P5032",
            "shared_mah",
            format!(
                "reported {} mAh, the transfers sum to {shared} mAh",
                plan.shared_mah
            ),
        )
    })
}

fn sum_tt(plan: &Plan) -> f64 {
    plan.hops.iter().map(|h| h.tt_min).sum()
}

fn sum_nt(plan: &Plan) -> f64 {
    plan.hops
        .iter()
        .filter_map(|h| h.stop.as_ref().map(|s| s.nt_min))
        .sum()
}

// ---- Each hop's flight.

/// The rules of one hop's flight, in order; a rule whose failure leaves the rest undefined (a
/// path that is not one, an unknown node, a missing edge, batteries of the wrong size) ends the
/// hop's checks. The schedule is re-checked only on a well-formed swarm (`swarm_ok`).
fn check_flight(out: &mut Vec<Violation>, raw: &Raw, f: &str, hop: &Hop, swarm_ok: bool) {
    if let Some(x) = p5009_path_runs_between_the_hop_ends(f, hop) {
        out.push(x);
        return;
    }
    let nodes = match p5010_path_nodes_exist(raw, f, hop) {
        Ok(nodes) => nodes,
        Err(x) => {
            out.push(x);
            return;
        }
    };
    let legs = match p5011_path_follows_edges(raw, f, hop, &nodes) {
        Ok(legs) => legs,
        Err(xs) => {
            out.extend(xs);
            return;
        }
    };
    let distance_m: f64 = legs.iter().map(|l| l.distance_m).sum();
    out.extend(p5012_distance_is_the_edges(f, hop, distance_m));
    out.extend(p5013_tt_is_distance_over_speed(raw, f, hop, distance_m));
    out.extend(p5033_legs_follow_the_path(raw, f, hop, distance_m));
    out.extend(p5044_legs_are_the_edges(raw, f, hop, &legs));
    out.extend(p5014_departs_full(raw, f, hop));
    let n = raw.swarm.drones.len();
    if hop.departure_battery_mah.len() != n || hop.arrival_battery_mah.len() != n {
        return;
    }
    out.extend(p5016_no_transfer_without_sharing(raw, f, hop));
    if swarm_ok {
        out.extend(p5015_schedule_passes_the_hop_checker(raw, f, hop, &legs));
    }
}

/// P5009: the path runs from the hop's start to its end over at least one edge.
fn p5009_path_runs_between_the_hop_ends(f: &str, hop: &Hop) -> Option<Violation> {
    let ok = hop.path.first() == Some(&hop.from)
        && hop.path.last() == Some(&hop.to)
        && hop.path.len() >= 2;
    (!ok).then(|| {
        violation(
            "P5009",
            format!("{f}.path"),
            format!(
                "path {:?} does not run from {} to {} over at least one edge",
                hop.path, hop.from, hop.to
            ),
        )
    })
}

/// P5010: every node of the path is a node of the network; their indices.
fn p5010_path_nodes_exist(raw: &Raw, f: &str, hop: &Hop) -> Result<Vec<usize>, Violation> {
    hop.path
        .iter()
        .enumerate()
        .map(|(i, id)| {
            raw.index.get(id.as_str()).copied().ok_or_else(|| {
                violation(
                    "P5010",
                    format!("{f}.path[{i}]"),
                    format!("`{id}` is not a node of the network"),
                )
            })
        })
        .collect()
}

/// P5011: every consecutive pair of path nodes is an edge of the network; the legs flown.
fn p5011_path_follows_edges(
    raw: &Raw,
    f: &str,
    hop: &Hop,
    nodes: &[usize],
) -> Result<Vec<RawLeg>, Vec<Violation>> {
    let mut legs = Vec::with_capacity(nodes.len().saturating_sub(1));
    let mut missing = Vec::new();
    for (i, w) in nodes.windows(2).enumerate() {
        match raw_leg(raw.network, w[0], w[1]) {
            Some(l) => legs.push(l),
            None => missing.push(violation(
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
    if missing.is_empty() {
        Ok(legs)
    } else {
        Err(missing)
    }
}

/// The edge joining `a` and `b` in either direction, rebuilt as the leg `a -> b`.
pub(super) fn raw_leg(network: &Network, a: usize, b: usize) -> Option<RawLeg> {
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

/// P5012: the hop's length is the sum of its edges' lengths.
fn p5012_distance_is_the_edges(f: &str, hop: &Hop, distance_m: f64) -> Option<Violation> {
    (!close(hop.distance_m, distance_m)).then(|| {
        violation(
            "P5012",
            format!("{f}.distance_m"),
            format!(
                "reported {} m, the edges sum to {distance_m} m",
                hop.distance_m
            ),
        )
    })
}

/// P5013: `tt = distance / v_g`.
fn p5013_tt_is_distance_over_speed(
    raw: &Raw,
    f: &str,
    hop: &Hop,
    distance_m: f64,
) -> Option<Violation> {
    let speed = raw.speed_m_per_min;
    let tt = distance_m / speed;
    (!close(hop.tt_min, tt)).then(|| {
        violation(
            "P5013",
            format!("{f}.tt_min"),
            format!(
                "reported {} min, distance / speed = {distance_m} / {speed} = {tt} min",
                hop.tt_min
            ),
        )
    })
}

/// P5033: the per-leg breakdown follows the path and its travel times add up to the hop's.
fn p5033_legs_follow_the_path(raw: &Raw, f: &str, hop: &Hop, distance_m: f64) -> Option<Violation> {
    let tt = distance_m / raw.speed_m_per_min;
    let pairs_match = hop.legs.len() + 1 == hop.path.len()
        && hop
            .legs
            .iter()
            .zip(hop.path.windows(2))
            .all(|(s, w)| s.from == w[0] && s.to == w[1]);
    let legs_tt: f64 = hop.legs.iter().map(|s| s.tt_min).sum();
    (!pairs_match || !close(legs_tt, tt)).then(|| {
        violation(
            "P5033",
            format!("{f}.legs"),
            format!(
                "the {} legs listed do not follow the path or their tt sum to {legs_tt} min, not {tt} min",
                hop.legs.len()
            ),
        )
    })
}

/// P5044: every leg listed states its edge's numbers: length, heading from the node coordinates
/// (modulo 360 degrees), wind speed and direction, and travel time `distance / v_g`; one
/// violation per number that differs, with the stated and the recomputed value. A leg that does
/// not follow the path (P5033) is not compared.
fn p5044_legs_are_the_edges(raw: &Raw, f: &str, hop: &Hop, legs: &[RawLeg]) -> Vec<Violation> {
    let angle_close = |a: f64, b: f64| {
        let d = (a - b).rem_euclid(360.0);
        d.min(360.0 - d) <= super::INTEGRATION_TOLERANCE * 360.0
    };
    let mut out = Vec::new();
    for (j, ((stated, raw_leg), ends)) in hop
        .legs
        .iter()
        .zip(legs)
        .zip(hop.path.windows(2))
        .enumerate()
    {
        if stated.from != ends[0] || stated.to != ends[1] {
            continue;
        }
        let tt = raw_leg.distance_m / raw.speed_m_per_min;
        let numbers = [
            (
                "distance_m",
                stated.distance_m,
                raw_leg.distance_m,
                close(stated.distance_m, raw_leg.distance_m),
            ),
            (
                "heading_deg",
                stated.heading_deg,
                raw_leg.heading_deg,
                angle_close(stated.heading_deg, raw_leg.heading_deg),
            ),
            (
                "wind_speed_mps",
                stated.wind_speed_mps,
                raw_leg.wind.speed_mps,
                close(stated.wind_speed_mps, raw_leg.wind.speed_mps),
            ),
            (
                "wind_from_deg",
                stated.wind_from_deg,
                raw_leg.wind.from_deg,
                angle_close(stated.wind_from_deg, raw_leg.wind.from_deg),
            ),
            ("tt_min", stated.tt_min, tt, close(stated.tt_min, tt)),
        ];
        for (name, got, want, ok) in numbers {
            if !ok {
                out.push(violation(
                    "P5044",
                    format!("{f}.legs[{j}].{name}"),
                    format!(
                        "states {got}, the edge {} - {} gives {want}",
                        stated.from, stated.to
                    ),
                ));
            }
        }
    }
    out
}

/// P5014: the hop departs with every battery full, and lists one departure and one arrival
/// battery per drone.
fn p5014_departs_full(raw: &Raw, f: &str, hop: &Hop) -> Option<Violation> {
    let n = raw.swarm.drones.len();
    let sizes_ok = hop.departure_battery_mah.len() == n && hop.arrival_battery_mah.len() == n;
    let full = sizes_ok
        && hop
            .departure_battery_mah
            .iter()
            .zip(&raw.full)
            .all(|(&b, &c)| close(b, c));
    (!full).then(|| {
        violation(
            "P5014",
            format!("{f}.departure_battery_mah"),
            format!(
                "departs with {:?} mAh, not every battery full ({:?} mAh)",
                hop.departure_battery_mah, raw.full
            ),
        )
    })
}

/// P5016: no transfer under a policy that does not share.
fn p5016_no_transfer_without_sharing(raw: &Raw, f: &str, hop: &Hop) -> Option<Violation> {
    (!raw.sharing.shares() && !hop.transfers.is_empty()).then(|| {
        violation(
            "P5016",
            format!("{f}.transfers"),
            format!(
                "{} transfer(s) under sharing policy {}, which does not share",
                hop.transfers.len(),
                json_name(&raw.sharing)
            ),
        )
    })
}

/// P5015: the hop's schedule, with its arrival batteries, passes [`check_hop`] on the hop
/// problem rebuilt from the raw network, the profile and the energy model; each `C3xxx` is
/// reported under P5015 (C3017, lowest batteries, excepted: a plan does not record them).
fn p5015_schedule_passes_the_hop_checker(
    raw: &Raw,
    f: &str,
    hop: &Hop,
    legs: &[RawLeg],
) -> Vec<Violation> {
    let problem = hop_problem(raw.profile, raw.swarm, legs, &hop.departure_battery_mah);
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
    check_hop(&problem, &outcome)
        .into_iter()
        .filter(|x| x.code != "C3017")
        .map(|x| {
            violation(
                "P5015",
                plan_field_of_hop_field(f, &x.field),
                format!("[{}] {} (hop checker field `{}`)", x.code, x.cause, x.field),
            )
        })
        .collect()
}

/// The hop problem of a hop flown over `legs` from `departure_battery_mah` (one per drone), built
/// from the profile, the energy model and the swarm.
fn hop_problem(
    profile: &Profile,
    swarm: &Swarm,
    legs: &[RawLeg],
    departure_battery_mah: &[f64],
) -> HopProblem {
    let s = &profile.sharing;
    let speed_m_per_min = profile.drone.speed_kmh * 1000.0 / 60.0;
    HopProblem {
        legs: legs
            .iter()
            .map(|l| eaas::LegRates {
                duration_min: l.distance_m / speed_m_per_min,
                rate_mah_per_min: energy::rate_matrix_mah_per_min(
                    profile,
                    swarm,
                    l.heading_deg,
                    &l.wind,
                )
                .into(),
            })
            .collect(),
        drones: swarm
            .drones
            .iter()
            .zip(departure_battery_mah)
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
    }
}

/// The hop problem `hop`'s schedule is checked on (P5015), rebuilt from the raw network, the
/// profile, the energy model and the swarm: the legs of the hop's path as the network's edges,
/// the hop's departure batteries.
///
/// # Returns
/// `None` when the problem cannot be rebuilt: the swarm is not well formed (P5037), the hop's
/// path is not a path of the network (P5009-P5011), or its departure batteries are not one per
/// drone.
///
/// # Complexity
/// `O(N + L * S + L * D^2)` for `N` nodes, `S` edges, `L` legs and `D` drones.
pub fn rebuilt_hop_problem(
    network: &Network,
    profile: &Profile,
    swarm: &Swarm,
    hop: &Hop,
) -> Option<HopProblem> {
    let n = swarm.drones.len();
    if !p5037_swarm_is_well_formed(swarm).is_empty()
        || hop.departure_battery_mah.len() != n
        || p5009_path_runs_between_the_hop_ends("", hop).is_some()
    {
        return None;
    }
    let index = super::node_index(network);
    let nodes: Vec<usize> = hop
        .path
        .iter()
        .map(|id| index.get(id.as_str()).copied())
        .collect::<Option<_>>()?;
    let legs: Vec<RawLeg> = nodes
        .windows(2)
        .map(|w| raw_leg(network, w[0], w[1]))
        .collect::<Option<_>>()?;
    Some(hop_problem(
        profile,
        swarm,
        &legs,
        &hop.departure_battery_mah,
    ))
}

/// The plan's field a hop checker's field stands for: a hop outcome's batteries are the hop's
/// arrival batteries, its transfers and shared energy the hop's own; anything else (a drone, the
/// hop's feasibility) is the hop as a whole.
fn plan_field_of_hop_field(hop: &str, field: &str) -> String {
    let rest = field
        .strip_prefix("final_battery_mah")
        .or_else(|| field.strip_prefix("min_battery_mah"))
        .map(|rest| format!("arrival_battery_mah{rest}"));
    match rest {
        Some(battery) => format!("{hop}.{battery}"),
        None if field.starts_with("transfers") || field.starts_with("shared_mah") => {
            format!("{hop}.{field}")
        }
        None => hop.to_string(),
    }
}

// ---- Each stop.

/// The rules of one recharging stop, in order; an unknown node, a node without pads or arrival
/// batteries of the wrong size end the stop's checks.
fn check_stop(out: &mut Vec<Violation>, raw: &Raw, f: &str, hop: &Hop, stop: &Stop) {
    let f = format!("{f}.stop");
    out.extend(p5020_stop_is_at_the_hop_end(&f, hop, stop));
    let node = match p5020_stop_node_is_in_the_network(raw, &f, stop) {
        Ok(node) => node,
        Err(x) => {
            out.push(x);
            return;
        }
    };
    out.extend(p5021_pads_are_the_nodes(&f, stop, node));
    if node.pads == 0 {
        return;
    }
    let ct = charge_times_min(raw, hop, node);
    out.extend(p5022_charge_times_follow_the_arrival(
        raw,
        &f,
        hop,
        stop,
        node,
        ct.as_deref(),
    ));
    let Some(ct) = ct else {
        return;
    };
    let n = raw.swarm.drones.len();
    out.extend(p5023_pads_used_exist(&f, stop, node));
    out.extend(p5024_assigned_drones_exist(&f, stop, n));
    out.extend(p5025_assignment_is_a_partition(&f, stop, n));
    out.extend(p5026_nt_is_the_makespan(&f, stop, &ct));
    if n <= OPTIMALITY_CHECK_DRONES && stop.status == SolveStatus::Optimal {
        out.extend(p5028_nt_is_optimal(&f, stop, &ct, node.pads as usize));
    }
    out.extend(p5027_nt_above_the_lower_bound(&f, stop, &ct, node.pads));
}

/// P5020: the stop is at the node the hop ends at.
fn p5020_stop_is_at_the_hop_end(f: &str, hop: &Hop, stop: &Stop) -> Option<Violation> {
    (stop.node != hop.to).then(|| {
        violation(
            "P5020",
            format!("{f}.node"),
            format!("stop at {} but the hop ends at {}", stop.node, hop.to),
        )
    })
}

/// P5020: the stop's node is a node of the network; that node.
fn p5020_stop_node_is_in_the_network<'a>(
    raw: &Raw<'a>,
    f: &str,
    stop: &Stop,
) -> Result<&'a Node, Violation> {
    match raw.index.get(stop.node.as_str()) {
        Some(&i) => Ok(&raw.network.nodes[i]),
        None => Err(violation(
            "P5020",
            format!("{f}.node"),
            format!("`{}` is not a node of the network", stop.node),
        )),
    }
}

/// P5021: the stop's node has pads, as many as the stop says.
fn p5021_pads_are_the_nodes(f: &str, stop: &Stop, node: &Node) -> Option<Violation> {
    (node.pads == 0 || stop.pads != node.pads).then(|| {
        violation(
            "P5021",
            format!("{f}.pads"),
            format!(
                "node {} has {} pad(s), the stop says {}",
                node.id, node.pads, stop.pads
            ),
        )
    })
}

/// Pad charging rate at `node`, mAh/min: the node's own, else the profile's.
fn pad_rate_mah_per_min(raw: &Raw, node: &Node) -> f64 {
    node.pad_charge_rate_mah_per_min
        .unwrap_or(raw.profile.pads.charge_rate_mah_per_min)
}

/// Every drone's charge time at `node`, `ct_d = (C_d - b_d) / q_v`, min, from the hop's arrival
/// batteries; `None` when they are not one per drone.
fn charge_times_min(raw: &Raw, hop: &Hop, node: &Node) -> Option<Vec<f64>> {
    if hop.arrival_battery_mah.len() != raw.swarm.drones.len() {
        return None;
    }
    let rate = pad_rate_mah_per_min(raw, node);
    Some(
        raw.swarm
            .drones
            .iter()
            .zip(&hop.arrival_battery_mah)
            .map(|(d, &b)| (d.capacity_mah - b).max(0.0) / rate)
            .collect(),
    )
}

/// P5022: the charge times are `(C_d - b_d) / q_v` of the arrival batteries `b_d` (`ct` the
/// re-computed ones, `None` when the arrival batteries are not one per drone).
fn p5022_charge_times_follow_the_arrival(
    raw: &Raw,
    f: &str,
    hop: &Hop,
    stop: &Stop,
    node: &Node,
    ct: Option<&[f64]>,
) -> Option<Violation> {
    let n = raw.swarm.drones.len();
    let Some(ct) = ct else {
        return Some(violation(
            "P5022",
            format!("{f}.charge_times_min"),
            format!(
                "{} arrival batteries for {n} drones: charge times undefined",
                hop.arrival_battery_mah.len()
            ),
        ));
    };
    let same = stop.charge_times_min.len() == n
        && stop
            .charge_times_min
            .iter()
            .zip(ct)
            .all(|(&a, &b)| close(a, b));
    (!same).then(|| {
        violation(
            "P5022",
            format!("{f}.charge_times_min"),
            format!(
                "reported {:?} min, (capacity - arrival) / {} gives {ct:?} min",
                stop.charge_times_min,
                pad_rate_mah_per_min(raw, node)
            ),
        )
    })
}

/// P5023: the assignment uses at most the node's pads.
fn p5023_pads_used_exist(f: &str, stop: &Stop, node: &Node) -> Option<Violation> {
    (stop.assignment.len() > node.pads as usize).then(|| {
        violation(
            "P5023",
            format!("{f}.assignment"),
            format!(
                "{} pads used, the node has {}",
                stop.assignment.len(),
                node.pads
            ),
        )
    })
}

/// P5024: every drone charged is a drone of the swarm.
fn p5024_assigned_drones_exist(f: &str, stop: &Stop, n: usize) -> Vec<Violation> {
    stop.assignment
        .iter()
        .flatten()
        .filter(|&&d| d >= n)
        .map(|d| {
            violation(
                "P5024",
                format!("{f}.assignment"),
                format!("drone {d} does not exist (swarm of {n})"),
            )
        })
        .collect()
}

/// P5025: every drone is charged exactly once.
fn p5025_assignment_is_a_partition(f: &str, stop: &Stop, n: usize) -> Option<Violation> {
    let mut seen = vec![0usize; n];
    for &d in stop.assignment.iter().flatten().filter(|&&d| d < n) {
        seen[d] += 1;
    }
    let d = seen.iter().position(|&c| c != 1)?;
    Some(violation(
        "P5025",
        format!("{f}.assignment"),
        format!(
            "drone {d} charged {} time(s): not a partition of the drones",
            seen[d]
        ),
    ))
}

/// P5026: `nt` is the assignment's makespan: the longest sum of charge times on one pad.
fn p5026_nt_is_the_makespan(f: &str, stop: &Stop, ct: &[f64]) -> Option<Violation> {
    let n = ct.len();
    let makespan = stop
        .assignment
        .iter()
        .map(|pad| pad.iter().filter(|&&d| d < n).map(|&d| ct[d]).sum::<f64>())
        .fold(0.0, f64::max);
    (!close(makespan, stop.nt_min)).then(|| {
        violation(
            "P5026",
            format!("{f}.nt_min"),
            format!(
                "nt {} min, but the assignment's makespan is {makespan} min",
                stop.nt_min
            ),
        )
    })
}

/// P5028: `nt` is the optimal makespan, found by exhaustive search (small swarms only, stops
/// labelled optimal: a node limit may leave a feasible incumbent).
fn p5028_nt_is_optimal(f: &str, stop: &Stop, ct: &[f64], pads: usize) -> Option<Violation> {
    let best = optimal_makespan_min(ct, pads);
    (stop.nt_min > best + super::INTEGRATION_TOLERANCE * (1.0 + best)).then(|| {
        violation(
            "P5028",
            format!("{f}.nt_min"),
            format!(
                "nt {} min, but an assignment with makespan {best} min exists",
                stop.nt_min
            ),
        )
    })
}

/// P5027: `nt >= max(max ct, sum ct / k_v)`.
fn p5027_nt_above_the_lower_bound(
    f: &str,
    stop: &Stop,
    ct: &[f64],
    pads: u32,
) -> Option<Violation> {
    let max_ct = ct.iter().copied().fold(0.0, f64::max);
    let bound = max_ct.max(ct.iter().sum::<f64>() / pads as f64);
    (stop.nt_min < bound - super::INTEGRATION_TOLERANCE * (1.0 + bound)).then(|| {
        violation(
            "P5027",
            format!("{f}.nt_min"),
            format!(
                "nt {} min below the lower bound max(max ct, sum ct / pads) = {bound} min",
                stop.nt_min
            ),
        )
    })
}

/// The optimal makespan of `ct` on `pads` identical pads by exhaustive search (0 without drones):
/// each drone in turn goes on a pad already used or on the first empty one (pads are
/// interchangeable), cut when the partial makespan reaches the best found.
///
/// # Complexity
/// At most `pads^n / pads!` assignments for `n` drones: meant for at most
/// [`OPTIMALITY_CHECK_DRONES`] drones.
pub fn optimal_makespan_min(ct: &[f64], pads: usize) -> f64 {
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
