//! Scoring schedules and routes written outside the planner (`src/evaluate/`,
//! `models/evaluate.md`): hop schedules flown as written, their rule breaks, their re-ordering
//! mode, their gap to the continuous-time optimum; stop sequences flown hop by hop against the
//! joint optimum.
//!
//! Every expected value comes from a hand computation written next to it (the two-drone hop of
//! `tests/eaas.rs`, the hops of `instances/eaas/known_optima.json`, `flat-stop` of
//! `instances/tiny/README.md`) or from a second path of the crate that shares no code with
//! `evaluate`: the policies' own simulation (`eaas::simulate`), the continuous model's own row
//! (`eaas::compare::run_method`), and the planner's own plans (`Context::plan`).

mod common;

use common::{assert_close, drone, flat_instance, flat_stop_request, known_optima, line};
use common::{integral_hop, paper_195, uniform_leg, Known};
use swarmplan::compose::{Context, PlanOptions, RouteMethod};
use swarmplan::eaas::compare::{run_method, HopMethod};
use swarmplan::eaas::exact::milp::MilpOptions;
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactStatus, Objective, Reorder};
use swarmplan::eaas::hop_file::HopFile;
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{
    simulate, simulate_with, FailureReason, HopProblem, PolicyOptions, SharingPolicy, Transfer,
};
use swarmplan::error::Error;
use swarmplan::evaluate::{
    default_reference, evaluate_hop, evaluate_route, smallest_mode, HopEvaluation, RouteEvaluation,
    WrittenTransfer,
};
use swarmplan::precompose::Positioning;
use swarmplan::problem::{Request, Role};
use swarmplan::solver::{GapLabel, ReferenceKind};

// ---------------------------------------------------------------------------------------------
// Helpers.

/// A transfer as a user writes it: energy and slot left to their defaults.
fn wt(support: usize, consumer: usize, start_min: f64, end_min: f64) -> WrittenTransfer {
    WrittenTransfer {
        support,
        consumer,
        start_min,
        end_min,
        energy_mah: None,
        consumer_slot: None,
    }
}

/// [`wt`] with the consumer flying in `slot`.
fn wt_in(
    support: usize,
    consumer: usize,
    start_min: f64,
    end_min: f64,
    slot: usize,
) -> WrittenTransfer {
    WrittenTransfer {
        consumer_slot: Some(slot),
        ..wt(support, consumer, start_min, end_min)
    }
}

/// A complete transfer (for [`smallest_mode`], which takes checked transfers).
fn tr(support: usize, consumer: usize, start_min: f64, end_min: f64, slot: usize) -> Transfer {
    Transfer {
        support,
        consumer,
        start_min,
        end_min,
        energy_mah: 0.0,
        consumer_slot: slot,
    }
}

/// The reference settings of [`default_reference`] in re-ordering mode `reorder`.
fn reference_in(reorder: Reorder) -> MilpOptions {
    MilpOptions {
        reorder,
        ..default_reference()
    }
}

/// The violations of an [`Error::Invalid`], panicking on anything else.
fn violations(result: swarmplan::error::Result<HopEvaluation>) -> Vec<swarmplan::error::Violation> {
    match result {
        Err(Error::Invalid(v)) => v,
        Err(other) => panic!("expected Error::Invalid, got {other}"),
        Ok(e) => panic!("expected a rule break, got {e:?}"),
    }
}

/// The codes of a malformed schedule, asserting each names a transfer or a drone and tells the
/// user to change the schedule (not to report a planner bug).
fn codes_of(problem: &HopProblem, transfers: &[WrittenTransfer]) -> Vec<&'static str> {
    let v = violations(evaluate_hop(
        problem,
        &Objective::MaxMinArrival,
        transfers,
        None,
    ));
    for x in &v {
        assert!(
            x.field.starts_with("transfers[") || x.field.starts_with("drones["),
            "{x:?}"
        );
        assert!(x.action.starts_with("change the schedule"), "{x:?}");
    }
    v.iter().map(|x| x.code).collect()
}

/// d0 delivery (cap 200, 80 mAh, 10 mAh/min), d1 support (cap 500, `support_mah`, 5 mAh/min),
/// slots at x = 0 and `support_x`, tt = 10 min, rho = 4, gamma = 50, lambda = 20, delta = 100
/// (the hop of `tests/eaas.rs` and of `eaas::simulate`'s doc example).
fn two_drones_with(support_mah: f64, support_x: f64) -> HopProblem {
    let (slots_m, initial_slot) = line(&[0.0, support_x]);
    HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 200.0, 80.0),
            drone(Role::Support, 500.0, support_mah),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 4.0,
        range_m: 1.2,
        gamma_mah: 50.0,
        lambda_mah: 20.0,
        delta_mah: 100.0,
    }
}

fn two_drones() -> HopProblem {
    two_drones_with(500.0, 1.0)
}

/// Drones at the abscissae `xs` (drone d in slot d) with `roles`, each 200 mAh of 200 (500 of
/// 500 for a support drone), 10 mAh/min (5 for a support drone), one 10-minute leg, rho = 4,
/// range 1.2 m, delta = 100.
fn on_a_line(xs: &[f64], roles: &[Role]) -> HopProblem {
    let (slots_m, initial_slot) = line(xs);
    let support = |r: &Role| *r == Role::Support;
    HopProblem {
        legs: vec![uniform_leg(
            10.0,
            &roles
                .iter()
                .map(|r| if support(r) { 5.0 } else { 10.0 })
                .collect::<Vec<_>>(),
        )],
        drones: roles
            .iter()
            .map(|r| {
                let c = if support(r) { 500.0 } else { 200.0 };
                drone(*r, c, c)
            })
            .collect(),
        slots_m,
        initial_slot,
        rho_mah_per_min: 4.0,
        range_m: 1.2,
        gamma_mah: 50.0,
        lambda_mah: 20.0,
        delta_mah: 100.0,
    }
}

/// A hop of `instances/eaas/known_optima.json` by name.
fn known(name: &str) -> Known {
    known_optima()
        .instances
        .into_iter()
        .find(|k| k.name == name)
        .unwrap_or_else(|| panic!("no known optimum {name}"))
}

fn assert_all_close(got: &[f64], expected: &[f64], what: &str) {
    assert_eq!(got.len(), expected.len(), "{what}: {got:?} vs {expected:?}");
    for (i, (&g, &e)) in got.iter().zip(expected).enumerate() {
        assert_close(g, e, &format!("{what}[{i}]"));
    }
}

/// The relative gap of an evaluation, which must have one.
fn relative_gap(e: &HopEvaluation) -> f64 {
    e.gap
        .and_then(|g| g.relative)
        .unwrap_or_else(|| panic!("no gap: {e:?}"))
}

// ---------------------------------------------------------------------------------------------
// A hop flown as written, by hand.

