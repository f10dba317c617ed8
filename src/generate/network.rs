//! Seeded synthetic rooftop network: a jittered street grid thinned and crossed like a city.

use super::{below, normal, round_to, shuffle, unit};
use crate::error::{Error, Result};
use crate::problem::validate::validate_network;
use crate::problem::{Edge, Network, Node, Wind, SCHEMA_VERSION};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Parameters of [`generate_network`].
#[derive(Debug, Clone, PartialEq)]
pub struct NetworkParams {
    /// Number of nodes, at least [`MIN_NODES`].
    pub nodes: usize,
    /// Seed of the `ChaCha8Rng`.
    pub seed: u64,
    /// Street-grid spacing in metres (default [`DEFAULT_SPACING_M`]).
    pub spacing_m: f64,
}

/// Default number of nodes: the paper's 195 rooftops.
pub const DEFAULT_NODES: usize = 195;
/// Smallest node count for which every node can have degree 2 or more.
pub const MIN_NODES: usize = 3;
/// Largest node count accepted.
pub const MAX_NODES: usize = 100_000;
/// Default grid spacing, metres. With 195 nodes the grid is 14 x 14 cells, 6.5 km x 6.5 km.
pub const DEFAULT_SPACING_M: f64 = 500.0;
/// Share of grid edges considered for removal (only removed when both ends keep degree >= 2 and the
/// network stays connected).
pub const REMOVE_PROBABILITY: f64 = 0.2;
/// Share of grid cells that get a diagonal edge (when both ends have degree < 4).
pub const DIAGONAL_PROBABILITY: f64 = 0.15;
/// Node jitter as a share of the spacing, uniform in `[-J, J]` on each axis.
pub const JITTER_SHARE: f64 = 0.3;
/// Probability of 0, 1, 2, 3, 4 pads at a node.
pub const PAD_PROBABILITIES: [f64; 5] = [0.40, 0.15, 0.20, 0.15, 0.10];
/// Mean wind speed of a network is drawn uniformly from this range, m/s.
pub const MEAN_WIND_RANGE_MPS: (f64, f64) = (3.0, 7.0);
/// Log-normal spread of an edge's wind speed around the network mean.
pub const WIND_SPEED_LOG_SD: f64 = 0.4;
/// Edge wind speeds are redrawn until below this cap, m/s (well under the 13.8 m/s limit).
pub const WIND_SPEED_CAP_MPS: f64 = 13.0;
/// Standard deviation of an edge's wind direction around the prevailing direction, degrees.
pub const WIND_DIRECTION_SD_DEG: f64 = 25.0;

impl Default for NetworkParams {
    fn default() -> Self {
        NetworkParams {
            nodes: DEFAULT_NODES,
            seed: 0,
            spacing_m: DEFAULT_SPACING_M,
        }
    }
}

/// Checks generator parameters (codes E1901, E1902).
pub fn check_network_params(p: &NetworkParams) -> Vec<crate::error::Violation> {
    let mut out = Vec::new();
    if !(MIN_NODES..=MAX_NODES).contains(&p.nodes) {
        out.push(crate::error::Violation::new(
            "E1901",
            "--nodes",
            format!("node count is {}", p.nodes),
            format!("give a node count from {MIN_NODES} to {MAX_NODES}"),
        ));
    }
    if !(p.spacing_m.is_finite() && (1.0..=100_000.0).contains(&p.spacing_m)) {
        out.push(crate::error::Violation::new(
            "E1902",
            "--spacing-m",
            format!("grid spacing is {}", p.spacing_m),
            "give a spacing from 1 to 100000 metres",
        ));
    }
    out
}

