//! Benchmark of the exact node time on the classical P||Cmax benchmark classes
//! (`src/generate/pcmax.rs`, `models/generate.md`).
//!
//! ```text
//! cargo run --release --example bench_pcmax_classes -- [--classes u1,nu1,...] [--sizes 50x5,100x10,...]
//!     [--time-limit 10] [--reps 10] [--seed 1]
//! ```
//!
//! Per class and size `n x m`, `--reps` instances with seeds `seed, seed + 1, ...` (the same files
//! as `swarmplan generate node-time --class C --jobs n --pads m --seed s`), each solved by
//! `node_time::exact` with a wall-clock limit of `--time-limit` seconds (as `node-time
//! --time-limit`; `--limit-s`, its former name, still works). Reports the instances proven
//! optimal, the median and worst solve time, and how each proven optimum was cross-checked:
//! - every returned assignment is re-evaluated from the raw times (each job once, makespan = the
//!   largest load), independently of the solver;
//! - `bound`: the optimum equals the simple lower bound `max(ceil(sum/m), p_max, p_m + p_{m+1})`
//!   (times sorted descending), computed here, so no search is needed to trust it;
//! - `brute`: the paper's brute force agrees (only where `m^n <= 1e8`);
//! - `card`: the optimum equals the cardinality bound (`models/node_time.md`, "Lower bounds
//!   (root)"), written out here separately from the solver's code: for the `N` longest jobs and
//!   `s` pads, the `s` pads holding the most of them hold at least `s floor(N/m) + min(s, N mod m)`;
//! - `milp`: the assignment MILP on the default backend agrees (only `n <= 12`, 60 s limit);
//! - `lp`: the bin-packing LP bound (`node_time::lp_lower_bound`, column generation rounded by
//!   Farley's bound, 60 s limit) equals the optimum, a second proof of the lower bound,
//!   independent of the search that proved it;
//! - otherwise the optimum is unchecked (`unchk`).
//!
//! Any disagreement is printed as `WRONG` and counted. Default grid: `u*`, `nu*` at n in {50, 100},
//! m in {5, 10, 25}; `l*` at (40, 20) and (100, 40) (n/m = 2 and 2.5, published sizes); the
//! `e*` classes at their largest published sizes, `e4-*` at (10, 2) and (9, 3).

use swarmplan::generate::pcmax::{generate_pcmax, PcmaxClass, PcmaxParams};
use swarmplan::node_time::{brute, exact, lp_lower_bound, milp, Limits};
use swarmplan::solver::{MilpBackend, SolveStatus};