#[test]
fn the_empty_schedule_runs_the_delivery_drone_out_at_the_hand_computed_time() {
    let p = two_drones();
    // d0: 80 - 10 t reaches 0 at t = 8 min and ends at 80 - 100 = -20; d1: 500 - 5 * 10 = 450.
    let e = evaluate_hop(&p, &Objective::MaxMinArrival, &[], None).unwrap();
    assert!(!e.outcome.feasible);
    let f = e.outcome.failure.expect("a failure");
    assert_eq!((f.drone, f.reason), (0, FailureReason::BatteryDepleted));
    assert_close(f.time_min, 8.0, "failure time");
    assert_all_close(&e.outcome.final_battery_mah, &[-20.0, 450.0], "final");
    assert_all_close(&e.outcome.min_battery_mah, &[-20.0, 450.0], "lowest");
    assert_eq!(e.value, None);
    assert_eq!(e.outcome.shared_mah, 0.0);
    assert_eq!(e.mode, Reorder::None);
    assert_eq!((e.reference, e.gap, e.gap_label), (None, None, None));

    // A short transfer delays the failure: on [0, 1] d0 nets -10 + 4 = -6 mAh/min, 74 mAh at
    // t = 1, then 74 / 10 = 7.4 min more: empty at 8.4 min.
    let e = evaluate_hop(&p, &Objective::MaxMinArrival, &[wt(1, 0, 0.0, 1.0)], None).unwrap();
    assert!(!e.outcome.feasible);
    let f = e.outcome.failure.unwrap();
    assert_eq!(f.drone, 0);
    assert_close(f.time_min, 8.4, "failure time after 1 min of sharing");
    // 80 - 100 + 4 = -16; 500 - 50 - 4 = 446.
    assert_all_close(&e.outcome.final_battery_mah, &[-16.0, 446.0], "final");

    // With a reference an infeasible schedule has no gap, and says why.
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[],
        Some(&default_reference()),
    )
    .unwrap();
    assert_eq!(e.gap, None);
    assert_eq!(e.gap_label, Some(GapLabel::Infeasible));
    // The reference is still the hop's optimum: 80 - 100 + 4 * 10 = 20 (see below).
    assert_close(e.reference.unwrap().value.unwrap(), 20.0, "reference");
}

#[test]
fn a_written_transfer_gives_the_hand_computed_batteries_value_and_gap() {
    let p = two_drones();
    // Sharing on [2, 8]: 4 * 6 = 24 mAh. d0 = 80 - 100 + 24 = 4, falling all along (net -10 or
    // -6 mAh/min): its lowest is its final 4. d1 = 500 - 50 - 24 = 426, lowest 426.
    let e = evaluate_hop(&p, &Objective::MaxMinArrival, &[wt(1, 0, 2.0, 8.0)], None).unwrap();
    assert!(e.outcome.feasible, "{e:?}");
    assert_eq!(e.outcome.failure, None);
    assert_all_close(&e.outcome.final_battery_mah, &[4.0, 426.0], "final");
    assert_all_close(&e.outcome.min_battery_mah, &[4.0, 426.0], "lowest");
    assert_close(e.outcome.shared_mah, 24.0, "shared");
    // The defaults filled in: rho x duration and the consumer's own slot.
    assert_eq!(e.outcome.transfers.len(), 1);
    assert_close(e.outcome.transfers[0].energy_mah, 24.0, "energy");
    assert_eq!(e.outcome.transfers[0].consumer_slot, 0);
    // Max-min arrival: the only delivery drone's arrival battery.
    assert_close(e.value.unwrap(), 4.0, "value");
    assert!(e.value_proven);
    assert_eq!(e.mode, Reorder::None);

    // The reference: d1 can spare 500 - 50 - 100 = 350 mAh, far above the 4 * 10 = 40 mAh that
    // the hop's 10 minutes let it give; d0 only falls (net -6 at best), so it never hits its
    // capacity: the best arrival is 80 - 100 + 40 = 20 mAh, by sharing all along.
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt(1, 0, 2.0, 8.0)],
        Some(&default_reference()),
    )
    .unwrap();
    let r = e.reference.expect("a reference");
    assert_eq!(r.status, ExactStatus::Optimal);
    assert_eq!(r.kind, Some(ReferenceKind::Optimal));
    assert_eq!(r.reorder, Reorder::Paper);
    assert_close(r.value.unwrap(), 20.0, "reference");
    // Maximised, a loss reads positive: (20 - 4) / 20 = 0.8.
    assert_close(relative_gap(&e), 0.8, "gap");
    assert_eq!(e.gap.unwrap().reference, ReferenceKind::Optimal);
    assert_eq!(e.gap_label, None);

    // The whole hop reaches the optimum: gap 0.
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt(1, 0, 0.0, 10.0)],
        Some(&default_reference()),
    )
    .unwrap();
    assert_close(e.value.unwrap(), 20.0, "value of the whole hop");
    assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");

    // The same schedule scored by node time on 2 pads at 10 mAh/min: ct0 = (200 - 4) / 10 =
    // 19.6, ct1 = (500 - 426) / 10 = 7.4, one drone per pad: 19.6. Sharing x mAh (x <= 40)
    // gives ct0 = (220 - x) / 10 >= 18 and ct1 = (50 + x) / 10 <= 9: the optimum is 18 at
    // x = 40, and the gap (19.6 - 18) / 18.
    let two_pads = Objective::NodeTime(EndPads {
        pads: 2,
        pad_rate_mah_per_min: 10.0,
    });
    let e = evaluate_hop(
        &p,
        &two_pads,
        &[wt(1, 0, 2.0, 8.0)],
        Some(&default_reference()),
    )
    .unwrap();
    assert_close(e.value.unwrap(), 19.6, "node time on 2 pads");
    assert_close(e.reference.unwrap().value.unwrap(), 18.0, "reference");
    assert_close(relative_gap(&e), 1.6 / 18.0, "gap");

    // On 1 pad the node time is the total deficit (700 - (80 + 500 - 150)) / 10 = 27 whatever
    // is shared: gap 0.
    let one_pad = Objective::NodeTime(EndPads {
        pads: 1,
        pad_rate_mah_per_min: 10.0,
    });
    let e = evaluate_hop(
        &p,
        &one_pad,
        &[wt(1, 0, 2.0, 8.0)],
        Some(&default_reference()),
    )
    .unwrap();
    assert_close(e.value.unwrap(), 27.0, "node time on 1 pad");
    assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");
}

#[test]
fn the_hand_schedules_of_the_known_optima_reach_the_continuous_optimum() {
    // monotone_balance_2_pads: deficits 40 - x and 20 + x, least max at x = 10 mAh, 2.5 min at
    // rho = 4, anywhere in the leg: 30 min (continuous_source of the table).
    let k = known("monotone_balance_2_pads");
    for (start, end) in [(0.0, 2.5), (1.5, 4.0)] {
        let e = evaluate_hop(
            &k.problem,
            &k.objective,
            &[wt(1, 0, start, end)],
            Some(&reference_in(k.reorder)),
        )
        .unwrap();
        assert_close(e.value.unwrap(), 30.0, "monotone balance");
        assert_close(
            e.reference.unwrap().value.unwrap(),
            k.continuous_optimum,
            "reference",
        );
        assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");
    }
    // rising_consumer_2_pads: x = 5 mAh, served in [9.5, 10): 81 -> 85 mAh; deficits 15 and 15.
    let k = known("rising_consumer_2_pads");
    let e = evaluate_hop(
        &k.problem,
        &k.objective,
        &[wt(1, 0, 9.5, 10.0)],
        Some(&reference_in(k.reorder)),
    )
    .unwrap();
    assert_close(e.value.unwrap(), 15.0, "rising consumer");
    assert_all_close(&e.outcome.final_battery_mah, &[85.0, 185.0], "final");
    assert_close(e.reference.unwrap().value.unwrap(), 15.0, "reference");
    assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");
}

