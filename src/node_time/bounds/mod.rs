//! Lower bounds on the node time: the root bound `max(p_1, sum/k, ...)`, the cardinality bound
//! that widens it, the Martello–Toth `L2` and a two-class count bin-packing bound, their lift by
//! bisection, and the bin-packing LP bound (`lp.rs`). See `models/node_time.md`, "Lower bounds
//! (root)", "Decision version" and "LP bound".

pub(crate) mod lp;

use crate::node_time::search::CAP_SLACK;
use crate::node_time::REL_TOL;

/// Root lower bound on the optimal makespan for times sorted in decreasing order:
/// `max(p_1, sum/k, max over t >= 1 with t*k < n of p_{tk-t+1} + ... + p_{tk+1})`
/// (1-based; `t = 1` gives `p_k + p_{k+1}`), rounded up when `integral`.
///
/// The last family: among the `t*k + 1` longest jobs some pad holds at least `t + 1` (pigeonhole),
/// and those weigh at least the `t + 1` shortest of them.
pub(crate) fn lower_bound_sorted(pads: usize, sorted_desc: &[f64], integral: bool) -> f64 {
    let n = sorted_desc.len();
    if n == 0 {
        return 0.0;
    }
    let total: f64 = sorted_desc.iter().sum();
    let mut lb = sorted_desc[0].max(total / pads as f64);
    let mut t = 1;
    while t * pads < n {
        let last = t * pads; // 0-based index of job t*k+1
        let s: f64 = sorted_desc[last - t..=last].iter().sum();
        lb = lb.max(s);
        t += 1;
    }
    if integral {
        // sum/k may be fractional; a whole-number optimum is at least its ceiling.
        lb = (lb - 1e-9).ceil().max(0.0);
    }
    lb
}

/// Cardinality bound on the makespan for times sorted in decreasing order: for the `N` longest
/// drones `B` and `s` pads (`1 <= s <= k`), the `s` pads that hold the most of `B` hold at least
/// `h = s floor(N/k) + min(s, N mod k)` of them (the counts of a balanced assignment), so they
/// weigh at least the `h` shortest drones of `B`, and one of them at least a share `1/s` of
/// that. The bound is the largest such share over `N` and `s`, rounded up when `integral`.
///
/// It contains the root bound ([`lower_bound_sorted`]: `N = 1` gives `p_1`, `N = n, s = k` the
/// volume, `N = t k + 1, s = 1` the pigeonhole family) and widens it: when most pads must hold
/// the same number of long drones, the bound is their average, while the pads that hold one
/// fewer absorb the longest drones and every short one (Frangioni et al.'s non-uniform classes,
/// where it is the optimum). See `models/node_time.md`, "Lower bounds (root)".
///
/// Complexity `O(n k)`.
pub(crate) fn cardinality_bound(pads: usize, sorted_desc: &[f64], integral: bool) -> f64 {
    let n = sorted_desc.len();
    // prefix[i] = p_1 + ... + p_i; the `h` shortest of the `N` longest weigh prefix[N] - prefix[N - h].
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    for &x in sorted_desc {
        prefix.push(prefix.last().copied().unwrap_or(0.0) + x);
    }
    let mut lb = 0.0_f64;
    for big in 1..=n {
        let (each, extra) = (big / pads, big % pads);
        for s in 1..=pads.min(big) {
            let held = s * each + s.min(extra);
            lb = lb.max((prefix[big] - prefix[big - held]) / s as f64);
        }
    }
    if integral {
        lb = (lb - 1e-9).ceil().max(0.0);
    }
    lb
}

