//! The hop MILP written in CPLEX LP format (`eaas::exact::milp::write_lp`) on the hops of
//! `instances/eaas/known_optima.json`: its header, its size against the formula of
//! `models/eaas_milp.md`, the MILP optimum's schedule as a point of the file (checked by a small LP
//! reader here, not by the code under test), and with the `highs` feature the file read back and
//! solved by HiGHS to the known optimum.

mod common;

use common::model_files::{read_lp, Lp};
use common::{close, known_optima, tmp, Known, TOL};
use std::collections::HashMap;
use swarmplan::eaas::exact::milp::{lp_text, solve_milp, write_lp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactStatus, Objective, Reorder};
use swarmplan::eaas::HopProblem;
use swarmplan::problem::Role;
#[cfg(feature = "highs")]
use swarmplan::solver::MilpBackend;

fn options(reorder: Reorder, period_min: f64) -> MilpOptions {
    MilpOptions {
        period_min,
        reorder,
        time_limit_s: 60.0,
        ..MilpOptions::default()
    }
}

/// The header line starting with `key: `, without it.
fn header<'a>(lp: &'a Lp, key: &str) -> &'a str {
    lp.header
        .iter()
        .find_map(|h| h.strip_prefix(&format!("{key}: ")))
        .unwrap_or_else(|| panic!("no `{key}:` in the header {:#?}", lp.header))
}

/// Numbers of a text in order, such as `24 variables (14 binary)` -> [24, 14].
fn numbers(text: &str) -> Vec<f64> {
    text.split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .filter_map(|w| w.parse().ok())
        .collect()
}

/// A move of models/eaas_milp.md `(s, c, q, p)`, from the definition of `K` in `none`/`paper`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Move {
    s: usize,
    c: usize,
    q: usize,
    p: Option<usize>,
}

fn expected_moves(p: &HopProblem, reorder: Reorder) -> Vec<Move> {
    let n = p.drones.len();
    let dist = |a: usize, b: usize| (p.slots_m[a] - p.slots_m[b]).norm();
    let holder = |q: usize| (0..n).find(|&d| p.initial_slot[d] == q).unwrap();
    let mut out = Vec::new();
    for s in (0..n).filter(|&s| p.drones[s].role == Role::Support) {
        let qs = p.initial_slot[s];
        for c in (0..n).filter(|&c| p.drones[c].role == Role::Delivery) {
            let own = p.initial_slot[c];
            if dist(qs, own) <= p.range_m {
                out.push(Move {
                    s,
                    c,
                    q: own,
                    p: None,
                });
            } else if reorder == Reorder::Paper {
                for q in (0..n).filter(|&q| q != own && dist(qs, q) <= p.range_m) {
                    let h = holder(q);
                    if p.drones[h].role == Role::Delivery {
                        out.push(Move {
                            s,
                            c,
                            q,
                            p: Some(h),
                        });
                    }
                }
            }
        }
    }
    out
}

