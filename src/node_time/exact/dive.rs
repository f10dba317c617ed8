//! Search for an assignment within a capacity guided by the bin-packing LP: the LP dive of
//! `bounds/lp.rs` fixes pads one LP solution at a time; where it ends short of placing every
//! drone, bin completion (`completion.rs`) packs the drones left, and when it cannot, the last
//! pads fixed are released and packed again with them (1, 2, 4, ... pads back). See
//! `models/node_time.md`, "LP dive".
//!
//! It serves where the LP bound is the node time but bin completion, the perfect-partition
//! search and the repacking do not reach it: Lawrinenko's class 6 at 100 drones on 40 pads (two
//! or three drones per pad; `models/experiments/node_time.md`).

use super::completion::BinCompletion;
use crate::node_time::bounds::lp::LpBound;
use crate::node_time::search::{Budget, Decision, Memo};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Bin-completion nodes of one attempt to pack the drones the dive left.
const DIVE_COMPLETION_NODES: u64 = 50_000;

/// Looks for an assignment of the drones `p` (whole minutes, sorted decreasingly, positive; the
/// drones `lp` was built from) on `m` pads with every load `<= cap` by one dive: dive `0`
/// follows the LP's largest values, dive `attempt > 0` draws with a generator seeded by
/// `attempt`. Returns the pad of each drone, or `None` when neither the dive nor the
/// completions found one (which proves nothing).
///
/// Complexity: one dive ([`LpBound::dive`]), then at most `log2 m + 2` bin completions of at
/// most [`DIVE_COMPLETION_NODES`] nodes each ([`complete_dive`]).
pub(crate) fn lp_dive(
    m: usize,
    p: &[f64],
    cap: f64,
    attempt: u64,
    lp: &LpBound,
    budget: &mut Budget,
) -> Option<Vec<usize>> {
    let mut rng = ChaCha8Rng::seed_from_u64(0xd1e5_0000 ^ attempt);
    let (fixed, complete) = lp.dive(m, cap, (attempt > 0).then_some(&mut rng), budget);
    // The drones of type `t` are the `d_t` consecutive ones from `first[t]`.
    let first: Vec<usize> = lp
        .counts()
        .iter()
        .scan(0usize, |at, &c| {
            let start = *at;
            *at += c as usize;
            Some(start)
        })
        .collect();
    complete_dive(m, p, cap, &first, &fixed, complete, budget)
}

