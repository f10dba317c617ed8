//! Search for an assignment with every load within a target `C` (whole minutes) where the total
//! slack `k C - sum` is a few minutes: exact front pads, then an exact cover of the tail. See
//! `models/node_time.md`, "Upper bound: exact front and covered tail".
//!
//! With the slack `s = k C - sum`, every pad of such an assignment carries between `C - s` and
//! `C`. One attempt fills all but `t` pads (the front) to exactly `C`, each with drones drawn at
//! random (every second attempt, the longest drone left and drones drawn at random) and closed by
//! a drone of exactly the room left; the `t` tail pads keep the whole slack
//! `s`. The tail is then decided exactly: every set of tail drones with a sum in `[C - s, C]` is
//! listed (a pattern), and a search picks disjoint patterns that cover every tail drone, always
//! branching on the drone in the fewest patterns still open (Knuth's exact cover, on bitsets).
//! An attempt whose front or tail fails (no exact pad within its draws, no cover within the
//! tail's node cap) is followed by another with new draws; a tail with more patterns than the cap
//! ends the search. When the tail is the whole swarm there is nothing to draw: the one cover
//! search gets the whole budget. The search finds assignments; it proves nothing when it fails.

use crate::node_time::search::WordHasher;
use crate::node_time::search::{Budget, SubsetSums, TABLE_WORDS_PER_NODE};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;
use std::hash::BuildHasherDefault;

/// Drones left to the tail: `round(COVER_TAIL_DRONES k / n)` pads, at least one. With four
/// drones per pad (u3 100x25 of the classical classes, slack 5–10 min, seeds 1, 5, 8, drawn
/// fronts) 11 tail pads found a cover on all three within 3.6 s in all, 10 pads on one of three
/// in 300 to 400 attempts, 12 pads took 6 to 16 times longer per attempt
/// (`models/experiments/node_time.md`).
const COVER_TAIL_DRONES: usize = 44;

/// Most patterns of one tail (u3 100x25: 11,000 to 22,000 on average); a tail with more is
/// given up, and so is the search, since the next tails would be as large.
const COVER_PATTERNS_MAX: usize = 1 << 17;

/// Nodes of one tail's cover search. The covers found took 41 to 2,872 nodes; a tail without one
/// runs up to tens of thousands, so with a cap of 3,000 the first cover came 1.6 to 8 times
/// sooner than with none (u3 100x25 seeds 1, 5, 8).
const COVER_TAIL_NODES: u64 = 3_000;

/// Attempts at one front pad before the attempt as a whole starts again.
const FRONT_PAD_ATTEMPTS: usize = 5_000;

/// Sets visited by the pattern listing that count as one node of the shared budget.
const VISITS_PER_NODE: u64 = 64;

/// Largest target (minutes) for which the pattern listing prunes by a subset-sum table of the
/// tail: at most 4,097 words a row and 129 rows.
const LISTING_TABLE_MAX_SUM: u64 = 1 << 18;

/// Tail drones a pattern mask can hold.
const TAIL_MAX_DRONES: usize = 128;

