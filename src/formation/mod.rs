//! Swarm formations (paper 5.1, after Alkouz et al. 2020): slot geometry ([`shapes`]) and the
//! wake/shielding model that gives each slot its position factor ([`wake`]). See models/formation.md.

pub mod shapes;
pub mod wake;

pub use crate::energy::Wind;
pub use shapes::slots_m;
pub use wake::position_factors;

use serde::{Deserialize, Serialize};

/// The five formations of the paper (Fig. 5).
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Hash,
    PartialOrd,
    Ord,
    Serialize,
    Deserialize,
    clap::ValueEnum,
)]
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

impl FormationKind {
    /// Every formation in a fixed order (also the tie-break order of formation selection).
    pub const ALL: [FormationKind; 5] = [
        FormationKind::Column,
        FormationKind::Front,
        FormationKind::Echelon,
        FormationKind::Vee,
        FormationKind::Diamond,
    ];

    /// The formation's name as used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            FormationKind::Column => "column",
            FormationKind::Front => "front",
            FormationKind::Echelon => "echelon",
            FormationKind::Vee => "vee",
            FormationKind::Diamond => "diamond",
        }
    }
}