/// Consumers 0 (x = -1) and 1 (x = 1), full at 100 of 100 mAh and using 1 mAh/min, support
/// drone 2 (x = 0, 1000 mAh, 1 mAh/min) within range of both, rho = 2, one 10-minute leg
/// (`tests/eaas_continuous.rs`, the infimum only approached).
fn two_full_consumers() -> HopProblem {
    HopProblem {
        legs: vec![uniform_leg(10.0, &[1.0, 1.0, 1.0])],
        drones: vec![
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m: line(&[-1.0, 1.0, 0.0]).0,
        initial_slot: vec![0, 1, 2],
        rho_mah_per_min: 2.0,
        range_m: 1.2,
        gamma_mah: 50.0,
        lambda_mah: 20.0,
        delta_mah: 0.0,
    }
}

#[test]
fn a_schedule_is_measured_against_an_infimum_the_model_only_approaches() {
    let p = two_full_consumers();
    // A served consumer nets +1 mAh/min and may not pass 100, so it must first drop. Serving d1
    // on [10/3, 20/3] and d0 on [20/3, 10]: d1 falls to 96.667, climbs back to 100 at 20/3 and
    // falls to 96.667; d0 falls to 93.333 at 20/3 and climbs to 96.667. Lowest arrival 290/3.
    // The support drone gives 2 x 20/3 = 40/3 mAh and uses 10 itself. Each consumer served 5
    // min would bring both to 100, the infimum (no schedule reaches it).
    let schedule = [wt(2, 1, 10.0 / 3.0, 20.0 / 3.0), wt(2, 0, 20.0 / 3.0, 10.0)];
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &schedule,
        Some(&default_reference()),
    )
    .unwrap();
    assert!(e.outcome.feasible, "{e:?}");
    assert_all_close(
        &e.outcome.final_battery_mah,
        &[290.0 / 3.0, 290.0 / 3.0, 1000.0 - 10.0 - 40.0 / 3.0],
        "final",
    );
    assert_all_close(
        &e.outcome.min_battery_mah,
        &[280.0 / 3.0, 290.0 / 3.0, 1000.0 - 10.0 - 40.0 / 3.0],
        "lowest",
    );
    assert_close(e.value.unwrap(), 290.0 / 3.0, "value");
    let r = e.reference.unwrap();
    assert_eq!(r.status, ExactStatus::OptimalWithin);
    assert_eq!(r.kind, Some(ReferenceKind::Infimum));
    assert_close(r.value.unwrap(), 100.0, "infimum");
    let eps = r.epsilon.unwrap();
    assert!(eps > 0.0 && eps < 0.1, "epsilon {eps}");
    assert_eq!(e.gap.unwrap().reference, ReferenceKind::Infimum);
    // Maximised: the loss (100 - 290/3) / 100 reads positive.
    assert_close(relative_gap(&e), (100.0 - 290.0 / 3.0) / 100.0, "gap");
    // Serving d0 from the start would pass its capacity: C3011.
    assert_eq!(codes_of(&p, &[wt(2, 0, 0.0, 1.0)]), ["C3011"]);
}

// ---------------------------------------------------------------------------------------------
// Rule breaks: each with the checker's code, none panics.

#[test]
fn each_rule_break_is_an_error_with_the_checkers_code() {
    let p = two_drones();
    // C3001: a support drone, a consumer or a slot that does not exist (the consumer's default
    // slot is then out of range too).
    assert_eq!(codes_of(&p, &[wt(5, 0, 2.0, 8.0)]), ["C3001"]);
    assert_eq!(codes_of(&p, &[wt(1, 7, 2.0, 8.0)]), ["C3001"]);
    assert_eq!(codes_of(&p, &[wt_in(1, 0, 2.0, 8.0, 9)]), ["C3001"]);
    assert_eq!(
        codes_of(&p, &[wt(1, 0, 2.0, 8.0), wt(usize::MAX, 0, 0.0, 1.0)]),
        ["C3001"]
    );
    // C3002: the giver is a delivery drone (it then also shares below delta = 100: d0 is at
    // 80 - 10 * 8 = 0 mAh at t = 8, so C3012 comes along).
    assert!(codes_of(&p, &[wt(0, 0, 2.0, 8.0)]).contains(&"C3002"));
    // C3003: the consumer is the support drone itself.
    assert_eq!(codes_of(&p, &[wt(1, 1, 2.0, 8.0)]), ["C3003"]);
    // C3004: past tt = 10, empty or reversed spans, before 0, and times that are not numbers.
    assert_eq!(codes_of(&p, &[wt(1, 0, 8.0, 12.0)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, 6.0, 5.0)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, 5.0, 5.0)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, -1.0, 2.0)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, f64::NAN, 2.0)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, 2.0, f64::NAN)]), ["C3004"]);
    assert_eq!(codes_of(&p, &[wt(1, 0, 2.0, f64::INFINITY)]), ["C3004"]);
    assert_eq!(
        codes_of(
            &p,
            &[WrittenTransfer {
                energy_mah: Some(f64::NAN),
                ..wt(1, 0, 2.0, 8.0)
            }]
        ),
        ["C3004"]
    );
    // C3005: 99 mAh stated, rho x duration = 4 x 6 = 24.
    let wrong = WrittenTransfer {
        energy_mah: Some(99.0),
        ..wt(1, 0, 2.0, 8.0)
    };
    assert_eq!(codes_of(&p, &[wrong]), ["C3005"]);
    // ... and the right energy stated is accepted.
    let right = WrittenTransfer {
        energy_mah: Some(24.0),
        ..wt(1, 0, 2.0, 8.0)
    };
    assert!(evaluate_hop(&p, &Objective::MaxMinArrival, &[right], None).is_ok());
    // Two rules of one transfer at once: beyond tt and a wrong energy (4 x 4 = 16 expected).
    let both = WrittenTransfer {
        energy_mah: Some(99.0),
        ..wt(1, 0, 8.0, 12.0)
    };
    assert_eq!(codes_of(&p, &[both]), ["C3004", "C3005"]);

    // C3006: the support drone 2 m away, range 1.2 m.
    let far = two_drones_with(500.0, 2.0);
    assert_eq!(codes_of(&far, &[wt(1, 0, 2.0, 8.0)]), ["C3006"]);

    // C3011: rising_consumer_2_pads served from the start: 100 + (10 - 2) * 0.5 = 104 > 100.
    let k = known("rising_consumer_2_pads");
    assert_eq!(codes_of(&k.problem, &[wt(1, 0, 0.0, 0.5)]), ["C3011"]);

    // C3013: a support drone of 160 mAh uses 5 * 10 = 50 itself and keeps delta = 100: it may
    // give 10 mAh. On [0, 5] it gives 20 (and is at 160 - 25 - 20 = 115 >= 100 at t = 5: no
    // C3012); on [0, 10] it gives 40 and ends at 160 - 50 - 40 = 70 < 100 while sharing: C3012
    // too.
    let poor = two_drones_with(160.0, 1.0);
    assert_eq!(codes_of(&poor, &[wt(1, 0, 0.0, 5.0)]), ["C3013"]);
    let mut c = codes_of(&poor, &[wt(1, 0, 0.0, 10.0)]);
    c.sort_unstable();
    assert_eq!(c, ["C3012", "C3013"]);
}

