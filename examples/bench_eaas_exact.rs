//! Solve time of the hop MILP (node time on 2 pads) against swarm size and number of periods, for
//! each re-ordering mode, with the fluid LP bound's time beside it. Seeded random hops: `D`
//! delivery and `S` support drones (capacity 100 mAh) on the library's Vee with 0.7 m spacing
//! (range 1.2 m), one leg of `P` minutes on a 1-minute grid, rates 2-6 mAh/min varying by slot, rho = 8 mAh/min
//! (both times 16 / P beyond 16 periods),
//! delivery batteries 30-100 mAh (some need sharing to fly), support drones full. Three hops per
//! size; each reported time is the median, with the status counts.
//!
//! `cargo run --release --example bench_eaas_exact [-- TIME_LIMIT_S [BACKEND [D,S,P ...]]]`
//! (default 30 s per solve, the first backend of the build, and the sizes below); with the
//! `highs` feature, `-- 10 highs 10,3,30` times the goal size (10 delivery and 3 support
//! drones, 30 periods).

#[path = "common/bench_hop.rs"]
mod bench_hop;
use bench_hop::hop;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use swarmplan::eaas::exact::fluid;
use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactStatus, Objective, Reorder};
use swarmplan::solver::MilpBackend;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let time_limit_s: f64 = args.first().and_then(|a| a.parse().ok()).unwrap_or(30.0);
    let backend = match args.get(1).map(String::as_str) {
        None => MilpBackend::default(),
        Some(name) => *MilpBackend::all()
            .iter()
            .find(|b| b.to_string() == name)
            .unwrap_or_else(|| panic!("backend {name} is not in this build")),
    };
    let mut sizes: Vec<(usize, usize, usize)> = args
        .iter()
        .skip(2)
        .map(|a| {
            let v: Vec<usize> = a.split(',').map(|x| x.parse().expect("D,S,P")).collect();
            (v[0], v[1], v[2])
        })
        .collect();
    if sizes.is_empty() {
        for (nd, ns) in [(2, 1), (3, 1), (4, 2), (5, 2)] {
            for periods in [4, 8, 16] {
                sizes.push((nd, ns, periods));
            }
        }
    }
    let objective = Objective::NodeTime(EndPads {
        pads: 2,
        pad_rate_mah_per_min: 10.0,
    });
    println!(
        "backend {}, time limit {time_limit_s} s per solve, 3 hops per row",
        backend
    );
    println!("| D | S | periods | reorder | milp median ms | statuses (opt/feas/infeas/none) | fluid median ms | fair QP median ms |");
    println!("|---|---|---|---|---|---|---|---|");
    for &(nd, ns, periods) in &sizes {
        {
            for reorder in [Reorder::None, Reorder::Paper, Reorder::Free] {
                let mut rng = ChaCha8Rng::seed_from_u64(1000 + 10 * nd as u64 + ns as u64);
                let (mut ms, mut fl, mut fq, mut counts) =
                    (Vec::new(), Vec::new(), Vec::new(), [0usize; 4]);
                for _ in 0..3 {
                    let p = hop(&mut rng, nd, ns, periods);
                    let o = solve_milp(
                        &p,
                        &objective,
                        &MilpOptions {
                            period_min: 1.0,
                            reorder,
                            backend,
                            time_limit_s,
                            node_limit: None,
                        },
                    )
                    .expect("valid hop");
                    ms.push(o.solve_ms);
                    counts[match o.status {
                        ExactStatus::Optimal => 0,
                        ExactStatus::Feasible => 1,
                        ExactStatus::Infeasible => 2,
                        // Statuses of the continuous model only.
                        ExactStatus::TimeLimitNoSolution
                        | ExactStatus::OptimalWithin
                        | ExactStatus::NoScheduleFound => 3,
                    }] += 1;
                    let f = fluid::bound(&p, &objective, reorder, time_limit_s).expect("valid hop");
                    fl.push(f.solve_ms);
                    let q = fluid::fair(&p, &objective, reorder, time_limit_s).expect("valid hop");
                    fq.push(q.solve_ms);
                }
                println!(
                    "| {nd} | {ns} | {periods} | {} | {:.1} | {}/{}/{}/{} | {:.2} | {:.2} |",
                    reorder,
                    median(ms),
                    counts[0],
                    counts[1],
                    counts[2],
                    counts[3],
                    median(fl),
                    median(fq)
                );
            }
        }
    }
}
