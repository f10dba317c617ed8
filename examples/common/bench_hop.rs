//! The seeded random hops of the exact-hop benchmarks (`bench_eaas_exact`, `bench_eaas_continuous`):
//! `nd` delivery and `ns` support drones (capacity 100 mAh) on the library's Vee with 0.7 m
//! spacing (range 1.2 m), one leg of `periods` minutes, rates 2-6 mAh/min varying by slot,
//! rho = 8 mAh/min (both times 16 / periods beyond 16 periods), delivery batteries 30-100 mAh,
//! support drones full.

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use swarmplan::eaas::{DroneState, HopProblem, LegRates};
use swarmplan::formation::slots_m;
use swarmplan::problem::{FormationKind, Role};

/// One benchmark hop drawn from `rng`.
pub fn hop(rng: &mut ChaCha8Rng, nd: usize, ns: usize, periods: usize) -> HopProblem {
    let n = nd + ns;
    // Beyond 16 periods rates and rho shrink in proportion, so a hop uses the same share of a
    // battery whatever its length (otherwise long hops are infeasible for every schedule).
    let scale = 16.0 / (periods.max(16) as f64);
    let slots_m = slots_m(FormationKind::Vee, n, 0.7);
    // Support drones in the middle of the formation.
    let mut initial_slot: Vec<usize> = (0..n).collect();
    for s in 0..ns {
        initial_slot.swap(nd + s, s);
    }
    HopProblem {
        legs: vec![LegRates {
            duration_min: periods as f64,
            rate_mah_per_min: (0..n)
                .map(|_| (0..n).map(|_| scale * rng.random_range(2.0..6.0)).collect())
                .collect::<Vec<_>>()
                .into(),
        }],
        drones: (0..n)
            .map(|d| DroneState {
                role: if d < nd {
                    Role::Delivery
                } else {
                    Role::Support
                },
                capacity_mah: 100.0,
                battery_mah: if d < nd {
                    rng.random_range(30.0..100.0)
                } else {
                    100.0
                },
            })
            .collect(),
        slots_m,
        initial_slot,
        rho_mah_per_min: 8.0 * scale,
        range_m: 1.2,
        gamma_mah: 40.0,
        lambda_mah: 16.0,
        delta_mah: 5.0,
    }
}
