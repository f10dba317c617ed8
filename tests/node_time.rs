//! Node time (P||Cmax): the paper's example, exact against brute force, LPT's guarantee, MILP on
//! every backend, the known-optima table, validation.

mod common;

use common::repo_path;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Deserialize;
use swarmplan::error::Error;
use swarmplan::node_time::{
    brute, exact, lpt, milp, solve, validate, Limits, NodeTimeMethod, NodeTimeSolution,
};
use swarmplan::solver::{MilpBackend, SolveStatus};

const PAPER_TIMES: [f64; 5] = [60.0, 50.0, 40.0, 30.0, 20.0];

/// Independent check of a solution: every drone on exactly one of at most `pads` pads, and the
/// reported makespan equal to the largest recomputed pad load.
fn check(pads: usize, times: &[f64], s: &NodeTimeSolution) {
    assert!(s.assignment.len() <= pads, "more pad lists than pads");
    let mut seen = vec![0; times.len()];
    let mut makespan: f64 = 0.0;
    for pad in &s.assignment {
        let mut load = 0.0;
        for &j in pad {
            seen[j] += 1;
            load += times[j];
        }
        makespan = makespan.max(load);
    }
    assert!(
        seen.iter().all(|&c| c == 1),
        "a drone is missing or charged twice: {seen:?}"
    );
    assert!(
        (makespan - s.makespan_min).abs() <= 1e-9 * makespan.max(1.0),
        "reported {} but the loads give {makespan}",
        s.makespan_min
    );
    assert!(s.lower_bound_min <= s.makespan_min * (1.0 + 1e-9) + 1e-12);
}

fn random_times(rng: &mut ChaCha8Rng, n: usize) -> Vec<f64> {
    let kind = rng.random_range(0..4);
    (0..n)
        .map(|_| match kind {
            // whole minutes, with ties
            0 => f64::from(rng.random_range(0..=20u32)),
            // real minutes
            1 => rng.random_range(0.0..100.0),
            // few distinct values: many identical drones
            2 => f64::from(rng.random_range(1..=4u32)) * 7.5,
            // a mix with zero-time drones
            _ => {
                if rng.random_bool(0.3) {
                    0.0
                } else {
                    rng.random_range(1.0..60.0)
                }
            }
        })
        .collect()
}

#[test]
fn paper_example_gives_200_70_and_60_minutes() {
    // Paper, section 5: 1 pad: 60+50+40+30+20 = 200; 3 pads: {60}, {50,20}, {40,30} -> 70
    // (and 70 is optimal: the 60 job alone leaves 140 min for two pads, so one pad gets >= 70);
    // 5 pads: max = 60.
    for (pads, expected) in [(1, 200.0), (3, 70.0), (5, 60.0), (7, 60.0)] {
        for method in [
            NodeTimeMethod::Exact,
            NodeTimeMethod::Brute,
            NodeTimeMethod::Milp,
        ] {
            for backend in MilpBackend::all() {
                let s = solve(method, backend, pads, &PAPER_TIMES, &Limits::default()).unwrap();
                check(pads, &PAPER_TIMES, &s);
                assert_eq!(s.method, method);
                assert!(
                    (s.makespan_min - expected).abs() < 1e-9,
                    "{method:?} on {pads} pads gave {}",
                    s.makespan_min
                );
                assert_eq!(s.status, SolveStatus::Optimal);
                assert!((s.lower_bound_min - expected).abs() < 1e-9);
            }
        }
    }
}

#[test]
fn exact_equals_brute_force_on_random_small_cases() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    for case in 0..1500 {
        let n = rng.random_range(1..=9);
        let k = rng.random_range(1..=4);
        let times = random_times(&mut rng, n);
        let b = brute(k, &times, &Limits::default()).unwrap();
        let e = exact(k, &times, &Limits::default()).unwrap();
        check(k, &times, &b);
        check(k, &times, &e);
        assert_eq!(e.status, SolveStatus::Optimal);
        assert!(
            (e.makespan_min - b.makespan_min).abs() <= 1e-9 * b.makespan_min.max(1.0),
            "case {case}: k={k} times={times:?}: exact {} brute {}",
            e.makespan_min,
            b.makespan_min
        );
    }
}

#[test]
fn exact_node_time_equals_brute_force_on_real_times() {
    // Real-valued times (no ties, no whole minutes): the optimum is rarely the root bound, so the
    // searches run to their proof. Brute force is the independent reference.
    let mut rng = ChaCha8Rng::seed_from_u64(23);
    for case in 0..1000 {
        let n = rng.random_range(2..=10);
        let k = rng.random_range(2..=4);
        let times: Vec<f64> = (0..n).map(|_| rng.random_range(0.5..100.0)).collect();
        let b = brute(k, &times, &Limits::default()).unwrap();
        let e = exact(k, &times, &Limits::default()).unwrap();
        check(k, &times, &e);
        assert_eq!(e.status, SolveStatus::Optimal);
        assert!(
            (e.makespan_min - b.makespan_min).abs() <= 1e-9 * b.makespan_min,
            "case {case}: k={k} times={times:?}: exact {} brute {}",
            e.makespan_min,
            b.makespan_min
        );
    }
}

