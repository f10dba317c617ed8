//! `swarmplan solve`: plan one request and print the plan.

use super::inputs::{self, ExactArgs, InstanceArgs};
use crate::compose::{Context, HopPaths, PlanOptions, RequestReport, RouteMethod};
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::problem::io::json_name;
use crate::problem::Request;
use std::path::PathBuf;

/// Plan one request: route, sharing schedules, node times, delivery time.
#[derive(Debug, clap::Args)]
pub struct SolveArgs {
    /// Network and profile.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Solver settings of `--sharing exact|fair`.
    #[command(flatten)]
    pub exact: ExactArgs,
    /// Request set (JSON) holding the request [default: the shipped paper-195 requests].
    #[arg(long, alias = "request-file", value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// Id of the request in the request set.
    #[arg(long, value_name = "ID", conflicts_with_all = ["from", "to", "packages"])]
    pub request_id: Option<String>,
    /// Source node id (with --to and --packages, instead of --request-id).
    #[arg(long, value_name = "NODE", requires_all = ["to", "packages"])]
    pub from: Option<String>,
    /// Destination node id.
    #[arg(long, value_name = "NODE", requires_all = ["from", "packages"])]
    pub to: Option<String>,
    /// Package masses in kg, comma-separated, one delivery drone each (e.g. 1.2,0.8).
    #[arg(
        long,
        value_name = "KG,KG,...",
        requires_all = ["from", "to"],
        allow_hyphen_values = true
    )]
    pub packages: Option<String>,
    /// In-flight energy sharing policy.
    #[arg(long, value_enum, default_value = "pb")]
    pub sharing: SharingPolicy,
    /// Initial positioning of the support drones.
    #[arg(long, value_enum, default_value = "location-aware")]
    pub positioning: Positioning,
    /// Route composition method.
    #[arg(long, value_enum, default_value = "sequential")]
    pub route: RouteMethod,
    /// Number of support drones, overriding the redundancy table (not used by `--sharing none`,
    /// the paper's baseline without support drones; `idle-support` flies them without sharing).
    #[arg(long, value_name = "N")]
    pub support: Option<usize>,
    /// Paths the hops of `--route optimal` (and of the `--gap` reference) may follow: `rule`, the
    /// shortest path by distance between two stops; `any`, every path flyable from full
    /// batteries (a resource-constrained search; `--sharing none` or `idle-support` only).
    #[arg(long, value_enum, default_value = "rule")]
    pub hop_paths: HopPaths,
    /// Node limit of the exact node time at every stop (search nodes, the same on every machine);
    /// a stop it stops keeps its incumbent, `status: feasible`.
    #[arg(long, value_name = "N", default_value_t = crate::node_time::DEFAULT_STOP_NODE_LIMIT)]
    pub node_limit: u64,
    /// The swarms `--route optimal --sharing exact` ranges over: `this`, the swarm
    /// pre-composition gives for `--positioning` and `--support`; `best`, the least delivery
    /// time over both positionings (with `--support`) and the swarm without support drones,
    /// the swarms `bench` compares with (`swarms_compared` in the JSON).
    #[arg(long, value_enum, default_value = "this")]
    pub swarm: SwarmScope,
    /// Print the full report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Also plan the request with `--route optimal` (same sharing policy, positioning and support
    /// drones) and give this plan's gap against it (`route_gap` in the JSON; not with `fair`).
    #[arg(long)]
    pub gap: bool,
    /// Re-verify the plan as printed with the independent checker (as `swarmplan check` does);
    /// violations go to stderr, and the exit code is 1 when there is one.
    #[arg(long)]
    pub check: bool,
}

/// The swarms an optimum ranges over (`solve --swarm`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum SwarmScope {
    /// The swarm pre-composition gives for `--positioning` and `--support`.
    This,
    /// The best of both positionings and the swarm without support drones.
    Best,
}

