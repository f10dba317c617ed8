//! Floyd–Warshall all-pairs shortest paths over dense row-major matrices.
//!
//! For a directed graph on nodes `0..n` with non-negative edge costs `c(u, v)`:
//!
//! ```text
//! d0[i][j] = min over edges (i, j) of c(i, j), d0[i][i] = 0, else unreachable
//! dk[i][j] = min(d(k-1)[i][j], d(k-1)[i][k] + d(k-1)[k][j])   for k = 0, ..., n - 1
//! ```
//!
//! with `prev[i][j]`, the node before `j` on the shortest `i -> j` path, taken from `prev[k][j]`
//! whenever the path through `k` is strictly shorter. The relaxation order (`k`, then `i`, then
//! `j`), the strict comparison, the initialisation (edges in the order given, the first of equal
//! parallel edges kept, then the diagonal set to 0 with `prev[i][i] = i`) and the unreachable
//! value `f64::MAX` are those of petgraph 0.8's `floyd_warshall_path`, so both return the same
//! distances and predecessors (`tests/network.rs` checks this on random graphs); the matrices here
//! are flat `n * n` arrays and the inner loop runs over whole rows, which the compiler vectorises.

/// The distance of a pair with no path: `f64::MAX`, as petgraph's `floyd_warshall_path`.
pub const UNREACHABLE: f64 = f64::MAX;

/// The predecessor of a pair with no path.
const NO_PREDECESSOR: u32 = u32::MAX;

/// Shortest paths between every pair of nodes: distances and predecessors, `n * n` each.
#[derive(Debug, Clone, PartialEq)]
pub struct AllPairs {
    node_count: usize,
    /// `distance[i * n + j]`: length of the shortest `i -> j` path, [`UNREACHABLE`] if none.
    distance: Vec<f64>,
    /// `prev[i * n + j]`: the node before `j` on that path (`i` for `j = i`).
    prev: Vec<u32>,
}

/// All-pairs shortest paths by Floyd–Warshall.
///
/// # Arguments
/// * `node_count`: `n`, the nodes are `0..n`.
/// * `edges_min`: directed edges `(from, to, cost)`, costs finite and non-negative (the
///   relaxation relies on it: a pair through an unreachable node is never shorter, so such rows
///   are skipped, and the diagonal stays 0). Parallel edges keep the first of the cheapest.
///
/// # Returns
/// The distances and predecessors of every pair, equal to those of petgraph 0.8's
/// `floyd_warshall_path` on a graph with the same nodes and the edges added in the same order.
///
/// # Panics
/// When an edge names a node `>= node_count`, or `node_count >= u32::MAX`.
///
/// # Complexity
/// O(n^3) time (`n^3` relaxations at most, rows `i` with no path to `k` skipped), O(n^2) memory.
///
/// # Example
/// ```
/// use swarmplan::network::floyd_warshall::floyd_warshall;
/// let paths = floyd_warshall(3, &[(0, 1, 1.0), (1, 2, 1.0), (0, 2, 3.0)]);
/// assert_eq!(paths.distance(0, 2), Some(2.0));
/// assert_eq!(paths.path(0, 2), Some(vec![0, 1, 2]));
/// assert_eq!(paths.path(2, 0), None);
/// ```
pub fn floyd_warshall(node_count: usize, edges_min: &[(usize, usize, f64)]) -> AllPairs {
    let n = node_count;
    assert!(
        u32::try_from(n).is_ok_and(|n| n < NO_PREDECESSOR),
        "{n} nodes: too many for u32 predecessors"
    );
    let mut distance = vec![UNREACHABLE; n * n];
    let mut prev = vec![NO_PREDECESSOR; n * n];
    for &(u, v, cost) in edges_min {
        assert!(u < n && v < n, "edge ({u}, {v}) outside 0..{n}");
        if distance[u * n + v] > cost {
            distance[u * n + v] = cost;
            prev[u * n + v] = u as u32;
        }
    }
    for i in 0..n {
        distance[i * n + i] = 0.0;
        prev[i * n + i] = i as u32;
    }
    // Row k does not change while k is the intermediate node (d[k][k] = 0 and costs are
    // non-negative), so a copy of it serves every row i.
    let mut distance_k = vec![0.0; n];
    let mut prev_k = vec![0u32; n];
    for k in 0..n {
        distance_k.copy_from_slice(&distance[k * n..(k + 1) * n]);
        prev_k.copy_from_slice(&prev[k * n..(k + 1) * n]);
        for (distance_i, prev_i) in distance.chunks_exact_mut(n).zip(prev.chunks_exact_mut(n)) {
            let d_ik = distance_i[k];
            // d_ik + d_kj >= f64::MAX >= d_ij for every j: nothing to relax.
            if d_ik == UNREACHABLE {
                continue;
            }
            relax_row(d_ik, distance_i, prev_i, &distance_k, &prev_k);
        }
    }
    AllPairs {
        node_count: n,
        distance,
        prev,
    }
}

