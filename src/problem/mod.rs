//! Input types: skyway network, parameter profile, delivery requests. Serde types with
//! `deny_unknown_fields`, a `schema_version`, and units in every field name. Nothing here knows about
//! solvers.
//! User guide: "Input files and profiles" (`docs/src/inputs.md`).

pub mod fingerprint;
mod graph;
pub mod inputs;
mod instance;
pub mod io;
mod network;
pub mod pcmax_file;
mod profile;
mod request;
pub mod shipped;
mod swarm;
pub mod validate;
mod wind;

pub use graph::{heading_deg, read_network, SkywayEdge, SkywayGraph, MAX_CACHED_DISTANCE_NODES};
pub use instance::Instance;
pub use network::{Edge, Network, Node};
pub use profile::{
    Candidates, DroneParams, EnergyParams, FailureModel, FailureParams, FailureTerms,
    FailureWeights, FormationParams, PadParams, PbRequest, Profile, Readings, RedundancyLevel,
    RedundancyParams, RedundancyRow, SharingParams, SupportParams,
};
pub use request::{Request, RequestSet, COMMAND_LINE_REQUEST_ID, PYTHON_REQUEST_ID};
pub use swarm::{Drone, FormationKind, Role, Swarm};
pub use wind::Wind;

/// Most delivery drones (packages) in one request: the exact node time at a stop, an NP-hard
/// P||Cmax over every drone of the swarm, is fast far beyond the paper's 2-8 packages but takes
/// minutes on swarms of 45 drones (rule E3304).
pub const MAX_DELIVERY_DRONES: usize = 32;

/// Most support drones in one swarm, from the redundancy table (E2023) or `--support` (E0006).
pub const MAX_SUPPORT_DRONES: usize = 32;

/// Most drones in a swarm a profile may rank formations with (`formation.select_swarm_size`).
pub const MAX_SWARM_DRONES: usize = MAX_DELIVERY_DRONES + MAX_SUPPORT_DRONES;

/// Version of the JSON/TOML schemas written and read by this build.
pub const SCHEMA_VERSION: u32 = 1;