/// Looks for an assignment of the drones `p` (whole minutes, sorted decreasingly, positive) on
/// `m` pads with every load `<= target`; `seed` varies the draws between calls. Stops when it
/// finds one or when the `work` budget (nodes of `budget`, also bounded by the caller's limits)
/// runs out. Returns the pad of every drone; the caller recomputes its makespan.
///
/// Complexity per attempt: `O(n)` draws per front pad, the patterns of the tail (at most
/// [`COVER_PATTERNS_MAX`]) and at most [`COVER_TAIL_NODES`] cover nodes of `O(|T| P / 64)` words
/// each, `T` the tail drones and `P` the patterns.
pub(crate) fn cover_at(
    m: usize,
    p: &[f64],
    target: f64,
    work: u64,
    seed: u64,
    budget: &mut Budget,
) -> Option<Vec<usize>> {
    let n = p.len();
    if m == 0 || n == 0 {
        return None;
    }
    let pi: Vec<u64> = p.iter().map(|&x| x as u64).collect();
    let cap = target.floor() as u64;
    let sum: u64 = pi.iter().sum();
    let slack = (m as u64).checked_mul(cap)?.checked_sub(sum)?;
    let tail_pads = ((COVER_TAIL_DRONES * m + n / 2) / n).clamp(1, m);
    let mut rng = ChaCha8Rng::seed_from_u64(0xc0fe_0000 ^ seed);
    let stop_at = budget.nodes.saturating_add(work);
    let mut used = vec![false; n];
    let mut pad_of = vec![usize::MAX; n];
    let mut sums = SubsetSums::default();
    let mut attempt = 0u64;
    while budget.nodes < stop_at && !budget.spent() {
        used.fill(false);
        let longest_first = attempt % 2 == 1;
        attempt += 1;
        let mut left = n;
        let mut front_ok = true;
        for pad in 0..m - tail_pads {
            // Drones per pad as on average over the pads left (rounded at random).
            let pads_left = m - pad;
            let size =
                left / pads_left + usize::from(rng.random_range(0..pads_left) < left % pads_left);
            if size == 0 || size > left {
                // Fewer drones than pads left (not with `n > k`): no front to build.
                return None;
            }
            if !fill_front_pad(
                &pi,
                cap,
                size,
                longest_first,
                pad,
                &mut used,
                &mut pad_of,
                &mut rng,
                budget,
                stop_at,
            ) {
                front_ok = false;
                break;
            }
            left -= size;
        }
        if !front_ok {
            continue;
        }
        let tail: Vec<usize> = (0..n).filter(|&j| !used[j]).collect();
        if tail.len() > TAIL_MAX_DRONES {
            return None;
        }
        let tq: Vec<u64> = tail.iter().map(|&j| pi[j]).collect();
        let max_visits = stop_at
            .saturating_sub(budget.nodes)
            .saturating_mul(VISITS_PER_NODE);
        let lo = cap.saturating_sub(slack);
        let patterns = list_patterns(&tq, lo, cap, max_visits, &mut sums, budget)?;
        let mut cover = Cover::new(patterns, tail.len(), tail_pads);
        let whole_swarm = tail_pads == m;
        let limit = if whole_swarm {
            stop_at
        } else {
            budget.nodes.saturating_add(COVER_TAIL_NODES).min(stop_at)
        };
        let covered = cover.run(slack, budget, limit);
        if covered != Some(true) && whole_swarm {
            // Nothing was drawn: another attempt would repeat this one.
            return None;
        }
        if covered == Some(true) {
            for (q, &pat) in cover.chosen.iter().enumerate() {
                let mut rest = cover.patterns[pat].0;
                while rest != 0 {
                    let i = rest.trailing_zeros() as usize;
                    rest &= rest - 1;
                    pad_of[tail[i]] = m - tail_pads + q;
                }
            }
            debug_assert!(pad_of.iter().all(|&i| i < m));
            return Some(pad_of);
        }
    }
    None
}

/// Fills front pad `pad` to exactly `cap` with `size` drones: `size - 1` unused drones (with
/// `longest_first`, the longest unused drone and `size - 2` drawn at random; else all drawn),
/// closed by an unused drone of exactly the room left. True when it did within
/// [`FRONT_PAD_ATTEMPTS`] draws.
#[allow(clippy::too_many_arguments)]
fn fill_front_pad(
    pi: &[u64],
    cap: u64,
    size: usize,
    longest_first: bool,
    pad: usize,
    used: &mut [bool],
    pad_of: &mut [usize],
    rng: &mut ChaCha8Rng,
    budget: &mut Budget,
    stop_at: u64,
) -> bool {
    let n = pi.len();
    let mut taken: Vec<usize> = Vec::with_capacity(size);
    let longest = used.iter().position(|&u| !u).expect("size <= drones left");
    for _ in 0..FRONT_PAD_ATTEMPTS {
        if budget.tick() || budget.nodes >= stop_at {
            break;
        }
        taken.clear();
        let mut load = 0u64;
        // A drone of `cap` or more shares no pad: then all are drawn.
        if longest_first && size >= 2 && pi[longest] < cap {
            taken.push(longest);
            load += pi[longest];
        }
        while taken.len() + 1 < size {
            let j = rng.random_range(0..n);
            if used[j] || taken.contains(&j) {
                continue;
            }
            taken.push(j);
            load += pi[j];
        }
        if load >= cap {
            continue;
        }
        for &j in &taken {
            used[j] = true;
        }
        let last = unused_of_length(pi, used, cap - load);
        for &j in &taken {
            used[j] = false;
        }
        if let Some(last) = last {
            taken.push(last);
            for &j in &taken {
                used[j] = true;
                pad_of[j] = pad;
            }
            return true;
        }
    }
    false
}