/// Columns relaxed together: a block the compiler turns into vector instructions (2 lanes of
/// `f64` with SSE2) with enough independent work between them.
const BLOCK: usize = 8;

/// `d_i[j] = d_ik + d_k[j]` and `p_i[j] = p_k[j]` wherever that is strictly shorter, for every `j`,
/// in blocks of [`BLOCK`] columns.
#[inline]
fn relax_row(d_ik: f64, d_i: &mut [f64], p_i: &mut [u32], d_k: &[f64], p_k: &[u32]) {
    let mut d_i_blocks = d_i.chunks_exact_mut(BLOCK);
    let mut p_i_blocks = p_i.chunks_exact_mut(BLOCK);
    let mut d_k_blocks = d_k.chunks_exact(BLOCK);
    let mut p_k_blocks = p_k.chunks_exact(BLOCK);
    for (((d_i, p_i), d_k), p_k) in (&mut d_i_blocks)
        .zip(&mut p_i_blocks)
        .zip(&mut d_k_blocks)
        .zip(&mut p_k_blocks)
    {
        for j in 0..BLOCK {
            relax(d_ik, &mut d_i[j], &mut p_i[j], d_k[j], p_k[j]);
        }
    }
    for (((d_ij, p_ij), &d_kj), &p_kj) in d_i_blocks
        .into_remainder()
        .iter_mut()
        .zip(p_i_blocks.into_remainder())
        .zip(d_k_blocks.remainder())
        .zip(p_k_blocks.remainder())
    {
        relax(d_ik, d_ij, p_ij, d_kj, p_kj);
    }
}

/// One relaxation, `d_ij > d_ik + d_kj` as petgraph compares, written with bit masks rather than
/// a branch or a conditional store so that it vectorises.
#[inline(always)]
fn relax(d_ik: f64, d_ij: &mut f64, p_ij: &mut u32, d_kj: f64, p_kj: u32) {
    let via = d_ik + d_kj;
    let shorter = *d_ij > via;
    let mask = u64::from(shorter).wrapping_neg();
    *d_ij = f64::from_bits((via.to_bits() & mask) | (d_ij.to_bits() & !mask));
    let mask = u32::from(shorter).wrapping_neg();
    *p_ij = (p_kj & mask) | (*p_ij & !mask);
}

impl AllPairs {
    /// Number of nodes `n`.
    pub fn node_count(&self) -> usize {
        self.node_count
    }

    /// Length of the shortest `source -> target` path, `None` if there is none.
    ///
    /// # Panics
    /// When a node is `>= n`.
    pub fn distance(&self, source: usize, target: usize) -> Option<f64> {
        let d = self.distance[self.at(source, target)];
        (d != UNREACHABLE).then_some(d)
    }

    /// The distance matrix, row-major `n * n`, [`UNREACHABLE`] where there is no path: petgraph's
    /// distance map as a matrix.
    pub fn distances(&self) -> &[f64] {
        &self.distance
    }

    /// The node before `target` on the shortest `source -> target` path (`source` itself when
    /// `target = source`), `None` if there is no path: petgraph's `prev[source][target]`.
    ///
    /// # Panics
    /// When a node is `>= n`.
    pub fn predecessor(&self, source: usize, target: usize) -> Option<usize> {
        let p = self.prev[self.at(source, target)];
        (p != NO_PREDECESSOR).then_some(p as usize)
    }

    /// The shortest `source -> target` path as node indices, from `source` to `target`, read back
    /// through the predecessors; `None` if there is no path.
    ///
    /// # Panics
    /// When a node is `>= n`.
    ///
    /// # Complexity
    /// O(n).
    pub fn path(&self, source: usize, target: usize) -> Option<Vec<usize>> {
        let mut path = vec![target];
        let mut at = target;
        while at != source {
            match self.predecessor(source, at) {
                Some(p) if path.len() <= self.node_count => {
                    path.push(p);
                    at = p;
                }
                _ => return None,
            }
        }
        path.reverse();
        Some(path)
    }

    fn at(&self, source: usize, target: usize) -> usize {
        assert!(
            source < self.node_count && target < self.node_count,
            "node ({source}, {target}) outside 0..{}",
            self.node_count
        );
        source * self.node_count + target
    }
}