#[test]
fn lp_file_states_the_hop_and_has_the_size_of_the_model() {
    let mut failing = Vec::new();
    for k in known_optima().instances {
        let path = tmp(&format!("{}.lp", k.name));
        let about = format!("known optimum {}", k.name);
        let size = write_lp(
            &k.problem,
            &k.objective,
            &options(k.reorder, k.period_min),
            &about,
            &path,
        )
        .unwrap();
        let lp = read_lp(&std::fs::read_to_string(&path).unwrap());
        let p = &k.problem;
        let n = p.drones.len();
        let supports = (0..n)
            .filter(|&d| p.drones[d].role == Role::Support)
            .count();
        let delivery = n - supports;
        let tt: f64 = p.legs.iter().map(|l| l.duration_min).sum();
        let periods = (tt / k.period_min).ceil() as usize; // one leg per instance
        let mv = expected_moves(p, k.reorder);
        let pad_binaries = match k.objective {
            Objective::NodeTime(EndPads { pads, .. }) => {
                let m = pads.min(n);
                (0..n).map(|d| d.min(m - 1) + 1).sum()
            }
            _ => 0,
        };
        let binaries = mv.len() * periods + pad_binaries;
        // Rows with variables: per period one per support drone with a move, one per delivery
        // drone that can move, one battery balance per drone; one reserve per support drone
        // with a move; max-min: g <= b_d for every delivery drone.
        let with_move = |d: usize| mv.iter().any(|m| m.s == d || m.c == d || m.p == Some(d));
        let movers = (0..n).filter(|&d| with_move(d)).count();
        let sharing_supports = (0..n)
            .filter(|&d| p.drones[d].role == Role::Support && with_move(d))
            .count();
        let rows = periods * (movers + n)
            + sharing_supports
            + match k.objective {
                Objective::MaxMinArrival => delivery,
                _ => 0,
            };
        let mut check = |ok: bool, what: String| {
            if !ok {
                failing.push(format!("{}: {what}", k.name));
            }
        };
        check(
            header(&lp, "hop").starts_with(&about),
            format!("hop line {}", header(&lp, "hop")),
        );
        check(
            header(&lp, "reorder") == k.reorder.to_string(),
            "reorder line".into(),
        );
        check(
            numbers(header(&lp, "grid")) == vec![k.period_min, k.period_min, periods as f64],
            format!("grid line {}", header(&lp, "grid")),
        );
        check(
            lp.header
                .iter()
                .any(|h| h.contains("optimal over full-period schedules on this grid")),
            "no grid optimality note".into(),
        );
        let objective_line = header(&lp, "objective");
        let named = match k.objective {
            Objective::NodeTime(EndPads {
                pads,
                pad_rate_mah_per_min,
            }) => objective_line.starts_with(&format!(
                "node_time, pads = {pads}, pad_rate_mah_per_min = {pad_rate_mah_per_min}:"
            )),
            Objective::MaxMinArrival => objective_line.starts_with("max_min_arrival"),
            Objective::Feasible => objective_line.starts_with("feasible"),
        };
        check(named, format!("objective line {objective_line}"));
        let stated = numbers(header(&lp, "size"));
        check(
            stated[..3]
                == [
                    lp.bounds.len() as f64,
                    lp.generals.len() as f64,
                    lp.rows.len() as f64,
                ],
            format!("size line {stated:?} against the body"),
        );
        check(
            size.binaries == binaries && lp.generals.len() == binaries,
            format!(
                "{} binaries written, {} counted, {binaries} by the formula",
                size.binaries,
                lp.generals.len()
            ),
        );
        check(
            lp.generals
                .iter()
                .all(|g| lp.bounds.get(g) == Some(&(0.0, 1.0))),
            "an integer variable not in [0, 1]".into(),
        );
        if !matches!(k.objective, Objective::NodeTime(EndPads { .. })) {
            check(
                lp.rows.len() == rows,
                format!("{} rows, {rows} by the formula", lp.rows.len()),
            );
        }
        let last = format!("b_d{}_t{periods}", n - 1);
        for name in ["y_k0_t0", "b_d0_t1", last.as_str()] {
            check(lp.bounds.contains_key(name), format!("no variable {name}"));
        }
        let goal = match k.objective {
            Objective::NodeTime(EndPads { .. }) => Some(("M", false)),
            Objective::MaxMinArrival => Some(("g", true)),
            Objective::Feasible => None,
        };
        if let Some((g, maximise)) = goal {
            check(
                lp.objective == vec![(1.0, g.to_string())] && lp.maximise == maximise,
                format!("objective {:?}", lp.objective),
            );
        }
    }
    assert!(failing.is_empty(), "failing:\n{}", failing.join("\n"));
}