/// Runs the subcommand; exit code 0 when the request is delivered, 1 when it fails.
pub fn run(args: SolveArgs) -> Result<i32> {
    // Every input file read before any problem is reported: all their problems at once.
    let set = args
        .request_id
        .is_some()
        .then(|| crate::problem::inputs::load_requests(args.requests.as_deref()));
    let (instance, set) = crate::error::both(args.instance.load(), set.transpose())?;
    let instance =
        match (&args.request_id, &args.from, &args.to, &args.packages) {
            (Some(id), None, None, None) => {
                let set = set.expect("read above, with --request-id");
                instance.with_request_from(&set, id)?
            }
            (None, Some(from), Some(to), Some(packages)) => instance
                .with_requests(vec![Request {
                    id: crate::problem::COMMAND_LINE_REQUEST_ID.to_string(),
                    source: from.clone(),
                    destination: to.clone(),
                    packages_kg: inputs::parse_list(packages, "--packages", "E0003")?,
                }])
                .map_err(options_named)?,
            _ => return Err(Error::invalid(
                "E3402",
                "--request-id | --from/--to/--packages",
                "no request given",
                "pass --request-id ID (with --requests F), or --from A --to B --packages 1.2,0.8",
            )),
        };
    let request = instance.requests[0].clone();
    let mut context = Context::new(&instance.network, &instance.graph, &instance.profile);
    context.exact = args.exact.settings()?;
    context.node_limit = Some(args.node_limit);
    context.hop_paths = args.hop_paths;
    let options = PlanOptions {
        sharing: args.sharing,
        positioning: args.positioning,
        route: args.route,
        support: args.support,
    };
    context.validate(&options)?;
    if args.swarm == SwarmScope::Best
        && (options.route != RouteMethod::Optimal || options.sharing != SharingPolicy::Exact)
    {
        return Err(Error::invalid(
            "E0033",
            "--swarm best",
            "the best swarm is that of an optimum: it applies to --route optimal --sharing exact",
            "add --route optimal --sharing exact, or leave --swarm out",
        ));
    }
    for note in crate::experiment::applicable_options(&[options], args.gap, args.support)? {
        eprintln!("{note}");
    }
    // A hop solve can take up to --hop-time-limit, and a route makes many.
    let spinner = args
        .sharing
        .is_exact()
        .then(|| super::progress::spinner(format!("planning request {}", request.id)));
    let mut report = match args.swarm {
        SwarmScope::This => context.plan(&request, &options)?,
        SwarmScope::Best => context.plan_best_swarm(&request, &options)?,
    };
    if args.gap {
        report.route_gap = Some(context.route_gap(&request, &report)?);
    }
    drop(spinner);
    if args.json {
        super::print_json(&report)?;
    } else {
        print_human(&report)?;
    }
    let valid = !args.check || check_as_printed(&instance, &report)?;
    Ok(if report.plan.delivered() && valid {
        0
    } else {
        1
    })
}

/// The violations of a request given by `--from`, `--to`, `--packages`, named after the options
/// rather than the request's fields (`requests[0].source` is `--from`).
fn options_named(e: Error) -> Error {
    match e {
        Error::Invalid(mut list) => {
            for v in &mut list {
                for (field, option) in [
                    ("requests[0].source", "--from"),
                    ("requests[0].destination", "--to"),
                    ("requests[0].packages_kg", "--packages"),
                    ("request cli.source", "--from"),
                    ("request cli.destination", "--to"),
                ] {
                    if let Some(rest) = v.field.strip_prefix(field) {
                        v.field = format!("{option}{rest}");
                    }
                }
            }
            Error::Invalid(list)
        }
        other => other,
    }
}

/// `--check`: the report written as JSON, read back and re-verified by
/// [`crate::check::check_report`]; the verdict and every violation go to stderr.
fn check_as_printed(instance: &crate::problem::Instance, report: &RequestReport) -> Result<bool> {
    let text = serde_json::to_string(report).expect("serialising plain data cannot fail");
    let read = crate::check::plan_file::parse_plan_file(&text, "the plan printed")?;
    let violations = crate::check::check_report(
        &instance.network,
        &instance.profile,
        &instance.requests,
        &read,
    );
    if violations.is_empty() {
        eprintln!("check: the plan passes the independent checker");
    } else {
        eprintln!("check: {} violation(s)", violations.len());
        for x in &violations {
            eprintln!("  {x}");
        }
    }
    Ok(violations.is_empty())
}