#[test]
fn overlapping_transfers_break_the_one_at_a_time_rules() {
    use Role::{Delivery, Support};
    // d0 at x = 0, d1 at x = 2, support d2 at x = 1: both consumers within 1 m.
    let p = on_a_line(&[0.0, 2.0, 1.0], &[Delivery, Delivery, Support]);
    // C3008: d2 gives to d0 on [0, 2] and to d1 on [1, 3].
    assert_eq!(
        codes_of(&p, &[wt(2, 0, 0.0, 2.0), wt(2, 1, 1.0, 3.0)]),
        ["C3008"]
    );
    // Back to back is fine.
    assert!(evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt(2, 0, 0.0, 2.0), wt(2, 1, 2.0, 3.0)],
        None
    )
    .is_ok());
    // C3007: d0 flying in the support drone's slot.
    assert_eq!(codes_of(&p, &[wt_in(2, 0, 0.0, 2.0, 2)]), ["C3007"]);

    // C3009: d0 at x = 0 between support drones at x = 1 and x = -1, served by both on [1, 2].
    let p = on_a_line(&[0.0, 1.0, -1.0], &[Delivery, Support, Support]);
    assert_eq!(
        codes_of(&p, &[wt(1, 0, 0.0, 2.0), wt(2, 0, 1.0, 3.0)]),
        ["C3009"]
    );

    // C3010: d0 (x = -3) swaps into d1's slot (x = 0) to be served by d2 (x = 1) on [0, 2],
    // while d3 (x = -1) serves d1 in its own slot on [1, 3]: d1 moves in both.
    let p = on_a_line(
        &[-3.0, 0.0, 1.0, -1.0],
        &[Delivery, Delivery, Support, Support],
    );
    assert_eq!(
        codes_of(&p, &[wt_in(2, 0, 0.0, 2.0, 1), wt(3, 1, 1.0, 3.0)]),
        ["C3010"]
    );
    // Apart in time, the same two transfers keep the rules.
    assert!(evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt_in(2, 0, 0.0, 2.0, 1), wt(3, 1, 2.0, 3.0)],
        None
    )
    .is_ok());
}

// ---------------------------------------------------------------------------------------------
// The smallest re-ordering mode of a schedule.

#[test]
fn the_mode_of_a_schedule_follows_the_papers_move_rules() {
    use Role::{Delivery, Support};
    // d0 at x = 0 and d1 at x = 2, both 1 m from the support drone d2 at x = 1 (range 1.2).
    let p = on_a_line(&[0.0, 2.0, 1.0], &[Delivery, Delivery, Support]);
    // Own slots within range: `none`.
    assert_eq!(smallest_mode(&p, &[]), Reorder::None);
    assert_eq!(
        smallest_mode(&p, &[tr(2, 0, 0.0, 1.0, 0), tr(2, 1, 1.0, 2.0, 1)]),
        Reorder::None
    );
    // d0 is within range, so the paper leaves it in place; moving it into d1's slot (1 m from
    // the support drone, a valid swap with a delivery drone) is only a `free` schedule.
    assert_eq!(smallest_mode(&p, &[tr(2, 0, 0.0, 1.0, 1)]), Reorder::Free);
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt_in(2, 0, 0.0, 1.0, 1)],
        Some(&default_reference()),
    )
    .unwrap();
    assert!(e.outcome.feasible);
    assert_eq!(e.mode, Reorder::Free);
    // Outside the `paper` reference: no gap.
    assert_eq!(
        (e.gap, e.gap_label),
        (None, Some(GapLabel::OutsideReference))
    );
    // ... but inside a `free` one.
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &[wt_in(2, 0, 0.0, 1.0, 1)],
        Some(&reference_in(Reorder::Free)),
    )
    .unwrap();
    assert_eq!(e.gap_label, None);
    assert!(e.gap.is_some(), "{e:?}");

    // paper_swap_max_min: d0 at x = -2 is 3 m from the support drone d2 (x = 1): out of range;
    // d1's slot (x = 0) is 1 m away and held by a delivery drone: the paper's swap.
    let k = known("paper_swap_max_min");
    let swap = tr(2, 0, 0.0, 2.0, 1);
    let own = tr(2, 1, 2.0, 5.0, 1);
    assert_eq!(smallest_mode(&k.problem, &[swap]), Reorder::Paper);
    assert_eq!(smallest_mode(&k.problem, &[swap, own]), Reorder::Paper);
    assert_eq!(smallest_mode(&k.problem, &[own]), Reorder::None);
}

#[test]
fn a_swapping_schedule_is_scored_against_paper_and_left_out_of_none() {
    let k = known("paper_swap_max_min");
    // The hand optimum: d2 serves d0 swapped into slot 1 on [0, 2], then d1 in place on [2, 5].
    // d0 = 100 - 10 * 5 + 4 * 2 = 58; d1 flies slot 0 at 12 for 2 min and slot 1 at 10 for 3:
    // 100 - 24 - 30 + 4 * 3 = 58; d2 = 100 - 5 * 5 - 4 * 5 = 55.
    let schedule = [wt_in(2, 0, 0.0, 2.0, 1), wt(2, 1, 2.0, 5.0)];
    let e = evaluate_hop(
        &k.problem,
        &k.objective,
        &schedule,
        Some(&reference_in(Reorder::Paper)),
    )
    .unwrap();
    assert!(e.outcome.feasible);
    assert_all_close(&e.outcome.final_battery_mah, &[58.0, 58.0, 55.0], "final");
    assert_close(e.outcome.shared_mah, 20.0, "shared");
    assert_eq!(e.mode, Reorder::Paper);
    assert_close(e.value.unwrap(), 58.0, "value");
    assert_close(
        e.reference.unwrap().value.unwrap(),
        k.continuous_optimum,
        "paper reference",
    );
    assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");

    // Against `none` the swap lies outside the reference's schedules: no gap. The reference
    // itself is the hand value without the swap: d0 keeps 50 mAh.
    let e = evaluate_hop(
        &k.problem,
        &k.objective,
        &schedule,
        Some(&reference_in(Reorder::None)),
    )
    .unwrap();
    assert_eq!(e.gap, None);
    assert_eq!(e.gap_label, Some(GapLabel::OutsideReference));
    assert_eq!(e.reference.unwrap().reorder, Reorder::None);
    assert_close(e.reference.unwrap().value.unwrap(), 50.0, "none reference");

    // Serving d1 in place all along: d0 = 50, d1 = 100 - 50 + 20 = 70; min 50. In `none` it is
    // optimal (gap 0); against `paper` it loses (58 - 50) / 58 (maximised: a loss is positive).
    let in_place = [wt(2, 1, 0.0, 5.0)];
    let e = evaluate_hop(
        &k.problem,
        &k.objective,
        &in_place,
        Some(&reference_in(Reorder::None)),
    )
    .unwrap();
    assert_eq!(e.mode, Reorder::None);
    assert_close(e.value.unwrap(), 50.0, "in place");
    assert!(relative_gap(&e).abs() <= 1e-6, "{e:?}");
    let e = evaluate_hop(
        &k.problem,
        &k.objective,
        &in_place,
        Some(&reference_in(Reorder::Paper)),
    )
    .unwrap();
    assert_close(relative_gap(&e), (58.0 - 50.0) / 58.0, "in place vs paper");
}

