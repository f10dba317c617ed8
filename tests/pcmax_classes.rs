//! The P||Cmax benchmark class generators (`generate node-time`): counts, ranges and seeds as the
//! class definitions state them (models/generate.md), and files that `swarmplan node-time` reads.

mod common;

use common::{swarmplan, tmp};
use swarmplan::generate::pcmax::{generate_pcmax, PcmaxClass, PcmaxParams};

fn times(class: PcmaxClass, jobs: usize, pads: usize, seed: u64) -> Vec<u64> {
    generate_pcmax(&PcmaxParams {
        class,
        jobs,
        pads,
        seed,
    })
    .unwrap()
    .charge_times_min
}

/// The stated range `[a, b]` of every uniform class, written out from the papers' definitions
/// (not from the code). `None`: the range depends on n or the class is not uniform.
fn stated_uniform_range(name: &str) -> Option<(u64, u64)> {
    Some(match name {
        "u1" | "l1" | "e3-1-100" | "e4-1-100" => (1, 100),
        "u2" => (1, 1000),
        "u3" => (1, 10_000),
        "l2" => (20, 100),
        "l3" | "e4-50-100" => (50, 100),
        "e1-1-20" | "e4-1-20" => (1, 20),
        "e1-20-50" | "e4-20-50" => (20, 50),
        "e2-100-800" | "e4-100-800" => (100, 800),
        "e3-100-200" | "e4-100-200" => (100, 200),
        _ => return None,
    })
}

