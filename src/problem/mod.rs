//! Input types: skyway network, parameter profile, delivery requests. Serde types with
//! `deny_unknown_fields`, a `schema_version`, and units in every field name. Nothing here knows about
//! solvers.

pub mod io;
pub mod network;
pub mod profile;
pub mod request;
pub mod validate;

pub use network::{Network, Node, Segment};
pub use profile::Profile;
pub use request::{Request, RequestSet};

/// Version of the JSON/TOML schemas written and read by this build.
pub const SCHEMA_VERSION: u32 = 1;
