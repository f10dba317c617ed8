//! Number of support drones (paper 5.1, Eq. 1, Eq. 2 and Table 2). See models/precompose.md.
//!
//! ```text
//! p1 = D_pr = (1/N) sum_i p_i / payload_norm_kg      payload ratio (Eq. 1), clamped to [0, 1]
//! p2 = min(1, d(alpha, beta) / distance_norm_m)      route distance
//! p3 = battery_mah / E_c = 1 / (1 + extra_batteries)  support capacity (more capacity, lower P)
//! p4 = min(1, W / wind_limit_mps)                    averaged wind speed
//! product:      P = 100 * prod_i (w_i * p_i)          (Eq. 2 as written)
//! weighted-sum: P = 100 * sum_i (w_i * p_i) / sum_i w_i
//! ```
//!
//! `P` (percent, clamped to [0, 100]) selects the last row of the redundancy table whose `from_pct`
//! is at most `P`; the row's level (`N+k`, `2N`, `2(N+1)`) gives the count for `N` delivery drones.

use crate::energy::Wind;
use crate::problem::profile::{FailureModel, RedundancyLevel};
use crate::problem::Profile;
use serde::Serialize;

/// The outcome of support drone selection.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SupportDecision {
    /// Which form of Eq. 2 was used.
    pub model: FailureModel,
    /// The four normalised terms `[p1, p2, p3, p4]` (payload, distance, capacity, wind).
    pub terms: [f64; 4],
    /// Failure probability `P`, percent in [0, 100].
    pub probability_pct: f64,
    /// Index of the redundancy table row `P` falls in.
    pub row: usize,
    /// That row's redundancy level.
    pub level: RedundancyLevel,
    /// Number of support drones.
    pub count: usize,
}

/// The four normalised terms `[p1, p2, p3, p4]` of Eq. 2, each in [0, 1].
pub fn failure_terms(
    profile: &Profile,
    packages_kg: &[f64],
    route_distance_m: f64,
    avg_wind: &Wind,
) -> [f64; 4] {
    let clamp = |x: f64| {
        if x.is_finite() {
            x.clamp(0.0, 1.0)
        } else {
            1.0
        }
    };
    let f = &profile.failure;
    let n = packages_kg.len();
    let p1 = if n == 0 {
        0.0
    } else {
        packages_kg
            .iter()
            .map(|p| p / f.payload_norm_kg)
            .sum::<f64>()
            / n as f64
    };
    let p2 = route_distance_m / f.distance_norm_m;
    let p3 = 1.0 / (1.0 + profile.support.extra_batteries as f64);
    let p4 = avg_wind.speed_mps / profile.energy.wind_limit_mps;
    [clamp(p1), clamp(p2), clamp(p3), clamp(p4)]
}

/// Decides how many support drones a request needs.
///
/// # Arguments
/// * `profile` - failure model, weights, normalisers and the redundancy table.
/// * `packages_kg` - the request's packages, one per delivery drone (`N = packages_kg.len()`).
/// * `route_distance_m` - the source-to-destination distance (the paper uses the shortest path).
/// * `avg_wind` - the averaged wind of the network.
///
/// # Returns
/// The terms, the probability, the table row and the count. A malformed table (rejected by
/// [`crate::problem::profile::validate_profile`]) falls back to its first row, an empty one to `N+1`.
///
/// # Complexity
/// O(N + rows).
pub fn support_count(
    profile: &Profile,
    packages_kg: &[f64],
    route_distance_m: f64,
    avg_wind: &Wind,
) -> SupportDecision {
    let terms = failure_terms(profile, packages_kg, route_distance_m, avg_wind);
    let w = &profile.failure.weights;
    let weights = [w.payload, w.distance, w.capacity, w.wind];
    let raw = match profile.failure.model {
        FailureModel::Product => {
            100.0
                * weights
                    .iter()
                    .zip(&terms)
                    .map(|(w, p)| w * p)
                    .product::<f64>()
        }
        FailureModel::WeightedSum => {
            let total: f64 = weights.iter().sum();
            if total > 0.0 {
                100.0 * weights.iter().zip(&terms).map(|(w, p)| w * p).sum::<f64>() / total
            } else {
                0.0
            }
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
        terms,
        probability_pct,
        row,
        level,
        count: level.support_drones(packages_kg.len()),
    }
}
