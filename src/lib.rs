//! # swarmplan
//!
//! An optimization-backed planner for swarm-based drone delivery with in-flight energy sharing,
//! after Alkouz, Abusafia, Lakhdari and Bouguettaya, "In-Flight Energy-Driven Composition of Drone
//! Swarm Services".
//!
//! A swarm of delivery drones (one package each) and support drones (extra batteries) flies a fixed
//! formation over a skyway network of rooftops. The delivery time of a request is
//!
//! ```text
//! dt = sum over flown hops of tt  +  sum over recharging stops of nt
//! ```
//!
//! where `tt` is a hop's travel time (a hop is a flight between two stops over one or more edges) and `nt` the node time: the makespan of charging every drone
//! to full on the node's `k` pads (identical parallel machines, P||Cmax). On a hop, support drones
//! share energy with delivery drones in flight at rate `rho` (mAh/min), one consumer at a time.
//!
//! Layout: [`problem`] holds the input types and their validation and knows nothing of solvers;
//! [`solver`] the backend choice and solve status shared by every exact method. Each model the code
//! builds is written up in `models/` under the name of the module that builds it.
//!
//! The user guide (`docs/`, an mdBook: `mdbook serve docs`) gives the concepts, every command
//! and output, and the write-ups of `models/` in reading order; each public module's doc names
//! its chapter.
// Lints are set in Cargo.toml's `[lints]` table (for every target); the library also forbids
// unsafe code outright and states its rule for the public API here.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

/// `Display` for choice enums: the value's serde name (kebab-case), which is also the name the
/// command line's clap derive gives it (`tests/choice_names.rs` checks that the two agree), so the
/// names of methods, policies and backends have one source and no hand-written table.
macro_rules! display_as_value_name {
    ($($t:ty),+ $(,)?) => {$(
        impl std::fmt::Display for $t {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.pad(&crate::choice_name(self))
            }
        }
    )+};
}

/// The serde name of a unit variant of a choice enum (empty for anything else).
fn choice_name<T: serde::Serialize>(value: &T) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(name)) => name,
        _ => String::new(),
    }
}

pub mod bench;
pub mod check;
#[cfg(feature = "cli")]
pub mod cli;
pub mod compose;
pub mod eaas;
pub mod energy;
pub mod error;
pub mod evaluate;
pub mod experiment;
pub mod formation;
pub mod generate;
pub mod human;
pub mod network;
pub mod node_time;
pub mod plot;
pub mod precompose;
pub mod problem;
pub mod solver;
