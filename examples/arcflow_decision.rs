//! Cross-check of one node-time decision, "do the drones fit on `m` pads of capacity `C`?", by
//! the arc-flow MILP of bin packing (Valério de Carvalho, "Exact solution of bin-packing problems
//! using column generation and branch-and-bound", Ann. Oper. Res. 86:629-659, 1999) on HiGHS,
//! independent of `node_time`: a second method for the classical classes whose optimum the exact
//! search proves through the LP bound (`models/experiments/node_time.md`).
//!
//! ```text
//! cargo run --release --features highs --example arcflow_decision -- CLASS JOBS PADS SEED CAP
//! cargo run --release --features highs --example arcflow_decision -- l6 100 40 2 618
//! ```
//!
//! The instance is `swarmplan generate node-time --class CLASS --jobs JOBS --pads PADS --seed
//! SEED`. Nodes are the loads `0..=CAP` reachable by drones taken in decreasing length; an arc
//! `(u, u + w)` places a drone of length `w` on a pad loaded `u`, only from loads reachable with
//! drones at least as long (every pad's drones, longest first, follow such arcs); loss arcs
//! `(u, CAP)` close a pad. Variables: the integer flow on every arc and the number of pads `z`;
//! constraints: `z` leaves 0, `z` enters `CAP`, flow is conserved at every other reachable load
//! (an arc may end at a load no drones reach, which no arc leaves: it carries no flow), and the
//! arcs of each length carry at least the drones of that length; objective `min z`. When `z <= PADS`,
//! the flow is split into `z` paths from 0 to `CAP` (one per pad), the drones are dealt to them,
//! and every pad's load is recomputed from the generated times: the fit is checked here, not
//! taken from the solver. When `z > PADS`, the answer rests on HiGHS's proof of optimality
//! (integer feasibility tolerance `1e-6`, flows and `z` read as integers).

