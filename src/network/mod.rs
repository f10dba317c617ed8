//! Routes over the skyway network: legs, routes and shortest paths over a
//! [`SkywayGraph`](crate::problem::SkywayGraph), whose edge cost is the edge length `distance_m`,
//! and all-pairs shortest paths on any edge costs ([`floyd_warshall`]).
//! User guide: "Network" (`docs/src/models/network.md`) and "Network, swarm, hop, stop, route"
//! (`docs/src/concepts.md`).
//!
//! Conventions: `x_m` is easting and `y_m` northing; a heading is the direction flown, degrees
//! clockwise from north in `[0, 360)`; `wind_from_deg` is where the wind blows from (meteorological).

pub mod floyd_warshall;
mod paths;

pub use paths::{Leg, Route, ShortestPathsTo};
