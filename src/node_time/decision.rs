//! Decision version of the node time: "do all drones fit on the `k` pads with every load `<= C`?"
//! (bin packing with `k` bins of capacity `C`), the Martello–Toth `L2` bin-packing bound and a
//! swap/move local search for the upper bound. See `models/node_time.md`, "Decision version".
//!
//! The feasibility check is a bin-completion search (Korf 2002; Dell'Amico & Martello 1995): pads
//! are filled one after another; each pad first takes the longest drone still unplaced, then a
//! maximal set of further drones (no unplaced drone still fits), and the total waste
//! `sum_i (C - L_i)` may not exceed `k C - sum_j p_j`. Failed states (the set of unplaced drones,
//! the number of pads filled) are remembered.

use super::{Limits, REL_TOL};
use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};
use std::time::Instant;

/// How often (in nodes) the search reads the clock.
const CLOCK_EVERY_NODES: u64 = 1024;

/// Real-valued times are checked against `C (1 + CAP_SLACK)`: exact arithmetic would fill the
/// last pad to exactly its share of the waste, and rounding must not turn that into a failure.
/// A failure then proves `nt > C`; a success returns an assignment whose makespan is recomputed.
pub(crate) const CAP_SLACK: f64 = 1e-11;

/// Largest number of failed states remembered by one decision search.
const MEMO_MAX_STATES: usize = 1 << 21;

/// Multiply-rotate hash of the memo keys (bitsets of placed drones): the keys are exact, the hash
/// only spreads them, so a cheap one serves better than the default keyed hash.
#[derive(Default)]
pub(crate) struct WordHasher(u64);

impl Hasher for WordHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517c_c1b7_2722_0a95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// Failed states of the bin-completion search: the bitset of placed drones, then the number of
/// full pads.
pub(crate) type Memo = HashSet<Box<[u64]>, BuildHasherDefault<WordHasher>>;

/// Outcome of a decision search.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decision {
    /// Every drone fits; the pads are in the search's `pad_of`.
    Fits,
    /// Proven: no assignment has every load `<= C`.
    DoesNotFit,
    /// A node or time limit stopped the search.
    Stopped,
}

/// Node and time budget shared by every search of one solve.
pub(crate) struct Budget<'l> {
    /// Placements made so far (all phases).
    pub nodes: u64,
    /// Start of the solve.
    pub start: Instant,
    /// The caller's limits.
    pub limits: &'l Limits,
}

impl Budget<'_> {
    /// Counts one placement; true when a limit is reached.
    pub(crate) fn tick(&mut self) -> bool {
        self.nodes += 1;
        if let Some(max_nodes) = self.limits.node_limit {
            if self.nodes >= max_nodes {
                return true;
            }
        }
        if let Some(t) = self.limits.time_limit_s {
            if self.nodes.is_multiple_of(CLOCK_EVERY_NODES)
                && self.start.elapsed().as_secs_f64() >= t
            {
                return true;
            }
        }
        false
    }
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

/// Bin-completion search for one capacity `cap`.
pub(crate) struct BinCompletion<'a> {
    /// `p[j]`, decreasing, all `> 0`.
    p: &'a [f64],
    /// Number of pads `k`.
    k: usize,
    cap: f64,
    /// Rounding allowance of the waste and maximality prunings: 0 for whole minutes,
    /// `1e-12 n C` otherwise (the last pad's room equals the waste left in exact arithmetic).
    tol: f64,
    used: Vec<bool>,
    /// Bitset of the placed drones (memo key).
    words: Vec<u64>,
    /// Pad of each drone when the search answers `Fits`.
    pub pad_of: Vec<usize>,
    memo: Memo,
    /// Per pad index `b`: the candidates of `fill_pad(b)` and their suffix sums (kept between
    /// calls, so the search does not allocate per node).
    cand_at: Vec<Vec<usize>>,
    suffix_at: Vec<Vec<f64>>,
    /// Times of the drones taken by the pad being checked for dominance.
    taken_buf: Vec<f64>,
}

