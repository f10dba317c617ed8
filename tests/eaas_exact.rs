//! Exact hop models: the time-indexed MILP and the fluid relaxation. Expected values come from hand
//! computation (`instances/eaas/known_optima.json`), from brute force over every grid schedule,
//! or from the order the models' feasible sets are in; never from the code under test.

mod common;

use common::{close, drone, integral_hop, known_optima, uniform_leg, Known};
use nalgebra::Vector2;
use proptest::prelude::*;
use swarmplan::check::check_hop;
use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactOutcome, ExactStatus, Objective, Reorder};
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{sharing_budget_mah, simulate, DroneState, HopProblem, LegRates, Transfer};
use swarmplan::node_time;
use swarmplan::problem::Role;
use swarmplan::solver::MilpBackend;

fn known(name: &str) -> Known {
    known_optima()
        .instances
        .into_iter()
        .find(|k| k.name == name)
        .unwrap()
}

fn options(backend: MilpBackend, reorder: Reorder, period_min: f64) -> MilpOptions {
    MilpOptions {
        period_min,
        reorder,
        backend,
        time_limit_s: 60.0,
        node_limit: None,
    }
}

/// Every schedule an outcome carries passes the independent checker.
fn assert_checked(p: &HopProblem, o: &ExactOutcome) {
    if let Some(out) = &o.outcome {
        let v = check_hop(p, out);
        assert!(v.is_empty(), "checker: {v:#?}");
        assert_eq!(out.transfers.len(), o.transfers.len());
    }
}

/// Node time of final batteries by the paper's brute force (not the MILP's pad model).
fn brute_node_time(p: &HopProblem, pads: usize, pad_rate: f64, fin: &[f64]) -> f64 {
    let times: Vec<f64> = p
        .drones
        .iter()
        .zip(fin)
        .map(|(d, b)| ((d.capacity_mah - b) / pad_rate).max(0.0))
        .collect();
    node_time::brute(pads, &times, &node_time::Limits::default())
        .unwrap()
        .makespan_min
}

#[test]
fn known_optima_table_is_reproduced_by_the_milp_on_every_backend() {
    let t = known_optima();
    assert_eq!(t.schema_version, 1);
    let mut failing = Vec::new();
    for backend in MilpBackend::all() {
        for k in &t.instances {
            let o = solve_milp(
                &k.problem,
                &k.objective,
                &options(backend, k.reorder, k.period_min),
            )
            .unwrap();
            assert_checked(&k.problem, &o);
            let ok = o.status == ExactStatus::Optimal
                && o.objective.is_some_and(|v| close(v, k.optimum))
                && o.model_objective.is_some_and(|v| close(v, k.optimum))
                && o.grid_step_min == k.period_min;
            if !ok {
                failing.push(format!(
                    "{} on {}: {:?} objective {:?} model {:?}, expected {}",
                    k.name, backend, o.status, o.objective, o.model_objective, k.optimum
                ));
            }
        }
    }
    assert!(
        failing.is_empty(),
        "failing instances:\n{}",
        failing.join("\n")
    );
}

#[test]
fn node_time_optimum_shares_less_than_pb() {
    let k = known("pb_overshares_3_pads");
    // PB by hand: 10 mAh to each delivery drone, final 90, 90, 60: nt = 40 min on 3 pads.
    let pb = simulate(&k.problem, Heuristic::Pb).unwrap();
    assert!(close(pb.shared_mah, 20.0), "PB shares {}", pb.shared_mah);
    assert!(close(
        brute_node_time(&k.problem, 3, 1.0, &pb.final_battery_mah),
        40.0
    ));
    for backend in MilpBackend::all() {
        let o = solve_milp(
            &k.problem,
            &k.objective,
            &options(backend, Reorder::Paper, 1.0),
        )
        .unwrap();
        let shared = o.outcome.as_ref().unwrap().shared_mah;
        assert!(shared < pb.shared_mah - 1.0, "MILP shares {shared}");
        assert!(close(o.objective.unwrap(), 20.0));
    }
}

