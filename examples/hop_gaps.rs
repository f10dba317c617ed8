//! Per-hop optimality gaps of the sharing heuristics PB and FB on the hops of planned requests,
//! against the hop MILP (`models/eaas_milp.md`) and the fluid LP bound (`models/eaas_fluid.md`),
//! and the direct hops to the destination that only an optimal schedule flies.
//!
//! ```text
//! cargo run --release --example hop_gaps -- [--profile F] [--network F] [--requests F] \
//!     [--limit N] [--time-limit S] [--period-min X] [--backend B] [--threads T] [--csv FILE]
//! ```
//!
//! Defaults: the `fast-sharing` profile, the paper-195 network, its first 1,000 requests, 3 s per
//! MILP, a 1-minute grid, one thread, no time budget.
//!
//! Each request is planned with PB and with FB (Algorithm 1, sequential route, location-aware
//! positions; both policies fly the swarm with support drones of the redundancy table). For every
//! hop ending at a stop, the hop's sharing problem is rebuilt from its path and departure batteries
//! (as `swarmplan eaas` does) and three node times are compared: the heuristic's (from the plan),
//! the MILP optimum over whole-period schedules on the grid (`Reorder::Paper`) and the fluid LP
//! bound. Gaps `(heuristic - reference) / reference` are kept apart by the reference's kind:
//! `optimal` (MILP proven optimal), `incumbent` (MILP stopped by the time limit) and `bound`
//! (fluid LP). A heuristic's transfers start and end off the grid, so it can beat the grid optimum:
//! negative gaps against the MILP are shown as they are.
//!
//! Flyable only with an optimal schedule: at every step of a plan that did not fly straight to the
//! destination (the source and every stop before the last hop, and the node of a dead end), the
//! direct hop to the destination (Algorithm 1, lines 5-10) failed under the policy, with full
//! batteries. It is tested with the fluid LP (`Feasible`: infeasible proves that no schedule at all
//! flies it) and, when the LP does not rule it out, with the MILP `Feasible` objective: a schedule
//! found is a hop the optimal schedule flies and the heuristic does not.
//!
//! Time limits are wall-clock: on a loaded machine a MILP stopped by the limit may be proven
//! optimal on an idle one. The per-hop CSV (`--csv`) has one row per hop and one per direct test.

use clap::Parser;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::{Context, PlanOptions, PlanOutcome, Planner, RouteMethod};
use swarmplan::eaas::exact::fluid;
use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
use swarmplan::eaas::exact::EndPads;
use swarmplan::eaas::exact::{ExactStatus, Objective, Reorder};
use swarmplan::eaas::{simulate_with, HopProblem, PolicyOptions, SharingPolicy};
use swarmplan::error::Result;
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;
use swarmplan::problem::Instance;
use swarmplan::problem::Request;
use swarmplan::solver::MilpBackend;

/// Per-hop gaps of PB and FB against the hop MILP and the fluid LP bound.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long, value_name = "FILE")]
    requests: Option<PathBuf>,
    /// Number of requests, from the start of the file.
    #[arg(long, default_value_t = 1000)]
    limit: usize,
    /// Time limit of each MILP and LP solve, seconds.
    #[arg(long, default_value_t = 3.0)]
    time_limit: f64,
    /// Longest period of the MILP's grid, minutes.
    #[arg(long, default_value_t = 1.0)]
    period_min: f64,
    /// MILP backend [default: the first of the build].
    #[arg(long, value_enum)]
    backend: Option<MilpBackend>,
    /// Worker threads (each takes the next request of the file; the output does not depend on it,
    /// except through the wall-clock time limits).
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Stop taking new requests after this many seconds of wall clock (requests already started
    /// finish); the requests measured are then the first ones of the file, and the output says
    /// how many.
    #[arg(long, value_name = "S")]
    budget_s: Option<f64>,
    /// Write one row per hop and per direct-hop test to this CSV file.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
}

const POLICIES: [SharingPolicy; 2] = [SharingPolicy::Pb, SharingPolicy::Fb];
const ZERO_GAP: f64 = 1e-9;

