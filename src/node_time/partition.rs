//! Exact node time for many drones per pad: sequential partitioning, the fullest pad first, with
//! every pad's set of drones enumerated by meet in the middle (Horowitz–Sahni subset sums).
//! See `models/node_time.md`, "Sequential partitioning".
//!
//! Order the pads of any assignment by decreasing load; the first is a set `A` with
//! `s(A) >= sum/k` and the makespan is `s(A)`. So
//!
//! ```text
//! nt = min { s(A) : s(A) >= LB, the other drones fit on k - 1 pads with loads <= s(A) }
//! ```
//!
//! and the sets `A` are tried in increasing `s(A)` from the lower bound `LB`: the first that
//! completes is optimal. Completing is the decision version on `b` pads of capacity `c`: the
//! fullest of them takes a set `B` with `s(B)` in `[S_R / b, c]` (`S_R` the drones left), the other
//! `b - 1` pads then get capacity `s(B)`; two pads need one set `B` holding the longest drone with
//! `s(B)` in `[S_R - c, c]`. Each window query splits the drones left into two halves, lists both
//! halves' subset sums in increasing order and walks the two lists against each other:
//! `O(2^(r/2))` for `r` drones, plus one step per set found.
//!
//! Real-valued charge times near `sum/k` leave no pad of the optimum with room for a combinatorial
//! argument, and there the assignment search and bin completion explore up to `2^r` sets; the
//! window queries see only the few sets whose load lies in the window.

use super::decision::{Budget, Decision};
use super::le_tol;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// Most drones the method takes: subsets are `u64` masks, and each half list has up to
/// `2^(n/2)` entries (`2^20` at 40 drones, 16 MiB).
pub(crate) const PARTITION_MAX_DRONES: usize = 40;

/// Relative allowance on every capacity for the rounding of `f64` sums: a refusal at
/// `c (1 + SLACK)` proves that no assignment has loads `<= c`.
const SLACK: f64 = 1e-12;

/// Every subset sum of a set of drones in increasing order, with the subsets as bit masks.
struct SubsetSums {
    sums: Vec<f64>,
    masks: Vec<u64>,
}

impl SubsetSums {
    /// The `2^len` subset sums of the drones `items` (indices into `p`), built by merging the
    /// sorted list with itself shifted by each drone in turn: `O(2^len)`.
    fn new(p: &[f64], items: &[usize]) -> Self {
        let size = 1usize << items.len();
        let mut sums = vec![0.0; size];
        let mut masks = vec![0u64; size];
        let mut next_sums = vec![0.0; size];
        let mut next_masks = vec![0u64; size];
        let mut len = 1;
        for &j in items {
            let v = p[j];
            let bit = 1u64 << j;
            let (mut a, mut b) = (0, 0);
            let (src_s, src_m) = (&sums[..len], &masks[..len]);
            let (dst_s, dst_m) = (&mut next_sums[..2 * len], &mut next_masks[..2 * len]);
            for (out_s, out_m) in dst_s.iter_mut().zip(dst_m.iter_mut()) {
                if b == len || (a < len && src_s[a] <= src_s[b] + v) {
                    *out_s = src_s[a];
                    *out_m = src_m[a];
                    a += 1;
                } else {
                    *out_s = src_s[b] + v;
                    *out_m = src_m[b] | bit;
                    b += 1;
                }
            }
            len *= 2;
            std::mem::swap(&mut sums, &mut next_sums);
            std::mem::swap(&mut masks, &mut next_masks);
        }
        SubsetSums { sums, masks }
    }

    fn len(&self) -> usize {
        self.sums.len()
    }
}

/// The two halves' subset sums of `items`: drones alternate between the halves, so both hold
/// long and short drones.
fn halves(p: &[f64], items: &[usize]) -> (SubsetSums, SubsetSums) {
    let first: Vec<usize> = items.iter().copied().step_by(2).collect();
    let second: Vec<usize> = items.iter().copied().skip(1).step_by(2).collect();
    // The shorter list first: it drives the outer loop.
    (SubsetSums::new(p, &second), SubsetSums::new(p, &first))
}

