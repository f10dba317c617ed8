//! Edge sharing model: hand-computed cases for none, PB and FB, fixed re-ordering, the support
//! reserve, piecewise legs, and the independent checker.

mod common;

use common::{assert_close, close, drone, line, uniform_leg};
use nalgebra::Vector2;
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use swarmplan::check::check_hop;
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{
    battery_trace, simulate, simulate_with, HopOutcome, HopProblem, LegRates, PolicyOptions,
    SharingPolicy,
};
use swarmplan::problem::Role;
use swarmplan::problem::{PbRequest, Readings};

fn passes(p: &HopProblem, o: &HopOutcome) {
    let v = check_hop(p, o);
    assert!(v.is_empty(), "checker: {v:#?}");
}

/// d0 delivery (cap 200, 80 mAh, 10 mAh/min), d1 support (500 mAh, 5 mAh/min), 1 m apart,
/// tt = 10 min, rho = 4, gamma = 50, lambda = 20, delta = 100.
fn two_drones() -> HopProblem {
    let (slots_m, initial_slot) = line(&[0.0, 1.0]);
    HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 200.0, 80.0),
            drone(Role::Support, 500.0, 500.0),
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

#[test]
fn one_leg_two_drones_by_hand() {
    let p = two_drones();
    // None: d0 = 80 - 10 * 10 = -20, empty at t = 80 / 10 = 8 min.
    let none = simulate(&p, Heuristic::None).unwrap();
    assert!(!none.feasible);
    let f = none.failure.unwrap();
    assert_eq!(f.drone, 0);
    assert_close(f.time_min, 8.0, "failure time");
    assert_close(none.final_battery_mah[0], -20.0, "none d0");
    assert_close(none.final_battery_mah[1], 450.0, "none d1");
    passes(&p, &none);

    // PB: 80 - 10 t = 50 at st = 3; re = 200 - 50 = 150 -> 37.5 min at rho = 4, clipped at
    // tt = 10: transfer [3, 10], 4 * 7 = 28 mAh. d0 = 80 - 100 + 28 = 8; d1 = 500 - 50 - 28 = 422.
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.feasible);
    assert_eq!(pb.transfers.len(), 1);
    let x = pb.transfers[0];
    assert_eq!((x.support, x.consumer, x.consumer_slot), (1, 0, 0));
    assert_close(x.start_min, 3.0, "pb start");
    assert_close(x.end_min, 10.0, "pb end");
    assert_close(x.energy_mah, 28.0, "pb energy");
    assert_close(pb.final_battery_mah[0], 8.0, "pb d0");
    assert_close(pb.final_battery_mah[1], 422.0, "pb d1");
    assert_close(pb.min_battery_mah[0], 8.0, "pb d0 min");
    assert_close(pb.shared_mah, 28.0, "pb shared");
    passes(&p, &pb);

    // FB: lambda / rho = 5 min rounds to d0: [0, 5] and [5, 10], 40 mAh.
    // d0 = 80 - 100 + 40 = 20; d1 = 500 - 50 - 40 = 410.
    let fb = simulate(&p, Heuristic::Fb).unwrap();
    assert!(fb.feasible);
    assert_eq!(fb.transfers.len(), 2);
    assert_close(fb.transfers[0].end_min, 5.0, "fb round 1 end");
    assert_close(fb.transfers[1].start_min, 5.0, "fb round 2 start");
    assert_close(fb.final_battery_mah[0], 20.0, "fb d0");
    assert_close(fb.final_battery_mah[1], 410.0, "fb d1");
    passes(&p, &fb);
}