fn default_sizes(c: PcmaxClass) -> Vec<(usize, usize)> {
    let name = c.name();
    if name.starts_with('u') || name.starts_with("nu") {
        vec![(50, 5), (50, 10), (50, 25), (100, 5), (100, 10), (100, 25)]
    } else if name.starts_with('l') {
        vec![(40, 20), (100, 40)]
    } else if name.starts_with("e1") {
        vec![(25, 5)]
    } else if name.starts_with("e2") {
        vec![(100, 3), (100, 10)]
    } else if name.starts_with("e3") {
        vec![(52, 10)]
    } else {
        vec![(10, 2), (9, 3)]
    }
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Makespan of `assignment` recomputed from the raw times; `None` unless every job appears once.
fn check_assignment(times: &[f64], assignment: &[Vec<usize>]) -> Option<f64> {
    let mut seen = vec![false; times.len()];
    let mut worst = 0.0f64;
    for pad in assignment {
        let mut load = 0.0;
        for &j in pad {
            if j >= times.len() || seen[j] {
                return None;
            }
            seen[j] = true;
            load += times[j];
        }
        worst = worst.max(load);
    }
    seen.iter().all(|&s| s).then_some(worst)
}

/// `max(ceil(sum/m), p_max, p_m + p_{m+1})` for whole-number times.
fn simple_bound(times: &[f64], m: usize) -> f64 {
    let mut t = times.to_vec();
    t.sort_by(|a, b| b.total_cmp(a));
    let sum: f64 = t.iter().sum();
    let mut lb = (sum / m as f64).ceil().max(t[0]);
    if t.len() > m {
        lb = lb.max(t[m - 1] + t[m]);
    }
    lb
}

/// The cardinality bound, computed directly: for each `N`, the `N` longest times in increasing
/// order; for each `s` in `1..=m`, the `s` pads holding the most of them hold at least
/// `h = s floor(N/m) + min(s, N mod m)`, which weigh at least the `h` shortest, so one pad at least
/// `ceil(that / s)` (whole-number times).
fn cardinality_bound(times: &[f64], m: usize) -> f64 {
    let mut t = times.to_vec();
    t.sort_by(|a, b| b.total_cmp(a));
    let mut lb = 0.0_f64;
    for big in 1..=t.len() {
        let mut longest: Vec<f64> = t[..big].to_vec();
        longest.reverse();
        for s in 1..=m.min(big) {
            let h = s * (big / m) + s.min(big % m);
            let weight: f64 = longest[..h].iter().sum();
            lb = lb.max((weight / s as f64).ceil());
        }
    }
    lb
}

fn arg<'a>(args: &'a [String], key: &str) -> Option<&'a str> {
    args.iter()
        .position(|a| a == key)
        .and_then(|i| args.get(i + 1))
        .map(String::as_str)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let limit_s: f64 = arg(&args, "--time-limit")
        .or_else(|| arg(&args, "--limit-s"))
        .map_or(10.0, |s| s.parse().expect("--time-limit: seconds"));
    let reps: u64 = arg(&args, "--reps").map_or(10, |s| s.parse().expect("--reps"));
    let seed0: u64 = arg(&args, "--seed").map_or(1, |s| s.parse().expect("--seed"));
    let classes: Vec<PcmaxClass> = match arg(&args, "--classes") {
        Some(list) => list
            .split(',')
            .map(|s| PcmaxClass::from_name(s).unwrap_or_else(|| panic!("unknown class {s}")))
            .collect(),
        None => PcmaxClass::ALL.to_vec(),
    };
    let sizes: Option<Vec<(usize, usize)>> = arg(&args, "--sizes").map(|list| {
        list.split(',')
            .map(|s| {
                let (n, m) = s.split_once('x').expect("--sizes: NxM,NxM,...");
                (n.parse().expect("n"), m.parse().expect("m"))
            })
            .collect()
    });
    let limits = Limits {
        time_limit_s: Some(limit_s),
        node_limit: None,
    };
    let milp_limits = Limits {
        time_limit_s: Some(60.0),
        node_limit: None,
    };

    println!(
        "# exact node time on the P||Cmax classes: {reps} seeded instances per row (seeds {seed0}..{}), limit {limit_s} s",
        seed0 + reps - 1
    );
    println!(
        "{:<11} {:>4} {:>3} {:>6} {:>10} {:>10} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5}  open (lb..ub)",
        "class",
        "n",
        "m",
        "proven",
        "median_ms",
        "worst_ms",
        "bound",
        "brute",
        "card",
        "milp",
        "lp",
        "unchk",
        "wrong"
    );
    let mut total_wrong = 0;
    let (mut total, mut total_proven) = (0, 0);
    for &class in &classes {
        let rows = sizes.clone().unwrap_or_else(|| default_sizes(class));
        for (n, m) in rows {
            let mut ms = Vec::new();
            let (mut proven, mut by_bound, mut by_brute, mut by_card) = (0, 0, 0, 0);
            let (mut by_milp, mut by_lp) = (0, 0);
            let (mut unchecked, mut wrong) = (0, 0);
            let mut open = Vec::new();
            for seed in seed0..seed0 + reps {
                let file = generate_pcmax(&PcmaxParams {
                    class,
                    jobs: n,
                    pads: m,
                    seed,
                })
                .expect("valid parameters");
                let times: Vec<f64> = file.charge_times_min.iter().map(|&t| t as f64).collect();
                let s = exact(m, &times, &limits).expect("valid instance");
                ms.push(s.solve_ms);
                if check_assignment(&times, &s.assignment) != Some(s.makespan_min) {
                    wrong += 1;
                    println!(
                        "WRONG {class} {n}x{m} seed {seed}: assignment does not give its makespan"
                    );
                }
                if s.status != SolveStatus::Optimal {
                    open.push(format!("{}..{}", s.lower_bound_min, s.makespan_min));
                    continue;
                }
                proven += 1;
                let lb = simple_bound(&times, m);
                let bf_ok = (m.min(n) as f64).powi(n as i32) <= 1e8;
                if s.makespan_min < lb {
                    wrong += 1;
                    println!(
                        "WRONG {class} {n}x{m} seed {seed}: {} below bound {lb}",
                        s.makespan_min
                    );
                } else if bf_ok {
                    let b = brute(m, &times, &Limits::default()).expect("small instance");
                    if b.makespan_min == s.makespan_min {
                        by_brute += 1;
                    } else {
                        wrong += 1;
                        println!(
                            "WRONG {class} {n}x{m} seed {seed}: exact {} brute {}",
                            s.makespan_min, b.makespan_min
                        );
                    }
                } else if s.makespan_min == lb {
                    by_bound += 1;
                } else if s.makespan_min < cardinality_bound(&times, m) {
                    wrong += 1;
                    println!(
                        "WRONG {class} {n}x{m} seed {seed}: {} below the cardinality bound",
                        s.makespan_min
                    );
                } else if s.makespan_min == cardinality_bound(&times, m) {
                    by_card += 1;
                } else if n <= 12 {
                    let l =
                        milp(m, &times, MilpBackend::default(), &milp_limits).expect("milp runs");
                    if l.status == SolveStatus::Optimal && l.makespan_min == s.makespan_min {
                        by_milp += 1;
                    } else if l.status == SolveStatus::Optimal {
                        wrong += 1;
                        println!(
                            "WRONG {class} {n}x{m} seed {seed}: exact {} milp {}",
                            s.makespan_min, l.makespan_min
                        );
                    } else {
                        unchecked += 1;
                    }
                } else {
                    let bound = lp_lower_bound(m, &times, &milp_limits).expect("valid instance");
                    if bound > s.makespan_min {
                        wrong += 1;
                        println!(
                            "WRONG {class} {n}x{m} seed {seed}: exact {} below the LP bound {bound}",
                            s.makespan_min
                        );
                    } else if bound == s.makespan_min {
                        by_lp += 1;
                    } else {
                        unchecked += 1;
                    }
                }
            }
            let worst = ms.iter().copied().fold(0.0, f64::max);
            println!(
                "{:<11} {:>4} {:>3} {:>3}/{:<2} {:>10.2} {:>10.2} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5} {:>5}  {}",
                class.name(),
                n,
                m,
                proven,
                reps,
                median(&mut ms),
                worst,
                by_bound,
                by_brute,
                by_card,
                by_milp,
                by_lp,
                unchecked,
                wrong,
                open.join(" ")
            );
            total += reps;
            total_proven += proven;
            total_wrong += wrong;
        }
    }
    println!("# total: {total_proven}/{total} proven, {total_wrong} wrong");
}
