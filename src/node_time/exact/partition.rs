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

use crate::node_time::search::{Budget, Decision, SearchOutcome, WordHasher};
use crate::node_time::{le_tol, REL_TOL};
use std::cell::RefCell;
use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap};
use std::hash::BuildHasherDefault;

/// Most drones the method takes: subsets are `u64` masks, and each half list has up to
/// `2^(n/2)` entries (`2^20` at 40 drones, 16 MiB).
pub(crate) const PARTITION_MAX_DRONES: usize = 40;

/// Width of the first window of fullest-pad loads, relative to the lower bound (`1.5e-3` min at
/// a bound of 500 min; measured on 30 real-valued drones on 3 to 7 pads: `1e-6` was 10 to 20%
/// slower on 4 to 6 pads, equal on 3).
const FIRST_WINDOW_REL: f64 = 3e-6;

/// Most sets the cache of one window of fullest-pad loads holds (`Partition::cache`); a window
/// with more leaves the completions to list-building window queries.
const CACHE_MAX_SETS: usize = 1 << 16;

/// Most failed cached completions remembered by one search (`Partition::failed`).
const FAILED_MAX_STATES: usize = 1 << 21;

/// Failed cached completions: key `rest | bins << 58` (at most 40 drones, fewer than 40 pads),
/// value the largest capacity under which the drones of `rest` did not fit on `bins` pads.
type Failed = HashMap<u64, f64, BuildHasherDefault<WordHasher>>;

/// Work of a query beyond its node, in cached sets scanned, that counts as one more node of the
/// budget: a query's work grows with `2^(r/2)` for `r` drones left, so counting it keeps the
/// node limit a bound on time here as in the other searches. 16 sets scanned take about 20 ns,
/// as long as a node of bin completion (measured on 30 to 40 drones on 3 to 7 pads).
const WORK_PER_NODE: u64 = 16;

/// Work of listing one subset sum of a window query's two half lists (building them and the
/// walk), in cached sets scanned: about 12 ns against 1.5 ns.
const LIST_WORK: u64 = 8;

/// Relative allowance on every capacity for the rounding of `f64` sums: a refusal at
/// `c (1 + SLACK)` proves that no assignment has loads `<= c`.
const SLACK: f64 = 1e-12;

/// Every subset sum of a set of drones in increasing order; the subset of any entry is recovered
/// from one bit per merge step. The buffers are kept between builds, so a search allocates them
/// once.
#[derive(Default)]
struct SubsetSums {
    /// `sums[..len]` increasing, then one `+inf` sentinel.
    sums: Vec<f64>,
    len: usize,
    next: Vec<f64>,
    /// The drone merged in at each level (level `l` doubles the list to `2^(l+1)` entries).
    items: Vec<usize>,
    /// Per level, bit `o` is set when output `o` came from the shifted list (it holds the level's
    /// drone); `rank` counts the set bits of the level's earlier words. Level `l` starts at word
    /// `2^(l+1) / 64` rounded down (levels below 6 share word 0 ... 5, one word each).
    bits: Vec<u64>,
    rank: Vec<u32>,
}

/// Merges run as this many independent pieces side by side (below, one), so the processor
/// overlaps their dependency chains.
const MERGE_PIECES: usize = 4;

/// First word of level `l` in `SubsetSums::bits` (`2^(l+1)` outputs): levels `0..6` take one word
/// each, level `l >= 6` the `2^(l-5)` words after the `2^(l-5) - 2 + 6` words of the levels below.
fn level_offset(l: usize) -> usize {
    if l < 6 {
        l
    } else {
        (1usize << (l - 5)) + 4
    }
}

