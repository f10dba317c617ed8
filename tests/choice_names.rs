//! Choice enums have one name per value: the clap derive's (what `--help` lists and the command
//! line accepts) is what `Display` prints and what serde writes and reads.

use clap::ValueEnum;
use serde::{de::DeserializeOwned, Serialize};
use std::fmt::Display;
use swarmplan::compose::{FixedRoute, HopPaths, RouteMethod};
use swarmplan::eaas::compare::HopMethod;
use swarmplan::eaas::exact::Reorder;
use swarmplan::eaas::SharingPolicy;
use swarmplan::node_time::NodeTimeMethod;
use swarmplan::precompose::Positioning;
use swarmplan::problem::FormationKind;
use swarmplan::problem::{Candidates, PbRequest};

/// Every value's clap name, `Display` and serde name agree; returns the names.
fn names<T: ValueEnum + Display + Serialize>() -> Vec<String> {
    T::value_variants()
        .iter()
        .map(|v| {
            let clap = v.to_possible_value().unwrap().get_name().to_string();
            assert_eq!(v.to_string(), clap);
            assert_eq!(serde_json::to_value(v).unwrap(), serde_json::json!(clap));
            clap
        })
        .collect()
}

/// Every value reads back from its name, through serde and through clap.
fn reads_back<T: ValueEnum + Display + DeserializeOwned + PartialEq + std::fmt::Debug>() {
    for v in T::value_variants() {
        let name = v.to_string();
        let de: T = serde_json::from_value(serde_json::json!(name)).unwrap();
        assert_eq!(&de, v);
        assert_eq!(&T::from_str(&name, false).unwrap(), v);
    }
}

#[test]
fn every_choice_has_one_name() {
    // The spellings the README documents for the command line.
    assert_eq!(
        names::<RouteMethod>(),
        [
            "sequential",
            "astar",
            "dijkstra",
            "floyd-warshall",
            "optimal"
        ]
    );
    assert_eq!(
        names::<SharingPolicy>(),
        ["none", "idle-support", "pb", "fb", "exact", "fair"]
    );
    assert_eq!(names::<Positioning>(), ["location-aware", "energy-aware"]);
    assert_eq!(names::<Reorder>(), ["paper", "free", "none"]);
    assert_eq!(names::<HopPaths>(), ["rule", "any"]);
    assert_eq!(
        names::<HopMethod>(),
        ["none", "pb", "fb", "continuous", "milp", "fluid", "fair"]
    );
    assert_eq!(names::<NodeTimeMethod>(), ["exact", "milp", "lpt", "brute"]);
    assert_eq!(
        names::<FormationKind>(),
        ["column", "front", "echelon", "vee", "diamond"]
    );
    assert_eq!(names::<FixedRoute>(), ["dijkstra", "floyd-warshall"]);
    assert_eq!(names::<PbRequest>(), ["to-hop-end", "fill"]);
    assert_eq!(names::<Candidates>(), ["pad-nodes", "adjacent"]);
}

#[test]
fn every_choice_reads_back_from_its_name() {
    reads_back::<SharingPolicy>();
    reads_back::<Positioning>();
    reads_back::<Reorder>();
    // The Python package reads these through serde.
    reads_back::<RouteMethod>();
    reads_back::<HopPaths>();
    reads_back::<HopMethod>();
    reads_back::<swarmplan::solver::MilpBackend>();
    reads_back::<FormationKind>();
    reads_back::<PbRequest>();
    reads_back::<Candidates>();
}