/// Packs the drones the dive's pads `fixed` leave by bin completion, releasing the last 1, 2,
/// 4, ... of those pads when it cannot.
fn complete_dive(
    m: usize,
    p: &[f64],
    cap: f64,
    first: &[usize],
    fixed: &[Vec<u64>],
    complete: bool,
    budget: &mut Budget,
) -> Option<Vec<usize>> {
    let mut back = usize::from(!complete);
    loop {
        let kept = fixed.len().saturating_sub(back);
        let mut pad_of = vec![usize::MAX; p.len()];
        let mut next = first.to_vec();
        for (i, a) in fixed[..kept].iter().enumerate() {
            for (t, &c) in a.iter().enumerate() {
                for _ in 0..c {
                    pad_of[next[t]] = i;
                    next[t] += 1;
                }
            }
        }
        let rest: Vec<usize> = (0..p.len()).filter(|&j| pad_of[j] == usize::MAX).collect();
        if rest.is_empty() {
            return Some(pad_of);
        }
        let sub_p: Vec<f64> = rest.iter().map(|&j| p[j]).collect();
        let mut search = BinCompletion::new(&sub_p, m - kept, cap, true, Memo::default());
        let decision = budget.within(DIVE_COMPLETION_NODES, |sub| search.decide(sub));
        if decision == Decision::Fits {
            for (a, &j) in rest.iter().enumerate() {
                pad_of[j] = kept + search.pad_of[a];
            }
            return Some(pad_of);
        }
        if kept == 0 || budget.spent() {
            return None;
        }
        back *= 2;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::node_time::Limits;
    use rand::Rng;

    /// Smallest capacity at which bin completion alone (no dive) fits the drones on `m` pads.
    fn optimum_by_bin_completion(m: usize, p: &[f64]) -> f64 {
        let limits = Limits::default();
        let sum: f64 = p.iter().sum();
        let mut c = (sum / m as f64).ceil().max(p[0]);
        loop {
            let mut budget = Budget::new(&limits);
            let mut search = BinCompletion::new(p, m, c, true, Memo::default());
            match search.decide(&mut budget) {
                Decision::Fits => return c,
                Decision::DoesNotFit => c += 1.0,
                Decision::Stopped => panic!("bin completion stopped"),
            }
        }
    }

    /// An assignment's largest load, when every drone has a pad among `m`.
    fn makespan(m: usize, p: &[f64], pad_of: &[usize]) -> Option<f64> {
        let mut loads = vec![0.0; m];
        for (j, &i) in pad_of.iter().enumerate() {
            *loads.get_mut(i)? += p[j];
        }
        (pad_of.len() == p.len()).then(|| loads.iter().copied().fold(0.0, f64::max))
    }

    /// Seeded swarms of two to three drones per pad, lengths 20 to 80 min (Lawrinenko's class 6
    /// in small). At the optimum found by bin completion alone, a complete dive's pads hold every
    /// drone once within it, every assignment [`lp_dive`] returns is valid (each drone on one of
    /// the pads, no load above it), and both succeed on most swarms; one minute below, no dive
    /// may return anything, since nothing fits there.
    #[test]
    fn dives_find_valid_assignments_at_the_optimum_and_none_below() {
        let limits = Limits::default();
        let mut rng = ChaCha8Rng::seed_from_u64(18);
        let (mut found, mut dived, cases) = (0, 0, 120);
        for _ in 0..cases {
            let m = rng.random_range(4..=8);
            let n = m * 2 + rng.random_range(0..=m);
            let mut p: Vec<f64> = (0..n)
                .map(|_| f64::from(rng.random_range(20..=80)))
                .collect();
            p.sort_by(|a, b| b.total_cmp(a));
            let opt = optimum_by_bin_completion(m, &p);
            let mut budget = Budget::new(&limits);
            let lp = LpBound::new(&p, true);
            // The dive alone: its pads, when complete, hold every drone within `opt`.
            let (pads, complete) = lp.dive(m, opt, None, &mut budget);
            if complete {
                let first: Vec<usize> = (0..p.len())
                    .filter(|&j| j == 0 || p[j] != p[j - 1])
                    .collect();
                let mut held = vec![0u64; first.len()];
                for a in &pads {
                    let weight: f64 = a.iter().zip(&first).map(|(&c, &j)| c as f64 * p[j]).sum();
                    assert!(weight <= opt, "pad {a:?} weighs {weight} above {opt}");
                    for (h, &c) in held.iter_mut().zip(a) {
                        *h += c;
                    }
                }
                assert_eq!(held, lp.counts(), "{p:?}");
                assert!(pads.len() <= m);
                dived += 1;
            }
            if let Some(pad_of) = (0..3).find_map(|a| lp_dive(m, &p, opt, a, &lp, &mut budget)) {
                let got = makespan(m, &p, &pad_of).expect("every drone on a pad");
                assert!(got <= opt, "{got} above {opt} for {p:?} on {m}");
                found += 1;
            }
            let below = (0..3).find_map(|a| lp_dive(m, &p, opt - 1.0, a, &lp, &mut budget));
            assert_eq!(below, None, "{p:?} on {m} pads below {opt}");
        }
        // Measured: the dive alone completes on 116 of the 120, with the completions all 120.
        assert!(
            dived >= cases * 5 / 6,
            "dives complete on {dived} of {cases}"
        );
        assert!(found >= cases * 9 / 10, "found {found} of {cases}");
    }
}
