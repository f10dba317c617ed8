//! `swarmplan node-time`: the node time of one recharging stop (pad-to-drone assignment, P||Cmax).
//!
//! ```text
//! swarmplan node-time --pads 3 --times 60,50,40,30,20
//! swarmplan node-time --file stop.json --method milp --backend microlp --time-limit 10 --json
//! swarmplan node-time --pads 3 --times 60,50,40,30,20 --write-lp stop.mps --method lpt
//! swarmplan node-time --instance instances/node_time/pcmax-u1-n10-m3-seed1.txt
//! ```
//! where `stop.json` is `{"pads": 3, "charge_times_min": [60, 50, 40, 30, 20]}` and `--instance`
//! reads the published P||Cmax text format ([`crate::problem::pcmax_file`]).

use crate::error::{Error, Result, Violation};
use crate::human::round;
use crate::node_time::{self, Limits, NodeTimeMethod, NodeTimeSolution};
use crate::problem::io::read_json;
use crate::solver::{MilpBackend, SolveStatus};
use serde::Deserialize;
use std::path::PathBuf;

/// Arguments of `swarmplan node-time`.
#[derive(Debug, clap::Args)]
pub struct NodeTimeArgs {
    /// Number of identical charging pads at the node (with --times).
    #[arg(
        long,
        required_unless_present_any = ["file", "instance"],
        conflicts_with_all = ["file", "instance"],
        value_parser = parse_pads,
        allow_negative_numbers = true
    )]
    pub pads: Option<usize>,
    /// Charge time of each drone in minutes, comma-separated, e.g. 60,50,40.
    #[arg(
        long,
        required_unless_present_any = ["file", "instance"],
        conflicts_with_all = ["file", "instance"],
        allow_hyphen_values = true
    )]
    pub times: Option<String>,
    /// JSON file `{"pads": K, "charge_times_min": [...]}` instead of --pads and --times.
    #[arg(long, conflicts_with = "instance")]
    pub file: Option<PathBuf>,
    /// A P||Cmax instance in the published benchmark text format (m machines = pads, n jobs,
    /// then the n processing times = charge times, min) instead of --pads and --times.
    #[arg(long, value_name = "FILE")]
    pub instance: Option<PathBuf>,
    /// Method: exact branch and bound, MILP, LPT heuristic, or the paper's brute force.
    #[arg(long, value_enum, default_value_t = NodeTimeMethod::Exact)]
    pub method: NodeTimeMethod,
    /// MILP backend (with --method milp).
    #[arg(
        long,
        value_parser = super::inputs::backend_value_parser(),
        default_value_t = MilpBackend::default()
    )]
    pub backend: MilpBackend,
    /// Time limit in seconds, at most 1e6; a stopped solve reports its incumbent as `feasible`
    /// with its lower bound.
    #[arg(long, allow_negative_numbers = true, default_value_t = 10.0)]
    pub time_limit: f64,
    /// Node limit of the search (branch-and-bound nodes, the same on every machine); a solve it
    /// stops reports its incumbent as `feasible` with its lower bound and gap [default: none].
    #[arg(long, value_name = "N")]
    pub node_limit: Option<u64>,
    /// Write the assignment MILP of `--method milp` for this instance (free MPS when FILE ends
    /// in `.mps`, CPLEX LP otherwise) before solving with the method asked for.
    #[arg(long, value_name = "FILE")]
    pub write_lp: Option<PathBuf>,
    /// Overwrite the `--write-lp` file when it exists (E0013 otherwise).
    #[arg(long)]
    pub force: bool,
    /// Print the result as JSON on stdout.
    #[arg(long)]
    pub json: bool,
}

/// `--pads`: a whole number; a negative one is E5001 (0 pads is E5001 too, from
/// [`node_time::validate`], with the other problems of the instance).
fn parse_pads(s: &str) -> std::result::Result<usize, Box<dyn std::error::Error + Send + Sync>> {
    match s.trim().parse::<usize>() {
        Ok(n) => Ok(n),
        Err(_) if s.trim().parse::<i64>().is_ok() => Err(Violation::new(
            "E5001",
            "--pads",
            format!("{s} is negative"),
            "give the number of pads at the node, at least 1",
        )
        .into()),
        Err(e) => Err(e.into()),
    }
}

/// Node-time instance file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NodeTimeFile {
    /// Optional schema version; only 1 exists.
    #[serde(default)]
    pub schema_version: Option<u32>,
    /// Number of pads `k`.
    pub pads: usize,
    /// Charge time of each drone, minutes.
    pub charge_times_min: Vec<f64>,
}

