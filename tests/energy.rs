//! Energy model and formations: hand-computed rates and the paper's qualitative findings
//! (section 5.1, after Alkouz et al. 2020).

mod common;

use common::shipped_profile;
use nalgebra::Vector2;
use proptest::prelude::*;
use swarmplan::energy::{
    consumption_rates_mah_per_min, payload_factor, rate_matrix_mah_per_min, slot_factors,
    wind_factor,
};
use swarmplan::formation::slots_m;

use swarmplan::problem::validate::validate_profile;
use swarmplan::problem::{Drone, FormationKind, Profile, Role, Swarm, Wind};

fn paper() -> Profile {
    shipped_profile("paper")
}

/// Sum over the drones of the position factors of `kind` with `n` drones on a leg flown north.
fn total(p: &Profile, kind: FormationKind, n: usize, wind: &Wind) -> f64 {
    let slots = slots_m(kind, n, p.formation.spacing_m);
    slot_factors(p, &slots, 0.0, wind).iter().sum()
}

fn least(p: &Profile, n: usize, wind: &Wind) -> (FormationKind, Vec<(FormationKind, f64)>) {
    let all: Vec<(FormationKind, f64)> = FormationKind::ALL
        .iter()
        .map(|&k| (k, total(p, k, n, wind)))
        .collect();
    let best = all
        .iter()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|x| x.0)
        .unwrap();
    (best, all)
}

fn single_drone_swarm(payload_kg: f64) -> Swarm {
    Swarm {
        formation: FormationKind::Column,
        drones: vec![Drone {
            id: 0,
            role: Role::Delivery,
            payload_kg,
            capacity_mah: 4480.0,
        }],
        slots_m: vec![Vector2::new(0.0, 0.0)],
        initial_slot: vec![0],
    }
}

#[test]
fn shipped_profiles_validate() {
    for name in ["paper", "fast-sharing"] {
        let v = validate_profile(&shipped_profile(name));
        assert!(v.is_empty(), "{name}: {v:?}");
    }
}

#[test]
fn unloaded_and_full_payload_rates_in_still_air_match_hand_computation() {
    // Hand computation (paper profile):
    //   r0 = 4480 mAh / 23 min = 194.7826 mAh/min; one drone alone has position factor 1 and
    //   still air gives W = 0.9 + 0.1 * 1^3 = 1.
    //   1.4 kg: P = ((1.280 + 1.4) / 1.280)^1.5 = 2.09375^1.5 = 3.029614, rate = 590.116 mAh/min;
    //   flight time 4480 / 590.116 = 7.592 min, range 7.592 / 60 * 30 = 3.796 km.
    let p = paper();
    let calm = Wind::CALM;
    let r_empty = consumption_rates_mah_per_min(&p, &single_drone_swarm(0.0), 0.0, &calm)[0];
    let r_full = consumption_rates_mah_per_min(&p, &single_drone_swarm(1.4), 0.0, &calm)[0];
    assert!((r_empty - 194.7826).abs() < 1e-3, "{r_empty}");
    assert!((r_full - 590.116).abs() < 1e-3, "{r_full}");
    let range_full_km = p.drone.battery_mah / r_full / 60.0 * p.drone.speed_kmh;
    assert!((range_full_km - 3.796).abs() < 1e-3, "{range_full_km}");
    let range_empty_km = p.drone.battery_mah / r_empty / 60.0 * p.drone.speed_kmh;
    assert!((range_empty_km - 11.5).abs() < 1e-9, "{range_empty_km}");
}

#[test]
fn two_drone_column_in_head_wind_matches_hand_computation() {
    // Wake model reduced to drag shielding only: a_sh = 0.2, sigma_sh = 1 m, L_sh = 1 m, s0 = 0,
    // every other gain 0. Column of two, 1 m apart, flown north into a 5 m/s wind from the north.
    // Air relative to the swarm: (-(8.3333 + 5), 0), so drone 1 is s = 1 m straight behind drone 0.
    //   f_0 = 1 (nothing upstream), f_1 = 1 - 0.2 * exp(-1) = 0.9264241.
    //   W = 0.9 + 0.1 * (13.3333 / 8.3333)^3 = 0.9 + 0.1 * 1.6^3 = 1.3096.
    //   drone 1 with 1.4 kg: 194.7826 * 3.029614 * 1.3096 * 0.9264241 = 715.955 mAh/min;
    //   drone 0 unloaded:    194.7826 * 1 * 1.3096 * 1 = 255.087 mAh/min.
    let mut p = paper();
    let f = &mut p.formation;
    f.shield_gain = 0.2;
    f.shield_width_m = 1.0;
    f.shield_decay_m = 1.0;
    f.wake_onset_m = 0.0;
    f.downwash_gain = 0.0;
    f.upwash_gain = 0.0;
    f.abreast_gain = 0.0;
    let swarm = Swarm {
        formation: FormationKind::Column,
        drones: vec![
            Drone {
                id: 0,
                role: Role::Delivery,
                payload_kg: 0.0,
                capacity_mah: 4480.0,
            },
            Drone {
                id: 1,
                role: Role::Delivery,
                payload_kg: 1.4,
                capacity_mah: 4480.0,
            },
        ],
        slots_m: slots_m(FormationKind::Column, 2, 1.0),
        initial_slot: vec![0, 1],
    };
    let head = Wind {
        speed_mps: 5.0,
        from_deg: 0.0,
    };
    let rates = consumption_rates_mah_per_min(&p, &swarm, 0.0, &head);
    assert!((rates[0] - 255.087).abs() < 1e-3, "{rates:?}");
    assert!((rates[1] - 715.955).abs() < 1e-3, "{rates:?}");
    // The matrix gives the other pairings too: drone 1 in the lead slot pays 194.7826 * 3.029614 *
    // 1.3096 = 772.816 mAh/min.
    let m = rate_matrix_mah_per_min(&p, &swarm, 0.0, &head);
    assert!((m[1][0] - 772.816).abs() < 1e-3, "{m:?}");
}

