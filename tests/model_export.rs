//! Models written as files: the node-time MILP in CPLEX LP and free MPS
//! (`node_time::write_model`, `node-time --write-lp`) and the hop MILP in free MPS
//! (`eaas::exact::milp::write_lp` with a `.mps` name). Each file is read back by the small readers of
//! `tests/common/model_files.rs` and compared with the model of `models/node_time.md` written out
//! by hand, its size counted by hand, and its optimum found by enumerating the file's binaries.

mod common;

use common::model_files::{read_lp, read_mps, Lp, Terms};
use common::{known_optima, stderr, swarmplan, tmp};
use swarmplan::eaas::exact::milp::{write_lp, MilpOptions};
use swarmplan::node_time::write_model;
use swarmplan::solver::lp_file::ModelFormat;

fn terms(pairs: &[(f64, &str)]) -> Terms {
    pairs.iter().map(|&(c, n)| (c, n.to_string())).collect()
}

/// Writes the node-time model of `pads` and `times` under `name.{ext}` and reads it back.
fn node_time_file(pads: usize, times: &[f64], name: &str, ext: &str) -> Lp {
    let path = tmp(&format!("{name}.{ext}"));
    let (_, format) = write_model(pads, times, "test", &path).unwrap();
    let expected = if ext == "mps" {
        ModelFormat::Mps
    } else {
        ModelFormat::Lp
    };
    assert_eq!(format, expected, "{ext}");
    let text = std::fs::read_to_string(&path).unwrap();
    if ext == "mps" {
        read_mps(&text)
    } else {
        read_lp(&text)
    }
}

/// The least `C` over every 0/1 value of the file's integer columns that satisfies its rows, for
/// the node-time model (one continuous column `C`, in the load rows with coefficient -1).
fn optimum_by_enumeration(lp: &Lp) -> f64 {
    let binaries = &lp.generals;
    assert!(binaries.len() <= 16, "too many binaries to enumerate");
    let mut best = f64::INFINITY;
    for mask in 0u32..(1 << binaries.len()) {
        let value = |name: &str| {
            let i = binaries.iter().position(|b| b == name).unwrap();
            f64::from((mask >> i) & 1)
        };
        // The least C this assignment allows, or none when an equality fails.
        let mut c_min = lp.bounds["C"].0;
        let mut feasible = true;
        for (row, op, rhs) in &lp.rows {
            let rest: f64 = row
                .iter()
                .filter(|(_, n)| n != "C")
                .map(|(a, n)| a * value(n))
                .sum();
            match op.as_str() {
                "=" => feasible &= (rest - rhs).abs() < 1e-9,
                // rest - C <= rhs
                "<=" => c_min = c_min.max(rest - rhs),
                _ => panic!("row {op}"),
            }
        }
        if feasible {
            best = best.min(c_min);
        }
    }
    best
}

#[test]
fn node_time_milp_files_are_the_model_written_out_by_hand() {
    // 2 pads, times 3, 5, 4 min: the jobs by decreasing time are 5 (drone 1), 4 (drone 2) and
    // 3 (drone 0); x_j{j}_i{i} for i <= min(j, 1).
    let x = ["x_j0_i0", "x_j1_i0", "x_j1_i1", "x_j2_i0", "x_j2_i1"];
    for ext in ["lp", "mps"] {
        let lp = node_time_file(2, &[3.0, 5.0, 4.0], "node_time_hand", ext);
        assert!(!lp.maximise, "{ext}");
        assert_eq!(lp.objective, terms(&[(1.0, "C")]), "{ext}");
        let rows = vec![
            (terms(&[(1.0, x[0])]), "=".to_string(), 1.0),
            (terms(&[(1.0, x[1]), (1.0, x[2])]), "=".to_string(), 1.0),
            (terms(&[(1.0, x[3]), (1.0, x[4])]), "=".to_string(), 1.0),
            (
                terms(&[(-1.0, "C"), (5.0, x[0]), (4.0, x[1]), (3.0, x[3])]),
                "<=".to_string(),
                0.0,
            ),
            (
                terms(&[(-1.0, "C"), (4.0, x[2]), (3.0, x[4])]),
                "<=".to_string(),
                0.0,
            ),
        ];
        assert_eq!(lp.rows, rows, "{ext}");
        assert_eq!(lp.generals, x, "{ext}");
        assert_eq!(lp.bounds.len(), 6, "{ext}");
        assert_eq!(lp.bounds["C"], (0.0, f64::INFINITY), "{ext}");
        for b in x {
            assert_eq!(lp.bounds[b], (0.0, 1.0), "{ext}: {b}");
        }
        for line in [
            "  job 0 = drone 1, p = 5",
            "  job 1 = drone 2, p = 4",
            "  job 2 = drone 0, p = 3",
            "size: 6 variables (5 binary), 5 constraints",
        ] {
            assert!(lp.header.iter().any(|h| h == line), "{ext}: no `{line}`");
        }
        // 5 | 4 + 3 = 7; the other splits give 5 + 4 = 9 or 5 + 3 = 8 or all 12 on one pad.
        assert_eq!(optimum_by_enumeration(&lp), 7.0, "{ext}");
    }
}

