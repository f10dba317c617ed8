//! Every plan `solve --json` would print, read back and re-verified: for every method combination
//! (sharing x positioning x route) on the first requests of a request set, the plan is made,
//! written as the JSON document of `solve --json`, read back with the plan reader, compared with
//! the original (the round trip must be exact) and checked by `check::check_report`, as
//! `swarmplan check` does.
//!
//! ```text
//! cargo run --release --example check_all -- [--limit 1000] [--exact-limit 20] [--threads 2]
//!     [--network F] [--profile F] [--requests F]
//! ```
//!
//! `none`, `idle-support`, `pb` and `fb` run on the first `--limit` requests, `exact` and `fair`
//! (default backend and limits) on the first `--exact-limit`. Prints one line per combination:
//! requests, delivered, failures by kind, plans with a violation, violations by code, wall time.
//! Exit code 1 when any plan breaks a rule or does not read back unchanged.

use clap::{Parser, ValueEnum};
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;
use swarmplan::check::{check_report, plan_file};
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::{Context, PlanOptions, RouteMethod};
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;
use swarmplan::problem::{Instance, Request};

/// Plan, write, read back and check every method combination.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long, value_name = "FILE")]
    requests: Option<PathBuf>,
    /// Requests planned by `none`, `idle-support`, `pb` and `fb`.
    #[arg(long, default_value_t = 1000)]
    limit: usize,
    /// Requests planned by `exact` and `fair`.
    #[arg(long, default_value_t = 20)]
    exact_limit: usize,
    /// Worker threads; the counts do not depend on it.
    #[arg(long, default_value_t = 1)]
    threads: usize,
}

/// What the plans of one combination gave.
#[derive(Default)]
struct Tally {
    plans: usize,
    delivered: usize,
    failed_by_kind: BTreeMap<String, usize>,
    plans_with_violations: usize,
    violations_by_code: BTreeMap<&'static str, usize>,
    /// Plans whose document did not read back equal to what was written.
    not_round_trip: usize,
    /// One example violation per code, for the report.
    examples: BTreeMap<&'static str, String>,
}

impl Tally {
    fn merge(&mut self, other: Tally) {
        self.plans += other.plans;
        self.delivered += other.delivered;
        for (k, n) in other.failed_by_kind {
            *self.failed_by_kind.entry(k).or_default() += n;
        }
        self.plans_with_violations += other.plans_with_violations;
        for (k, n) in other.violations_by_code {
            *self.violations_by_code.entry(k).or_default() += n;
        }
        self.not_round_trip += other.not_round_trip;
        for (k, x) in other.examples {
            self.examples.entry(k).or_insert(x);
        }
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::from(1),
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run(args: &Args) -> swarmplan::error::Result<bool> {
    let set = load_requests(args.requests.as_deref())?;
    let mut requests = set.requests.clone();
    requests.truncate(args.limit.max(args.exact_limit));
    let instance = args.instance.load()?.with_requests(requests)?;
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    let start_all = Instant::now();
    let mut total = Tally::default();
    println!(
        "sharing,positioning,route,requests,delivered,failed_by_kind,plans_with_violations,violations_by_code,not_round_trip,wall_s"
    );
    for &sharing in SharingPolicy::value_variants() {
        let limit = if sharing.is_exact() {
            args.exact_limit
        } else {
            args.limit
        };
        let requests = &instance.requests[..limit.min(instance.requests.len())];
        for positioning in [Positioning::LocationAware, Positioning::EnergyAware] {
            for route in RouteMethod::ALL {
                let options = PlanOptions {
                    sharing,
                    positioning,
                    route,
                    support: None,
                };
                let start = Instant::now();
                let tally = check_all(
                    &context,
                    &instance,
                    &set.requests,
                    requests,
                    &options,
                    args.threads,
                )?;
                println!(
                    "{},{},{},{},{},{},{},{},{},{:.1}",
                    sharing,
                    positioning,
                    route,
                    tally.plans,
                    tally.delivered,
                    counts(&tally.failed_by_kind),
                    tally.plans_with_violations,
                    counts(&tally.violations_by_code),
                    tally.not_round_trip,
                    start.elapsed().as_secs_f64()
                );
                total.merge(tally);
            }
        }
    }
    println!(
        "total: {} plans, {} delivered, {} with a violation ({}), {} not read back unchanged, {:.1} s",
        total.plans,
        total.delivered,
        total.plans_with_violations,
        counts(&total.violations_by_code),
        total.not_round_trip,
        start_all.elapsed().as_secs_f64()
    );
    for (code, example) in &total.examples {
        println!("  {code}: {example}");
    }
    Ok(total.plans_with_violations == 0 && total.not_round_trip == 0)
}

/// The tally of one combination over `requests`, split over `threads` contiguous blocks.
fn check_all(
    context: &Context,
    instance: &Instance,
    file: &[Request],
    requests: &[Request],
    options: &PlanOptions,
    threads: usize,
) -> swarmplan::error::Result<Tally> {
    let chunk = requests.len().div_ceil(threads.max(1)).max(1);
    let blocks: Vec<swarmplan::error::Result<Tally>> = std::thread::scope(|scope| {
        let handles: Vec<_> = requests
            .chunks(chunk)
            .map(|block| scope.spawn(move || check_block(context, instance, file, block, options)))
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a checking thread panicked"))
            .collect()
    });
    let mut tally = Tally::default();
    for block in blocks {
        tally.merge(block?);
    }
    Ok(tally)
}

fn check_block(
    context: &Context,
    instance: &Instance,
    file: &[Request],
    requests: &[Request],
    options: &PlanOptions,
) -> swarmplan::error::Result<Tally> {
    let mut tally = Tally::default();
    for request in requests {
        let report = context.plan(request, options)?;
        let text = serde_json::to_string_pretty(&report).expect("plain data");
        let read = plan_file::parse_plan_file(&text, &request.id)?;
        tally.plans += 1;
        if read != report {
            tally.not_round_trip += 1;
        }
        if read.plan.delivered() {
            tally.delivered += 1;
        } else {
            *tally
                .failed_by_kind
                .entry(read.plan.outcome.kind())
                .or_default() += 1;
        }
        let violations = check_report(&instance.network, &instance.profile, file, &read);
        if !violations.is_empty() {
            tally.plans_with_violations += 1;
        }
        for x in violations {
            *tally.violations_by_code.entry(x.code).or_default() += 1;
            tally
                .examples
                .entry(x.code)
                .or_insert_with(|| format!("{} {options:?}: {x}", request.id));
        }
    }
    Ok(tally)
}

/// `key=n;key=n`, or `-` when empty.
fn counts<K: std::fmt::Display>(map: &BTreeMap<K, usize>) -> String {
    if map.is_empty() {
        return "-".into();
    }
    map.iter()
        .map(|(k, n)| format!("{k}={n}"))
        .collect::<Vec<_>>()
        .join(";")
}