/// One hop ending at a stop.
#[derive(Debug, Clone)]
struct HopRow {
    request: usize,
    request_id: String,
    policy: usize,
    hop: usize,
    from: String,
    to: String,
    drones: usize,
    pads: usize,
    tt_min: f64,
    periods: usize,
    /// The heuristic's node time at the stop (the plan's), min.
    heuristic_nt: f64,
    heuristic_shared: f64,
    /// Whether the rebuilt problem replays to the plan's arrival batteries.
    replay_matches: bool,
    milp_status: ExactStatus,
    milp_nt: Option<f64>,
    milp_bound: Option<f64>,
    milp_shared: Option<f64>,
    milp_ms: f64,
    fluid_status: ExactStatus,
    fluid_bound: Option<f64>,
}

/// One direct hop to the destination that the policy failed.
#[derive(Debug, Clone)]
struct DirectRow {
    request: usize,
    request_id: String,
    policy: usize,
    from: String,
    to: String,
    periods: usize,
    fluid_status: ExactStatus,
    /// `None` when the fluid LP already proved the hop unflyable.
    milp_status: Option<ExactStatus>,
    milp_ms: f64,
    /// Whether this step is the request's source.
    at_source: bool,
    /// The MILP's schedule, replayed, flies and passes the independent checker.
    checked: bool,
}

#[derive(Default)]
struct Rows {
    hops: Vec<HopRow>,
    direct: Vec<DirectRow>,
    plans: [usize; 2],
    delivered: [usize; 2],
    /// Solves the backend failed on (numerical errors), per policy: hop left out, counted.
    errors: [usize; 2],
}

fn main() -> ExitCode {
    let mut args = Args::parse();
    if args.instance.profile.is_none() {
        args.instance.profile = Some(
            [
                env!("CARGO_MANIFEST_DIR"),
                "instances/profiles/fast-sharing.toml",
            ]
            .iter()
            .collect(),
        );
    }
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn status_name(s: ExactStatus) -> &'static str {
    match s {
        ExactStatus::Optimal => "optimal",
        ExactStatus::Feasible => "feasible",
        ExactStatus::Infeasible => "infeasible",
        ExactStatus::TimeLimitNoSolution => "time_limit_no_solution",
        ExactStatus::OptimalWithin => "optimal_within",
        ExactStatus::NoScheduleFound => "no_schedule_found",
    }
}

fn policy_name(p: usize) -> &'static str {
    ["pb", "fb"][p]
}

fn run(args: &Args) -> Result<()> {
    let started = Instant::now();
    let mut requests = load_requests(args.requests.as_deref())?.requests;
    let available = requests.len();
    requests.truncate(args.limit);
    let instance = args.instance.load()?.with_requests(requests)?;
    let requests = &instance.requests;
    let threads = args.threads.max(1);
    let backend = args.backend.unwrap_or_default();
    let milp = MilpOptions {
        period_min: args.period_min,
        reorder: Reorder::Paper,
        backend,
        time_limit_s: args.time_limit,
        node_limit: None,
    };
    let mut all = Rows::default();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let parts: Vec<Result<Rows>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|_| {
                let instance = &instance;
                let milp = &milp;
                let next = &next;
                scope.spawn(move || {
                    let mut rows = Rows::default();
                    loop {
                        if args
                            .budget_s
                            .is_some_and(|b| started.elapsed().as_secs_f64() > b)
                        {
                            break;
                        }
                        let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                        let Some(r) = requests.get(i) else { break };
                        request_rows(instance, i, r, milp, args.time_limit, &mut rows)?;
                        if (i + 1).is_multiple_of(50) {
                            eprintln!(
                                "[{:.0} s] request {} of {} done",
                                started.elapsed().as_secs_f64(),
                                i + 1,
                                requests.len()
                            );
                        }
                    }
                    Ok(rows)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("worker panicked"))
            .collect()
    });
    for part in parts {
        let part = part?;
        all.hops.extend(part.hops);
        all.direct.extend(part.direct);
        for p in 0..2 {
            all.plans[p] += part.plans[p];
            all.delivered[p] += part.delivered[p];
            all.errors[p] += part.errors[p];
        }
    }
    all.hops.sort_by_key(|h| (h.request, h.policy, h.hop));
    all.direct.sort_by(|a, b| {
        (a.request, a.policy)
            .cmp(&(b.request, b.policy))
            .then_with(|| a.from.cmp(&b.from))
    });
    let elapsed = started.elapsed().as_secs_f64();
    // Every index handed out was measured, so the measured requests are a prefix of the file.
    let measured = next.into_inner().min(requests.len());
    if measured < requests.len() {
        println!(
            "stopped by --budget-s: measured the first {measured} of the {} requests asked",
            requests.len()
        );
    }
    print_table(
        args,
        &instance,
        &requests[..measured],
        available,
        &all,
        backend,
        elapsed,
    );
    if let Some(path) = &args.csv {
        write_csv(path, &all)?;
        println!("per-hop rows written to {}", path.display());
    }
    Ok(())
}