// ---------------------------------------------------------------------------------------------
// Against the policies' own simulation and the continuous model's own schedule.

/// Checks PB's and the continuous model's schedules on `problem`, scored by `objective`, both
/// fed back through `evaluate_hop`; returns whether the continuous schedule was optimal.
fn policies_fed_back(problem: &HopProblem, objective: &Objective, what: &str) -> bool {
    let reference = default_reference();
    let minimise = matches!(objective, Objective::NodeTime(EndPads { .. }));
    // PB: its own simulation gives the batteries and feasibility; its row the value.
    let pb = simulate_with(problem, Heuristic::Pb, &PolicyOptions::default()).unwrap();
    let written: Vec<WrittenTransfer> = pb.transfers.iter().map(WrittenTransfer::from).collect();
    let e = evaluate_hop(problem, objective, &written, Some(&reference)).unwrap();
    assert_eq!(e.outcome.feasible, pb.feasible, "{what}: PB feasibility");
    assert_all_close(
        &e.outcome.final_battery_mah,
        &pb.final_battery_mah,
        &format!("{what}: PB final"),
    );
    assert_all_close(
        &e.outcome.min_battery_mah,
        &pb.min_battery_mah,
        &format!("{what}: PB lowest"),
    );
    assert_close(
        e.outcome.shared_mah,
        pb.shared_mah,
        &format!("{what}: PB shared"),
    );
    assert_eq!(
        e.outcome.failure.map(|f| f.drone),
        pb.failure.map(|f| f.drone),
        "{what}: PB failure"
    );
    let row = run_method(
        problem,
        objective,
        HopMethod::Pb,
        &reference,
        &PolicyOptions::default(),
    )
    .unwrap();
    match (e.value, row.objective) {
        (Some(a), Some(b)) => assert_close(a, b, &format!("{what}: PB value")),
        (a, b) => assert_eq!(a, b, "{what}: PB value"),
    }
    // PB swaps only out-of-range consumers into in-range delivery slots: within `paper`.
    assert_ne!(e.mode, Reorder::Free, "{what}: PB mode");
    if let Some(g) = e.gap.and_then(|g| g.relative) {
        // A gap is a loss under either sense: never below the optimum.
        let beyond = if minimise {
            "node time below"
        } else {
            "arrival above"
        };
        assert!(g >= -1e-6, "{what}: PB {beyond} the optimum, gap {g}");
    } else if pb.feasible {
        assert!(
            e.gap_label == Some(GapLabel::NoReference) || e.gap.is_some(),
            "{what}: {e:?}"
        );
    } else {
        assert_eq!(e.gap_label, Some(GapLabel::Infeasible), "{what}");
    }

    // The continuous model's own schedule scores its own optimum: gap 0.
    let row = run_method(
        problem,
        objective,
        HopMethod::Continuous,
        &reference,
        &PolicyOptions::default(),
    )
    .unwrap();
    let optimal = row.status == Some(ExactStatus::Optimal) && row.objective_proven;
    if optimal {
        let written: Vec<WrittenTransfer> =
            row.transfers.iter().map(WrittenTransfer::from).collect();
        let e = evaluate_hop(problem, objective, &written, Some(&reference)).unwrap();
        assert!(
            e.outcome.feasible,
            "{what}: continuous schedule infeasible: {e:?}"
        );
        assert_close(
            e.value.unwrap(),
            row.objective.unwrap(),
            &format!("{what}: continuous value"),
        );
        assert_eq!(e.reference.unwrap().kind, Some(ReferenceKind::Optimal));
        if let Some(g) = e.gap.and_then(|g| g.relative) {
            assert!(g.abs() <= 1e-6, "{what}: continuous gap {g}");
        } else {
            // A zero reference (an arrival battery of 0) has no relative gap.
            assert_close(row.objective.unwrap(), 0.0, what);
        }
    }
    optimal
}

#[test]
fn pb_and_continuous_schedules_fed_back_keep_their_batteries_and_gap_signs() {
    let mut optimal = 0;
    let mut cases = 0;
    for seed in 0..40u64 {
        let p = integral_hop(seed);
        for objective in [
            Objective::MaxMinArrival,
            Objective::NodeTime(EndPads {
                pads: 2,
                pad_rate_mah_per_min: 1.0,
            }),
        ] {
            cases += 1;
            optimal += usize::from(policies_fed_back(
                &p,
                &objective,
                &format!("seed {seed} {objective:?}"),
            ));
        }
    }
    // The hops of the known optima too, with their hand-computed continuous optimum as the
    // reference's value.
    for k in known_optima().instances {
        if k.reorder != Reorder::Paper {
            continue;
        }
        cases += 1;
        optimal += usize::from(policies_fed_back(&k.problem, &k.objective, &k.name));
        let r = swarmplan::evaluate::hop_reference(&k.problem, &k.objective, &default_reference())
            .unwrap();
        assert_close(r.value.unwrap(), k.continuous_optimum, &k.name);
    }
    // Not vacuous: most continuous solves are optimal.
    assert!(optimal * 2 >= cases, "{optimal} of {cases} optimal");
}

// ---------------------------------------------------------------------------------------------
// Routes on flat-stop, by hand (instances/tiny/README.md and tests/exact_route.rs).
//
// A - M - B, 2500 m each (5 min at 500 m/min), M with 2 pads at 100 mAh/min. Drones 0, 1 carry
// 0.21 kg (133.1 mAh/min), drone 2 0.44 kg (172.8), drone 3 supports (172.8, 2000 mAh). From
// full over 5 min: arrivals 334.5, 334.5, 136, 1136 mAh; charge times 6.655, 6.655, 8.64, 8.64
// min; on 2 pads nt = 15.295 ({6.655, 8.64} on each). Direct A -> B (10 min): drone 2 is empty
// at 1000 / 172.8 = 5.787 min. The joint optimum is 5 + 15.295 + 5 = 25.295: sharing never
// changes the summed charge time 30.59, so nt >= 15.295, and no schedule flies A -> B direct.

const FLAT_STOP_NT_MIN: f64 = 15.295;
const FLAT_STOP_DT_MIN: f64 = 25.295;

fn flat_stop_route(
    stops: &[&str],
    schedule: &mut dyn FnMut(&HopFile) -> swarmplan::error::Result<Vec<WrittenTransfer>>,
    with_reference: bool,
) -> swarmplan::error::Result<RouteEvaluation> {
    let (network, graph, profile) = flat_instance("flat-stop.json");
    let context = Context::new(&network, &graph, &profile);
    let request = flat_stop_request("flat-stop");
    let stops: Vec<String> = stops.iter().map(|s| s.to_string()).collect();
    evaluate_route(
        &context,
        &request,
        Positioning::LocationAware,
        Some(1),
        &stops,
        schedule,
        with_reference,
    )
}

fn no_sharing(_: &HopFile) -> swarmplan::error::Result<Vec<WrittenTransfer>> {
    Ok(Vec::new())
}