/// An unused drone of length exactly `len` (`pi` decreasing).
fn unused_of_length(pi: &[u64], used: &[bool], len: u64) -> Option<usize> {
    let from = pi.partition_point(|&x| x > len);
    (from..pi.len())
        .take_while(|&j| pi[j] == len)
        .find(|&j| !used[j])
}

/// Every set of the drones `q` (decreasing) with a sum in `[lo, hi]`, as (mask, `hi - sum`),
/// sorted by the second; `None` past [`COVER_PATTERNS_MAX`] patterns or `max_visits` sets
/// visited. [`VISITS_PER_NODE`] sets visited count one node. A set is extended by a drone only
/// when the drones after it can still bring the sum into `[lo, hi]` (the subset-sum table
/// `sums` of the suffixes, rebuilt here, up to [`LISTING_TABLE_MAX_SUM`]), so every set visited
/// is, or leads to, a pattern. Building the table counts [`TABLE_WORDS_PER_NODE`] words as one
/// node; its queries (at most `|q|` per set visited) are not counted.
fn list_patterns(
    q: &[u64],
    lo: u64,
    hi: u64,
    max_visits: u64,
    sums: &mut SubsetSums,
    budget: &mut Budget,
) -> Option<Vec<(u128, u64)>> {
    let n = q.len();
    let mut suffix = vec![0u64; n + 1];
    for j in (0..n).rev() {
        suffix[j] = suffix[j + 1] + q[j];
    }
    // Row `r` of the table: the sums of the last `r` drones.
    let use_table = hi <= LISTING_TABLE_MAX_SUM;
    if use_table {
        let reversed: Vec<usize> = (0..n).rev().collect();
        let words = sums.build(q, &reversed, hi as usize);
        budget.nodes = budget.nodes.saturating_add(words / TABLE_WORDS_PER_NODE);
    }
    let mut listing = Listing {
        q,
        suffix: &suffix,
        sums: use_table.then_some(&*sums),
        lo,
        hi,
        out: Vec::new(),
        visits_left: max_visits,
    };
    let complete = listing.extend(0, 0, 0);
    let visited = max_visits - listing.visits_left;
    budget.nodes = budget.nodes.saturating_add(visited / VISITS_PER_NODE);
    if !complete {
        return None;
    }
    let mut out = listing.out;
    out.sort_by_key(|&(_, idle)| idle);
    Some(out)
}

/// The pattern listing's state.
struct Listing<'a> {
    q: &'a [u64],
    suffix: &'a [u64],
    sums: Option<&'a SubsetSums>,
    lo: u64,
    hi: u64,
    out: Vec<(u128, u64)>,
    visits_left: u64,
}

impl Listing<'_> {
    /// Adds the sets `mask ∪ S`, `S ⊆ {from, ..}`, with a sum in `[lo, hi]`; false when a cap
    /// stopped it.
    fn extend(&mut self, from: usize, sum: u64, mask: u128) -> bool {
        if self.visits_left == 0 {
            return false;
        }
        self.visits_left -= 1;
        if sum >= self.lo && mask != 0 {
            self.out.push((mask, self.hi - sum));
            if self.out.len() > COVER_PATTERNS_MAX {
                return false;
            }
        }
        let n = self.q.len();
        // The drones longer than the room left come first (`q` decreasing).
        let room = self.hi - sum;
        let first = from + self.q[from..].partition_point(|&x| x > room);
        for j in first..n {
            if sum + self.suffix[j] < self.lo {
                break;
            }
            let with = sum + self.q[j];
            if with > self.hi {
                continue;
            }
            // Some set of the drones after `j` (maybe none) brings `with` into the window.
            let reaches = self.sums.is_none_or(|t| {
                t.any_in(
                    n - j - 1,
                    self.lo.saturating_sub(with) as usize,
                    (self.hi - with) as usize,
                )
            });
            if reaches && !self.extend(j + 1, with, mask | 1 << j) {
                return false;
            }
        }
        true
    }
}

