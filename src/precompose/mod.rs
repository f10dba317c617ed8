//! Pre-composition (paper 5.1): choose the formation from the averaged wind
//! ([`select_formation`]), the number of support drones from Eq. 2 and the redundancy table
//! ([`support_count()`]), and the initial slot of every drone ([`build_swarm`]). See
//! models/precompose.md.
//! User guide: "Pre-composition" (`docs/src/models/precompose.md`).

mod formation_select;
mod positioning;
mod support_count;

pub use formation_select::{averaged_wind, select_formation, select_formation_for_heading};
pub use positioning::{build_swarm, build_swarm_in_wind, slot_ranking};
pub use support_count::{failure_terms, support_count, SupportDecision};

use serde::{Deserialize, Serialize};

/// Where support drones start (paper 5.1, "Support Drones Positioning").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum Positioning {
    /// Support drones in the worst slots; delivery drones by payload, heaviest in the best slot.
    LocationAware,
    /// Support drones in the best slots; then delivery drones by payload, heaviest first.
    EnergyAware,
}

display_as_value_name!(Positioning);
