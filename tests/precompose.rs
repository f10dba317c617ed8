//! Pre-composition (paper 5.1): averaged wind, formation selection, support count (Eq. 1, Eq. 2,
//! Table 2), positioning; and profile validation.

mod common;

use common::{repo_path, shipped_profile};
use proptest::prelude::*;
use swarmplan::energy::slot_factors;
use swarmplan::precompose::{
    averaged_wind, build_swarm, select_formation, support_count, Positioning,
};
use swarmplan::problem::io::parse_toml;
use swarmplan::problem::validate::validate_profile;
use swarmplan::problem::FormationKind;
use swarmplan::problem::{Edge, Network, Node, Profile, RequestSet, Role, Wind};
use swarmplan::problem::{FailureModel, FailureTerms, FailureWeights, RedundancyLevel};

fn paper() -> Profile {
    shipped_profile("paper")
}

fn node(id: &str, x_m: f64, y_m: f64) -> Node {
    Node {
        id: id.into(),
        x_m,
        y_m,
        pads: 1,
        pad_charge_rate_mah_per_min: None,
    }
}

fn seg(from: &str, to: &str, wind_speed_mps: f64, wind_from_deg: f64) -> Edge {
    Edge {
        from: from.into(),
        to: to.into(),
        distance_m: None,
        wind_speed_mps,
        wind_from_deg,
    }
}

fn network(nodes: Vec<Node>, edges: Vec<Edge>) -> Network {
    Network {
        schema_version: 1,
        name: None,
        nodes,
        edges,
    }
}

#[test]
fn averaged_wind_is_the_mean_speed_and_the_most_frequent_direction_bin() {
    // Speeds 2, 4, 6, 8 -> mean 5. Directions with 45-degree bins centred on N, NE, ...:
    // 10 -> round(0.22) = 0; 350 -> round(7.78) = 8 = 0 (mod 8); 100 -> round(2.22) = 2; 5 -> 0.
    // Bin 0 (north) has 3 of 4: the averaged wind blows from 0 degrees.
    let p = paper();
    let net = network(
        vec![
            node("a", 0.0, 0.0),
            node("b", 100.0, 0.0),
            node("c", 0.0, 100.0),
        ],
        vec![
            seg("a", "b", 2.0, 10.0),
            seg("b", "c", 4.0, 350.0),
            seg("c", "a", 6.0, 100.0),
            seg("a", "c", 8.0, 5.0),
        ],
    );
    let w = averaged_wind(&net, &p);
    assert!((w.speed_mps - 5.0).abs() < 1e-12);
    assert_eq!(w.from_deg, 0.0);
}

#[test]
fn a_direction_tie_goes_to_the_lowest_bin() {
    // One wind from 180 (bin 4), one from 90 (bin 2): tie, bin 2 wins -> 90 degrees.
    let p = paper();
    let net = network(
        vec![node("a", 0.0, 0.0), node("b", 100.0, 0.0)],
        vec![seg("a", "b", 3.0, 180.0), seg("b", "a", 5.0, 90.0)],
    );
    let w = averaged_wind(&net, &p);
    assert_eq!(w.from_deg, 90.0);
    assert!((w.speed_mps - 4.0).abs() < 1e-12);
}

#[test]
fn a_north_south_network_with_a_north_wind_selects_vee() {
    // Flown north the wind is a head wind; flown south a 5 m/s tail wind is slower than the
    // 8.33 m/s cruise speed, so the air still meets the swarm head on: the paper's front-wind case.
    let p = paper();
    let net = network(
        vec![
            node("a", 0.0, 0.0),
            node("b", 0.0, 1000.0),
            node("c", 0.0, 2500.0),
        ],
        vec![seg("a", "b", 5.0, 0.0), seg("b", "c", 5.0, 0.0)],
    );
    let (kind, wind) = select_formation(&net, &p);
    assert_eq!(kind, FormationKind::Vee);
    assert_eq!(
        wind,
        Wind {
            speed_mps: 5.0,
            from_deg: 0.0
        }
    );
}