/// Generates a connected rooftop network.
///
/// Construction, all draws from `ChaCha8Rng::seed_from_u64(seed)` in this order:
/// 1. **Nodes** on a `cols x rows` grid, `cols = ceil(sqrt(N))`, `rows = ceil(N / cols)`, filled row
///    by row from the south-west; node `k` sits at column `k % cols`, row `k / cols`, spacing `s`,
///    jittered uniformly by up to `0.3 s` on each axis and shifted by `0.3 s` so that coordinates are
///    >= 0 (rounded to 0.1 m). Ids `n000`...
/// 2. **Streets**: every horizontal and vertical grid neighbour pair is an edge (degree 2–4).
/// 3. **Thinning**: in shuffled order, each street is removed with probability 0.2 if both ends keep
///    degree >= 2 and the network stays connected.
/// 4. **Avenues**: each grid cell, in shuffled order, gets with probability 0.15 one of its two
///    diagonals (chosen 50/50) if both ends have degree < 4 and the other diagonal is absent.
/// 5. **Repair**: a node left with degree < 2 (possible only in a partial last row or tiny grids) is
///    joined to its nearest non-adjacent node of degree < 4.
/// 6. **Pads** per node: 0, 1, 2, 3, 4 with probabilities 0.40, 0.15, 0.20, 0.15, 0.10 (mean 1.4);
///    if no node got pads, one uniformly chosen node gets 2.
/// 7. **Wind**: a prevailing from-direction `theta` uniform in [0, 360) and a mean speed `v` uniform
///    in [3, 7] m/s per network; per edge (sorted by end indices) the from-direction is
///    `theta + 25 z` degrees (normal noise, wrapped to [0, 360), rounded to 0.1) and the speed
///    `v exp(0.4 z' - 0.08)` (log-normal with mean `v`), redrawn until below 13 m/s, rounded to 0.01.
///
/// Edge `distance_m` is left out, so it is the Euclidean distance between the ends.
///
/// # Arguments
/// * `params` - node count, seed, grid spacing.
///
/// # Returns
/// A network that passes [`validate_network`], connected, every node of degree 2–4.
///
/// # Errors
/// [`Error::Invalid`] with E1901/E1902 for parameters out of range.
///
/// # Complexity
/// O(N (N + E)) for the connectivity checks during thinning; milliseconds for 195 nodes.
pub fn generate_network(params: &NetworkParams) -> Result<Network> {
    let violations = check_network_params(params);
    if !violations.is_empty() {
        return Err(Error::Invalid(violations));
    }
    let n = params.nodes;
    let s = params.spacing_m;
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let cols = (n as f64).sqrt().ceil() as usize;
    let width = (n - 1).to_string().len().max(3);

    // 1. Nodes.
    let mut pos = Vec::with_capacity(n);
    for k in 0..n {
        let (c, r) = ((k % cols) as f64, (k / cols) as f64);
        let jx = (2.0 * unit(&mut rng) - 1.0) * JITTER_SHARE * s;
        let jy = (2.0 * unit(&mut rng) - 1.0) * JITTER_SHARE * s;
        // Offset by the jitter bound so that every coordinate is >= 0.
        let o = JITTER_SHARE * s;
        pos.push((round_to(o + c * s + jx, 1), round_to(o + r * s + jy, 1)));
    }

    // 2. Streets.
    let matrix = (n <= 4000).then(|| vec![vec![false; n]; n]);
    let mut edges: Vec<(usize, usize)> = Vec::new();
    for k in 0..n {
        if k % cols + 1 < cols && k + 1 < n {
            edges.push((k, k + 1));
        }
        if k + cols < n {
            edges.push((k, k + cols));
        }
    }
    let mut g = Adjacency::new(n, matrix);
    for &(a, b) in &edges {
        g.add(a, b);
    }

    // 3. Thinning.
    let mut order = edges.clone();
    shuffle(&mut rng, &mut order);
    for (a, b) in order {
        let remove = unit(&mut rng) < REMOVE_PROBABILITY;
        if remove && g.degree(a) > 2 && g.degree(b) > 2 {
            g.remove(a, b);
            if !g.connected_between(a, b) {
                g.add(a, b);
            }
        }
    }

    // 4. Avenues.
    let mut cells: Vec<usize> = (0..n)
        .filter(|&k| k % cols + 1 < cols && k + cols + 1 < n)
        .collect();
    shuffle(&mut rng, &mut cells);
    for k in cells {
        let add = unit(&mut rng) < DIAGONAL_PROBABILITY;
        let rising = below(&mut rng, 2) == 0;
        if !add {
            continue;
        }
        let (d1, d2) = ((k, k + cols + 1), (k + 1, k + cols));
        let (mine, other) = if rising { (d1, d2) } else { (d2, d1) };
        if !g.has(other.0, other.1) && g.degree(mine.0) < 4 && g.degree(mine.1) < 4 {
            g.add(mine.0, mine.1);
        }
    }

    // 5. Repair.
    for k in 0..n {
        while g.degree(k) < 2 {
            let best = (0..n)
                .filter(|&j| j != k && !g.has(k, j) && g.degree(j) < 4)
                .min_by(|&i, &j| {
                    dist2(pos[k], pos[i])
                        .total_cmp(&dist2(pos[k], pos[j]))
                        .then(i.cmp(&j))
                });
            match best {
                Some(j) => g.add(k, j),
                None => break,
            }
        }
    }

    // 6. Pads.
    let pads = draw_network_pads(&mut rng, n);

    // 7. Wind.
    let mut pairs = g.edge_list();
    pairs.sort_unstable();
    let winds = draw_edge_winds(&mut rng, pairs.len());
    let id = |k: usize| format!("n{k:0width$}");
    let edges = pairs
        .into_iter()
        .zip(winds)
        .map(|((a, b), wind)| Edge {
            from: id(a),
            to: id(b),
            distance_m: None,
            wind_speed_mps: wind.speed_mps,
            wind_from_deg: wind.from_deg,
        })
        .collect();
    let nodes = (0..n)
        .map(|k| Node {
            id: id(k),
            x_m: pos[k].0,
            y_m: pos[k].1,
            pads: pads[k],
            pad_charge_rate_mah_per_min: None,
        })
        .collect();
    let network = Network {
        schema_version: SCHEMA_VERSION,
        name: Some(format!(
            "synthetic-{n}-seed-{}-spacing-{}m",
            params.seed, params.spacing_m
        )),
        nodes,
        edges,
    };
    let violations = validate_network(&network);
    if !violations.is_empty() {
        return Err(Error::Invalid(violations));
    }
    Ok(network)
}