/// Runs the subcommand; returns the exit code.
pub fn run(args: NodeTimeArgs) -> Result<i32> {
    if let Some(path) = &args.write_lp {
        let inputs: Vec<&std::path::Path> = [&args.file, &args.instance]
            .into_iter()
            .flatten()
            .map(std::path::PathBuf::as_path)
            .collect();
        super::distinct_from_inputs(&[path], &inputs)?;
        super::may_write(path, args.force)?;
    }
    let (pads, times) = match (&args.file, &args.instance) {
        (_, Some(path)) => {
            let i = crate::problem::pcmax_file::read_pcmax(path)?;
            (i.pads, i.charge_times_min)
        }
        (Some(path), None) => {
            let f: NodeTimeFile = read_json(path)?;
            if let Some(v) = f.schema_version.filter(|&v| v != 1) {
                return Err(Error::invalid(
                    "E5008",
                    "schema_version",
                    format!("schema version {v} is not known"),
                    "use schema_version 1 or leave it out",
                ));
            }
            (f.pads, f.charge_times_min)
        }
        (None, None) => {
            let pads = args.pads.unwrap_or(0);
            match super::inputs::parse_list(args.times.as_deref().unwrap_or(""), "--times", "E5007")
            {
                Ok(times) => (pads, times),
                Err(Error::Invalid(mut violations)) => {
                    // Report the pad count's problems together with the unreadable times.
                    if let Err(Error::Invalid(more)) = node_time::validate(pads, &[0.0]) {
                        violations.extend(more);
                    }
                    return Err(Error::Invalid(violations));
                }
                Err(e) => return Err(e),
            }
        }
    };
    if let Some(path) = &args.write_lp {
        let about = format!("{} drones on {pads} pads", times.len());
        let (size, format) = node_time::write_model(pads, &times, &about, path)?;
        eprintln!(
            "wrote {} file {}: {} variables ({} binary), {} constraints",
            format.name(),
            path.display(),
            size.variables,
            size.binaries,
            size.constraints
        );
    }
    let limits = Limits {
        time_limit_s: Some(args.time_limit),
        node_limit: args.node_limit,
    };
    let spinner = (args.method != NodeTimeMethod::Lpt).then(|| {
        super::progress::spinner(format!(
            "node time of {} drones on {pads} pads",
            times.len()
        ))
    });
    let mut solution = node_time::solve(args.method, args.backend, pads, &times, &limits)?;
    if solution.status == SolveStatus::Feasible {
        lift_bound(&mut solution, pads, &times, &limits);
    }
    drop(spinner);
    if args.json {
        crate::cli::print_json(&node_time::NodeTimeReport::new(pads, &times, solution))?;
    } else {
        print_human(&solution, &times, args.backend)?;
    }
    Ok(0)
}

/// A solve that stopped (or a heuristic) gets the best bound there is: the bin-packing LP's
/// (`models/node_time.md`, "LP bound") when it is above the method's own; equal to the
/// makespan, it proves the assignment optimal. The LP bound has a budget of its own: the time
/// limit given, at least 1 s, and no node limit (its work is bounded anyway: a bisection of
/// column generations, each of at most 200 LPs; 0.25 s on 100 drones and 40 pads).
fn lift_bound(solution: &mut NodeTimeSolution, pads: usize, times: &[f64], limits: &Limits) {
    let lp_limits = Limits {
        time_limit_s: Some(limits.time_limit_s.unwrap_or(1.0).max(1.0)),
        node_limit: None,
    };
    let Ok(lp) = node_time::lp_lower_bound(pads, times, &lp_limits) else {
        return;
    };
    let lp = lp.min(solution.makespan_min);
    if lp > solution.lower_bound_min {
        solution.lower_bound_min = lp;
    }
    if solution.lower_bound_min >= solution.makespan_min {
        solution.status = SolveStatus::Optimal;
    }
}

fn print_human(s: &NodeTimeSolution, times: &[f64], backend: MilpBackend) -> Result<()> {
    let status = match s.status {
        SolveStatus::Optimal => "optimal",
        SolveStatus::Feasible => "feasible, not proven optimal",
        SolveStatus::Infeasible => "infeasible",
    };
    let method = if s.method == NodeTimeMethod::Milp {
        format!("milp on {}", backend)
    } else {
        s.method.to_string().to_string()
    };
    // Minutes to two places (0.6 s), as `solve` prints them; --json keeps every digit.
    let min = |x: f64| round(x, 2);
    outln!(
        "node time: {} min ({status}; method {method})",
        min(s.makespan_min)
    );
    outln!("lower bound: {} min", min(s.lower_bound_min));
    if let Some(g) = s.gap().filter(|_| s.status == SolveStatus::Feasible) {
        let why = if s.method == NodeTimeMethod::Lpt {
            "LPT is a heuristic"
        } else {
            "the solve stopped at its limit"
        };
        outln!(
            "gap: {} against the lower bound ({why}; the bound is the best of the method's and \
             the bin-packing LP's)",
            g.relative.map_or("n/a (bound 0)".to_string(), |r| {
                crate::human::gap_percent(r, 4)
            })
        );
    }
    for (i, pad) in s.assignment.iter().enumerate() {
        let load: f64 = pad.iter().map(|&j| times[j]).sum();
        let drones: Vec<String> = pad
            .iter()
            .map(|&j| format!("{j} ({} min)", min(times[j])))
            .collect();
        outln!(
            "pad {i}: load {} min: drones {}",
            min(load),
            drones.join(", ")
        );
    }
    outln!("solve time: {:.3} ms", s.solve_ms);
    Ok(())
}
