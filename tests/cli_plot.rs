//! `swarmplan plot`: the figure's numbers ([`figure_data`]) against hand-computed plans on the
//! tiny `flat` instances (arithmetic in tests/cli_solve.rs and instances/tiny/README.md), and
//! the SVG's contents counted from its text: one legend entry per drone, one label per pad bar,
//! one translucent band per transfer, the failure marked; every sharing policy and route method
//! drawn; the command's refusals with their codes.

mod common;

use common::{close, repo_arg, repo_path, swarmplan, tmp, write_tmp, FLAT_STOP_REQUEST_ARGS};
use std::process::Output;
use swarmplan::check::plan_file::parse_plan_file;
use swarmplan::compose::RequestReport;
use swarmplan::plot::data::{figure_data, BatteryUnit, Figure};
use swarmplan::problem::io::{read_json, read_toml};
use swarmplan::problem::{Network, Profile};

fn tiny(name: &str) -> String {
    repo_arg(&format!("instances/tiny/{name}"))
}

/// `solve --json` on a flat instance with the given request and options.
fn solve(network: &str, extra: &[&str]) -> Output {
    let (net, profile) = (tiny(network), tiny("flat.toml"));
    let mut args = vec!["solve", "--network", &net, "--profile", &profile, "--json"];
    args.extend_from_slice(extra);
    swarmplan(&args)
}

fn report(out: &Output) -> RequestReport {
    parse_plan_file(&String::from_utf8_lossy(&out.stdout), "solve").expect("a plan document")
}

fn instance(network: &str) -> (Network, Profile) {
    (
        read_json(&repo_path(&format!("instances/tiny/{network}"))).unwrap(),
        read_toml(&repo_path("instances/tiny/flat.toml")).unwrap(),
    )
}

fn figure(network: &str, reports: &[&RequestReport]) -> Figure {
    let (net, profile) = instance(network);
    figure_data(&net, &profile, reports, BatteryUnit::Mah).unwrap()
}

/// `plot` of the plan file `plan` (and `compare`) on a flat instance, the SVG on stdout.
fn plot(network: &str, plan: &str, compare: Option<&str>) -> Output {
    let (net, profile) = (tiny(network), tiny("flat.toml"));
    let mut args = vec![
        "plot",
        "--network",
        &net,
        "--profile",
        &profile,
        "--plan",
        plan,
        "-o",
        "-",
    ];
    if let Some(c) = compare {
        args.extend(["--compare", c]);
    }
    swarmplan(&args)
}

/// The texts of the SVG's `<text>` elements.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let body = t.split_once('>')?.1;
            Some(body.split("</text>").next()?.trim().to_string())
        })
        .collect()
}

fn count(texts: &[String], pred: impl Fn(&str) -> bool) -> usize {
    texts.iter().filter(|t| pred(t)).count()
}

/// The transfer bands: the only rectangles filled with sky blue.
fn transfer_bands(svg: &str) -> usize {
    svg.split("<rect")
        .skip(1)
        .filter(|r| {
            r.split('>')
                .next()
                .unwrap_or("")
                .contains("fill=\"#56B4E9\"")
        })
        .count()
}

/// Every point of every series lies within the figure's axes.
fn assert_axes_hold_every_value(f: &Figure) {
    let (t0, t1) = f.time_range_min;
    let (b0, b1) = f.battery_range;
    for p in &f.plans {
        for d in &p.drones {
            assert!(
                b0 <= 0.0 && d.capacity <= b1,
                "{:?} {}",
                f.battery_range,
                d.capacity
            );
            for &(t, b) in &d.points {
                assert!(t0 <= t && t <= t1, "t {t} outside {:?}", f.time_range_min);
                assert!(
                    b0 <= b && b <= b1,
                    "battery {b} outside {:?}",
                    f.battery_range
                );
            }
        }
        assert!(p.dt_min <= t1);
        if let Some(x) = &p.failure {
            assert!(x.time_min <= t1);
        }
        for s in &p.stops {
            assert!(s.nt_min <= f.stop_range_min.1);
        }
    }
}

