//! Coded validation rules for networks (E1xxx) and requests (E3xxx).
//!
//! Every rule is checked and every violation reported at once, each naming the field
//! (`edges[3].wind_speed_mps`, `requests[17].packages_kg[2]`), the cause with the offending value,
//! and what to do. Profile rules (E2xxx) live with the profile type.
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

use super::{Network, Request, RequestSet, MAX_DELIVERY_DRONES, SCHEMA_VERSION};
use crate::error::{show, Violation};
use crate::problem::SkywayGraph;
use std::collections::{HashMap, HashSet};

/// Safe-flight wind limit (m/s): an edge's wind speed must be strictly below it.
pub const MAX_WIND_SPEED_MPS: f64 = 13.8;
/// Largest coordinate magnitude, m (E1106): 10,000 km from the frame's origin, a quarter of the
/// Earth's circumference, holds any city's skyway network; differences stay finite.
pub const MAX_COORDINATE_M: f64 = 1e7;
/// Longest edge, m (E1208): 1,000 km, far beyond any drone's range (the paper's flies about 11.5
/// km on a battery), so that a travel time stays at most 6e4 min at the slowest 1 km/h.
pub const MAX_EDGE_M: f64 = 1e6;
/// Slowest pad charge rate, mAh/min (E1107, and `pads.charge_rate_mah_per_min` of a profile): a
/// full 4480 mAh charge in 31 days; slower is not a charger.
pub const MIN_PAD_RATE_MAH_PER_MIN: f64 = 0.1;
/// Fastest pad charge rate, mAh/min (E1107): a full charge of the largest battery allowed (1e6
/// mAh) in a minute.
pub const MAX_PAD_RATE_MAH_PER_MIN: f64 = 1e6;
/// Most pads at one node (E1108): more pads than drones change nothing (a swarm has at most 64
/// drones), and a rooftop holds far fewer than 1,000.
pub const MAX_PADS: u32 = 1_000;