#[test]
fn vee_is_the_least_energy_formation_in_a_head_wind() {
    let p = paper();
    for n in 4..=6 {
        for speed in [0.0, 2.0, 5.0, 8.0, 13.7] {
            let head = Wind {
                speed_mps: speed,
                from_deg: 0.0,
            };
            let (best, all) = least(&p, n, &head);
            assert_eq!(
                best,
                FormationKind::Vee,
                "n = {n}, head wind {speed} m/s: {all:?}"
            );
        }
    }
}

#[test]
fn diamond_is_the_least_energy_formation_in_a_side_wind() {
    let p = paper();
    for n in 4..=6 {
        for speed in [6.0, 8.0, 10.0, 12.0, 13.7] {
            for from_deg in [90.0, 270.0] {
                let side = Wind {
                    speed_mps: speed,
                    from_deg,
                };
                let (best, all) = least(&p, n, &side);
                assert_eq!(
                    best,
                    FormationKind::Diamond,
                    "n = {n}, side wind {speed} m/s from {from_deg}: {all:?}"
                );
            }
        }
    }
}

#[test]
fn the_vee_leader_pays_most_in_a_head_wind() {
    let p = paper();
    for n in 2..=9 {
        let slots = slots_m(FormationKind::Vee, n, 1.0);
        let f = slot_factors(
            &p,
            &slots,
            0.0,
            &Wind {
                speed_mps: 6.0,
                from_deg: 0.0,
            },
        );
        for (s, fs) in f.iter().enumerate().skip(1) {
            assert!(f[0] > *fs, "n = {n}: leader {} vs slot {s} {fs}", f[0]);
        }
    }
}

#[test]
fn head_wind_costs_more_and_tail_wind_less_than_still_air() {
    // Hand values: tail wind 5 m/s: W = 0.9 + 0.1 * (3.3333 / 8.3333)^3 = 0.9064;
    // side wind 10 m/s: W = 0.9 + 0.1 * (sqrt(8.3333^2 + 10^2) / 8.3333)^3 = 1.28114.
    let p = paper();
    let w = |speed: f64, from: f64| {
        wind_factor(
            &p,
            0.0,
            &Wind {
                speed_mps: speed,
                from_deg: from,
            },
        )
    };
    assert!((w(0.0, 0.0) - 1.0).abs() < 1e-12);
    assert!((w(5.0, 0.0) - 1.3096).abs() < 1e-9);
    assert!((w(5.0, 180.0) - 0.9064).abs() < 1e-9);
    assert!((w(10.0, 90.0) - 1.28114).abs() < 1e-5);
}