/// The value of every variable of the file at the schedule of a MILP optimum: `y` from its
/// transfers, `b` integrated period by period, `g` the lowest delivery arrival battery.
fn point_of(k: &Known, lp: &Lp, transfers: &[swarmplan::eaas::Transfer]) -> HashMap<String, f64> {
    let p = &k.problem;
    let n = p.drones.len();
    let mv: Vec<Move> = lp
        .header
        .iter()
        .filter_map(|h| h.trim().strip_prefix('k'))
        .map(|h| {
            let f: Vec<&str> = h.split_whitespace().collect();
            let num = |s: &str| s[1..].parse::<usize>().unwrap();
            Move {
                s: num(f[1]),
                c: num(f[2]),
                q: num(f[3]),
                p: f.get(4).map(|x| num(x)),
            }
        })
        .collect();
    assert_eq!(mv, expected_moves(p, k.reorder), "moves in the header");
    let leg = &p.legs[0];
    let periods = (leg.duration_min / k.period_min).ceil() as usize;
    let h = leg.duration_min / periods as f64;
    let mut x = HashMap::new();
    let mut b: Vec<f64> = p.drones.iter().map(|d| d.battery_mah).collect();
    for t in 0..periods {
        let mid = (t as f64 + 0.5) * h;
        let mut slot = p.initial_slot.clone();
        let mut delta = vec![0.0; n];
        for (i, m) in mv.iter().enumerate() {
            let on = transfers.iter().any(|x| {
                x.support == m.s
                    && x.consumer == m.c
                    && x.consumer_slot == m.q
                    && x.start_min < mid
                    && mid < x.end_min
            });
            x.insert(format!("y_k{i}_t{t}"), if on { 1.0 } else { 0.0 });
            if on {
                slot[m.c] = m.q;
                if let Some(q) = m.p {
                    slot[q] = p.initial_slot[m.c];
                }
                delta[m.c] += p.rho_mah_per_min * h;
                delta[m.s] -= p.rho_mah_per_min * h;
            }
        }
        for d in 0..n {
            b[d] += delta[d] - h * leg.rate_mah_per_min[d][slot[d]];
            x.insert(format!("b_d{d}_t{}", t + 1), b[d]);
        }
    }
    let g = (0..n)
        .filter(|&d| p.drones[d].role == Role::Delivery)
        .map(|d| b[d])
        .fold(f64::INFINITY, f64::min);
    x.insert("g".into(), g);
    x
}

#[test]
fn the_milp_optimum_is_a_point_of_the_lp_file_with_the_same_objective() {
    // Max-min and feasibility hops: their variables are all fixed by the schedule.
    let mut checked = 0;
    for k in known_optima().instances {
        if matches!(k.objective, Objective::NodeTime(EndPads { .. })) {
            continue;
        }
        let opt = options(k.reorder, k.period_min);
        let (text, _) = lp_text(&k.problem, &k.objective, &opt, &k.name).unwrap();
        let lp = read_lp(&text);
        let o = solve_milp(&k.problem, &k.objective, &opt).unwrap();
        assert_eq!(o.status, ExactStatus::Optimal, "{}", k.name);
        let x = point_of(&k, &lp, &o.transfers);
        assert_eq!(
            x.len() - 1 + usize::from(k.objective != Objective::Feasible),
            lp.bounds.len()
        );
        let value = |terms: &[(f64, String)]| -> f64 {
            terms
                .iter()
                .map(|(c, name)| c * x.get(name).copied().unwrap_or_else(|| panic!("{name}")))
                .sum()
        };
        for (name, (lo, up)) in &lp.bounds {
            let v = x[name];
            assert!(v >= lo - TOL && v <= up + TOL, "{}: {name} = {v}", k.name);
        }
        for (i, (terms, op, rhs)) in lp.rows.iter().enumerate() {
            let v = value(terms);
            let ok = match op.as_str() {
                "<=" => v <= rhs + TOL,
                "=" => close(v, *rhs),
                ">=" => v >= rhs - TOL,
                _ => false,
            };
            assert!(ok, "{}: row c{i}: {v} {op} {rhs}", k.name);
        }
        if k.objective == Objective::MaxMinArrival {
            assert!(close(value(&lp.objective), k.optimum), "{}", k.name);
            assert!(close(value(&lp.objective), o.model_objective.unwrap()));
        }
        checked += 1;
    }
    assert!(checked >= 2, "{checked} instances checked");
}

