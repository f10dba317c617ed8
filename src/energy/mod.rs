//! Energy model: the consumption rate of every drone of a swarm, mAh/min. See models/energy.md.
//! User guide: "Energy" (`docs/src/models/energy.md`).
//!
//! ```text
//! rate(d, slot) = r0 * P(m_d) * W(v_air) * F(slot)
//! r0     = battery_mah / endurance_min                      base rate, unloaded, still air, cruise
//! P(p)   = ((m0 + p) / m0)^e_m                              payload factor, m0 = empty + battery mass
//! W(v_a) = (1 - c_par) + c_par * (|v_air| / v)^3            wind factor from the air-relative speed
//! F      = wake/shielding position factor of the slot       (crate::formation::wake)
//! ```
//!
//! A support drone's payload is its extra batteries. `v_air` is the air's velocity relative to the
//! swarm: the wind's velocity minus the swarm's ground velocity (`v` along the heading).

use crate::formation::position_factors;
use crate::problem::{Profile, Swarm, Wind};
use nalgebra::Vector2;

/// Base rate `r0`: an unloaded drone with its own battery at cruise in still air, mAh/min.
pub fn base_rate_mah_per_min(profile: &Profile) -> f64 {
    profile.base_rate_mah_per_min()
}

/// Payload factor `P(p) = ((m0 + p) / m0)^e_m`; `m0` is the drone's mass with its own battery.
pub fn payload_factor(profile: &Profile, payload_kg: f64) -> f64 {
    let m0 = profile.base_mass_kg();
    ((m0 + payload_kg.max(0.0)) / m0).powf(profile.energy.payload_exponent)
}

/// The air's velocity relative to the swarm in the body frame (x along the heading, y to the right),
/// m/s, for a leg flown towards `heading_deg` (clockwise from north) at the profile's cruise speed.
///
/// A wind from the heading (head wind) gives `(-(v + w), 0)`; a wind from the right `(-v, -w)`.
pub fn air_velocity_body_mps(profile: &Profile, heading_deg: f64, wind: &Wind) -> Vector2<f64> {
    let rel = (wind.from_deg - heading_deg).to_radians();
    let w = wind.speed_mps;
    // The wind comes from bearing `rel` in the body frame, so the air moves towards `rel + 180`.
    let wind_body = Vector2::new(-w * rel.cos(), -w * rel.sin());
    wind_body - Vector2::new(profile.speed_mps(), 0.0)
}

/// Wind factor `W = (1 - c_par) + c_par * (|v_air| / v)^3` (parasitic drag power ~ air speed cubed;
/// the rest of the power, rotor induced and profile power, is taken as independent of the wind).
/// It is 1 in still air, above 1 in a head or side wind, below 1 in a tail wind, and never below
/// `1 - c_par > 0`.
pub fn wind_factor(profile: &Profile, heading_deg: f64, wind: &Wind) -> f64 {
    let c = profile.energy.parasitic_fraction;
    let ratio = air_velocity_body_mps(profile, heading_deg, wind).norm() / profile.speed_mps();
    (1.0 - c) + c * ratio.powi(3)
}

/// Position factor `F` of every slot of `slots_m` for a leg towards `heading_deg` under `wind`.
pub fn slot_factors(
    profile: &Profile,
    slots_m: &[Vector2<f64>],
    heading_deg: f64,
    wind: &Wind,
) -> Vec<f64> {
    let flow = air_velocity_body_mps(profile, heading_deg, wind);
    position_factors(slots_m, flow, &profile.formation)
}

/// Consumption rate of one drone with `payload_kg` in a slot of factor `slot_factor`, under a wind
/// factor `wind_factor`, mAh/min.
pub fn rate_mah_per_min(
    profile: &Profile,
    payload_kg: f64,
    wind_factor: f64,
    slot_factor: f64,
) -> f64 {
    profile.base_rate_mah_per_min()
        * payload_factor(profile, payload_kg)
        * wind_factor
        * slot_factor
}

/// Consumption rate of every drone in every slot: `rate[drone][slot]`, mAh/min.
///
/// # Arguments
/// * `profile` - energy and formation constants.
/// * `swarm` - its drones (by id) and slots.
/// * `heading_deg` - direction flown, degrees clockwise from north.
/// * `wind` - the leg's wind (`from_deg` meteorological: a wind from the heading is a head wind).
///
/// # Returns
/// A `drones x slots` matrix; `rate[d][s]` is what drone `d` would consume if it flew in slot `s`
/// (the slot factors depend on the geometry only, so every pairing is meaningful).
///
/// # Complexity
/// O(n^2) for n slots (the wake model), plus O(n^2) to fill the matrix.
pub fn rate_matrix_mah_per_min(
    profile: &Profile,
    swarm: &Swarm,
    heading_deg: f64,
    wind: &Wind,
) -> Vec<Vec<f64>> {
    let wf = wind_factor(profile, heading_deg, wind);
    let sf = slot_factors(profile, &swarm.slots_m, heading_deg, wind);
    rate_matrix_from_factors(&payload_rates_mah_per_min(profile, swarm), wf, &sf)
}

/// Every drone's still-air rate in a slot of factor 1, `base rate x payload factor`, mAh/min:
/// the part of [`rate_matrix_mah_per_min`] that does not depend on the leg.
pub fn payload_rates_mah_per_min(profile: &Profile, swarm: &Swarm) -> Vec<f64> {
    swarm
        .drones
        .iter()
        .map(|d| profile.base_rate_mah_per_min() * payload_factor(profile, d.payload_kg))
        .collect()
}

/// [`rate_matrix_mah_per_min`] from its parts: the drones' [`payload_rates_mah_per_min`], the
/// leg's [`wind_factor`] and its [`slot_factors`].
pub fn rate_matrix_from_factors(
    payload_rates_mah_per_min: &[f64],
    wind_factor: f64,
    slot_factors: &[f64],
) -> Vec<Vec<f64>> {
    payload_rates_mah_per_min
        .iter()
        .map(|&p| {
            slot_factors
                .iter()
                .map(|&f| rate_from_factors(p, wind_factor, f))
                .collect()
        })
        .collect()
}

/// One entry of [`rate_matrix_from_factors`]: `(payload rate x wind factor) x slot factor`,
/// mAh/min, multiplied in that order (every caller gets the same number to the last digit).
pub fn rate_from_factors(payload_rate_mah_per_min: f64, wind_factor: f64, slot_factor: f64) -> f64 {
    payload_rate_mah_per_min * wind_factor * slot_factor
}

/// Consumption rate of every drone (by id) in its initial slot, mAh/min. A swarm whose
/// `initial_slot` does not name a slot for a drone (not one built by
/// [`crate::precompose::build_swarm`]) gets NaN for that drone.
///
/// # Complexity
/// O(n^2), as [`rate_matrix_mah_per_min`].
pub fn consumption_rates_mah_per_min(
    profile: &Profile,
    swarm: &Swarm,
    heading_deg: f64,
    wind: &Wind,
) -> Vec<f64> {
    let m = rate_matrix_mah_per_min(profile, swarm, heading_deg, wind);
    swarm
        .drones
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let slot = swarm.initial_slot.get(d.id).copied().unwrap_or(i);
            m[i].get(slot).copied().unwrap_or(f64::NAN)
        })
        .collect()
}