/// Checks every network rule (E1xxx) and returns every violation found, in file order.
///
/// # Arguments
/// * `n` - the network as read from its file.
///
/// # Returns
/// All violations; empty when the network is valid.
///
/// # Complexity
/// O(V + E) expected time (hash sets of ids and node pairs).
pub fn validate_network(n: &Network) -> Vec<Violation> {
    let mut out = Vec::new();
    if n.schema_version != SCHEMA_VERSION {
        out.push(Violation::new(
            "E1001",
            "schema_version",
            format!(
                "schema_version is {}, this build reads {SCHEMA_VERSION}",
                n.schema_version
            ),
            format!(
                "set schema_version to {SCHEMA_VERSION} after checking the file against README.md"
            ),
        ));
    }
    if n.nodes.is_empty() {
        out.push(Violation::new(
            "E1002",
            "nodes",
            "the network has no nodes",
            "list at least two rooftop nodes",
        ));
    }
    let mut positions: HashMap<&str, (f64, f64)> = HashMap::new();
    for (i, node) in n.nodes.iter().enumerate() {
        if node.id.trim().is_empty() {
            out.push(Violation::new(
                "E1101",
                format!("nodes[{i}].id"),
                "the node id is empty",
                "give every node a non-empty unique id",
            ));
        } else if positions.contains_key(node.id.as_str()) {
            out.push(Violation::new(
                "E1102",
                format!("nodes[{i}].id"),
                format!("node id '{}' is used by an earlier node", node.id),
                "rename one of the nodes so that ids are unique",
            ));
        } else {
            positions.insert(node.id.as_str(), (node.x_m, node.y_m));
        }
        for (name, v) in [("x_m", node.x_m), ("y_m", node.y_m)] {
            if !v.is_finite() {
                out.push(Violation::new(
                    "E1103",
                    format!("nodes[{i}].{name}"),
                    format!("coordinate is {v}"),
                    "give a finite coordinate in metres",
                ));
            } else if v.abs() > MAX_COORDINATE_M {
                out.push(Violation::new(
                    "E1106",
                    format!("nodes[{i}].{name}"),
                    format!(
                        "coordinate {} m is outside the stated range [-1e7, 1e7] m",
                        show(v)
                    ),
                    "move the frame's origin near the network (coordinates within ±1e7 m)",
                ));
            }
        }
        if let Some(rate) = node.pad_charge_rate_mah_per_min {
            if !(rate.is_finite() && rate > 0.0) {
                out.push(Violation::new(
                    "E1104",
                    format!("nodes[{i}].pad_charge_rate_mah_per_min"),
                    format!("pad charge rate is {rate}"),
                    "give a finite rate above 0 mAh/min, or omit it to use the profile's rate",
                ));
            } else if !(MIN_PAD_RATE_MAH_PER_MIN..=MAX_PAD_RATE_MAH_PER_MIN).contains(&rate) {
                out.push(Violation::new(
                    "E1107",
                    format!("nodes[{i}].pad_charge_rate_mah_per_min"),
                    format!(
                        "pad charge rate {} mAh/min is outside the stated range [0.1, 1e6] mAh/min",
                        show(rate)
                    ),
                    "give a rate within [0.1, 1e6] mAh/min, or omit it to use the profile's rate",
                ));
            }
        }
        if node.pads > MAX_PADS {
            out.push(Violation::new(
                "E1108",
                format!("nodes[{i}].pads"),
                format!(
                    "{} pads, more than the stated maximum {MAX_PADS}",
                    node.pads
                ),
                "give at most 1000 pads (more pads than drones in a swarm change nothing)",
            ));
        }
    }
    if !n.nodes.is_empty() && n.nodes.iter().all(|node| node.pads == 0) {
        out.push(Violation::new(
            "E1105",
            "nodes",
            "no node has recharging pads",
            "give at least one node pads >= 1 so that drones can recharge",
        ));
    }
    let mut pairs: HashMap<(&str, &str), usize> = HashMap::new();
    for (j, seg) in n.edges.iter().enumerate() {
        let from = positions.get(seg.from.as_str()).copied();
        let to = positions.get(seg.to.as_str()).copied();
        for (name, id, pos) in [("from", &seg.from, from), ("to", &seg.to, to)] {
            if pos.is_none() {
                out.push(Violation::new(
                    "E1201",
                    format!("edges[{j}].{name}"),
                    format!("node id '{id}' is not in nodes"),
                    "use the id of a listed node, or add the node",
                ));
            }
        }
        if seg.from == seg.to {
            out.push(Violation::new(
                "E1202",
                format!("edges[{j}]"),
                format!("edge joins node '{}' to itself", seg.from),
                "remove the edge; an edge joins two different nodes",
            ));
        } else {
            let key = if seg.from <= seg.to {
                (seg.from.as_str(), seg.to.as_str())
            } else {
                (seg.to.as_str(), seg.from.as_str())
            };
            if let Some(first) = pairs.get(&key) {
                out.push(Violation::new(
                    "E1203",
                    format!("edges[{j}]"),
                    format!(
                        "edges[{first}] already joins '{}' and '{}' (edges are flown both ways)",
                        key.0, key.1
                    ),
                    "keep one edge per pair of nodes",
                ));
            } else {
                pairs.insert(key, j);
            }
        }
        match seg.distance_m {
            Some(d) if !(d.is_finite() && d > 0.0) => out.push(Violation::new(
                "E1204",
                format!("edges[{j}].distance_m"),
                format!("distance is {d}"),
                "give a finite distance above 0 m, or omit it to use the Euclidean distance",
            )),
            Some(d) if d > MAX_EDGE_M => out.push(too_long(j, d, "distance_m is")),
            None => {
                if let (Some(a), Some(b)) = (from, to) {
                    let d = euclidean_m(a, b);
                    if seg.from != seg.to && !(d.is_finite() && d > 0.0) {
                        out.push(Violation::new(
                            "E1204",
                            format!("edges[{j}].distance_m"),
                            format!(
                                "distance_m is absent and the Euclidean distance between '{}' and '{}' is {d}",
                                seg.from, seg.to
                            ),
                            "give distance_m, or distinct finite coordinates to the two nodes",
                        ));
                    } else if seg.from != seg.to && d > MAX_EDGE_M {
                        let what = format!(
                            "distance_m is absent and the Euclidean distance between '{}' and '{}' is",
                            seg.from, seg.to
                        );
                        out.push(too_long(j, d, &what));
                    }
                }
            }
            _ => {}
        }
        let w = seg.wind_speed_mps;
        if !(w.is_finite() && w >= 0.0) {
            out.push(Violation::new(
                "E1205",
                format!("edges[{j}].wind_speed_mps"),
                format!("wind speed is {w}"),
                "give a finite wind speed of 0 m/s or more",
            ));
        } else if w >= MAX_WIND_SPEED_MPS {
            out.push(Violation::new(
                "E1206",
                format!("edges[{j}].wind_speed_mps"),
                format!("wind speed {w} m/s is at or over the safe-flight limit {MAX_WIND_SPEED_MPS} m/s"),
                "drones cannot fly this edge: lower the wind speed below 13.8 m/s or remove the edge",
            ));
        }
        let dir = seg.wind_from_deg;
        if !(dir.is_finite() && (0.0..=360.0).contains(&dir)) {
            out.push(Violation::new(
                "E1207",
                format!("edges[{j}].wind_from_deg"),
                format!("wind direction is {dir}"),
                "give the direction the wind blows from in degrees clockwise from north, within [0, 360]",
            ));
        }
    }
    out
}