/// Calls `visit(sum, mask)` for every pair of a subset of `l1` and one of `l2` whose sum lies in
/// `[lo, hi]`, until `visit` returns `false`. Returns `false` when it was stopped that way.
///
/// Both lists increase, so the range of partners of `l1[i]` moves down as `i` grows: two
/// pointers, `O(|l1| + |l2|)` plus one step per pair.
fn for_each_in_window(
    l1: &SubsetSums,
    l2: &SubsetSums,
    lo: f64,
    hi: f64,
    mut visit: impl FnMut(f64, u64) -> bool,
) -> bool {
    let (mut lo_ptr, mut hi_ptr) = (l2.len(), l2.len());
    for i in 0..l1.len() {
        let a = l1.sums[i];
        if a > hi {
            break;
        }
        while hi_ptr > 0 && a + l2.sums[hi_ptr - 1] > hi {
            hi_ptr -= 1;
        }
        while lo_ptr > 0 && a + l2.sums[lo_ptr - 1] >= lo {
            lo_ptr -= 1;
        }
        for q in lo_ptr..hi_ptr {
            if !visit(a + l2.sums[q], l1.masks[i] | l2.masks[q]) {
                return false;
            }
        }
    }
    true
}

/// Pairs of the two lists with sum `>= lo`, in increasing sum: one heap entry per entry of `l1`,
/// pointing at its smallest partner not yet given out (Schroeppel–Shamir's order, on two lists).
struct Ascending<'a> {
    l1: &'a SubsetSums,
    l2: &'a SubsetSums,
    partner: Vec<usize>,
    /// `(sum as ordered bits, index into l1)`; sums are `>= 0`, whose bits order like the values.
    heap: BinaryHeap<Reverse<(u64, usize)>>,
}

impl<'a> Ascending<'a> {
    fn new(l1: &'a SubsetSums, l2: &'a SubsetSums, lo: f64) -> Self {
        let mut partner = vec![0; l1.len()];
        let mut entries = Vec::with_capacity(l1.len());
        let mut q = l2.len();
        for (i, (&a, first)) in l1.sums.iter().zip(partner.iter_mut()).enumerate() {
            while q > 0 && a + l2.sums[q - 1] >= lo {
                q -= 1;
            }
            *first = q;
            if q < l2.len() {
                entries.push(Reverse(((a + l2.sums[q]).to_bits(), i)));
            }
        }
        Ascending {
            l1,
            l2,
            partner,
            heap: BinaryHeap::from(entries),
        }
    }

    /// The next pair: its sum and its mask.
    fn next(&mut self) -> Option<(f64, u64)> {
        let Reverse((bits, i)) = self.heap.pop()?;
        let q = self.partner[i];
        let mask = self.l1.masks[i] | self.l2.masks[q];
        self.partner[i] = q + 1;
        if q + 1 < self.l2.len() {
            let s = self.l1.sums[i] + self.l2.sums[q + 1];
            self.heap.push(Reverse((s.to_bits(), i)));
        }
        Some((f64::from_bits(bits), mask))
    }
}

/// Drones of `mask` in increasing index, i.e. decreasing charge time.
fn members(mask: u64) -> Vec<usize> {
    let mut out = Vec::with_capacity(mask.count_ones() as usize);
    let mut rest = mask;
    while rest != 0 {
        out.push(rest.trailing_zeros() as usize);
        rest &= rest - 1;
    }
    out
}

/// Reads the clock and counts one step; true when a limit is reached.
fn spent(budget: &mut Budget) -> bool {
    if budget.tick() {
        return true;
    }
    budget
        .limits
        .time_limit_s
        .is_some_and(|t| budget.start.elapsed().as_secs_f64() >= t)
}

/// The search: drones `p` (decreasing, positive, at most [`PARTITION_MAX_DRONES`]) and the
/// pads chosen so far.
struct Partition<'a> {
    p: &'a [f64],
    /// The drones of each pad filled so far, fullest first.
    pads: Vec<u64>,
}

