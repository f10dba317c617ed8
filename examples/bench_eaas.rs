//! Time of one hop's sharing schedule per policy, at paper-like scale: 5 delivery and 2
//! support drones (4480 mAh), 1-4 legs of 1-10 min, rates 100-200 mAh/min, rho = 5.88 mAh/min,
//! lambda = 2240 mAh, range 1.2 m, 10,000 seeded random hops; each schedule also passes the
//! checker (checked outside the timing).
//!
//! `cargo run --release --example bench_eaas`

use nalgebra::Vector2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::time::Instant;
use swarmplan::check::check_hop;
use swarmplan::eaas::Heuristic;
use swarmplan::eaas::{simulate, DroneState, HopProblem, LegRates};
use swarmplan::problem::Role;

fn problem(rng: &mut ChaCha8Rng) -> HopProblem {
    let n: usize = 7;
    // Vee with 1 m spacing: apex, then pairs behind.
    let slots_m: Vec<Vector2<f64>> = (0..n)
        .map(|q| {
            let row = (q as u32).div_ceil(2) as f64;
            let side = if q % 2 == 1 { -1.0 } else { 1.0 };
            Vector2::new(-0.7 * row, side * 0.7 * row)
        })
        .collect();
    let legs = (0..rng.random_range(1..=4))
        .map(|_| LegRates {
            duration_min: rng.random_range(1.0..10.0),
            rate_mah_per_min: (0..n)
                .map(|_| (0..n).map(|_| rng.random_range(100.0..200.0)).collect())
                .collect::<Vec<_>>()
                .into(),
        })
        .collect();
    let drones = (0..n)
        .map(|d| DroneState {
            role: if d < 5 { Role::Delivery } else { Role::Support },
            capacity_mah: 4480.0,
            battery_mah: rng.random_range(1500.0..4480.0),
        })
        .collect();
    HopProblem {
        legs,
        drones,
        slots_m,
        initial_slot: vec![1, 2, 3, 4, 5, 0, 6],
        rho_mah_per_min: 5.88,
        range_m: 1.2,
        gamma_mah: 1344.0,
        lambda_mah: 2240.0,
        delta_mah: 500.0,
    }
}

fn main() {
    let count = 10_000;
    let mut rng = ChaCha8Rng::seed_from_u64(2024);
    let problems: Vec<HopProblem> = (0..count).map(|_| problem(&mut rng)).collect();
    for policy in [Heuristic::None, Heuristic::Pb, Heuristic::Fb] {
        let start = Instant::now();
        let outcomes: Vec<_> = problems
            .iter()
            .map(|p| simulate(p, policy).expect("valid problem"))
            .collect();
        let secs = start.elapsed().as_secs_f64();
        let feasible = outcomes.iter().filter(|o| o.feasible).count();
        let transfers: usize = outcomes.iter().map(|o| o.transfers.len()).sum();
        let bad = problems
            .iter()
            .zip(&outcomes)
            .filter(|(p, o)| !check_hop(p, o).is_empty())
            .count();
        println!(
            "{policy:?}: {secs:.3} s for {count} hops ({:.1} us each), feasible {feasible}/{count}, \
             transfers {transfers}, checker failures {bad}/{count}",
            1e6 * secs / count as f64
        );
    }
}
