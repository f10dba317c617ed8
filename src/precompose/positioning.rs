//! Initial positions of the drones (paper 5.1, "Support Drones Positioning"). See
//! models/precompose.md.
//!
//! Slots are ranked best to worst by their position factor `F` (lower is better); equal factors
//! keep slot order. Delivery drones are ordered by payload, heaviest first (equal payloads by id).
//! * location-aware: delivery drones take the best slots in that order, support drones the rest
//!   (the worst slots), by id.
//! * energy-aware: support drones take the best slots by id, then the delivery drones in that order.

use super::Positioning;
use crate::energy::slot_factors;
use crate::formation::slots_m;
use crate::problem::FormationKind;
use crate::problem::Profile;
use crate::problem::Wind;
use crate::problem::{Drone, Role, Swarm};
use nalgebra::Vector2;

/// Slot indices from best to worst position factor for a leg towards `heading_deg` under `wind`.
///
/// # Complexity
/// O(n^2) (the wake model) + O(n log n).
pub fn slot_ranking(
    profile: &Profile,
    slots: &[Vector2<f64>],
    heading_deg: f64,
    wind: &Wind,
) -> Vec<usize> {
    let f = slot_factors(profile, slots, heading_deg, wind);
    let mut order: Vec<usize> = (0..slots.len()).collect();
    // Stable: equal factors (within 1e-12) keep slot order.
    order.sort_by(|&a, &b| {
        if (f[a] - f[b]).abs() <= 1e-12 {
            std::cmp::Ordering::Equal
        } else {
            f[a].total_cmp(&f[b])
        }
    });
    order
}

/// Builds the swarm with positions ranked for the reference flow: the air meeting the swarm head
/// on (still air, or any head wind), the case in which the paper states its positioning findings.
/// Use [`build_swarm_in_wind`] to rank the slots for a given heading and wind instead.
///
/// # Arguments
/// * `profile` - drone, support and formation constants.
/// * `formation` - the formation (from [`super::select_formation`] or the user).
/// * `packages_kg` - one package per delivery drone, in request order (ids `0..n`).
/// * `support` - number of support drones (ids `n..n+support`): the
///   [`super::SupportDecision::count`] or a `--support N` override.
/// * `positioning` - where support drones start.
///
/// # Returns
/// The swarm with `initial_slot[id]` filled.
///
/// # Complexity
/// O(n^2) for n drones.
pub fn build_swarm(
    profile: &Profile,
    formation: FormationKind,
    packages_kg: &[f64],
    support: usize,
    positioning: Positioning,
) -> Swarm {
    build_swarm_in_wind(
        profile,
        formation,
        packages_kg,
        support,
        positioning,
        0.0,
        &Wind::CALM,
    )
}

/// As [`build_swarm`], with the slots ranked for a leg towards `heading_deg` under `wind`.
///
/// # Complexity
/// O(n^2) for n drones.
pub fn build_swarm_in_wind(
    profile: &Profile,
    formation: FormationKind,
    packages_kg: &[f64],
    support: usize,
    positioning: Positioning,
    heading_deg: f64,
    wind: &Wind,
) -> Swarm {
    let n = packages_kg.len();
    let total = n + support;
    let mut drones: Vec<Drone> = packages_kg
        .iter()
        .enumerate()
        .map(|(id, &p)| Drone {
            id,
            role: Role::Delivery,
            payload_kg: p,
            capacity_mah: profile.drone.battery_mah,
        })
        .collect();
    drones.extend((n..total).map(|id| Drone {
        id,
        role: Role::Support,
        payload_kg: profile.support_payload_kg(),
        capacity_mah: profile.support_capacity_mah(),
    }));
    let slots = slots_m(formation, total, profile.formation.spacing_m);
    let ranking = slot_ranking(profile, &slots, heading_deg, wind);

    let mut delivery: Vec<usize> = (0..n).collect();
    delivery.sort_by(|&a, &b| packages_kg[b].total_cmp(&packages_kg[a]).then(a.cmp(&b)));
    let supports: Vec<usize> = (n..total).collect();
    let order: Vec<usize> = match positioning {
        Positioning::LocationAware => delivery.into_iter().chain(supports).collect(),
        Positioning::EnergyAware => supports.into_iter().chain(delivery).collect(),
    };
    let mut initial_slot = vec![0; total];
    for (rank, id) in order.into_iter().enumerate() {
        initial_slot[id] = ranking[rank];
    }
    Swarm {
        formation,
        drones,
        slots_m: slots,
        initial_slot,
    }
}