/// Plans one request under PB and FB and measures its hops.
fn request_rows(
    instance: &Instance,
    index: usize,
    request: &Request,
    milp: &MilpOptions,
    time_limit_s: f64,
    rows: &mut Rows,
) -> Result<()> {
    let graph = &instance.graph;
    let context = Context::new(&instance.network, graph, &instance.profile);
    let readings = PolicyOptions::from(&instance.profile.readings);
    let pad_rate_default = instance.profile.pads.charge_rate_mah_per_min;
    for (p, &policy) in POLICIES.iter().enumerate() {
        let options = PlanOptions {
            sharing: policy,
            positioning: Positioning::LocationAware,
            route: RouteMethod::Sequential,
            support: None,
        };
        let report = context.plan(request, &options)?;
        rows.plans[p] += 1;
        rows.delivered[p] += usize::from(report.plan.delivered());
        let planner = Planner::new(graph, &instance.profile, &report.swarm, policy);
        let full = planner.full_battery_mah();
        let Some(destination) = graph.index_of(&request.destination) else {
            continue;
        };
        // Steps at which Algorithm 1 did not fly straight to the destination.
        let mut steps: Vec<usize> = Vec::new();
        for (h, hop) in report.plan.hops.iter().enumerate() {
            let Some(stop) = &hop.stop else { continue };
            let nodes: Vec<usize> = hop
                .path
                .iter()
                .filter_map(|id| graph.index_of(id))
                .collect();
            let Some(path) = graph.path_from_nodes(&nodes) else {
                continue;
            };
            steps.push(nodes[0]);
            let end = *nodes.last().expect("a hop has nodes");
            let problem = planner.hop_problem(&path, &hop.departure_battery_mah)?;
            let heuristic = policy.heuristic().expect("PB and FB are simulated");
            let replay = simulate_with(&problem, heuristic, &readings)?;
            let replay_matches = replay.feasible
                && replay
                    .final_battery_mah
                    .iter()
                    .zip(&hop.arrival_battery_mah)
                    .all(|(a, b)| (a - b).abs() <= 1e-6 * (1.0 + b.abs()));
            let pads = graph.pads(end) as usize;
            let objective = Objective::NodeTime(EndPads {
                pads,
                pad_rate_mah_per_min: graph.pad_rate_mah_per_min(end, pad_rate_default),
            });
            let (Ok(exact), Ok(lp)) = (
                solve_milp(&problem, &objective, milp),
                fluid::bound(&problem, &objective, Reorder::Paper, time_limit_s),
            ) else {
                rows.errors[p] += 1;
                continue;
            };
            rows.hops.push(HopRow {
                request: index,
                request_id: request.id.clone(),
                policy: p,
                hop: h,
                from: hop.from.clone(),
                to: hop.to.clone(),
                drones: problem.drones.len(),
                pads,
                tt_min: hop.tt_min,
                periods: exact.periods,
                heuristic_nt: stop.nt_min,
                heuristic_shared: hop.shared_mah,
                replay_matches,
                milp_status: exact.status,
                milp_nt: exact.objective,
                milp_bound: exact.bound,
                milp_shared: exact.outcome.as_ref().map(|o| o.shared_mah).or_else(|| {
                    exact
                        .objective
                        .map(|_| exact.transfers.iter().map(|t| t.energy_mah).sum())
                }),
                milp_ms: exact.solve_ms,
                fluid_status: lp.status,
                fluid_bound: lp.bound,
            });
        }
        if matches!(report.plan.outcome, PlanOutcome::DeadEnd { .. }) {
            let last = report
                .plan
                .hops
                .last()
                .map_or(request.source.as_str(), |h| h.to.as_str());
            if let Some(v) = graph.index_of(last) {
                steps.push(v);
            }
        }
        for (k, from) in steps.into_iter().enumerate() {
            let Some(path) = graph.shortest_path(from, destination) else {
                continue;
            };
            let problem: HopProblem = planner.hop_problem(&path, &full)?;
            let Ok(lp) = fluid::bound(&problem, &Objective::Feasible, Reorder::Paper, time_limit_s)
            else {
                rows.errors[p] += 1;
                continue;
            };
            let (milp_status, milp_ms, periods, checked) = if lp.status == ExactStatus::Infeasible {
                let periods = swarmplan::eaas::exact::milp::Grid::new(&problem, milp.period_min)
                    .map_or(0, |g| g.periods());
                (None, 0.0, periods, false)
            } else {
                let Ok(o) = solve_milp(&problem, &Objective::Feasible, milp) else {
                    rows.errors[p] += 1;
                    continue;
                };
                let checked = o.outcome.as_ref().is_some_and(|x| {
                    x.feasible && swarmplan::check::check_hop(&problem, x).is_empty()
                });
                (Some(o.status), o.solve_ms, o.periods, checked)
            };
            rows.direct.push(DirectRow {
                request: index,
                request_id: request.id.clone(),
                policy: p,
                from: graph.id_of(from).to_string(),
                to: request.destination.clone(),
                periods,
                fluid_status: lp.status,
                milp_status,
                milp_ms,
                at_source: k == 0 && report.plan.source == request.source,
                checked,
            });
        }
    }
    Ok(())
}