impl SubsetSums {
    /// Lists the `2^len` subset sums of the drones `items` (indices into `p`) by merging the
    /// sorted list with itself shifted by each drone in turn: `O(2^len)`. The merge runs against
    /// a `+inf` sentinel (one comparison a step, no test of the list ends) and, on long lists, as
    /// [`MERGE_PIECES`] pieces whose starts are found by binary search on the merge path. Each
    /// step records whether it took the shifted list, one bit, from which [`SubsetSums::mask`]
    /// walks back.
    fn build(&mut self, p: &[f64], items: &[usize]) {
        let levels = items.len();
        let size = 1usize << levels;
        for buf in [&mut self.sums, &mut self.next] {
            if buf.len() < size + 1 {
                buf.resize(size + 1, 0.0);
            }
        }
        let words = level_offset(levels);
        if self.bits.len() < words {
            self.bits.resize(words, 0);
            self.rank.resize(words, 0);
        }
        self.items.clear();
        self.items.extend_from_slice(items);
        self.sums[0] = 0.0;
        self.sums[1] = f64::INFINITY;
        let mut len = 1;
        for (l, &j) in items.iter().enumerate() {
            let v = p[j];
            let src = &self.sums[..=len];
            let dst = &mut self.next[..=2 * len];
            let out = 2 * len;
            let off = level_offset(l);
            let bits = &mut self.bits[off..level_offset(l + 1)];
            // One merge step: the smaller of `src[a]` and `src[b] + v`, ties to `a`; inf + v is
            // inf, so a list that ran out is never taken again. Returns (sum, took b).
            let step = |a: &mut usize, b: &mut usize| {
                let (x, y) = (src[*a], src[*b] + v);
                let take_a = x <= y;
                *a += usize::from(take_a);
                *b += usize::from(!take_a);
                (if take_a { x } else { y }, u64::from(!take_a))
            };
            if out < 64 * MERGE_PIECES {
                let (mut a, mut b) = (0, 0);
                let mut word = 0u64;
                for (o, slot) in dst[..out].iter_mut().enumerate() {
                    let (x, took_b) = step(&mut a, &mut b);
                    *slot = x;
                    word |= took_b << (o & 63);
                    if o & 63 == 63 || o + 1 == out {
                        bits[o >> 6] = word;
                        word = 0;
                    }
                }
            } else {
                // Pieces of a multiple of 64 outputs: each fills whole words.
                let piece = out / MERGE_PIECES;
                let mut a = [0; MERGE_PIECES];
                let mut b = [0; MERGE_PIECES];
                let mut word = [0u64; MERGE_PIECES];
                for w in 0..MERGE_PIECES {
                    a[w] = merge_path_split(src, len, v, w * piece);
                    b[w] = w * piece - a[w];
                }
                for t in 0..piece {
                    for w in 0..MERGE_PIECES {
                        let (x, took_b) = step(&mut a[w], &mut b[w]);
                        dst[w * piece + t] = x;
                        word[w] |= took_b << (t & 63);
                        if t & 63 == 63 {
                            bits[(w * piece + t) >> 6] = word[w];
                            word[w] = 0;
                        }
                    }
                }
            }
            let rank = &mut self.rank[off..level_offset(l + 1)];
            let mut ones = 0u32;
            for (r, &w) in rank.iter_mut().zip(bits.iter()) {
                *r = ones;
                ones += w.count_ones();
            }
            dst[out] = f64::INFINITY;
            len = out;
            std::mem::swap(&mut self.sums, &mut self.next);
        }
        self.len = len;
    }

    fn len(&self) -> usize {
        self.len
    }

    /// The sums, increasing.
    fn sums(&self) -> &[f64] {
        &self.sums[..self.len]
    }

    /// The subset of entry `i` as a bit mask of drones: back through the levels, an output that
    /// came from the shifted list holds the level's drone and was entry `rank1(o)` of the list
    /// before, else entry `o - rank1(o)`. `O(levels)`.
    fn mask(&self, i: usize) -> u64 {
        let mut o = i;
        let mut mask = 0u64;
        for l in (0..self.items.len()).rev() {
            let off = level_offset(l);
            let word = self.bits[off + (o >> 6)];
            let ones = self.rank[off + (o >> 6)] as usize
                + (word & ((1u64 << (o & 63)) - 1)).count_ones() as usize;
            if word >> (o & 63) & 1 == 1 {
                mask |= 1u64 << self.items[l];
                o = ones;
            } else {
                o -= ones;
            }
        }
        mask
    }
}

/// How many of the first `k` outputs of the merge of `src[..len]` with `src[..len] + v` come
/// from the unshifted list (ties go to it): binary search on the merge path.
fn merge_path_split(src: &[f64], len: usize, v: f64, k: usize) -> usize {
    let (mut lo, mut hi) = (k.saturating_sub(len), k.min(len));
    while lo < hi {
        let i = (lo + hi) / 2;
        if src[i] <= src[k - i - 1] + v {
            lo = i + 1;
        } else {
            hi = i;
        }
    }
    lo
}

/// Lists the two halves' subset sums of `items` into `lists`: drones alternate between the
/// halves, so both hold long and short drones. The shorter list comes first: it drives the
/// outer loop of the window walk.
fn halves(p: &[f64], items: &[usize], lists: &mut (SubsetSums, SubsetSums)) {
    let first: Vec<usize> = items.iter().copied().step_by(2).collect();
    let second: Vec<usize> = items.iter().copied().skip(1).step_by(2).collect();
    lists.0.build(p, &second);
    lists.1.build(p, &first);
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
    let l2_sums = l2.sums();
    let (mut lo_ptr, mut hi_ptr) = (l2_sums.len(), l2_sums.len());
    for (i, &a) in l1.sums().iter().enumerate() {
        if a > hi {
            break;
        }
        while hi_ptr > 0 && a + l2_sums[hi_ptr - 1] > hi {
            hi_ptr -= 1;
        }
        while lo_ptr > 0 && a + l2_sums[lo_ptr - 1] >= lo {
            lo_ptr -= 1;
        }
        for (q, &b) in l2_sums.iter().enumerate().take(hi_ptr).skip(lo_ptr) {
            if !visit(a + b, l1.mask(i) | l2.mask(q)) {
                return false;
            }
        }
    }
    true
}

/// Pairs of the two lists with sum in `[lo, hi)`, in increasing sum: one heap entry per entry of
/// `l1`, pointing at its smallest partner not yet given out (Schroeppel–Shamir's order, on two
/// lists). Entries whose partners all reach `hi` never enter the heap.
struct Ascending<'a> {
    l1: &'a SubsetSums,
    l2: &'a SubsetSums,
    hi: f64,
    partner: Vec<usize>,
    /// `(sum as ordered bits, index into l1)`; sums are `>= 0`, whose bits order like the values.
    heap: BinaryHeap<Reverse<(u64, usize)>>,
}