#[test]
fn node_time_milp_files_have_the_size_counted_by_hand() {
    // (pads, times, (variables 1 + sum_j (min(j, m - 1) + 1), binaries, rows n + m), optimum)
    type Case<'a> = (usize, &'a [f64], (usize, usize, usize), f64);
    let cases: [Case; 3] = [
        // m = 3: 1 + 1 + 2 + 3 + 3 + 3; {60}, {50, 20}, {40, 30}: 70. Below 70, 60 is alone
        // (60 + 20 > 69) and 140 does not fit on two pads of at most 69.
        (3, &[60.0, 50.0, 40.0, 30.0, 20.0], (13, 12, 8), 70.0),
        // m = min(5, 3) = 3: 1 + 1 + 2 + 3; one drone a pad: the longest, 9.
        (5, &[2.0, 9.0, 4.0], (7, 6, 6), 9.0),
        // m = 1: 1 + 4; one pad charges all: 1 + 2 + 3 + 4 = 10.
        (1, &[1.0, 2.0, 3.0, 4.0], (5, 4, 5), 10.0),
    ];
    let mut failing = Vec::new();
    for (pads, times, counted, optimum) in cases {
        for ext in ["lp", "mps"] {
            let lp = node_time_file(pads, times, &format!("node_time_{pads}"), ext);
            let got = (lp.bounds.len(), lp.generals.len(), lp.rows.len());
            if got != counted {
                failing.push(format!("k={pads} {ext}: {got:?}, by hand {counted:?}"));
            }
            let best = optimum_by_enumeration(&lp);
            if best != optimum {
                failing.push(format!("k={pads} {ext}: optimum {best}, by hand {optimum}"));
            }
        }
    }
    assert!(failing.is_empty(), "failing:\n{}", failing.join("\n"));
}

/// Every known-optimum hop's MILP in free MPS is the model of its CPLEX LP file (written by
/// `lp_solvers`' writer, read by the other reader): same objective, rows, bounds, integers and
/// header.
#[test]
fn hop_milp_mps_file_is_the_model_of_its_lp_file() {
    let mut failing = Vec::new();
    for k in known_optima().instances {
        let options = MilpOptions {
            period_min: k.period_min,
            reorder: k.reorder,
            time_limit_s: 60.0,
            ..MilpOptions::default()
        };
        let read = |ext: &str| {
            let path = tmp(&format!("{}.{ext}", k.name));
            let size = write_lp(&k.problem, &k.objective, &options, "test", &path).unwrap();
            (size, std::fs::read_to_string(&path).unwrap())
        };
        let ((lp_size, lp_text), (mps_size, mps_text)) = (read("lp"), read("mps"));
        let (lp, mps) = (read_lp(&lp_text), read_mps(&mps_text));
        let mut check = |ok: bool, what: &str| {
            if !ok {
                failing.push(format!("{}: {what}", k.name));
            }
        };
        check(lp_size == mps_size, "sizes");
        check(lp.maximise == mps.maximise, "sense");
        // An empty objective (feasibility) is `+0 x` in the LP file, no entry in the MPS file.
        let nonzero = |t: &Terms| t.iter().filter(|e| e.0 != 0.0).cloned().collect::<Terms>();
        check(
            nonzero(&lp.objective) == nonzero(&mps.objective),
            "objective",
        );
        check(lp.rows == mps.rows, "rows");
        check(lp.bounds == mps.bounds, "bounds");
        check(lp.generals == mps.generals, "integers");
        // lp_solvers ends the LP header with the model's name.
        check(lp.header[..lp.header.len() - 1] == mps.header[..], "header");
        check(!mps.rows.is_empty(), "no rows");
    }
    assert!(failing.is_empty(), "failing:\n{}", failing.join("\n"));
}

#[test]
fn node_time_cli_writes_the_format_of_the_file_name() {
    let write = |path: &std::path::Path| {
        let file = path.to_str().unwrap();
        let args = [
            "node-time",
            "--pads",
            "2",
            "--times",
            "3,5,4",
            "--method",
            "lpt",
        ];
        swarmplan(&[&args[..], &["--write-lp", file, "--force"]].concat())
    };
    let path = tmp("cli_node_time.mps");
    let out = write(&path);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let said = stderr(&out);
    assert!(said.contains("wrote free MPS file"), "{said}");
    let mps = read_mps(&std::fs::read_to_string(&path).unwrap());
    assert_eq!((mps.bounds.len(), mps.rows.len()), (6, 5));
    // A folder that does not exist: E0010, exit code 2.
    let out = write(&tmp("no-such-folder/x.lp"));
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("E0010"), "{}", stderr(&out));
}