/// d0, d1 delivery (cap 400; 60 and 300 mAh; 12 mAh/min), d2 support (1000 mAh, 5 mAh/min) in the
/// middle slot; tt = 10, rho = 10, gamma = 150, lambda = 50, delta = 100.
fn needy_and_healthy() -> HopProblem {
    let (slots_m, _) = line(&[0.0, 1.0, 2.0]);
    HopProblem {
        legs: vec![uniform_leg(10.0, &[12.0, 12.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 400.0, 60.0),
            drone(Role::Delivery, 400.0, 300.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m,
        initial_slot: vec![0, 2, 1],
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 150.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    }
}

#[test]
fn fails_without_sharing_and_succeeds_with_pb() {
    let p = needy_and_healthy();
    // None: d0 = 60 - 120 = -60, empty at 60 / 12 = 5 min.
    let none = simulate(&p, Heuristic::None).unwrap();
    assert!(!none.feasible);
    assert_eq!(none.failure.unwrap().drone, 0);
    assert_close(none.failure.unwrap().time_min, 5.0, "none failure");
    // PB: d0 is below gamma at once: st = 0, re = 400 - 60 = 340 (34 min, clipped at 10):
    // 100 mAh, d0 = 60 - 120 + 100 = 40. d1 crosses gamma at (300 - 150) / 12 = 12.5 > tt: no
    // request, d1 = 300 - 120 = 180.
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.feasible);
    assert_eq!(pb.transfers.len(), 1);
    assert_eq!(pb.transfers[0].consumer, 0);
    assert_close(pb.final_battery_mah[0], 40.0, "pb d0");
    assert_close(pb.final_battery_mah[1], 180.0, "pb d1");
    passes(&p, &pb);
    passes(&p, &none);
}

#[test]
fn pb_serves_the_neediest_first_while_fb_spreads_and_the_needy_drone_fails() {
    let p = needy_and_healthy();
    // FB: rounds of 50 / 10 = 5 min, by id: d0 [0, 5], d1 [5, 10].
    // d0: 60 - (12 - 10) * 5 = 50 at t = 5, then -12/min: empty at 5 + 50 / 12 = 9.1667 min,
    // -10 at tt. d1: 300 - 120 + 50 = 230.
    let fb = simulate(&p, Heuristic::Fb).unwrap();
    assert!(!fb.feasible);
    let f = fb.failure.unwrap();
    assert_eq!(f.drone, 0);
    assert_close(f.time_min, 5.0 + 50.0 / 12.0, "fb failure time");
    assert_eq!(fb.transfers.len(), 2);
    assert_eq!((fb.transfers[0].consumer, fb.transfers[1].consumer), (0, 1));
    assert_close(fb.final_battery_mah[0], -10.0, "fb d0");
    assert_close(fb.final_battery_mah[1], 230.0, "fb d1");
    passes(&p, &fb);
    // PB (previous test): feasible with d0 = 40.
    assert!(simulate(&p, Heuristic::Pb).unwrap().feasible);
}

#[test]
fn out_of_range_consumer_swaps_next_to_the_support_drone_and_pays_that_slots_rate() {
    // Slots at x = 0, 2, 3 m; d0 (consumer) in slot 0 is 3 m from the support drone d2 in slot 2,
    // range 1.2: d0 swaps with d1 (slot 1, 1 m from the support drone).
    // rate[d][slot]: d0: 10 in slot 0, 20 in slot 1; d1: 6 in slot 0, 8 in slot 1; d2: 5.
    let (slots_m, initial_slot) = line(&[0.0, 2.0, 3.0]);
    let p = HopProblem {
        legs: vec![LegRates {
            duration_min: 10.0,
            rate_mah_per_min: vec![
                vec![10.0, 20.0, 99.0],
                vec![6.0, 8.0, 99.0],
                vec![99.0, 99.0, 5.0],
            ]
            .into(),
        }],
        drones: vec![
            drone(Role::Delivery, 400.0, 120.0),
            drone(Role::Delivery, 400.0, 300.0),
            drone(Role::Support, 500.0, 500.0),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 150.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    };
    // PB: d0 below gamma at once: st = 0, re = 280 (28 min, clipped): transfer [0, 10], 100 mAh,
    // d0 in slot 1. d0 = 120 - 20 * 10 + 100 = 20 (10 mAh/min in slot 0 would have given 20 + 100
    // = 120 more: 220); d1 in slot 0: 300 - 6 * 10 = 240; d2 = 500 - 50 - 100 = 350.
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.feasible);
    assert_eq!(pb.transfers.len(), 1);
    assert_eq!(pb.transfers[0].consumer_slot, 1);
    assert_close(pb.final_battery_mah[0], 20.0, "d0");
    assert_close(pb.final_battery_mah[1], 240.0, "d1");
    assert_close(pb.final_battery_mah[2], 350.0, "d2");
    passes(&p, &pb);
    // The same transfer without the swap is out of range (3 m > 1.2 m).
    let mut unswapped = pb.clone();
    unswapped.transfers[0].consumer_slot = 0;
    let codes: Vec<_> = check_hop(&p, &unswapped).iter().map(|v| v.code).collect();
    assert!(codes.contains(&"C3006"), "{codes:?}");
    // Without sharing nobody moves: d0 = 120 - 100 = 20, d1 = 300 - 80 = 220.
    let none = simulate(&p, Heuristic::None).unwrap();
    assert_close(none.final_battery_mah[0], 20.0, "none d0");
    assert_close(none.final_battery_mah[1], 220.0, "none d1");
}

#[test]
fn transfer_stops_when_the_consumer_is_full() {
    // d0: cap 100, 90 mAh, 2 mAh/min; support: 2000 mAh, 5 mAh/min; rho = 10, lambda = 50
    // (5 min rounds), tt = 10. FB round 1 at t = 0: +8 mAh/min, full at 10 / 8 = 1.25 min:
    // [0, 1.25], 12.5 mAh. At 1.25 d0 is full and consumes 2 < rho: skipped; nobody else to
    // serve, so the support drone waits one round, to 6.25, when d0 = 100 - 2 * 5 = 90: again
    // full after 1.25 min: [6.25, 7.5], 12.5 mAh. Then it waits to 12.5 > tt.
    // d0 at tt = 100 - 2 * 2.5 = 95.
    let (slots_m, initial_slot) = line(&[0.0, 1.0]);
    let p = HopProblem {
        legs: vec![uniform_leg(10.0, &[2.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 100.0, 90.0),
            drone(Role::Support, 2000.0, 2000.0),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 0.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    };
    let fb = simulate(&p, Heuristic::Fb).unwrap();
    assert_eq!(fb.transfers.len(), 2);
    assert_close(fb.transfers[0].end_min, 1.25, "first end");
    assert_close(fb.transfers[0].energy_mah, 12.5, "first energy");
    assert_close(fb.transfers[1].start_min, 6.25, "second start");
    assert_close(fb.transfers[1].end_min, 7.5, "second end");
    assert_close(fb.final_battery_mah[0], 95.0, "d0");
    assert!(fb.min_battery_mah[0] <= 100.0);
    passes(&p, &fb);
}

#[test]
fn support_reserve_delta_is_respected() {
    // Support: 200 mAh, 5 mAh/min over 10 min = 50 of its own, delta = 100: it may share
    // 200 - 50 - 100 = 50 mAh. d0: cap 400, 60 mAh, 10 mAh/min; rho = 10, lambda = 30 (3 min).
    let (slots_m, initial_slot) = line(&[0.0, 1.0]);
    let p = HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 400.0, 60.0),
            drone(Role::Support, 200.0, 200.0),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 100.0,
        lambda_mah: 30.0,
        delta_mah: 100.0,
    };
    // FB: [0, 3] 30 mAh, then [3, 5] stops at the budget (20 mAh). d0 = 60 - 100 + 50 = 10;
    // support = 200 - 50 - 50 = 100 = delta.
    let fb = simulate(&p, Heuristic::Fb).unwrap();
    assert!(fb.feasible);
    assert_eq!(fb.transfers.len(), 2);
    assert_close(fb.transfers[1].end_min, 5.0, "budget stop");
    assert_close(fb.shared_mah, 50.0, "shared");
    assert_close(fb.final_battery_mah[1], 100.0, "support at delta");
    assert_close(fb.final_battery_mah[0], 10.0, "d0");
    passes(&p, &fb);
    // PB: st = 0, re = 400 - 60 = 340 > 50 available: not served (Algorithm 2's er.re <= SD.ae).
    // d0 empties at 60 / 10 = 6 min.
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.transfers.is_empty());
    assert!(!pb.feasible);
    assert_close(pb.failure.unwrap().time_min, 6.0, "pb failure");
}

#[test]
fn piecewise_legs_change_the_rates() {
    // Leg 0: 5 min, d0 at 10 mAh/min; leg 1: 5 min, d0 at 20. d0: cap 300, 200 mAh.
    // No sharing: 150 at t = 5, 50 at t = 10.
    // PB, gamma = 120: 150 - 20 (t - 5) = 120 at st = 6.5; re = 300 - 120 = 180 (18 min at
    // rho = 10, clipped): [6.5, 10], 35 mAh; d0 = 50 + 35 = 85.
    let (slots_m, initial_slot) = line(&[0.0, 1.0]);
    let p = HopProblem {
        legs: vec![
            uniform_leg(5.0, &[10.0, 5.0]),
            uniform_leg(5.0, &[20.0, 5.0]),
        ],
        drones: vec![
            drone(Role::Delivery, 300.0, 200.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 120.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    };
    let none = simulate(&p, Heuristic::None).unwrap();
    assert_close(none.final_battery_mah[0], 50.0, "none d0");
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert_eq!(pb.transfers.len(), 1);
    assert_close(pb.transfers[0].start_min, 6.5, "pb start");
    assert_close(pb.transfers[0].energy_mah, 35.0, "pb energy");
    assert_close(pb.final_battery_mah[0], 85.0, "pb d0");
    passes(&p, &pb);
    let trace = battery_trace(&p, &pb.transfers).unwrap();
    let expect = [(0.0, 200.0), (5.0, 150.0), (6.5, 120.0), (10.0, 85.0)];
    for (t, b) in expect {
        let hit = trace
            .iter()
            .find(|(ti, _)| close(*ti, t))
            .unwrap_or_else(|| panic!("no breakpoint at {t}"));
        assert_close(hit.1[0], b, "trace d0");
    }
}

#[test]
fn pb_literal_reading_skips_a_request_that_starts_while_the_support_is_busy() {
    // d0 (slot 0): cap 150, 100 mAh; d1 (slot 2): cap 200, 130 mAh; both 10 mAh/min; support in
    // slot 1 between them; rho = 10, gamma = 120, tt = 10.
    // Requests: d0 st = 0, re = 50 -> [0, 5]; d1 st = 1 (130 - 10 = 120), re = 80.
    // After the first service d0 is at 100 at t = 5 (net 0), below gamma: new request st = 5,
    // re = 50.
    // Waiting reading: d1 (st 1) comes first and starts when the support is free: [5, 10];
    //   d0 = 100 - 50 = 50, d1 = 130 - 100 + 50 = 80.
    // Literal reading: d1's st = 1 < 5 is skipped; d0's st = 5 is served: [5, 10];
    //   d0 = 100, d1 = 130 - 100 = 30.
    let (slots_m, _) = line(&[0.0, 1.0, 2.0]);
    let p = HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 10.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 150.0, 100.0),
            drone(Role::Delivery, 200.0, 130.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m,
        initial_slot: vec![0, 2, 1],
        rho_mah_per_min: 10.0,
        range_m: 1.2,
        gamma_mah: 120.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    };
    let wait = simulate(&p, Heuristic::Pb).unwrap();
    assert_eq!(wait.transfers.len(), 2);
    assert_eq!(wait.transfers[1].consumer, 1);
    assert_close(wait.final_battery_mah[0], 50.0, "wait d0");
    assert_close(wait.final_battery_mah[1], 80.0, "wait d1");
    passes(&p, &wait);
    let literal = PolicyOptions {
        pb_wait_for_support: false,
        ..PolicyOptions::default()
    };
    let lit = simulate_with(&p, Heuristic::Pb, &literal).unwrap();
    assert_eq!(lit.transfers.len(), 2);
    assert_eq!(lit.transfers[1].consumer, 0);
    assert_close(lit.final_battery_mah[0], 100.0, "literal d0");
    assert_close(lit.final_battery_mah[1], 30.0, "literal d1");
    passes(&p, &lit);
}

#[test]
fn malformed_problems_are_invalid_input() {
    let mut p = two_drones();
    p.initial_slot = vec![0, 0];
    p.rho_mah_per_min = f64::NAN;
    std::sync::Arc::make_mut(&mut p.legs[0].rate_mah_per_min)[0].pop();
    let err = simulate(&p, Heuristic::Pb).unwrap_err();
    assert_eq!(err.exit_code(), 2);
    let swarmplan::error::Error::Invalid(v) = err else {
        panic!("expected Invalid")
    };
    let codes: Vec<&str> = v.iter().map(|x| x.code).collect();
    assert_eq!(codes, vec!["E4003", "E4006", "E4010"]);
}

#[test]
fn checker_rejects_corrupted_schedules() {
    let p = needy_and_healthy();
    let fb = simulate(&p, Heuristic::Fb).unwrap();
    passes(&p, &fb);
    let codes =
        |o: &HopOutcome| -> Vec<&'static str> { check_hop(&p, o).iter().map(|v| v.code).collect() };
    // One support drone giving to d0 on [0, 5] and to d1 from t = 4: overlap.
    let mut overlap = fb.clone();
    overlap.transfers[1].start_min = 4.0;
    overlap.transfers[1].energy_mah = 60.0;
    assert!(codes(&overlap).contains(&"C3008"), "{:?}", codes(&overlap));
    // Energy that is not rho x duration.
    let mut energy = fb.clone();
    energy.transfers[0].energy_mah += 1.0;
    assert!(codes(&energy).contains(&"C3005"));
    // A drone below zero reported as feasible (FB's d0 ends at -10).
    let mut below = fb.clone();
    below.feasible = true;
    below.failure = None;
    assert!(codes(&below).contains(&"C3014"));
    // Transfers removed but batteries kept: the re-integration disagrees.
    let mut dropped = fb.clone();
    dropped.transfers.clear();
    let c = codes(&dropped);
    assert!(c.contains(&"C3016") && c.contains(&"C3018"), "{c:?}");
    // A consumer moved into the support drone's own slot: nobody to swap with.
    let mut onto = fb.clone();
    onto.transfers[0].consumer_slot = 1;
    assert!(codes(&onto).contains(&"C3007"));
}

/// A random small hop from a seed.
fn random_problem(seed: u64) -> HopProblem {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let deliveries = rng.random_range(1..=4);
    let supports = rng.random_range(0..=2);
    let n = deliveries + supports;
    let mut cells: Vec<(i32, i32)> = (0..4).flat_map(|x| (0..3).map(move |y| (x, y))).collect();
    for i in (1..cells.len()).rev() {
        cells.swap(i, rng.random_range(0..=i));
    }
    let slots_m = cells[..n]
        .iter()
        .map(|&(x, y)| Vector2::new(x as f64, y as f64))
        .collect();
    let mut initial_slot: Vec<usize> = (0..n).collect();
    for i in (1..n).rev() {
        initial_slot.swap(i, rng.random_range(0..=i));
    }
    let legs: Vec<LegRates> = (0..rng.random_range(1..=3))
        .map(|_| LegRates {
            duration_min: if rng.random_bool(0.1) {
                0.0
            } else {
                rng.random_range(0.5..20.0)
            },
            rate_mah_per_min: (0..n)
                .map(|_| (0..n).map(|_| rng.random_range(0.0..30.0)).collect())
                .collect::<Vec<_>>()
                .into(),
        })
        .collect();
    let drones = (0..n)
        .map(|d| {
            let capacity_mah = rng.random_range(100.0..1000.0);
            let battery_mah = if rng.random_bool(0.3) {
                capacity_mah
            } else {
                rng.random_range(0.0..capacity_mah)
            };
            let role = if d < deliveries {
                Role::Delivery
            } else {
                Role::Support
            };
            drone(role, capacity_mah, battery_mah)
        })
        .collect();
    let rho_mah_per_min = rng.random_range(1.0..40.0);
    let range_m = rng.random_range(0.5..2.5);
    let gamma_mah = rng.random_range(0.0..600.0);
    // Within FB's work bound (`MAX_FB_ROUNDS` rounds per hop; beyond it FB refuses the hop with
    // E4015, tested on its own): at most 400 rounds of lambda.
    let tt_min: f64 = legs.iter().map(|l: &LegRates| l.duration_min).sum();
    let least_lambda_mah = tt_min * rho_mah_per_min * supports as f64 / 400.0;
    let lambda_mah = rng.random_range(5.0..200.0f64).max(least_lambda_mah);
    HopProblem {
        legs,
        drones,
        slots_m,
        initial_slot,
        rho_mah_per_min,
        range_m,
        gamma_mah,
        lambda_mah,
        delta_mah: rng.random_range(0.0..200.0),
    }
}

/// d0, d1 delivery (cap 200, 150 mAh), s2 support (500 mAh, 5 mAh/min), slots on a line at
/// x = 0, 1, 2 (drone d in slot d): d0 is 2 m from the support drone, out of range, and the only
/// in-range slot is d1's. d1 costs 30 mAh/min in d0's slot and 10 in its own; d0 10 everywhere.
/// tt = 10 min, rho = 4, gamma = 100, lambda = 40 (a round is the whole hop), delta = 100.
fn swap_partner_hop() -> HopProblem {
    let (slots_m, initial_slot) = line(&[0.0, 1.0, 2.0]);
    HopProblem {
        legs: vec![LegRates {
            duration_min: 10.0,
            rate_mah_per_min: vec![
                vec![10.0, 10.0, 10.0],
                vec![30.0, 10.0, 10.0],
                vec![5.0, 5.0, 5.0],
            ]
            .into(),
        }],
        drones: vec![
            drone(Role::Delivery, 200.0, 150.0),
            drone(Role::Delivery, 200.0, 150.0),
            drone(Role::Support, 500.0, 500.0),
        ],
        slots_m,
        initial_slot,
        rho_mah_per_min: 4.0,
        range_m: 1.2,
        gamma_mah: 100.0,
        lambda_mah: 40.0,
        delta_mah: 100.0,
    }
}

#[test]
fn a_transfer_that_would_take_its_swap_partner_below_zero_is_not_made() {
    // By hand. Without sharing both delivery drones end at 150 - 10 x 10 = 50: the hop is flyable.
    // Serving d0 swaps d1 into slot 0 (30 mAh/min), where it would end far below zero: FB's
    // round to d0 over [0, 10) gives 150 - 300 = -150, PB's request from t = 5 (b = gamma)
    // gives 100 - 30 x 5 = -50. Both are refused and d1, in range in its own slot, is served:
    // FB a round of lambda = 40 mAh over [0, 10) (d1 ends at 50 + 40 = 90); PB, with the request
    // sized to end the hop at gamma (re = 100 - 50 = 50), from t = 5 to the hop end: 4 x 5 = 20
    // mAh (d1 ends at 70).
    let p = swap_partner_hop();
    assert!(simulate(&p, Heuristic::None).unwrap().feasible);
    for (policy, energy, start, d1_final) in [
        (SharingPolicy::Fb, 40.0, 0.0, 90.0),
        (SharingPolicy::Pb, 20.0, 5.0, 70.0),
    ] {
        for o in [
            PolicyOptions::default(),
            PolicyOptions::from(&Readings::literal()),
        ] {
            let out = simulate_with(&p, policy.heuristic().unwrap(), &o).unwrap();
            // Literal PB fills (re = 200 - 100 = 100 for both): d0 first by id, refused; d1's
            // request also starts at 5 with the support drone free, clipped at 10: the same.
            let what = format!("{policy:?} {o:?}");
            assert!(out.feasible, "{what}: {out:?}");
            assert_eq!(out.transfers.len(), 1, "{what}");
            let x = &out.transfers[0];
            assert_eq!((x.consumer, x.consumer_slot), (1, 1), "{what}");
            assert_close(x.start_min, start, &what);
            assert_close(x.energy_mah, energy, &what);
            assert_close(out.final_battery_mah[0], 50.0, &what);
            assert_close(out.final_battery_mah[1], d1_final, &what);
            assert_close(out.final_battery_mah[2], 500.0 - 50.0 - energy, &what);
            passes(&p, &out);
        }
    }
}

#[test]
fn pb_requests_sized_to_the_hop_end_serve_the_needier_of_two_simultaneous_requests_first() {
    // By hand. d0 (10 mAh/min from 150) and d1 (20 mAh/min from 200) both reach gamma = 100 at
    // t = 5, and would end at 50 and 0. Sized to end the hop at gamma, d0 asks 50 and d1 100:
    // d1 is served first (re descending), [5, 10) at rho = 20 moves 100 mAh and holds d1 at 100;
    // d0's request then starts at 10 = tt and is dropped. Filling the battery, both ask
    // 200 - 100 = 100: the tie goes to d0 by id, which gains 10 mAh/min net to 150, and d1 ends at 0.
    let (slots_m, _) = line(&[0.0, 2.0, 1.0]);
    let p = HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 20.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 200.0, 150.0),
            drone(Role::Delivery, 200.0, 200.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m,
        initial_slot: vec![0, 1, 2],
        rho_mah_per_min: 20.0,
        range_m: 1.2,
        gamma_mah: 100.0,
        lambda_mah: 40.0,
        delta_mah: 0.0,
    };
    for (size, consumer, finals) in [
        (PbRequest::ToHopEnd, 1, [50.0, 100.0]),
        (PbRequest::Fill, 0, [150.0, 0.0]),
    ] {
        let o = PolicyOptions {
            pb_request: size,
            ..PolicyOptions::default()
        };
        let out = simulate_with(&p, Heuristic::Pb, &o).unwrap();
        let what = format!("{size:?}");
        assert_eq!(out.transfers.len(), 1, "{what}: {out:?}");
        assert_eq!(out.transfers[0].consumer, consumer, "{what}");
        assert_close(out.transfers[0].start_min, 5.0, &what);
        assert_close(out.transfers[0].energy_mah, 100.0, &what);
        assert_close(out.final_battery_mah[0], finals[0], &what);
        assert_close(out.final_battery_mah[1], finals[1], &what);
        assert_close(out.final_battery_mah[2], 1000.0 - 50.0 - 100.0, &what);
        passes(&p, &out);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn sharing_never_turns_a_hop_flyable_without_it_into_an_unflyable_one(seed in any::<u64>()) {
        let p = random_problem(seed);
        prop_assume!(simulate(&p, Heuristic::None).unwrap().feasible);
        let readings = [
            PolicyOptions::default(),
            PolicyOptions::from(&Readings::literal()),
            PolicyOptions { pb_request: PbRequest::Fill, ..PolicyOptions::default() },
        ];
        for policy in [SharingPolicy::IdleSupport, SharingPolicy::Pb, SharingPolicy::Fb] {
            for o in &readings {
                let out = simulate_with(&p, policy.heuristic().unwrap(), o).unwrap();
                prop_assert!(out.feasible, "{policy:?} {o:?}: {:?}\n{p:?}", out.failure);
            }
        }
    }


    #[test]
    fn every_policy_schedule_passes_the_checker(seed in any::<u64>()) {
        let p = random_problem(seed);
        let readings = [
            PolicyOptions::default(),
            PolicyOptions::from(&Readings::literal()),
        ];
        for policy in [SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb] {
            for o in &readings {
                let out = simulate_with(&p, policy.heuristic().unwrap(), o).unwrap();
                let v = check_hop(&p, &out);
                prop_assert!(v.is_empty(), "{policy:?} {o:?}: {v:#?}\n{p:?}\n{out:?}");
            }
        }
    }

    #[test]
    fn without_sharing_each_battery_ends_at_its_start_minus_its_consumption(seed in any::<u64>()) {
        let p = random_problem(seed);
        let o = simulate(&p, Heuristic::None).unwrap();
        for d in 0..p.drones.len() {
            let q = p.initial_slot[d];
            let used: f64 = p.legs.iter().map(|l| l.rate_mah_per_min[d][q] * l.duration_min).sum();
            let expect = p.drones[d].battery_mah - used;
            prop_assert!(close(o.final_battery_mah[d], expect), "{} vs {expect}", o.final_battery_mah[d]);
        }
        // Rates are >= 0, so the lowest battery is the final one.
        let all_reach = (0..p.drones.len()).all(|d| {
            let q = p.initial_slot[d];
            let used: f64 = p.legs.iter().map(|l| l.rate_mah_per_min[d][q] * l.duration_min).sum();
            p.drones[d].battery_mah - used >= -1e-6
        });
        prop_assert_eq!(o.feasible, all_reach);
    }

    #[test]
    fn pb_serves_a_drone_only_once_its_battery_is_at_or_below_gamma(seed in any::<u64>()) {
        let p = random_problem(seed);
        let o = simulate(&p, Heuristic::Pb).unwrap();
        let trace = battery_trace(&p, &o.transfers).unwrap();
        for x in &o.transfers {
            let b = trace.iter().rev().find(|(t, _)| *t <= x.start_min + 1e-9).unwrap().1[x.consumer];
            prop_assert!(b <= p.gamma_mah + 1e-6, "consumer {} at {b} > gamma {}", x.consumer, p.gamma_mah);
        }
    }

    #[test]
    fn fb_never_gives_more_than_lambda_in_one_round(seed in any::<u64>()) {
        let p = random_problem(seed);
        let o = simulate(&p, Heuristic::Fb).unwrap();
        for x in &o.transfers {
            prop_assert!(x.energy_mah <= p.lambda_mah * (1.0 + 1e-9));
        }
    }

    #[test]
    fn sharing_never_lowers_the_lowest_delivery_battery_of_a_single_drone_swarm(seed in any::<u64>()) {
        // With one delivery drone there is no swap partner, so sharing can only add energy.
        let mut p = random_problem(seed);
        let keep: Vec<usize> = (0..p.drones.len())
            .filter(|&d| d == 0 || p.drones[d].role == Role::Support)
            .collect();
        if keep.len() < 2 {
            return Ok(());
        }
        p.drones = keep.iter().map(|&d| p.drones[d]).collect();
        p.slots_m = keep.iter().map(|&d| p.slots_m[d]).collect();
        p.initial_slot = (0..keep.len()).collect();
        for leg in &mut p.legs {
            leg.rate_mah_per_min = keep
                .iter()
                .map(|&d| keep.iter().map(|&q| leg.rate_mah_per_min[d][q]).collect())
                .collect::<Vec<_>>()
                .into();
        }
        let none = simulate(&p, Heuristic::None).unwrap();
        for policy in [SharingPolicy::Pb, SharingPolicy::Fb] {
            let o = simulate(&p, policy.heuristic().unwrap()).unwrap();
            prop_assert!(o.final_battery_mah[0] >= none.final_battery_mah[0] - 1e-9);
            prop_assert!(o.min_battery_mah[0] >= none.min_battery_mah[0] - 1e-9);
        }
    }
}

#[test]
fn swap_slot_is_the_nearest_in_range_with_ties_to_the_lower_slot() {
    use swarmplan::eaas::reorder::choose_consumer_slot;
    // Support d0 in slot 0 at (0, 0); slots 1 at (1, 0) and 2 at (0, 1) are both 1 m away;
    // slot 3 at (0.5, 0.5) is 0.707 m away but held by a support drone; consumer d4 in slot 4 at
    // (3, 0). Range 1.2.
    let p = HopProblem {
        legs: vec![uniform_leg(1.0, &[1.0; 5])],
        drones: vec![
            drone(Role::Support, 100.0, 100.0),
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Delivery, 100.0, 100.0),
            drone(Role::Support, 100.0, 100.0),
            drone(Role::Delivery, 100.0, 50.0),
        ],
        slots_m: vec![
            Vector2::new(0.0, 0.0),
            Vector2::new(1.0, 0.0),
            Vector2::new(0.0, 1.0),
            Vector2::new(0.5, 0.5),
            Vector2::new(3.0, 0.0),
        ],
        initial_slot: vec![0, 1, 2, 3, 4],
        rho_mah_per_min: 1.0,
        range_m: 1.2,
        gamma_mah: 0.0,
        lambda_mah: 1.0,
        delta_mah: 0.0,
    };
    let free = vec![false; 5];
    assert_eq!(choose_consumer_slot(&p, 0, 4, &free), Some(1));
    let mut busy = free.clone();
    busy[1] = true;
    assert_eq!(choose_consumer_slot(&p, 0, 4, &busy), Some(2));
    busy[2] = true;
    assert_eq!(choose_consumer_slot(&p, 0, 4, &busy), None);
    // A consumer already within range stays put.
    assert_eq!(choose_consumer_slot(&p, 0, 1, &free), Some(1));
}

#[test]
fn problem_round_trips_through_json_with_slots_as_pairs() {
    let p = two_drones();
    let text = serde_json::to_string(&p).unwrap();
    assert!(text.contains("\"slots_m\":[[0.0,0.0],[1.0,0.0]]"), "{text}");
    let back: HopProblem = serde_json::from_str(&text).unwrap();
    assert_eq!(back, p);
    let policy: SharingPolicy = serde_json::from_str("\"fb\"").unwrap();
    assert_eq!(policy, SharingPolicy::Fb);
}

#[test]
fn pb_compares_the_energy_it_can_deliver_in_the_hop_with_the_budget() {
    // As `two_drones` with the support drone at 250 mAh: budget 250 - 5 * 10 - 100 = 100 mAh.
    // d0's request re = 150 exceeds it, but only 4 * (10 - 3) = 28 mAh fit before tt: served.
    let mut p = two_drones();
    p.drones[1].battery_mah = 250.0;
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert_eq!(pb.transfers.len(), 1);
    assert_close(pb.shared_mah, 28.0, "shared");
    assert_close(pb.final_battery_mah[1], 250.0 - 50.0 - 28.0, "support");
    // With a 20 mAh budget (support at 170) even the 28 mAh do not fit: no transfer, d0 fails.
    p.drones[1].battery_mah = 170.0;
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.transfers.is_empty());
    assert!(!pb.feasible);
}

