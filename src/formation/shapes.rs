//! Slot positions of the five formations for any swarm size, in the body frame: `x` forward along the
//! direction flown, `y` to the right, metres. Neighbouring slots are `spacing_m` apart in every
//! formation; diagonal steps use `a = spacing_m / sqrt(2)` on each axis. See models/formation.md.

use crate::problem::FormationKind;
use nalgebra::Vector2;

/// Slot positions of `kind` for `n` drones with neighbours `spacing_m` apart.
///
/// Slot 0 is the front (the leader of Column, Echelon, Vee and Diamond; the leftmost of Front); the
/// other slots follow front to back, then left to right.
///
/// * Column: `(-k s, 0)`, one behind the other.
/// * Front: `(0, (k - (n-1)/2) s)`, abreast, centred on the track.
/// * Echelon: `(-k a, k a)`, a diagonal line back to the right.
/// * Vee: the leader at the origin, then alternately left `(-k a, -k a)` and right `(-k a, k a)`.
/// * Diamond: the `n` points of the 45-degree lattice `(-(i+j) a, (j-i) a)`, `0 <= i, j < K`,
///   `K = ceil(sqrt(n))`, closest to the lattice's centre (ties: front first, then left first),
///   shifted so the front slot is at `x = 0`. `n = 4` is the classic diamond, `n = 5` the diamond with
///   a centre drone, `n = 9` the full 3 x 3 diamond.
///
/// # Arguments
/// * `kind` - the formation.
/// * `n` - number of drones (0 gives no slots).
/// * `spacing_m` - distance between neighbouring drones, m.
///
/// # Returns
/// `n` positions, m, body frame.
///
/// # Complexity
/// O(n log n).
pub fn slots_m(kind: FormationKind, n: usize, spacing_m: f64) -> Vec<Vector2<f64>> {
    let s = spacing_m;
    let a = spacing_m / std::f64::consts::SQRT_2;
    // Adding +0.0 turns a negative zero into +0.0, so the front slot reads (0, 0) in reports.
    let slots: Vec<Vector2<f64>> = match kind {
        FormationKind::Column => (0..n).map(|k| Vector2::new(-(k as f64) * s, 0.0)).collect(),
        FormationKind::Front => {
            let mid = (n as f64 - 1.0) / 2.0;
            (0..n)
                .map(|k| Vector2::new(0.0, (k as f64 - mid) * s))
                .collect()
        }
        FormationKind::Echelon => (0..n)
            .map(|k| Vector2::new(-(k as f64) * a, k as f64 * a))
            .collect(),
        FormationKind::Vee => (0..n)
            .map(|i| {
                if i == 0 {
                    return Vector2::new(0.0, 0.0);
                }
                let k = i.div_ceil(2) as f64;
                let side = if i % 2 == 1 { -1.0 } else { 1.0 };
                Vector2::new(-k * a, side * k * a)
            })
            .collect(),
        FormationKind::Diamond => diamond(n, a),
    };
    slots
        .into_iter()
        .map(|p| Vector2::new(p.x + 0.0, p.y + 0.0))
        .collect()
}

fn diamond(n: usize, a: f64) -> Vec<Vector2<f64>> {
    if n == 0 {
        return Vec::new();
    }
    let k = (1..=n).find(|k| k * k >= n).unwrap_or(n);
    // Work in integer lattice units so ties are exact: squared distance to the centre times 4.
    let mut pts: Vec<(usize, usize)> = (0..k).flat_map(|i| (0..k).map(move |j| (i, j))).collect();
    let key = |&(i, j): &(usize, usize)| {
        let di = 2 * i as i64 - (k as i64 - 1);
        let dj = 2 * j as i64 - (k as i64 - 1);
        // distance, then front first (smaller i + j), then left first (smaller j - i)
        (di * di + dj * dj, (i + j) as i64, j as i64 - i as i64)
    };
    pts.sort_by_key(key);
    pts.truncate(n);
    let front = pts.iter().map(|&(i, j)| i + j).min().unwrap_or(0);
    let mut out: Vec<(i64, i64)> = pts
        .iter()
        .map(|&(i, j)| ((i + j - front) as i64, j as i64 - i as i64))
        .collect();
    out.sort();
    out.into_iter()
        .map(|(back, right)| Vector2::new(-(back as f64) * a, right as f64 * a))
        .collect()
}
