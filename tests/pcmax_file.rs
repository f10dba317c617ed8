//! P||Cmax instances in the published text format (`problem::pcmax_file`, `node-time
//! --instance`): the shipped example read as written, its optimum by hand and by brute force
//! here, the layout's variants, and every malformed file as a coded error (exit code 2).

mod common;

use common::{repo_arg, repo_path, stderr, swarmplan, write_tmp};
use swarmplan::node_time::{exact, Limits};
use swarmplan::problem::pcmax_file::{parse_pcmax, read_pcmax};
use swarmplan::solver::SolveStatus;

const SHIPPED: &str = "instances/node_time/pcmax-u1-n10-m3-seed1.txt";

/// The least makespan over every assignment of `times` to `pads` machines.
fn brute_force(pads: usize, times: &[f64]) -> f64 {
    let n = times.len() as u32;
    let mut best = f64::INFINITY;
    for code in 0..(pads as u64).pow(n) {
        let mut loads = vec![0.0; pads];
        let mut rest = code;
        for &p in times {
            loads[(rest % pads as u64) as usize] += p;
            rest /= pads as u64;
        }
        best = best.min(loads.into_iter().fold(0.0, f64::max));
    }
    best
}

#[test]
fn shipped_pcmax_file_reads_as_written_and_its_optimum_is_177() {
    let i = read_pcmax(&repo_path(SHIPPED)).unwrap();
    // The file: 3, 10, then the ten times below, one a line.
    let times = [2.0, 96.0, 86.0, 67.0, 34.0, 65.0, 52.0, 11.0, 36.0, 81.0];
    assert_eq!(i.pads, 3);
    assert_eq!(i.charge_times_min, times);
    // By hand: ceil(530 / 3) = 177 is a lower bound, and {2, 86, 52, 36} = 176,
    // {96, 81} = 177, {67, 34, 65, 11} = 177 attains it.
    assert_eq!(times.iter().sum::<f64>(), 530.0);
    assert_eq!(brute_force(3, &times), 177.0);
    let solved = exact(i.pads, &i.charge_times_min, &Limits::default()).unwrap();
    assert_eq!(solved.makespan_min, 177.0);
    assert_eq!(solved.status, SolveStatus::Optimal);
    let out = swarmplan(&["node-time", "--instance", &repo_arg(SHIPPED), "--json"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["makespan_min"], 177.0);
    assert_eq!(json["status"], "optimal");
}

#[test]
fn pcmax_layout_reads_the_same_on_any_lines() {
    let one_a_line = parse_pcmax("3\n5\n60\n50\n40\n30\n20\n", "a").unwrap();
    let packed = parse_pcmax("3 5\n60 50 40\n  30\t20", "b").unwrap();
    assert_eq!(one_a_line, packed);
    assert_eq!(packed.pads, 3);
    assert_eq!(packed.charge_times_min, [60.0, 50.0, 40.0, 30.0, 20.0]);
}

#[test]
fn malformed_pcmax_files_give_coded_errors_naming_the_field() {
    // (file text, every code expected in order, a part of each field)
    let cases: [(&str, &[(&str, &str)]); 6] = [
        ("", &[("E5009", "x: m"), ("E5009", "x: n")]),
        ("0\n3\n1\n2\n3\n", &[("E5009", "x: m")]),
        ("2\nthree\n1\n2\n3\n", &[("E5009", "x: n")]),
        ("2\n3\n1\n2\n", &[("E5010", "x: p")]),
        ("2\n3\n1\nabc\n2\n", &[("E5010", "x: p[2] (line 4)")]),
        (
            "2\n3\n1\nabc\n2\n?\n",
            &[("E5010", "x: p[2] (line 4)"), ("E5010", "x: p[3] (line 6)")],
        ),
    ];
    let mut failing = Vec::new();
    for (text, expected) in cases {
        match parse_pcmax(text, "x") {
            Ok(i) => failing.push(format!("{text:?}: read as {i:?}")),
            Err(swarmplan::error::Error::Invalid(v)) => {
                let got: Vec<(&str, String)> =
                    v.iter().map(|v| (v.code, v.field.clone())).collect();
                let want: Vec<(&str, String)> =
                    expected.iter().map(|&(c, f)| (c, f.to_string())).collect();
                if got != want {
                    failing.push(format!("{text:?}: {got:?}, expected {want:?}"));
                }
            }
            Err(e) => failing.push(format!("{text:?}: {e}")),
        }
    }
    assert!(failing.is_empty(), "failing:\n{}", failing.join("\n"));
}

#[test]
fn node_time_instance_errors_exit_2_with_their_codes() {
    let cases = [
        (write_tmp("bad_count.txt", b"2\n3\n1\n2\n"), "E5010"),
        // Read, then the node-time rules: a negative charge time.
        (write_tmp("negative.txt", b"2\n2\n-1\n3\n"), "E5003"),
        (
            repo_path("instances/node_time/no-such-file.txt")
                .to_str()
                .unwrap()
                .to_string(),
            "E0008",
        ),
    ];
    for (file, code) in cases {
        let out = swarmplan(&["node-time", "--instance", &file]);
        assert_eq!(out.status.code(), Some(2), "{file}: {}", stderr(&out));
        assert!(stderr(&out).contains(code), "{file}: {}", stderr(&out));
        assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
    }
    // --instance stands instead of --pads/--times and --file.
    let out = swarmplan(&["node-time", "--instance", &repo_arg(SHIPPED), "--pads", "2"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}
