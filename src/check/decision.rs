//! Re-derives pre-composition's support decision (paper Eq. 2 and the redundancy table,
//! `models/precompose.md`) from the raw instance, without the pre-composition code: the
//! source-to-destination distance by a Dijkstra of its own over `network.edges`, the averaged
//! wind from the edges, the four failure terms, their weights, the probability, the table row,
//! its level and the support count. Every stated number is compared with its recomputation
//! (P5045, one violation per number with the stated and recomputed values), and the swarm flies
//! the decided count unless the plan's options gave one (P5046).

use super::close;
use crate::compose::RequestReport;
use crate::error::Violation;
use crate::problem::io::json_name;
use crate::problem::{FailureModel, FailureTerms};
use crate::problem::{Network, Profile, Request};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "plan the request again: pre-composition decides the support drones from the request and \
         the instance alone",
    )
}

/// The decision rebuilt from the raw instance.
struct Recomputed {
    terms: [f64; 4],
    weighted_terms: [f64; 4],
    probability_pct: f64,
    row: usize,
    count: usize,
}

/// P5045 and P5046: the document's `support_decision` is the one the instance gives `request`
/// (the request set's),
/// and its swarm flies that many support drones (unless `options.support` overrides it, or the
/// policy flies none).
///
/// # Complexity
/// `O(E log N)` for the distance, `O(E + B)` for the averaged wind over `B` direction bins.
pub fn check_support_decision(
    network: &Network,
    profile: &Profile,
    request: &Request,
    report: &RequestReport,
) -> Vec<Violation> {
    let distance_m = shortest_distance_m(network, &request.source, &request.destination);
    let wind_mps = mean_wind_speed_mps(network);
    let got = recompute(profile, &request.packages_kg, distance_m, wind_mps);
    let stated = &report.support_decision;
    let mut out = Vec::new();
    let mut number = |field: String, stated: f64, recomputed: f64| {
        if !close(stated, recomputed) {
            out.push(violation(
                "P5045",
                field,
                format!(
                    "states {stated}, the instance gives {recomputed} (source-to-destination \
                     distance {distance_m} m, mean wind {wind_mps} m/s)"
                ),
            ));
        }
    };
    for i in 0..4 {
        number(
            format!("support_decision.terms[{i}]"),
            stated.terms[i],
            got.terms[i],
        );
        number(
            format!("support_decision.weighted_terms[{i}]"),
            stated.weighted_terms[i],
            got.weighted_terms[i],
        );
    }
    number(
        "support_decision.probability_pct".to_string(),
        stated.probability_pct,
        got.probability_pct,
    );
    number(
        "support_decision.row".to_string(),
        stated.row as f64,
        got.row as f64,
    );
    number(
        "support_decision.count".to_string(),
        stated.count as f64,
        got.count as f64,
    );
    if let Some(row) = profile.redundancy.rows.get(got.row) {
        if stated.level != row.level {
            out.push(violation(
                "P5045",
                "support_decision.level",
                format!(
                    "states {}, row {} of the redundancy table is {}",
                    json_name(&stated.level),
                    got.row,
                    json_name(&row.level)
                ),
            ));
        }
    }
    if stated.model != profile.failure.model || stated.term_mode != profile.failure.terms {
        out.push(violation(
            "P5045",
            "support_decision.model",
            format!(
                "states {} with {} terms, the profile has {} with {}",
                json_name(&stated.model),
                json_name(&stated.term_mode),
                json_name(&profile.failure.model),
                json_name(&profile.failure.terms)
            ),
        ));
    }
    let flies = report.options.sharing.flies_support();
    if flies && report.options.support.is_none() && report.support_drones != got.count {
        out.push(violation(
            "P5046",
            "support_drones",
            format!(
                "flies {} support drones, the redundancy table gives {} (no --support given)",
                report.support_drones, got.count
            ),
        ));
    }
    out
}

