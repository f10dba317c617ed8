//! How far the proven node time lies above the root lower bound on seeded uniform random charge
//! times: the quantity that decides whether the exact search has to refute assignments (see
//! `models/node_time.md`, "Expected excess of the optimum over `sum/k`"; measured figures in
//! `models/experiments/node_time.md`, "Optimum above the bound").
//!
//! ```text
//! cargo run --release --example optimum_above_bound -- [SEED]
//! ```
//!
//! For 30 drones per row, 21 instances: the median, least and largest `nt - LB` in minutes, with
//! `LB = max(sum/k, p_1, p_k + p_{k+1})` (rounded up for whole minutes), and how many instances
//! have their optimum at the bound (within the tolerance for real minutes).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use swarmplan::node_time::{exact, Limits, REL_TOL};
use swarmplan::solver::SolveStatus;

const DRONES: usize = 30;
const INSTANCES: usize = 21;

fn main() {
    let seed: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    println!("# nt - LB (min), {DRONES} drones, {INSTANCES} instances per row (seed {seed})");
    println!("times          k      median       least     largest  at_bound");
    for (label, hi, integral) in [
        ("int[1,10000]", 10000u32, true),
        ("real[1,100)", 100, false),
    ] {
        for k in [3usize, 5, 7, 9] {
            let mut gaps = Vec::with_capacity(INSTANCES);
            let mut at_bound = 0;
            for _ in 0..INSTANCES {
                let times: Vec<f64> = (0..DRONES)
                    .map(|_| {
                        if integral {
                            f64::from(rng.random_range(1..=hi))
                        } else {
                            rng.random_range(1.0..f64::from(hi))
                        }
                    })
                    .collect();
                let s = exact(k, &times, &Limits::default()).expect("valid instance");
                assert_eq!(s.status, SolveStatus::Optimal, "no limit: proven");
                let mut sorted = times.clone();
                sorted.sort_by(|a, b| b.total_cmp(a));
                let sum: f64 = times.iter().sum();
                let lb = (sum / k as f64)
                    .max(sorted[0])
                    .max(sorted[k - 1] + sorted[k]);
                let lb = if integral { lb.ceil() } else { lb };
                let gap = s.makespan_min - lb;
                at_bound += usize::from(gap <= REL_TOL * lb);
                gaps.push(gap);
            }
            gaps.sort_by(f64::total_cmp);
            println!(
                "{label:<13} {k:>2} {:>11.3e} {:>11.3e} {:>11.3e} {at_bound:>5}/{INSTANCES}",
                gaps[INSTANCES / 2],
                gaps[0],
                gaps[INSTANCES - 1]
            );
        }
    }
}