/// Martello–Toth lower bound `L2` on the number of bins of capacity `cap` that hold items `p`
/// (sorted decreasingly, all `> 0`).
///
/// For `alpha` in `{0} ∪ {p_j <= cap/2}`: `J1 = {p > cap - alpha}`, `J2 = {cap/2 < p <= cap - alpha}`,
/// `J3 = {alpha <= p <= cap/2}`;
/// `L(alpha) = |J1| + |J2| + max(0, ceil((p(J3) - (|J2| cap - p(J2))) / cap))`, `L2 = max L(alpha)`.
/// Items of `J1 ∪ J2` pairwise cannot share a bin, nothing of `J3` fits with `J1`, and `J3` needs
/// its volume beyond the room left in the `J2` bins. Returns `usize::MAX` when an item exceeds `cap`.
///
/// Complexity `O(n d)`, `d` the number of distinct values `<= cap/2`.
pub(crate) fn l2_bins(p: &[f64], cap: f64) -> usize {
    if p.is_empty() {
        return 0;
    }
    if p[0] > cap {
        return usize::MAX;
    }
    let half = cap / 2.0;
    let mut best = 0usize;
    let mut alphas: Vec<f64> = vec![0.0];
    for &v in p.iter().filter(|&&v| v <= half) {
        if alphas.last() != Some(&v) {
            alphas.push(v);
        }
    }
    for &alpha in &alphas {
        let (mut n12, mut n2, mut s2, mut s3) = (0usize, 0usize, 0.0, 0.0);
        for &v in p {
            if v > cap - alpha {
                n12 += 1;
            } else if v > half {
                n12 += 1;
                n2 += 1;
                s2 += v;
            } else if v >= alpha {
                s3 += v;
            }
        }
        let extra = (s3 - (n2 as f64 * cap - s2)) / cap;
        // A little below the exact quotient, so rounding never overstates the bound.
        let extra = if extra > 0.0 {
            (extra - 1e-9).ceil().max(0.0) as usize
        } else {
            0
        };
        best = best.max(n12 + extra);
    }
    best
}

/// Two-class cardinality bound on the number of bins of capacity `cap` that hold items `p`
/// (sorted decreasingly, all `> 0`): the largest value of `n_B x + n_M y` over the weights `x`
/// for every "big" item (`p >= a`) and `y` for every "medium" one (`b <= p < a`, shorter items
/// weigh 0) such that every bin's items weigh at most 1, maximised over the thresholds `a > cap/4`
/// and `b > cap/8` taken among the item lengths. A bin that holds `i` big items holds at most
/// `j_i` medium ones (the `i` shortest big and `j_i` shortest medium items fit, one more medium
/// does not), so the constraints `i x + j_i y <= 1` cover every bin; the items weigh
/// `n_B x + n_M y` in total, hence at least that many bins. For each pair of thresholds the
/// two-variable linear programme is solved at its vertices. Returns `f64::INFINITY` when an item
/// exceeds `cap`.
///
/// It catches what `L2` does not, e.g. twelve items of at least `0.4 cap` with thirteen of
/// `0.19 cap` to `0.37 cap` on nine bins (see `models/node_time.md`, "Decision version").
///
/// Complexity `O(d_a d_b n)`, `d_a` and `d_b` the numbers of distinct lengths above `cap/4` and
/// `cap/8`.
#[cfg(test)]
fn count_bound(p: &[f64], cap: f64) -> f64 {
    if p.first().is_some_and(|&v| v > cap) {
        return f64::INFINITY;
    }
    let mut rows = Vec::new();
    threshold_pairs(p, cap)
        .map(|(nb, ne)| pair_value(p, cap, nb, ne, &mut rows))
        .fold(0.0, f64::max)
}

/// The thresholds `(n_B, n_B + n_M)` (end indices of the big and medium items in `p`) over which
/// [`count_bound`] maximises: big items longer than `cap/4`, medium ones longer than `cap/8`, each
/// class ending at a change of length.
fn threshold_pairs(p: &[f64], cap: f64) -> impl Iterator<Item = (usize, usize)> + '_ {
    let n = p.len();
    (1..=n)
        .take_while(move |&nb| p[nb - 1] > cap / 4.0)
        .filter(move |&nb| nb == n || p[nb] != p[nb - 1])
        .flat_map(move |nb| {
            (nb..=n)
                .take_while(move |&ne| ne == nb || p[ne - 1] > cap / 8.0)
                .filter(move |&ne| ne == nb || ne == n || p[ne] != p[ne - 1])
                .map(move |ne| (nb, ne))
        })
}

/// The weight of the items `p` (sorted decreasingly, all `<= cap`) under the best weights `x` for
/// the big items `p[..nb]` and `y` for the medium ones `p[nb..ne]` (see [`count_bound`]). `rows`
/// is scratch space. Nonincreasing in `cap`: a larger capacity only raises the counts `j_i` and
/// `i_max`, which tightens the constraints.
#[cfg(test)]
fn pair_value(p: &[f64], cap: f64, nb: usize, ne: usize, rows: &mut Vec<(f64, f64)>) -> f64 {
    pair_value_over(p, cap, nb, ne, rows, 0.0)
}

