//! Parameter profile (TOML): every constant of the models, each documented with its source in the
//! shipped profile files under `instances/profiles/`.

use serde::{Deserialize, Serialize};

/// A parameter profile.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Schema version, must equal [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Profile name, such as `paper`.
    pub name: String,
    /// The drone model every drone of the swarm uses.
    pub drone: DroneParams,
    /// What makes a support drone.
    pub support: SupportParams,
    /// In-flight energy sharing (EaaS).
    pub sharing: SharingParams,
    /// Recharging pads at nodes.
    pub pads: PadParams,
}

/// Drone model (paper Table 3: DJI Phantom 3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DroneParams {
    /// Capacity of one battery, mAh.
    pub battery_mah: f64,
    /// Battery voltage, V.
    pub voltage_v: f64,
    /// Ground speed of the swarm, km/h.
    pub speed_kmh: f64,
    /// Mass of the drone without battery and payload, kg.
    pub empty_mass_kg: f64,
    /// Mass of one battery, kg.
    pub battery_mass_kg: f64,
    /// Heaviest package one drone may carry, kg.
    pub max_payload_kg: f64,
}

/// Support drones: same airframe, extra batteries as payload.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportParams {
    /// Extra batteries carried (3 in the paper: capacity 4x a delivery drone's).
    pub extra_batteries: u32,
}

/// In-flight energy sharing parameters (paper 5.2.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SharingParams {
    /// Transfer rate `rho` from a support drone to one consumer, mAh/min.
    pub rate_mah_per_min: f64,
    /// Largest support-to-consumer distance at which energy can be transferred, m.
    pub range_m: f64,
    /// Fairness-based round size `lambda`, mAh.
    pub lambda_mah: f64,
    /// Priority-based request threshold `gamma`: a delivery drone requests energy when its battery
    /// falls below this, mAh.
    pub gamma_mah: f64,
    /// Support reserve `delta`: a support drone stops sharing at this battery level, mAh.
    pub delta_mah: f64,
}

/// Recharging pads at nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PadParams {
    /// Default charge rate of one pad, mAh/min (a node may override it).
    pub charge_rate_mah_per_min: f64,
}