#[test]
fn a_route_without_sharing_on_flat_stop_has_the_hand_computed_delivery_time_and_no_gap() {
    let r = flat_stop_route(&["A", "M", "B"], &mut no_sharing, true).unwrap();
    assert!(r.delivered, "{r:?}");
    assert_eq!(r.support_drones, 1);
    assert_eq!(r.stops, ["A", "M", "B"]);
    assert_eq!(r.hops.len(), 2);
    assert_close(r.tt_min, 10.0, "tt");
    assert_close(r.nt_min, FLAT_STOP_NT_MIN, "nt");
    assert_close(r.dt_min.unwrap(), FLAT_STOP_DT_MIN, "dt");
    assert!(r.dt_proven);
    assert_eq!(r.mode, Reorder::None);

    let h0 = &r.hops[0];
    assert_eq!((h0.hop.from.as_str(), h0.hop.to.as_str()), ("A", "M"));
    assert_eq!(h0.hop.path, ["A", "M"]);
    assert_eq!(h0.hop.hop_index, 0);
    assert_close(h0.tt_min, 5.0, "hop 0 tt");
    // Departing full: 1000 mAh each, 2000 for the support drone.
    let departure: Vec<f64> = h0.hop.hop.drones.iter().map(|d| d.battery_mah).collect();
    assert_all_close(&departure, &[1000.0, 1000.0, 1000.0, 2000.0], "departure");
    assert_all_close(
        &h0.evaluation.outcome.final_battery_mah,
        &[334.5, 334.5, 136.0, 1136.0],
        "arrival at M",
    );
    // Into M the objective is the node time on its 2 pads.
    assert_eq!(
        h0.hop.objective(),
        Objective::NodeTime(EndPads {
            pads: 2,
            pad_rate_mah_per_min: 100.0
        })
    );
    assert_close(
        h0.evaluation.value.unwrap(),
        FLAT_STOP_NT_MIN,
        "hop 0 value",
    );
    let stop = h0.stop.as_ref().expect("a stop at M");
    assert_eq!(stop.node, "M");
    assert_close(stop.nt_min, FLAT_STOP_NT_MIN, "stop nt");
    assert_all_close(
        &stop.charge_times_min,
        &[6.655, 6.655, 8.64, 8.64],
        "charge times",
    );
    // Into the destination: no stop, the lowest delivery arrival, again 334.5 / 136 -> 136.
    let h1 = &r.hops[1];
    assert_eq!(h1.stop, None);
    assert_eq!(h1.hop.end, None);
    assert_eq!(h1.hop.objective(), Objective::MaxMinArrival);
    assert_close(h1.evaluation.value.unwrap(), 136.0, "hop 1 value");

    let reference = r.reference.expect("a reference");
    assert_close(reference.dt_min.unwrap(), FLAT_STOP_DT_MIN, "reference dt");
    assert_eq!(reference.kind, ReferenceKind::Optimal);
    assert_eq!(reference.reorder, Reorder::Paper);
    let gap = r.gap.expect("a gap");
    assert_eq!(gap.reference, ReferenceKind::Optimal);
    assert!(gap.relative.unwrap().abs() <= 1e-6, "gap {gap:?}");
    assert_eq!(r.gap_label, None);
}

#[test]
fn pb_schedules_on_flat_stop_give_the_hand_computed_overshared_stop() {
    // PB on A -> M: drone 2 drops below gamma = 500 at 500 / 172.8 = 2.8935 min and is served
    // until tt: 120 (5 - 2.8935) = 252.78 mAh; the 0.21 kg drones (below 500 at 3.757 min) wait
    // for the busy support drone. Charge times 6.655, 6.655, 6.1122, 11.1678: on 2 pads the best
    // split is {6.655, 6.655} | {6.1122, 11.1678} = 17.28, so dt = 5 + 17.28 + 5 = 27.28.
    let mut pb = |file: &HopFile| {
        let o = simulate(&file.hop, Heuristic::Pb)?;
        Ok(o.transfers.iter().map(WrittenTransfer::from).collect())
    };
    let r = flat_stop_route(&["A", "M", "B"], &mut pb, true).unwrap();
    assert!(r.delivered);
    let shared = 120.0 * (5.0 - 500.0 / 172.8);
    let h0 = &r.hops[0].evaluation;
    assert_close(h0.outcome.shared_mah, shared, "shared into M");
    assert_all_close(
        &h0.outcome.final_battery_mah,
        &[334.5, 334.5, 136.0 + shared, 1136.0 - shared],
        "arrival at M",
    );
    assert_close(r.nt_min, 17.28, "nt");
    assert_close(r.dt_min.unwrap(), 27.28, "dt");
    assert_ne!(r.mode, Reorder::Free);
    assert_close(
        r.gap.and_then(|g| g.relative).unwrap(),
        (27.28 - FLAT_STOP_DT_MIN) / FLAT_STOP_DT_MIN,
        "gap",
    );
}

#[test]
fn a_route_that_runs_out_is_not_delivered_and_has_no_gap() {
    // Direct A -> B without sharing: drone 2 is empty at 1000 / 172.8 min.
    let r = flat_stop_route(&["A", "B"], &mut no_sharing, true).unwrap();
    assert!(!r.delivered);
    assert_eq!(r.dt_min, None);
    assert_eq!(r.hops.len(), 1);
    let f = r.hops[0].evaluation.outcome.failure.expect("a failure");
    assert_eq!(f.drone, 2);
    assert_close(f.time_min, 1000.0 / 172.8, "failure time");
    assert_close(r.tt_min, 10.0, "tt of the hop flown");
    assert_eq!((r.gap, r.gap_label), (None, Some(GapLabel::NotDelivered)));
    assert_close(
        r.reference.unwrap().dt_min.unwrap(),
        FLAT_STOP_DT_MIN,
        "reference dt",
    );
}

/// flat-deadend (instances/tiny/README.md): A, M1 (2000 m, 1 pad), M2 (4000 m, 1 pad), B
/// (11000 m) on a line; one 0.21 kg drone, 133.1 mAh/min, so it flies at most 1000 / 133.1 =
/// 7.513 min. A hop of 4 min arrives with 1000 - 532.4 = 467.6 mAh and the stop lasts
/// 532.4 / 100 = 5.324 min; B is 14 min from M2.
#[test]
fn a_route_is_flown_up_to_its_first_hop_that_runs_out() {
    let (network, graph, profile) = flat_instance("flat-deadend.json");
    let context = Context::new(&network, &graph, &profile);
    let request = Request {
        id: "deadend".into(),
        source: "A".into(),
        destination: "B".into(),
        packages_kg: vec![0.21],
    };
    let route = |stops: &[&str], with_reference: bool| {
        let stops: Vec<String> = stops.iter().map(|s| s.to_string()).collect();
        let mut flown = Vec::new();
        let mut schedule = |file: &HopFile| {
            flown.push(file.to.clone());
            Ok(Vec::new())
        };
        let r = evaluate_route(
            &context,
            &request,
            Positioning::LocationAware,
            Some(0),
            &stops,
            &mut schedule,
            with_reference,
        )
        .unwrap();
        (r, flown)
    };
    // A, M1, M2, B: two stops of 5.324 min, then 14 min into B: empty at 7.513 min.
    let (r, flown) = route(&["A", "M1", "M2", "B"], true);
    assert_eq!(flown, ["M1", "M2", "B"]);
    assert!(!r.delivered);
    assert_eq!(r.hops.len(), 3);
    assert_close(r.nt_min, 2.0 * 5.324, "nt of the stops made");
    assert_close(r.tt_min, 4.0 + 4.0 + 14.0, "tt of the hops flown");
    assert_all_close(
        &r.hops[0].evaluation.outcome.final_battery_mah,
        &[467.6],
        "arrival at M1",
    );
    let f = r.hops[2].evaluation.outcome.failure.unwrap();
    assert_eq!(f.drone, 0);
    assert_close(f.time_min, 1000.0 / 133.1, "failure time");
    // No route delivers either: M2, the pad node nearest B, is 14 min away.
    assert_eq!(r.reference.unwrap().dt_min, None);
    assert_eq!(r.gap_label, Some(GapLabel::NotDelivered));

    // A, M2, M1, B: A -> M2 is 8 min, the drone is empty at 7.513; nothing after it is flown.
    let (r, flown) = route(&["A", "M2", "M1", "B"], false);
    assert_eq!(flown, ["M2"]);
    assert!(!r.delivered);
    assert_eq!(r.hops.len(), 1);
    assert_eq!(r.hops[0].hop.path, ["A", "M1", "M2"]);
    assert_eq!(r.hops[0].stop, None);
    assert_close(r.tt_min, 8.0, "tt");
    assert_eq!(r.nt_min, 0.0);
    assert_eq!(r.reference, None);
}

