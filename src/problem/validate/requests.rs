//! Request rules (E3xxx), one function per rule code; the table of codes is in [`super`].

use crate::error::{show, Violation};
use crate::problem::{Request, RequestSet, SkywayGraph, MAX_DELIVERY_DRONES};
use std::collections::HashMap;

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
    e3101_request_id_not_empty(&at, r, &mut out);
    let ends = Ends {
        source: graph.index_of(&r.source),
        destination: graph.index_of(&r.destination),
    };
    e3201_ends_exist(&at, r, ends, &mut out);
    e3202_destination_differs(&at, r, ends, &mut out);
    e3203_destination_reachable(&at, r, ends, graph, &mut out);
    e3301_has_packages(&at, r, &mut out);
    e3304_packages_at_most_max(&at, r, &mut out);
    for (p, &m) in r.packages_kg.iter().enumerate() {
        e3302_package_positive(&at, p, m, &mut out);
        e3303_package_at_most_max_payload(&at, p, m, max_payload_kg, &mut out);
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
        out.extend(validate_request(r, k, graph, max_payload_kg));
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
    e3001_schema_version(set, &mut out);
    e3002_has_requests(set, &mut out);
    let first = first_request_of_ids(set);
    for (k, r) in set.requests.iter().enumerate() {
        e3102_request_id_unique(k, r, &first, &mut out);
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
/// [`crate::error::Error::Invalid`] with E0008 or E0009 if the file cannot be read or is not UTF-8, with E0001 for
/// malformed JSON or with every E3xxx violation, each field prefixed by the file name.
pub fn read_request_set(
    path: &std::path::Path,
    graph: &SkywayGraph,
    max_payload_kg: f64,
) -> crate::error::Result<RequestSet> {
    let set: RequestSet = crate::problem::io::read_json(path)?;
    let violations = validate_request_set(&set, graph, max_payload_kg);
    if violations.is_empty() {
        Ok(set)
    } else {
        Err(crate::problem::graph::prefix_fields(
            crate::error::Error::Invalid(violations),
            path,
        ))
    }
}

/// The graph nodes of a request's source and destination, where the network has them.
#[derive(Debug, Clone, Copy)]
struct Ends {
    source: Option<usize>,
    destination: Option<usize>,
}

/// The index of the first request with each non-empty id.
fn first_request_of_ids(set: &RequestSet) -> HashMap<&str, usize> {
    let mut first = HashMap::new();
    for (k, r) in set.requests.iter().enumerate() {
        if !r.id.trim().is_empty() {
            first.entry(r.id.as_str()).or_insert(k);
        }
    }
    first
}

/// E3001: the file's schema version is the one this build reads.
fn e3001_schema_version(set: &RequestSet, out: &mut Vec<Violation>) {
    super::json_schema_version("E3001", set.schema_version, out);
}

/// E3002: the set has at least one request.
fn e3002_has_requests(set: &RequestSet, out: &mut Vec<Violation>) {
    if set.requests.is_empty() {
        out.push(Violation::new(
            "E3002",
            "requests",
            "the request set is empty",
            "list at least one request",
        ));
    }
}

/// E3102: no earlier request has the same (non-empty) id.
fn e3102_request_id_unique(
    k: usize,
    r: &Request,
    first: &HashMap<&str, usize>,
    out: &mut Vec<Violation>,
) {
    if matches!(first.get(r.id.as_str()), Some(&j) if j != k) {
        out.push(Violation::new(
            "E3102",
            format!("requests[{k}].id"),
            format!("request id '{}' is used by an earlier request", r.id),
            "rename one of the requests so that ids are unique",
        ));
    }
}

/// E3101: a request id is not empty.
fn e3101_request_id_not_empty(at: &str, r: &Request, out: &mut Vec<Violation>) {
    if r.id.trim().is_empty() {
        out.push(Violation::new(
            "E3101",
            format!("{at}.id"),
            "the request id is empty",
            "give every request a non-empty unique id",
        ));
    }
}

/// E3201: the source and the destination name nodes of the network.
fn e3201_ends_exist(at: &str, r: &Request, ends: Ends, out: &mut Vec<Violation>) {
    for (name, id, found) in [
        ("source", &r.source, ends.source.is_some()),
        ("destination", &r.destination, ends.destination.is_some()),
    ] {
        if !found {
            out.push(Violation::new(
                "E3201",
                format!("{at}.{name}"),
                format!("node id '{id}' is not in the network"),
                "use the id of a node of the network file given",
            ));
        }
    }
}

/// E3202: the destination differs from the source.
fn e3202_destination_differs(at: &str, r: &Request, ends: Ends, out: &mut Vec<Violation>) {
    if let (Some(s), Some(d)) = (ends.source, ends.destination) {
        if s == d {
            out.push(Violation::new(
                "E3202",
                format!("{at}.destination"),
                format!("destination '{}' equals the source", r.destination),
                "give a destination different from the source",
            ));
        }
    }
}

/// E3203: the destination is reachable from a different source over edges.
fn e3203_destination_reachable(
    at: &str,
    r: &Request,
    ends: Ends,
    graph: &SkywayGraph,
    out: &mut Vec<Violation>,
) {
    if let (Some(s), Some(d)) = (ends.source, ends.destination) {
        if s != d && !graph.is_connected(s, d) {
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
}

/// E3301: a request has at least one package.
fn e3301_has_packages(at: &str, r: &Request, out: &mut Vec<Violation>) {
    if r.packages_kg.is_empty() {
        out.push(Violation::new(
            "E3301",
            format!("{at}.packages_kg"),
            "the request has no packages",
            "list at least one package mass in kg (one delivery drone per package)",
        ));
    }
}

/// E3304: a request has at most [`MAX_DELIVERY_DRONES`] packages.
fn e3304_packages_at_most_max(at: &str, r: &Request, out: &mut Vec<Violation>) {
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
}

/// A package mass the models can carry: finite and above 0.
fn positive_mass(m: f64) -> bool {
    m.is_finite() && m > 0.0
}

/// E3302: a package mass is finite and above 0.
fn e3302_package_positive(at: &str, p: usize, m: f64, out: &mut Vec<Violation>) {
    if !positive_mass(m) {
        out.push(Violation::new(
            "E3302",
            format!("{at}.packages_kg[{p}]"),
            format!("package mass is {}", show(m)),
            "give a finite package mass above 0 kg",
        ));
    }
}

/// E3303: a positive package mass is at most the drone's max payload.
fn e3303_package_at_most_max_payload(
    at: &str,
    p: usize,
    m: f64,
    max_payload_kg: f64,
    out: &mut Vec<Violation>,
) {
    if positive_mass(m) && m > max_payload_kg {
        out.push(Violation::new(
            "E3303",
            format!("{at}.packages_kg[{p}]"),
            format!(
                "package mass {} kg is over the drone's max payload {} kg",
                show(m),
                show(max_payload_kg)
            ),
            "split the package, or use a profile whose drone carries more",
        ));
    }
}
