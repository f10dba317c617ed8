//! Largest differencing (Karmarkar & Karp 1982), a starting point of the exact search with many
//! drones per pad.

/// Largest differencing (Karmarkar & Karp 1982, "The differencing method of set partitioning",
/// for `m` pads as in Korf, "Multi-way number partitioning", IJCAI 2009) on the drones
/// `sorted_desc` (decreasing): every drone starts as a partial assignment with its time on one
/// pad; the two partial assignments with the largest spread (largest minus smallest load) are
/// merged, the heaviest pad of one with the lightest of the other, until one is left. Writes the
/// pad of each drone into `pad_of_sorted` and returns the makespan.
///
/// With many drones per pad it balances far better than LPT, which leaves the last, shortest
/// drones to even out the loads. Complexity `O(n^2 + n m log m)` (merging the drone lists).
pub(crate) fn ldm_sorted(m: usize, sorted_desc: &[f64], pad_of_sorted: &mut [usize]) -> f64 {
    // A partial assignment: pads as (load, drones), heaviest first.
    type Partial = Vec<(f64, Vec<usize>)>;
    let spread = |a: &Partial| a[0].0 - a[a.len() - 1].0;
    let mut parts: Vec<Partial> = sorted_desc
        .iter()
        .enumerate()
        .map(|(j, &v)| {
            let mut pads = vec![(0.0, Vec::new()); m];
            pads[0] = (v, vec![j]);
            pads
        })
        .collect();
    while parts.len() > 1 {
        // The two largest spreads (ties: the earlier, so the result is reproducible).
        let (mut first, mut second) = (0, 1);
        if spread(&parts[1]) > spread(&parts[0]) {
            (first, second) = (1, 0);
        }
        for q in 2..parts.len() {
            let s = spread(&parts[q]);
            if s > spread(&parts[first]) {
                second = first;
                first = q;
            } else if s > spread(&parts[second]) {
                second = q;
            }
        }
        let (hi, lo) = (first.max(second), first.min(second));
        let b = parts.swap_remove(hi);
        let a = parts.swap_remove(lo);
        // Heaviest of one with lightest of the other.
        let mut merged: Partial = a
            .into_iter()
            .zip(b.into_iter().rev())
            .map(|((la, mut da), (lb, db))| {
                da.extend(db);
                (la + lb, da)
            })
            .collect();
        merged.sort_by(|x, y| y.0.total_cmp(&x.0));
        parts.push(merged);
    }
    for (i, (_, drones)) in parts[0].iter().enumerate() {
        for &j in drones {
            pad_of_sorted[j] = i;
        }
    }
    // Recompute the loads from the assignment.
    let mut loads = vec![0.0_f64; m];
    for (j, &i) in pad_of_sorted.iter().enumerate() {
        loads[i] += sorted_desc[j];
    }
    loads.iter().copied().fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::heuristics::lpt::lpt_sorted;

    /// Karmarkar and Karp's example, worked by hand. Two pads: 8 and 7 leave 1; 6 and 5 leave 1;
    /// 4 and 1 leave 3; 3 and 1 leave 2, so the loads are (30 + 2) / 2 = 16 and 14 (the optimum
    /// is 15, {8, 7} and {6, 5, 4}). LPT gives 17: 8 | 7, then 6, 5 and 4 on the lighter pad:
    /// 13 | 13, then 17. Three pads: (8,0,0) and (7,0,0) give (8,7,0); with (6,0,0), heaviest
    /// against lightest, (8,7,6); (5,0,0) and (4,0,0) give (5,4,0); with (8,7,6) reversed,
    /// (11,11,8): makespan 11, the optimum ({8}, {7, 4}, {6, 5}).
    #[test]
    fn largest_differencing_matches_the_hand_computed_example() {
        let p = [8.0, 7.0, 6.0, 5.0, 4.0];
        for (m, expected, loads) in [
            (2, 16.0, vec![16.0, 14.0]),
            (3, 11.0, vec![11.0, 11.0, 8.0]),
        ] {
            let mut pad_of = vec![usize::MAX; p.len()];
            assert_eq!(ldm_sorted(m, &p, &mut pad_of), expected);
            let mut got = vec![0.0; m];
            for (j, &i) in pad_of.iter().enumerate() {
                got[i] += p[j];
            }
            got.sort_by(|a, b| b.total_cmp(a));
            assert_eq!(got, loads);
        }
        let mut pad_of = vec![0; p.len()];
        assert_eq!(lpt_sorted(2, &p, &mut pad_of), 17.0);
    }
}