#[test]
fn a_malformed_hop_schedule_names_its_hop_and_a_schedule_error_passes_through() {
    let mut bad_second = |file: &HopFile| {
        Ok(if file.hop_index == 1 {
            vec![wt(9, 0, 0.0, 1.0)]
        } else {
            Vec::new()
        })
    };
    match flat_stop_route(&["A", "M", "B"], &mut bad_second, false) {
        Err(Error::Invalid(v)) => {
            assert_eq!(v.len(), 1, "{v:?}");
            assert_eq!(v[0].code, "C3001");
            assert_eq!(v[0].field, "hops[1].transfers[0]");
        }
        other => panic!("expected C3001, got {other:?}"),
    }
    let mut failing = |_: &HopFile| -> swarmplan::error::Result<Vec<WrittenTransfer>> {
        Err(Error::invalid("E9999", "mine", "my own error", "none"))
    };
    match flat_stop_route(&["A", "M", "B"], &mut failing, false) {
        Err(Error::Invalid(v)) => assert_eq!(v[0].code, "E9999"),
        other => panic!("expected the schedule's error, got {other:?}"),
    }
}

// ---------------------------------------------------------------------------------------------
// Bad stop lists.

fn stop_codes(stops: &[&str]) -> Vec<(&'static str, String)> {
    let mut called = false;
    let mut schedule = |_: &HopFile| {
        called = true;
        Ok(Vec::new())
    };
    let result = flat_stop_route(stops, &mut schedule, false);
    assert!(!called, "{stops:?}: a hop was flown");
    match result {
        Err(Error::Invalid(v)) => v.into_iter().map(|x| (x.code, x.field)).collect(),
        other => panic!("{stops:?}: expected a stop error, got {other:?}"),
    }
}

#[test]
fn bad_stop_lists_are_rejected_with_their_codes() {
    let e = |code: &'static str, field: &str| (code, field.to_string());
    // E0022: not from the source, not to the destination, too short.
    assert_eq!(stop_codes(&["M", "B"]), vec![e("E0022", "stops")]);
    assert_eq!(stop_codes(&["A", "M"]), vec![e("E0022", "stops")]);
    assert_eq!(stop_codes(&["A"]), vec![e("E0022", "stops")]);
    assert_eq!(stop_codes(&[]), vec![e("E0022", "stops")]);
    // E0023: an unknown id (with E0022 when it is the first stop).
    assert_eq!(stop_codes(&["A", "X", "B"]), vec![e("E0023", "stops[1]")]);
    assert_eq!(
        stop_codes(&["X", "B"]),
        vec![e("E0022", "stops"), e("E0023", "stops[0]")]
    );
    // E0024: B has no pads, so it cannot be a stop on the way.
    assert_eq!(
        stop_codes(&["A", "B", "M", "B"]),
        vec![e("E0024", "stops[1]")]
    );
    // E0025: M twice in a row.
    assert_eq!(
        stop_codes(&["A", "M", "M", "B"]),
        vec![e("E0025", "stops[2]")]
    );
}

#[test]
fn stops_the_network_does_not_connect_are_rejected() {
    // island.json: Q has 3 pads and no edge (instances/tiny/README.md).
    let (network, graph, profile) = flat_instance("island.json");
    let context = Context::new(&network, &graph, &profile);
    let request = Request {
        id: "island".into(),
        source: "X".into(),
        destination: "Y".into(),
        packages_kg: vec![0.21],
    };
    let stops: Vec<String> = ["X", "Q", "Y"].iter().map(|s| s.to_string()).collect();
    let mut schedule =
        |_: &HopFile| -> swarmplan::error::Result<Vec<WrittenTransfer>> { panic!("no hop flies") };
    match evaluate_route(
        &context,
        &request,
        Positioning::LocationAware,
        None,
        &stops,
        &mut schedule,
        false,
    ) {
        Err(Error::Invalid(v)) => {
            assert_eq!(v.len(), 1, "{v:?}");
            assert_eq!((v[0].code, v[0].field.as_str()), ("E0025", "stops[1]"));
        }
        other => panic!("expected E0025, got {other:?}"),
    }
}

// ---------------------------------------------------------------------------------------------
// Routes on paper-195 against the planner's own plans.

/// Requests of paper-195 whose PB plan with `--route optimal` delivers with a transfer, each
/// planned in well under a second under `--sharing exact`.
const PAPER_195_REQUESTS: [&str; 5] = ["r00023", "r00080", "r00125", "r00136", "r00312"];

fn options(sharing: SharingPolicy) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning: Positioning::LocationAware,
        route: RouteMethod::Optimal,
        support: None,
    }
}

/// Feeds `plan`'s stops and its hops' own transfers back through `evaluate_route`, checking
/// every hop against the plan's and the delivery time against `plan.dt_min`.
fn fed_back(
    context: &Context,
    request: &Request,
    plan: &swarmplan::compose::Plan,
    what: &str,
) -> RouteEvaluation {
    let mut stops = vec![plan.source.clone()];
    stops.extend(plan.hops.iter().map(|h| h.to.clone()));
    let mut schedule = |file: &HopFile| {
        let hop = &plan.hops[file.hop_index];
        // The rule path between the stops is the path the optimal route flew.
        assert_eq!(file.path, hop.path, "{what}: hop {}", file.hop_index);
        Ok(hop.transfers.iter().map(WrittenTransfer::from).collect())
    };
    let r = evaluate_route(
        context,
        request,
        Positioning::LocationAware,
        None,
        &stops,
        &mut schedule,
        true,
    )
    .unwrap();
    assert!(r.delivered, "{what}: {r:?}");
    assert_eq!(r.hops.len(), plan.hops.len(), "{what}");
    for (i, (got, hop)) in r.hops.iter().zip(&plan.hops).enumerate() {
        let w = format!("{what}: hop {i}");
        assert_close(got.tt_min, hop.tt_min, &format!("{w} tt"));
        assert_all_close(
            &got.evaluation.outcome.final_battery_mah,
            &hop.arrival_battery_mah,
            &format!("{w} arrival"),
        );
        match (&got.stop, &hop.stop) {
            (Some(a), Some(b)) => {
                assert_eq!(a.node, b.node, "{w}");
                assert_close(a.nt_min, b.nt_min, &format!("{w} nt"));
            }
            (a, b) => assert_eq!(a.is_some(), b.is_some(), "{w}: stops {a:?} {b:?}"),
        }
    }
    let dt = r.dt_min.unwrap();
    assert!(
        (dt - plan.dt_min).abs() <= 1e-6 * plan.dt_min,
        "{what}: dt {dt}, plan {}",
        plan.dt_min
    );
    r
}