#[test]
fn an_east_west_network_with_a_north_wind_selects_diamond() {
    // Flown east or west, a 10 m/s north wind is a side wind: the paper's side-wind case.
    let p = paper();
    let net = network(
        vec![
            node("a", 0.0, 0.0),
            node("b", 1000.0, 0.0),
            node("c", 2500.0, 0.0),
        ],
        vec![seg("a", "b", 10.0, 0.0), seg("b", "c", 10.0, 0.0)],
    );
    assert_eq!(select_formation(&net, &p).0, FormationKind::Diamond);
}

#[test]
fn support_count_follows_eq_2_as_written_and_as_a_weighted_sum() {
    // Packages 1.0 and 2.0 kg: p1 = (1/5 + 2/5) / 2 = 0.3 (Eq. 1, normaliser 5 kg).
    // Distance 5750 m: p2 = 5750 / 11500 = 0.5. Capacity: p3 = 1 / (1 + 3) = 0.25.
    // Wind 6.9 m/s: p4 = 6.9 / 13.8 = 0.5.
    // Product, unit weights: P = 100 * 0.3 * 0.5 * 0.25 * 0.5 = 1.875 -> row 0 (0-19) -> N+1 -> 1.
    let mut p = paper();
    let wind = Wind {
        speed_mps: 6.9,
        from_deg: 0.0,
    };
    let d = support_count(&p, &[1.0, 2.0], 5750.0, &wind);
    for (got, want) in d.terms.iter().zip([0.3, 0.5, 0.25, 0.5]) {
        assert!((got - want).abs() < 1e-12, "{:?}", d.terms);
    }
    assert!((d.probability_pct - 1.875).abs() < 1e-9);
    assert_eq!((d.row, d.level, d.count), (0, RedundancyLevel::NPlus(1), 1));
    // Weighted sum, unit weights: P = 100 * (0.3 + 0.5 + 0.25 + 0.5) / 4 = 38.75 -> row 1 (20-39)
    // -> N+2 -> 2.
    p.failure.model = FailureModel::WeightedSum;
    let d = support_count(&p, &[1.0, 2.0], 5750.0, &wind);
    assert!((d.probability_pct - 38.75).abs() < 1e-9);
    assert_eq!((d.row, d.level, d.count), (1, RedundancyLevel::NPlus(2), 2));
    // Terms at their caps, capacity weight 0: P = 100 * (1 + 1 + 1) / 3 = 100 -> row 4 (80-100) -> 2N;
    // with 3 packages that is 3 support drones.
    p.failure.weights.capacity = 0.0;
    let storm = Wind {
        speed_mps: 13.7999,
        from_deg: 0.0,
    };
    let d = support_count(&p, &[9.0, 9.0, 9.0], 1e6, &storm);
    assert!(d.probability_pct > 99.99);
    assert_eq!((d.row, d.level, d.count), (4, RedundancyLevel::TwoN, 3));
}

/// The paper profile with Eq. 2 as a weighted sum of per-unit terms, weights `[w1, w2, w3, w4]`.
fn paper_per_unit_sum(weights: [f64; 4]) -> Profile {
    let mut p = paper();
    p.failure.terms = FailureTerms::PerUnit;
    p.failure.model = FailureModel::WeightedSum;
    let [payload, distance, capacity, wind] = weights;
    p.failure.weights = FailureWeights {
        payload,
        distance,
        capacity,
        wind,
    };
    p
}

#[test]
fn the_papers_worked_example_gives_0_3_for_5_km_at_30_kmh_and_3_percent_per_minute() {
    // Paper 5.1: "a swarm consumes 3% of its total power to travel for 1 minute at a speed of
    // 30 km/hr, hence w2 = 0.03. The distance ... is 5km. Therefore P_{i=2} = 0.03 * ((5/30)*60)
    // = 0.3". The paper profile flies at 30 km/h.
    let flight_min = (5.0 / 30.0) * 60.0; // 10 min
    let p2 = 0.03 * flight_min; // 0.3
    let p = paper_per_unit_sum([0.0, 0.03, 0.0, 0.0]);
    assert_eq!(p.drone.speed_kmh, 30.0);
    let d = support_count(&p, &[1.0, 2.0], 5000.0, &Wind::CALM);
    assert!((d.terms[1] - flight_min).abs() < 1e-12, "{:?}", d.terms);
    assert!(
        (d.weighted_terms[1] - p2).abs() < 1e-12,
        "{:?}",
        d.weighted_terms
    );
    // The distance term alone: P = 100 * 0.3 = 30 % -> row 1 (20-39) -> N+2.
    assert!((d.probability_pct - 100.0 * p2).abs() < 1e-9);
    assert_eq!((d.row, d.level, d.count), (1, RedundancyLevel::NPlus(2), 2));
}