#[test]
fn two_support_drones_serve_their_nearest_delivery_drones_at_the_same_time() {
    // Slots at x = 0, 1, 2, 3 m: d0 (delivery) in slot 0, support d2 in slot 1, support d3 in
    // slot 2, d1 (delivery) in slot 3. Nearest support: d0 -> d2 (1 m vs 2 m), d1 -> d3.
    // Deliveries: cap 400, 50 mAh, 10 mAh/min; supports 1000 mAh, 5 mAh/min; rho = 6, tt = 10,
    // gamma = 100. Both request at st = 0 (re = 350, 58.3 min, clipped): [0, 10] each, 60 mAh.
    // Each delivery drone ends at 50 - 100 + 60 = 10; without sharing both empty at t = 5.
    let (slots_m, _) = line(&[0.0, 1.0, 2.0, 3.0]);
    let p = HopProblem {
        legs: vec![uniform_leg(10.0, &[10.0, 10.0, 5.0, 5.0])],
        drones: vec![
            drone(Role::Delivery, 400.0, 50.0),
            drone(Role::Delivery, 400.0, 50.0),
            drone(Role::Support, 1000.0, 1000.0),
            drone(Role::Support, 1000.0, 1000.0),
        ],
        slots_m,
        initial_slot: vec![0, 3, 1, 2],
        rho_mah_per_min: 6.0,
        range_m: 1.2,
        gamma_mah: 100.0,
        lambda_mah: 50.0,
        delta_mah: 100.0,
    };
    assert_eq!(
        swarmplan::eaas::responsible_support(&p),
        vec![Some(2), Some(3), None, None]
    );
    let pb = simulate(&p, Heuristic::Pb).unwrap();
    assert!(pb.feasible);
    let pairs: Vec<(usize, usize)> = pb
        .transfers
        .iter()
        .map(|x| (x.support, x.consumer))
        .collect();
    assert_eq!(pairs, vec![(2, 0), (3, 1)]);
    for x in &pb.transfers {
        assert_close(x.start_min, 0.0, "start");
        assert_close(x.energy_mah, 60.0, "energy");
    }
    assert_close(pb.final_battery_mah[0], 10.0, "d0");
    assert_close(pb.final_battery_mah[1], 10.0, "d1");
    passes(&p, &pb);
    assert!(!simulate(&p, Heuristic::None).unwrap().feasible);
}

#[test]
fn fb_refuses_a_hop_over_its_work_bound_with_e4015_and_plans_one_within_it() {
    // tt = 10 min at rho = 4 mAh/min: 40 / lambda rounds for the one support drone.
    let mut p = two_drones();
    p.lambda_mah = 0.01; // 4,000 rounds: over MAX_FB_ROUNDS = 500
    let e = simulate(&p, Heuristic::Fb).unwrap_err().to_string();
    assert!(e.contains("[E4015] lambda_mah"), "{e}");
    assert!(
        e.contains("4000 rounds") && e.contains("at least 1 mAh"),
        "{e}"
    );
    // PB does not depend on lambda.
    assert!(simulate(&p, Heuristic::Pb).is_ok());
    p.lambda_mah = 0.1; // 400 rounds, within MAX_FB_ROUNDS
    const { assert!(400.0 <= swarmplan::eaas::MAX_FB_ROUNDS) };
    let o = simulate(&p, Heuristic::Fb).unwrap();
    passes(&p, &o);
}