impl<'a> BinCompletion<'a> {
    /// A search for `k` pads of capacity `cap` over the drones `p` (decreasing, positive).
    ///
    /// `memo` holds failed states from earlier searches with a capacity `>= cap` (a state that
    /// cannot be completed under a capacity cannot under a smaller one); give an empty set
    /// otherwise. [`BinCompletion::into_memo`] hands it back.
    pub(crate) fn new(p: &'a [f64], k: usize, cap: f64, integral: bool, memo: Memo) -> Self {
        let n = p.len();
        BinCompletion {
            p,
            k,
            cap,
            tol: if integral {
                0.0
            } else {
                1e-12 * (n as f64 + 1.0) * cap
            },
            used: vec![false; n],
            words: vec![0; n / 64 + 2],
            pad_of: vec![0; n],
            memo,
            cand_at: vec![Vec::new(); k],
            suffix_at: vec![Vec::new(); k],
            taken_buf: Vec::new(),
        }
    }

    /// The failed states found so far (valid for every capacity `<= cap`).
    pub(crate) fn into_memo(self) -> Memo {
        self.memo
    }

    /// Decides whether every drone fits on the `k` pads with loads `<= cap`.
    pub(crate) fn decide(&mut self, budget: &mut Budget) -> Decision {
        let total: f64 = self.p.iter().sum();
        let waste = self.k as f64 * self.cap - total;
        if self.p.first().is_some_and(|&v| v > self.cap) || waste < -self.tol {
            return Decision::DoesNotFit;
        }
        if l2_bins(self.p, self.cap) > self.k {
            return Decision::DoesNotFit;
        }
        self.fill_pad(0, waste, budget)
    }

    fn set(&mut self, j: usize, on: bool) {
        self.used[j] = on;
        self.words[j / 64] ^= 1u64 << (j % 64);
    }

    /// Fills pad `b` (pads `0..b` are full) with at most `waste` minutes left idle in total.
    fn fill_pad(&mut self, b: usize, waste: f64, budget: &mut Budget) -> Decision {
        let n = self.p.len();
        let Some(first) = (0..n).find(|&j| !self.used[j]) else {
            return Decision::Fits;
        };
        if b >= self.k {
            return Decision::DoesNotFit;
        }
        // Drones longer than cap/2 pairwise need different pads.
        let half = self.cap / 2.0;
        let mut long = 0;
        for j in first..n {
            if self.used[j] {
                continue;
            }
            if self.p[j] > half {
                long += 1;
            } else {
                break;
            }
        }
        if long > self.k - b {
            return Decision::DoesNotFit;
        }
        let last = self.words.len() - 1;
        self.words[last] = b as u64;
        if self.memo.contains(&self.words[..]) {
            return Decision::DoesNotFit;
        }
        let mut cand = std::mem::take(&mut self.cand_at[b]);
        let mut suffix = std::mem::take(&mut self.suffix_at[b]);
        cand.clear();
        cand.extend((first + 1..n).filter(|&j| !self.used[j]));
        suffix.clear();
        suffix.resize(cand.len() + 1, 0.0);
        for q in (0..cand.len()).rev() {
            suffix[q] = suffix[q + 1] + self.p[cand[q]];
        }
        self.set(first, true);
        self.pad_of[first] = b;
        let out = if budget.tick() {
            Decision::Stopped
        } else {
            let r = self.cap - self.p[first];
            self.complete(b, waste, &cand, &suffix, 0, r, f64::INFINITY, budget)
        };
        self.set(first, false);
        self.cand_at[b] = cand;
        self.suffix_at[b] = suffix;
        if out == Decision::DoesNotFit && self.memo.len() < MEMO_MAX_STATES {
            // The key as on entry: `set` restored the placed drones, `words[last]` is still `b`.
            self.words[last] = b as u64;
            self.memo.insert(self.words.clone().into_boxed_slice());
        }
        out
    }