#[cfg(feature = "highs")]
fn main() {
    use good_lp::{
        constraint, highs, variable, variables, Expression, Solution, SolutionStatus, SolverModel,
    };
    use std::collections::BTreeMap;
    use swarmplan::generate::pcmax::{generate_pcmax, PcmaxClass, PcmaxParams};

    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.len() != 5 {
        eprintln!("usage: arcflow_decision CLASS JOBS PADS SEED CAP");
        std::process::exit(2);
    }
    let num = |i: usize, what: &str| -> u64 {
        args[i].parse().unwrap_or_else(|_| {
            eprintln!("{what}: `{}` is not a whole number", args[i]);
            std::process::exit(2)
        })
    };
    let class = PcmaxClass::from_name(&args[0]).unwrap_or_else(|| {
        eprintln!(
            "CLASS: unknown class `{}` (see `swarmplan generate node-time --help`)",
            args[0]
        );
        std::process::exit(2)
    });
    let (jobs, pads, seed, cap) = (
        num(1, "JOBS") as usize,
        num(2, "PADS") as usize,
        num(3, "SEED"),
        num(4, "CAP") as usize,
    );
    let file = generate_pcmax(&PcmaxParams {
        class,
        jobs,
        pads,
        seed,
    })
    .unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2)
    });
    let times: Vec<usize> = file.charge_times_min.iter().map(|&t| t as usize).collect();
    if times.iter().any(|&t| t > cap) {
        println!("does not fit: a drone is longer than {cap}");
        return;
    }
    let mut demand: BTreeMap<usize, usize> = BTreeMap::new();
    for &t in &times {
        *demand.entry(t).or_default() += 1;
    }
    // Arcs (from, length), lengths in decreasing order; `reach[u]`: load u reachable so far.
    let mut reach = vec![false; cap + 1];
    reach[0] = true;
    let mut arcs: Vec<(usize, usize)> = Vec::new();
    for (&w, &d) in demand.iter().rev() {
        let mut with_w = reach.clone();
        for _ in 0..d {
            let before = with_w.clone();
            for u in 0..=cap - w {
                if before[u] {
                    with_w[u + w] = true;
                }
            }
        }
        arcs.extend((0..=cap - w).filter(|&u| with_w[u]).map(|u| (u, w)));
        reach = with_w;
    }
    let losses: Vec<usize> = (1..cap).filter(|&u| reach[u]).collect();
    println!(
        "{class} {jobs}x{pads} seed {seed}, capacity {cap}: {} drones, {} lengths, {} arcs, {} loss arcs",
        times.len(),
        demand.len(),
        arcs.len(),
        losses.len()
    );
    let mut vars = variables!();
    let x: Vec<_> = arcs
        .iter()
        .map(|_| vars.add(variable().integer().min(0)))
        .collect();
    let loss: Vec<_> = losses
        .iter()
        .map(|_| vars.add(variable().integer().min(0)))
        .collect();
    let z = vars.add(variable().integer().min(0));
    let mut inflow: Vec<Expression> = vec![Expression::from(0.0); cap + 1];
    let mut outflow: Vec<Expression> = vec![Expression::from(0.0); cap + 1];
    for (a, &(u, w)) in arcs.iter().enumerate() {
        outflow[u] += x[a];
        inflow[u + w] += x[a];
    }
    for (l, &u) in losses.iter().enumerate() {
        outflow[u] += loss[l];
        inflow[cap] += loss[l];
    }
    let mut model = vars.minimise(z).using(highs);
    model = model.with(constraint!(outflow[0].clone() == z));
    model = model.with(constraint!(inflow[cap].clone() == z));
    for u in 1..cap {
        if reach[u] {
            model = model.with(constraint!(inflow[u].clone() == outflow[u].clone()));
        }
    }
    for (&w, &d) in &demand {
        let carried: Expression = arcs
            .iter()
            .zip(&x)
            .filter(|((_, len), _)| *len == w)
            .map(|(_, &v)| v)
            .sum();
        model = model.with(constraint!(carried >= d as f64));
    }
    let start = std::time::Instant::now();
    let solution = model.solve().unwrap_or_else(|e| {
        eprintln!("HiGHS: {e}");
        std::process::exit(1)
    });
    let seconds = start.elapsed().as_secs_f64();
    if !matches!(solution.status(), SolutionStatus::Optimal) {
        println!("not decided: HiGHS stopped before proving its MILP optimal ({seconds:.1} s)");
        return;
    }
    let bins = solution.value(z).round() as usize;
    if bins > pads {
        println!(
            "does not fit: the MILP needs {bins} pads of {cap} (HiGHS optimal, {seconds:.1} s)"
        );
        return;
    }
    // Split the flow into `bins` paths from 0 to `cap`, one pad each.
    let mut flow: Vec<i64> = x
        .iter()
        .map(|&v| solution.value(v).round() as i64)
        .collect();
    let mut loss_flow: Vec<i64> = loss
        .iter()
        .map(|&v| solution.value(v).round() as i64)
        .collect();
    let mut pads_of_lengths: Vec<Vec<usize>> = Vec::new();
    for _ in 0..bins {
        let (mut u, mut lengths) = (0usize, Vec::new());
        while u < cap {
            if let Some(a) = (0..arcs.len()).find(|&a| arcs[a].0 == u && flow[a] > 0) {
                flow[a] -= 1;
                lengths.push(arcs[a].1);
                u += arcs[a].1;
            } else if let Some(l) = (0..losses.len()).find(|&l| losses[l] == u && loss_flow[l] > 0)
            {
                loss_flow[l] -= 1;
                u = cap;
            } else {
                eprintln!("the flow cannot be split into pads at load {u}");
                std::process::exit(1);
            }
        }
        pads_of_lengths.push(lengths);
    }
    // Deal the drones to the pads by length (a pad may carry a length more often than there are
    // drones of it: the surplus is dropped), then recompute every load.
    let mut left = demand.clone();
    let mut loads = vec![0usize; bins];
    for (i, lengths) in pads_of_lengths.iter().enumerate() {
        for &w in lengths {
            let d = left.get_mut(&w).expect("a length of the instance");
            if *d > 0 {
                *d -= 1;
                loads[i] += w;
            }
        }
    }
    let placed = left.values().all(|&d| d == 0);
    let largest = loads.iter().copied().max().unwrap_or(0);
    if !placed || largest > cap {
        eprintln!("the MILP's packing does not check: every drone placed {placed}, largest load {largest}");
        std::process::exit(1);
    }
    println!(
        "fits: {bins} pads, largest load {largest} <= {cap}, every drone placed once (checked; HiGHS {seconds:.1} s)"
    );
}

#[cfg(not(feature = "highs"))]
fn main() {
    eprintln!("arcflow_decision needs a build with HiGHS: --features highs");
    std::process::exit(2);
}
