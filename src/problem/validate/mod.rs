//! Coded validation rules for networks (E1xxx), profiles (E2xxx) and requests (E3xxx).
//!
//! Every rule is checked and every violation reported at once, each naming the field
//! (`edges[3].wind_speed_mps`, `requests[17].packages_kg[2]`), the cause with the offending value,
//! and what to do.
//!
//! Each rule is one function named after its code, `eNNNN_what(.., out: &mut Vec<Violation>)`,
//! that pushes its violations onto `out`; [`validate_network`], [`validate_profile`],
//! [`validate_request`] and [`validate_request_set`] call them in a fixed order (per node, per
//! edge, per request and per package where the rule concerns one), so violations come in file
//! order. A rule that only makes sense once another passed (a range after finiteness) checks that
//! itself and stays silent otherwise, so no field is reported twice.
//!
//! ## Networks (`network.rs`)
//!
//! | code  | field                               | rule |
//! |-------|-------------------------------------|------|
//! | E1001 | `schema_version`                    | equals [`SCHEMA_VERSION`] |
//! | E1002 | `nodes`                             | at least one node |
//! | E1101 | `nodes[i].id`                       | not empty |
//! | E1102 | `nodes[i].id`                       | unique |
//! | E1103 | `nodes[i].x_m`, `nodes[i].y_m`      | finite (negative is fine: the frame's origin is arbitrary) |
//! | E1104 | `nodes[i].pad_charge_rate_mah_per_min` | finite and > 0 when given |
//! | E1105 | `nodes`                             | at least one node has pads |
//! | E1106 | `nodes[i].x_m`, `nodes[i].y_m`      | within ±[`MAX_COORDINATE_M`] (1e7 m) |
//! | E1107 | `nodes[i].pad_charge_rate_mah_per_min` | within [[`MIN_PAD_RATE_MAH_PER_MIN`], [`MAX_PAD_RATE_MAH_PER_MIN`]] |
//! | E1108 | `nodes[i].pads`                     | at most [`MAX_PADS`] |
//! | E1201 | `edges[j].from`, `edges[j].to` | names a node id |
//! | E1202 | `edges[j]`                       | no self-loop |
//! | E1203 | `edges[j]`                       | no second edge between the same two nodes (either direction) |
//! | E1204 | `edges[j].distance_m`            | finite and > 0 (given, or the Euclidean distance when absent) |
//! | E1205 | `edges[j].wind_speed_mps`        | finite and >= 0 |
//! | E1206 | `edges[j].wind_speed_mps`        | below [`MAX_WIND_SPEED_MPS`] (13.8 m/s) |
//! | E1207 | `edges[j].wind_from_deg`         | finite, within [0, 360] |
//! | E1208 | `edges[j].distance_m`            | at most [`MAX_EDGE_M`] (1e6 m; given, or the Euclidean distance) |
//!
//! ## Profiles (`profile.rs`)
//!
//! | code  | field                               | rule |
//! |-------|-------------------------------------|------|
//! | E2001 | `schema_version`                    | equals [`SCHEMA_VERSION`] |
//! | E2002 | `drone.*`, `sharing.rate_mah_per_min`, `.range_m`, `.lambda_mah`, `pads.charge_rate_mah_per_min`, `energy.*` but `parasitic_fraction`, `formation.spacing_m`, `.*_width_m`, `.*_decay_m`, `.abreast_band_m`, `.min_position_factor`, `failure.*_norm_*` | finite and > 0 |
//! | E2003 | `sharing.gamma_mah`, `.delta_mah`, `formation.*_gain`, `.upwash_offset_m`, `.wake_onset_m`, `.abreast_offset_m` | finite and >= 0 |
//! | E2004 | `energy.parasitic_fraction`         | finite, within [0, 1) |
//! | E2005 | `formation.min_position_factor`     | at most 1 |
//! | E2006 | `formation.select_swarm_size`, `formation.direction_bins` | within 1..=[`MAX_SWARM_DRONES`] (64), within 1..=360 |
//! | E2007 | `support.extra_batteries`           | their mass at most `drone.max_payload_kg` |
//! | E2008 | `sharing.delta_mah`                 | below a support drone's capacity |
//! | E2009 | `sharing.gamma_mah`                 | below `drone.battery_mah` |
//! | E2010 | `redundancy.rows`                   | at least one row |
//! | E2011 | `redundancy.rows[0].from_pct`       | 0 |
//! | E2012 | `redundancy.rows[i].from_pct`       | finite, within [0, 100], above the previous row's |
//! | E2013 | every quantity of [`profile_ranges`] | within its stated range (not for a field already reported by E2002, E2003, E2020 or E2022) |
//! | E2020 | `failure.weights.*`                 | within [0, 1] under `failure.terms = "normalised"` |
//! | E2021 | `failure.weights`                   | one weight > 0 under `failure.model = "weighted-sum"` |
//! | E2022 | `failure.weights.*`                 | finite and >= 0 under `failure.terms = "per-unit"` |
//! | E2023 | `redundancy.rows[i].level`          | `n+k` with k at most [`MAX_SUPPORT_DRONES`] (32) |
//!
//! ## Requests (`requests.rs`)
//!
//! | code  | field                               | rule |
//! |-------|-------------------------------------|------|
//! | E3001 | `schema_version`                    | equals [`SCHEMA_VERSION`] |
//! | E3002 | `requests`                          | at least one request |
//! | E3101 | `requests[k].id`                    | not empty |
//! | E3102 | `requests[k].id`                    | unique within the set |
//! | E3201 | `requests[k].source`, `.destination` | names a node id of the network |
//! | E3202 | `requests[k].destination`           | differs from the source |
//! | E3203 | `requests[k].destination`           | reachable from the source over edges |
//! | E3301 | `requests[k].packages_kg`           | at least one package |
//! | E3302 | `requests[k].packages_kg[p]`        | finite and > 0 |
//! | E3303 | `requests[k].packages_kg[p]`        | at most the drone's max payload |
//! | E3304 | `requests[k].packages_kg`           | at most [`MAX_DELIVERY_DRONES`] packages |
//!
//! [`SCHEMA_VERSION`]: crate::problem::SCHEMA_VERSION
//! [`MAX_SWARM_DRONES`]: crate::problem::MAX_SWARM_DRONES
//! [`MAX_SUPPORT_DRONES`]: crate::problem::MAX_SUPPORT_DRONES
//! [`MAX_DELIVERY_DRONES`]: crate::problem::MAX_DELIVERY_DRONES

mod network;
mod profile;
mod requests;

pub(crate) use network::euclidean_m;
pub use network::{
    validate_network, MAX_COORDINATE_M, MAX_EDGE_M, MAX_PADS, MAX_PAD_RATE_MAH_PER_MIN,
    MAX_WIND_SPEED_MPS, MIN_PAD_RATE_MAH_PER_MIN,
};
pub use profile::{profile_ranges, validate_profile, StatedRange, MAX_EXTRA_BATTERIES};
pub use requests::{
    read_request_set, validate_request, validate_request_set, validate_request_set_header,
};

use crate::error::Violation;
use crate::problem::SCHEMA_VERSION;

/// The schema-version rule of a JSON file (E1001 for a network, E3001 for a request set): the
/// file's `schema_version` is the one this build reads.
fn json_schema_version(code: &'static str, found: u32, out: &mut Vec<Violation>) {
    if found != SCHEMA_VERSION {
        out.push(Violation::new(
            code,
            "schema_version",
            format!("schema_version is {found}, this build reads {SCHEMA_VERSION}"),
            format!(
                "set schema_version to {SCHEMA_VERSION} after checking the file against \
                 docs/src/inputs.md"
            ),
        ));
    }
}
