//! `swarmplan check`: re-verify a plan written by `solve --json` with the independent checker.

use super::inputs::{self, InstanceArgs};
use crate::check::{check_report, plan_file};
use crate::compose::RequestReport;
use crate::error::{Error, Result, Violation};
use std::io::Read;
use std::path::PathBuf;

/// Re-verify a plan written by `solve --json`: exit 0 valid, 1 invalid, 2 malformed input.
#[derive(Debug, clap::Args)]
pub struct CheckArgs {
    /// Network and profile the plan was made with.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Request set (JSON) holding the plan's request [default: the shipped paper-195 requests].
    #[arg(long, value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// The plan: the JSON `solve --json` prints (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub plan: PathBuf,
    /// Print the violations as a JSON list (empty when the plan is valid).
    #[arg(long)]
    pub json: bool,
}

/// Runs the subcommand; exit code 0 when the plan passes, 1 when it breaks a rule.
pub fn run(args: CheckArgs) -> Result<i32> {
    let instance = args.instance.load()?;
    let set = inputs::load_requests(args.requests.as_deref())?;
    let report = read_plan(&args.plan)?;
    // Another instance is the user's mix-up (exit 2), not a plan that breaks the model.
    let mismatch = crate::check::report::made_on_another_instance(
        &instance.network,
        &instance.profile,
        &report,
    );
    if !mismatch.is_empty() {
        return Err(Error::Invalid(mismatch));
    }
    let violations = check_report(&instance.network, &instance.profile, &set.requests, &report);
    if args.json {
        super::print_json(&violations)?;
    } else {
        print_human(&report, &violations)?;
    }
    Ok(if violations.is_empty() { 0 } else { 1 })
}

/// The plan file, or standard input for `-`.
fn read_plan(path: &std::path::Path) -> Result<RequestReport> {
    if path.as_os_str() != "-" {
        return plan_file::read_plan_file(path);
    }
    let mut bytes = Vec::new();
    std::io::stdin().read_to_end(&mut bytes).map_err(|e| {
        Error::invalid(
            "E0008",
            "standard input",
            format!("cannot read the plan: {e}"),
            "pipe the output of `swarmplan solve --json` into `swarmplan check --plan -`",
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
            "pipe the output of `swarmplan solve --json` into `swarmplan check --plan -`",
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
