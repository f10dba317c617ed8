//! Route composition on tiny instances with hand-computed answers (issue 3, item 7).
//!
//! Every case uses the `flat` profile (instances/tiny/flat.toml) on windless networks, so the energy
//! is hand-computable (src/energy/mod.rs: rate = r0 * P(p) * W * F):
//! * r0 = battery_mah / endurance_min = 1000 / 10 = 100 mAh/min;
//! * P(p) = ((m0 + p) / m0)^1.5 with m0 = empty + battery = 0.56 + 0.44 = 1 kg:
//!   p = 0.21 -> 1.21^1.5 = 1.1^3 = 1.331 (133.1 mAh/min, 1000 mAh last 7.513 min = 3756.6 m),
//!   p = 0.44 -> 1.44^1.5 = 1.2^3 = 1.728 (172.8 mAh/min, 5.787 min = 2893.5 m)
//!   (requests need packages above 0 kg, rule E3302, so these are the light and the heavy one);
//! * a support drone carries 1 extra battery of 0.44 kg: 172.8 mAh/min, capacity 2000 mAh;
//! * W = 0.9 + 0.1 * (|v_air| / v)^3 = 1 without wind; F = 1 - (sum of gains) = 1, every gain 0;
//! * speed 30 km/h = 500 m/min, so tt = distance_m / 500;
//! * sharing rho = 120 mAh/min, gamma = 500, lambda = 1200 (an FB round lasts 10 min), delta = 50;
//! * pad rate 100 mAh/min: ct = (capacity - arrival) / 100.
//!
//! Every plan is also re-verified by the independent checker.

mod common;