/// Pads of `n` nodes, each drawn from [`PAD_PROBABILITIES`]; when every node drew none, a node
/// drawn uniformly gets 2 (a network needs a pad somewhere).
pub(crate) fn draw_network_pads(rng: &mut ChaCha8Rng, n: usize) -> Vec<u32> {
    let mut pads: Vec<u32> = (0..n).map(|_| draw_pads(rng)).collect();
    if n > 0 && pads.iter().all(|&p| p == 0) {
        let k = below(rng, n);
        pads[k] = 2;
    }
    pads
}

/// Winds of `edges` edges: a prevailing direction uniform in `[0, 360)` and a network mean speed
/// uniform in [`MEAN_WIND_RANGE_MPS`], then per edge a direction normal around the prevailing one
/// (sd [`WIND_DIRECTION_SD_DEG`], 0.1 degree) and a log-normal speed with that mean (log sd
/// [`WIND_SPEED_LOG_SD`], redrawn until below [`WIND_SPEED_CAP_MPS`], 0.01 m/s).
pub(crate) fn draw_edge_winds(rng: &mut ChaCha8Rng, edges: usize) -> Vec<Wind> {
    let prevailing_deg = 360.0 * unit(rng);
    let mean_mps =
        MEAN_WIND_RANGE_MPS.0 + (MEAN_WIND_RANGE_MPS.1 - MEAN_WIND_RANGE_MPS.0) * unit(rng);
    (0..edges)
        .map(|_| {
            let from_deg = round_to(
                (prevailing_deg + WIND_DIRECTION_SD_DEG * normal(rng)).rem_euclid(360.0),
                1,
            ) % 360.0;
            let log_mean_shift = WIND_SPEED_LOG_SD * WIND_SPEED_LOG_SD / 2.0;
            let speed_mps = loop {
                let v = mean_mps * (WIND_SPEED_LOG_SD * normal(rng) - log_mean_shift).exp();
                if v < WIND_SPEED_CAP_MPS {
                    break round_to(v, 2);
                }
            };
            Wind {
                speed_mps,
                from_deg,
            }
        })
        .collect()
}

fn draw_pads(rng: &mut ChaCha8Rng) -> u32 {
    let u = unit(rng);
    let mut acc = 0.0;
    for (p, w) in PAD_PROBABILITIES.iter().enumerate() {
        acc += w;
        if u < acc {
            return p as u32;
        }
    }
    (PAD_PROBABILITIES.len() - 1) as u32
}

fn dist2(a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)
}

/// Working adjacency structure of the generator: sorted neighbour lists plus an optional matrix.
struct Adjacency {
    lists: Vec<Vec<usize>>,
    matrix: Option<Vec<Vec<bool>>>,
}

impl Adjacency {
    fn new(n: usize, matrix: Option<Vec<Vec<bool>>>) -> Self {
        Adjacency {
            lists: vec![Vec::new(); n],
            matrix,
        }
    }
    fn has(&self, a: usize, b: usize) -> bool {
        match &self.matrix {
            Some(m) => m[a][b],
            None => self.lists[a].contains(&b),
        }
    }
    fn add(&mut self, a: usize, b: usize) {
        if self.has(a, b) {
            return;
        }
        self.lists[a].push(b);
        self.lists[b].push(a);
        if let Some(m) = &mut self.matrix {
            m[a][b] = true;
            m[b][a] = true;
        }
    }
    fn remove(&mut self, a: usize, b: usize) {
        self.lists[a].retain(|&x| x != b);
        self.lists[b].retain(|&x| x != a);
        if let Some(m) = &mut self.matrix {
            m[a][b] = false;
            m[b][a] = false;
        }
    }
    fn degree(&self, a: usize) -> usize {
        self.lists[a].len()
    }
    /// Breadth-first search from `a` until `b` is found.
    fn connected_between(&self, a: usize, b: usize) -> bool {
        let mut seen = vec![false; self.lists.len()];
        let mut queue = std::collections::VecDeque::from([a]);
        seen[a] = true;
        while let Some(u) = queue.pop_front() {
            if u == b {
                return true;
            }
            for &v in &self.lists[u] {
                if !seen[v] {
                    seen[v] = true;
                    queue.push_back(v);
                }
            }
        }
        false
    }
    fn edge_list(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (a, l) in self.lists.iter().enumerate() {
            for &b in l {
                if a < b {
                    out.push((a, b));
                }
            }
        }
        out
    }
}
