//! Pre-composition (paper 5.1): choose the formation from the averaged wind
//! ([`formation_select`]), the number of support drones from Eq. 2 and the redundancy table
//! ([`support_count()`]), and the initial slot of every drone ([`positioning`]). See
//! models/precompose.md.

pub mod formation_select;
pub mod positioning;
pub mod support_count;

pub use formation_select::{averaged_wind, select_formation, select_formation_for_heading};
pub use positioning::{build_swarm, build_swarm_in_wind, slot_ranking};
pub use support_count::{failure_terms, support_count, SupportDecision};

use crate::formation::FormationKind;
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

/// What a drone does in the swarm: one type shared with the in-flight sharing model.
pub use crate::eaas::Role;

/// One drone of a swarm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drone {
    /// Id: delivery drones `0..n` in the request's package order, support drones `n..n+m`. Equals the
    /// drone's index in [`Swarm::drones`].
    pub id: usize,
    /// Delivery or support.
    pub role: Role,
    /// What it carries, kg: the package for a delivery drone, the extra batteries for a support drone.
    pub payload_kg: f64,
    /// Battery capacity, mAh: one battery for a delivery drone, `1 + extra_batteries` for a support
    /// drone.
    pub capacity_mah: f64,
}

/// A swarm in its formation.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Swarm {
    /// The formation, fixed for the whole trip.
    pub formation: FormationKind,
    /// The drones, indexed by id.
    pub drones: Vec<Drone>,
    /// Slot positions, body frame (x forward, y right), m. Serialised as `[[x, y], ...]`.
    #[serde(serialize_with = "serialize_points")]
    pub slots_m: Vec<Vector2<f64>>,
    /// `initial_slot[id]` = slot index of drone `id` at take-off.
    pub initial_slot: Vec<usize>,
}

impl Swarm {
    /// Number of delivery drones.
    pub fn delivery_count(&self) -> usize {
        self.drones
            .iter()
            .filter(|d| d.role == Role::Delivery)
            .count()
    }

    /// Number of support drones.
    pub fn support_count(&self) -> usize {
        self.drones
            .iter()
            .filter(|d| d.role == Role::Support)
            .count()
    }
}

/// Where support drones start (paper 5.1, "Support Drones Positioning").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Positioning {
    /// Support drones in the worst slots; delivery drones by payload, heaviest in the best slot.
    LocationAware,
    /// Support drones in the best slots; then delivery drones by payload, heaviest first.
    EnergyAware,
}

fn serialize_points<S: serde::Serializer>(
    points: &[Vector2<f64>],
    serializer: S,
) -> Result<S::Ok, S::Error> {
    use serde::ser::SerializeSeq;
    let mut seq = serializer.serialize_seq(Some(points.len()))?;
    for p in points {
        seq.serialize_element(&[p.x, p.y])?;
    }
    seq.end()
}