/// [`pair_value`] when it exceeds `floor`; otherwise some value `<= floor` (the linear programme
/// is skipped when its simple bound `n_B / i_max + n_M / j_0` is at most `floor`).
fn pair_value_over(
    p: &[f64],
    cap: f64,
    nb: usize,
    ne: usize,
    rows: &mut Vec<(f64, f64)>,
    floor: f64,
) -> f64 {
    // Rows (i, j_i): the i shortest big items and as many of the shortest medium ones.
    rows.clear();
    let mut big_load = 0.0;
    let mut j = 0;
    let mut med_load = 0.0;
    while j < ne - nb && med_load + p[ne - 1 - j] <= cap {
        med_load += p[ne - 1 - j];
        j += 1;
    }
    let mut i = 0;
    loop {
        rows.push((i as f64, j as f64));
        if i == nb || big_load + p[nb - 1 - i] > cap {
            break;
        }
        big_load += p[nb - 1 - i];
        i += 1;
        while j > 0 && big_load + med_load > cap {
            j -= 1;
            med_load -= p[ne - 1 - j];
        }
        if j == 0 {
            med_load = 0.0;
        }
    }
    if rows.len() == 1 {
        // Not even the shortest big item fits.
        return f64::INFINITY;
    }
    let (n_big, n_med) = (nb as f64, (ne - nb) as f64);
    let (i_max, j_0) = (rows[rows.len() - 1].0, rows[0].1);
    let most = n_big / i_max + if j_0 > 0.0 { n_med / j_0 } else { 0.0 };
    if most <= floor {
        return most;
    }
    let rows = &rows[..];
    let feasible = |x: f64, y: f64| {
        x >= 0.0 && y >= 0.0 && rows.iter().all(|&(i, j)| i * x + j * y <= 1.0 + 1e-12)
    };
    let mut best = 0.0_f64;
    let mut consider = |x: f64, y: f64| {
        if feasible(x, y) {
            best = best.max(n_big * x + n_med * y);
        }
    };
    for (a, &(i1, j1)) in rows.iter().enumerate() {
        if i1 > 0.0 {
            consider(1.0 / i1, 0.0);
        }
        if j1 > 0.0 {
            consider(0.0, 1.0 / j1);
        }
        for &(i2, j2) in &rows[a + 1..] {
            let det = i1 * j2 - i2 * j1;
            if det != 0.0 {
                consider((j2 - j1) / det, (i1 - i2) / det);
            }
        }
    }
    best
}

/// Bins of capacity `cap` needed for the items `p` (sorted decreasingly, all `> 0`) by the
/// larger of `L2` and the two-class cardinality bound; `usize::MAX` when an item exceeds `cap`.
#[cfg(test)]
fn bins_bound(p: &[f64], cap: f64) -> usize {
    let l2 = l2_bins(p, cap);
    if l2 == usize::MAX {
        return l2;
    }
    // A little below the exact value, so rounding never overstates the bound.
    let count = (count_bound(p, cap) - 1e-9).ceil().max(0.0) as usize;
    l2.max(count)
}

/// Largest `c` in `[lo, hi)` found by bisection with `L2(c) > k` or the two-class count bound
/// above `k`, i.e. proven `nt > c`; `None` when neither holds at `lo`. Any such `c` is a valid
/// bound because feasibility is monotone in `c`. The count bound is a maximum over pairs of
/// thresholds of values nonincreasing in `c`, so only the pairs above `k` at `lo` are evaluated
/// during the bisection.
pub(crate) fn bound_lift(p: &[f64], k: usize, lo: f64, hi: f64, integral: bool) -> Option<f64> {
    let widen = |c: f64| if integral { c } else { c * (1.0 + CAP_SLACK) };
    // A little above `k`, so rounding never overstates the count bound.
    let target = k as f64 + 1e-9;
    let mut rows = Vec::new();
    let pairs: Vec<(usize, usize)> = threshold_pairs(p, widen(lo))
        .filter(|&(nb, ne)| pair_value_over(p, widen(lo), nb, ne, &mut rows, target) > target)
        .collect();
    let mut proves = |c: f64| {
        l2_bins(p, c) > k
            || pairs
                .iter()
                .any(|&(nb, ne)| pair_value_over(p, c, nb, ne, &mut rows, target) > target)
    };
    if pairs.is_empty() && l2_bins(p, widen(lo)) <= k {
        return None;
    }
    Some(largest_refuted(lo, hi, integral, |c| {
        Some(proves(widen(c)))
    }))
}

