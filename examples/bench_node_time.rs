//! Benchmark of the node-time methods (P||Cmax) on seeded uniform random charge times.
//!
//! ```text
//! cargo run --release --example bench_node_time -- [SEED] [quick]
//! ```
//!
//! Reports: the exact branch and bound's median and worst time up to 30 drones / 10 pads; the two
//! searches after its first phase (sequential partitioning, bin completion) side by side; 100-job /
//! 10-pad instances proven optimal; the route planner's small real-valued cases (n <= 12, k <= 4);
//! the MILP on every enabled backend on smaller instances with a
//! time limit; and the speed-up of exact over the paper's brute force where brute force finishes.
//! Integer times follow the classic P||Cmax classes (uniform whole minutes in [1,100], [1,1000],
//! [1,10000], and [20,100], [50,100] for 100 jobs); continuous times are uniform reals in [1,100).

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use swarmplan::node_time::{brute, exact, exact_with, lpt, milp, ExactSearch, Limits};
use swarmplan::solver::{MilpBackend, SolveStatus};

fn instance(rng: &mut ChaCha8Rng, n: usize, lo: u32, hi: u32, integral: bool) -> Vec<f64> {
    // Whole minutes U[lo, hi], or reals U[lo, hi).
    (0..n)
        .map(|_| {
            if integral {
                f64::from(rng.random_range(lo..=hi))
            } else {
                rng.random_range(f64::from(lo)..f64::from(hi))
            }
        })
        .collect()
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seed: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(1);
    let quick = args.iter().any(|a| a == "quick");
    let reps = if quick { 20 } else { 100 };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let no_limits = Limits::default();
    let limited = Limits {
        time_limit_s: Some(10.0),
        node_limit: None,
    };
    let one_second = Limits {
        time_limit_s: Some(1.0),
        node_limit: None,
    };

    println!("# exact branch and bound, {reps} instances per row (seed {seed}), time limit 1 s");
    println!("times           n   k  median_ms    max_ms  proven  lpt_optimal");
    for (label, hi, integral) in [
        ("int[1,100]", 100, true),
        ("int[1,1000]", 1000, true),
        ("int[1,10000]", 10000, true),
        ("real[1,100)", 100, false),
    ] {
        for &n in &[10usize, 20, 30] {
            for k in 2usize..=10 {
                let mut ms = Vec::with_capacity(reps);
                let mut proven = 0;
                let mut lpt_opt = 0;
                for _ in 0..reps {
                    let t = instance(&mut rng, n, 1, hi, integral);
                    let s = exact(k, &t, &one_second).expect("valid instance");
                    let l = lpt(k, &t).expect("valid instance");
                    ms.push(s.solve_ms);
                    proven += usize::from(s.status == SolveStatus::Optimal);
                    lpt_opt += usize::from(l.makespan_min <= s.makespan_min * (1.0 + 1e-9));
                }
                let max = ms.iter().copied().fold(0.0, f64::max);
                println!(
                    "{label:<13} {n:>3} {k:>3} {:>10.4} {max:>9.3} {proven:>4}/{reps} {lpt_opt:>6}/{reps}",
                    median(&mut ms)
                );
            }
        }
    }

    let reps_cmp = if quick { 5 } else { 20 };
    let two_seconds = Limits {
        time_limit_s: Some(2.0),
        node_limit: None,
    };
    println!(
        "\n# the two searches after phase 1 on real[1,100), {reps_cmp} instances per row, \
         time limit 2 s (exact picks partitioning for n > 4k, k <= 7, n <= 40)"
    );
    println!(
        "  n   k  partition_median_ms  max_ms  proven  bin_completion_median_ms  max_ms  proven  agree"
    );
    let mut rng_c = ChaCha8Rng::seed_from_u64(seed ^ 0xc0);
    for &(n, k) in &[
        (20usize, 2usize),
        (18, 3),
        (20, 4),
        (25, 3),
        (30, 2),
        (30, 3),
        (30, 4),
        (30, 5),
        (30, 6),
        (20, 5),
        (24, 6),
        (28, 7),
        (30, 7),
        (30, 8),
        (32, 8),
        (30, 10),
        (35, 3),
        (40, 4),
        (40, 5),
    ] {
        let (mut pm, mut bm) = (Vec::new(), Vec::new());
        let (mut pp, mut bp, mut agree) = (0, 0, 0);
        for _ in 0..reps_cmp {
            let t = instance(&mut rng_c, n, 1, 100, false);
            let a = exact_with(k, &t, &two_seconds, ExactSearch::Partition).expect("valid");
            let b = exact_with(k, &t, &two_seconds, ExactSearch::BinCompletion).expect("valid");
            pm.push(a.solve_ms);
            bm.push(b.solve_ms);
            let (ao, bo) = (
                a.status == SolveStatus::Optimal,
                b.status == SolveStatus::Optimal,
            );
            pp += usize::from(ao);
            bp += usize::from(bo);
            agree += usize::from(
                ao && bo && (a.makespan_min - b.makespan_min).abs() <= 1e-9 * b.makespan_min,
            );
        }
        let (pmax, bmax) = (
            pm.iter().copied().fold(0.0, f64::max),
            bm.iter().copied().fold(0.0, f64::max),
        );
        println!(
            "{n:>3} {k:>3} {:>20.3} {pmax:>7.1} {pp:>4}/{reps_cmp} {:>25.3} {bmax:>7.1} {bp:>4}/{reps_cmp} {agree:>4}/{reps_cmp}",
            median(&mut pm),
            median(&mut bm)
        );
    }

    let reps_small = if quick { 500 } else { 5000 };
    let mut rng_s = ChaCha8Rng::seed_from_u64(seed ^ 0x5a11);
    println!(
        "\n# exact on small real-valued cases (route planner sizes), n in [2,12], k in [2,4], \
         real[1,100), {reps_small} instances per row"
    );
    println!("  k  median_us  p90_us    max_us  proven");
    for &k in &[2usize, 3, 4] {
        let mut us = Vec::with_capacity(reps_small);
        let mut proven = 0;
        for _ in 0..reps_small {
            let n = rng_s.random_range(2..=12);
            let t = instance(&mut rng_s, n, 1, 100, false);
            let s = exact(k, &t, &no_limits).expect("valid instance");
            us.push(s.solve_ms * 1000.0);
            proven += usize::from(s.status == SolveStatus::Optimal);
        }
        let max = us.iter().copied().fold(0.0, f64::max);
        let med = median(&mut us);
        let p90 = us[us.len() * 9 / 10];
        println!("{k:>3} {med:>10.2} {p90:>7.2} {max:>9.1} {proven:>5}/{reps_small}");
    }

    let reps100 = if quick { 5 } else { 20 };
    println!("\n# exact on 100 jobs / 10 pads, {reps100} instances per class, time limit 10 s");
    println!("times         median_ms    max_ms  proven");
    for (label, lo, hi, integral) in [
        ("int[1,100]", 1, 100, true),
        ("int[20,100]", 20, 100, true),
        ("int[50,100]", 50, 100, true),
        ("real[1,100)", 1, 100, false),
    ] {
        let mut ms = Vec::new();
        let mut proven = 0;
        for _ in 0..reps100 {
            let t = instance(&mut rng, 100, lo, hi, integral);
            let s = exact(10, &t, &limited).expect("valid instance");
            ms.push(s.solve_ms);
            proven += usize::from(s.status == SolveStatus::Optimal);
        }
        let max = ms.iter().copied().fold(0.0, f64::max);
        println!(
            "{label:<12} {:>10.3} {max:>9.3} {proven:>4}/{reps100}",
            median(&mut ms)
        );
    }

    let reps_milp = if quick { 3 } else { 5 };
    println!("\n# MILP vs exact, int[1,100], {reps_milp} instances per row, time limit 10 s");
    println!(
        "backend     n   k  milp_median_ms  milp_max_ms  milp_optimal  exact_median_ms  agree"
    );
    for backend in MilpBackend::all() {
        for &(n, k) in &[(10usize, 3usize), (20, 5), (30, 10), (100, 10)] {
            let mut rng_b = ChaCha8Rng::seed_from_u64(seed ^ (n as u64 * 31 + k as u64));
            let mut ms = Vec::new();
            let mut ems = Vec::new();
            let mut optimal = 0;
            let mut agree = 0;
            for _ in 0..reps_milp {
                let t = instance(&mut rng_b, n, 1, 100, true);
                let e = exact(k, &t, &limited).expect("valid instance");
                ems.push(e.solve_ms);
                match milp(k, &t, backend, &limited) {
                    Ok(s) => {
                        ms.push(s.solve_ms);
                        optimal += usize::from(s.status == SolveStatus::Optimal);
                        agree += usize::from((s.makespan_min - e.makespan_min).abs() < 1e-6);
                    }
                    Err(err) => {
                        ms.push(10_000.0);
                        eprintln!("milp {} n={n} k={k}: {err}", backend);
                    }
                }
            }
            let max = ms.iter().copied().fold(0.0, f64::max);
            println!(
                "{:<8} {n:>4} {k:>3} {:>15.2} {max:>12.2} {optimal:>9}/{reps_milp} {:>16.4} {agree:>4}/{reps_milp}",
                backend.to_string(),
                median(&mut ms),
                median(&mut ems)
            );
        }
    }

    let reps_brute = if quick { 3 } else { 10 };
    println!("\n# exact vs the paper's brute force, int[1,100], {reps_brute} instances per row");
    println!("  n   k  brute_median_ms  exact_median_ms  speed-up  agree");
    for &(n, k) in &[
        (8usize, 2usize),
        (8, 3),
        (10, 3),
        (12, 3),
        (10, 4),
        (12, 4),
        (10, 5),
    ] {
        let mut bms = Vec::new();
        let mut ems = Vec::new();
        let mut agree = 0;
        for _ in 0..reps_brute {
            let t = instance(&mut rng, n, 1, 100, true);
            let b = brute(k, &t, &no_limits).expect("within the brute-force limit");
            let e = exact(k, &t, &no_limits).expect("valid instance");
            bms.push(b.solve_ms);
            ems.push(e.solve_ms);
            agree += usize::from(b.makespan_min == e.makespan_min);
        }
        let bm = median(&mut bms);
        let em = median(&mut ems);
        println!(
            "{n:>3} {k:>3} {bm:>16.3} {em:>16.4} {:>9.0}x {agree:>3}/{reps_brute}",
            bm / em.max(1e-6)
        );
    }
}
