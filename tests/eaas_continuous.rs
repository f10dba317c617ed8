//! The continuous-time configuration LP (`models/eaas_config.md`): hand-computed continuous optima
//! (`instances/eaas/known_optima.json`), the counterexample without a Slater point, an infimum
//! approached but not attained, and properties on random hops against the fluid LP, the grid MILP
//! and the heuristics, on every backend.

mod common;

use common::{close, drone, integral_hop, known_optima};
use nalgebra::Vector2;
use proptest::prelude::*;
use swarmplan::check::{check_free_hop, check_hop};
use swarmplan::eaas::exact::continuous::{
    relaxed_node_time, solve_continuous, ContinuousOptions, PadMethod, RelaxedNodeTime,
};
use swarmplan::eaas::exact::fluid;
use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactOutcome, ExactStatus, Objective, Reorder};
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{simulate, HopProblem, LegRates, SlotInterval};
use swarmplan::problem::Role;
use swarmplan::solver::MilpBackend;

fn options(backend: MilpBackend, reorder: Reorder) -> ContinuousOptions {
    ContinuousOptions {
        reorder,
        backend,
        ..ContinuousOptions::default()
    }
}

/// The schedule an outcome carries passes the independent checker, flies, and its objective is
/// the bound plus the reported epsilon.
fn assert_checked(p: &HopProblem, o: &ExactOutcome, objective: &Objective) {
    if let Some(free) = &o.intervals {
        let v = check_free_hop(p, &free.intervals, &free.final_battery_mah);
        assert!(v.is_empty(), "free checker: {v:#?}");
    }
    let Some(out) = &o.outcome else { return };
    let v = check_hop(p, out);
    assert!(v.is_empty(), "checker: {v:#?}");
    assert!(out.feasible);
    if let (Some(value), Some(bound), Some(eps)) = (o.objective, o.bound, o.epsilon) {
        let d = match objective {
            Objective::MaxMinArrival => bound - value,
            _ => value - bound,
        };
        assert!(
            (d.max(0.0) - eps).abs() <= 1e-9 * (1.0 + bound.abs()),
            "{d} vs {eps}"
        );
    }
}

