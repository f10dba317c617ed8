//! `swarmplan import`: the hand-written samples of `instances/import-samples/` (their README gives
//! the expected networks, worked out by hand), same seed same bytes, and coded errors for bad
//! input.

mod common;

use common::{repo_arg, stderr, swarmplan, tmp, write_tmp};
use serde_json::Value;

/// Runs `import` with `args` and `-o <tmp>/<name> --force`; returns the network written.
fn import(name: &str, args: &[&str]) -> Value {
    let out_path = tmp(name);
    let out_arg = out_path.to_str().unwrap().to_string();
    let mut all: Vec<&str> = vec!["import"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["-o", &out_arg, "--force"]);
    let out = swarmplan(&all);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    serde_json::from_slice(&std::fs::read(&out_path).unwrap()).unwrap()
}

fn ids(network: &Value, what: &str) -> Vec<String> {
    network[what]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| match what {
            "nodes" => x["id"].as_str().unwrap().to_string(),
            _ => format!(
                "{}-{}",
                x["from"].as_str().unwrap(),
                x["to"].as_str().unwrap()
            ),
        })
        .collect()
}

#[test]
fn the_csv_sample_keeps_the_triangle_with_the_shortest_roads() {
    let (nodes, edges) = (
        repo_arg("instances/import-samples/nodes.csv"),
        repo_arg("instances/import-samples/edges.csv"),
    );
    let args = ["--nodes", &nodes, "--edges", &edges, "--seed", "7"];
    let net = import("csv.json", &args);
    assert_eq!(ids(&net, "nodes"), ["A", "B", "C"]);
    assert_eq!(net["nodes"][1]["x_m"], 300.0);
    assert_eq!(net["nodes"][1]["y_m"], 400.0);
    assert_eq!(ids(&net, "edges"), ["A-B", "A-C", "B-C"]);
    // A-B: 480 m given beats the straight 500 m; A-C: no length given (straight 300 m); B-C: 450.
    assert_eq!(net["edges"][0]["distance_m"], 480.0);
    assert!(net["edges"][1].get("distance_m").is_none());
    assert_eq!(net["edges"][2]["distance_m"], 450.0);
    for e in net["edges"].as_array().unwrap() {
        let v = e["wind_speed_mps"].as_f64().unwrap();
        assert!((0.0..13.0).contains(&v), "{v}");
    }
    assert!(net["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .any(|n| n["pads"].as_u64().unwrap() > 0));
    // Same seed, same bytes; the file is a network every command reads.
    let again = import("csv2.json", &args);
    assert_eq!(net, again);
    let network = tmp("csv.json");
    let out = swarmplan(&[
        "solve",
        "--network",
        network.to_str().unwrap(),
        "--from",
        "A",
        "--to",
        "C",
        "--packages",
        "0.5",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

#[test]
fn nearest_keeps_the_nodes_closest_to_the_centre() {
    let (nodes, edges) = (
        repo_arg("instances/import-samples/nodes.csv"),
        repo_arg("instances/import-samples/edges.csv"),
    );
    // D (1000, 0) and E (1000, 300) are 150 m from (1000, 150); C, the next, is 715 m away.
    let net = import(
        "nearest.json",
        &[
            "--nodes",
            &nodes,
            "--edges",
            &edges,
            "--seed",
            "7",
            "--nearest",
            "2",
            "--centre",
            "1000,150",
        ],
    );
    assert_eq!(ids(&net, "nodes"), ["D", "E"]);
    assert_eq!(ids(&net, "edges"), ["D-E"]);
}

#[test]
fn the_geojson_sample_cuts_roads_at_intersections_and_measures_them_on_the_sphere() {
    let geojson = repo_arg("instances/import-samples/roads.geojson");
    let net = import("geo.json", &["--geojson", &geojson, "--seed", "7"]);
    assert_eq!(ids(&net, "nodes"), ["n0", "n1", "n2", "n3"]);
    assert_eq!(ids(&net, "edges"), ["n0-n1", "n1-n2", "n1-n3"]);
    // 0.001 degree of a great circle of the mean Earth radius: 111.195 km per degree.
    for e in net["edges"].as_array().unwrap() {
        let d = e["distance_m"].as_f64().unwrap();
        assert!((d - 111.195).abs() < 0.001, "{d}");
    }
    // The projected positions: n0 to n1 is 0.001 degree of longitude near the equator.
    let x = |i: usize| net["nodes"][i]["x_m"].as_f64().unwrap();
    let y = |i: usize| net["nodes"][i]["y_m"].as_f64().unwrap();
    assert!((x(1) - x(0) - 111.19).abs() < 0.02, "{}", x(1) - x(0));
    assert_eq!(y(1), y(0));
    assert!((y(3) - y(1) - 111.195).abs() < 0.001);
}

#[test]
fn bad_road_networks_are_coded_errors() {
    let nodes = write_tmp("n.csv", b"id,x,y\nA,0,0\nB,100,0\n");
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                write_tmp("n_bad.csv", b"name,x,y\nA,0,0\n"),
                write_tmp("e1.csv", b"from,to\nA,B\n"),
            ],
            "E1950",
        ),
        (
            vec![nodes.clone(), write_tmp("e2.csv", b"from,to\nA,Z\n")],
            "E1951",
        ),
        (
            vec![
                write_tmp("n_dup.csv", b"id,x,y\nA,0,0\nA,1,1\n"),
                write_tmp("e3.csv", b"from,to\nA,A\n"),
            ],
            "E1951",
        ),
        (
            vec![
                nodes.clone(),
                write_tmp("e4.csv", b"from,to,length_m\nA,B,-5\n"),
            ],
            "E1953",
        ),
        (
            vec![nodes.clone(), write_tmp("e5.csv", b"from,to\nA,A\n")],
            "E1954",
        ),
    ];
    let out_arg = tmp("bad.json").to_str().unwrap().to_string();
    for (files, code) in &cases {
        let out = swarmplan(&[
            "import", "--nodes", &files[0], "--edges", &files[1], "--seed", "1", "-o", &out_arg,
            "--force",
        ]);
        assert_eq!(out.status.code(), Some(2), "{code}: {}", stderr(&out));
        assert!(stderr(&out).contains(code), "{code}: {}", stderr(&out));
    }
    // Longitude out of range.
    let lonlat = write_tmp("ll.csv", b"id,x,y\nA,200,0\nB,0,0\n");
    let edges = write_tmp("e6.csv", b"from,to\nA,B\n");
    let out = swarmplan(&[
        "import",
        "--nodes",
        &lonlat,
        "--edges",
        &edges,
        "--coordinates",
        "lon-lat",
        "--seed",
        "1",
        "-o",
        &out_arg,
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("E1952"), "{}", stderr(&out));
    // Not a FeatureCollection; a bad centre; no input at all.
    let geo = write_tmp("g.geojson", b"{\"type\": \"Feature\"}");
    for (args, code) in [
        (vec!["--geojson", geo.as_str()], "E1950"),
        (
            vec![
                "--geojson",
                geo.as_str(),
                "--nearest",
                "3",
                "--centre",
                "x,1",
            ],
            "E1956",
        ),
        (vec![], "E1957"),
    ] {
        let mut all = vec!["import"];
        all.extend(args);
        all.extend(["--seed", "1", "-o", out_arg.as_str(), "--force"]);
        let out = swarmplan(&all);
        assert_eq!(out.status.code(), Some(2), "{code}: {}", stderr(&out));
        assert!(stderr(&out).contains(code), "{code}: {}", stderr(&out));
    }
}