#[test]
fn per_unit_terms_are_the_factors_in_their_own_units_for_the_product_and_the_sum() {
    // Packages 1.0 and 2.0 kg: p1 = D_pr = (1/5 + 2/5) / 2 = 0.3. 6 km at 30 km/h (500 m/min):
    // p2 = 12 min. p3 = C / E_c = 1 / (1 + 3) = 0.25. Wind 6.9 m/s: p4 = 6.9.
    // Weights 0.5, 0.04, 0.2, 0.01: q = 0.15, 0.48, 0.05, 0.069.
    // Weighted sum: P = 100 * (0.15 + 0.48 + 0.05 + 0.069) = 74.9 -> row 3 (60-79) -> N+4.
    // Product: P = 100 * 0.15 * 0.48 * 0.05 * 0.069 = 0.02484 -> row 0 -> N+1.
    let mut p = paper_per_unit_sum([0.5, 0.04, 0.2, 0.01]);
    let wind = Wind {
        speed_mps: 6.9,
        from_deg: 0.0,
    };
    let d = support_count(&p, &[1.0, 2.0], 6000.0, &wind);
    for (got, want) in d.terms.iter().zip([0.3, 12.0, 0.25, 6.9]) {
        assert!((got - want).abs() < 1e-12, "{:?}", d.terms);
    }
    for (got, want) in d.weighted_terms.iter().zip([0.15, 0.48, 0.05, 0.069]) {
        assert!((got - want).abs() < 1e-12, "{:?}", d.weighted_terms);
    }
    assert!(
        (d.probability_pct - 74.9).abs() < 1e-9,
        "{}",
        d.probability_pct
    );
    assert_eq!((d.row, d.level, d.count), (3, RedundancyLevel::NPlus(4), 4));
    p.failure.model = FailureModel::Product;
    let d = support_count(&p, &[1.0, 2.0], 6000.0, &wind);
    assert!(
        (d.probability_pct - 0.02484).abs() < 1e-12,
        "{}",
        d.probability_pct
    );
    assert_eq!((d.row, d.count), (0, 1));
    // Shares above a whole battery: 30 km is 60 min, q2 = 2.4, P is capped at 100 -> 2N.
    p.failure.model = FailureModel::WeightedSum;
    let d = support_count(&p, &[1.0, 2.0, 0.5], 30_000.0, &wind);
    assert_eq!(d.probability_pct, 100.0);
    assert_eq!((d.row, d.level, d.count), (4, RedundancyLevel::TwoN, 3));
    // An unreachable destination is certain failure; a zero weight drops even that term.
    let d = support_count(&p, &[1.0], f64::INFINITY, &wind);
    assert_eq!((d.probability_pct, d.row), (100.0, 4));
    p.failure.weights.distance = 0.0;
    let d = support_count(&p, &[1.0], f64::INFINITY, &wind);
    assert_eq!(d.weighted_terms[1], 0.0);
    assert!(d.probability_pct < 100.0);
}