#[test]
fn known_continuous_optima_are_reproduced_on_every_backend() {
    let t = known_optima();
    let mut failing = Vec::new();
    for backend in MilpBackend::all() {
        for k in &t.instances {
            let o =
                solve_continuous(&k.problem, &k.objective, &options(backend, k.reorder)).unwrap();
            assert_checked(&k.problem, &o, &k.objective);
            let ok = o.status == ExactStatus::Optimal
                && o.objective.is_some_and(|v| close(v, k.continuous_optimum))
                && o.bound.is_some_and(|v| close(v, k.continuous_optimum))
                && o.grid_step_min == 0.0;
            if !ok {
                failing.push(format!(
                    "{} on {backend}: {:?} objective {:?} bound {:?}, expected {}",
                    k.name, o.status, o.objective, o.bound, k.continuous_optimum
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

/// A random hop into a stop as a plan flies it: every drone full at the start, 2-5 delivery
/// and 1-2 support drones, 1-4 legs of real rates, rho 2-40 mAh/min (slow and fast sharing),
/// slots on a line 1 m apart (range 1.2 m), shuffled.
fn full_start_hop(seed: u64) -> HopProblem {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let nd = rng.random_range(2..=5usize);
    let ns = rng.random_range(1..=2usize);
    let n = nd + ns;
    let legs = (0..rng.random_range(1..=4usize))
        .map(|_| LegRates {
            duration_min: rng.random_range(0.5..4.0),
            rate_mah_per_min: (0..n)
                .map(|_| (0..n).map(|_| rng.random_range(4.0..14.0)).collect())
                .collect::<Vec<_>>()
                .into(),
        })
        .collect();
    let mut initial_slot: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        initial_slot.swap(i, rng.random_range(0..=i));
    }
    HopProblem {
        legs,
        drones: (0..n)
            .map(|d| {
                let (role, cap) = if d < nd {
                    (Role::Delivery, 100.0)
                } else {
                    (Role::Support, 250.0)
                };
                drone(role, cap, cap)
            })
            .collect(),
        slots_m: (0..n).map(|q| Vector2::new(q as f64, 0.0)).collect(),
        initial_slot,
        rho_mah_per_min: if rng.random_bool(0.5) {
            rng.random_range(2.0..8.0)
        } else {
            rng.random_range(15.0..40.0)
        },
        range_m: 1.2,
        gamma_mah: 95.0,
        lambda_mah: 20.0,
        delta_mah: 0.0,
    }
}

/// The pad search (the default) against the pad MILP it replaces, kept as the reference
/// implementation: on 200 random hops into a stop with 1-3 pads, in `none` and `paper`, the
/// same status (or the search's `optimal` where the MILP's is `optimal_within`) and the same
/// model value, and each one's schedule no better than the other's proven bound.
#[test]
fn the_pad_search_agrees_with_the_pad_milp_on_200_random_hops() {
    let mut failing = Vec::new();
    let mut compared = 0;
    for seed in 0..200u64 {
        let p = full_start_hop(seed);
        let objective = Objective::NodeTime(EndPads {
            pads: 1 + (seed % 3) as usize,
            pad_rate_mah_per_min: 9.0,
        });
        for reorder in [Reorder::None, Reorder::Paper] {
            let with = |pad_method| ContinuousOptions {
                pad_method,
                ..options(MilpBackend::Microlp, reorder)
            };
            let s = solve_continuous(&p, &objective, &with(PadMethod::Search)).unwrap();
            let m = solve_continuous(&p, &objective, &with(PadMethod::Milp)).unwrap();
            assert_checked(&p, &s, &objective);
            let tol = |v: f64| 1e-7 + 1e-7 * v.abs();
            // The search may attain an optimum the MILP's point only approaches (its leaf is
            // another optimal point, and the MILP's is tried after it): never the other way.
            let status_ok = s.status == m.status
                || (s.status == ExactStatus::Optimal && m.status == ExactStatus::OptimalWithin);
            let agree = status_ok
                && match (s.bound, m.bound, s.objective, m.objective) {
                    (Some(sb), Some(mb), Some(sv), Some(mv)) => {
                        (sb - mb).abs() <= tol(mb) && sv >= mb - tol(mb) && mv >= sb - tol(sb)
                    }
                    (sb, mb, sv, mv) => sb == mb && sv == mv,
                };
            if !agree {
                failing.push(format!(
                    "seed {seed} {reorder}: search {:?} {:?} bound {:?}; milp {:?} {:?} bound {:?}",
                    s.status, s.objective, s.bound, m.status, m.objective, m.bound
                ));
            }
            compared += usize::from(s.bound.is_some());
        }
    }
    assert!(failing.is_empty(), "{}", failing.join("\n"));
    assert!(compared >= 200, "only {compared} solves with a bound");
}

/// The joint search's arc bound `l2` ([`relaxed_node_time`]) against the exact hop solved by the
/// pad MILP (microlp; no dense simplex on that path) on 200 random hops in `none` and `paper`,
/// with and without their support drones: `Infeasible` (the search then takes the arc as
/// infinite) only where the exact solve finds no schedule and neither the empty schedule nor,
/// under `paper`, PB and FB fly; where the exact solve finds none, `Infeasible` from the dense simplex too
/// (never a bound); a bound never above the MILP's proven bound; hops of both kinds among them.
#[test]
fn the_relaxed_node_time_is_infeasible_only_where_no_schedule_flies() {
    let (mut infeasible, mut bounded, mut unknown) = (0, 0, 0);
    for seed in 0..200u64 {
        let mut p = full_start_hop(seed);
        if seed % 4 == 0 {
            // The swarm without its support drones: the empty configuration alone.
            let keep: Vec<usize> = (0..p.drones.len())
                .filter(|&d| p.drones[d].role == Role::Delivery)
                .collect();
            // Each kept drone keeps its slot: slot i of the new hop is drone keep[i]'s.
            let slot: Vec<usize> = keep.iter().map(|&d| p.initial_slot[d]).collect();
            p.drones = keep.iter().map(|&d| p.drones[d].clone()).collect();
            p.slots_m = slot.iter().map(|&q| p.slots_m[q]).collect();
            p.initial_slot = (0..keep.len()).collect();
            for leg in &mut p.legs {
                let rates: Vec<Vec<f64>> = keep
                    .iter()
                    .map(|&d| slot.iter().map(|&q| leg.rate_mah_per_min[d][q]).collect())
                    .collect();
                leg.rate_mah_per_min = rates.into();
            }
        }
        let objective = Objective::NodeTime(EndPads {
            pads: 1 + (seed % 3) as usize,
            pad_rate_mah_per_min: 9.0,
        });
        for reorder in [Reorder::None, Reorder::Paper] {
            let o = ContinuousOptions {
                pad_method: PadMethod::Milp,
                ..options(MilpBackend::Microlp, reorder)
            };
            let m = solve_continuous(&p, &objective, &o).unwrap();
            let what = format!("seed {seed} {reorder}");
            match relaxed_node_time(&p, &objective, &o) {
                RelaxedNodeTime::Infeasible => {
                    assert_eq!(m.status, ExactStatus::Infeasible, "{what}");
                    // PB and FB re-order the formation: their schedules are the model's
                    // under `paper` only.
                    let heuristics: &[Heuristic] = match reorder {
                        Reorder::Paper => &[Heuristic::None, Heuristic::Pb, Heuristic::Fb],
                        _ => &[Heuristic::None],
                    };
                    for &h in heuristics {
                        assert!(!simulate(&p, h).unwrap().feasible, "{what}: {h:?} flies");
                    }
                    infeasible += 1;
                }
                RelaxedNodeTime::Bound(b) => {
                    assert_ne!(m.status, ExactStatus::Infeasible, "{what}");
                    let mb = m.bound.expect("a hop that flies has a bound");
                    assert!(b <= mb + 1e-7 * (1.0 + mb.abs()), "{what}: {b} > {mb}");
                    bounded += 1;
                }
                RelaxedNodeTime::Unknown => {
                    assert_ne!(m.status, ExactStatus::Infeasible, "{what}: unknown");
                    unknown += 1;
                }
            }
        }
    }
    assert!(
        infeasible >= 20 && bounded >= 100,
        "{infeasible} infeasible, {bounded} bounded, {unknown} unknown"
    );
}

#[test]
fn the_swap_is_worth_8_mah_over_none_on_the_paper_swap_hop() {
    let k = known_optima()
        .instances
        .into_iter()
        .find(|k| k.name == "paper_swap_max_min")
        .unwrap();
    // Hand: without the swap drone 0 arrives with 100 - 5 x 10 = 50 mAh.
    let none = solve_continuous(
        &k.problem,
        &k.objective,
        &options(MilpBackend::default(), Reorder::None),
    )
    .unwrap();
    assert_eq!(none.status, ExactStatus::Optimal);
    assert!(close(none.objective.unwrap(), 50.0), "{none:?}");
    let paper = solve_continuous(
        &k.problem,
        &k.objective,
        &options(MilpBackend::default(), Reorder::Paper),
    )
    .unwrap();
    assert!(close(paper.objective.unwrap(), 58.0));
    // The swap schedule moves drone 0 into slot 1.
    assert!(paper
        .transfers
        .iter()
        .any(|t| t.consumer == 0 && t.consumer_slot == 1));
}

/// Support drone 2 in range of consumers 0 and 1 (all on a 1 m line), capacity 100 mAh for the
/// consumers, rho = 2 mAh/min.
fn two_consumers(legs: Vec<(f64, f64)>) -> HopProblem {
    HopProblem {
        legs: legs
            .into_iter()
            .map(|(duration_min, r)| LegRates {
                duration_min,
                rate_mah_per_min: vec![vec![r; 3], vec![r; 3], vec![1.0; 3]].into(),
            })
            .collect(),
        drones: vec![
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m: vec![
            Vector2::new(-1.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 0.0),
        ],
        initial_slot: vec![0, 1, 2],
        rho_mah_per_min: 2.0,
        range_m: 1.2,
        gamma_mah: 50.0,
        lambda_mah: 20.0,
        delta_mah: 0.0,
    }
}

/// models/eaas_config.md, the counterexample: leg 0 (1 min at 101 mAh/min) forces both consumers
/// to exactly 0 at t = 1 (the support drone serving each half the minute); on leg 1 (1 min at
/// 1 mAh/min) it can hold only one of them there.
#[test]
fn fluid_lp_feasible_but_no_schedule_flies() {
    let p = two_consumers(vec![(1.0, 101.0), (1.0, 1.0)]);
    let fl = fluid::bound(&p, &Objective::Feasible, Reorder::None, 10.0).unwrap();
    assert_eq!(fl.status, ExactStatus::Optimal, "the fluid LP is feasible");
    for policy in [Heuristic::None, Heuristic::Pb, Heuristic::Fb] {
        assert!(!simulate(&p, policy).unwrap().feasible, "{policy:?} flies");
    }
    for backend in MilpBackend::all() {
        for reorder in [Reorder::None, Reorder::Paper] {
            let o = solve_continuous(&p, &Objective::Feasible, &options(backend, reorder)).unwrap();
            assert_eq!(
                o.status,
                ExactStatus::NoScheduleFound,
                "{backend} {reorder}: {o:?}"
            );
            assert_eq!(o.bound, Some(0.0));
            assert!(o.outcome.is_none() && o.objective.is_none());
        }
    }
}

/// Both consumers full, rho = 2 against 1 mAh/min for 10 min: the most both can arrive with is
/// 100 mAh (each served 5 min, a straight line at capacity), which no schedule reaches: a served
/// full drone would pass its capacity, so each must first drop.
#[test]
fn an_infimum_only_approached_is_optimal_within_its_certified_epsilon() {
    let p = two_consumers(vec![(10.0, 1.0)]);
    for backend in MilpBackend::all() {
        let o = solve_continuous(
            &p,
            &Objective::MaxMinArrival,
            &options(backend, Reorder::None),
        )
        .unwrap();
        assert_eq!(o.status, ExactStatus::OptimalWithin, "{o:?}");
        assert!(close(o.bound.unwrap(), 100.0));
        let eps = o.epsilon.unwrap();
        let value = o.objective.unwrap();
        assert!(eps > 0.0 && eps < 0.1, "epsilon {eps}");
        assert!(value < 100.0 && value > 99.9, "{value}");
        assert_checked(&p, &o, &Objective::MaxMinArrival);
    }
}

/// The paper swap hop in `free` mode: the only other slot assignment is the swap itself, so the
/// optimum is the `paper` one, 58 mAh, now as slot intervals the free checker replays; each
/// change to them is caught with its code.
#[test]
fn free_schedules_are_slot_intervals_the_checker_replays() {
    let k = known_optima()
        .instances
        .into_iter()
        .find(|k| k.name == "paper_swap_max_min")
        .unwrap();
    let o = solve_continuous(
        &k.problem,
        &k.objective,
        &options(MilpBackend::default(), Reorder::Free),
    )
    .unwrap();
    assert_eq!(o.status, ExactStatus::Optimal, "{o:?}");
    assert!(close(o.objective.unwrap(), 58.0));
    assert_checked(&k.problem, &o, &k.objective);
    let free = o.intervals.clone().unwrap();
    assert!(
        free.final_battery_mah[..2].iter().all(|&b| close(b, 58.0)),
        "{free:?}"
    );
    let codes = |intervals: &[SlotInterval], finals: &[f64]| -> Vec<String> {
        check_free_hop(&k.problem, intervals, finals)
            .iter()
            .map(|v| v.code.to_string())
            .collect()
    };
    let serving = free
        .intervals
        .iter()
        .position(|x| !x.serves.is_empty())
        .unwrap();
    // The support drone (2) leaves its slot.
    let mut moved = free.intervals.clone();
    moved[serving].slot.swap(1, 2);
    assert!(codes(&moved, &free.final_battery_mah).contains(&"C3020".to_string()));
    // The consumer served from slot 0, 3 m from the support drone.
    let mut far = free.intervals.clone();
    let c = far[serving].serves[0].1;
    far[serving].slot[c] = 0;
    far[serving].slot[1 - c] = 1;
    assert!(codes(&far, &free.final_battery_mah).contains(&"C3023".to_string()));
    // A stated battery that is not the re-integrated one.
    let mut finals = free.final_battery_mah.clone();
    finals[0] += 1.0;
    assert_eq!(codes(&free.intervals, &finals), vec!["C3027".to_string()]);
    // A gap in time.
    let mut short = free.intervals.clone();
    short.pop();
    assert!(codes(&short, &free.final_battery_mah).contains(&"C3019".to_string()));
}

#[test]
fn too_many_configurations_is_a_coded_error() {
    let p = two_consumers(vec![(10.0, 1.0)]);
    let few = ContinuousOptions {
        max_configurations: 2,
        ..options(MilpBackend::default(), Reorder::None)
    };
    // Configurations: {}, {2 -> 0}, {2 -> 1}.
    let e = solve_continuous(&p, &Objective::Feasible, &few).unwrap_err();
    assert!(e.to_string().contains("E4117"), "{e}");
}

const NT2: Objective = Objective::NodeTime(EndPads {
    pads: 2,
    pad_rate_mah_per_min: 1.0,
});

/// `value` under a minimisation is at most `limit` up to rounding.
fn at_most(value: f64, limit: f64) -> bool {
    value <= limit + 1e-6 * (1.0 + limit.abs())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// fluid <= continuous <= grid MILP (1 and 0.5 min) in every mode, and continuous <= PB, FB,
    /// no sharing in `paper`; free <= paper <= none; every schedule passes its checker; every
    /// backend agrees.
    #[test]
    fn continuous_lies_between_the_fluid_bound_and_the_grid_and_below_the_heuristics(
        seed in any::<u64>(),
        fast in any::<bool>(),
    ) {
        let mut p = integral_hop(seed);
        if fast {
            // Consumers gain while served: batteries rise inside legs.
            p.rho_mah_per_min = 4.0;
        }
        let mut values = Vec::new();
        for backend in MilpBackend::all() {
            for reorder in [Reorder::None, Reorder::Paper, Reorder::Free] {
                let o = solve_continuous(&p, &NT2, &options(backend, reorder)).unwrap();
                assert_checked(&p, &o, &NT2);
                let fl = fluid::bound(&p, &NT2, reorder, 10.0).unwrap();
                match o.status {
                    ExactStatus::Infeasible => {
                        for period_min in [1.0, 0.5] {
                            let g = solve_milp(&p, &NT2, &MilpOptions { period_min, reorder, backend, time_limit_s: 60.0, node_limit: None }).unwrap();
                            prop_assert_eq!(g.status, ExactStatus::Infeasible);
                        }
                        values.push((reorder, f64::INFINITY));
                        continue;
                    }
                    ExactStatus::Optimal | ExactStatus::OptimalWithin | ExactStatus::NoScheduleFound => {}
                    s => prop_assert!(false, "status {:?}", s),
                }
                let bound = o.bound.unwrap();
                prop_assert!(at_most(fl.bound.unwrap(), bound), "fluid {:?} above {}", fl.bound, bound);
                for period_min in [1.0, 0.5] {
                    let g = solve_milp(&p, &NT2, &MilpOptions { period_min, reorder, backend, time_limit_s: 60.0, node_limit: None }).unwrap();
                    if g.status == ExactStatus::Optimal {
                        prop_assert!(at_most(bound, g.objective.unwrap()), "grid {:?} below {}", g.objective, bound);
                    }
                }
                if reorder == Reorder::Paper {
                    for policy in [Heuristic::None, Heuristic::Pb, Heuristic::Fb] {
                        let h = simulate(&p, policy).unwrap();
                        if h.feasible {
                            let times: Vec<f64> = p.drones.iter().zip(&h.final_battery_mah)
                                .map(|(d, b)| (d.capacity_mah - b).max(0.0)).collect();
                            let nt = swarmplan::node_time::brute(2, &times, &Default::default()).unwrap().makespan_min;
                            prop_assert!(at_most(bound, nt), "{:?} {} below the bound {}", policy, nt, bound);
                            if let Some(v) = o.objective {
                                prop_assert!(at_most(v, nt), "{:?} {} below the schedule {}", policy, nt, v);
                            }
                        }
                    }
                }
                values.push((reorder, bound));
            }
        }
        // Modes are nested: free <= paper <= none (an infeasible mode counts as +infinity).
        let of = |mode: Reorder| values.iter().find(|(r, _)| *r == mode).map(|(_, v)| *v).unwrap();
        prop_assert!(at_most(of(Reorder::Free), of(Reorder::Paper)), "free {} above paper {}", of(Reorder::Free), of(Reorder::Paper));
        prop_assert!(at_most(of(Reorder::Paper), of(Reorder::None)), "paper {} above none {}", of(Reorder::Paper), of(Reorder::None));
        // Every backend gives the same value per mode.
        for (reorder, v) in &values {
            for (r2, v2) in &values {
                if reorder == r2 {
                    prop_assert!(v == v2 || close(*v, *v2), "{} vs {}", v, v2);
                }
            }
        }
    }
}

/// The one dispatch of the exact formulations: the continuous model gives each hand-computed
/// optimum of the known-optima table as a schedule, the fluid LP a bound at or below it
/// (minimising) or at or above it (maximising) and no schedule, the grid MILP a schedule at or
/// above it (every grid schedule is a continuous one), and the fair QP its layout with no bound
/// on the hop's objective.
#[test]
fn the_dispatch_runs_every_formulation_with_its_outcome_type() {
    use swarmplan::eaas::exact::dispatch::{solve, Solved};
    use swarmplan::eaas::exact::Formulation;
    use swarmplan::eaas::PolicyOptions;
    let t = known_optima();
    for k in &t.instances {
        let milp = MilpOptions {
            reorder: k.reorder,
            time_limit_s: 60.0,
            ..MilpOptions::default()
        };
        let maximise = matches!(k.objective, Objective::MaxMinArrival);
        let at_or_beyond = |v: f64| {
            let tol = 1e-6 * (1.0 + v.abs());
            if maximise {
                v <= k.continuous_optimum + tol
            } else {
                v >= k.continuous_optimum - tol
            }
        };
        for f in Formulation::ALL {
            let solved = solve(
                f,
                &k.problem,
                &k.objective,
                &milp,
                &PolicyOptions::default(),
            )
            .unwrap();
            match (f, solved) {
                (Formulation::Continuous, Solved::Schedule(o)) => {
                    assert!(o.objective.is_some_and(|v| close(v, k.continuous_optimum)));
                }
                (Formulation::Fluid, Solved::Bound(b)) => {
                    let bound = b.bound.unwrap();
                    // The bound is on the other side of the optimum from every schedule.
                    assert!(
                        close(bound, k.continuous_optimum) || !at_or_beyond(bound),
                        "{}: bound {bound} beyond {}",
                        k.name,
                        k.continuous_optimum
                    );
                }
                (Formulation::Milp, Solved::Schedule(o)) => {
                    if let Some(v) = o.objective {
                        assert!(at_or_beyond(v), "{}: grid {v}", k.name);
                    }
                }
                (Formulation::Fair, Solved::Schedule(o)) => {
                    assert!(
                        o.bound.is_none() && o.model_objective.is_some(),
                        "{}",
                        k.name
                    );
                }
                (f, other) => panic!("{}: {f:?} answered {other:?}", k.name),
            }
        }
    }
}
