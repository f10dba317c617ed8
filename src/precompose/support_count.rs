//! Number of support drones (paper 5.1, Eq. 1, Eq. 2 and Table 2). See models/precompose.md.
//!
//! Terms, `normalised` (the default, each clamped to [0, 1]) or `per-unit` (each in its own unit):
//!
//! ```text
//! term  normalised                                 per-unit
//! p1    D_pr = (1/N) sum_i p_i / payload_norm_kg     D_pr                     payload ratio (Eq. 1)
//! p2    d(alpha, beta) / distance_norm_m             d(alpha, beta) / v, min  route distance
//! p3    C / E_c = 1 / (1 + extra_batteries)          C / E_c                  support capacity
//! p4    W / wind_limit_mps                           W, m/s                   averaged wind speed
//! ```
//!
//! With the weighted terms `q_i = w_i * p_i`:
//!
//! ```text
//! product:      P = 100 * prod_i q_i                         (Eq. 2 as written, both readings)
//! weighted-sum: P = 100 * sum_i q_i / sum_i w_i              (normalised)
//!               P = 100 * sum_i q_i                          (per-unit: each q_i is a battery share)
//! ```
//!
//! `P` (percent, clamped to [0, 100]) selects the last row of the redundancy table whose `from_pct`
//! is at most `P`; the row's level (`N+k`, `2N`, `2(N+1)`) gives the count for `N` delivery drones.

use crate::problem::Profile;
use crate::problem::Wind;
use crate::problem::{FailureModel, FailureTerms, RedundancyLevel};
use serde::{Deserialize, Serialize};

/// The outcome of support drone selection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportDecision {
    /// Which form of Eq. 2 was used.
    pub model: FailureModel,
    /// Which reading of the terms was used.
    pub term_mode: FailureTerms,
    /// The four terms `[p1, p2, p3, p4]` (payload, distance, capacity, wind), see
    /// [`failure_terms`]: normalised to [0, 1], or in their own units.
    pub terms: [f64; 4],
    /// The weighted terms `[w1 p1, w2 p2, w3 p3, w4 p4]`; a weight of 0 gives 0 whatever its term.
    pub weighted_terms: [f64; 4],
    /// Failure probability `P`, percent in [0, 100].
    pub probability_pct: f64,
    /// Index of the redundancy table row `P` falls in.
    pub row: usize,
    /// That row's redundancy level.
    pub level: RedundancyLevel,
    /// Number of support drones.
    pub count: usize,
}

/// The four terms `[p1, p2, p3, p4]` of Eq. 2 under the profile's `failure.terms`.
///
/// * `normalised`: `[D_pr, d / distance_norm_m, C / E_c, W / wind_limit_mps]`, each clamped to
///   [0, 1] (a non-finite term counts as 1).
/// * `per-unit`: `[D_pr, flight_min, C / E_c, W_mps]` with `flight_min = d / v` at the cruise
///   speed `drone.speed_kmh`; not clamped (an unreachable destination gives an infinite `p2`).
///
/// `D_pr` is 0 for a request without packages.
pub fn failure_terms(
    profile: &Profile,
    packages_kg: &[f64],
    route_distance_m: f64,
    avg_wind: &Wind,
) -> [f64; 4] {
    let f = &profile.failure;
    let n = packages_kg.len();
    let payload_ratio = if n == 0 {
        0.0
    } else {
        packages_kg
            .iter()
            .map(|p| p / f.payload_norm_kg)
            .sum::<f64>()
            / n as f64
    };
    let capacity_ratio = 1.0 / (1.0 + profile.support.extra_batteries as f64);
    match f.terms {
        FailureTerms::Normalised => {
            let clamp = |x: f64| {
                if x.is_finite() {
                    x.clamp(0.0, 1.0)
                } else {
                    1.0
                }
            };
            [
                clamp(payload_ratio),
                clamp(route_distance_m / f.distance_norm_m),
                clamp(capacity_ratio),
                clamp(avg_wind.speed_mps / profile.energy.wind_limit_mps),
            ]
        }
        FailureTerms::PerUnit => {
            let speed_m_per_min = profile.drone.speed_kmh * 1000.0 / 60.0;
            [
                payload_ratio,
                route_distance_m / speed_m_per_min,
                capacity_ratio,
                avg_wind.speed_mps,
            ]
        }
    }
}