#[test]
fn per_unit_weights_may_exceed_1_but_not_be_negative_and_normalised_ones_stay_in_0_1() {
    let mut p = paper();
    p.failure.weights.payload = 3.2;
    let v = validate_profile(&p);
    let codes: Vec<(&str, &str)> = v.iter().map(|x| (x.code, x.field.as_str())).collect();
    assert_eq!(codes, [("E2020", "failure.weights.payload")]);
    p.failure.terms = FailureTerms::PerUnit;
    assert!(validate_profile(&p).is_empty());
    p.failure.weights.wind = -0.001;
    p.failure.weights.capacity = f64::INFINITY;
    let v = validate_profile(&p);
    let codes: Vec<(&str, &str)> = v.iter().map(|x| (x.code, x.field.as_str())).collect();
    assert_eq!(
        codes,
        [
            ("E2022", "failure.weights.capacity"),
            ("E2022", "failure.weights.wind")
        ]
    );
    // A negative weight beside positive ones is not also "no positive weight" (E2021); all zero is.
    p.failure.model = FailureModel::WeightedSum;
    p.failure.weights.capacity = 0.1;
    let v = validate_profile(&p);
    let codes: Vec<(&str, &str)> = v.iter().map(|x| (x.code, x.field.as_str())).collect();
    assert_eq!(codes, [("E2022", "failure.weights.wind")]);
    p.failure.weights = FailureWeights {
        payload: 0.0,
        distance: 0.0,
        capacity: 0.0,
        wind: 0.0,
    };
    let v = validate_profile(&p);
    let codes: Vec<(&str, &str)> = v.iter().map(|x| (x.code, x.field.as_str())).collect();
    assert_eq!(codes, [("E2021", "failure.weights")]);
    // An unknown reading of the terms is a TOML error with its code.
    let text = std::fs::read_to_string(repo_path("instances/profiles/redundancy-levels.toml"))
        .unwrap()
        .replace("terms = \"per-unit\"", "terms = \"per-minute\"");
    let err = parse_toml::<Profile>(&text, "bad.toml").unwrap_err();
    assert_eq!(err.exit_code(), 2);
    assert!(err.to_string().contains("E0002"), "{err}");
}

/// Shortest distances from `source` over the network's edges (Euclidean lengths), by a plain
/// O(V^2) Dijkstra written for this test, independent of the crate's graph code.
fn test_dijkstra_m(net: &Network, source: usize) -> Vec<f64> {
    let n = net.nodes.len();
    let at = |id: &str| net.nodes.iter().position(|x| x.id == id).unwrap();
    let mut adj = vec![Vec::new(); n];
    for s in &net.edges {
        let (a, b) = (at(&s.from), at(&s.to));
        let len = s.distance_m.unwrap_or_else(|| {
            (net.nodes[a].x_m - net.nodes[b].x_m).hypot(net.nodes[a].y_m - net.nodes[b].y_m)
        });
        adj[a].push((b, len));
        adj[b].push((a, len));
    }
    let mut dist = vec![f64::INFINITY; n];
    let mut done = vec![false; n];
    dist[source] = 0.0;
    for _ in 0..n {
        let u = (0..n)
            .filter(|&u| !done[u])
            .min_by(|&a, &b| dist[a].total_cmp(&dist[b]))
            .unwrap();
        done[u] = true;
        for &(v, len) in &adj[u] {
            dist[v] = dist[v].min(dist[u] + len);
        }
    }
    dist
}

#[test]
fn every_row_of_table_2_is_reached_on_the_first_200_paper_195_requests_under_redundancy_levels() {
    // P recomputed here from the formula of instances/profiles/redundancy-levels.toml
    // (weighted sum of per-unit terms): P = 100 (0.3152 D_pr + 0.04348 d / 500 m/min
    // + 0.1099 / 4 + 0.0007599 W), W the mean edge wind speed, d by the Dijkstra above.
    // The expected counts [11, 55, 83, 37, 14] of 200 come from an independent Python script
    // (own JSON reading and Dijkstra); the closest P to a row boundary is 0.049 points away.
    let p = shipped_profile("redundancy-levels");
    assert!(validate_profile(&p).is_empty());
    let net: Network =
        swarmplan::problem::io::read_json(&repo_path("instances/paper-195/network.json"))
            .expect("network parses");
    let set: RequestSet =
        swarmplan::problem::io::read_json(&repo_path("instances/paper-195/requests.json"))
            .expect("requests parse");
    let w_mps = net.edges.iter().map(|s| s.wind_speed_mps).sum::<f64>() / net.edges.len() as f64;
    assert!((w_mps - 5.262).abs() < 5e-4, "{w_mps}");
    let graph = swarmplan::problem::SkywayGraph::new(&net).unwrap();
    let context = swarmplan::compose::Context::new(&net, &graph, &p);
    let at = |id: &str| net.nodes.iter().position(|x| x.id == id).unwrap();
    let mut counts = [0usize; 5];
    for (i, r) in set.requests.iter().take(200).enumerate() {
        let d_m = test_dijkstra_m(&net, at(&r.source))[at(&r.destination)];
        let d_pr = r.packages_kg.iter().map(|x| x / 5.0).sum::<f64>() / r.packages_kg.len() as f64;
        let share = 0.3152 * d_pr + 0.04348 * d_m / 500.0 + 0.1099 / 4.0 + 0.0007599 * w_mps;
        let want_pct = (100.0 * share).min(100.0);
        let want_row = [20.0, 40.0, 60.0, 80.0]
            .iter()
            .filter(|&&b| want_pct >= b)
            .count();
        if i == 0 {
            // r00000, n179 -> n049, packages 0.012 and 0.357 kg: the Python script's
            // d = 5920.22 m (11.8404 min), D_pr = 0.0369, P = 1.1631 + 51.4823 + 2.7475 + 0.3999
            // = 55.79 % -> row 2 (40-59) -> N+3.
            assert!((d_m - 5920.22).abs() < 0.01, "{d_m}");
            assert!((want_pct - 55.79).abs() < 0.01, "{want_pct}");
            assert_eq!(want_row, 2);
        }
        let got = context
            .swarm_for(r, Positioning::LocationAware, None)
            .unwrap()
            .support_decision;
        assert!(
            (got.probability_pct - want_pct).abs() < 1e-9,
            "{}: {} vs {want_pct}",
            r.id,
            got.probability_pct
        );
        assert_eq!(got.row, want_row, "{}", r.id);
        counts[want_row] += 1;
    }
    assert_eq!(counts, [11, 55, 83, 37, 14]);
}

