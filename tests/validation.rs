//! Validation reports every violation at once, each with its code and field. Expected lists are the
//! ones written out by hand in instances/tiny/README.md.

mod common;

use common::repo_path;
use std::path::PathBuf;
use swarmplan::error::Error;
use swarmplan::problem::io::{parse_json, read_json};
use swarmplan::problem::validate::{validate_network, validate_request, validate_request_set};
use swarmplan::problem::SkywayGraph;
use swarmplan::problem::{Network, Request, RequestSet};

fn tiny(name: &str) -> PathBuf {
    repo_path("instances/tiny").join(name)
}

fn codes_and_fields(v: &[swarmplan::error::Violation]) -> Vec<(&'static str, String)> {
    v.iter().map(|x| (x.code, x.field.clone())).collect()
}

fn pairs(list: &[(&'static str, &str)]) -> Vec<(&'static str, String)> {
    list.iter().map(|(c, f)| (*c, f.to_string())).collect()
}

#[test]
fn invalid_network_reports_all_eleven_violations_with_fields() {
    let n: Network = read_json(&tiny("invalid-network.json")).unwrap();
    let v = validate_network(&n);
    assert_eq!(
        codes_and_fields(&v),
        pairs(&[
            ("E1102", "nodes[2].id"),
            ("E1101", "nodes[3].id"),
            ("E1104", "nodes[3].pad_charge_rate_mah_per_min"),
            ("E1105", "nodes"),
            ("E1206", "edges[0].wind_speed_mps"),
            ("E1201", "edges[1].to"),
            ("E1202", "edges[2]"),
            ("E1203", "edges[3]"),
            ("E1204", "edges[3].distance_m"),
            ("E1205", "edges[3].wind_speed_mps"),
            ("E1207", "edges[3].wind_from_deg"),
        ])
    );
    // Every violation says what is wrong and what to do.
    assert!(v
        .iter()
        .all(|x| !x.cause.is_empty() && !x.action.is_empty()));
    assert!(v[4].cause.contains("14"));
    // Building a graph refuses the network with the same list.
    match SkywayGraph::new(&n) {
        Err(Error::Invalid(list)) => assert_eq!(list, v),
        other => panic!("expected Error::Invalid, got {other:?}"),
    }
}

#[test]
fn non_finite_numbers_and_schema_version_are_reported() {
    // JSON has no NaN, so these come from code (e.g. a network built by a program).
    let mut n: Network = read_json(&tiny("line4.json")).unwrap();
    n.schema_version = 9;
    n.nodes[1].x_m = f64::NAN;
    n.nodes[2].y_m = f64::INFINITY;
    n.edges[0].wind_speed_mps = f64::NAN;
    n.edges[1].wind_from_deg = f64::NAN;
    n.edges[2].distance_m = Some(f64::NAN);
    let v = validate_network(&n);
    assert_eq!(
        codes_and_fields(&v),
        pairs(&[
            ("E1001", "schema_version"),
            ("E1103", "nodes[1].x_m"),
            ("E1103", "nodes[2].y_m"),
            // B's x is NaN, so the default A-B and B-C lengths are NaN as well.
            ("E1204", "edges[0].distance_m"),
            ("E1205", "edges[0].wind_speed_mps"),
            ("E1204", "edges[1].distance_m"),
            ("E1207", "edges[1].wind_from_deg"),
            ("E1204", "edges[2].distance_m"),
        ])
    );
}

#[test]
fn wind_just_under_the_limit_is_valid_and_at_the_limit_is_not() {
    let mut n: Network = read_json(&tiny("line4.json")).unwrap();
    assert!(validate_network(&n).is_empty()); // C-D has 13.7 m/s
    n.edges[2].wind_speed_mps = 13.8;
    assert_eq!(
        codes_and_fields(&validate_network(&n)),
        pairs(&[("E1206", "edges[2].wind_speed_mps")])
    );
}

#[test]
fn coincident_nodes_without_distance_are_reported() {
    let mut n: Network = read_json(&tiny("line4.json")).unwrap();
    n.nodes[1].x_m = 0.0; // B on top of A: A-B has Euclidean length 0
    assert_eq!(
        codes_and_fields(&validate_network(&n)),
        pairs(&[("E1204", "edges[0].distance_m")])
    );
}

#[test]
fn invalid_requests_report_all_eight_violations_with_fields() {
    let n: Network = read_json(&tiny("line4.json")).unwrap();
    let g = SkywayGraph::new(&n).unwrap();
    let set: RequestSet = read_json(&tiny("line4-invalid-requests.json")).unwrap();
    let v = validate_request_set(&set, &g, 1.4);
    assert_eq!(
        codes_and_fields(&v),
        pairs(&[
            ("E3001", "schema_version"),
            ("E3201", "requests[0].destination"),
            ("E3102", "requests[1].id"),
            ("E3202", "requests[1].destination"),
            ("E3301", "requests[1].packages_kg"),
            ("E3303", "requests[2].packages_kg[0]"),
            ("E3302", "requests[2].packages_kg[1]"),
            ("E3302", "requests[2].packages_kg[2]"),
        ])
    );
}

#[test]
fn valid_requests_pass_and_a_disconnected_destination_does_not() {
    let n: Network = read_json(&tiny("line4.json")).unwrap();
    let g = SkywayGraph::new(&n).unwrap();
    let set: RequestSet = read_json(&tiny("line4-requests.json")).unwrap();
    assert!(validate_request_set(&set, &g, 1.4).is_empty());
    // r2 carries a 1.4 kg package: over a 1.0 kg payload.
    assert_eq!(
        codes_and_fields(&validate_request_set(&set, &g, 1.0)),
        pairs(&[
            ("E3303", "requests[0].packages_kg[1]"),
            ("E3303", "requests[1].packages_kg[0]")
        ])
    );

    let island: Network = read_json(&tiny("island.json")).unwrap();
    let g = SkywayGraph::new(&island).unwrap();
    let r = Request {
        id: "".into(),
        source: "X".into(),
        destination: "Q".into(),
        packages_kg: vec![0.5, f64::NAN],
    };
    assert_eq!(
        codes_and_fields(&validate_request(&r, 17, &g, 1.4)),
        pairs(&[
            ("E3101", "requests[17].id"),
            ("E3203", "requests[17].destination"),
            ("E3302", "requests[17].packages_kg[1]"),
        ])
    );
    let empty = RequestSet {
        schema_version: 1,
        seed: None,
        requests: vec![],
    };
    assert_eq!(
        codes_and_fields(&validate_request_set(&empty, &g, 1.4)),
        pairs(&[("E3002", "requests")])
    );
}

#[test]
fn malformed_json_and_unknown_fields_are_coded_errors() {
    let bad = r#"{ "schema_version": 1, "nodes": [ { "id": "A", "x_m": 0.0 "#;
    match parse_json::<Network>(bad, "broken.json") {
        Err(Error::Invalid(v)) => {
            assert_eq!(v.len(), 1);
            assert_eq!(v[0].code, "E0001");
            assert_eq!(v[0].field, "broken.json");
            assert!(v[0].cause.contains("line 1"));
        }
        other => panic!("expected E0001, got {other:?}"),
    }
    let unknown = r#"{ "schema_version": 1, "nodes": [], "edges": [], "roads": [] }"#;
    match parse_json::<Network>(unknown, "unknown.json") {
        Err(e) => assert_eq!(e.exit_code(), 2),
        Ok(_) => panic!("unknown field accepted"),
    }
    // A well-formed but empty network: no nodes (E1002); no pads cannot be judged without nodes.
    let empty: Network =
        parse_json(r#"{ "schema_version": 1, "nodes": [], "edges": [] }"#, "e").unwrap();
    assert_eq!(
        codes_and_fields(&validate_network(&empty)),
        pairs(&[("E1002", "nodes")])
    );
}

#[test]
fn file_readers_name_the_file_in_every_field() {
    let bad = tiny("invalid-network.json");
    match swarmplan::problem::read_network(&bad) {
        Err(Error::Invalid(v)) => {
            assert_eq!(v.len(), 11);
            assert!(v
                .iter()
                .all(|x| x.field.starts_with(&format!("{}: ", bad.display()))));
            assert!(v[0].field.ends_with("nodes[2].id"));
        }
        other => panic!("expected 11 violations, got {other:?}"),
    }
    let (network, g) = swarmplan::problem::read_network(&tiny("line4.json")).unwrap();
    assert_eq!(network.nodes.len(), 4);
    let ok = swarmplan::problem::validate::read_request_set(&tiny("line4-requests.json"), &g, 1.4)
        .unwrap();
    assert_eq!(ok.requests.len(), 2);
    let reqs = tiny("line4-invalid-requests.json");
    match swarmplan::problem::validate::read_request_set(&reqs, &g, 1.4) {
        Err(e) => {
            assert_eq!(e.exit_code(), 2);
            let text = e.to_string();
            assert!(text.contains("8 problem(s)"), "{text}");
            assert!(text.contains("requests[2].packages_kg[2]"), "{text}");
        }
        Ok(_) => panic!("invalid requests accepted"),
    }
}

/// The shipped profiles, each as a TOML table.
fn shipped_profiles() -> Vec<(String, toml::Table)> {
    let dir = repo_path("instances/profiles");
    let mut out = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        out.push((
            path.display().to_string(),
            text.parse::<toml::Table>().unwrap(),
        ));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

/// Sets the dotted `field` of a profile table to `value` (an integer for integer fields).
fn set_field(t: &mut toml::Table, field: &str, value: f64) {
    let (section, name) = field.split_once('.').unwrap();
    let mut table = t;
    let mut name = name;
    let mut section = section;
    loop {
        table = table
            .entry(section)
            .or_insert_with(|| toml::Value::Table(toml::Table::new()))
            .as_table_mut()
            .unwrap();
        match name.split_once('.') {
            Some((s, n)) => {
                section = s;
                name = n;
            }
            None => break,
        }
    }
    let v = match table.get(name) {
        Some(toml::Value::Integer(_)) => toml::Value::Integer(value as i64),
        _ => toml::Value::Float(value),
    };
    table.insert(name.to_string(), v);
}

#[test]
fn every_profile_quantity_has_a_stated_range_and_each_bound_is_enforced_with_e2013() {
    use swarmplan::problem::validate::{profile_ranges, validate_profile};
    use swarmplan::problem::Profile;
    for (name, table) in shipped_profiles() {
        let profile: Profile = toml::from_str(&toml::to_string(&table).unwrap()).unwrap();
        assert_eq!(
            validate_profile(&profile),
            vec![],
            "{name} is within its ranges"
        );
        let ranges = profile_ranges(&profile);
        assert!(ranges.len() >= 30, "{name}: {} ranges", ranges.len());
        let mut failures = Vec::new();
        for r in ranges {
            // Just outside each end (below a minimum of 0 is a sign error, reported as E2002,
            // E2003 or E2022, not E2013); just inside each end is valid.
            let mut outside = vec![r.max * 1.5 + 1.0];
            if r.min > 0.0 {
                outside.push(r.min / 2.0);
            }
            for v in outside {
                let mut t = table.clone();
                set_field(&mut t, r.field, v);
                let p: Profile = toml::from_str(&toml::to_string(&t).unwrap()).unwrap();
                let got = validate_profile(&p);
                if !got.iter().any(|x| x.code == "E2013" && x.field == r.field) {
                    failures.push(format!("{name}: {} = {v}: {got:?}", r.field));
                }
            }
        }
        assert!(failures.is_empty(), "{}", failures.join("\n"));
    }
}

#[test]
fn network_coordinates_lengths_pad_rates_and_pad_counts_have_stated_ranges() {
    let text = r#"{"schema_version": 1, "nodes": [
        {"id": "A", "x_m": 1e7, "y_m": -1e7, "pads": 1000, "pad_charge_rate_mah_per_min": 0.1},
        {"id": "B", "x_m": 1e7, "y_m": -9999000.0, "pads": 0, "pad_charge_rate_mah_per_min": 1e6},
        {"id": "C", "x_m": 10000001.0, "y_m": 0.0, "pads": 1001, "pad_charge_rate_mah_per_min": 0.09},
        {"id": "D", "x_m": 0.0, "y_m": 0.0, "pads": 0}],
      "edges": [
        {"from": "A", "to": "B", "wind_speed_mps": 0, "wind_from_deg": 0},
        {"from": "A", "to": "D", "distance_m": 1e6, "wind_speed_mps": 0, "wind_from_deg": 0},
        {"from": "B", "to": "D", "distance_m": 1000000.1, "wind_speed_mps": 0, "wind_from_deg": 0},
        {"from": "C", "to": "D", "wind_speed_mps": 0, "wind_from_deg": 0}]}"#;
    let n: Network = parse_json(text, "t").unwrap();
    assert_eq!(
        codes_and_fields(&validate_network(&n)),
        pairs(&[
            ("E1106", "nodes[2].x_m"),
            ("E1107", "nodes[2].pad_charge_rate_mah_per_min"),
            ("E1108", "nodes[2].pads"),
            ("E1208", "edges[2].distance_m"),
            ("E1208", "edges[3].distance_m"),
        ])
    );
}
