//! Decision version of the node time: "do all drones fit on the `k` pads with every load `<= C`?"
//! (bin packing with `k` bins of capacity `C`). See `models/node_time.md`, "Decision version".
//!
//! The feasibility check is a bin-completion search (Korf 2002; Dell'Amico & Martello 1995): pads
//! are filled one after another; each pad first takes the longest drone still unplaced, then a
//! maximal set of further drones (no unplaced drone still fits), and the total waste
//! `sum_i (C - L_i)` may not exceed `k C - sum_j p_j`. Failed states (the set of unplaced drones,
//! the number of pads filled) are remembered.

use crate::node_time::bounds::l2_bins;
use crate::node_time::search::{Budget, Decision, Memo, MEMO_MAX_STATES};

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
    /// fitting drone left out so far (the pad must end up with less room than that). Taking a
    /// drone recurses, leaving it out loops, so the recursion is at most one frame per drone
    /// placed and two per pad: `n + 2 k` deep.
    #[allow(clippy::too_many_arguments)]
    fn complete(
        &mut self,
        b: usize,
        waste: f64,
        cand: &[usize],
        suffix: &[f64],
        mut pos: usize,
        r: f64,
        mut min_out: f64,
        budget: &mut Budget,
    ) -> Decision {
        loop {
            // Drones too long for the room are left out; they stay too long for any smaller room.
            while pos < cand.len() && self.p[cand[pos]] > r {
                pos += 1;
            }
            // Even taking every remaining candidate, the pad wastes more than allowed, or a drone
            // left out would still fit (the pad is not maximal).
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
            pos += 1;
            while pos < cand.len() && self.p[cand[pos]] == v {
                pos += 1;
            }
            min_out = min_out.min(v);
        }
    }
}
