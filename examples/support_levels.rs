//! Distribution of the redundancy levels (paper Eq. 2, Table 2) the support-count rule gives a
//! request set: per row of the profile's redundancy table, the requests that fall in it out of the
//! total, and min / median / max of the failure probability `P`.
//!
//! ```text
//! cargo run --release --example support_levels -- [--profile F] [--network F] [--requests F]
//! ```
//!
//! Defaults: the shipped `paper` profile, paper-195 network and its 10,000 requests. Each request
//! is decided as `swarmplan solve` decides it (`Context::swarm_for`: shortest-path distance, the
//! network's averaged wind from `precompose::select_formation`).

use clap::Parser;
use std::path::PathBuf;
use std::process::ExitCode;
use swarmplan::cli::inputs::InstanceArgs;
use swarmplan::compose::Context;
use swarmplan::precompose::Positioning;
use swarmplan::problem::inputs::load_requests;

/// Redundancy level distribution of a request set.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped instances/paper-195/requests.json].
    #[arg(long, value_name = "FILE")]
    requests: Option<PathBuf>,
}

fn main() -> ExitCode {
    let args = Args::parse();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("{e}");
            ExitCode::from(e.exit_code() as u8)
        }
    }
}

fn run(args: &Args) -> swarmplan::error::Result<()> {
    let requests = load_requests(args.requests.as_deref())?.requests;
    let instance = args.instance.load()?.with_requests(requests)?;
    let requests = &instance.requests;
    let context = Context::new(&instance.network, &instance.graph, &instance.profile);
    let profile = &instance.profile;
    let rows = &profile.redundancy.rows;
    let mut count = vec![0usize; rows.len().max(1)];
    let mut p_pct = Vec::with_capacity(requests.len());
    for r in requests {
        let choice = context.swarm_for(r, Positioning::LocationAware, None)?;
        count[choice.support_decision.row] += 1;
        p_pct.push(choice.support_decision.probability_pct);
    }
    let total = requests.len();
    let name = |v: serde_json::Value| v.as_str().unwrap_or_default().to_string();
    println!(
        "profile `{}`: failure.model = {}, failure.terms = {}; averaged wind {:.3} m/s",
        profile.name,
        name(serde_json::json!(profile.failure.model)),
        name(serde_json::json!(profile.failure.terms)),
        context.average_wind.speed_mps
    );
    println!("| row | P, % | level | requests |");
    println!("|---|---|---|---|");
    for (i, r) in rows.iter().enumerate() {
        let upper = rows
            .get(i + 1)
            .map_or("100]".to_string(), |next| format!("{})", next.from_pct));
        println!(
            "| {i} | [{}, {upper} | {} | {} / {total} |",
            r.from_pct,
            String::from(r.level).to_uppercase(),
            count[i]
        );
    }
    if total > 0 {
        p_pct.sort_by(f64::total_cmp);
        let median = if total % 2 == 1 {
            p_pct[total / 2]
        } else {
            0.5 * (p_pct[total / 2 - 1] + p_pct[total / 2])
        };
        println!(
            "P, %: min {:.3}, median {:.3}, max {:.3} (over {total} requests)",
            p_pct[0],
            median,
            p_pct[total - 1]
        );
    }
    Ok(())
}