    /// Whether the pad just filled (the first drone and the taken `cand`, room `r` left) is
    /// dominated (Korf, "An improved algorithm for optimal bin packing", IJCAI 2003): a drone `e`
    /// left out could replace one taken drone `i` (`p_i < p_e <= p_i + r`) or two, `i` and `j`
    /// (`p_i + p_j <= p_e <= p_i + p_j + r`). Swapping them with `e`'s pad in any completion keeps
    /// that pad within `C` and this one too, so whenever a completion exists, one exists through
    /// an undominated pad. Real-valued times get the margin `tol` against rounding.
    fn dominated(&mut self, cand: &[usize], r: f64) -> bool {
        let mut taken = std::mem::take(&mut self.taken_buf);
        taken.clear();
        taken.extend(cand.iter().filter(|&&j| self.used[j]).map(|&j| self.p[j]));
        let (tol, p, used) = (self.tol, self.p, &self.used);
        let replaces = |pe: f64| {
            taken.iter().enumerate().any(|(a, &pi)| {
                (pi + tol < pe && pe <= pi + r - tol)
                    || taken[a + 1..]
                        .iter()
                        .any(|&pj| pi + pj + tol <= pe && pe <= pi + pj + r - tol)
            })
        };
        let found = cand.iter().filter(|&&j| !used[j]).any(|&j| replaces(p[j]));
        self.taken_buf = taken;
        found
    }

    /// Chooses which of `cand[pos..]` join pad `b`, whose room is `r`; `min_out` is the shortest
    /// fitting drone left out so far (the pad must end up with less room than that).
    #[allow(clippy::too_many_arguments)]
    fn complete(
        &mut self,
        b: usize,
        waste: f64,
        cand: &[usize],
        suffix: &[f64],
        mut pos: usize,
        r: f64,
        min_out: f64,
        budget: &mut Budget,
    ) -> Decision {
        // Drones too long for the room are left out; they stay too long for any smaller room.
        while pos < cand.len() && self.p[cand[pos]] > r {
            pos += 1;
        }
        // Even taking every remaining candidate, the pad wastes more than allowed, or a drone left
        // out would still fit (the pad is not maximal).
        let least_room = r - suffix[pos];
        if least_room > waste + self.tol || min_out <= least_room - self.tol {
            return Decision::DoesNotFit;
        }
        if pos == cand.len() {
            if self.dominated(cand, r) {
                return Decision::DoesNotFit;
            }
            return self.fill_pad(b + 1, waste - r, budget);
        }
        let j = cand[pos];
        let v = self.p[j];
        // Take drone j.
        self.set(j, true);
        self.pad_of[j] = b;
        let out = if budget.tick() {
            Decision::Stopped
        } else {
            self.complete(b, waste, cand, suffix, pos + 1, r - v, min_out, budget)
        };
        self.set(j, false);
        if out != Decision::DoesNotFit {
            return out;
        }
        // Leave drone j out, and with it every later drone of the same length (taking a later
        // copy instead of j gives the same pad).
        let mut q = pos + 1;
        while q < cand.len() && self.p[cand[q]] == v {
            q += 1;
        }
        self.complete(b, waste, cand, suffix, q, r, min_out.min(v), budget)
    }
}

/// Largest `c` in `[lo, hi)` found by bisection with `L2(c) > k`, i.e. proven `nt > c`; `None`
/// when `L2(lo) <= k`. Any such `c` is a valid bound because feasibility is monotone in `c`.
pub(crate) fn l2_lift(p: &[f64], k: usize, lo: f64, hi: f64, integral: bool) -> Option<f64> {
    let widen = |c: f64| if integral { c } else { c * (1.0 + CAP_SLACK) };
    if l2_bins(p, widen(lo)) <= k {
        return None;
    }
    let (mut fail, mut ok) = (lo, hi);
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
        if l2_bins(p, widen(mid)) > k {
            fail = mid;
        } else {
            ok = mid;
        }
    }
    Some(fail)
}