fn mean_max(v: &[f64]) -> (f64, f64) {
    if v.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let max = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    (v.iter().sum::<f64>() / v.len() as f64, max)
}

fn pct(x: f64) -> String {
    if x.is_nan() {
        "-".to_string()
    } else {
        format!("{:+.2}%", 100.0 * x)
    }
}

fn gap(h: f64, r: f64) -> Option<f64> {
    (r.abs() > 0.0).then(|| (h - r) / r)
}

#[allow(clippy::too_many_arguments)]
fn print_table(
    args: &Args,
    instance: &Instance,
    requests: &[Request],
    available: usize,
    all: &Rows,
    backend: MilpBackend,
    elapsed_s: f64,
) {
    println!(
        "profile `{}`, {} of {} requests, MILP reorder paper on a {} min grid (whole-period \
         transfers), backend {}, time limit {} s per solve, {} thread(s); {:.1} s wall clock",
        instance.profile.name,
        requests.len(),
        available,
        args.period_min,
        backend,
        args.time_limit,
        args.threads.max(1),
        elapsed_s
    );
    println!(
        "gap = (heuristic - reference) / reference on the node time at the stop ending each hop; \
         the MILP is optimal over grid schedules only, so a heuristic with off-grid transfers can \
         beat it: negative gaps vs optimal are real and not clipped"
    );
    println!();
    println!(
        "| policy | delivered | hops to a stop | replay = plan | MILP optimal / incumbent / infeasible on grid / no solution in time | gap vs optimal: mean, max, min | at gap 0 (of optimal) | heuristic better than grid optimum | gap vs incumbent: mean, max | gap vs fluid bound: mean, max (of hops) | at bound | direct hop flyable only with an optimal schedule (of direct hops tested) | LP proves unflyable | MILP grid infeasible / no solution in time |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    let mut direct_lines = Vec::new();
    for p in 0..2 {
        let hops: Vec<&HopRow> = all.hops.iter().filter(|h| h.policy == p).collect();
        let count = |s: ExactStatus| hops.iter().filter(|h| h.milp_status == s).count();
        let opt: Vec<f64> = hops
            .iter()
            .filter(|h| h.milp_status == ExactStatus::Optimal)
            .filter_map(|h| h.milp_nt.and_then(|m| gap(h.heuristic_nt, m)))
            .collect();
        let opt_zero_ref = hops
            .iter()
            .filter(|h| h.milp_status == ExactStatus::Optimal)
            .filter(|h| h.milp_nt.is_some_and(|m| m.abs() == 0.0))
            .count();
        let inc: Vec<f64> = hops
            .iter()
            .filter(|h| h.milp_status == ExactStatus::Feasible)
            .filter_map(|h| h.milp_nt.and_then(|m| gap(h.heuristic_nt, m)))
            .collect();
        let bnd: Vec<f64> = hops
            .iter()
            .filter(|h| h.fluid_status == ExactStatus::Optimal)
            .filter_map(|h| h.fluid_bound.and_then(|b| gap(h.heuristic_nt, b)))
            .collect();
        let (om, ox) = mean_max(&opt);
        let omin = opt.iter().copied().fold(f64::INFINITY, f64::min);
        let (im, ix) = mean_max(&inc);
        let (bm, bx) = mean_max(&bnd);
        let at0 = opt.iter().filter(|g| g.abs() <= ZERO_GAP).count();
        let better = opt.iter().filter(|g| **g < -ZERO_GAP).count();
        let bnd0 = bnd.iter().filter(|g| g.abs() <= ZERO_GAP).count();
        let direct: Vec<&DirectRow> = all.direct.iter().filter(|d| d.policy == p).collect();
        let found = |d: &&&DirectRow| {
            matches!(
                d.milp_status,
                Some(ExactStatus::Optimal) | Some(ExactStatus::Feasible)
            )
        };
        let only_opt = direct.iter().filter(found).count();
        let only_checked = direct.iter().filter(found).filter(|d| d.checked).count();
        let sources = direct.iter().filter(|d| d.at_source).count();
        let only_source = direct.iter().filter(found).filter(|d| d.at_source).count();
        let lp_no = direct
            .iter()
            .filter(|d| d.fluid_status == ExactStatus::Infeasible)
            .count();
        let grid_no = direct
            .iter()
            .filter(|d| d.milp_status == Some(ExactStatus::Infeasible))
            .count();
        let time_no = direct
            .iter()
            .filter(|d| d.milp_status == Some(ExactStatus::TimeLimitNoSolution))
            .count();
        let replay = hops.iter().filter(|h| h.replay_matches).count();
        direct_lines.push(format!(
            "| {} | {} | {} / {} | {} / {} | {} / {} | {} / {} | {} / {} | {} / {} |",
            policy_name(p).to_uppercase(),
            direct.len(),
            only_opt,
            direct.len(),
            only_checked,
            only_opt,
            only_source,
            sources,
            lp_no,
            direct.len(),
            grid_no,
            direct.len(),
            time_no,
            direct.len(),
        ));
        let mut zero_note = String::new();
        if opt_zero_ref > 0 {
            let _ = write!(zero_note, " ({opt_zero_ref} with optimum 0 left out)");
        }
        println!(
            "| {} | {} / {} | {} | {} / {} | {} / {} / {} / {} | {}, {}, {} (n = {}){} | {} / {} | {} / {} | {}, {} (n = {}) | {}, {} (n = {}) | {} / {} | {} / {} | {} / {} | {} / {} (of {}) |",
            policy_name(p).to_uppercase(),
            all.delivered[p],
            all.plans[p],
            hops.len(),
            replay,
            hops.len(),
            count(ExactStatus::Optimal),
            count(ExactStatus::Feasible),
            count(ExactStatus::Infeasible),
            count(ExactStatus::TimeLimitNoSolution),
            pct(om),
            pct(ox),
            if opt.is_empty() { "-".to_string() } else { pct(omin) },
            opt.len(),
            zero_note,
            at0,
            opt.len(),
            better,
            opt.len(),
            pct(im),
            pct(ix),
            inc.len(),
            pct(bm),
            pct(bx),
            bnd.len(),
            bnd0,
            bnd.len(),
            only_opt,
            direct.len(),
            lp_no,
            direct.len(),
            grid_no,
            time_no,
            direct.len(),
        );
    }
    println!(
        "backend errors (solve left out, hop or test not counted above): PB {}, FB {}",
        all.errors[0], all.errors[1]
    );
    println!();
    println!(
        "Direct hops to the destination that the policy failed (Algorithm 1 lines 5-10), full \
         batteries, at the source and at every stop before the last hop and at a dead end:"
    );
    println!("| policy | direct hops tested | MILP finds a flying schedule | of which the schedule passes check_hop | at the source (of sources tested) | fluid LP proves unflyable (every schedule) | MILP infeasible on the grid | MILP no solution in time |");
    println!("|---|---|---|---|---|---|---|---|");
    for line in direct_lines {
        println!("{line}");
    }
    // Sharing of the optimum against the heuristic, on hops proven optimal.
    println!();
    println!("| policy | optimal hops | MILP shares less / same / more than the heuristic | energy shared, heuristic vs MILP (sum over those hops, mAh) | MILP median solve ms (hops) |");
    println!("|---|---|---|---|---|");
    for p in 0..2 {
        let opt: Vec<&HopRow> = all
            .hops
            .iter()
            .filter(|h| h.policy == p && h.milp_status == ExactStatus::Optimal)
            .collect();
        let (mut less, mut same, mut more, mut hs, mut ms) = (0, 0, 0, 0.0, 0.0);
        for h in &opt {
            let m = h.milp_shared.unwrap_or(0.0);
            let tol = 1e-6 * (1.0 + h.heuristic_shared.abs());
            if m < h.heuristic_shared - tol {
                less += 1;
            } else if m > h.heuristic_shared + tol {
                more += 1;
            } else {
                same += 1;
            }
            hs += h.heuristic_shared;
            ms += m;
        }
        let mut times: Vec<f64> = all
            .hops
            .iter()
            .filter(|h| h.policy == p)
            .map(|h| h.milp_ms)
            .collect();
        times.sort_by(f64::total_cmp);
        let median = times.get(times.len() / 2).copied().unwrap_or(f64::NAN);
        println!(
            "| {} | {} | {} / {} / {} | {:.0} vs {:.0} | {:.0} ({}) |",
            policy_name(p).to_uppercase(),
            opt.len(),
            less,
            same,
            more,
            hs,
            ms,
            median,
            times.len()
        );
    }
}

fn opt_str(x: Option<f64>) -> String {
    x.map_or(String::new(), |v| format!("{v}"))
}

fn write_csv(path: &std::path::Path, all: &Rows) -> Result<()> {
    let mut out = String::from(
        "kind,request,request_id,policy,hop,from,to,drones,pads,tt_min,periods,heuristic_nt_min,\
         heuristic_shared_mah,replay_matches,milp_status,milp_nt_min,milp_bound_min,\
         milp_shared_mah,milp_ms,gap_vs_milp,gap_vs_milp_kind,fluid_status,fluid_bound_min,\
         gap_vs_bound\n",
    );
    for h in &all.hops {
        let (g, kind) = match (h.milp_status, h.milp_nt) {
            (ExactStatus::Optimal, Some(m)) => (gap(h.heuristic_nt, m), "optimal"),
            (ExactStatus::Feasible, Some(m)) => (gap(h.heuristic_nt, m), "incumbent"),
            _ => (None, ""),
        };
        let gb = h.fluid_bound.and_then(|b| gap(h.heuristic_nt, b));
        let _ = writeln!(
            out,
            "hop,{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{:.1},{},{},{},{},{}",
            h.request,
            h.request_id,
            policy_name(h.policy),
            h.hop,
            h.from,
            h.to,
            h.drones,
            h.pads,
            h.tt_min,
            h.periods,
            h.heuristic_nt,
            h.heuristic_shared,
            h.replay_matches,
            status_name(h.milp_status),
            opt_str(h.milp_nt),
            opt_str(h.milp_bound),
            opt_str(h.milp_shared),
            h.milp_ms,
            opt_str(g),
            kind,
            status_name(h.fluid_status),
            opt_str(h.fluid_bound),
            opt_str(gb),
        );
    }
    for d in &all.direct {
        let _ = writeln!(
            out,
            "direct,{},{},{},,{},{},,,,{},,,,{},,,,{:.1},,,{},,",
            d.request,
            d.request_id,
            policy_name(d.policy),
            d.from,
            d.to,
            d.periods,
            d.milp_status.map_or("skipped_lp_infeasible", status_name),
            d.milp_ms,
            status_name(d.fluid_status),
        );
    }
    std::fs::write(path, out).map_err(|source| swarmplan::error::Error::Io {
        path: path.display().to_string(),
        source,
    })
}