impl Partition<'_> {
    /// Decides whether the drones of `rest` fit on `bins` pads with every load `<= cap`; on
    /// `Fits` the pads are appended to `self.pads`.
    fn fits(&mut self, rest: u64, bins: usize, cap: f64, budget: &mut Budget) -> Decision {
        let items = members(rest);
        if items.is_empty() {
            return Decision::Fits;
        }
        let total: f64 = items.iter().map(|&j| self.p[j]).sum();
        let cap_x = cap * (1.0 + SLACK);
        if bins == 1 {
            if total <= cap_x {
                self.pads.push(rest);
                return Decision::Fits;
            }
            return Decision::DoesNotFit;
        }
        if self.p[items[0]] > cap_x || total > bins as f64 * cap_x {
            return Decision::DoesNotFit;
        }
        if items.len() <= bins {
            self.pads.extend(items.iter().map(|&j| 1u64 << j));
            return Decision::Fits;
        }
        if spent(budget) {
            return Decision::Stopped;
        }
        if bins == 2 {
            // One pad holds the longest drone and a load in [total - cap, cap].
            let longest = items[0];
            let (l1, l2) = halves(self.p, &items[1..]);
            let p0 = self.p[longest];
            let mut found = None;
            for_each_in_window(&l1, &l2, total - cap_x - p0, cap_x - p0, |_, mask| {
                found = Some(mask | (1u64 << longest));
                false
            });
            return match found {
                Some(b) => {
                    self.pads.push(b);
                    self.pads.push(rest & !b);
                    Decision::Fits
                }
                None => Decision::DoesNotFit,
            };
        }
        // The fullest of the `bins` pads: load in [total / bins, cap].
        let (l1, l2) = halves(self.p, &items);
        let mut candidates = Vec::new();
        let lo = total / bins as f64 * (1.0 - SLACK);
        for_each_in_window(&l1, &l2, lo, cap_x, |s, mask| {
            candidates.push((s, mask));
            true
        });
        drop((l1, l2));
        for (s, mask) in candidates {
            self.pads.push(mask);
            match self.fits(rest & !mask, bins - 1, s.min(cap), budget) {
                Decision::DoesNotFit => {
                    self.pads.pop();
                }
                other => return other,
            }
        }
        Decision::DoesNotFit
    }
}

/// Exact node time by sequential partitioning for the drones `p` (decreasing, positive, at most
/// [`PARTITION_MAX_DRONES`]) on `m >= 2` pads, from the lower bound `lb` and the incumbent `ub`
/// (pads in `pad_of`, replaced when a better assignment is found).
///
/// Returns (proven, lower bound, incumbent makespan). The lower bound is the load of the fullest
/// pad tried last: every set with a smaller load failed to complete.
pub(crate) fn partition(
    m: usize,
    p: &[f64],
    mut lb: f64,
    ub: f64,
    pad_of: &mut [usize],
    budget: &mut Budget,
) -> (bool, f64, f64) {
    let n = p.len();
    debug_assert!(n <= PARTITION_MAX_DRONES && m >= 2);
    let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
    let items: Vec<usize> = (0..n).collect();
    let (l1, l2) = halves(p, &items);
    let mut ascending = Ascending::new(&l1, &l2, lb * (1.0 - SLACK));
    let mut search = Partition {
        p,
        pads: Vec::with_capacity(m),
    };
    while let Some((s, mask)) = ascending.next() {
        if le_tol(ub, s) {
            // Every assignment whose fullest pad is below s failed: ub is within REL_TOL.
            return (true, lb.max(s.min(ub)), ub);
        }
        lb = lb.max(s * (1.0 - SLACK));
        search.pads.clear();
        search.pads.push(mask);
        match search.fits(all & !mask, m - 1, s, budget) {
            Decision::Fits => {
                let mut found_pad_of = vec![0; n];
                let mut loads = vec![0.0_f64; m];
                for (i, &pad) in search.pads.iter().enumerate() {
                    for j in members(pad) {
                        found_pad_of[j] = i;
                        loads[i] += p[j];
                    }
                }
                let found = loads.iter().copied().fold(0.0, f64::max);
                if found < ub {
                    pad_of.copy_from_slice(&found_pad_of);
                    return (true, lb, found);
                }
                return (true, lb, ub);
            }
            Decision::DoesNotFit => {}
            Decision::Stopped => return (false, lb, ub),
        }
    }
    // Every set was tried: the incumbent is optimal.
    (true, ub, ub)
}
