//! Swarm formations (paper 5.1, after Alkouz et al. 2020): slot geometry ([`slots_m`]) and the
//! wake/shielding model that gives each slot its position factor ([`position_factors`]). See models/formation.md.
//! User guide: "Formation" (`docs/src/models/formation.md`).

mod shapes;
mod wake;

pub use shapes::slots_m;
pub use wake::{pair_gain, position_factors};