/// E1208: an edge longer than [`MAX_EDGE_M`]; `what` says where the length comes from.
fn too_long(j: usize, d: f64, what: &str) -> Violation {
    Violation::new(
        "E1208",
        format!("edges[{j}].distance_m"),
        format!(
            "{what} {} m, outside the stated range (0, 1e6] m",
            show(d)
        ),
        "split the edge at intermediate nodes, or check its length and the nodes' coordinates (metres)",
    )
}

/// Euclidean distance in metres between two positions.
pub(crate) fn euclidean_m(a: (f64, f64), b: (f64, f64)) -> f64 {
    (b.0 - a.0).hypot(b.1 - a.1)
}

/// Checks one request (E32xx, E33xx and E3101) against a validated network.
///
/// # Arguments
/// * `r` - the request.
/// * `index` - its position in the request file, used in field names (`requests[index]`).
/// * `graph` - the network it runs on.
/// * `max_payload_kg` - the delivery drone's maximum payload (the profile's value).
///
/// # Returns
/// All violations of this request; empty when it is valid.
///
/// # Complexity
/// O(P) for P packages (connectivity is a constant-time component lookup).
pub fn validate_request(
    r: &Request,
    index: usize,
    graph: &SkywayGraph,
    max_payload_kg: f64,
) -> Vec<Violation> {
    let mut out = Vec::new();
    let at = format!("requests[{index}]");
    if r.id.trim().is_empty() {
        out.push(Violation::new(
            "E3101",
            format!("{at}.id"),
            "the request id is empty",
            "give every request a non-empty unique id",
        ));
    }
    let source = graph.index_of(&r.source);
    let destination = graph.index_of(&r.destination);
    for (name, id, found) in [
        ("source", &r.source, source),
        ("destination", &r.destination, destination),
    ] {
        if found.is_none() {
            out.push(Violation::new(
                "E3201",
                format!("{at}.{name}"),
                format!("node id '{id}' is not in the network"),
                "use the id of a node of the network file given",
            ));
        }
    }
    if let (Some(s), Some(d)) = (source, destination) {
        if s == d {
            out.push(Violation::new(
                "E3202",
                format!("{at}.destination"),
                format!("destination '{}' equals the source", r.destination),
                "give a destination different from the source",
            ));
        } else if !graph.is_connected(s, d) {
            out.push(Violation::new(
                "E3203",
                format!("{at}.destination"),
                format!(
                    "no chain of edges joins source '{}' to destination '{}'",
                    r.source, r.destination
                ),
                "pick a destination reachable from the source, or add edges to the network",
            ));
        }
    }
    if r.packages_kg.is_empty() {
        out.push(Violation::new(
            "E3301",
            format!("{at}.packages_kg"),
            "the request has no packages",
            "list at least one package mass in kg (one delivery drone per package)",
        ));
    }
    if r.packages_kg.len() > MAX_DELIVERY_DRONES {
        out.push(Violation::new(
            "E3304",
            format!("{at}.packages_kg"),
            format!(
                "{} packages, more than the {MAX_DELIVERY_DRONES} delivery drones a swarm may have",
                r.packages_kg.len()
            ),
            "split the request into requests of at most 32 packages",
        ));
    }
    for (p, &m) in r.packages_kg.iter().enumerate() {
        if !(m.is_finite() && m > 0.0) {
            out.push(Violation::new(
                "E3302",
                format!("{at}.packages_kg[{p}]"),
                format!("package mass is {m}"),
                "give a finite package mass above 0 kg",
            ));
        } else if m > max_payload_kg {
            out.push(Violation::new(
                "E3303",
                format!("{at}.packages_kg[{p}]"),
                format!("package mass {m} kg is over the drone's max payload {max_payload_kg} kg"),
                "split the package, or use a profile whose drone carries more",
            ));
        }
    }
    out
}

