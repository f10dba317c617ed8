//! `swarmplan check`: re-verify a plan written by `solve --json` with the independent checker.

use super::inputs::InstanceArgs;
use crate::check::{check_report, plan_file};
use crate::compose::RequestReport;
use crate::error::{Error, Result, Violation};
use std::io::Read;
use std::path::PathBuf;

/// Re-verify a plan written by `solve --json` (or a hop file, or a node-time result): exit 0
/// valid, 1 invalid, 2 malformed input.
#[derive(Debug, clap::Args)]
#[group(
    id = "document",
    required = true,
    multiple = false,
    args = ["plan", "hop_file", "node_time", "bench"]
)]
pub struct CheckArgs {
    /// Network and profile the plan was made with.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Request set (JSON) holding the plan's request [default: the shipped paper-195 requests].
    #[arg(long, value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// The plan: the JSON `solve --json` prints (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub plan: Option<PathBuf>,
    /// A hop file (`eaas --write-hop`): every number of its hop rebuilt from the instance and
    /// the request it names.
    #[arg(long, value_name = "FILE")]
    pub hop_file: Option<PathBuf>,
    /// A node-time result (`node-time --json`): its assignment, makespan, bound and gap
    /// re-verified on the instance it records.
    #[arg(long, value_name = "FILE")]
    pub node_time: Option<PathBuf>,
    /// A bench run's directory (`bench --out DIR`): the rows of its `requests.csv`, each request
    /// planned again with the row's combination and the run's settings, the plan checked and
    /// every column compared with it.
    #[arg(long, value_name = "DIR")]
    pub bench: Option<PathBuf>,
    /// With --bench: the number of requests whose rows are checked (the first in the file)
    /// [default: all].
    #[arg(long, value_name = "N", requires = "bench")]
    pub request_limit: Option<usize>,
    /// With --node-time: the instance file (`{"pads": K, "charge_times_min": [...]}`) the result
    /// should answer.
    #[arg(long, value_name = "FILE", requires = "node_time")]
    pub node_time_instance: Option<PathBuf>,
    /// Print the violations as a JSON list (empty when the plan is valid).
    #[arg(long)]
    pub json: bool,
}

/// Runs the subcommand; exit code 0 when the plan passes, 1 when it breaks a rule.
pub fn run(args: CheckArgs) -> Result<i32> {
    if let Some(dir) = &args.bench {
        return check_bench(&args, dir);
    }
    let instance = args.instance.load()?;
    let set = crate::problem::inputs::load_requests(args.requests.as_deref())?;
    if let Some(path) = &args.node_time {
        return check_node_time(path, args.node_time_instance.as_deref(), args.json);
    }
    if let Some(path) = &args.hop_file {
        let file = crate::eaas::hop_file::read_hop_file(path)?;
        let found = crate::check::hop_file::check_hop_file(
            &instance.network,
            &instance.profile,
            &set.requests,
            &file,
        );
        let what = format!(
            "hop {} of request {} ({} -> {})",
            file.hop_index, file.request_id, file.from, file.to
        );
        return print_verdict(&what, &found, args.json);
    }
    let report = read_plan(
        args.plan
            .as_deref()
            .expect("one document, by the clap group"),
    )?;
    // Another instance is the user's mix-up (exit 2), not a plan that breaks the model.
    let mismatch =
        crate::check::made_on_another_instance(&instance.network, &instance.profile, &report);
    if !mismatch.is_empty() {
        return Err(Error::Invalid(mismatch));
    }
    let violations = check_report(&instance.network, &instance.profile, &set.requests, &report);
    if let Some(why) = crate::check::search::why_not_rerun(&report) {
        eprintln!(
            "note: the search report (solve statuses, bounds, counts) was checked for consistency \
             only, not re-run: {why}"
        );
    }
    if args.json {
        super::print_json(&violations)?;
    } else {
        print_human(&report, &violations)?;
    }
    Ok(if violations.is_empty() { 0 } else { 1 })
}

/// `check --node-time R [--node-time-instance F]`. The instance recorded in R and the one in F
/// are input: the node-time rules (E5001-E5004, a negative charge time is E5003) apply to them
/// as to `node-time`'s, each field named with its file.
fn check_node_time(
    path: &std::path::Path,
    instance: Option<&std::path::Path>,
    json: bool,
) -> Result<i32> {
    let valid = |file: &std::path::Path, pads: usize, times: &[f64]| {
        crate::node_time::validate(pads, times).map_err(|e| match e {
            Error::Invalid(list) => Error::Invalid(
                list.into_iter()
                    .map(|v| Violation {
                        field: format!("{}: {}", file.display(), v.field),
                        ..v
                    })
                    .collect(),
            ),
            other => other,
        })
    };
    let report: crate::node_time::NodeTimeReport = crate::problem::io::read_json(path)?;
    let given = instance
        .map(crate::problem::io::read_json::<super::node_time::NodeTimeFile>)
        .transpose()?;
    let recorded = valid(path, report.pads, &report.charge_times_min);
    let stated = match (instance, &given) {
        (Some(file), Some(f)) => valid(file, f.pads, &f.charge_times_min),
        _ => Ok(()),
    };
    crate::error::both(recorded, stated)?;
    let found = crate::check::node_time::check_node_time(
        &report,
        given
            .as_ref()
            .map(|f| (f.pads, f.charge_times_min.as_slice())),
    );
    let what = format!(
        "node time of {} drones on {} pads ({}, {})",
        report.charge_times_min.len(),
        report.pads,
        report.solution.method,
        crate::problem::io::json_name(&report.solution.status)
    );
    print_verdict(&what, &found, json)
}