#[test]
fn needy_pair_flies_only_with_an_optimal_schedule() {
    let k = known("needy_pair_max_min");
    // By hand: drone 1 has 25 mAh at 10 mAh/min and no sharing before t = 3 under PB and FB;
    // without sharing both drones empty at 2.5 min and the lower id is reported.
    for (policy, drone) in [(Heuristic::None, 0), (Heuristic::Pb, 1), (Heuristic::Fb, 1)] {
        let o = simulate(&k.problem, policy).unwrap();
        assert!(!o.feasible, "{policy:?} flies");
        let f = o.failure.unwrap();
        assert_eq!(f.drone, drone, "{policy:?}");
        assert!(close(f.time_min, 2.5), "{policy:?} fails at {}", f.time_min);
    }
    for backend in MilpBackend::all() {
        for reorder in [Reorder::Paper, Reorder::Free, Reorder::None] {
            let o = solve_milp(
                &k.problem,
                &Objective::Feasible,
                &options(backend, reorder, 1.0),
            )
            .unwrap();
            assert_eq!(o.status, ExactStatus::Optimal);
            assert!(o.outcome.as_ref().is_some_and(|x| x.feasible));
            assert_checked(&k.problem, &o);
        }
    }
}

#[test]
fn a_hop_nobody_can_fly_is_infeasible_for_the_milp() {
    // The needy pair with rho = 5: at most 20 mAh in 4 min, but 30 are needed.
    let mut p = known("needy_pair_max_min").problem;
    p.rho_mah_per_min = 5.0;
    for backend in MilpBackend::all() {
        let o = solve_milp(
            &p,
            &Objective::MaxMinArrival,
            &options(backend, Reorder::Free, 1.0),
        )
        .unwrap();
        assert_eq!(o.status, ExactStatus::Infeasible);
        assert!(o.objective.is_none() && o.transfers.is_empty());
    }
}

#[test]
fn bad_grid_objective_and_time_limit_are_coded_errors() {
    let p = known("needy_pair_max_min").problem;
    let codes = |r: swarmplan::error::Result<ExactOutcome>| -> Vec<&'static str> {
        match r {
            Err(swarmplan::error::Error::Invalid(v)) => v.iter().map(|x| x.code).collect(),
            other => panic!("expected invalid input, got {other:?}"),
        }
    };
    let base = MilpOptions::default();
    let bad_period = MilpOptions {
        period_min: 0.0,
        ..base
    };
    assert_eq!(
        codes(solve_milp(&p, &Objective::Feasible, &bad_period)),
        ["E4101"]
    );
    let tiny = MilpOptions {
        period_min: 1e-6,
        ..base
    };
    assert_eq!(
        codes(solve_milp(&p, &Objective::Feasible, &tiny)),
        ["E4102"]
    );
    let nt = Objective::NodeTime(EndPads {
        pads: 0,
        pad_rate_mah_per_min: f64::NAN,
    });
    assert_eq!(codes(solve_milp(&p, &nt, &base)), ["E4103", "E4104"]);
    let no_time = MilpOptions {
        time_limit_s: -1.0,
        ..base
    };
    assert_eq!(
        codes(solve_milp(&p, &Objective::Feasible, &no_time)),
        ["E4105"]
    );
    let mut broken = p.clone();
    broken.rho_mah_per_min = 0.0;
    assert_eq!(
        codes(solve_milp(&broken, &Objective::Feasible, &base)),
        ["E4010"]
    );
}

#[test]
fn grid_cuts_legs_into_equal_periods_at_most_period_min_long() {
    let mut p = known("needy_pair_max_min").problem;
    let leg = p.legs[0].clone();
    p.legs = vec![
        LegRates {
            duration_min: 2.5,
            ..leg.clone()
        },
        LegRates {
            duration_min: 0.0,
            ..leg.clone()
        },
        LegRates {
            duration_min: 1.5,
            ..leg
        },
    ];
    let g = swarmplan::eaas::exact::milp::Grid::new(&p, 1.0).unwrap();
    // 2.5 -> 3 periods of 5/6 min, 0 -> none, 1.5 -> 2 periods of 0.75 min.
    assert_eq!(g.periods(), 5);
    assert_eq!(g.leg, vec![0, 0, 0, 2, 2]);
    let expect = [0.0, 2.5 / 3.0, 5.0 / 3.0, 2.5, 3.25, 4.0];
    for (a, b) in g.points_min.iter().zip(expect) {
        assert!(close(*a, b), "{:?}", g.points_min);
    }
    assert!(close(g.step_min(), 2.5 / 3.0));
}