#[test]
fn every_class_gives_n_times_in_its_stated_range_and_the_same_times_for_the_same_seed() {
    let mut failures = Vec::new();
    for class in PcmaxClass::ALL {
        for (n, m) in [(10, 2), (50, 5), (100, 25)] {
            let t = times(class, n, m, 11);
            if t.len() != n {
                failures.push(format!("{class} {n}x{m}: {} times", t.len()));
            }
            if t != times(class, n, m, 11) {
                failures.push(format!("{class} {n}x{m}: not reproducible"));
            }
            if t == times(class, n, m, 12) && n >= 50 {
                failures.push(format!(
                    "{class} {n}x{m}: seeds 11 and 12 give the same times"
                ));
            }
            if let Some((a, b)) = stated_uniform_range(class.name()) {
                if let Some(x) = t.iter().find(|&&x| x < a || x > b) {
                    failures.push(format!("{class} {n}x{m}: {x} outside [{a}, {b}]"));
                }
            }
            if t.contains(&0) {
                failures.push(format!("{class} {n}x{m}: a zero time"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn uniform_classes_reach_both_ends_of_their_range_on_many_jobs() {
    // 5000 draws from U{1..20}: each end is missed with probability (19/20)^5000, about 1e-111.
    let t = times(PcmaxClass::E1R1To20, 5000, 5, 3);
    assert_eq!(t.iter().min(), Some(&1));
    assert_eq!(t.iter().max(), Some(&20));
    let t = times(PcmaxClass::L3, 5000, 5, 3);
    assert_eq!((t.iter().min(), t.iter().max()), (Some(&50), Some(&100)));
}

#[test]
fn lawrinenko_n_dependent_classes_follow_n() {
    // l6: U{n..4n}. l7: N(4n, n^2) truncated, so within 4n +- 6n except with negligible chance,
    // and its sample mean near 4n.
    for n in [40, 100] {
        let t = times(PcmaxClass::L6, n, n / 2, 5);
        assert!(
            t.iter().all(|&x| (n as u64..=4 * n as u64).contains(&x)),
            "{t:?}"
        );
    }
    let t = times(PcmaxClass::L7, 2000, 800, 5);
    let mean = t.iter().sum::<u64>() as f64 / t.len() as f64;
    assert!((mean - 4.0 * 2000.0).abs() < 0.1 * 2000.0, "mean {mean}");
}

#[test]
fn lawrinenko_normal_classes_have_the_stated_mean_and_spread() {
    // l4: N(100, 20^2); l5: N(100, 50^2), truncated towards zero (mean about 0.5 lower), values
    // below 1 redrawn (rare for l5: P(N < 1) is about 2.4%, which raises its mean slightly).
    for (class, sigma) in [(PcmaxClass::L4, 20.0), (PcmaxClass::L5, 50.0)] {
        let t = times(class, 20_000, 10, 9);
        let mean = t.iter().sum::<u64>() as f64 / t.len() as f64;
        let var = t.iter().map(|&x| (x as f64 - mean).powi(2)).sum::<f64>() / t.len() as f64;
        assert!((mean - 100.0).abs() < 3.0, "{class}: mean {mean}");
        assert!(
            (var.sqrt() - sigma).abs() < 0.1 * sigma,
            "{class}: sd {}",
            var.sqrt()
        );
        assert!(t.iter().all(|&x| x >= 1));
    }
}

#[test]
fn non_uniform_classes_have_two_percent_short_jobs_and_the_rest_long() {
    // Frangioni et al. 2004 as read here: round(0.02 n) jobs in [a, max(a, floor(0.02(b-a)))],
    // the others in [ceil(0.9(b-a)), b], a = 1.
    let cases = [
        // class, b, short range, long range (by hand: 0.02*99 = 1.98, 0.9*99 = 89.1, ...)
        (PcmaxClass::Nu1, (1, 1), (90, 100)),
        (PcmaxClass::Nu2, (1, 19), (900, 1000)),
        (PcmaxClass::Nu3, (1, 199), (9000, 10_000)),
    ];
    for (class, (s_lo, s_hi), (l_lo, l_hi)) in cases {
        for (n, short) in [(10, 0), (50, 1), (100, 2), (1000, 20)] {
            for seed in 0..5 {
                let t = times(class, n, 5, seed);
                let s = t.iter().filter(|&&x| (s_lo..=s_hi).contains(&x)).count();
                let l = t.iter().filter(|&&x| (l_lo..=l_hi).contains(&x)).count();
                assert_eq!(
                    (s, l),
                    (short, n - short),
                    "{class} n={n} seed {seed}: {t:?}"
                );
            }
        }
    }
}

#[test]
fn published_grids_match_the_papers_sizes() {
    use PcmaxClass::*;
    // França / Frangioni: n in {10, 50, 100, 500, 1000}, m in {5, 10, 25}, n > m (780 instances).
    let count = [10, 50, 100, 500, 1000]
        .iter()
        .flat_map(|&n| [5, 10, 25].map(|m| (n, m)))
        .filter(|&(n, m)| U1.published_grid(n, m))
        .count();
    assert_eq!(count, 13);
    assert!(!Nu1.published_grid(10, 10));
    // Lawrinenko: n/m in {2, 2.25, 2.5, 2.75, 3}.
    assert!(L1.published_grid(40, 20)); // 2
    assert!(L1.published_grid(100, 40)); // 2.5
    assert!(L7.published_grid(36, 16)); // 2.25
    assert!(L7.published_grid(198, 66)); // 3
    assert!(L7.published_grid(22, 8)); // 2.75
    assert!(!L1.published_grid(50, 25)); // n = 50 is not in any list
                                         // Berndt et al.
    assert!(E1R1To20.published_grid(25, 5) && !E1R1To20.published_grid(20, 5));
    assert!(E2R100To800.published_grid(100, 3) && !E2R100To800.published_grid(10, 4));
    assert!(E3R1To100.published_grid(52, 10) && !E3R1To100.published_grid(50, 10));
    assert!(E4R100To800.published_grid(9, 3) && !E4R100To800.published_grid(9, 2));
}

#[test]
fn class_names_round_trip_and_every_class_cites_a_source() {
    for class in PcmaxClass::ALL {
        assert_eq!(PcmaxClass::from_name(class.name()), Some(class));
        assert!(!class.source().is_empty());
    }
    assert_eq!(PcmaxClass::from_name("NU2"), Some(PcmaxClass::Nu2));
    assert_eq!(PcmaxClass::from_name("u4"), None);
}

#[test]
fn cli_writes_a_file_that_node_time_solves() {
    let f = tmp("e4.json");
    let _ = std::fs::remove_file(&f);
    let path = f.to_str().unwrap();
    let out = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "e4-1-100",
        "--jobs",
        "10",
        "--pads",
        "2",
        "--seed",
        "4",
        "-o",
        path,
    ]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("swarmplan node-time --file"), "{stderr}");
    // The file holds the library's times.
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&f).unwrap()).unwrap();
    let file_times: Vec<u64> = serde_json::from_value(v["charge_times_min"].clone()).unwrap();
    assert_eq!(file_times, times(PcmaxClass::E4R1To100, 10, 2, 4));
    assert_eq!(v["pads"], 2);
    // node-time reads it, and brute force agrees with exact.
    let exact = swarmplan(&["node-time", "--file", path, "--json"]);
    assert_eq!(exact.status.code(), Some(0), "{exact:?}");
    let brute = swarmplan(&["node-time", "--file", path, "--method", "brute", "--json"]);
    let e: serde_json::Value = serde_json::from_slice(&exact.stdout).unwrap();
    let b: serde_json::Value = serde_json::from_slice(&brute.stdout).unwrap();
    assert_eq!(e["status"], "optimal");
    assert_eq!(e["makespan_min"], b["makespan_min"]);
    // Same seed, same bytes on stdout; the file is not overwritten without --force.
    let a1 = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "l7",
        "--jobs",
        "40",
        "--pads",
        "20",
        "--seed",
        "2",
    ]);
    let a2 = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "l7",
        "--jobs",
        "40",
        "--pads",
        "20",
        "--seed",
        "2",
    ]);
    assert_eq!(a1.status.code(), Some(0));
    assert_eq!(a1.stdout, a2.stdout);
    let again = swarmplan(&[
        "generate",
        "node-time",
        "--class",
        "u1",
        "--jobs",
        "10",
        "--pads",
        "2",
        "--seed",
        "4",
        "-o",
        path,
    ]);
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("E0013"));
}

#[test]
fn cli_refuses_bad_parameters_with_codes_and_exit_2() {
    for (args, code) in [
        (
            [
                "--class", "u9", "--jobs", "10", "--pads", "2", "--seed", "1",
            ],
            "E3905",
        ),
        (
            ["--class", "u1", "--jobs", "0", "--pads", "2", "--seed", "1"],
            "E3906",
        ),
        (
            [
                "--class", "u1", "--jobs", "10", "--pads", "-1", "--seed", "1",
            ],
            "E3907",
        ),
        (
            [
                "--class", "u1", "--jobs", "10", "--pads", "2", "--seed", "x",
            ],
            "E3908",
        ),
    ] {
        let mut all = vec!["generate", "node-time"];
        all.extend_from_slice(&args);
        let out = swarmplan(&all);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(
            String::from_utf8_lossy(&out.stderr).contains(code),
            "{args:?}: {out:?}"
        );
    }
}