/// Exact cover of the tail drones by patterns, with the idle minutes of the chosen patterns
/// within the slack. The open patterns of a node are bitsets over the patterns of a frame; a
/// node whose open patterns fill less than `1 / COMPACT_DENSITY` of the frame's words that
/// hold patterns within its slack starts a new frame of just those, so deep nodes count and
/// filter over short bitsets. Building a frame is not counted in nodes (it costs about as much
/// as the node's own counting, and the clock check of every node bounds it).
struct Cover {
    /// (drones, idle minutes), increasing in idle minutes.
    patterns: Vec<(u128, u64)>,
    drones: usize,
    pads: usize,
    /// Stack of frames; frame 0 holds every pattern.
    frames: Vec<Frame>,
    /// Per depth: the patterns still open (disjoint from the chosen ones), over the node's frame.
    open: Vec<Vec<u64>>,
    /// Failed states: (drones left, depth) -> the largest slack with which they failed.
    failed: HashMap<(u128, usize), u64, BuildHasherDefault<WordHasher>>,
    chosen: Vec<usize>,
    /// [`COMPACT_DENSITY`] and [`COMPACT_MIN_WORDS`] (the tests set others).
    compact_density: usize,
    compact_min_words: usize,
}

/// Patterns of a subtree, renumbered.
#[derive(Default)]
struct Frame {
    /// Pattern of every frame position, increasing (so idle minutes are increasing too).
    ids: Vec<usize>,
    /// Words of a bitset over the frame.
    words: usize,
    /// `holding[i * words ..]`: the frame positions holding drone `i`.
    holding: Vec<u64>,
}

impl Frame {
    /// Renumbers the patterns `ids` (increasing) of `patterns` over `drones` drones.
    fn fill(&mut self, patterns: &[(u128, u64)], drones: usize, ids: impl Iterator<Item = usize>) {
        self.ids.clear();
        self.ids.extend(ids);
        self.words = self.ids.len().div_ceil(64);
        self.holding.clear();
        self.holding.resize(drones * self.words, 0);
        for (k, &id) in self.ids.iter().enumerate() {
            let mut rest = patterns[id].0;
            while rest != 0 {
                let i = rest.trailing_zeros() as usize;
                rest &= rest - 1;
                self.holding[i * self.words + k / 64] |= 1 << (k % 64);
            }
        }
    }

    fn holding(&self, i: usize) -> &[u64] {
        &self.holding[i * self.words..(i + 1) * self.words]
    }
}

/// A node starts a new frame when its open patterns are fewer than the frame's positions within
/// its slack over this (and those take more than [`COMPACT_MIN_WORDS`] words). The frames change
/// the time of a node, never the nodes: u3 100x25 seed 5 ran in 8.3 and 7.3 s with 16, 8.6 and
/// 7.8 s with 32, 8.7 and 7.0 s with 64, 9.3 and 8.2 s without frames
/// (`models/experiments/node_time.md`).
const COMPACT_DENSITY: usize = 16;

/// Nodes whose patterns within the slack take at most this many words of their frame never
/// start a new one.
const COMPACT_MIN_WORDS: usize = 4;

impl Cover {
    fn new(patterns: Vec<(u128, u64)>, drones: usize, pads: usize) -> Self {
        let mut root = Frame::default();
        root.fill(&patterns, drones, 0..patterns.len());
        let words = root.words;
        let mut all = vec![u64::MAX; words];
        if !patterns.len().is_multiple_of(64) {
            all[words - 1] = (1u64 << (patterns.len() % 64)) - 1;
        }
        let mut open = vec![Vec::new(); pads + 1];
        open[0] = all;
        Cover {
            patterns,
            drones,
            pads,
            frames: vec![root],
            open,
            failed: HashMap::default(),
            chosen: Vec::new(),
            compact_density: COMPACT_DENSITY,
            compact_min_words: COMPACT_MIN_WORDS,
        }
    }

