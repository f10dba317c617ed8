//! Seeded synthetic request sets over a network.

use super::{below, unit};
use crate::error::Violation;
use crate::error::{Error, Result};
use crate::problem::validate::validate_request_set;
use crate::problem::SkywayGraph;
use crate::problem::{Request, RequestSet, SCHEMA_VERSION};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Parameters of [`generate_requests`].
#[derive(Debug, Clone, PartialEq)]
pub struct RequestParams {
    /// Number of requests, from 1 to [`MAX_REQUESTS`].
    pub count: usize,
    /// Seed of the `ChaCha8Rng`.
    pub seed: u64,
    /// Largest package mass, kg (the drone's max payload; the paper's 1.4 kg by default).
    pub max_package_kg: f64,
}

/// Default number of requests.
pub const DEFAULT_REQUESTS: usize = 10_000;
/// Largest request count accepted.
pub const MAX_REQUESTS: usize = 10_000_000;
/// Default largest package mass, kg (paper Table 3).
pub const DEFAULT_MAX_PACKAGE_KG: f64 = 1.4;
/// Fewest packages per request.
pub const MIN_PACKAGES: usize = 2;
/// Most packages per request.
pub const MAX_PACKAGES: usize = 8;

impl Default for RequestParams {
    fn default() -> Self {
        RequestParams {
            count: DEFAULT_REQUESTS,
            seed: 0,
            max_package_kg: DEFAULT_MAX_PACKAGE_KG,
        }
    }
}

/// Checks generator parameters (codes E3901, E3902).
pub fn check_request_params(p: &RequestParams) -> Vec<Violation> {
    let mut out = Vec::new();
    if !(1..=MAX_REQUESTS).contains(&p.count) {
        out.push(Violation::new(
            "E3901",
            "--count",
            format!("request count is {}", p.count),
            format!("give a request count from 1 to {MAX_REQUESTS}"),
        ));
    }
    if !(p.max_package_kg.is_finite() && (0.001..=1000.0).contains(&p.max_package_kg)) {
        out.push(Violation::new(
            "E3902",
            "--max-package-kg",
            format!("max package mass is {}", p.max_package_kg),
            "give a mass from 0.001 to 1000 kg (the drone's max payload, 1.4 kg in the paper)",
        ));
    }
    out
}

/// Generates a request set over `graph`.
///
/// Each request, drawn in order from `ChaCha8Rng::seed_from_u64(seed)`:
/// - source uniform over the nodes that have at least one other node in their connected component;
/// - destination uniform over the other nodes of the source's component (so source != destination
///   and the two are always connected);
/// - package count uniform in 2..=8; each mass uniform on (0, max], rounded to the gram and kept
///   within [0.001 kg, max].
///
/// Ids are `r00000`, `r00001`, ... (at least five digits). The set records its seed.
///
/// # Arguments
/// * `graph` - a validated network.
/// * `params` - count, seed, max package mass.
///
/// # Returns
/// A request set that passes [`validate_request_set`] with `max_payload_kg = params.max_package_kg`.
///
/// # Errors
/// [`Error::Invalid`]: E3901/E3902 for parameters out of range, E3903 if no two nodes are connected.
///
/// # Complexity
/// O(V * C + count * 8) for C connected components.
pub fn generate_requests(graph: &SkywayGraph, params: &RequestParams) -> Result<RequestSet> {
    let violations = check_request_params(params);
    if !violations.is_empty() {
        return Err(Error::Invalid(violations));
    }
    // Group nodes by connected component, in node order.
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of = vec![0usize; graph.node_count()];
    for (i, slot) in group_of.iter_mut().enumerate() {
        match groups.iter().position(|g| graph.is_connected(g[0], i)) {
            Some(gi) => {
                groups[gi].push(i);
                *slot = gi;
            }
            None => {
                *slot = groups.len();
                groups.push(vec![i]);
            }
        }
    }
    let sources: Vec<usize> = (0..graph.node_count())
        .filter(|&i| groups[group_of[i]].len() >= 2)
        .collect();
    if sources.is_empty() {
        return Err(Error::invalid(
            "E3903",
            "--network",
            "no two nodes of the network are joined by edges",
            "give a network with edges",
        ));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let width = (params.count - 1).to_string().len().max(5);
    let max = params.max_package_kg;
    let requests = (0..params.count)
        .map(|k| {
            let source = sources[below(&mut rng, sources.len())];
            let group = &groups[group_of[source]];
            let mut d = below(&mut rng, group.len() - 1);
            if group[d] == source {
                d = group.len() - 1;
            }
            let destination = group[d];
            let count = MIN_PACKAGES + below(&mut rng, MAX_PACKAGES - MIN_PACKAGES + 1);
            let packages_kg = (0..count)
                .map(|_| {
                    let m = max * (1.0 - unit(&mut rng)); // (0, max]
                    ((m * 1000.0).round() / 1000.0).clamp(0.001, max)
                })
                .collect();
            Request {
                id: format!("r{k:0width$}"),
                source: graph.id_of(source).to_string(),
                destination: graph.id_of(destination).to_string(),
                packages_kg,
            }
        })
        .collect();
    let set = RequestSet {
        schema_version: SCHEMA_VERSION,
        seed: Some(params.seed),
        requests,
    };
    let violations = validate_request_set(&set, graph, max);
    if !violations.is_empty() {
        return Err(Error::Invalid(violations));
    }
    Ok(set)
}