#[test]
fn exact_node_time_never_exceeds_lpt_and_lpt_meets_grahams_bound() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    for _ in 0..400 {
        let n = rng.random_range(1..=9);
        let k = rng.random_range(1..=4);
        let times = random_times(&mut rng, n);
        // The optimum comes from brute force, independent of the exact search.
        let opt = brute(k, &times, &Limits::default()).unwrap().makespan_min;
        let e = exact(k, &times, &Limits::default()).unwrap().makespan_min;
        let l = lpt(k, &times).unwrap();
        check(k, &times, &l);
        let graham = 4.0 / 3.0 - 1.0 / (3.0 * k as f64);
        assert!(
            e <= l.makespan_min * (1.0 + 1e-9),
            "exact {e} > lpt {}",
            l.makespan_min
        );
        assert!(
            l.makespan_min <= graham * opt * (1.0 + 1e-9),
            "lpt {} above Graham's bound {graham} x {opt} for {times:?} on {k}",
            l.makespan_min
        );
    }
}

#[test]
fn lpt_is_not_optimal_on_grahams_tight_example() {
    // Graham's tight example for k = 2: times 3,3,2,2,2. LPT: 3|3, 2 -> 5|3, 2 -> 5|5, 2 -> 7|5,
    // makespan 7; optimum 6 = {3,3} | {2,2,2}; 7/6 = 4/3 - 1/6.
    let times = [3.0, 3.0, 2.0, 2.0, 2.0];
    let l = lpt(2, &times).unwrap();
    assert_eq!(l.makespan_min, 7.0);
    assert_eq!(l.status, SolveStatus::Feasible);
    assert_eq!(l.lower_bound_min, 6.0);
    let e = exact(2, &times, &Limits::default()).unwrap();
    check(2, &times, &e);
    assert_eq!(e.makespan_min, 6.0);
    assert_eq!(e.status, SolveStatus::Optimal);
}

#[test]
fn node_limit_returns_the_incumbent_labelled_feasible() {
    // Same instance: LPT's 7 is the first incumbent; one node cannot prove 6.
    let times = [3.0, 3.0, 2.0, 2.0, 2.0];
    let limits = Limits {
        time_limit_s: None,
        node_limit: Some(1),
    };
    let e = exact(2, &times, &limits).unwrap();
    check(2, &times, &e);
    assert_eq!(e.status, SolveStatus::Feasible);
    assert_eq!(e.makespan_min, 7.0);
    // Root bound: max(p_max 3, sum/k = 12/2 = 6, p_2 + p_3 = 3 + 2 = 5) = 6.
    assert_eq!(e.lower_bound_min, 6.0);
}