#[test]
fn a_support_override_gives_that_many_support_drones_with_extra_batteries() {
    // 3 extra batteries of 0.365 kg = 1.095 kg payload, capacity 4 x 4480 = 17 920 mAh.
    let p = paper();
    let s = build_swarm(
        &p,
        FormationKind::Vee,
        &[0.5, 1.2],
        3,
        Positioning::LocationAware,
    );
    assert_eq!(s.drones.len(), 5);
    assert_eq!((s.delivery_count(), s.support_count()), (2, 3));
    for d in &s.drones[2..] {
        assert_eq!(d.role, Role::Support);
        assert!((d.payload_kg - 1.095).abs() < 1e-12);
        assert_eq!(d.capacity_mah, 17920.0);
    }
    assert_eq!(s.drones[1].payload_kg, 1.2);
}

#[test]
fn location_aware_puts_a_support_drone_in_the_vee_leader_slot_and_energy_aware_does_not() {
    // The Vee leader pays most in a head wind (tests/energy.rs), so the leader slot (0) is the worst:
    // location-aware gives it to a support drone; energy-aware gives it to the lightest delivery
    // drone (id 0, 0.5 kg).
    let p = paper();
    let pk = [0.5, 1.2, 0.8];
    let la = build_swarm(&p, FormationKind::Vee, &pk, 2, Positioning::LocationAware);
    let leader = (0..5).find(|&id| la.initial_slot[id] == 0).unwrap();
    assert_eq!(la.drones[leader].role, Role::Support);
    let ea = build_swarm(&p, FormationKind::Vee, &pk, 2, Positioning::EnergyAware);
    let leader = (0..5).find(|&id| ea.initial_slot[id] == 0).unwrap();
    assert_eq!(leader, 0);
}

fn arb_formation() -> impl Strategy<Value = FormationKind> {
    prop::sample::select(FormationKind::ALL.to_vec())
}

proptest! {
    #[test]
    fn positioning_assigns_every_slot_once_and_orders_drones_by_role_and_payload(
        kind in arb_formation(),
        packages in prop::collection::vec(0.0f64..1.4, 0..9),
        support in 0usize..5,
        energy_aware in any::<bool>(),
    ) {
        let p = paper();
        let pos = if energy_aware { Positioning::EnergyAware } else { Positioning::LocationAware };
        let s = build_swarm(&p, kind, &packages, support, pos);
        let n = packages.len() + support;
        prop_assert_eq!(s.slots_m.len(), n);
        let mut seen = vec![false; n];
        for &slot in &s.initial_slot {
            prop_assert!(slot < n && !seen[slot]);
            seen[slot] = true;
        }
        let f = slot_factors(&p, &s.slots_m, 0.0, &Wind::CALM);
        let fac = |id: usize| f[s.initial_slot[id]];
        let deliveries = 0..packages.len();
        let supports = packages.len()..n;
        for d in deliveries.clone() {
            for sp in supports.clone() {
                if energy_aware {
                    prop_assert!(fac(sp) <= fac(d) + 1e-12);
                } else {
                    prop_assert!(fac(sp) >= fac(d) - 1e-12);
                }
            }
            for e in deliveries.clone() {
                if packages[d] > packages[e] {
                    prop_assert!(fac(d) <= fac(e) + 1e-12, "heavier drone {} in a worse slot than {}", d, e);
                }
            }
        }
    }
}