use common::{assert_close, flat_instance};
use swarmplan::check::check_plan;
use swarmplan::compose::{Context, PlanOptions, PlanOutcome, RequestReport, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::Candidates;
use swarmplan::problem::SkywayGraph;
use swarmplan::problem::{Network, Profile, Request};

struct Tiny {
    network: Network,
    graph: SkywayGraph,
    profile: Profile,
}

fn tiny(file: &str) -> Tiny {
    let (network, graph, profile) = flat_instance(file);
    assert!(swarmplan::problem::validate::validate_profile(&profile).is_empty());
    Tiny {
        network,
        graph,
        profile,
    }
}

impl Tiny {
    /// Plans `from -> to` with `packages_kg` and `support` support drones, and checks the plan.
    fn plan(
        &self,
        from: &str,
        to: &str,
        packages_kg: &[f64],
        support: usize,
        sharing: SharingPolicy,
        route: RouteMethod,
    ) -> RequestReport {
        let request = Request {
            id: format!("{from}-{to}"),
            source: from.into(),
            destination: to.into(),
            packages_kg: packages_kg.to_vec(),
        };
        let invalid = swarmplan::problem::validate::validate_request(
            &request,
            0,
            &self.graph,
            self.profile.drone.max_payload_kg,
        );
        assert!(invalid.is_empty(), "the test request is valid: {invalid:?}");
        let options = PlanOptions {
            sharing,
            positioning: Positioning::LocationAware,
            route,
            support: Some(support),
        };
        let report = Context::new(&self.network, &self.graph, &self.profile)
            .plan(&request, &options)
            .unwrap();
        let v = check_plan(
            &self.network,
            &self.profile,
            &request,
            &report.swarm,
            sharing,
            &report.plan,
        );
        assert!(v.is_empty(), "{from}->{to} {options:?}: checker says {v:?}");
        report
    }
}

fn path_of(report: &RequestReport) -> Vec<String> {
    let mut nodes = vec![report.plan.source.clone()];
    for h in &report.plan.hops {
        nodes.extend(h.path[1..].iter().cloned());
    }
    nodes
}

#[test]
fn direct_reach_flies_straight_without_a_stop() {
    // flat-line A -> B = 2000 m: tt = 2000 / 500 = 4 min. One drone with 0.21 kg: 133.1 mAh/min,
    // 4 * 133.1 = 532.4 mAh used, arrives with 467.6 mAh. dt = tt = 4 min, no stop, no sharing.
    let t = tiny("flat-line.json");
    for route in RouteMethod::ALL {
        let r = t.plan("A", "B", &[0.21], 0, SharingPolicy::Pb, route);
        let p = &r.plan;
        assert!(p.delivered(), "{route:?}");
        assert_eq!(p.hops.len(), 1);
        assert!(p.hops[0].stop.is_none());
        assert_eq!(p.hops[0].path, ["A", "B"]);
        assert_close(p.dt_min, 4.0, "dt");
        assert_close(p.nt_min, 0.0, "nt");
        assert_close(p.hops[0].arrival_battery_mah[0], 467.6, "arrival");
        assert_eq!(p.shared_mah, 0.0);
        // +0.0, not -0.0 (which reports printed as "-0.0" before the fix in src/eaas/simulate.rs).
        assert!(p.hops[0].shared_mah.is_sign_positive() && p.hops[0].shared_mah == 0.0);
    }
}

#[test]
fn reach_only_thanks_to_sharing_fails_without_and_succeeds_with_pb() {
    // flat-line A -> D = 4000 m (A, B, C, D): tt = 8 min. One delivery drone with 0.21 kg
    // (133.1 mAh/min) needs 8 * 133.1 = 1064.8 > 1000 mAh: 64.8 mAh short, and no recharging
    // node is reachable other than the source A, so without sharing the request fails.
    let t = tiny("flat-line.json");
    let none = t.plan(
        "A",
        "D",
        &[0.21],
        1,
        SharingPolicy::None,
        RouteMethod::Sequential,
    );
    assert!(!none.plan.delivered());
    assert!(
        matches!(none.plan.outcome, PlanOutcome::DeadEnd { .. }),
        "{:?}",
        none.plan.outcome
    );
    assert!(none.plan.hops.is_empty());

    // PB. Support drone: 8 * 172.8 = 1382.4 mAh of its own, spare B = 2000 - 1382.4 - 50 =
    // 567.6 mAh. The delivery drone falls below gamma = 500 at st = 500 / 133.1 = 3.75657 min,
    // requests 1000 - 500 = 500 mAh = 500 / 120 = 4.16667 min, served in [3.75657, 7.92324)
    // (500 <= 567.6); it ends at 500 - (133.1 - 120) * 4.16667 = 445.42 < gamma, so a new request
    // starts at once and is clipped at tt = 8 (120 * 0.07676 = 9.21 mAh <= 67.6 left). Sharing runs
    // without a gap from st to tt: 120 * (8 - 500 / 133.1) = 960 - 450.78888 = 509.21112 mAh.
    // Arrival: 1000 - 1064.8 + 509.21112 = 444.41112; support 2000 - 1382.4 - 509.21112 =
    // 108.38888 (>= delta). dt = 8 min, no stop.
    let shared = 120.0 * (8.0 - 500.0 / 133.1);
    assert_close(shared, 509.211119, "hand arithmetic");
    let pb = t.plan(
        "A",
        "D",
        &[0.21],
        1,
        SharingPolicy::Pb,
        RouteMethod::Sequential,
    );
    let p = &pb.plan;
    assert!(p.delivered(), "{:?}", p.outcome);
    assert_eq!(p.hops.len(), 1);
    assert_eq!(p.hops[0].path, ["A", "B", "C", "D"]);
    assert_close(p.dt_min, 8.0, "dt");
    assert_close(p.shared_mah, shared, "shared");
    assert_close(
        p.hops[0].transfers[0].start_min,
        500.0 / 133.1,
        "first transfer start",
    );
    assert_close(
        p.hops[0].arrival_battery_mah[0],
        1000.0 - 1064.8 + shared,
        "delivery",
    );
    assert_close(
        p.hops[0].arrival_battery_mah[1],
        2000.0 - 1382.4 - shared,
        "support",
    );
}

#[test]
fn a_stop_with_fewer_pads_than_drones_takes_the_optimal_makespan() {
    // flat-stop A - M - B, 2500 m each (5 min), M has 2 pads. Three delivery drones 0.21, 0.21,
    // 0.44 kg: 133.1, 133.1, 172.8 mAh/min. Direct A -> B is 10 min: 1331 > 1000 mAh, impossible.
    // At M they arrive with 1000 - 665.5 = 334.5, 334.5, 1000 - 864 = 136 mAh: ct = 6.655, 6.655,
    // 8.64 min. Two pads: {6.655, 6.655} | {8.64} gives 13.31; {6.655, 8.64} | {6.655} gives
    // 15.295: nt = 13.31 (above the bound max(8.64, 21.95 / 2) = 10.975, so it is the exact
    // makespan, not the bound). From M (full) to B: 5 min. dt = 5 + 13.31 + 5 = 23.31.
    let t = tiny("flat-stop.json");
    for route in RouteMethod::ALL {
        let r = t.plan("A", "B", &[0.21, 0.21, 0.44], 0, SharingPolicy::None, route);
        let p = &r.plan;
        assert!(p.delivered(), "{route:?}: {:?}", p.outcome);
        assert_eq!(p.stops(), ["M"], "{route:?}");
        let stop = p.hops[0].stop.as_ref().unwrap();
        assert_eq!(stop.pads, 2);
        for (ct, want) in stop.charge_times_min.iter().zip([6.655, 6.655, 8.64]) {
            assert_close(*ct, want, "ct");
        }
        assert_close(stop.nt_min, 13.31, "nt");
        let mut pads: Vec<Vec<usize>> = stop
            .assignment
            .iter()
            .map(|p| {
                let mut p = p.clone();
                p.sort();
                p
            })
            .collect();
        pads.sort();
        assert_eq!(pads, vec![vec![0, 1], vec![2]]);
        assert_close(p.tt_min, 10.0, "tt");
        assert_close(p.dt_min, 23.31, "dt");
    }
}

#[test]
fn a_dead_end_fails_with_a_reason_and_never_loops() {
    // flat-deadend A - M1 (2000 m) - M2 (4000 m) - B (11000 m); M1 and M2 have one pad. One drone
    // with 0.21 kg, 133.1 mAh/min: at most 7.513 min = 3756.6 m without stopping.
    // From A: B is 22 min away, M2 8 min (1064.8 mAh: too far). Only candidate M1: tt 4, arrival
    // 1000 - 532.4 = 467.6, nt = ct = 532.4 / 100 = 5.324: stop at M1. From M1: B 18 min away;
    // M2 (4 + 5.324): stop at M2. From M2: B is 14 min away, M1 was stopped at already: dead end
    // at M2. Without the stopped-at rule M1 and M2 would alternate forever.
    // Flown: 2 * (4 + 5.324) = 18.648 min.
    let t = tiny("flat-deadend.json");
    for route in [RouteMethod::Sequential, RouteMethod::Astar] {
        let r = t.plan("A", "B", &[0.21], 0, SharingPolicy::None, route);
        let p = &r.plan;
        assert!(!p.delivered());
        assert_eq!(p.stops(), ["M1", "M2"], "{route:?}");
        let PlanOutcome::DeadEnd { node, direct, .. } = &p.outcome else {
            panic!("{:?}", p.outcome);
        };
        assert_eq!(node, "M2");
        assert!(
            p.outcome.to_string().contains("dead end at M2"),
            "{}",
            p.outcome
        );
        // Flying on from M2 full, the drone is empty after 1000 / 133.1 = 7.513 min.
        assert_eq!(direct.drone, 0);
        assert_close(direct.time_min, 1000.0 / 133.1, "direct failure");
        assert_close(p.dt_min, 18.648, "dt flown");
    }
    // The fixed route A, M1, M2, B (the only one): the farthest reachable pad node from A is M1,
    // from M1 it is M2; B is 14 min from M2: fails, naming B, after the same 18.648 min.
    for route in [RouteMethod::Dijkstra, RouteMethod::FloydWarshall] {
        let r = t.plan("A", "B", &[0.21], 0, SharingPolicy::None, route);
        let p = &r.plan;
        assert!(!p.delivered());
        assert_eq!(p.stops(), ["M1", "M2"], "{route:?}");
        let PlanOutcome::HopInfeasible { from, to, failure } = &p.outcome else {
            panic!("{:?}", p.outcome);
        };
        assert_eq!((from.as_str(), to.as_str()), ("M2", "B"));
        assert!(
            p.outcome.to_string().contains("cannot reach B"),
            "{}",
            p.outcome
        );
        assert_eq!(failure.drone, 0);
        assert_close(failure.time_min, 1000.0 / 133.1, "hop failure");
        assert_close(p.dt_min, 18.648, "dt flown");
    }
}

#[test]
fn pb_serves_the_needy_drone_where_fb_spreads_by_id_and_fails() {
    // flat-line A -> C = 3250 m, tt = 6.5 min. Drone 0 carries 0.21 kg (133.1 mAh/min, uses
    // 865.15), drone 1 0.44 kg (172.8, uses 1123.2: 123.2 short, empty at 1000 / 172.8 =
    // 5.787 min), drone 2 the support (172.8, uses 1123.2; spare 2000 - 1123.2 - 50 = 826.8).
    // Paper: PB serves by need, FB by turn. FB: drone 0 first, a round of 1200 mAh lasts 10 min >
    // tt, so it gets [0, 6.5) = 780 mAh and drone 1 nothing: drone 1 runs dry, no recharging node
    // is reachable: the request fails. PB: drone 1 falls below gamma first (500 / 172.8 = 2.8935
    // min, drone 0 at 500 / 133.1 = 3.7566), served [2.8935, 6.5): 120 * (6.5 - 2.8935) = 432.778
    // mAh; drone 0's request would start when the support drone is free, at tt: none. Arrivals:
    // drone 0: 1000 - 865.15 = 134.85; drone 1: 1000 - 1123.2 + 432.778 = 309.578; support
    // 2000 - 1123.2 - 432.778 = 444.022.
    let t = tiny("flat-line.json");
    let fb = t.plan(
        "A",
        "C",
        &[0.21, 0.44],
        1,
        SharingPolicy::Fb,
        RouteMethod::Sequential,
    );
    assert!(!fb.plan.delivered());
    assert!(matches!(fb.plan.outcome, PlanOutcome::DeadEnd { .. }));

    let pb = t.plan(
        "A",
        "C",
        &[0.21, 0.44],
        1,
        SharingPolicy::Pb,
        RouteMethod::Sequential,
    );
    let p = &pb.plan;
    assert!(p.delivered(), "{:?}", p.outcome);
    assert_close(p.dt_min, 6.5, "dt");
    let h = &p.hops[0];
    assert_eq!(h.transfers.len(), 1);
    assert_eq!((h.transfers[0].support, h.transfers[0].consumer), (2, 1));
    let given = 120.0 * (6.5 - 500.0 / 172.8);
    assert_close(given, 432.777778, "hand arithmetic");
    assert_close(h.transfers[0].energy_mah, given, "PB transfer");
    assert_close(h.arrival_battery_mah[0], 134.85, "drone 0");
    assert_close(h.arrival_battery_mah[1], 1000.0 - 1123.2 + given, "drone 1");
    assert_close(h.arrival_battery_mah[2], 2000.0 - 1123.2 - given, "support");
}

#[test]
fn each_route_method_takes_its_own_route() {
    // flat-routes: S - W 1000 m (west); S - P1 - P2 - T, 1900 m each (the shortest S -> T, 5700 m);
    // S - R - T, 3000 m each. W, P1, P2, R have one pad; S and T none. One drone with 0.21 kg:
    // 133.1 mAh/min, at most 7.513 min without stopping. A hop of tt min from full then a stop
    // costs tt + nt = tt + 133.1 tt / 100 = 2.331 tt. Direct S -> T (11.4 min) is impossible, and
    // so is any hop of 7.6 min (P1 -> T, S -> P2: 1011.56 mAh) or more.
    let t = tiny("flat-routes.json");
    let plan = |route| t.plan("S", "T", &[0.21], 0, SharingPolicy::None, route);

    // Sequential, candidates by tt + nt: from S, W 2 * 2.331 = 4.662, P1 3.8 * 2.331 = 8.8578,
    // R 6 * 2.331 = 13.986 (P2 too far): stop at W. From W: P1 via S 2900 m, 5.8 * 2.331 =
    // 13.5198 (R and P2 too far): stop at P1. From P1: T too far, P2 8.8578: stop at P2, then T
    // (3.8). dt = 4.662 + 13.5198 + 8.8578 + 3.8 = 30.8396.
    let seq = plan(RouteMethod::Sequential);
    assert!(seq.plan.delivered());
    assert_eq!(seq.plan.stops(), ["W", "P1", "P2"]);
    assert_eq!(path_of(&seq), ["S", "W", "S", "P1", "P2", "T"]);
    assert_close(seq.plan.dt_min, 30.8396, "sequential dt");

    // A*: plus h(v) = dist(v, T) / 500: W 4.662 + 13.4 = 18.062, P1 8.8578 + 7.6 = 16.4578,
    // R 13.986 + 6 = 19.986: stop at P1; from P1, P2 8.8578 + 3.8: stop at P2; then T.
    // dt = 2 * 8.8578 + 3.8 = 21.5156.
    let astar = plan(RouteMethod::Astar);
    assert!(astar.plan.delivered());
    assert_eq!(astar.plan.stops(), ["P1", "P2"]);
    assert_eq!(path_of(&astar), ["S", "P1", "P2", "T"]);
    assert_close(astar.plan.dt_min, 21.5156, "astar dt");

    // Dijkstra on c(u, v) = tt(u, v) + nt(v), nt(v) = 1.331 tt(u, v) at a pad node (one edge
    // from full), 0 at T: S-P1-P2-T costs 8.8578 + 8.8578 + 3.8 = 21.5156, S-R-T 13.986 + 6 =
    // 19.986: route S, R, T. Flown: T is 12 min away, R 6: stop at R (nt 7.986), then 6 to T.
    // dt = 19.986.
    let dijkstra = plan(RouteMethod::Dijkstra);
    assert!(dijkstra.plan.delivered());
    assert_eq!(dijkstra.plan.stops(), ["R"]);
    assert_eq!(path_of(&dijkstra), ["S", "R", "T"]);
    assert_close(dijkstra.plan.dt_min, 19.986, "dijkstra dt");

    // Floyd–Warshall minimises the same edge cost c(u, v) as Dijkstra, so its route costs the
    // same; here the cheapest route is unique, so it is the same route with the same dt.
    let fw = plan(RouteMethod::FloydWarshall);
    assert!(fw.plan.delivered());
    assert_eq!(path_of(&fw), ["S", "R", "T"]);
    assert_close(fw.plan.dt_min, 19.986, "floyd-warshall dt");
}

#[test]
fn algorithm_1_over_adjacent_nodes_passes_nodes_without_pads_and_never_revisits() {
    // The literal reading of Algorithm 1's candidates ("nearest neighbor nodes"), on flat-routes
    // (numbers as in the test above: one 0.21 kg drone, a hop of tt min from full then a stop
    // costs 2.331 tt, at most 3756.6 m without stopping).
    let mut t = tiny("flat-routes.json");
    t.profile.readings.candidates = Candidates::Adjacent;
    let plan = |from, route| t.plan(from, "T", &[0.21], 0, SharingPolicy::None, route);

    // Sequential from S: neighbours W 4.662, P1 8.8578, R 13.986: stop at W. W's only neighbour,
    // S, is visited, and T (6700 m via S) is out of reach: dead end after 4.662 min.
    let seq = plan("S", RouteMethod::Sequential);
    assert!(!seq.plan.delivered());
    assert!(matches!(
        &seq.plan.outcome,
        PlanOutcome::DeadEnd { node, candidates: Candidates::Adjacent, .. } if node == "W"
    ));
    assert_eq!(seq.plan.stops(), ["W"]);
    assert_close(seq.plan.dt_min, 4.662, "sequential dt");

    // A* adds dist(v, T) / 500: W 18.062, P1 16.4578, R 19.986: stop at P1, then P2 (its only
    // unvisited neighbour), then T: dt = 2 x 8.8578 + 3.8 = 21.5156, as over pad nodes.
    let astar = plan("S", RouteMethod::Astar);
    assert!(astar.plan.delivered());
    assert_eq!(path_of(&astar), ["S", "P1", "P2", "T"]);
    assert_close(astar.plan.dt_min, 21.5156, "astar dt");

    // From W: T is out of reach (6700 m); the only neighbour S has no pads, tt 2, nt 0: passed
    // without charging. From S the hop W-S-P1 (2900 m, 5.8 min) is flyable, W-S-R (4000 m) is
    // not: P1 with arrival 1000 - 133.1 x 5.8 = 228.02 mAh, nt = 7.7198. Then P2 (nt 5.0578)
    // and T. dt = 5.8 + 7.7198 + 3.8 + 5.0578 + 3.8 = 26.1776.
    let passing = plan("W", RouteMethod::Sequential);
    assert!(passing.plan.delivered());
    assert_eq!(passing.plan.stops(), ["P1", "P2"]);
    assert_eq!(passing.plan.hops[0].path, ["W", "S", "P1"]);
    assert_close(passing.plan.dt_min, 26.1776, "dt through S");
}

#[test]
fn the_no_sharing_baseline_flies_no_support_drone_and_idle_support_pays_for_charging_them() {
    // flat-stop as above: without support drones nt = 13.31 and dt = 23.31, even when one support
    // drone is asked for (`none` is the paper's baseline, the swarm without support drones). With
    // one idle support drone (172.8 mAh/min, 2000 mAh) it arrives at M with 2000 - 864 = 1136 mAh,
    // ct = 8.64: jobs 6.655, 6.655, 8.64, 8.64 on 2 pads, nt = 6.655 + 8.64 = 15.295, and
    // dt = 5 + 15.295 + 5 = 25.295.
    let t = tiny("flat-stop.json");
    let none = t.plan(
        "A",
        "B",
        &[0.21, 0.21, 0.44],
        1,
        SharingPolicy::None,
        RouteMethod::Sequential,
    );
    assert_eq!(none.support_drones, 0);
    assert_eq!(none.swarm.drones.len(), 3);
    assert_close(none.plan.dt_min, 23.31, "none dt");
    let idle = t.plan(
        "A",
        "B",
        &[0.21, 0.21, 0.44],
        1,
        SharingPolicy::IdleSupport,
        RouteMethod::Sequential,
    );
    assert_eq!(idle.support_drones, 1);
    assert_eq!(idle.swarm.drones.len(), 4);
    assert_eq!(idle.plan.shared_mah, 0.0);
    assert_close(
        idle.plan.hops[0].stop.as_ref().unwrap().nt_min,
        15.295,
        "idle nt",
    );
    assert_close(idle.plan.dt_min, 25.295, "idle dt");
}
