//! Wind over an edge of the network.

use serde::{Deserialize, Serialize};

/// Wind: speed and the direction it blows FROM, degrees clockwise from north (meteorological).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Wind {
    /// Wind speed, m/s.
    pub speed_mps: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    pub from_deg: f64,
}

impl Wind {
    /// No wind.
    pub const CALM: Wind = Wind {
        speed_mps: 0.0,
        from_deg: 0.0,
    };
}