#[test]
fn lp_export_rejects_a_bad_grid_with_its_code() {
    let k = &known_optima().instances[0];
    let err = lp_text(&k.problem, &k.objective, &options(k.reorder, 0.0), "x").unwrap_err();
    assert!(err.to_string().contains("E4101"), "{err}");
    let mut still = k.problem.clone();
    still.legs[0].duration_min = 0.0;
    let err = lp_text(&still, &k.objective, &options(k.reorder, 1.0), "x").unwrap_err();
    assert!(err.to_string().contains("E4116"), "{err}");
}

/// HiGHS reads the written file and solves it; its optimum is the known optimum and the model
/// objective of `solve_milp` on every backend, also with `free` re-ordering.
#[cfg(feature = "highs")]
#[test]
fn highs_reads_the_lp_file_and_finds_the_known_optimum() {
    use std::ffi::CString;
    #[allow(unsafe_code)]
    fn solve_file(path: &std::path::Path) -> (highs_sys::HighsInt, f64) {
        let file = CString::new(path.to_str().unwrap()).unwrap();
        let key = |s: &str| CString::new(s).unwrap();
        // SAFETY: one HiGHS instance, created and destroyed here, used from this thread only;
        // every string passed is a valid NUL-terminated C string that outlives the call.
        unsafe {
            let h = highs_sys::Highs_create();
            assert!(!h.is_null());
            highs_sys::Highs_setBoolOptionValue(h, key("output_flag").as_ptr(), 0);
            highs_sys::Highs_setDoubleOptionValue(h, key("mip_rel_gap").as_ptr(), 1e-9);
            highs_sys::Highs_setDoubleOptionValue(h, key("mip_abs_gap").as_ptr(), 0.0);
            let read = highs_sys::Highs_readModel(h, file.as_ptr());
            assert_eq!(read, highs_sys::STATUS_OK, "HiGHS could not read {path:?}");
            let run = highs_sys::Highs_run(h);
            assert_ne!(run, highs_sys::STATUS_ERROR);
            let status = highs_sys::Highs_getModelStatus(h);
            let value = highs_sys::Highs_getObjectiveValue(h);
            highs_sys::Highs_destroy(h);
            (status, value)
        }
    }
    let mut failing = Vec::new();
    for k in known_optima().instances {
        for reorder in [k.reorder, Reorder::Free] {
            let opt = options(reorder, k.period_min);
            let path = tmp(&format!("{}-{}.lp", k.name, reorder));
            write_lp(&k.problem, &k.objective, &opt, &k.name, &path).unwrap();
            let (status, value) = solve_file(&path);
            if status != highs_sys::MODEL_STATUS_OPTIMAL {
                failing.push(format!(
                    "{} {}: HiGHS status {status}",
                    k.name,
                    reorder.to_string()
                ));
                continue;
            }
            if reorder == k.reorder && !close(value, k.optimum) {
                failing.push(format!("{}: {value}, known {}", k.name, k.optimum));
            }
            for backend in MilpBackend::all() {
                let o =
                    solve_milp(&k.problem, &k.objective, &MilpOptions { backend, ..opt }).unwrap();
                let model = o.model_objective.unwrap();
                if o.status != ExactStatus::Optimal || !close(value, model) {
                    failing.push(format!(
                        "{} {} on {}: file {value}, solve_milp {:?} {model}",
                        k.name,
                        reorder.to_string(),
                        backend.to_string(),
                        o.status
                    ));
                }
            }
        }
    }
    // A hop of the shipped instance (r00001's last hop: 11 legs, 16 periods of uneven length,
    // max-min): the file's optimum is the bound (the model objective) of `eaas --methods milp`.
    let path = tmp("r00001-9.lp");
    let out = common::eaas_r00001(
        "9",
        "milp",
        &[
            "--json",
            "--backend",
            "highs",
            "--write-lp",
            path.to_str().unwrap(),
            "--force",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let milp = &report["rows"][0];
    assert_eq!(milp["status"], "optimal");
    let (status, value) = solve_file(&path);
    assert_eq!(status, highs_sys::MODEL_STATUS_OPTIMAL);
    let model = milp["bound"].as_f64().unwrap();
    if !close(value, model) {
        failing.push(format!("r00001 hop 9: file {value}, eaas milp {model}"));
    }
    assert!(failing.is_empty(), "failing:\n{}", failing.join("\n"));
}