impl<'a> Ascending<'a> {
    fn new(l1: &'a SubsetSums, l2: &'a SubsetSums, lo: f64, hi: f64) -> Self {
        let mut partner = vec![0; l1.len()];
        let mut entries = Vec::new();
        let l2_sums = l2.sums();
        let mut q = l2_sums.len();
        for (i, (&a, first)) in l1.sums().iter().zip(partner.iter_mut()).enumerate() {
            while q > 0 && a + l2_sums[q - 1] >= lo {
                q -= 1;
            }
            *first = q;
            if q < l2_sums.len() && a + l2_sums[q] < hi {
                entries.push(Reverse(((a + l2_sums[q]).to_bits(), i)));
            }
        }
        Ascending {
            l1,
            l2,
            hi,
            partner,
            heap: BinaryHeap::from(entries),
        }
    }

    /// The next pair: its sum and its mask.
    fn next(&mut self) -> Option<(f64, u64)> {
        let Reverse((bits, i)) = self.heap.pop()?;
        let q = self.partner[i];
        let l2 = self.l2.sums();
        self.partner[i] = q + 1;
        if q + 1 < l2.len() {
            let s = self.l1.sums()[i] + l2[q + 1];
            if s < self.hi {
                self.heap.push(Reverse((s.to_bits(), i)));
            }
        }
        Some((f64::from_bits(bits), self.l1.mask(i) | self.l2.mask(q)))
    }
}

/// The pairs of the two lists around `t`: the one with the smallest sum `>= t` and the one
/// with the largest sum `< t`, as masks. One walk with two pointers, `O(|l1| + |l2|)`.
fn around(l1: &SubsetSums, l2: &SubsetSums, t: f64) -> (Option<u64>, Option<u64>) {
    let l2_sums = l2.sums();
    let mut q = l2_sums.len();
    let (mut above, mut below) = ((f64::INFINITY, None), (f64::NEG_INFINITY, None));
    for (i, &a) in l1.sums().iter().enumerate() {
        while q > 0 && a + l2_sums[q - 1] >= t {
            q -= 1;
        }
        // l2[q] is a's smallest partner reaching t, l2[q - 1] its largest below.
        if q < l2_sums.len() && a + l2_sums[q] < above.0 {
            above = (a + l2_sums[q], Some((i, q)));
        }
        if q > 0 && a + l2_sums[q - 1] > below.0 {
            below = (a + l2_sums[q - 1], Some((i, q - 1)));
        }
    }
    let mask = |(i, q): (usize, usize)| l1.mask(i) | l2.mask(q);
    (above.1.map(mask), below.1.map(mask))
}