#[test]
fn paper_195_plans_fed_back_keep_their_delivery_times_and_never_beat_the_joint_optimum() {
    let (network, graph, profile, requests) = paper_195();
    let context = Context::new(&network, &graph, &profile);
    let mut transfers = 0;
    let mut pb_above = 0;
    for id in PAPER_195_REQUESTS {
        let request = requests.iter().find(|r| r.id == id).unwrap();
        let pb = context.plan(request, &options(SharingPolicy::Pb)).unwrap();
        let joint = context
            .plan(request, &options(SharingPolicy::Exact))
            .unwrap();
        assert!(pb.plan.delivered() && joint.plan.delivered(), "{id}");
        transfers += pb
            .plan
            .hops
            .iter()
            .map(|h| h.transfers.len())
            .sum::<usize>();

        // PB's own route: its delivery time, at or above the joint optimum of the same swarm.
        let r = fed_back(&context, request, &pb.plan, &format!("{id} pb"));
        let reference = r.reference.unwrap();
        assert_close(
            reference.dt_min.unwrap(),
            joint.plan.dt_min,
            &format!("{id} reference"),
        );
        assert_eq!(r.support_drones, pb.support_drones, "{id}");
        assert_ne!(r.mode, Reorder::Free, "{id}");
        let gap = r.gap.and_then(|g| g.relative).expect("a gap");
        assert!(
            gap >= -1e-9,
            "{id}: PB route below the joint optimum, gap {gap}"
        );
        assert_close(
            gap,
            (pb.plan.dt_min - joint.plan.dt_min) / joint.plan.dt_min,
            &format!("{id} gap"),
        );
        pb_above += usize::from(gap > 1e-6);

        // The joint optimum's own route: gap 0.
        let r = fed_back(&context, request, &joint.plan, &format!("{id} joint"));
        let gap = r.gap.and_then(|g| g.relative).expect("a gap");
        assert!(gap.abs() <= 1e-6, "{id}: joint optimum fed back, gap {gap}");
    }
    // Not vacuous: PB's routes share, and the joint optimum beats some.
    assert!(
        transfers >= PAPER_195_REQUESTS.len(),
        "{transfers} transfers"
    );
    assert!(
        pb_above > 0,
        "PB reaches the joint optimum on every request"
    );
}

#[test]
fn written_transfers_round_trip_through_json() {
    // What the Python package writes: energy and slot may be left out; unknown fields rejected.
    let x: WrittenTransfer =
        serde_json::from_str(r#"{"support": 1, "consumer": 0, "start_min": 2, "end_min": 8}"#)
            .unwrap();
    assert_eq!(x, wt(1, 0, 2.0, 8.0));
    let t = x.complete(&two_drones());
    assert_close(t.energy_mah, 24.0, "energy filled in");
    assert_eq!(t.consumer_slot, 0);
    assert!(serde_json::from_str::<WrittenTransfer>(
        r#"{"support": 1, "consumer": 0, "start_min": 2, "end_min": 8, "slot": 0}"#
    )
    .is_err());
}

/// Found while writing these tests: without a reference `evaluate_hop` does not validate the
/// objective, so a pad rate that is not a positive number scores a node time of 0 (each charge
/// time `((C - b) / rate).max(0)` is 0 for a negative rate, and NaN.max(0) = 0 for NaN) instead
/// of the E4104 it gives with a reference (`validate_objective`, via the continuous model).
#[test]
fn an_invalid_pad_rate_is_an_error_with_or_without_a_reference() {
    let p = two_drones();
    for rate in [f64::NAN, -1.0] {
        let objective = Objective::NodeTime(EndPads {
            pads: 2,
            pad_rate_mah_per_min: rate,
        });
        for reference in [None, Some(default_reference())] {
            let v = violations(evaluate_hop(
                &p,
                &objective,
                &[wt(1, 0, 2.0, 8.0)],
                reference.as_ref(),
            ));
            assert!(v.iter().any(|x| x.code == "E4104"), "rate {rate}: {v:?}");
        }
    }
}

/// Drone 0 of the needy pair served on [0, 1.75), drone 1 on [1.75, 4): 17.5 and 22.5 mAh
/// shared, arrivals (by hand) 25 - 40 + 17.5 = 2.5 and 25 - 17.5 = 7.5 mAh (drone 1 falls until
/// served, then holds level), the support drone's deficit 40 mAh.
fn lopsided() -> [WrittenTransfer; 2] {
    [wt(2, 0, 0.0, 1.75), wt(2, 1, 1.75, 4.0)]
}

#[test]
fn a_loss_reads_as_a_positive_gap_whether_the_objective_is_maximised_or_minimised() {
    let max_min = known_optima()
        .instances
        .into_iter()
        .find(|k| k.name == "needy_pair_max_min")
        .expect("shipped");
    let p = max_min.problem;
    // Maximised (the lowest arrival, optimum 5 mAh by hand): (5 - 2.5) / 5 = +50 %.
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &lopsided(),
        Some(&default_reference()),
    )
    .unwrap();
    assert_all_close(&e.outcome.final_battery_mah, &[2.5, 7.5, 60.0], "final");
    assert_close(e.value.unwrap(), 2.5, "value");
    assert_close(e.reference.unwrap().value.unwrap(), 5.0, "optimum");
    assert_close(relative_gap(&e), 0.5, "maximised gap");
    // Minimised (node time on 3 pads at 1 mAh/min, optimum 95 min by hand): deficits 97.5,
    // 92.5 and 40, one drone per pad: 97.5 min, (97.5 - 95) / 95 = +2.63 %.
    let three_pads = Objective::NodeTime(EndPads {
        pads: 3,
        pad_rate_mah_per_min: 1.0,
    });
    let e = evaluate_hop(&p, &three_pads, &lopsided(), Some(&default_reference())).unwrap();
    assert_close(e.value.unwrap(), 97.5, "value");
    assert_close(e.reference.unwrap().value.unwrap(), 95.0, "optimum");
    assert_close(relative_gap(&e), 2.5 / 95.0, "minimised gap");
    // The optimum's own schedule: 0, printed without a sign.
    let best = [wt(2, 0, 0.0, 2.0), wt(2, 1, 2.0, 4.0)];
    let e = evaluate_hop(
        &p,
        &Objective::MaxMinArrival,
        &best,
        Some(&default_reference()),
    )
    .unwrap();
    assert_eq!(swarmplan::human::gap_percent(relative_gap(&e), 4), "0%");
}
