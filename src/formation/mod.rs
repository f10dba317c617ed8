//! Swarm formations (paper 5.1, after Alkouz et al. 2020): slot geometry ([`shapes`]) and the
//! wake/shielding model that gives each slot its position factor ([`wake`]). See models/formation.md.
//! User guide: "Formation" (`docs/src/models/formation.md`).

pub mod shapes;
pub mod wake;

pub use shapes::slots_m;
pub use wake::position_factors;