fn print_human(report: &RequestReport) -> Result<()> {
    let plan = &report.plan;
    outln!(
        "request {}: {} -> {}, formation {}, {} delivery + {} support drones",
        report.request.id,
        plan.source,
        plan.destination,
        json_name(&report.formation),
        report.swarm.drones.len() - report.support_drones,
        report.support_drones
    );
    for hop in &plan.hops {
        outln!(
            "  fly {} -> {} via {} edge(s): {:.0} m, tt {:.2} min, shared {:.1} mAh in {} transfer(s)",
            hop.from,
            hop.to,
            hop.path.len() - 1,
            hop.distance_m,
            hop.tt_min,
            hop.shared_mah,
            hop.transfers.len()
        );
        if let Some(stop) = &hop.stop {
            outln!(
                "  recharge at {} on {} pad(s): nt {:.2} min ({}), pads {:?}",
                stop.node,
                stop.pads,
                stop.nt_min,
                json_name(&stop.status),
                stop.assignment
            );
        }
    }
    if let Some(c) = &plan.hop_solves {
        let over = match report.options.sharing {
            crate::eaas::SharingPolicy::Exact => " (optimal over continuous-time schedules)",
            _ => "",
        };
        outln!(
            "hop solves: {} made{over}: {} optimal, {} within a certified distance, {} \
             infeasible, {} stopped at the limit with a schedule, {} without, {} backend \
             error(s); {} schedule(s) that do not fly; {} hop(s) flew without sharing instead",
            c.solves,
            c.optimal,
            c.optimal_within,
            c.infeasible,
            c.time_limit_incumbent,
            c.time_limit_no_solution + c.no_schedule_found,
            c.backend_errors,
            c.schedule_does_not_fly,
            c.fallbacks
        );
    }
    if let Some(o) = &plan.route_optimality {
        let exact = report.options.sharing == crate::eaas::SharingPolicy::Exact;
        let over = match (o.hop_paths, exact) {
            (HopPaths::Rule, false) => "stop sequences",
            (HopPaths::Rule, true) => "stop sequences, sharing schedules and pad assignments",
            (HopPaths::Any, _) => "stop sequences and hop paths",
        };
        let verdict = if !o.proven() {
            format!(
                "optimal over {over} for the solves found ({} stop(s) at the node limit, {} hop \
                 solve(s) unproven)",
                o.stops_unproven, o.hop_solves_unproven
            )
        } else if o.epsilon_min > 0.0 {
            format!(
                "proven optimal over {over} within {:.3e} min",
                o.epsilon_min
            )
        } else {
            format!("proven optimal over {over}")
        };
        outln!(
            "route: {verdict} (--hop-paths {}); {} recharging node(s) settled, {} hop(s) flown, \
             {} stop(s) solved",
            o.hop_paths,
            o.stops_settled,
            o.arcs_flown,
            o.stops_solved,
        );
    }
    print_swarm_scope(report)?;
    if plan.delivered() {
        outln!(
            "delivered: dt {:.2} min = tt {:.2} + nt {:.2}; {} stop(s); {:.2} ms",
            plan.dt_min,
            plan.tt_min,
            plan.nt_min,
            plan.stops().len(),
            report.execution_ms
        );
    } else {
        outln!("failed: {}", plan.outcome);
    }
    if let Some(g) = &report.route_gap {
        let proven = if g.optimal_proven {
            "proven"
        } else {
            "optimal for the node times found"
        };
        match (g.gap, g.optimal_dt_min) {
            (Some(gap), Some(best)) => outln!(
                "route gap: {} against the optimal route over stop sequences (dt {:.2} min, {proven})",
                crate::human::gap_percent(gap, 2),
                best
            ),
            (None, Some(best)) => outln!(
                "route gap: n/a, the optimal route over stop sequences delivers in {best:.2} min ({proven})"
            ),
            _ => outln!("route gap: n/a, the optimal route over stop sequences does not deliver either"),
        }
    }
    Ok(())
}

/// Which swarm an optimum is over: the swarms compared (`--swarm best`), or this swarm only.
fn print_swarm_scope(report: &RequestReport) -> Result<()> {
    let o = report.options;
    if o.route != RouteMethod::Optimal || o.sharing != SharingPolicy::Exact {
        return Ok(());
    }
    let name = |positioning: Positioning, support: usize| match support {
        0 => "no support drone".to_string(),
        1 => format!("{}, 1 support drone", json_name(&positioning)),
        n => format!("{}, {n} support drones", json_name(&positioning)),
    };
    let Some(c) = &report.swarms_compared else {
        outln!(
            "swarm: the optimum over this swarm only ({}); --swarm best ranges over both \
             positionings and the swarm without support drones",
            name(o.positioning, report.support_drones)
        );
        return Ok(());
    };
    let each: Vec<String> = c
        .swarms
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let dt = s
                .dt_min
                .map_or("does not deliver".to_string(), |t| format!("dt {t:.2} min"));
            let best = if c.best == Some(i) { " (best)" } else { "" };
            let proven = if s.proven { "" } else { ", unproven" };
            format!(
                "{}: {dt}{proven}{best}",
                name(s.positioning, s.support_drones)
            )
        })
        .collect();
    outln!(
        "swarm: the best of {} swarm(s): {}",
        c.swarms.len(),
        each.join("; ")
    );
    Ok(())
}
