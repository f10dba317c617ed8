//! Median, mean and worst solve time of `exact` on seeded random swarms of one size, for one of
//! the phase-2 searches; or the three searches on one swarm read from a file.
//!
//! ```text
//! cargo run --release --example node_time_sample -- DRONES PADS KIND COUNT [SEARCH] [SEED]
//! cargo run --release --example node_time_sample -- file TIMES.txt PADS
//! ```
//!
//! `KIND`: `real` (uniform in [1,100) min), `int100`, `int1000`, `int10000` (whole minutes in
//! [1,100], [1,1000], [1,10000]). `SEARCH`: `auto` (what `exact` does, the default), `bc` (bin
//! completion), `part` (sequential partitioning). `SEED` defaults to 7. `TIMES.txt` holds charge
//! times separated by commas. The `check` column is the sum of the node times, to compare runs.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use swarmplan::node_time::{exact_with, ExactSearch, Limits};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: node_time_sample DRONES PADS KIND COUNT [auto|bc|part] [SEED] \
                 | node_time_sample file TIMES.txt PADS";
    let arg = |i: usize| -> &str {
        args.get(i)
            .map_or_else(|| panic!("{usage}"), |s| s.as_str())
    };
    let limits = Limits {
        time_limit_s: Some(20.0),
        node_limit: None,
    };
    if arg(1) == "file" {
        let text = std::fs::read_to_string(arg(2)).expect("a readable file of times");
        let times: Vec<f64> = text
            .trim()
            .split(',')
            .map(|x| x.trim().parse().expect("a number"))
            .collect();
        let pads: usize = arg(3).parse().expect(usage);
        for search in [
            ExactSearch::Auto,
            ExactSearch::BinCompletion,
            ExactSearch::Partition,
        ] {
            let s = exact_with(pads, &times, &limits, search).expect("a valid instance");
            println!(
                "{search:?}: {:.2} ms, node time {} min, {:?}",
                s.solve_ms, s.makespan_min, s.status
            );
        }
        return;
    }
    let drones: usize = arg(1).parse().expect(usage);
    let pads: usize = arg(2).parse().expect(usage);
    let kind = arg(3);
    let count: usize = arg(4).parse().expect(usage);
    let search = match args.get(5).map(String::as_str) {
        Some("bc") => ExactSearch::BinCompletion,
        Some("part") => ExactSearch::Partition,
        _ => ExactSearch::Auto,
    };
    let seed: u64 = args.get(6).and_then(|s| s.parse().ok()).unwrap_or(7);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut ms = Vec::with_capacity(count);
    let mut check = 0.0;
    let mut proven = 0;
    for _ in 0..count {
        let times: Vec<f64> = (0..drones)
            .map(|_| match kind {
                "real" => rng.random_range(1.0..100.0),
                "int100" => f64::from(rng.random_range(1..=100u32)),
                "int1000" => f64::from(rng.random_range(1..=1000u32)),
                "int10000" => f64::from(rng.random_range(1..=10000u32)),
                _ => panic!("{usage}"),
            })
            .collect();
        let s = exact_with(pads, &times, &limits, search).expect("a valid instance");
        ms.push(s.solve_ms);
        check += s.makespan_min;
        proven += usize::from(s.status == swarmplan::solver::SolveStatus::Optimal);
    }
    let mean = ms.iter().sum::<f64>() / count as f64;
    ms.sort_by(f64::total_cmp);
    println!(
        "{drones}/{pads} {kind} {search:?} seed {seed}: median {:.3} ms, mean {:.3}, max {:.2}, \
         proven {proven}/{count}, check {check:.6}",
        ms[count / 2],
        mean,
        ms[count - 1]
    );
}