/// Decides how many support drones a request needs.
///
/// # Arguments
/// * `profile` - failure model, term reading, weights, normalisers and the redundancy table.
/// * `packages_kg` - the request's packages, one per delivery drone (`N = packages_kg.len()`).
/// * `route_distance_m` - the source-to-destination distance (the paper uses the shortest path).
/// * `avg_wind` - the averaged wind of the network.
///
/// # Returns
/// The terms, the weighted terms, the probability, the table row and the count. A malformed table
/// (rejected by [`crate::problem::validate::validate_profile`]) falls back to its first row, an
/// empty one to `N+1`.
///
/// # Complexity
/// O(N + rows).
///
/// # Example
/// The paper's worked example: 3% of the battery per minute of flight, 5 km at 30 km/h, `P_2 = 0.3`.
/// ```
/// use swarmplan::problem::Wind;
/// use swarmplan::precompose::support_count;
/// use swarmplan::problem::{FailureModel, FailureTerms, FailureWeights};
/// # let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("instances/profiles/paper.toml");
/// let mut profile: swarmplan::problem::Profile = swarmplan::problem::io::read_toml(&path).unwrap();
/// profile.failure.model = FailureModel::WeightedSum;
/// profile.failure.terms = FailureTerms::PerUnit;
/// profile.failure.weights = FailureWeights { payload: 0.0, distance: 0.03, capacity: 0.0, wind: 0.0 };
/// let d = support_count(&profile, &[1.0], 5000.0, &Wind::CALM);
/// assert!((d.weighted_terms[1] - 0.3).abs() < 1e-12);
/// assert!((d.probability_pct - 30.0).abs() < 1e-9);
/// ```
pub fn support_count(
    profile: &Profile,
    packages_kg: &[f64],
    route_distance_m: f64,
    avg_wind: &Wind,
) -> SupportDecision {
    let terms = failure_terms(profile, packages_kg, route_distance_m, avg_wind);
    let w = &profile.failure.weights;
    let weights = [w.payload, w.distance, w.capacity, w.wind];
    let mut weighted_terms = [0.0; 4];
    for ((q, &w), &p) in weighted_terms.iter_mut().zip(&weights).zip(&terms) {
        // A zero weight drops its term, even an infinite one.
        *q = if w == 0.0 { 0.0 } else { w * p };
    }
    let raw = match (profile.failure.model, profile.failure.terms) {
        (FailureModel::Product, _) => 100.0 * weighted_terms.iter().product::<f64>(),
        (FailureModel::WeightedSum, FailureTerms::Normalised) => {
            let total: f64 = weights.iter().sum();
            if total > 0.0 {
                100.0 * weighted_terms.iter().sum::<f64>() / total
            } else {
                0.0
            }
        }
        (FailureModel::WeightedSum, FailureTerms::PerUnit) => {
            100.0 * weighted_terms.iter().sum::<f64>()
        }
    };
    let probability_pct = if raw.is_finite() {
        raw.clamp(0.0, 100.0)
    } else {
        100.0
    };
    let rows = &profile.redundancy.rows;
    let row = rows
        .iter()
        .rposition(|r| r.from_pct <= probability_pct)
        .unwrap_or(0);
    let level = rows
        .get(row)
        .map(|r| r.level)
        .unwrap_or(RedundancyLevel::NPlus(1));
    SupportDecision {
        model: profile.failure.model,
        term_mode: profile.failure.terms,
        terms,
        weighted_terms,
        probability_pct,
        row,
        level,
        count: level.support_drones(packages_kg.len()),
    }
}