/// Eq. 2 under the profile's model and term reading (see `models/precompose.md`).
fn recompute(profile: &Profile, packages_kg: &[f64], distance_m: f64, wind_mps: f64) -> Recomputed {
    let f = &profile.failure;
    let payload = if packages_kg.is_empty() {
        0.0
    } else {
        packages_kg.iter().sum::<f64>() / f.payload_norm_kg / packages_kg.len() as f64
    };
    let capacity = 1.0 / (1.0 + profile.support.extra_batteries as f64);
    let terms = match f.terms {
        FailureTerms::Normalised => {
            let unit = |x: f64| {
                if x.is_finite() {
                    x.clamp(0.0, 1.0)
                } else {
                    1.0
                }
            };
            [
                unit(payload),
                unit(distance_m / f.distance_norm_m),
                unit(capacity),
                unit(wind_mps / profile.energy.wind_limit_mps),
            ]
        }
        FailureTerms::PerUnit => [
            payload,
            distance_m / (profile.drone.speed_kmh / 0.06),
            capacity,
            wind_mps,
        ],
    };
    let w = [
        f.weights.payload,
        f.weights.distance,
        f.weights.capacity,
        f.weights.wind,
    ];
    let weighted_terms: [f64; 4] =
        std::array::from_fn(|i| if w[i] == 0.0 { 0.0 } else { w[i] * terms[i] });
    let pct = match (f.model, f.terms) {
        (FailureModel::Product, _) => weighted_terms.iter().product::<f64>() * 100.0,
        (FailureModel::WeightedSum, FailureTerms::Normalised) => {
            let total: f64 = w.iter().sum();
            if total > 0.0 {
                weighted_terms.iter().sum::<f64>() / total * 100.0
            } else {
                0.0
            }
        }
        (FailureModel::WeightedSum, FailureTerms::PerUnit) => {
            weighted_terms.iter().sum::<f64>() * 100.0
        }
    };
    let probability_pct = if pct.is_finite() {
        pct.clamp(0.0, 100.0)
    } else {
        100.0
    };
    let rows = &profile.redundancy.rows;
    // The last row whose lower end the probability reaches.
    let row = (0..rows.len())
        .rev()
        .find(|&r| rows[r].from_pct <= probability_pct)
        .unwrap_or(0);
    let n = packages_kg.len();
    let count = rows.get(row).map_or(n + 1, |r| r.level.support_drones(n));
    Recomputed {
        terms,
        weighted_terms,
        probability_pct,
        row,
        count,
    }
}

/// Mean wind speed over the network's edges, m/s (0 without edges).
fn mean_wind_speed_mps(network: &Network) -> f64 {
    let edges = &network.edges;
    if edges.is_empty() {
        return 0.0;
    }
    edges.iter().map(|e| e.wind_speed_mps).sum::<f64>() / edges.len() as f64
}

/// A Dijkstra label: distance so far and node.
#[derive(PartialEq)]
struct Label(f64, usize);

impl Eq for Label {}

impl Ord for Label {
    fn cmp(&self, other: &Self) -> Ordering {
        // Least distance first.
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Label {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// Shortest distance from `source` to `destination` over the edges (either direction, the
/// file's `distance_m`, else Euclidean), m; infinite when no path joins them.
pub(super) fn shortest_distance_m(network: &Network, source: &str, destination: &str) -> f64 {
    let index = super::node_index(network);
    let (Some(&a), Some(&b)) = (index.get(source), index.get(destination)) else {
        return f64::INFINITY;
    };
    let mut adjacent = vec![Vec::new(); network.nodes.len()];
    for e in &network.edges {
        let (Some(&x), Some(&y)) = (index.get(e.from.as_str()), index.get(e.to.as_str())) else {
            continue;
        };
        let (p, q) = (&network.nodes[x], &network.nodes[y]);
        let length = e
            .distance_m
            .unwrap_or_else(|| (q.x_m - p.x_m).hypot(q.y_m - p.y_m));
        adjacent[x].push((y, length));
        adjacent[y].push((x, length));
    }
    let mut best = vec![f64::INFINITY; network.nodes.len()];
    best[a] = 0.0;
    let mut heap = BinaryHeap::from([Label(0.0, a)]);
    while let Some(Label(d, x)) = heap.pop() {
        if x == b {
            return d;
        }
        if d > best[x] {
            continue;
        }
        for &(y, length) in &adjacent[x] {
            if d + length < best[y] {
                best[y] = d + length;
                heap.push(Label(d + length, y));
            }
        }
    }
    f64::INFINITY
}
