//! Skyway network: rooftop nodes (some with recharging pads) joined by edges (line-of-sight segments).

use serde::{Deserialize, Serialize};

/// A skyway network, read from JSON.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Network {
    /// Schema version, must equal [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Optional human-readable name.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Rooftop nodes.
    pub nodes: Vec<Node>,
    /// Edges (line-of-sight segments between rooftops); each can be flown both ways. Files written
    /// before the field was named `edges` call it `segments`, which is still read.
    #[serde(alias = "segments")]
    pub edges: Vec<Edge>,
}

/// A rooftop node.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Node {
    /// Unique id, referenced by edges and requests.
    pub id: String,
    /// Easting in metres.
    pub x_m: f64,
    /// Northing in metres.
    pub y_m: f64,
    /// Number of recharging pads (0 = no recharging here).
    pub pads: u32,
    /// Charge rate of this node's pads; the profile's `pads.charge_rate_mah_per_min` when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pad_charge_rate_mah_per_min: Option<f64>,
}

/// An edge between two nodes, flown in either direction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Edge {
    /// Id of one end.
    pub from: String,
    /// Id of the other end.
    pub to: String,
    /// Length; the Euclidean distance between the ends when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub distance_m: Option<f64>,
    /// Wind speed on the edge, m/s; must be below 13.8 m/s (safe flight limit).
    pub wind_speed_mps: f64,
    /// Direction the wind blows FROM, degrees clockwise from north (meteorological convention).
    pub wind_from_deg: f64,
}