// ---------------------------------------------------------------------------------------------
// Brute force over every grid schedule of a tiny hop.

/// One support drone (id 2) between two delivery drones, all within range, slot-independent
/// rates, one leg of `periods` minutes.
fn tiny(batteries: [f64; 3], rates: [f64; 3], rho: f64, delta: f64, periods: usize) -> HopProblem {
    HopProblem {
        legs: vec![uniform_leg(periods as f64, &rates)],
        drones: vec![
            drone(Role::Delivery, 100.0, batteries[0]),
            drone(Role::Delivery, 100.0, batteries[1]),
            drone(Role::Support, 200.0, batteries[2]),
        ],
        slots_m: vec![
            Vector2::new(-1.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 0.0),
        ],
        initial_slot: vec![0, 1, 2],
        rho_mah_per_min: rho,
        range_m: 1.2,
        gamma_mah: 50.0,
        lambda_mah: 10.0,
        delta_mah: delta,
    }
}

/// Final batteries of every flyable full-period schedule (each period: idle, serve 0, serve 1),
/// integrated here by hand: batteries are linear in a period, so grid points suffice.
fn brute_finals(p: &HopProblem, periods: usize) -> Vec<Vec<f64>> {
    let rho = p.rho_mah_per_min;
    let budget = sharing_budget_mah(p, 2);
    let mut out = Vec::new();
    for code in 0..3usize.pow(periods as u32) {
        let mut b: Vec<f64> = p.drones.iter().map(|d| d.battery_mah).collect();
        let (mut c, mut given, mut ok) = (code, 0.0, true);
        for _ in 0..periods {
            let who = c % 3;
            c /= 3;
            for (d, bd) in b.iter_mut().enumerate() {
                *bd -= p.legs[0].rate_mah_per_min[d][0];
            }
            if who < 2 {
                b[who] += rho;
                b[2] -= rho;
                given += rho;
            }
            ok &= b
                .iter()
                .zip(&p.drones)
                .all(|(x, d)| *x >= -1e-9 && *x <= d.capacity_mah + 1e-9);
        }
        if ok && given <= budget + 1e-9 {
            out.push(b);
        }
    }
    out
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn milp_optimum_equals_brute_force_over_every_grid_schedule(
        b0 in 5.0..100.0f64, b1 in 5.0..100.0f64, bs in 20.0..200.0f64,
        r0 in 0.0..12.0f64, r1 in 0.0..12.0f64, rs in 0.0..6.0f64,
        rho in 2.0..15.0f64, delta in 0.0..20.0f64, pads in 1usize..4, periods in 1usize..4,
    ) {
        let p = tiny([b0, b1, bs], [r0, r1, rs], rho, delta, periods);
        let finals = brute_finals(&p, periods);
        for backend in MilpBackend::all() {
            let opt = options(backend, Reorder::Paper, 1.0);
            let nt = Objective::NodeTime(EndPads { pads, pad_rate_mah_per_min: 2.0 });
            let o = solve_milp(&p, &nt, &opt).unwrap();
            assert_checked(&p, &o);
            let mm = solve_milp(&p, &Objective::MaxMinArrival, &opt).unwrap();
            if finals.is_empty() {
                prop_assert_eq!(o.status, ExactStatus::Infeasible);
                prop_assert_eq!(mm.status, ExactStatus::Infeasible);
                continue;
            }
            let best_nt = finals
                .iter()
                .map(|f| brute_node_time(&p, pads, 2.0, f))
                .fold(f64::INFINITY, f64::min);
            let best_mm = finals.iter().map(|f| f[0].min(f[1])).fold(f64::NEG_INFINITY, f64::max);
            prop_assert_eq!(o.status, ExactStatus::Optimal);
            prop_assert!(close(o.objective.unwrap(), best_nt), "{:?} vs {}", o.objective, best_nt);
            prop_assert!(close(mm.objective.unwrap(), best_mm), "{:?} vs {}", mm.objective, best_mm);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Random small hops on an integral grid, where PB and FB transfers start and end on whole minutes.

/// Integral hop: rho = 1 mAh/min, integer rates, batteries, durations and capacities, gamma = C
/// (PB requests start at breakpoints), lambda integral (FB rounds of whole minutes): every
/// breakpoint of PB and FB is a whole minute.
fn on_whole_minutes(ts: &[Transfer]) -> bool {
    ts.iter().all(|x| {
        (x.start_min - x.start_min.round()).abs() < 1e-9
            && (x.end_min - x.end_min.round()).abs() < 1e-9
    })
}

/// Node time on 2 pads at 1 mAh/min, or infinity when the model has no flyable schedule.
fn nt_of(o: &ExactOutcome) -> f64 {
    match o.status {
        ExactStatus::Optimal => o.objective.unwrap(),
        ExactStatus::Infeasible => f64::INFINITY,
        s => panic!("unexpected status {s:?}"),
    }
}

const NT2: Objective = Objective::NodeTime(EndPads {
    pads: 2,
    pad_rate_mah_per_min: 1.0,
});

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn paper_milp_never_exceeds_pb_and_fb_when_their_transfers_lie_on_the_grid(seed in any::<u64>()) {
        let p = integral_hop(seed);
        for backend in MilpBackend::all() {
            let o = solve_milp(&p, &NT2, &options(backend, Reorder::Paper, 1.0)).unwrap();
            assert_checked(&p, &o);
            for policy in [Heuristic::None, Heuristic::Pb, Heuristic::Fb] {
                let h = simulate(&p, policy).unwrap();
                prop_assert!(on_whole_minutes(&h.transfers), "{:?}: {:?}", policy, h.transfers);
                if h.feasible {
                    let hv = brute_node_time(&p, 2, 1.0, &h.final_battery_mah);
                    prop_assert!(nt_of(&o) <= hv + 1e-6, "{:?}: milp {:?} > {}", policy, o.objective, hv);
                }
            }
        }
    }

    #[test]
    fn free_reordering_never_does_worse_than_paper_and_paper_never_worse_than_none(seed in any::<u64>()) {
        let p = integral_hop(seed);
        for backend in MilpBackend::all() {
            let v: Vec<f64> = [Reorder::Free, Reorder::Paper, Reorder::None]
                .iter()
                .map(|&r| {
                    let o = solve_milp(&p, &NT2, &options(backend, r, 1.0)).unwrap();
                    assert_checked(&p, &o);
                    nt_of(&o)
                })
                .collect();
            prop_assert!(v[0] <= v[1] + 1e-6 && v[1] <= v[2] + 1e-6, "free, paper, none: {:?}", v);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Fluid relaxation: LP bound and fair QP.

use swarmplan::eaas::exact::fluid;

#[test]
fn fluid_bounds_of_the_known_hops_match_hand_computation() {
    // (instance, objective, expected LP value): the relaxation of these one-leg hops is their
    // energy balance, solved by hand in each instance's source; for the needy pair on 3 pads the
    // LP also gives 95 (max deficit 100 - (S - 30) / 2 with S <= 40) and on 1 pad 230.
    for (name, expect) in [
        ("pb_overshares_3_pads", 20.0),
        ("pb_overshares_1_pad", 60.0),
        ("needy_pair_max_min", 5.0),
        ("needy_pair_node_time_3_pads", 95.0),
        ("needy_pair_node_time_1_pad", 230.0),
        ("needy_pair_feasible", 0.0),
    ] {
        let k = known(name);
        for mode in [Reorder::Paper, Reorder::Free, Reorder::None] {
            let o = fluid::bound(&k.problem, &k.objective, mode, 10.0).unwrap();
            assert_eq!(o.status, ExactStatus::Optimal, "{name}");
            let b = o.bound.unwrap();
            assert!(
                (b - expect).abs() < 1e-5 * (1.0 + expect),
                "{name} {mode:?}: {b}"
            );
        }
    }
}

#[test]
fn an_infeasible_fluid_lp_proves_the_hop_unflyable() {
    // Needy pair with rho = 5: 20 mAh can move in 4 min, 30 are needed (by hand).
    let mut p = known("needy_pair_max_min").problem;
    p.rho_mah_per_min = 5.0;
    let o = fluid::bound(&p, &Objective::Feasible, Reorder::Free, 10.0).unwrap();
    assert_eq!(o.status, ExactStatus::Infeasible);
    let f = fluid::fair(&p, &Objective::Feasible, Reorder::Free, 10.0).unwrap();
    assert_eq!(f.status, ExactStatus::Infeasible);
}

#[test]
fn fair_qp_of_the_needy_pair_splits_the_support_drone_evenly_and_flies() {
    // By hand: deficits 115 - a0, 115 - a1 and a0 + a1 with a0 + a1 <= 40; the unconstrained
    // optimum a0 = a1 = 460 / 12 violates the rate limit, so a0 = a1 = 20: 2 x 95^2 + 40^2.
    let k = known("needy_pair_max_min");
    let o = fluid::fair(&k.problem, &Objective::MaxMinArrival, Reorder::Paper, 10.0).unwrap();
    assert_eq!(o.status, ExactStatus::Optimal);
    assert!(
        (o.model_objective.unwrap() - 19_650.0).abs() < 1e-3,
        "{:?}",
        o.model_objective
    );
    let out = o.outcome.as_ref().unwrap();
    assert!(out.feasible);
    assert!(check_hop(&k.problem, out).is_empty());
    assert!((fluid::squared_deficits(&k.problem, &out.final_battery_mah) - 19_650.0).abs() < 1e-2);
    assert!((o.objective.unwrap() - 5.0).abs() < 1e-4);
    // Nobody is full at the start of pb_overshares: the fair optimum there shares nothing
    // (the gradient at a = 0 is -2 x 20 + 2 x 20 = 0): 3 x 20^2.
    let k = known("pb_overshares_3_pads");
    let o = fluid::fair(&k.problem, &k.objective, Reorder::None, 10.0).unwrap();
    assert!((o.model_objective.unwrap() - 1_200.0).abs() < 1e-3);
    assert!((o.objective.unwrap() - 20.0).abs() < 1e-3, "{o:?}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    #[test]
    fn fluid_bound_never_exceeds_any_schedule(seed in any::<u64>()) {
        let p = integral_hop(seed);
        let policies: Vec<_> = [Heuristic::None, Heuristic::Pb, Heuristic::Fb]
            .iter()
            .map(|&x| simulate(&p, x).unwrap())
            .filter(|o| o.feasible)
            .collect();
        for mode in [Reorder::Paper, Reorder::Free, Reorder::None] {
            let lp = fluid::bound(&p, &NT2, mode, 10.0).unwrap();
            let qp = fluid::fair(&p, &NT2, mode, 10.0).unwrap();
            if let Some(out) = &qp.outcome {
                let v = check_hop(&p, out);
                prop_assert!(v.is_empty(), "fair schedule: {:?}", v);
            }
            for backend in MilpBackend::all() {
                let o = solve_milp(&p, &NT2, &options(backend, mode, 1.0)).unwrap();
                if lp.status == ExactStatus::Infeasible {
                    prop_assert_eq!(o.status, ExactStatus::Infeasible);
                    prop_assert_eq!(qp.status, ExactStatus::Infeasible);
                    continue;
                }
                prop_assert_eq!(lp.status, ExactStatus::Optimal);
                let b = lp.bound.unwrap();
                if o.status == ExactStatus::Optimal {
                    prop_assert!(b <= o.objective.unwrap() + 1e-6, "{:?}: lp {} > milp {:?}", mode, b, o.objective);
                    if let Some(out) = &o.outcome {
                        let sq = fluid::squared_deficits(&p, &out.final_battery_mah);
                        prop_assert!(qp.model_objective.unwrap() <= sq + 1e-4, "qp above milp schedule");
                    }
                }
            }
            if mode != Reorder::None {
                for h in &policies {
                    let hv = brute_node_time(&p, 2, 1.0, &h.final_battery_mah);
                    prop_assert!(lp.bound.unwrap() <= hv + 1e-6, "lp {:?} > heuristic {}", lp.bound, hv);
                    let sq = fluid::squared_deficits(&p, &h.final_battery_mah);
                    prop_assert!(qp.model_objective.unwrap() <= sq + 1e-4, "qp above heuristic");
                }
            }
        }
    }
}

/// A hop too large to solve in a millisecond: 5 delivery and 2 support drones, 8 periods.
fn large_hop() -> HopProblem {
    let mut p = integral_hop(7);
    let n = 7;
    p.drones = (0..n)
        .map(|d| DroneState {
            role: if d < 5 { Role::Delivery } else { Role::Support },
            capacity_mah: 100.0,
            battery_mah: if d < 5 { 40.0 + 10.0 * d as f64 } else { 100.0 },
        })
        .collect();
    p.legs = vec![LegRates {
        duration_min: 8.0,
        rate_mah_per_min: (0..n)
            .map(|d| (0..n).map(|q| 2.0 + ((d * 3 + q) % 4) as f64).collect())
            .collect::<Vec<_>>()
            .into(),
    }];
    p.slots_m = (0..n).map(|q| Vector2::new(0.7 * q as f64, 0.0)).collect();
    p.initial_slot = vec![0, 1, 3, 5, 6, 2, 4];
    p.rho_mah_per_min = 8.0;
    p
}

#[test]
fn a_solve_stopped_by_the_time_limit_says_so_and_labels_its_bound() {
    let p = large_hop();
    let nt = Objective::NodeTime(EndPads {
        pads: 2,
        pad_rate_mah_per_min: 10.0,
    });
    let lp = fluid::bound(&p, &nt, Reorder::Paper, 10.0).unwrap();
    assert_eq!(lp.status, ExactStatus::Optimal);
    for backend in MilpBackend::all() {
        let o = solve_milp(
            &p,
            &nt,
            &MilpOptions {
                time_limit_s: 0.001,
                ..options(backend, Reorder::Paper, 1.0)
            },
        )
        .unwrap();
        match o.status {
            ExactStatus::Feasible => {
                let (v, b) = (o.objective.unwrap(), o.bound.unwrap());
                assert!(
                    b <= v + 1e-6 && b >= lp.bound.unwrap() - 1e-6,
                    "bound {b}, incumbent {v}"
                );
                assert_checked(&p, &o);
            }
            ExactStatus::TimeLimitNoSolution => {
                // The empty schedule is the first incumbent: only a hop it cannot fly ends so.
                assert!(!simulate(&p, Heuristic::None).unwrap().feasible);
                assert!(o.objective.is_none() && o.transfers.is_empty());
                assert!(o.bound.unwrap() >= lp.bound.unwrap() - 1e-6);
            }
            s => panic!("a 1 ms solve of this hop reported {s:?}"),
        }
    }
}

#[test]
fn a_hop_of_zero_duration_keeps_the_departure_batteries() {
    // No period: nothing to share; node time of deficits 75, 75, 0 on 3 pads at 1 mAh/min = 75,
    // lowest delivery battery 25 (by hand).
    let mut p = known("needy_pair_max_min").problem;
    p.legs[0].duration_min = 0.0;
    let nt3 = Objective::NodeTime(EndPads {
        pads: 3,
        pad_rate_mah_per_min: 1.0,
    });
    for backend in MilpBackend::all() {
        for (objective, expect) in [
            (nt3, 75.0),
            (Objective::MaxMinArrival, 25.0),
            (Objective::Feasible, 0.0),
        ] {
            let o = solve_milp(&p, &objective, &options(backend, Reorder::Paper, 1.0)).unwrap();
            assert_eq!(o.status, ExactStatus::Optimal);
            assert_eq!(o.periods, 0);
            assert!(close(o.objective.unwrap(), expect), "{objective:?}: {o:?}");
            assert_checked(&p, &o);
            let f = fluid::bound(&p, &objective, Reorder::Paper, 10.0).unwrap();
            assert!(
                close(f.bound.unwrap(), expect),
                "fluid {objective:?}: {f:?}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn every_backend_finds_the_same_optimum(seed in any::<u64>()) {
        let p = integral_hop(seed);
        for reorder in [Reorder::Paper, Reorder::Free] {
            let v: Vec<f64> = MilpBackend::all()
                .into_iter()
                .map(|b| nt_of(&solve_milp(&p, &NT2, &options(b, reorder, 1.0)).unwrap()))
                .collect();
            prop_assert!(v.iter().all(|x| (x - v[0]).abs() <= 1e-6 * (1.0 + v[0].abs()) || (x.is_infinite() && v[0].is_infinite())), "{:?}", v);
        }
    }
}