#[test]
fn profile_validation_reports_every_violation_at_once() {
    let mut p = paper();
    p.schema_version = 9;
    p.drone.battery_mah = f64::NAN;
    p.drone.speed_kmh = -30.0;
    p.energy.parasitic_fraction = 1.5;
    p.failure.weights.wind = -0.1;
    p.redundancy.rows[2].from_pct = 10.0;
    let v = validate_profile(&p);
    let codes: Vec<(&str, &str)> = v.iter().map(|x| (x.code, x.field.as_str())).collect();
    for want in [
        ("E2001", "schema_version"),
        ("E2002", "drone.battery_mah"),
        ("E2002", "drone.speed_kmh"),
        ("E2004", "energy.parasitic_fraction"),
        ("E2020", "failure.weights.wind"),
        ("E2012", "redundancy.rows[2].from_pct"),
    ] {
        assert!(codes.contains(&want), "missing {want:?} in {codes:?}");
    }
    assert_eq!(v.len(), 6, "{codes:?}");
}

#[test]
fn too_many_extra_batteries_for_the_max_payload_is_a_violation() {
    // 4 x 0.365 = 1.46 kg > 1.4 kg.
    let mut p = paper();
    p.support.extra_batteries = 4;
    let v = validate_profile(&p);
    assert_eq!(v.len(), 1, "{v:?}");
    assert_eq!(
        (v[0].code, v[0].field.as_str()),
        ("E2007", "support.extra_batteries")
    );
}

#[test]
fn redundancy_levels_parse_from_the_paper_notation_and_bad_ones_are_coded_errors() {
    assert_eq!(
        RedundancyLevel::try_from("N+2".to_string()),
        Ok(RedundancyLevel::NPlus(2))
    );
    assert_eq!(
        RedundancyLevel::try_from("2N".to_string()),
        Ok(RedundancyLevel::TwoN)
    );
    assert_eq!(
        RedundancyLevel::try_from("2(N+1)".to_string()),
        Ok(RedundancyLevel::TwoNPlusOne)
    );
    assert_eq!(RedundancyLevel::TwoNPlusOne.support_drones(3), 5);
    let text = std::fs::read_to_string(repo_path("instances/profiles/paper.toml"))
        .unwrap()
        .replace("level = \"n+3\"", "level = \"n-3\"");
    let err = parse_toml::<Profile>(&text, "bad.toml").unwrap_err();
    assert_eq!(err.exit_code(), 2);
    assert!(err.to_string().contains("E0002"), "{err}");
}

#[test]
fn a_profile_without_the_model_sections_reads_with_the_paper_values() {
    let text = r#"
schema_version = 1
name = "minimal"
[drone]
battery_mah = 4480.0
voltage_v = 15.2
speed_kmh = 30.0
empty_mass_kg = 0.915
battery_mass_kg = 0.365
max_payload_kg = 1.4
[support]
extra_batteries = 3
[sharing]
rate_mah_per_min = 5.88
range_m = 1.2
lambda_mah = 2240.0
gamma_mah = 896.0
delta_mah = 3584.0
[pads]
charge_rate_mah_per_min = 74.67
"#;
    let p: Profile = parse_toml(text, "minimal.toml").unwrap();
    let paper = paper();
    assert_eq!(p.energy, paper.energy);
    assert_eq!(p.formation, paper.formation);
    assert_eq!(p.redundancy, paper.redundancy);
    assert_eq!(p.failure, paper.failure);
    assert!(validate_profile(&p).is_empty());
}
