//! Subset sums of a list of drones (whole minutes), one bitset per prefix: the exact two-way
//! split of the perfect-partition search and the pruning of the cover search's pattern listing.

/// Table words that count as one node of the shared budget (the pair tables of the
/// perfect-partition search count at least one each).
pub(crate) const TABLE_WORDS_PER_NODE: u64 = 64;

/// `bits[q * words ..][s]`: sum `s` is reachable with the first `q` drones of the list.
#[derive(Default)]
pub(crate) struct SubsetSums {
    bits: Vec<u64>,
    words: usize,
}

impl SubsetSums {
    /// Builds the table of the drones `items` (lengths `p`) for sums `0..=max_sum`; returns the
    /// work in words.
    pub(crate) fn build(&mut self, p: &[u64], items: &[usize], max_sum: usize) -> u64 {
        self.words = (max_sum + 1).div_ceil(64);
        let w = self.words;
        self.bits.clear();
        self.bits.resize((items.len() + 1) * w, 0);
        self.bits[0] = 1;
        for (q, &j) in items.iter().enumerate() {
            let shift = p[j] as usize;
            let (prev, next) = self.bits.split_at_mut((q + 1) * w);
            let prev = &prev[q * w..];
            let next = &mut next[..w];
            next.copy_from_slice(prev);
            let (ws, bs) = (shift / 64, shift % 64);
            for k in (ws..w).rev() {
                let mut x = prev[k - ws] << bs;
                if bs > 0 && k > ws {
                    x |= prev[k - ws - 1] >> (64 - bs);
                }
                next[k] |= x;
            }
            // Clear the bits beyond `max_sum` in the last word.
            let extra = w * 64 - (max_sum + 1);
            if extra > 0 {
                next[w - 1] &= u64::MAX >> extra;
            }
        }
        (items.len() * w) as u64
    }

    /// Whether sum `s` (at most the table's largest) is reachable with the first `q` drones.
    pub(crate) fn reachable(&self, q: usize, s: usize) -> bool {
        self.bits[q * self.words + s / 64] >> (s % 64) & 1 == 1
    }

    /// Whether some sum in `lo..=hi` (`hi` at most the table's largest) is reachable with the
    /// first `q` drones.
    #[inline]
    pub(crate) fn any_in(&self, q: usize, lo: usize, hi: usize) -> bool {
        if lo > hi {
            return false;
        }
        let row = &self.bits[q * self.words..(q + 1) * self.words];
        let (first, last) = (lo / 64, hi / 64);
        let low_mask = u64::MAX << (lo % 64);
        let high_mask = u64::MAX >> (63 - hi % 64);
        if first == last {
            return row[first] & low_mask & high_mask != 0;
        }
        row[first] & low_mask != 0
            || row[first + 1..last].iter().any(|&x| x != 0)
            || row[last] & high_mask != 0
    }

    /// A subset of `items` with sum `s` (reachable), as a flag per item.
    pub(crate) fn subset(&self, p: &[u64], items: &[usize], mut s: usize) -> Vec<bool> {
        let mut take = vec![false; items.len()];
        for q in (0..items.len()).rev() {
            if !self.reachable(q, s) {
                take[q] = true;
                s -= p[items[q]] as usize;
            }
        }
        take
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn windows_and_subsets_match_hand_computed_sums() {
        // Drones 5, 3, 9: sums 0, 3, 5, 8, 9, 12, 14, 17.
        let p = [5u64, 3, 9];
        let mut t = SubsetSums::default();
        t.build(&p, &[0, 1, 2], 70);
        let sums: Vec<usize> = (0..=70).filter(|&s| t.reachable(3, s)).collect();
        assert_eq!(sums, vec![0, 3, 5, 8, 9, 12, 14, 17]);
        assert!(t.any_in(3, 15, 17));
        assert!(!t.any_in(3, 15, 16));
        assert!(!t.any_in(3, 18, 70));
        assert!(!t.any_in(2, 9, 9), "9 needs the third drone");
        assert!(t.any_in(1, 5, 5));
        assert!(!t.any_in(3, 10, 9), "an empty window");
        assert_eq!(t.subset(&p, &[0, 1, 2], 14), vec![true, false, true]);
    }

    /// Shifts that cross words (70, 130) and a word's last bit: every window against the sums
    /// of all 16 subsets, enumerated.
    #[test]
    fn windows_across_words_match_a_scan() {
        let p = [61u64, 70, 130, 7];
        let mut t = SubsetSums::default();
        t.build(&p, &[0, 1, 2, 3], 300);
        let sums: Vec<usize> = (0..16usize)
            .map(|mask| {
                (0..4)
                    .filter(|&j| mask >> j & 1 == 1)
                    .map(|j| p[j] as usize)
                    .sum()
            })
            .collect();
        for s in 0..=300 {
            assert_eq!(t.reachable(4, s), sums.contains(&s), "sum {s}");
        }
        for lo in 0..=300 {
            for hi in lo..=(lo + 70).min(300) {
                let scan = sums.iter().any(|&s| (lo..=hi).contains(&s));
                assert_eq!(t.any_in(4, lo, hi), scan, "{lo}..={hi}");
            }
        }
    }
}
