//! Formation selection (paper 5.1): the formation of least total consumption under the averaged wind
//! of the network, kept for the whole trip. See models/precompose.md.

use crate::energy::slot_factors;
use crate::formation::slots_m;
use crate::problem::FormationKind;
use crate::problem::Wind;
use crate::problem::{Network, Profile};

/// Averaged wind of a network: mean speed over all edges, most frequent direction.
///
/// Directions are put in `B = formation.direction_bins` equal bins of width `360 / B` degrees, bin
/// `k` centred on `k * 360 / B` (bin 0 centred on north), so a direction `phi` falls in bin
/// `round(phi / (360 / B)) mod B`. The most frequent bin wins; ties go to the lowest bin index. The
/// averaged wind's direction is that bin's centre. A network without edges has no wind.
///
/// # Complexity
/// O(edges + B).
pub fn averaged_wind(network: &Network, profile: &Profile) -> Wind {
    let segs = &network.edges;
    if segs.is_empty() {
        return Wind::CALM;
    }
    let bins = profile.formation.direction_bins.max(1) as usize;
    let width = 360.0 / bins as f64;
    let mut count = vec![0usize; bins];
    let mut sum = 0.0;
    for s in segs {
        sum += s.wind_speed_mps;
        let phi = s.wind_from_deg.rem_euclid(360.0);
        let k = ((phi / width).round() as usize) % bins;
        count[k] += 1;
    }
    // First maximum: ties go to the lowest bin.
    let mut best = 0;
    for (k, &c) in count.iter().enumerate() {
        if c > count[best] {
            best = k;
        }
    }
    Wind {
        speed_mps: sum / segs.len() as f64,
        from_deg: best as f64 * width,
    }
}

/// Total position factor `sum_j F_j` of `kind` with `n` drones on a leg towards `heading_deg`.
fn total_factor(
    profile: &Profile,
    kind: FormationKind,
    n: usize,
    heading_deg: f64,
    wind: &Wind,
) -> f64 {
    let slots = slots_m(kind, n, profile.formation.spacing_m);
    slot_factors(profile, &slots, heading_deg, wind)
        .iter()
        .sum()
}

/// The formation of least total consumption for `n` equal drones on a leg towards `heading_deg`
/// under `wind`. Payload and wind factors are the same for every formation, so the totals compare
/// the position factors. Ties go to the first formation in [`FormationKind::ALL`].
///
/// # Complexity
/// O(5 n^2).
pub fn select_formation_for_heading(
    profile: &Profile,
    wind: &Wind,
    heading_deg: f64,
    n: usize,
) -> FormationKind {
    let mut best = (FormationKind::Column, f64::INFINITY);
    for kind in FormationKind::ALL {
        let t = total_factor(profile, kind, n, heading_deg, wind);
        if t < best.1 - 1e-12 {
            best = (kind, t);
        }
    }
    best.0
}

/// Selects the network's formation from its averaged wind.
///
/// Our reading of the paper (models/precompose.md): the paper picks the formation once, on the
/// averaged wind, before any route is known. The swarm will fly the network's edges in both
/// directions, so each formation is scored by its total position factor for a swarm of
/// `formation.select_swarm_size` drones under the averaged wind, summed over every edge flown both
/// ways and weighted by the edge's length. A network without edges is scored on a leg
/// flown into the averaged wind (a head wind). Ties go to the first formation in
/// [`FormationKind::ALL`].
///
/// # Arguments
/// * `network` - the skyway network (assumed valid: edge ends exist).
/// * `profile` - wake model and swarm size used for the ranking.
///
/// # Returns
/// The formation and the averaged wind it was chosen for.
///
/// # Complexity
/// O(edges * 5 * n^2).
pub fn select_formation(network: &Network, profile: &Profile) -> (FormationKind, Wind) {
    let wind = averaged_wind(network, profile);
    let n = profile.formation.select_swarm_size.max(1) as usize;
    let pos: std::collections::HashMap<&str, (f64, f64)> = network
        .nodes
        .iter()
        .map(|nd| (nd.id.as_str(), (nd.x_m, nd.y_m)))
        .collect();
    // (heading, weight) of every edge flown both ways.
    let mut legs: Vec<(f64, f64)> = Vec::new();
    for s in &network.edges {
        let (Some(a), Some(b)) = (pos.get(s.from.as_str()), pos.get(s.to.as_str())) else {
            continue;
        };
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let len = (dx * dx + dy * dy).sqrt();
        if len.is_nan() || len <= 0.0 {
            continue;
        }
        let weight = s.distance_m.unwrap_or(len);
        let heading = dx.atan2(dy).to_degrees(); // clockwise from north: east = 90
        legs.push((heading, weight));
        legs.push((heading + 180.0, weight));
    }
    if legs.is_empty() {
        return (
            select_formation_for_heading(profile, &wind, wind.from_deg, n),
            wind,
        );
    }
    let mut best = (FormationKind::Column, f64::INFINITY);
    for kind in FormationKind::ALL {
        let slots = slots_m(kind, n, profile.formation.spacing_m);
        let t: f64 = legs
            .iter()
            .map(|&(h, w)| w * slot_factors(profile, &slots, h, &wind).iter().sum::<f64>())
            .sum();
        if t < best.1 * (1.0 - 1e-12) {
            best = (kind, t);
        }
    }
    (best.0, wind)
}