/// Two pads: the fullest pad of an optimal split, as `(load, mask)`. One pad holds the longest
/// drone `0`; its set `B = {0} + X` is, over all splits, either the lightest with
/// `s(B) >= total / 2` (then it is the fullest pad) or the heaviest with `s(B) < total / 2`
/// (then its complement is), so one walk over the subset sums of drones `1..n` decides it.
fn two_pads(p: &[f64], lists: &mut ListPair) -> Option<(f64, u64)> {
    let n = p.len();
    let all = (1u64 << n) - 1;
    let items: Vec<usize> = (1..n).collect();
    halves(p, &items, lists);
    let total: f64 = p.iter().sum();
    let load = |mask: u64| members(mask).iter().map(|&j| p[j]).sum::<f64>();
    let (above, below) = around(&lists.0, &lists.1, 0.5 * total - p[0]);
    let above = above.map(|x| (load(x | 1), x | 1));
    let below = below.map(|x| all & !(x | 1)).map(|a| (load(a), a));
    match (above, below) {
        (Some(x), Some(y)) => Some(if y.0 < x.0 { y } else { x }),
        (x, y) => x.or(y),
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

/// The search: drones `p` (decreasing, positive, at most [`PARTITION_MAX_DRONES`]) and the
/// pads chosen so far.
struct Partition<'a> {
    p: &'a [f64],
    /// The drones of each pad filled so far, fullest first.
    pads: Vec<u64>,
    /// Subset-sum lists of the window queries below the first level (one query at a time).
    lists: (SubsetSums, SubsetSums),
    /// Loads up to this are within `REL_TOL` of the lower bound: an assignment within it is
    /// proven optimal, so no pad needs to stay below a lighter fuller pad (see `fits`).
    within_tol: f64,
    /// Every set of drones whose load (as listed) lies in `[cache_lo, cache_hi]`, by increasing
    /// load: while the fullest pad stays below a bound, every window query of the completion
    /// falls in that range (see `build_cache`), so it reads the cache instead of building lists.
    cache_sums: Vec<f64>,
    cache_masks: Vec<u64>,
    /// Scratch of `build_cache`.
    cache_pairs: Vec<(f64, u64)>,
    cache_lo: f64,
    cache_hi: f64,
    /// Failed cached completions (a failure under a capacity is one under any smaller).
    failed: Failed,
    /// Work of the queries not yet counted as nodes, in cached sets scanned ([`WORK_PER_NODE`]).
    work: u64,
}

impl<'a> Partition<'a> {
    /// A search over the drones `p` from the lower bound `lb`, with `lists` as its scratch lists
    /// and an empty cache.
    fn new(p: &'a [f64], lists: ListPair, lb: f64) -> Self {
        Partition {
            p,
            pads: Vec::new(),
            lists,
            within_tol: lb * (1.0 + 0.5 * REL_TOL),
            cache_sums: Vec::new(),
            cache_masks: Vec::new(),
            cache_pairs: Vec::new(),
            cache_lo: f64::INFINITY,
            cache_hi: f64::NEG_INFINITY,
            failed: Failed::default(),
            work: 0,
        }
    }

    /// Lists into the cache every set with a load the completions can ask for while the fullest
    /// pad is lighter than `top` (`total` the load of all drones, `m` pads). Every pad after the
    /// fullest has capacity at most `cap = max(top, within_tol)`, so with `d` pads filled the
    /// `m - d` pads left share at least `total - d cap`, and the fullest of them holds at least
    /// that over `m - d`; the least of these, at `d = m - 2`, is the cache's lower end. A window
    /// with more than [`CACHE_MAX_SETS`] sets leaves the cache empty.
    fn build_cache(&mut self, lists: &ListPair, m: usize, total: f64, top: f64) {
        let cap = top.max(self.within_tol) * (1.0 + 2.0 * SLACK);
        let lo = (total - (m.saturating_sub(2)) as f64 * cap) / 2.0 * (1.0 - 4.0 * SLACK);
        let pairs = &mut self.cache_pairs;
        pairs.clear();
        let complete = for_each_in_window(&lists.0, &lists.1, lo, cap, |s, mask| {
            pairs.push((s, mask));
            pairs.len() < CACHE_MAX_SETS
        });
        self.cache_sums.clear();
        self.cache_masks.clear();
        if complete {
            pairs.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
            self.cache_sums.extend(pairs.iter().map(|e| e.0));
            self.cache_masks.extend(pairs.iter().map(|e| e.1));
            (self.cache_lo, self.cache_hi) = (lo, cap);
        } else {
            (self.cache_lo, self.cache_hi) = (f64::INFINITY, f64::NEG_INFINITY);
        }
    }

    /// What every completion decides at once for the drones of `rest` (load `total`) on `bins`
    /// pads of capacity `cap_x` (rounding allowance included): no drone left, one pad, a drone or
    /// the total too long for the pads, or at most one drone per pad. `None` when it takes a
    /// search; on `Fits` the pads are appended to `self.pads`.
    fn settled(&mut self, rest: u64, bins: usize, cap_x: f64, total: f64) -> Option<Decision> {
        if rest == 0 {
            return Some(Decision::Fits);
        }
        if bins == 1 {
            if total <= cap_x {
                self.pads.push(rest);
                return Some(Decision::Fits);
            }
            return Some(Decision::DoesNotFit);
        }
        let longest = rest.trailing_zeros() as usize;
        if self.p[longest] > cap_x || total > bins as f64 * cap_x {
            return Some(Decision::DoesNotFit);
        }
        if rest.count_ones() as usize <= bins {
            self.pads
                .extend(members(rest).into_iter().map(|j| 1u64 << j));
            return Some(Decision::Fits);
        }
        None
    }

    /// Counts one node, and one more per [`WORK_PER_NODE`] of the work since the last count
    /// (subset sums listed, cached sets scanned); true when the node limit is reached (the clock
    /// is read every 1024 nodes, `Budget::tick`).
    fn tick(&mut self, budget: &mut Budget) -> bool {
        budget.nodes = budget.nodes.saturating_add(self.work / WORK_PER_NODE);
        self.work %= WORK_PER_NODE;
        budget.tick()
    }

    /// [`Partition::tick`], and reads the clock; true when a limit is reached.
    fn spent(&mut self, budget: &mut Budget) -> bool {
        self.tick(budget)
            || budget
                .limits
                .time_limit_s
                .is_some_and(|t| budget.start.elapsed().as_secs_f64() >= t)
    }

    /// [`Partition::fits`] for the drones of `rest`, whose load is `total`, read from the cache
    /// when it covers the window `[total / bins, cap]` of the fullest pad (else by `fits`). Two
    /// pads need a set in that window: its complement weighs at most `total / 2`.
    fn fits_cached(
        &mut self,
        rest: u64,
        bins: usize,
        cap: f64,
        total: f64,
        budget: &mut Budget,
    ) -> Decision {
        let cap_x = cap * (1.0 + SLACK);
        if let Some(settled) = self.settled(rest, bins, cap_x, total) {
            return settled;
        }
        let lo = total / bins as f64 * (1.0 - SLACK);
        if lo < self.cache_lo || cap_x > self.cache_hi {
            return self.fits(rest, bins, cap, budget);
        }
        // A cached query is cheap: the clock is read every 1024 of them (`Budget::tick`).
        if self.tick(budget) {
            return Decision::Stopped;
        }
        let key = rest | (bins as u64) << 58;
        if self.failed.get(&key).is_some_and(|&c| c >= cap) {
            return Decision::DoesNotFit;
        }
        let mut idx = self.cache_sums.partition_point(|&x| x < lo);
        let end = idx + self.cache_sums[idx..].partition_point(|&x| x <= cap_x);
        let outside = !rest;
        loop {
            let found = self.cache_masks[idx..end]
                .iter()
                .position(|&mask| mask & outside == 0);
            self.work += found.map_or(end - idx, |step| step + 1) as u64;
            let Some(step) = found else { break };
            idx += step;
            let (s, mask) = (self.cache_sums[idx], self.cache_masks[idx]);
            idx += 1;
            self.pads.push(mask);
            if bins == 2 {
                self.pads.push(rest & !mask);
                return Decision::Fits;
            }
            // As in `fits`: the other pads stay at most as full as this one, or within the
            // tolerance.
            let next_cap = s.max(self.within_tol).min(cap);
            match self.fits_cached(rest & !mask, bins - 1, next_cap, total - s, budget) {
                Decision::DoesNotFit => {
                    self.pads.pop();
                }
                other => return other,
            }
        }
        if self.failed.len() < FAILED_MAX_STATES {
            let c = self.failed.entry(key).or_insert(cap);
            *c = c.max(cap);
        }
        Decision::DoesNotFit
    }

    /// Decides whether the drones of `rest` fit on `bins` pads with every load `<= cap`; on
    /// `Fits` the pads are appended to `self.pads`.
    fn fits(&mut self, rest: u64, bins: usize, cap: f64, budget: &mut Budget) -> Decision {
        let items = members(rest);
        let total: f64 = items.iter().map(|&j| self.p[j]).sum();
        let cap_x = cap * (1.0 + SLACK);
        if let Some(settled) = self.settled(rest, bins, cap_x, total) {
            return settled;
        }
        if self.spent(budget) {
            return Decision::Stopped;
        }
        if bins == 2 {
            // One pad holds the longest drone and a load in [total - cap, cap].
            let longest = items[0];
            halves(self.p, &items[1..], &mut self.lists);
            self.work += LIST_WORK * (self.lists.0.len() + self.lists.1.len()) as u64;
            let p0 = self.p[longest];
            let mut found = None;
            for_each_in_window(
                &self.lists.0,
                &self.lists.1,
                total - cap_x - p0,
                cap_x - p0,
                |_, mask| {
                    found = Some(mask | (1u64 << longest));
                    false
                },
            );
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
        halves(self.p, &items, &mut self.lists);
        self.work += LIST_WORK * (self.lists.0.len() + self.lists.1.len()) as u64;
        let mut candidates = Vec::new();
        let lo = total / bins as f64 * (1.0 - SLACK);
        for_each_in_window(&self.lists.0, &self.lists.1, lo, cap_x, |s, mask| {
            candidates.push((s, mask));
            true
        });
        for (s, mask) in candidates {
            self.pads.push(mask);
            // The other pads stay at most as full as this one, or within the tolerance.
            match self.fits(
                rest & !mask,
                bins - 1,
                s.max(self.within_tol).min(cap),
                budget,
            ) {
                Decision::DoesNotFit => {
                    self.pads.pop();
                }
                other => return other,
            }
        }
        Decision::DoesNotFit
    }
}

/// Expected number of subsets of the drones `p` per minute of load near `load`: the subset sums
/// are about normal with mean `sum/2` and spread `sqrt(sum p_j^2) / 2`, so there are about
/// `2^n phi(z) / spread` of them per minute, `z = (sum/2 - load) / spread`. The cache of the sets
/// a window of fullest-pad loads of width `w` needs spans `k w / 2` (see `build_cache`).
fn subset_density(p: &[f64], load: f64) -> f64 {
    let total: f64 = p.iter().sum();
    let spread = p.iter().map(|x| x * x).sum::<f64>().sqrt() / 2.0;
    let z = (total / 2.0 - load) / spread;
    let log = p.len() as f64 * std::f64::consts::LN_2 - 0.5 * z * z;
    log.exp() / (spread * (2.0 * std::f64::consts::PI).sqrt())
}

/// Two halves' subset-sum lists.
type ListPair = (SubsetSums, SubsetSums);

/// Largest list (entries) whose buffers a thread keeps for its next solve: `2^16` entries,
/// 1 MiB a buffer, which covers 32 drones. Fresh buffers of that size cost more in page faults
/// than the merges that fill them.
const KEEP_LIST_ENTRIES: usize = 1 << 16;

thread_local! {
    /// Buffers kept between solves on this thread: the first level's lists and the scratch
    /// lists of the levels below.
    static KEPT_LISTS: RefCell<Vec<ListPair>> = const { RefCell::new(Vec::new()) };
}

/// The outcome (proven, lower bound, incumbent makespan) of a partitioning search.
fn outcome(proven: bool, lower_bound_min: f64, incumbent_min: f64) -> SearchOutcome {
    SearchOutcome {
        proven,
        lower_bound_min,
        incumbent_min,
    }
}

/// Exact node time by sequential partitioning for the drones `p` (decreasing, positive, at most
/// [`PARTITION_MAX_DRONES`]) on `m >= 2` pads, from the lower bound `lb` and the incumbent `ub`
/// (pads in `pad_of`, replaced when a better assignment is found).
///
/// The outcome's lower bound is the load of the fullest pad tried last: every set with a smaller
/// load failed to complete.
pub(crate) fn partition(
    m: usize,
    p: &[f64],
    lb: f64,
    ub: f64,
    pad_of: &mut [usize],
    budget: &mut Budget,
) -> SearchOutcome {
    let take = || KEPT_LISTS.with(|kept| kept.borrow_mut().pop().unwrap_or_default());
    let mut top = take();
    let mut search = Partition::new(p, take(), lb);
    let result = partition_in(m, lb, ub, pad_of, budget, &mut top, &mut search);
    KEPT_LISTS.with(|kept| {
        let mut kept = kept.borrow_mut();
        for pair in [top, search.lists] {
            if pair.0.sums.len().max(pair.1.sums.len()) <= KEEP_LIST_ENTRIES + 1 {
                kept.push(pair);
            }
        }
    });
    result
}

/// [`partition`] with the first level's lists in `lists` and the search (drones, scratch lists
/// of the levels below) in `search`.
fn partition_in(
    m: usize,
    mut lb: f64,
    ub: f64,
    pad_of: &mut [usize],
    budget: &mut Budget,
    lists: &mut ListPair,
    search: &mut Partition,
) -> SearchOutcome {
    let p = search.p;
    let n = p.len();
    debug_assert!(n <= PARTITION_MAX_DRONES && m >= 2);
    let all = if n == 64 { u64::MAX } else { (1u64 << n) - 1 };
    // The assignment of the pads found, and its makespan.
    let take_found = |pads: &[u64], pad_of: &mut [usize]| {
        let mut loads = vec![0.0_f64; m];
        for (i, &pad) in pads.iter().enumerate() {
            for j in members(pad) {
                loads[i] += p[j];
            }
        }
        let found = loads.iter().copied().fold(0.0, f64::max);
        if found < ub {
            for (i, &pad) in pads.iter().enumerate() {
                for j in members(pad) {
                    pad_of[j] = i;
                }
            }
            return found;
        }
        ub
    };
    if m == 2 {
        // The fullest pad of an optimal split; its complement fits on the other pad (should
        // rounding refuse it, the general search below decides).
        if let Some((s, mask)) = two_pads(p, lists) {
            search.pads.push(mask);
            if search.fits(all & !mask, 1, s, budget) == Decision::Fits {
                let found = take_found(&search.pads, pad_of);
                return outcome(true, found.min(s), found);
            }
            search.pads.clear();
        }
    }
    let items: Vec<usize> = (0..n).collect();
    halves(p, &items, lists);
    // The sets come window by window, `[lo, lo + width)` with the width growing 4-fold (the
    // optimum is usually in the first one or two): with 4 pads or more from the cache of the
    // sets the window and its completions need, else from a heap that holds only the entries
    // with a partner in the window.
    let mut lo = lb * (1.0 - SLACK);
    let mut width = lb * FIRST_WINDOW_REL;
    if m >= 4 {
        // No wider than a cache of about `CACHE_MAX_SETS / 2` sets is expected to hold.
        let sets_per_min = subset_density(p, lb);
        width = width.min(CACHE_MAX_SETS as f64 / 2.0 / (sets_per_min * m as f64 / 2.0));
        width = width.max(lb * REL_TOL);
    }
    let total: f64 = p.iter().sum();
    while lo < ub {
        let hi = (lo + width).min(ub);
        if m >= 4 {
            search.build_cache(lists, m, total, hi);
        }
        // The sets of the window in increasing load: from the cache when it holds them, else
        // from the heap of `Ascending`.
        let cached = lo >= search.cache_lo && hi <= search.cache_hi;
        let mut ascending = (!cached).then(|| Ascending::new(&lists.0, &lists.1, lo, hi));
        let mut idx = search.cache_sums.partition_point(|&x| x < lo);
        loop {
            let (s, mask) = match ascending.as_mut() {
                Some(heap) => match heap.next() {
                    Some(set) => set,
                    None => break,
                },
                None => match search.cache_sums.get(idx) {
                    Some(&s) if s < hi => (s, search.cache_masks[idx]),
                    _ => break,
                },
            };
            idx += 1;
            if le_tol(ub, s) {
                // Every assignment whose fullest pad is below s failed: ub is within REL_TOL.
                return outcome(true, lb.max(s.min(ub)), ub);
            }
            lb = lb.max(s * (1.0 - SLACK));
            search.pads.clear();
            search.pads.push(mask);
            let cap = s.max(search.within_tol);
            match search.fits_cached(all & !mask, m - 1, cap, total - s, budget) {
                Decision::Fits => {
                    let found = take_found(&search.pads, pad_of);
                    return outcome(true, lb, found);
                }
                Decision::DoesNotFit => {}
                Decision::Stopped => return outcome(false, lb, ub),
            }
        }
        // Every set below hi failed.
        lb = lb.max(hi * (1.0 - SLACK)).min(ub);
        lo = hi;
        width *= 4.0;
    }
    // Every set was tried: the incumbent is optimal.
    outcome(true, ub, ub)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The lists hold every subset exactly once, by nondecreasing sum, each sum equal to its
    /// subset's sum (direct enumeration of the `2^len` masks is the reference). Sizes run from one
    /// drone to past the length where merges split into pieces, with repeated times for ties.
    #[test]
    fn subset_sums_are_every_subset_in_increasing_order() {
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut lists = SubsetSums::default();
        for len in 1..=14 {
            for round in 0..4 {
                let p: Vec<f64> = (0..len + 3)
                    .map(|_| {
                        if round % 2 == 0 {
                            f64::from(rng.random_range(1..=3))
                        } else {
                            rng.random_range(1.0..100.0)
                        }
                    })
                    .collect();
                // Drones 3.. of p, so masks use bits other than the first ones.
                let items: Vec<usize> = (3..len + 3).collect();
                lists.build(&p, &items);
                let entries: Vec<(f64, u64)> = (0..lists.len())
                    .map(|i| (lists.sums()[i], lists.mask(i)))
                    .collect();
                assert_eq!(entries.len(), 1 << len);
                assert!(
                    entries.windows(2).all(|w| w[0].0 <= w[1].0),
                    "len {len}: unsorted"
                );
                let mut seen: Vec<u64> = entries.iter().map(|e| e.1).collect();
                seen.sort_unstable();
                let expected: Vec<u64> = (0u64..1 << len).map(|x| x << 3).collect();
                assert_eq!(seen, expected, "len {len}: not every subset once");
                for &(sum, mask) in &entries {
                    let direct: f64 = (0..p.len())
                        .filter(|&j| mask >> j & 1 == 1)
                        .map(|j| p[j])
                        .sum();
                    assert!((sum - direct).abs() <= 1e-9 * direct.max(1.0), "len {len}");
                }
            }
        }
    }

    /// Two pads: the set returned is the fullest pad of a best split, checked against every
    /// split (`2^(n-1)` of them).
    #[test]
    fn two_pads_matches_every_split() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let mut lists = (SubsetSums::default(), SubsetSums::default());
        for n in 2..=14 {
            for _ in 0..20 {
                let mut p: Vec<f64> = (0..n).map(|_| rng.random_range(1.0..100.0)).collect();
                p.sort_by(|a, b| b.total_cmp(a));
                let total: f64 = p.iter().sum();
                let mut best = f64::INFINITY;
                for mask in 0u64..1 << (n - 1) {
                    let s: f64 = (0..n).filter(|&j| mask >> j & 1 == 1).map(|j| p[j]).sum();
                    best = best.min(s.max(total - s));
                }
                let (load, mask) = two_pads(&p, &mut lists).expect("some split");
                let direct: f64 = (0..n).filter(|&j| mask >> j & 1 == 1).map(|j| p[j]).sum();
                assert!((load - direct).abs() <= 1e-9 * total, "n {n}");
                assert!(
                    load >= total - load - 1e-9 * total,
                    "n {n}: not the fuller pad"
                );
                assert!(
                    (load - best).abs() <= 1e-9 * total,
                    "n {n}: {load} vs {best}"
                );
            }
        }
    }

    /// A list query counts the work of its lists as nodes: two pads for 24 drones list the
    /// subset sums of the 23 after the longest, `2^11 + 2^12` of them, `8 * 6144 / 16 = 3072`
    /// nodes besides the query's own, counted at the next node. So the node limit bounds the time
    /// of a search whose queries each build long lists.
    #[test]
    fn a_list_query_counts_its_work_as_nodes() {
        let mut rng = ChaCha8Rng::seed_from_u64(14);
        let mut p: Vec<f64> = (0..24).map(|_| rng.random_range(1.0..100.0)).collect();
        p.sort_by(|a, b| b.total_cmp(a));
        let total: f64 = p.iter().sum();
        let limits = crate::node_time::Limits::default();
        let mut budget = Budget::new(&limits);
        let mut search = Partition::new(&p, ListPair::default(), total / 2.0);
        let decision = search.fits((1 << 24) - 1, 2, 0.6 * total, &mut budget);
        assert_eq!(decision, Decision::Fits);
        assert_eq!(budget.nodes, 1);
        assert!(!search.tick(&mut budget));
        let listed = (1 << 11) + (1 << 12);
        assert_eq!(budget.nodes, 2 + LIST_WORK * listed / WORK_PER_NODE);
    }

    /// Whether the drones of `rest` fit on `bins` pads with loads `<= cap`, by trying every pad
    /// for each drone (empty pads are interchangeable: only the first is tried).
    fn fits_by_enumeration(p: &[f64], rest: u64, bins: usize, cap: f64) -> bool {
        fn place(p: &[f64], items: &[usize], loads: &mut Vec<f64>, cap: f64) -> bool {
            let Some((&j, more)) = items.split_first() else {
                return true;
            };
            for i in 0..loads.len() {
                if loads[i] + p[j] <= cap && (i == 0 || loads[i - 1] > 0.0 || loads[i] > 0.0) {
                    loads[i] += p[j];
                    let ok = place(p, more, loads, cap);
                    loads[i] -= p[j];
                    if ok {
                        return true;
                    }
                }
            }
            false
        }
        place(p, &members(rest), &mut vec![0.0; bins], cap)
    }

    /// The cached completion decides like enumeration (up to 9 drones left) and like the
    /// list-building completion (up to 24 drones), on the queries the search makes: the drones
    /// left after a fullest pad taken from the cache, on 3 to 7 pads. Every `Fits` is checked as
    /// an assignment: each drone left on exactly one pad, every load within the capacity.
    #[test]
    fn cached_completion_decides_like_enumeration_and_list_queries() {
        let mut rng = ChaCha8Rng::seed_from_u64(13);
        let mut lists = (SubsetSums::default(), SubsetSums::default());
        let mut asked = [0usize; 2];
        for case in 0..400 {
            let m = rng.random_range(3..=7);
            let n = rng.random_range(m + 1..=if case % 2 == 0 { 12 } else { 24 });
            let whole = rng.random_bool(0.3);
            let mut p: Vec<f64> = (0..n)
                .map(|_| {
                    if whole {
                        f64::from(rng.random_range(1..=20u32))
                    } else {
                        rng.random_range(1.0..100.0)
                    }
                })
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let total: f64 = p.iter().sum();
            let lb = (total / m as f64).max(p[0]);
            let all = (1u64 << n) - 1;
            let items: Vec<usize> = (0..n).collect();
            halves(&p, &items, &mut lists);
            let mut search = Partition::new(&p, Default::default(), lb);
            let top = lb + rng.random_range(0.0..0.1) * lb;
            search.build_cache(&lists, m, total, top);
            // The search's queries (the drones left after a fullest pad below `top`), then any
            // drones, pads and capacity (outside the cache's range they go to list queries).
            let mut queries: Vec<(u64, usize, f64)> = (0..search.cache_sums.len())
                .map(|i| (search.cache_sums[i], search.cache_masks[i]))
                .filter(|&(s, _)| s >= lb * (1.0 - SLACK) && s < top)
                .take(8)
                .map(|(s, mask)| (all & !mask, m - 1, s.max(search.within_tol)))
                .collect();
            for _ in 0..8 {
                let rest = rng.random_range(1..=all);
                let bins = rng.random_range(1..=m);
                let load: f64 = members(rest).iter().map(|&j| p[j]).sum();
                queries.push((rest, bins, load / bins as f64 * rng.random_range(1.0..1.3)));
            }
            for (rest, bins, cap) in queries {
                let load: f64 = members(rest).iter().map(|&j| p[j]).sum();
                let mut budget = Budget {
                    nodes: 0,
                    start: std::time::Instant::now(),
                    limits: &crate::node_time::Limits::default(),
                };
                search.pads.clear();
                let cached = search.fits_cached(rest, bins, cap, load, &mut budget);
                let found = search.pads.clone();
                search.pads.clear();
                let listed = search.fits(rest, bins, cap, &mut budget);
                let context =
                    format!("case {case}: {bins} pads, cap {cap}, p {p:?}, rest {rest:b}");
                assert_eq!(cached, listed, "{context}");
                if rest.count_ones() <= 9 {
                    let direct = fits_by_enumeration(&p, rest, bins, cap * (1.0 + 1e-12));
                    assert_eq!(cached == Decision::Fits, direct, "{context}");
                    asked[0] += 1;
                }
                asked[1] += 1;
                if cached == Decision::Fits {
                    assert!(found.len() <= bins, "{context}");
                    assert_eq!(found.iter().fold(0, |u, &pad| u | pad), rest, "{context}");
                    assert_eq!(
                        found.iter().map(|pad| pad.count_ones()).sum::<u32>(),
                        rest.count_ones()
                    );
                    for &pad in &found {
                        let load: f64 = members(pad).iter().map(|&j| p[j]).sum();
                        assert!(
                            load <= cap * (1.0 + 1e-9),
                            "{context}: load {load} cap {cap}"
                        );
                    }
                }
            }
        }
        assert!(
            asked[0] >= 1000 && asked[1] >= 4000,
            "too few queries: {asked:?}"
        );

        // A failure is remembered for its capacity and below, not above.
        let p = [5.0, 4.0, 3.0, 3.0, 1.0];
        let mut search = Partition::new(&p, Default::default(), 0.0);
        halves(&p, &[0, 1, 2, 3, 4], &mut lists);
        search.build_cache(&lists, 3, 16.0, 9.0);
        let mut budget = Budget {
            nodes: 0,
            start: std::time::Instant::now(),
            limits: &crate::node_time::Limits::default(),
        };
        // {5, 4, 3, 3, 1} on 2 pads: 8 | 8 fits capacity 8; 7.9 does not.
        assert_eq!(
            search.fits_cached(0b11111, 2, 7.9, 16.0, &mut budget),
            Decision::DoesNotFit
        );
        assert_eq!(
            search.fits_cached(0b11111, 2, 8.0, 16.0, &mut budget),
            Decision::Fits
        );
        assert_eq!(
            search.fits_cached(0b11111, 2, 7.5, 16.0, &mut budget),
            Decision::DoesNotFit
        );
    }
}
