//! Re-verifies a hop file (`swarmplan eaas --write-hop`, a [`HopFile`]) against the instance and
//! request set it names: every number of its hop problem is rebuilt from the raw network, the
//! profile and the request, without the planner, and compared (relative tolerance `1e-9`), one
//! violation per number with the stated and rebuilt values:
//!
//! * P5601: the request `request_id` is in the request set;
//! * P5602: the path's nodes exist and each consecutive pair is an edge;
//! * P5603: each leg lasts its edge's length over the ground speed;
//! * P5604: each leg's rate matrix is the energy model's for the swarm (the request's packages,
//!   the profile's support payload) on the edge's heading and wind;
//! * P5605: drones: delivery drones first, one per package; each has the profile's capacity and
//!   departs with a full battery (every hop of a plan does);
//! * P5606: the slots are a formation's at the profile's spacing, the initial slots a
//!   permutation of them;
//! * P5607: the sharing constants (`rho`, range, `gamma`, `lambda`, `delta`) are the profile's;
//! * P5608: `end` holds the pads and pad rate of the end node (`null` when it has no pads).
//!
//! * P5609: with `plan` (the combination of the plan the hop was taken from), the request planned
//!   again with it has a hop `hop_index` along the file's path.
//!
//! Without `plan`, `hop_index` is the hop's place in a route the file does not record and is not
//! checked; the profile's name is a label. The fingerprint `made_on` is compared first, as for
//! plans (E6004, E6005).

use super::close;
use super::plan::{raw_leg, RawLeg};
use crate::eaas::hop_file::HopFile;
use crate::eaas::HopProblem;
use crate::energy;
use crate::error::Violation;
use crate::formation;
use crate::problem::io::json_name;
use crate::problem::{Drone, FormationKind, Network, Profile, Request, Role, Swarm};

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "write the hop again with `swarmplan eaas --request-id ID --hop N --write-hop FILE` on \
         the instance it comes from",
    )
}

/// Pushes a P-violation when `stated` is not `rebuilt`.
fn compare(out: &mut Vec<Violation>, code: &'static str, field: String, stated: f64, rebuilt: f64) {
    if !close(stated, rebuilt) {
        out.push(violation(
            code,
            field,
            format!("states {stated}, the instance gives {rebuilt}"),
        ));
    }
}

/// Checks a hop file against the raw instance and a request set.
///
/// # Returns
/// E6004 and E6005 alone when the file records another network or profile; else every broken
/// rule (codes `P5601`-`P5608`); empty when the file passes.
///
/// # Complexity
/// `O(N + E)` to index the network, then `O(L D S)` for `L` legs, `D` drones, `S` slots.
pub fn check_hop_file(
    network: &Network,
    profile: &Profile,
    requests: &[Request],
    file: &HopFile,
) -> Vec<Violation> {
    if let Some(made_on) = &file.made_on {
        let mismatch = super::report::fingerprint_mismatch(network, profile, made_on);
        if !mismatch.is_empty() {
            return mismatch;
        }
    }
    let mut out = Vec::new();
    if let Err(x) = check_hop(network, profile, requests, file, &mut out) {
        out.push(x);
    }
    out
}

/// The rules in order, each group on what the previous ones established; a violation after
/// which the rest cannot be checked (an unknown request, a broken path, wrong roles, slots of no
/// formation, another number of legs) is returned and ends the check.
fn check_hop(
    network: &Network,
    profile: &Profile,
    requests: &[Request],
    file: &HopFile,
    out: &mut Vec<Violation>,
) -> Result<(), Violation> {
    let request = request_of_the_file(requests, file)?;
    let legs = legs_of_the_path(network, &file.path)?;
    if let Some(plan) = &file.plan {
        if let Some(x) = hop_of_the_plan(network, profile, request, file, plan) {
            out.push(x);
        }
    }
    let hop = &file.hop;
    roles_of_the_drones(request, hop)?;
    compare_capacities(profile, hop, out);
    let formation = formation_of_the_slots(profile, hop)?;
    initial_slots_permutation(hop)?;
    let swarm = swarm_of_the_hop(profile, request, hop, formation);
    if hop.legs.len() != legs.len() {
        return Err(violation(
            "P5603",
            "hop.legs",
            format!("{} legs, the path has {} edges", hop.legs.len(), legs.len()),
        ));
    }
    compare_legs(profile, &swarm, hop, &legs, out);
    compare_sharing_constants(profile, hop, out);
    compare_end_pads(network, profile, file, out);
    Ok(())
}