/// Checks a whole request set: its header (E3001, E3002), unique ids (E3102) and every request.
///
/// # Arguments
/// * `set` - the request set as read from its file.
/// * `graph` - the network the requests run on.
/// * `max_payload_kg` - the delivery drone's maximum payload.
///
/// # Returns
/// All violations, header first, then request by request in file order.
///
/// # Complexity
/// O(total packages + number of requests) expected time.
pub fn validate_request_set(
    set: &RequestSet,
    graph: &SkywayGraph,
    max_payload_kg: f64,
) -> Vec<Violation> {
    set_rules(set, |k, r, out| {
        out.extend(validate_request(r, k, graph, max_payload_kg))
    })
}

/// The rules of a request set that do not need the network: its header (E3001, E3002) and unique
/// ids (E3102).
///
/// # Complexity
/// O(number of requests) expected time.
pub fn validate_request_set_header(set: &RequestSet) -> Vec<Violation> {
    set_rules(set, |_, _, _| {})
}

/// The header rules, then request by request in file order the unique-id rule and `each`.
fn set_rules(
    set: &RequestSet,
    mut each: impl FnMut(usize, &Request, &mut Vec<Violation>),
) -> Vec<Violation> {
    let mut out = Vec::new();
    if set.schema_version != SCHEMA_VERSION {
        out.push(Violation::new(
            "E3001",
            "schema_version",
            format!(
                "schema_version is {}, this build reads {SCHEMA_VERSION}",
                set.schema_version
            ),
            format!(
                "set schema_version to {SCHEMA_VERSION} after checking the file against README.md"
            ),
        ));
    }
    if set.requests.is_empty() {
        out.push(Violation::new(
            "E3002",
            "requests",
            "the request set is empty",
            "list at least one request",
        ));
    }
    let mut seen: HashSet<&str> = HashSet::new();
    for (k, r) in set.requests.iter().enumerate() {
        if !r.id.trim().is_empty() && !seen.insert(r.id.as_str()) {
            out.push(Violation::new(
                "E3102",
                format!("requests[{k}].id"),
                format!("request id '{}' is used by an earlier request", r.id),
                "rename one of the requests so that ids are unique",
            ));
        }
        each(k, r, &mut out);
    }
    out
}

/// Reads a request-set JSON file and checks it against a network.
///
/// # Arguments
/// * `path` - the request file.
/// * `graph` - the network the requests run on.
/// * `max_payload_kg` - the delivery drone's maximum payload.
///
/// # Returns
/// The request set.
///
/// # Errors
/// [`crate::Error::Invalid`] with E0008 or E0009 if the file cannot be read or is not UTF-8, with E0001 for
/// malformed JSON or with every E3xxx violation, each field prefixed by the file name.
pub fn read_request_set(
    path: &std::path::Path,
    graph: &SkywayGraph,
    max_payload_kg: f64,
) -> crate::error::Result<RequestSet> {
    let set: RequestSet = super::io::read_json(path)?;
    let violations = validate_request_set(&set, graph, max_payload_kg);
    if violations.is_empty() {
        Ok(set)
    } else {
        Err(super::graph::prefix_fields(
            crate::Error::Invalid(violations),
            path,
        ))
    }
}