/// Largest capacity found refuted by bisection in `[fail, ok)`, `fail` known refuted: stops at a
/// width of 1 min (whole minutes, bisecting at whole minutes) or `REL_TOL` relative, after 60
/// steps, or when `refutes` returns `None` (a spent budget). Feasibility is monotone in the
/// capacity, so any refuted capacity is a valid lower bound.
pub(crate) fn largest_refuted(
    mut fail: f64,
    mut ok: f64,
    integral: bool,
    mut refutes: impl FnMut(f64) -> Option<bool>,
) -> f64 {
    for _ in 0..60 {
        if integral {
            if ok - fail <= 1.0 {
                break;
            }
        } else if ok - fail <= REL_TOL * ok {
            break;
        }
        let mid = if integral {
            ((fail + ok) / 2.0).floor()
        } else {
            0.5 * (fail + ok)
        };
        match refutes(mid) {
            Some(true) => fail = mid,
            Some(false) => ok = mid,
            None => break,
        }
    }
    fail
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// Fewest bins of capacity `cap` for the items `p`, by the exact dynamic programme over
    /// subsets: for each set of packed items the lexicographically least (bins, load of the open
    /// bin), items added one at a time.
    fn min_bins(p: &[f64], cap: f64) -> usize {
        let n = p.len();
        let mut best = vec![(usize::MAX, f64::INFINITY); 1 << n];
        best[0] = (1, 0.0);
        for mask in 0..1usize << n {
            let (bins, load) = best[mask];
            if bins == usize::MAX {
                continue;
            }
            for (j, &v) in p.iter().enumerate() {
                if mask & (1 << j) != 0 {
                    continue;
                }
                let next = if load + v <= cap {
                    (bins, load + v)
                } else {
                    (bins + 1, v)
                };
                let slot = &mut best[mask | (1 << j)];
                if next.0 < slot.0 || (next.0 == slot.0 && next.1 < slot.1) {
                    *slot = next;
                }
            }
        }
        best[(1 << n) - 1].0
    }

    /// Seven items of 3.4 in bins of 10: three never share a bin (10.2), so the weight 1/2 on
    /// each is valid and the bound is 7/2 = 3.5, i.e. 4 bins. `L2` sees only the volume:
    /// every item is below 5 and `ceil(23.8 / 10) = 3`.
    #[test]
    fn count_bound_counts_items_that_fit_two_per_bin() {
        let p = [3.4; 7];
        assert!((count_bound(&p, 10.0) - 3.5).abs() < 1e-12);
        assert_eq!(l2_bins(&p, 10.0), 3);
        assert_eq!(bins_bound(&p, 10.0), 4);
        assert_eq!(min_bins(&p, 10.0), 4);
    }

    /// Four items of 45 and five of 24 in bins of 100. A bin holds at most four 24s (0 of 45),
    /// one 45 with two 24s (93; a third makes 117), or two 45s alone (90; a 24 makes 114). The
    /// weights 1/2 (45) and 1/4 (24) satisfy `4y <= 1`, `x + 2y <= 1`, `2x <= 1`, and are the best
    /// vertex: 4/2 + 5/4 = 3.25, so 4 bins; the volume (300) and `L2` say 3. The same items on 3
    /// pads therefore need more than 100 min; the optimum is 114 ({45, 45, 24} and twice
    /// {45, 24, 24}), which the exact search confirms.
    #[test]
    fn count_bound_weighs_two_classes_where_l2_sees_volume() {
        let p = [45.0, 45.0, 45.0, 45.0, 24.0, 24.0, 24.0, 24.0, 24.0];
        assert!((count_bound(&p, 100.0) - 3.25).abs() < 1e-12);
        assert_eq!(l2_bins(&p, 100.0), 3);
        assert_eq!(bins_bound(&p, 100.0), 4);
        assert_eq!(min_bins(&p, 100.0), 4);
        let s = crate::node_time::exact(3, &p, &crate::node_time::Limits::default()).unwrap();
        assert_eq!(s.makespan_min, 114.0);
    }

    /// The bound never exceeds the fewest bins (exact dynamic programme) on 3,000 random cases
    /// of at most 10 items, real and whole lengths, capacities from the longest item to the
    /// total, or lengths 20 to 50 in bins of 100; and it is sometimes stronger than `L2`, so the
    /// check is not vacuous. Each pair of thresholds gives a value nonincreasing in the capacity.
    #[test]
    fn count_bound_never_exceeds_the_fewest_bins() {
        let mut rng = ChaCha8Rng::seed_from_u64(50);
        let mut stronger = 0;
        for case in 0..3000 {
            let n = rng.random_range(1..=10);
            let whole = case % 2 == 0;
            // A third of the cases: lengths from 20 to 50 and capacity 100, where few items
            // share a bin and the count matters.
            let (lo, hi) = if case % 3 == 2 { (20, 50) } else { (1, 40) };
            let mut p: Vec<f64> = (0..n)
                .map(|_| {
                    if whole {
                        f64::from(rng.random_range(lo..=hi))
                    } else {
                        rng.random_range(f64::from(lo)..f64::from(hi))
                    }
                })
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let total: f64 = p.iter().sum();
            let cap = if case % 3 == 2 {
                100.0
            } else {
                rng.random_range(p[0]..=total.max(p[0] + 1e-9))
            };
            let cap = if whole { cap.floor().max(p[0]) } else { cap };
            let exact = min_bins(&p, cap);
            let bound = count_bound(&p, cap);
            assert!(
                bound <= exact as f64 + 1e-9,
                "case {case}: cap {cap} p {p:?}: bound {bound} > {exact} bins"
            );
            assert!(bins_bound(&p, cap) <= exact, "case {case}");
            // Every pair of thresholds is nonincreasing in the capacity, which the lift relies on.
            let mut rows = Vec::new();
            for (nb, ne) in threshold_pairs(&p, cap) {
                let here = pair_value(&p, cap, nb, ne, &mut rows);
                let wider = pair_value(&p, cap * 1.1, nb, ne, &mut rows);
                assert!(wider <= here + 1e-12, "case {case}: ({nb}, {ne})");
                // The shortcut of the lift decides like the full programme.
                for floor in [1.0, 2.0, 3.0, here - 1e-6, here + 1e-6] {
                    let over = pair_value_over(&p, cap, nb, ne, &mut rows, floor);
                    assert_eq!(over > floor, here > floor, "case {case}: floor {floor}");
                }
            }
            stronger += usize::from(bins_bound(&p, cap) > l2_bins(&p, cap));
        }
        assert!(stronger >= 30, "stronger than L2 in only {stronger} cases");
    }

    /// A 30-drone swarm on 9 pads whose optimum (202.152 min, pad {82.27, 81.17, 38.71}) lies
    /// 5.7 min above `sum/9` = 196.483: twelve drones of 81.17 min or more and thirteen of 38.71 to
    /// 74.92. Below the optimum a pad holds two of the twelve and nothing of the thirteen, one
    /// and at most two of them, or at most four of them, so weights 1/2 and 1/4 sum to
    /// 12/2 + 13/4 = 9.25 > 9 pads. An assignment with that makespan is given (and checked), so
    /// it is the optimum: the lift reaches it and never passes it, and the exact search proves it.
    #[test]
    fn count_bound_lifts_a_far_bound_to_the_optimum() {
        let times: Vec<f64> = vec![
            54.49978123107401,
            91.94924194720863,
            74.92378454200538,
            3.2334332179503757,
            51.376264535415,
            40.69950956099767,
            4.507486052274642,
            48.25952465184519,
            95.07536988957618,
            97.8358126579111,
            42.76134290543398,
            46.320018545370864,
            7.335948289444916,
            52.743138153591595,
            38.71455233560278,
            92.11481725671348,
            81.16909006043325,
            85.01426442389788,
            98.83063561513653,
            83.50427494699228,
            68.88829211606598,
            82.26845251472304,
            6.575930264312698,
            93.00570143118915,
            83.67252769652556,
            14.784321923245479,
            48.6305614703886,
            88.01493207810168,
            43.758394051630795,
            47.87876575272594,
        ];
        let assignment: Vec<Vec<usize>> = vec![
            vec![7, 18, 26],
            vec![4, 9, 28],
            vec![8, 11, 13],
            vec![0, 23, 29],
            vec![10, 19, 20],
            vec![2, 5, 24],
            vec![1, 3, 12, 22, 27],
            vec![6, 15, 17, 25],
            vec![14, 16, 21],
        ];
        let mut seen: Vec<usize> = assignment.iter().flatten().copied().collect();
        seen.sort_unstable();
        assert_eq!(seen, (0..30).collect::<Vec<_>>());
        let pad = crate::node_time::makespan_of(&times, &assignment);
        assert!((pad - (times[21] + times[16] + times[14])).abs() < 1e-12);
        let mut p = times.clone();
        p.sort_by(|a, b| b.total_cmp(a));
        assert!(count_bound(&p, pad - 1e-6) >= 9.25 - 1e-12);
        assert!(count_bound(&p, pad + 1e-6) <= 9.0 + 1e-9);
        let sum_over_pads = p.iter().sum::<f64>() / 9.0;
        assert!((sum_over_pads - 196.4829).abs() < 1e-3);
        let lifted = bound_lift(&p, 9, sum_over_pads, pad + 1.0, false).expect("a lift");
        assert!(
            lifted <= pad && lifted >= pad * (1.0 - 2e-9),
            "{lifted} against {pad}"
        );
        let s = crate::node_time::exact(9, &times, &crate::node_time::Limits::default()).unwrap();
        assert_eq!(s.status, crate::solver::SolveStatus::Optimal);
        assert!((s.makespan_min - pad).abs() <= 1e-9 * pad);
    }

    /// Eight drones of 10, 10, 9, 9, 8, 8, 5, 4 min (63 in all) on 3 pads. The two pads that hold
    /// the most drones hold at least 6 (3 + 3 + 2 is the most balanced), which weigh at least the
    /// six shortest, 4 + 5 + 8 + 8 + 9 + 9 = 43, so one of them at least 21.5, i.e. 22 (whole
    /// minutes). The root bound says 21 (the volume, and `p_5 + p_6 + p_7`), and neither `L2`
    /// nor the count bound refutes 21. The optimum is 22 ({10, 10}, {9, 8, 5}, {9, 8, 4}), by
    /// brute force.
    #[test]
    fn cardinality_bound_averages_the_pads_that_must_hold_three() {
        let p = [10.0, 10.0, 9.0, 9.0, 8.0, 8.0, 5.0, 4.0];
        assert_eq!(cardinality_bound(3, &p, true), 22.0);
        assert_eq!(cardinality_bound(3, &p, false), 21.5);
        assert_eq!(lower_bound_sorted(3, &p, true), 21.0);
        assert_eq!(bound_lift(&p, 3, 21.0, 22.0, true), None);
        let limits = crate::node_time::Limits::default();
        let opt = crate::node_time::brute::brute(3, &p, &limits).unwrap();
        assert_eq!(opt.makespan_min, 22.0);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(2000))]

        /// The cardinality bound never exceeds the optimum (brute force) on up to 9 drones, whole
        /// or real minutes, from a wide range or a narrow one near 100 (few drones per pad, where
        /// the counts bind), and never falls below the root bound it contains.
        #[test]
        fn cardinality_bound_never_exceeds_the_brute_force_optimum(
            pads in 2usize..=4,
            base in proptest::collection::vec(1u32..=40, 2..=9),
            frac in proptest::collection::vec(0.0f64..1.0, 9),
            real in proptest::bool::ANY,
            narrow in proptest::bool::ANY,
        ) {
            let mut p: Vec<f64> = base
                .iter()
                .zip(&frac)
                .map(|(&w, &f)| {
                    let w = if narrow { 80.0 + f64::from(w) / 2.0 } else { f64::from(w) };
                    if real { w + f } else { w.floor() }
                })
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let limits = crate::node_time::Limits::default();
            let opt = crate::node_time::brute::brute(pads, &p, &limits).unwrap().makespan_min;
            let cb = cardinality_bound(pads, &p, !real);
            proptest::prop_assert!(cb <= opt * (1.0 + 1e-12), "{cb} > {opt}: {pads} pads {p:?}");
            let root = lower_bound_sorted(pads, &p, !real);
            proptest::prop_assert!(cb >= root * (1.0 - 1e-12), "{cb} < root {root}");
        }
    }

    /// The bound is the optimum, and above the root bound, on many narrow random cases (3 to 9
    /// drones of 80 to 100 whole minutes on 2 to 4 pads), so the test above is not vacuous.
    #[test]
    fn cardinality_bound_is_often_the_optimum_above_the_root_bound() {
        let mut rng = ChaCha8Rng::seed_from_u64(190);
        let limits = crate::node_time::Limits::default();
        let mut tight_above_root = 0;
        for _ in 0..500 {
            let pads = rng.random_range(2..=4);
            let n = rng.random_range(3..=9);
            let mut p: Vec<f64> = (0..n)
                .map(|_| f64::from(rng.random_range(80..=100)))
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let opt = crate::node_time::brute::brute(pads, &p, &limits)
                .unwrap()
                .makespan_min;
            let cb = cardinality_bound(pads, &p, true);
            assert!(cb <= opt, "{cb} > {opt}: {pads} pads {p:?}");
            if cb == opt && cb > lower_bound_sorted(pads, &p, true) {
                tight_above_root += 1;
            }
        }
        assert!(tight_above_root >= 20, "{tight_above_root}");
    }
}