/// P5601: the request the file names, from the request set.
fn request_of_the_file<'a>(
    requests: &'a [Request],
    file: &HopFile,
) -> Result<&'a Request, Violation> {
    requests
        .iter()
        .find(|r| r.id == file.request_id)
        .ok_or_else(|| {
            violation(
                "P5601",
                "request_id",
                format!(
                    "no request with id `{}` in the request file",
                    file.request_id
                ),
            )
        })
}

/// P5605: one delivery drone per package of the request first, then support drones.
fn roles_of_the_drones(request: &Request, hop: &HopProblem) -> Result<(), Violation> {
    let n = request.packages_kg.len();
    let roles_ok = hop.drones.iter().enumerate().all(|(d, s)| {
        let want = if d < n { Role::Delivery } else { Role::Support };
        s.role == want
    }) && hop.drones.len() >= n;
    if roles_ok {
        return Ok(());
    }
    Err(violation(
        "P5605",
        "hop.drones",
        format!(
            "roles {}: the request's {n} packages need {n} delivery drones first, then \
             support drones",
            json_name(&hop.drones.iter().map(|d| d.role).collect::<Vec<_>>())
        ),
    ))
}

/// P5605: every drone has the profile's capacity of its role and departs with it full.
fn compare_capacities(profile: &Profile, hop: &HopProblem, out: &mut Vec<Violation>) {
    for (d, s) in hop.drones.iter().enumerate() {
        let capacity = match s.role {
            Role::Delivery => profile.drone.battery_mah,
            Role::Support => profile.support_capacity_mah(),
        };
        let f = format!("hop.drones[{d}]");
        compare(
            out,
            "P5605",
            format!("{f}.capacity_mah"),
            s.capacity_mah,
            capacity,
        );
        compare(
            out,
            "P5605",
            format!("{f}.battery_mah"),
            s.battery_mah,
            capacity,
        );
    }
}

/// P5606: the formation whose slots at the profile's spacing are the file's.
fn formation_of_the_slots(profile: &Profile, hop: &HopProblem) -> Result<FormationKind, Violation> {
    let spacing_m = profile.formation.spacing_m;
    let count = hop.drones.len();
    let formation = FormationKind::ALL.into_iter().find(|&kind| {
        let want = formation::slots_m(kind, count, spacing_m);
        want.len() == hop.slots_m.len()
            && want
                .iter()
                .zip(&hop.slots_m)
                .all(|(a, b)| close(a.x, b.x) && close(a.y, b.y))
    });
    formation.ok_or_else(|| {
        violation(
            "P5606",
            "hop.slots_m",
            format!("not the slots of any formation of {count} drones at {spacing_m} m spacing"),
        )
    })
}

/// P5606: the initial slots are a permutation of the slots.
fn initial_slots_permutation(hop: &HopProblem) -> Result<(), Violation> {
    let count = hop.drones.len();
    let mut sorted = hop.initial_slot.clone();
    sorted.sort_unstable();
    if sorted == (0..count).collect::<Vec<_>>() {
        return Ok(());
    }
    Err(violation(
        "P5606",
        "hop.initial_slot",
        format!(
            "{:?} is not a permutation of the {count} slots",
            hop.initial_slot
        ),
    ))
}

/// The swarm the hop flies: its drones with the request's packages (the profile's support
/// payload for a support drone), in `formation` on the file's slots.
fn swarm_of_the_hop(
    profile: &Profile,
    request: &Request,
    hop: &HopProblem,
    formation: FormationKind,
) -> Swarm {
    let n = request.packages_kg.len();
    Swarm {
        formation,
        drones: hop
            .drones
            .iter()
            .enumerate()
            .map(|(id, s)| Drone {
                id,
                role: s.role,
                payload_kg: if id < n {
                    request.packages_kg[id]
                } else {
                    profile.support_payload_kg()
                },
                capacity_mah: s.capacity_mah,
            })
            .collect(),
        slots_m: hop.slots_m.clone(),
        initial_slot: hop.initial_slot.clone(),
    }
}

/// P5603, P5604: every leg's duration and rate matrix against its edge's.
fn compare_legs(
    profile: &Profile,
    swarm: &Swarm,
    hop: &HopProblem,
    legs: &[RawLeg],
    out: &mut Vec<Violation>,
) {
    let speed_m_per_min = profile.drone.speed_kmh * 1000.0 / 60.0;
    for (l, (stated, raw)) in hop.legs.iter().zip(legs).enumerate() {
        let f = format!("hop.legs[{l}]");
        compare(
            out,
            "P5603",
            format!("{f}.duration_min"),
            stated.duration_min,
            raw.distance_m / speed_m_per_min,
        );
        let rates = energy::rate_matrix_mah_per_min(profile, swarm, raw.heading_deg, &raw.wind);
        for (d, row) in rates.iter().enumerate() {
            for (q, &rate) in row.iter().enumerate() {
                let got = stated
                    .rate_mah_per_min
                    .get(d)
                    .and_then(|r| r.get(q))
                    .copied()
                    .unwrap_or(f64::NAN);
                compare(
                    out,
                    "P5604",
                    format!("{f}.rate_mah_per_min[{d}][{q}]"),
                    got,
                    rate,
                );
            }
        }
    }
}