proptest! {
    #[test]
    fn consumption_rises_with_payload(a in 0.0f64..1.4, b in 0.0f64..1.4) {
        let p = paper();
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        prop_assume!(hi - lo > 1e-9);
        prop_assert!(payload_factor(&p, hi) > payload_factor(&p, lo));
        let calm = Wind::CALM;
        let r_lo = consumption_rates_mah_per_min(&p, &single_drone_swarm(lo), 0.0, &calm)[0];
        let r_hi = consumption_rates_mah_per_min(&p, &single_drone_swarm(hi), 0.0, &calm)[0];
        prop_assert!(r_hi > r_lo);
    }

    #[test]
    fn consumption_rises_with_head_wind(a in 0.0f64..13.8, b in 0.0f64..13.8, n in 1usize..8) {
        let p = paper();
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        prop_assume!(hi - lo > 1e-9);
        for kind in FormationKind::ALL {
            let slots = slots_m(kind, n, 1.0);
            let swarm = Swarm {
                formation: kind,
                drones: (0..n).map(|id| Drone { id, role: Role::Delivery, payload_kg: 0.5, capacity_mah: 4480.0 }).collect(),
                slots_m: slots,
                initial_slot: (0..n).collect(),
            };
            let (w_lo, w_hi) = (Wind { speed_mps: lo, from_deg: 0.0 }, Wind { speed_mps: hi, from_deg: 0.0 });
            let r_lo = consumption_rates_mah_per_min(&p, &swarm, 0.0, &w_lo);
            let r_hi = consumption_rates_mah_per_min(&p, &swarm, 0.0, &w_hi);
            for d in 0..n {
                prop_assert!(r_hi[d] > r_lo[d], "{:?} drone {}: {} vs {}", kind, d, r_hi[d], r_lo[d]);
            }
        }
    }

    #[test]
    fn every_rate_is_positive_and_finite_below_the_wind_limit(
        speed in 0.0f64..13.8, from in 0.0f64..360.0, heading in 0.0f64..360.0,
        n in 1usize..12, payload in 0.0f64..1.4,
    ) {
        let p = paper();
        let wind = Wind { speed_mps: speed, from_deg: from };
        prop_assert!(wind_factor(&p, heading, &wind) >= 0.9 - 1e-12);
        for kind in FormationKind::ALL {
            let swarm = Swarm {
                formation: kind,
                drones: (0..n).map(|id| Drone { id, role: Role::Delivery, payload_kg: payload, capacity_mah: 4480.0 }).collect(),
                slots_m: slots_m(kind, n, 1.0),
                initial_slot: (0..n).collect(),
            };
            for row in rate_matrix_mah_per_min(&p, &swarm, heading, &wind) {
                for r in row {
                    prop_assert!(r.is_finite() && r > 0.0);
                }
            }
        }
    }

    #[test]
    fn every_formation_has_n_distinct_slots_with_neighbours_one_spacing_apart(n in 2usize..40, spacing in 0.5f64..3.0) {
        for kind in FormationKind::ALL {
            let s = slots_m(kind, n, spacing);
            prop_assert_eq!(s.len(), n);
            let mut nearest = f64::INFINITY;
            for i in 0..n {
                let mut own = f64::INFINITY;
                for j in 0..n {
                    if i != j {
                        let d = (s[i] - s[j]).norm();
                        own = own.min(d);
                    }
                }
                // every drone has a neighbour exactly one spacing away, none closer
                prop_assert!((own - spacing).abs() < 1e-9, "{:?} n={} slot {} nearest {}", kind, n, i, own);
                nearest = nearest.min(own);
            }
            prop_assert!((nearest - spacing).abs() < 1e-9);
        }
    }
}

#[test]
fn five_drone_slots_match_the_drawn_formations() {
    // a = 1 / sqrt(2) = 0.70711 m for diagonal neighbours 1 m apart.
    let a = std::f64::consts::FRAC_1_SQRT_2;
    let pts = |k| {
        slots_m(k, 5, 1.0)
            .iter()
            .map(|v| (v.x, v.y))
            .collect::<Vec<_>>()
    };
    let close = |got: Vec<(f64, f64)>, want: Vec<(f64, f64)>| {
        assert_eq!(got.len(), want.len());
        for (g, w) in got.iter().zip(&want) {
            assert!(
                (g.0 - w.0).abs() < 1e-12 && (g.1 - w.1).abs() < 1e-12,
                "{got:?} vs {want:?}"
            );
        }
    };
    close(
        pts(FormationKind::Column),
        vec![
            (0.0, 0.0),
            (-1.0, 0.0),
            (-2.0, 0.0),
            (-3.0, 0.0),
            (-4.0, 0.0),
        ],
    );
    close(
        pts(FormationKind::Front),
        vec![(0.0, -2.0), (0.0, -1.0), (0.0, 0.0), (0.0, 1.0), (0.0, 2.0)],
    );
    close(
        pts(FormationKind::Vee),
        vec![
            (0.0, 0.0),
            (-a, -a),
            (-a, a),
            (-2.0 * a, -2.0 * a),
            (-2.0 * a, 2.0 * a),
        ],
    );
    // Diamond, 5 drones: the 3 x 3 diamond lattice's centre and its four lattice neighbours, i.e. a
    // front pair, the centre 1 m behind them diagonally, and a rear pair.
    close(pts(FormationKind::Diamond), diamond5(a));
    // Diamond, 4 drones: lead, two wings, tail.
    let four: Vec<(f64, f64)> = slots_m(FormationKind::Diamond, 4, 1.0)
        .iter()
        .map(|v| (v.x, v.y))
        .collect();
    close(four, vec![(0.0, 0.0), (-a, -a), (-a, a), (-2.0 * a, 0.0)]);
}

/// The 5-drone diamond: the 3 x 3 lattice's centre and its four neighbours, i.e. corners at
/// (-a, +-a), (-3a, +-a) around the centre (-2a, 0), shifted so the front pair is at x = 0.
fn diamond5(a: f64) -> Vec<(f64, f64)> {
    vec![
        (0.0, -a),
        (0.0, a),
        (-a, 0.0),
        (-2.0 * a, -a),
        (-2.0 * a, a),
    ]
}