/// `check --bench DIR [--request-limit N]`: the run's inputs are the files given, or, when none is,
/// the shipped instance the run names (findings-195 is the bench's default).
fn check_bench(args: &CheckArgs, dir: &std::path::Path) -> Result<i32> {
    if args.request_limit == Some(0) {
        return Err(Error::invalid(
            "E6007",
            "--request-limit",
            "0 requests: nothing would be checked".to_string(),
            "give a count of at least 1, or leave it out to check every row",
        ));
    }
    // The seal first: a file changed after the run is named before any row is read.
    let seal = crate::bench::verify_seal(dir)?;
    let (config, data) = crate::bench::read_data(dir)?;
    crate::bench::seal_agrees(dir, &seal, &config)?;
    let shipped = if config.network == crate::problem::shipped::FINDINGS_195.network_name
        || config.profile == crate::problem::shipped::FINDINGS_195.profile_name
    {
        &crate::problem::shipped::FINDINGS_195
    } else {
        &crate::problem::shipped::PAPER_195
    };
    let (instance, set) = crate::error::both(
        args.instance.load_or(shipped),
        crate::problem::inputs::load_requests(args.requests.as_deref()),
    )?;
    let requests = &set.requests[..config.limit.min(set.requests.len())];
    let given = crate::bench::inputs_sha256(&instance.network, &instance.profile, requests)?;
    if given != config.inputs_sha256 {
        return Err(Error::invalid(
            "E6006",
            format!("{}: config.json inputs_sha256", dir.display()),
            format!(
                "this run was made on other inputs (network, profile and requests: sha256 \
                 {}..., the files given: {}...)",
                config.inputs_sha256.chars().take(12).collect::<String>(),
                given.chars().take(12).collect::<String>()
            ),
            format!(
                "check it with the inputs it was made on (config.json: {}, {}, {})",
                config.network, config.profile, config.requests
            ),
        ));
    }
    let found = crate::check::bench_rows::check_bench_rows(
        &instance.network,
        &instance.profile,
        requests,
        &config,
        &data,
        args.request_limit.unwrap_or(usize::MAX),
    )?;
    if let Some(why) = found.skipped {
        eprintln!("note: the rows were not planned again: {why}");
    }
    let what = format!(
        "bench run {}: {} rows of {} requests",
        dir.display(),
        found.rows,
        found.requests
    );
    print_verdict(&what, &found.violations, args.json)
}

/// Prints the violations (or that there is none); exit code 0 or 1.
fn print_verdict(what: &str, violations: &[Violation], json: bool) -> Result<i32> {
    if json {
        super::print_json(&violations)?;
    } else if violations.is_empty() {
        outln!("{what}: valid");
    } else {
        outln!("{what}: {} violation(s)", violations.len());
        for x in violations {
            outln!("  {x}");
        }
    }
    Ok(if violations.is_empty() { 0 } else { 1 })
}

/// The plan file, or standard input for `-`.
pub(crate) fn read_plan(path: &std::path::Path) -> Result<RequestReport> {
    if path.as_os_str() != "-" {
        return plan_file::read_plan_file(path);
    }
    let mut bytes = Vec::new();
    std::io::stdin().read_to_end(&mut bytes).map_err(|e| {
        Error::invalid(
            "E0008",
            "standard input",
            format!("cannot read the plan: {e}"),
            "pipe the output of `swarmplan solve --json` into `--plan -`",
        )
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        Error::invalid(
            "E0009",
            "standard input",
            format!(
                "not UTF-8 text: invalid byte at byte {}",
                e.utf8_error().valid_up_to()
            ),
            "pipe the output of `swarmplan solve --json` into `--plan -`",
        )
    })?;
    plan_file::parse_plan_file(&text, "standard input")
}

fn print_human(report: &RequestReport, violations: &[Violation]) -> Result<()> {
    let o = &report.options;
    let what = format!(
        "plan of request {} ({} -> {}, sharing {}, positioning {}, route {}, {})",
        report.request.id,
        report.plan.source,
        report.plan.destination,
        o.sharing,
        o.positioning,
        o.route,
        report.plan.outcome.kind()
    );
    if violations.is_empty() {
        outln!("{what}: valid");
        return Ok(());
    }
    outln!("{what}: {} violation(s)", violations.len());
    for x in violations {
        outln!("  {x}");
    }
    Ok(())
}