#[test]
fn milp_equals_exact_on_every_backend() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for backend in MilpBackend::all() {
        for case in 0..40 {
            let n = rng.random_range(1..=8);
            let k = rng.random_range(1..=4);
            let times = random_times(&mut rng, n);
            let e = exact(k, &times, &Limits::default()).unwrap();
            let m = milp(k, &times, backend, &Limits::default()).unwrap();
            check(k, &times, &m);
            assert_eq!(m.status, SolveStatus::Optimal);
            assert!(
                (m.makespan_min - e.makespan_min).abs() <= 1e-6 * e.makespan_min.max(1.0),
                "{} case {case}: k={k} times={times:?}: milp {} exact {}",
                backend,
                m.makespan_min,
                e.makespan_min
            );
        }
    }
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KnownOptima {
    #[allow(dead_code)]
    schema_version: u32,
    #[allow(dead_code)]
    description: String,
    instances: Vec<KnownOptimum>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KnownOptimum {
    name: String,
    #[allow(dead_code)]
    description: String,
    pads: usize,
    charge_times_min: Vec<f64>,
    optimum_min: f64,
    #[allow(dead_code)]
    source: String,
}

#[test]
fn known_optima_table_is_reproduced_by_exact_and_milp() {
    let path = repo_path("instances/node_time/known_optima.json");
    let table: KnownOptima = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert!(table.instances.len() >= 5);
    let limits = Limits {
        time_limit_s: Some(60.0),
        node_limit: None,
    };
    let mut failures = Vec::new();
    for inst in &table.instances {
        let e = exact(inst.pads, &inst.charge_times_min, &limits).unwrap();
        check(inst.pads, &inst.charge_times_min, &e);
        if (e.makespan_min - inst.optimum_min).abs() > 1e-9 * inst.optimum_min.max(1.0)
            || e.status != SolveStatus::Optimal
        {
            failures.push(format!(
                "{}: exact {} ({:?}), table {}",
                inst.name, e.makespan_min, e.status, inst.optimum_min
            ));
        }
        if inst.charge_times_min.len() <= 12 {
            for backend in MilpBackend::all() {
                let m = milp(inst.pads, &inst.charge_times_min, backend, &limits).unwrap();
                if (m.makespan_min - inst.optimum_min).abs() > 1e-6 * inst.optimum_min.max(1.0) {
                    failures.push(format!(
                        "{}: milp on {} {}, table {}",
                        inst.name, backend, m.makespan_min, inst.optimum_min
                    ));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "failing instances:\n{}",
        failures.join("\n")
    );
}

#[test]
fn more_pads_than_drones_gives_the_longest_charge_time() {
    let times = [12.5, 40.25, 3.0];
    let e = exact(10, &times, &Limits::default()).unwrap();
    check(10, &times, &e);
    assert_eq!(e.makespan_min, 40.25);
    assert_eq!(e.status, SolveStatus::Optimal);
    assert_eq!(e.assignment.len(), 3);
}

#[test]
fn zero_time_drones_do_not_change_the_node_time() {
    // {10,10} on two pads plus three drones already full: 10.
    let times = [0.0, 10.0, 0.0, 10.0, 0.0];
    for s in [
        exact(2, &times, &Limits::default()).unwrap(),
        brute(2, &times, &Limits::default()).unwrap(),
        lpt(2, &times).unwrap(),
    ] {
        check(2, &times, &s);
        assert_eq!(s.makespan_min, 10.0);
    }
    let all_zero = [0.0; 6];
    let s = exact(2, &all_zero, &Limits::default()).unwrap();
    check(2, &all_zero, &s);
    assert_eq!(s.makespan_min, 0.0);
    assert_eq!(s.status, SolveStatus::Optimal);
}

fn codes(e: Error) -> Vec<&'static str> {
    match e {
        Error::Invalid(v) => v.iter().map(|x| x.code).collect(),
        other => panic!("expected Invalid, got {other}"),
    }
}

#[test]
fn validation_reports_every_violation_at_once() {
    assert_eq!(codes(validate(0, &[]).unwrap_err()), vec!["E5001", "E5002"]);
    assert_eq!(
        codes(validate(2, &[5.0, -1.0, f64::NAN, f64::INFINITY]).unwrap_err()),
        vec!["E5003", "E5004", "E5004"]
    );
    assert!(validate(1, &[0.0]).is_ok());
    for method in [
        NodeTimeMethod::Exact,
        NodeTimeMethod::Milp,
        NodeTimeMethod::Lpt,
        NodeTimeMethod::Brute,
    ] {
        let e = solve(
            method,
            MilpBackend::default(),
            0,
            &[1.0],
            &Limits::default(),
        )
        .unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert_eq!(codes(e), vec!["E5001"]);
    }
    let bad_limit = Limits {
        time_limit_s: Some(-1.0),
        node_limit: None,
    };
    assert_eq!(
        codes(exact(2, &[1.0, 2.0, 3.0], &bad_limit).unwrap_err()),
        vec!["E5006"]
    );
}

#[test]
fn brute_force_refuses_beyond_its_size_limit() {
    // 3^20 = 3,486,784,401 assignments > 10^8.
    let times: Vec<f64> = (1..=20).map(f64::from).collect();
    assert_eq!(
        codes(brute(3, &times, &Limits::default()).unwrap_err()),
        vec!["E5005"]
    );
    // Exact handles it: sum 210 over 3 pads gives the bound 70, met by the partition
    // {20,19,18,13} = 70, {17,16,15,14,8} = 70, {1..=12 without 8} = 78 - 8 = 70.
    let e = exact(3, &times, &Limits::default()).unwrap();
    check(3, &times, &e);
    assert_eq!(e.makespan_min, 70.0);
}

#[test]
fn the_default_backend_is_the_first_compiled_one_or_none_with_e0011() {
    let r = milp(3, &[60.0, 50.0], MilpBackend::default(), &Limits::default());
    match MilpBackend::all().first() {
        Some(&first) => {
            assert_eq!(MilpBackend::default(), first);
            assert!((r.unwrap().makespan_min - 60.0).abs() < 1e-9);
        }
        // A build without microlp and highs (`cargo test --no-default-features`).
        None => assert!(r.unwrap_err().to_string().contains("[E0011]")),
    }
}
