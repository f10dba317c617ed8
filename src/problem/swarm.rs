//! The swarm: its drones, their roles and the formation it flies.

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

/// Role of a drone in the swarm.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// Carries one package; may receive energy.
    Delivery,
    /// Carries extra batteries; may give energy, never moves in the formation.
    Support,
}

/// The five formations of the paper (Fig. 5).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum FormationKind {
    /// One drone behind the other.
    Column,
    /// Abreast, side by side.
    Front,
    /// A diagonal line back to the right.
    Echelon,
    /// A leader with two diagonal arms back to the left and right.
    Vee,
    /// A 45-degree lattice, compact in both directions.
    Diamond,
}

display_as_value_name!(FormationKind);

impl FormationKind {
    /// Every formation in a fixed order (also the tie-break order of formation selection).
    pub const ALL: [FormationKind; 5] = [
        FormationKind::Column,
        FormationKind::Front,
        FormationKind::Echelon,
        FormationKind::Vee,
        FormationKind::Diamond,
    ];
}

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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Swarm {
    /// The formation, fixed for the whole trip.
    pub formation: FormationKind,
    /// The drones, indexed by id.
    pub drones: Vec<Drone>,
    /// Slot positions, body frame (x forward, y right), m. Serialised as `[[x, y], ...]`.
    #[serde(
        serialize_with = "serialize_points",
        deserialize_with = "deserialize_points"
    )]
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

fn deserialize_points<'de, D: serde::Deserializer<'de>>(
    deserializer: D,
) -> Result<Vec<Vector2<f64>>, D::Error> {
    let points: Vec<[f64; 2]> = Deserialize::deserialize(deserializer)?;
    Ok(points
        .into_iter()
        .map(|[x, y]| Vector2::new(x, y))
        .collect())
}
