//! Move/swap local search on an assignment of the sorted drones (`models/node_time.md`,
//! "Decision version").

/// Improves an assignment by moves and swaps off a pad with the largest load: a drone moves to
/// another pad, or two drones of different length trade places, when the two new loads both stay
/// strictly below that largest load. Stops at a local optimum or after `10 n` improvements.
///
/// `pad_of[j]` is the pad of sorted drone `j`; returns the new makespan. Complexity `O(n^2)` per
/// improvement.
pub(crate) fn local_search(m: usize, p: &[f64], pad_of: &mut [usize]) -> f64 {
    let n = p.len();
    let mut loads = vec![0.0_f64; m];
    for (j, &i) in pad_of.iter().enumerate() {
        loads[i] += p[j];
    }
    for _ in 0..10 * n {
        let (imax, lmax) =
            loads
                .iter()
                .copied()
                .enumerate()
                .fold(
                    (0, f64::NEG_INFINITY),
                    |a, (i, l)| if l > a.1 { (i, l) } else { a },
                );
        // Best move: the one that leaves the smaller of the two pads' new maximum.
        let mut best: Option<(f64, usize, Option<usize>, usize)> = None;
        for j in 0..n {
            if pad_of[j] != imax {
                continue;
            }
            for (i, &li) in loads.iter().enumerate() {
                if i == imax {
                    continue;
                }
                let new_max = (lmax - p[j]).max(li + p[j]);
                if new_max < lmax && best.is_none_or(|b| new_max < b.0) {
                    best = Some((new_max, j, None, i));
                }
            }
            for l in 0..n {
                let i = pad_of[l];
                if i == imax || p[l] >= p[j] {
                    continue;
                }
                let d = p[j] - p[l];
                let new_max = (lmax - d).max(loads[i] + d);
                if new_max < lmax && best.is_none_or(|b| new_max < b.0) {
                    best = Some((new_max, j, Some(l), i));
                }
            }
        }
        let Some((_, j, swap, i)) = best else { break };
        pad_of[j] = i;
        loads[imax] -= p[j];
        loads[i] += p[j];
        if let Some(l) = swap {
            pad_of[l] = imax;
            loads[i] -= p[l];
            loads[imax] += p[l];
        }
    }
    // Recompute exactly from the assignment (no drift from the updates).
    loads.iter_mut().for_each(|l| *l = 0.0);
    for (j, &i) in pad_of.iter().enumerate() {
        loads[i] += p[j];
    }
    loads.iter().copied().fold(0.0, f64::max)
}