/// P5607: the sharing constants are the profile's.
fn compare_sharing_constants(profile: &Profile, hop: &HopProblem, out: &mut Vec<Violation>) {
    let s = &profile.sharing;
    for (field, stated, given) in [
        ("rho_mah_per_min", hop.rho_mah_per_min, s.rate_mah_per_min),
        ("range_m", hop.range_m, s.range_m),
        ("gamma_mah", hop.gamma_mah, s.gamma_mah),
        ("lambda_mah", hop.lambda_mah, s.lambda_mah),
        ("delta_mah", hop.delta_mah, s.delta_mah),
    ] {
        compare(out, "P5607", format!("hop.{field}"), stated, given);
    }
}

/// P5608: `end` holds the end node's pads and pad rate, `null` when it has none.
fn compare_end_pads(
    network: &Network,
    profile: &Profile,
    file: &HopFile,
    out: &mut Vec<Violation>,
) {
    let end = network.nodes.iter().find(|x| x.id == file.to);
    let pads = end.map_or(0, |x| x.pads);
    match (&file.end, end) {
        (Some(e), Some(node)) if pads > 0 => {
            compare(out, "P5608", "end.pads".into(), e.pads as f64, pads as f64);
            let rate = node
                .pad_charge_rate_mah_per_min
                .unwrap_or(profile.pads.charge_rate_mah_per_min);
            compare(
                out,
                "P5608",
                "end.pad_rate_mah_per_min".into(),
                e.pad_rate_mah_per_min,
                rate,
            );
        }
        (None, _) if pads == 0 => {}
        (stated, _) => out.push(violation(
            "P5608",
            "end",
            format!(
                "states {}, the end node `{}` has {pads} pads",
                json_name(&stated),
                file.to
            ),
        )),
    }
}

/// P5602: the legs of `path`, rebuilt from the network.
fn legs_of_the_path(network: &Network, path: &[String]) -> Result<Vec<RawLeg>, Violation> {
    let index = super::node_index(network);
    let mut nodes = Vec::with_capacity(path.len());
    for (i, id) in path.iter().enumerate() {
        match index.get(id.as_str()) {
            Some(&k) => nodes.push(k),
            None => {
                return Err(violation(
                    "P5602",
                    format!("path[{i}]"),
                    format!("`{id}` is not a node of the network"),
                ))
            }
        }
    }
    nodes
        .windows(2)
        .enumerate()
        .map(|(i, w)| {
            raw_leg(network, w[0], w[1]).ok_or_else(|| {
                violation(
                    "P5602",
                    format!("path[{}]", i + 1),
                    format!("no edge joins {} and {}", path[i], path[i + 1]),
                )
            })
        })
        .collect()
}

/// P5609: the request planned again with the file's `plan` has hop `hop_index` along `path`.
fn hop_of_the_plan(
    network: &Network,
    profile: &Profile,
    request: &Request,
    file: &HopFile,
    plan: &crate::eaas::hop_file::HopPlan,
) -> Option<Violation> {
    let options = match crate::compose::PlanOptions::try_from(plan) {
        Ok(o) => o,
        Err(why) => return Some(violation("P5609", "plan.route", why)),
    };
    let graph = crate::problem::SkywayGraph::new(network).ok()?;
    let context = crate::compose::Context::new(network, &graph, profile);
    let report = match context.plan(request, &options) {
        Ok(r) => r,
        Err(e) => {
            return Some(violation(
                "P5609",
                "plan",
                format!("the request cannot be planned again with this combination: {e}"),
            ))
        }
    };
    let hops = &report.plan.hops;
    match hops.get(file.hop_index) {
        Some(hop) if hop.path == file.path => None,
        Some(hop) => Some(violation(
            "P5609",
            "hop_index",
            format!(
                "hop {} of the plan ({}/{}/{}) flies {}, the file's path is {}",
                file.hop_index,
                options.sharing,
                options.positioning,
                options.route,
                hop.path.join(" - "),
                file.path.join(" - ")
            ),
        )),
        None => Some(violation(
            "P5609",
            "hop_index",
            format!(
                "the plan ({}/{}/{}) has {} hop(s), not a hop {}",
                options.sharing,
                options.positioning,
                options.route,
                hops.len(),
                file.hop_index
            ),
        )),
    }
}