#[test]
fn a_stop_plan_draws_three_batteries_and_three_pad_bars() {
    // flat-stop, no sharing: drones 0.21, 0.21, 0.44 kg leave A full (1000 mAh), reach M after
    // 5 min with 334.5, 334.5, 136 mAh; ct 6.655, 6.655, 8.64 min on 2 pads, nt 13.31 (drones 0
    // and 1 on one pad); B after 5 more min with the same batteries: dt 23.31 min.
    let out = solve(
        "flat-stop.json",
        &[&FLAT_STOP_REQUEST_ARGS[..], &["--sharing", "none"]].concat(),
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let r = report(&out);
    let f = figure("flat-stop.json", &[&r]);
    assert_axes_hold_every_value(&f);
    assert!(f.time_range_min.0 == 0.0 && f.time_range_min.1 >= 23.31);
    let p = &f.plans[0];
    assert_eq!(p.drones.len(), 3);
    let arrival = [334.5, 334.5, 136.0];
    for d in &p.drones {
        let at = |t: f64| {
            d.points
                .iter()
                .find(|q| close(q.0, t))
                .unwrap_or_else(|| panic!("no point at {t}: {:?}", d.points))
                .1
        };
        assert_eq!(d.points[0], (0.0, 1000.0), "departs full");
        assert!(close(at(5.0), arrival[d.drone]), "{:?}", d.points);
        let last = d.points.last().unwrap();
        assert!(close(last.0, 23.31) && close(last.1, arrival[d.drone]));
        // Time never runs back.
        assert!(d.points.windows(2).all(|w| w[0].0 <= w[1].0 + 1e-9));
    }
    assert!(p.transfers.is_empty());
    assert_eq!(p.stops.len(), 1);
    let s = &p.stops[0];
    assert_eq!((s.node.as_str(), s.pads), ("M", 2));
    assert!(close(s.arrival_min, 5.0) && close(s.nt_min, 13.31));
    assert_eq!(s.optimum_min, Some(s.nt_min));
    assert_eq!(s.bars.len(), 3);
    let ct = [6.655, 6.655, 8.64];
    for b in &s.bars {
        assert!(close(b.end_min - b.start_min, ct[b.drone]), "{b:?}");
    }
    // Drones 0 and 1 share a pad, back to back: one ends at nt.
    let (b0, b1) = (s.bars[0], s.bars[1]);
    assert_eq!(b0.pad, b1.pad);
    assert!(close(b0.end_min.max(b1.end_min), 13.31));
    assert!(close(s.bars[2].start_min, 0.0) && s.bars[2].pad != b0.pad);
    // The drone charged second waits at its arrival battery until its pad is free.
    let second = if b0.start_min > 0.0 { 0 } else { 1 };
    assert!(p.drones[second]
        .points
        .iter()
        .any(|q| close(q.0, 5.0 + 6.655) && close(q.1, 334.5)));

    let path = write_tmp("stop.json", &out.stdout);
    let svg = plot("flat-stop.json", &path, None);
    assert_eq!(svg.status.code(), Some(0), "{svg:?}");
    let svg = String::from_utf8(svg.stdout).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    let t = texts(&svg);
    for d in 0..3 {
        assert_eq!(count(&t, |x| x == format!("drone {d} (delivery)")), 1);
        assert_eq!(count(&t, |x| x == format!("d{d}")), 1, "{t:?}");
    }
    assert_eq!(count(&t, |x| x.starts_with("drone ")), 3);
    assert_eq!(
        count(&t, |x| x.contains("nt 13.31 min (optimal)")),
        1,
        "{t:?}"
    );
    assert_eq!(count(&t, |x| x == "M: 2 pads"), 1);
    assert_eq!(count(&t, |x| x == "source A" || x == "destination B"), 2);
    assert_eq!(transfer_bands(&svg), 0);
}

#[test]
fn the_transfers_drawn_are_the_plans() {
    // flat-line A -> D, 8 min: the 0.21 kg drone draws 133.1 mAh/min (64.8 mAh short of the
    // 1064.8 it needs); PB starts sharing at 500 / 133.1 min and gives 509.21112 mAh, so it
    // lands with 1000 - 1064.8 + 509.21112 = 444.41112 mAh.
    let out = solve(
        "flat-line.json",
        &[
            "--from",
            "A",
            "--to",
            "D",
            "--packages",
            "0.21",
            "--sharing",
            "pb",
            "--support",
            "1",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let r = report(&out);
    let f = figure("flat-line.json", &[&r]);
    assert_axes_hold_every_value(&f);
    let p = &f.plans[0];
    let stated = &r.plan.hops[0].transfers;
    assert!(!stated.is_empty());
    assert_eq!(p.transfers.len(), stated.len());
    for (drawn, x) in p.transfers.iter().zip(stated) {
        assert_eq!(
            (
                drawn.support,
                drawn.consumer,
                drawn.start_min,
                drawn.end_min
            ),
            (x.support, x.consumer, x.start_min, x.end_min)
        );
        assert!(drawn.battery_span.0 < drawn.battery_span.1);
    }
    assert!(close(p.transfers[0].start_min, 500.0 / 133.1));
    let consumer = &p.drones[0];
    assert!(close(consumer.points.last().unwrap().1, 444.41112));
    // The support drone has twice the capacity: both capacities fit on the axis.
    assert!(p.drones[1].capacity > p.drones[0].capacity);

    let path = write_tmp("pb.json", &out.stdout);
    let svg = plot("flat-line.json", &path, None);
    assert_eq!(svg.status.code(), Some(0), "{svg:?}");
    let svg = String::from_utf8(svg.stdout).unwrap();
    assert_eq!(transfer_bands(&svg), stated.len());
    let t = texts(&svg);
    assert_eq!(count(&t, |x| x == "drone 0 (delivery)"), 1);
    assert_eq!(count(&t, |x| x == "drone 1 (support)"), 1);
    assert_eq!(count(&t, |x| x == "no recharging stop"), 1);
}

#[test]
fn a_dead_end_draws_up_to_the_failure_and_marks_it() {
    // flat-deadend: the swarm stops at M1 then M2 and cannot reach B.
    let out = solve(
        "flat-deadend.json",
        &[
            "--from",
            "A",
            "--to",
            "B",
            "--packages",
            "0.21",
            "--support",
            "0",
        ],
    );
    assert_eq!(out.status.code(), Some(1), "{out:?}");
    let r = report(&out);
    let f = figure("flat-deadend.json", &[&r]);
    assert_axes_hold_every_value(&f);
    let p = &f.plans[0];
    assert_eq!(p.outcome_kind, "dead-end");
    assert_eq!(p.stops.len(), 2);
    let swarmplan::compose::PlanOutcome::DeadEnd { direct, .. } = &r.plan.outcome else {
        panic!("{:?}", r.plan.outcome);
    };
    let x = p.failure.as_ref().expect("the failure marked");
    assert_eq!(x.drone, direct.drone);
    assert!(close(x.time_min, r.plan.dt_min + direct.time_min));
    assert_eq!(p.failed_at.as_ref().map(|a| a.0.as_str()), Some("M2"));
    // The batteries are drawn up to the end of the part flown.
    assert!(close(p.drones[0].points.last().unwrap().0, r.plan.dt_min));

    let path = write_tmp("deadend.json", &out.stdout);
    let svg = plot("flat-deadend.json", &path, None);
    assert_eq!(svg.status.code(), Some(0), "{svg:?}");
    let t = texts(&String::from_utf8(svg.stdout).unwrap());
    assert_eq!(count(&t, |x| x.contains("runs dry")), 1, "{t:?}");
    assert_eq!(count(&t, |x| x == "plan fails at M2"), 1, "{t:?}");
    assert_eq!(count(&t, |x| x == "d0"), 2, "one bar per stop");
}

#[test]
fn every_sharing_policy_and_route_method_is_drawn() {
    let routes = [
        "sequential",
        "astar",
        "dijkstra",
        "floyd-warshall",
        "optimal",
    ];
    for sharing in ["none", "idle-support", "pb", "fb", "exact", "fair"] {
        for route in routes {
            if sharing == "fair" && route == "optimal" {
                continue;
            }
            let args = [
                &FLAT_STOP_REQUEST_ARGS[..],
                &["--sharing", sharing, "--route", route],
            ]
            .concat();
            let out = solve("flat-stop.json", &args);
            assert_eq!(out.status.code(), Some(0), "{sharing} {route}: {out:?}");
            let r = report(&out);
            let path = write_tmp(&format!("{sharing}-{route}.json"), &out.stdout);
            let svg = plot("flat-stop.json", &path, None);
            assert_eq!(svg.status.code(), Some(0), "{sharing} {route}: {svg:?}");
            let svg = String::from_utf8(svg.stdout).unwrap();
            let t = texts(&svg);
            let n = r.swarm.drones.len();
            assert_eq!(
                count(&t, |x| x.starts_with("drone ")),
                n,
                "{sharing} {route}"
            );
            let bars: usize = r.plan.hops.iter().filter(|h| h.stop.is_some()).count() * n;
            let labels = count(&t, |x| {
                x.strip_prefix('d')
                    .is_some_and(|d| d.parse::<usize>().is_ok())
            });
            assert_eq!(labels, bars, "{sharing} {route}");
            let transfers: usize = r.plan.hops.iter().map(|h| h.transfers.len()).sum();
            assert_eq!(transfer_bands(&svg), transfers, "{sharing} {route}");
            assert_axes_hold_every_value(&figure("flat-stop.json", &[&r]));
        }
    }
    // The failures of the fixed and the optimal routes on flat-deadend.
    for (route, kind) in [
        ("dijkstra", "hop-infeasible"),
        ("optimal", "no-stop-sequence"),
    ] {
        let out = solve(
            "flat-deadend.json",
            &[
                "--from",
                "A",
                "--to",
                "B",
                "--packages",
                "0.21",
                "--support",
                "0",
                "--route",
                route,
            ],
        );
        assert_eq!(out.status.code(), Some(1), "{out:?}");
        let r = report(&out);
        assert_eq!(r.plan.outcome.kind(), kind);
        let f = figure("flat-deadend.json", &[&r]);
        assert_axes_hold_every_value(&f);
        assert!(f.plans[0].failure.is_some(), "{route}");
        let path = write_tmp(&format!("deadend-{route}.json"), &out.stdout);
        let svg = plot("flat-deadend.json", &path, None);
        assert_eq!(svg.status.code(), Some(0), "{svg:?}");
        let t = texts(&String::from_utf8(svg.stdout).unwrap());
        assert_eq!(count(&t, |x| x.contains("runs dry")), 1, "{route}: {t:?}");
    }
}

#[test]
fn compare_draws_both_plans_on_the_same_axes_with_the_gap() {
    let request = ["--from", "A", "--to", "B", "--packages", "0.21,0.21,0.44"];
    let pb = solve(
        "flat-stop.json",
        &[&request[..], &["--sharing", "pb"]].concat(),
    );
    let exact = solve(
        "flat-stop.json",
        &[&request[..], &["--sharing", "exact", "--route", "optimal"]].concat(),
    );
    let (a, b) = (report(&pb), report(&exact));
    let f = figure("flat-stop.json", &[&a, &b]);
    assert_eq!(f.plans.len(), 2);
    assert_axes_hold_every_value(&f);
    let gap = (a.plan.dt_min - b.plan.dt_min) / b.plan.dt_min;
    assert!(close(f.gap().unwrap(), gap));

    let (pa, pb_path) = (
        write_tmp("cmp-pb.json", &pb.stdout),
        write_tmp("cmp-exact.json", &exact.stdout),
    );
    let svg = plot("flat-stop.json", &pa, Some(&pb_path));
    assert_eq!(svg.status.code(), Some(0), "{svg:?}");
    let t = texts(&String::from_utf8(svg.stdout).unwrap());
    let n = a.swarm.drones.len() + b.swarm.drones.len();
    assert_eq!(count(&t, |x| x.starts_with("drone ")), n);
    let dt = |x: &RequestReport| format!("dt {:.2} min", x.plan.dt_min);
    assert_eq!(
        count(&t, |x| x.starts_with("plan (") && x.contains(&dt(&a))),
        1
    );
    assert_eq!(
        count(&t, |x| x.starts_with("reference (") && x.contains(&dt(&b))),
        1
    );
    let gap_text = format!("{:+.2}%", 100.0 * gap);
    assert_eq!(
        count(&t, |x| x.contains("gap") && x.ends_with(&gap_text)),
        1,
        "{t:?}"
    );

    // The plan on standard input.
    let (net, profile) = (tiny("flat-stop.json"), tiny("flat.toml"));
    let out = tmp("cmp.svg");
    let _ = std::fs::remove_file(&out);
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args([
            "plot",
            "--network",
            &net,
            "--profile",
            &profile,
            "--plan",
            "-",
            "--compare",
            &pb_path,
            "-o",
            out.to_str().unwrap(),
        ])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    {
        use std::io::Write;
        child.stdin.take().unwrap().write_all(&pb.stdout).unwrap();
    }
    let done = child.wait_with_output().unwrap();
    assert_eq!(done.status.code(), Some(0), "{done:?}");
    assert!(std::fs::read_to_string(&out).unwrap().ends_with("</svg>\n"));
}

#[test]
fn plot_refuses_what_it_cannot_draw_with_codes() {
    let expect_2 = |out: &Output, code: &str| {
        assert_eq!(out.status.code(), Some(2), "{out:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(&format!("[{code}]")), "want {code}: {err}");
        assert!(out.stdout.is_empty(), "{out:?}");
    };
    let stop = solve(
        "flat-stop.json",
        &[&FLAT_STOP_REQUEST_ARGS[..], &["--sharing", "none"]].concat(),
    );
    let other = solve(
        "flat-stop.json",
        &[
            "--from",
            "A",
            "--to",
            "B",
            "--packages",
            "0.21",
            "--sharing",
            "none",
        ],
    );
    let (a, b) = (
        write_tmp("refuse-a.json", &stop.stdout),
        write_tmp("refuse-b.json", &other.stdout),
    );
    expect_2(&plot("flat-stop.json", &a, Some(&b)), "E8001");
    expect_2(&plot("flat-stop.json", "-", Some("-")), "E8002");
    // Another network than the plan's.
    expect_2(&plot("flat-line.json", &a, None), "E6004");
    // A path that is not the network's: the hop's path reversed.
    let mut doc: serde_json::Value = serde_json::from_slice(&stop.stdout).unwrap();
    doc.as_object_mut().unwrap().remove("made_on");
    doc["plan"]["hops"][0]["path"] = serde_json::json!(["A", "B"]);
    let bad = write_tmp("refuse-path.json", doc.to_string().as_bytes());
    expect_2(&plot("flat-stop.json", &bad, None), "E8003");
    // An output that exists, without --force; the plan itself as the output.
    let (net, profile) = (tiny("flat-stop.json"), tiny("flat.toml"));
    let exists = write_tmp("exists.svg", b"keep");
    let args = |o: &str| {
        swarmplan(&[
            "plot",
            "--network",
            &net,
            "--profile",
            &profile,
            "--plan",
            &a,
            "-o",
            o,
        ])
    };
    expect_2(&args(&exists), "E0013");
    assert_eq!(std::fs::read(&exists).unwrap(), b"keep");
    expect_2(&args(&a), "E0031");
}

/// `eaas --write-hop` of hop 0 of request r00003 on the shipped instance (ten legs, five
/// delivery drones and one support drone, PB a third below the optimum), and `eaas --json`'s
/// report of `methods` on it.
fn shipped_hop(name: &str, methods: &str) -> (String, serde_json::Value) {
    let hop = tmp(name);
    let _ = std::fs::remove_file(&hop);
    let hop = hop.to_string_lossy().to_string();
    let out = swarmplan(&[
        "eaas",
        "--request-id",
        "r00003",
        "--hop",
        "0",
        "--write-hop",
        &hop,
        "--methods",
        methods,
        "--json",
    ]);
    assert!(out.status.success(), "{out:?}");
    (hop, serde_json::from_slice(&out.stdout).unwrap())
}

fn plot_hop(hop: &str, methods: &str) -> Output {
    swarmplan(&["plot", "--hop-file", hop, "--methods", methods, "-o", "-"])
}

#[test]
fn a_hop_file_draws_each_methods_schedule_as_eaas_reports_it() {
    let methods = "pb,fb,continuous,milp";
    let (hop, report) = shipped_hop("plot-hop.json", methods);
    let out = plot_hop(&hop, methods);
    assert!(out.status.success(), "{out:?}");
    let svg = String::from_utf8(out.stdout).unwrap();
    let t = texts(&svg);
    let rows = report["rows"].as_array().unwrap();
    let drones = report["problem"]["drones"].as_array().unwrap();
    assert_eq!((rows.len(), drones.len()), (4, 6));
    // One panel per method: a legend entry per drone in each, the drone's role named.
    for (d, drone) in drones.iter().enumerate() {
        let entry = format!("drone {d} ({})", drone["role"].as_str().unwrap());
        assert_eq!(count(&t, |x| x == entry), rows.len(), "{entry}");
    }
    // One band per transfer of every schedule, as `eaas` reports the schedules.
    let transfers: usize = rows
        .iter()
        .map(|r| r["transfers"].as_array().unwrap().len())
        .sum();
    assert!(transfers > 2, "{transfers}");
    assert_eq!(transfer_bands(&svg), transfers);
    // Each method's line of the title: its objective as `eaas` computes it (the lowest delivery
    // arrival battery) and its transfers; PB's gap against the optimum, positive (a loss).
    for r in rows {
        let method = r["method"].as_str().unwrap();
        let line = t
            .iter()
            .find(|x| x.starts_with(&format!("{method}: ")))
            .unwrap_or_else(|| panic!("no title line of {method}: {t:?}"));
        let objective = r["objective"].as_f64().unwrap();
        assert!(line.contains(&format!("{objective:.2} mAh")), "{line}");
        let n = r["transfers"].as_array().unwrap().len();
        assert!(line.ends_with(&format!("| {n} transfer(s)")), "{line}");
    }
    let pb = &rows[0];
    let (v, optimum) = (
        pb["objective"].as_f64().unwrap(),
        rows[2]["objective"].as_f64().unwrap(),
    );
    assert!(optimum > v + 1.0, "{v} {optimum}");
    let gap = 100.0 * (optimum - v) / optimum;
    assert!(
        t.iter()
            .any(|x| x.contains(&format!("gap +{gap:.2}% vs optimal"))),
        "{t:?}"
    );
    assert_eq!(count(&t, |x| x.contains("runs dry")), 0);
}

#[test]
fn a_hop_a_drone_cannot_fly_marks_where_it_runs_dry() {
    use swarmplan::eaas::hop_file::read_hop_file;
    use swarmplan::plot::hop::{hop_figure_data, HopSchedule};
    let (hop, _) = shipped_hop("plot-hop-dry.json", "none");
    let mut doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&hop).unwrap()).unwrap();
    // Drone 1 leaves with half of what the hop's legs take from it in its own slot, without
    // sharing (`rate_mah_per_min[drone][slot]`).
    let legs = doc["hop"]["legs"].as_array().unwrap().clone();
    let slot = doc["hop"]["initial_slot"][1].as_u64().unwrap() as usize;
    let rate = |l: &serde_json::Value| l["rate_mah_per_min"][1][slot].as_f64().unwrap();
    let need: f64 = legs
        .iter()
        .map(|l| l["duration_min"].as_f64().unwrap() * rate(l))
        .sum();
    let battery = need / 2.0;
    doc["hop"]["drones"][1]["battery_mah"] = serde_json::json!(battery);
    doc.as_object_mut().unwrap().remove("made_on");
    let edited = write_tmp("plot-hop-dry-edited.json", doc.to_string().as_bytes());
    // By hand: the leg in which drone 1's cumulative consumption reaches its battery.
    let (mut t, mut left) = (0.0, battery);
    let mut dry_at = None;
    for l in &legs {
        let (dur, rate) = (l["duration_min"].as_f64().unwrap(), rate(l));
        if dry_at.is_none() && rate * dur >= left {
            dry_at = Some(t + left / rate);
        }
        left -= rate * dur;
        t += dur;
    }
    let dry_at = dry_at.unwrap();
    let file = read_hop_file(std::path::Path::new(&edited)).unwrap();
    let none = HopSchedule {
        method: "none".to_string(),
        summary: String::new(),
        transfers: Vec::new(),
    };
    let fig = hop_figure_data(&file, &[none], BatteryUnit::Mah).unwrap();
    let f = fig.figure.plans[0].failure.as_ref().expect("a failure");
    assert_eq!(f.drone, 1);
    assert!(close(f.time_min, dry_at), "{} {dry_at}", f.time_min);
    assert_axes_hold_every_value(&fig.figure);
    let out = plot_hop(&edited, "none");
    assert!(out.status.success(), "{out:?}");
    let t = texts(&String::from_utf8(out.stdout).unwrap());
    assert_eq!(
        count(&t, |x| x.starts_with("drone 1 runs dry at")),
        1,
        "{t:?}"
    );
    assert!(
        t.iter().any(|x| x.starts_with("none: does not fly")),
        "{t:?}"
    );
}

#[test]
fn plot_refuses_a_hop_method_without_a_schedule_and_a_plan_beside_a_hop() {
    let (hop, _) = shipped_hop("plot-hop-refuse.json", "pb");
    let out = plot_hop(&hop, "pb,fluid");
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("[E8004] --methods"));
    let out = swarmplan(&["plot", "--hop-file", &hop, "--compare", &hop, "-o", "-"]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(String::from_utf8_lossy(&out.stderr).contains("[E0007]"));
}

/// The README's figure, `docs/src/figures/plan.svg`, is what its caption's commands draw today:
/// PB on request r00029 against the optimal route with exact sharing. Drawn again here, it must
/// be the same bytes; `SWARMPLAN_BLESS=1 cargo test --release --test cli_plot` writes it anew
/// after a change to the figure.
#[test]
fn the_readme_figure_is_what_its_commands_draw() {
    let solve = |name: &str, extra: &[&str]| {
        let mut args = vec!["solve", "--request-id", "r00029", "--json"];
        args.extend_from_slice(extra);
        let out = swarmplan(&args);
        assert!(out.status.success(), "{out:?}");
        write_tmp(name, &out.stdout)
    };
    let pb = solve("readme-pb.json", &["--sharing", "pb"]);
    let exact = solve(
        "readme-exact.json",
        &["--route", "optimal", "--sharing", "exact"],
    );
    let out = swarmplan(&["plot", "--plan", &pb, "--compare", &exact, "-o", "-"]);
    assert!(out.status.success(), "{out:?}");
    let figure = repo_path("docs/src/figures/plan.svg");
    if std::env::var_os("SWARMPLAN_BLESS").is_some() {
        std::fs::write(&figure, &out.stdout).unwrap();
    }
    let committed = std::fs::read(&figure).unwrap_or_default();
    assert!(
        committed == out.stdout,
        "{} is not what `plot` draws today: SWARMPLAN_BLESS=1 cargo test --release --test \
         cli_plot writes it anew",
        figure.display()
    );
    let t = texts(&String::from_utf8(out.stdout).unwrap());
    assert!(t
        .iter()
        .any(|x| x.starts_with("gap of the plan against the reference")));
    // The README shows this figure under the commands drawn here.
    let readme = std::fs::read_to_string(repo_path("README.md")).unwrap();
    for line in [
        "](docs/src/figures/plan.svg)",
        "solve --request-id r00029 --json > pb.json",
        "solve --request-id r00029 --route optimal --sharing exact --json > exact.json",
        "plot --plan pb.json --compare exact.json",
    ] {
        assert!(readme.contains(line), "README lacks `{line}`");
    }
}