    /// Whether `pads` patterns cover every drone with at most `slack` idle minutes; `None` when
    /// it stopped at `limit` nodes of `budget`.
    fn run(&mut self, slack: u64, budget: &mut Budget, limit: u64) -> Option<bool> {
        let all = if self.drones == TAIL_MAX_DRONES {
            u128::MAX
        } else {
            (1u128 << self.drones) - 1
        };
        self.search(all, slack, 0, 0, budget, limit)
    }

    /// Covers the drones `left` with `pads - depth` patterns and `slack` idle minutes, the open
    /// patterns in `open[depth]` over frame `f`; `None` when the node limit stopped it.
    fn search(
        &mut self,
        left: u128,
        slack: u64,
        depth: usize,
        f: usize,
        budget: &mut Budget,
        limit: u64,
    ) -> Option<bool> {
        if left == 0 {
            return Some(true);
        }
        if depth == self.pads {
            return Some(false);
        }
        if budget.tick() || budget.nodes >= limit {
            return None;
        }
        if self.failed.get(&(left, depth)).is_some_and(|&s| s >= slack) {
            return Some(false);
        }
        let (f, top) = self.open_within(slack, depth, f);
        let (fewest, branch) = self.fewest_open(left, depth, f, top);
        if fewest > 0 {
            for k in self.options(branch, fewest, depth, f, top) {
                let (mask, idle) = self.take(k, depth, f, top);
                match self.search(left & !mask, slack - idle, depth + 1, f, budget, limit) {
                    Some(true) => return Some(true),
                    None => return None,
                    Some(false) => {}
                }
                self.chosen.pop();
            }
        }
        let best = self.failed.entry((left, depth)).or_insert(0);
        *best = (*best).max(slack);
        Some(false)
    }

    /// Closes for good the patterns open at `depth` (over frame `f`) with more idle minutes
    /// than `slack`, and gives the node's subtree a frame of its own when few are left open: the
    /// node's frame and the words of its open set.
    fn open_within(&mut self, slack: u64, depth: usize, f: usize) -> (usize, usize) {
        let patterns = &self.patterns;
        let fit = self.frames[f]
            .ids
            .partition_point(|&id| patterns[id].1 <= slack);
        let top = fit.div_ceil(64);
        {
            let open = &mut self.open[depth];
            open[top..].fill(0);
            if fit % 64 != 0 {
                open[top - 1] &= (1u64 << (fit % 64)) - 1;
            }
        }
        let count: usize = self.open[depth][..top]
            .iter()
            .map(|x| x.count_ones() as usize)
            .sum();
        if top > self.compact_min_words && count * self.compact_density < top * 64 {
            return self.compact(depth, f, top, count);
        }
        (f, top)
    }

    /// A new frame `f + 1` of the `count` patterns open at `depth` (in the first `top` words
    /// over frame `f`), for this node's subtree, every one open in it: the frame and its words.
    fn compact(&mut self, depth: usize, f: usize, top: usize, count: usize) -> (usize, usize) {
        if self.frames.len() == f + 1 {
            self.frames.push(Frame::default());
        }
        let (below, above) = self.frames.split_at_mut(f + 1);
        let (frame, next) = (&below[f], &mut above[0]);
        let open = &self.open[depth];
        let ids = (0..top).flat_map(|w| {
            let mut bits = open[w];
            std::iter::from_fn(move || {
                (bits != 0).then(|| {
                    let b = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    frame.ids[w * 64 + b]
                })
            })
        });
        next.fill(&self.patterns, self.drones, ids);
        let f = f + 1;
        let (fit, top) = (count, self.frames[f].words);
        let open = &mut self.open[depth];
        open.clear();
        open.resize(top, u64::MAX);
        if fit % 64 != 0 {
            open[top - 1] = (1u64 << (fit % 64)) - 1;
        }
        (f, top)
    }

    /// The drone of `left` in the fewest patterns open at `depth` (frame `f`, `top` words), the
    /// lowest among equals, and that count (0 stops the scan).
    fn fewest_open(&self, left: u128, depth: usize, f: usize, top: usize) -> (u32, usize) {
        let frame = &self.frames[f];
        let (mut fewest, mut branch) = (u32::MAX, 0);
        let mut rest = left;
        while rest != 0 {
            let i = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let count: u32 = self.open[depth][..top]
                .iter()
                .zip(frame.holding(i))
                .map(|(a, b)| (a & b).count_ones())
                .sum();
            if count < fewest {
                (fewest, branch) = (count, i);
                if count == 0 {
                    break;
                }
            }
        }
        (fewest, branch)
    }

    /// The frame positions of the `fewest` patterns open at `depth` (frame `f`, `top` words)
    /// that hold drone `branch`, increasing.
    fn options(
        &self,
        branch: usize,
        fewest: u32,
        depth: usize,
        f: usize,
        top: usize,
    ) -> Vec<usize> {
        let mut options = Vec::with_capacity(fewest as usize);
        for (w, (&a, &b)) in self.open[depth][..top]
            .iter()
            .zip(self.frames[f].holding(branch))
            .enumerate()
        {
            let mut bits = a & b;
            while bits != 0 {
                options.push(w * 64 + bits.trailing_zeros() as usize);
                bits &= bits - 1;
            }
        }
        options
    }

    /// Chooses the pattern at position `k` of frame `f` at `depth`: the patterns open at `depth`
    /// (`top` words) that share no drone with it stay open at `depth + 1`. Its drones and idle
    /// minutes.
    fn take(&mut self, k: usize, depth: usize, f: usize, top: usize) -> (u128, u64) {
        let frame = &self.frames[f];
        let id = frame.ids[k];
        let (mask, idle) = self.patterns[id];
        let (upper, lower) = self.open.split_at_mut(depth + 1);
        let (open, next) = (&upper[depth], &mut lower[0]);
        next.clear();
        next.extend_from_slice(&open[..top]);
        let mut drones = mask;
        while drones != 0 {
            let i = drones.trailing_zeros() as usize;
            drones &= drones - 1;
            for (x, h) in next.iter_mut().zip(frame.holding(i)) {
                *x &= !h;
            }
        }
        self.chosen.push(id);
        (mask, idle)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::{brute, Limits};
    use rand::seq::SliceRandom;

    /// Calls `cover_at` with `work` nodes and checks what it returns: every drone on a pad
    /// `< m`, every load (recomputed) within `target`.
    fn cover_checked(m: usize, p: &[f64], target: f64, work: u64, seed: u64) -> Option<Vec<usize>> {
        let limits = Limits::default();
        let mut budget = Budget::new(&limits);
        let found = cover_at(m, p, target, work, seed, &mut budget)?;
        assert_eq!(found.len(), p.len());
        assert!(found.iter().all(|&i| i < m), "{found:?}");
        let mut loads = vec![0.0; m];
        for (j, &i) in found.iter().enumerate() {
            loads[i] += p[j];
        }
        assert!(loads.iter().all(|&l| l <= target), "{loads:?} > {target}");
        Some(found)
    }

    /// By hand: 7, 6, 5, 4, 3, 2, 2, 1 (sum 30) on 3 pads of 10 ({7, 3}, {6, 4}, {5, 2, 2, 1}
    /// is one split). The tail is the whole swarm, so the search is exact: 9 is below `sum/k`,
    /// and three drones of 6 do not fit two pads of 9 although `2 x 9 = 18` is their sum.
    #[test]
    fn hand_computed_cases() {
        let p = [7.0, 6.0, 5.0, 4.0, 3.0, 2.0, 2.0, 1.0];
        assert!(cover_checked(3, &p, 10.0, 10_000, 0).is_some());
        assert_eq!(cover_checked(3, &p, 9.0, 10_000, 0), None);
        assert_eq!(cover_checked(2, &[6.0, 6.0, 6.0], 9.0, 10_000, 0), None);
        // One minute of slack: {6, 4} and {6, 3} on two pads of 10.
        assert!(cover_checked(2, &[6.0, 6.0, 4.0, 3.0], 10.0, 10_000, 0).is_some());
    }

    /// Small swarms (the tail is the whole swarm, so the search decides exactly): an assignment
    /// within the brute-force optimum is found, none one minute below it.
    #[test]
    fn decides_small_swarms_as_brute_force_does() {
        let mut rng = ChaCha8Rng::seed_from_u64(410);
        for case in 0..600 {
            let n = rng.random_range(2..=9);
            let m = rng.random_range(2..=4);
            let hi = [5, 20, 300][case % 3];
            let mut p: Vec<f64> = (0..n)
                .map(|_| f64::from(rng.random_range(1..=hi)))
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let opt = brute(m, &p, &Limits::default()).unwrap().makespan_min;
            assert!(
                cover_checked(m, &p, opt, 1_000_000, case as u64).is_some(),
                "case {case}: nothing within the optimum {opt}, k={m} {p:?}"
            );
            assert_eq!(
                cover_checked(m, &p, opt - 1.0, 1_000_000, case as u64),
                None
            );
        }
    }

    /// Fewest pads of `cap` that hold the drones `p`: the subset dynamic programme of bin
    /// packing (per set of packed drones, the fewest pads and then the least load on the last).
    fn pads_needed(p: &[u64], cap: u64) -> u64 {
        let n = p.len();
        let mut best = vec![(u64::MAX, u64::MAX); 1 << n];
        best[0] = (1, 0);
        for mask in 0..(1usize << n) {
            let (pads, load) = best[mask];
            if pads == u64::MAX {
                continue;
            }
            for (j, &x) in p.iter().enumerate() {
                if mask >> j & 1 == 0 {
                    let next = if load + x <= cap {
                        (pads, load + x)
                    } else {
                        (pads + 1, x)
                    };
                    best[mask | 1 << j] = best[mask | 1 << j].min(next);
                }
            }
        }
        best[(1 << n) - 1].0
    }

    /// Swarms of 13 to 16 short drones on 3 or 4 pads: thousands of patterns, so the search
    /// renumbers them into frames as it goes deeper. The optimum comes from the subset
    /// programme; the search, exact on the whole swarm, must fit it and not one minute below.
    #[test]
    fn decides_mid_swarms_as_the_subset_programme_does() {
        let mut rng = ChaCha8Rng::seed_from_u64(412);
        for case in 0..24 {
            let n = rng.random_range(13..=16);
            let m = rng.random_range(3..=4);
            let hi = [12, 30][case % 2];
            let mut pi: Vec<u64> = (0..n).map(|_| rng.random_range(1..=hi)).collect();
            pi.sort_unstable_by(|a, b| b.cmp(a));
            let sum: u64 = pi.iter().sum();
            let mut opt = pi[0].max(sum.div_ceil(m as u64));
            while pads_needed(&pi, opt) > m as u64 {
                opt += 1;
            }
            let p: Vec<f64> = pi.iter().map(|&x| x as f64).collect();
            assert!(
                cover_checked(m, &p, opt as f64, 50_000_000, case as u64).is_some(),
                "case {case}: nothing within the optimum {opt}, k={m} {pi:?}"
            );
            if opt > pi[0] {
                assert_eq!(
                    cover_checked(m, &p, (opt - 1) as f64, 50_000_000, case as u64),
                    None
                );
            }
        }
    }

    /// The listing, pruned by the suffix sums, gives exactly the sets a scan of all `2^n` finds,
    /// with their idle minutes, sorted by them.
    #[test]
    fn patterns_are_every_set_in_the_window() {
        let mut rng = ChaCha8Rng::seed_from_u64(414);
        let mut sums = SubsetSums::default();
        for case in 0..300 {
            let n = rng.random_range(1..=13);
            // A third of the cases above LISTING_TABLE_MAX_SUM: no table, suffix totals only.
            let unit = if case % 3 == 2 { 30_000 } else { 1 };
            let mut q: Vec<u64> = (0..n).map(|_| unit * rng.random_range(1..=40)).collect();
            q.sort_unstable_by(|a, b| b.cmp(a));
            let hi = rng.random_range(1..=q.iter().sum::<u64>() + 5);
            let lo = hi.saturating_sub(rng.random_range(0..=6) * unit);
            let limits = Limits::default();
            let mut budget = Budget::new(&limits);
            let listed = list_patterns(&q, lo, hi, u64::MAX, &mut sums, &mut budget).unwrap();
            assert!(listed.windows(2).all(|w| w[0].1 <= w[1].1), "case {case}");
            let mut listed: Vec<(u128, u64)> = listed;
            listed.sort_unstable();
            let mut scanned = Vec::new();
            for mask in 1u128..1 << n {
                let sum: u64 = (0..n).filter(|&j| mask >> j & 1 == 1).map(|j| q[j]).sum();
                if (lo..=hi).contains(&sum) {
                    scanned.push((mask, hi - sum));
                }
            }
            assert_eq!(listed, scanned, "case {case}: {q:?} in [{lo}, {hi}]");
        }
    }

    /// The cover search alone on whole swarms of 10 to 14 drones, without frames, renumbering
    /// into a new frame wherever the open patterns fill less than half of their frame, and as in
    /// the solver: each covers the drones within the subset programme's optimum with disjoint
    /// patterns and proves that one minute less fails, after the same nodes and with the same
    /// patterns chosen.
    #[test]
    fn frames_keep_the_cover_search_exact() {
        let mut rng = ChaCha8Rng::seed_from_u64(413);
        for case in 0..150 {
            let n = rng.random_range(10..=14);
            let m = rng.random_range(2..=4);
            let mut pi: Vec<u64> = (0..n).map(|_| rng.random_range(1..=20)).collect();
            pi.sort_unstable_by(|a, b| b.cmp(a));
            let sum: u64 = pi.iter().sum();
            let mut opt = pi[0].max(sum.div_ceil(m as u64));
            while pads_needed(&pi, opt) > m as u64 {
                opt += 1;
            }
            for (cap, fits) in [(opt, true), (opt - 1, false)] {
                let Some(slack) = (m as u64 * cap).checked_sub(sum) else {
                    continue;
                };
                let limits = Limits::default();
                let mut budget = Budget::new(&limits);
                let lo = cap.saturating_sub(slack);
                let mut sums = SubsetSums::default();
                let patterns =
                    list_patterns(&pi, lo, cap, u64::MAX, &mut sums, &mut budget).unwrap();
                // Without frames, then with frames wherever half empty, then as in the solver:
                // the same decision, after the same nodes, with the same patterns chosen.
                let mut first: Option<(u64, Vec<usize>)> = None;
                for (density, min_words) in [
                    (1, usize::MAX),
                    (2, 0),
                    (COMPACT_DENSITY, COMPACT_MIN_WORDS),
                ] {
                    let mut cover = Cover::new(patterns.clone(), n, m);
                    (cover.compact_density, cover.compact_min_words) = (density, min_words);
                    let mut budget = Budget::new(&limits);
                    let decided = cover.run(slack, &mut budget, u64::MAX);
                    assert_eq!(decided, Some(fits), "case {case}, C = {cap}, {pi:?}");
                    let run = (budget.nodes, cover.chosen.clone());
                    match &first {
                        None => first = Some(run),
                        Some(without) => assert_eq!(&run, without, "case {case}, C = {cap}"),
                    }
                    if fits {
                        let mut covered = 0u128;
                        for &k in &cover.chosen {
                            assert_eq!(covered & cover.patterns[k].0, 0, "case {case}");
                            covered |= cover.patterns[k].0;
                        }
                        assert_eq!(covered, (1u128 << n) - 1, "case {case}");
                    }
                }
            }
        }
    }

    /// Planted perfect splits with a front: 20 pads of exactly `C` minutes, four drones each
    /// (three drawn in `[1, C/3]`, the fourth the rest), shuffled. The search fills 9 front pads
    /// and covers the 11 tail pads (no slack: every pad exactly `C`). Whatever it returns is
    /// checked; it finds most of 30 instances within 5 million nodes each.
    #[test]
    fn finds_planted_perfect_splits_through_a_front() {
        let mut rng = ChaCha8Rng::seed_from_u64(411);
        let mut found = 0;
        for case in 0..30 {
            let cap = rng.random_range(2_000..=4_000u32);
            let mut p: Vec<f64> = Vec::new();
            for _ in 0..20 {
                let mut rest = cap;
                for _ in 0..3 {
                    let x = rng.random_range(1..=cap / 3);
                    p.push(f64::from(x));
                    rest -= x;
                }
                p.push(f64::from(rest));
            }
            p.shuffle(&mut rng);
            p.sort_by(|a, b| b.total_cmp(a));
            if cover_checked(20, &p, f64::from(cap), 5_000_000, case).is_some() {
                found += 1;
            }
        }
        // 27 of 30 when written; the search is a heuristic, so the test leaves it room.
        assert!(found >= 25, "{found} of 30 planted splits found");
    }
}
