//! `swarmplan bench`: the paper's experiments and the optimality-gap report, as files and
//! figures; `swarmplan bench merge`: the shards of a run, merged into the files one run writes.
//!
//! ```text
//! swarmplan bench --request-limit 1000 --out bench-out
//! swarmplan bench --shard 0/4 --out shard-0      # ... 3/4, then:
//! swarmplan bench merge shard-0 shard-1 shard-2 shard-3 --out bench-out
//! ```

use crate::bench::{self, table, BenchSettings, GridSize, Shard, Summary, Verdict, DATA_FILES};
use crate::compose::RouteMethod;
use crate::eaas::exact_hop::ExactChoices;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::problem::inputs::InstanceFiles;
use std::path::{Path, PathBuf};

/// Run the paper's experiments and the gap report, or merge shards.
#[derive(Debug, clap::Args)]
#[command(
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true,
    after_help = "Writes to --out: config.json, requests.csv (one row per request and \
combination), hops.csv and stops.csv (the exact subset), timings.csv (execution times, \
machine-dependent), summary.json and figures/*.svg. Every file but timings.csv and the times in \
summary.json is identical for any --threads, and for the merge of --shard runs."
)]
pub struct BenchArgs {
    /// `merge`: merge the output directories of shards.
    #[command(subcommand)]
    pub command: Option<BenchCommand>,
    /// The run.
    #[command(flatten)]
    pub run: RunArgs,
}

/// Subcommands of `bench`.
#[derive(Debug, clap::Subcommand)]
pub enum BenchCommand {
    /// Merge the output directories of the shards `0/N` ... `N-1/N` of one run into the files
    /// one run of the whole writes.
    Merge(MergeArgs),
}

/// Arguments of `bench merge`.
#[derive(Debug, clap::Args)]
pub struct MergeArgs {
    /// The shards' output directories, in any order.
    #[arg(required = true, value_name = "DIR")]
    pub dirs: Vec<PathBuf>,
    /// Output directory.
    #[arg(long, short = 'o', value_name = "DIR")]
    pub out: PathBuf,
    /// Overwrite the files of an earlier run in --out.
    #[arg(long)]
    pub force: bool,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Arguments of a bench run.
#[derive(Debug, clap::Args)]
pub struct RunArgs {
    /// Skyway network (JSON) [default: the shipped instances/findings-195/network.json].
    #[arg(long, value_name = "FILE")]
    pub network: Option<PathBuf>,
    /// Parameter profile (TOML) [default: the shipped instances/profiles/paper-findings.toml].
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Read the paper word for word where it can be read several ways (see `solve --help`).
    #[arg(long)]
    pub literal: bool,
    /// Request set (JSON) [default: the shipped paper-195 requests].
    #[arg(long, value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// Consider only the first N requests of the set [default: all] (a count of requests, as
    /// `--exact-limit`; limits in seconds are `--hop-time-limit`). `--limit` is its former name.
    #[arg(long = "request-limit", alias = "limit", value_name = "N")]
    pub limit: Option<usize>,
    /// Sharing policies, comma-separated (`none` is the paper's baseline without support
    /// drones: planned once, under location-aware, when both positionings are asked).
    #[arg(long, value_enum, value_delimiter = ',', default_value = "none,pb,fb")]
    pub sharing: Vec<SharingPolicy>,
    /// Support positionings, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "location-aware,energy-aware"
    )]
    pub positioning: Vec<Positioning>,
    /// Route methods, comma-separated.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "sequential,astar,dijkstra,floyd-warshall"
    )]
    pub route: Vec<RouteMethod>,
    /// Do not plan the optimal routes the route gaps are measured against.
    #[arg(long)]
    pub no_gap: bool,
    /// Do not compute each request's joint optimum (`--route optimal --sharing exact` over the
    /// swarms of both positionings and the swarm without support drones), nor split every
    /// heuristic combination's gap to it into sharing, route and swarm parts (`joint.csv`, the
    /// `gap_*` columns of `requests.csv`, the split table and `figures/gap-split.svg`), which a
    /// run computes by default.
    #[arg(long, conflicts_with = "joint")]
    pub no_joint: bool,
    /// The joint optimum and the gap split, the default (kept so that earlier command lines run).
    #[arg(long, hide = true)]
    pub joint: bool,
    /// Requests (the first of the set) whose hops under PB and FB are solved again by the
    /// continuous-time model and the fluid bound, and whose stops' LPT node times are compared with the exact ones.
    #[arg(long, value_name = "N", default_value_t = bench::DEFAULT_EXACT_LIMIT)]
    pub exact_limit: usize,
    /// Hop models: MILP backend.
    #[arg(
        long,
        value_parser = super::inputs::backend_value_parser(),
        default_value_t = crate::solver::MilpBackend::default()
    )]
    pub backend: crate::solver::MilpBackend,
    /// Hop models: wall-clock limit of each solve, seconds [default: none] (a solve it stops has
    /// no optimum, and its hop's gap is taken against the fluid `bound`; with it, the files
    /// depend on the machine and its load).
    #[arg(long = "hop-time-limit", allow_negative_numbers = true)]
    pub hop_time_limit_s: Option<f64>,
    /// Hop models: branch-and-bound nodes of each MILP call, the same on every machine.
    #[arg(long = "hop-node-limit", value_name = "N", default_value_t = crate::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT)]
    pub hop_node_limit: u64,
    /// Hop models: longest period of the grid MILP's grid, minutes (checked; the bench's hop
    /// table uses the continuous-time model, which has no grid).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub period_min: f64,
    /// Hop models: re-ordering allowed (`paper` or `none`).
    #[arg(long, value_enum, default_value_t = crate::eaas::exact::Reorder::Paper)]
    pub reorder: crate::eaas::exact::Reorder,
    /// Node limit of the exact node time at every stop.
    #[arg(long, value_name = "N", default_value_t = crate::node_time::DEFAULT_STOP_NODE_LIMIT)]
    pub node_limit: u64,
    /// Width of the distance buckets, km.
    #[arg(
        long,
        value_name = "KM",
        default_value_t = bench::DEFAULT_DISTANCE_BUCKET_KM,
        allow_negative_numbers = true
    )]
    pub distance_bucket_km: f64,
    /// Plan only the requests at positions I, I + N, I + 2N, ... (0 <= I < N); merge the shards
    /// with `bench merge`.
    #[arg(long, value_name = "I/N", value_parser = parse_shard)]
    pub shard: Option<Shard>,
    /// Worker threads [default: the number of available cores].
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Wall-clock budget of the whole run, seconds: no request is started after it, and the
    /// files are those of the requests before the first one left out (`config.json` records
    /// that `--request-limit`, so they are the files of `--request-limit K` for that K; stderr says what
    /// remains) [default: none].
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub time_budget: Option<f64>,
    /// Output directory.
    #[arg(long, short = 'o', value_name = "DIR", required = true)]
    pub out: Option<PathBuf>,
    /// Overwrite the files of an earlier run in --out.
    #[arg(long)]
    pub force: bool,
    /// Print the summary as JSON (the table goes to stdout otherwise).
    #[arg(long)]
    pub json: bool,
}

fn parse_shard(text: &str) -> std::result::Result<Shard, String> {
    Shard::parse(text).map_err(|e| e.to_string().replace("invalid input, 1 problem(s):\n", ""))
}

impl RunArgs {
    /// The run's settings, with `command` (the process arguments) to record in `summary.json`.
    pub fn settings(self, command: Vec<String>) -> BenchSettings {
        BenchSettings {
            instance: InstanceFiles {
                network: self.network,
                profile: self.profile,
                literal: self.literal,
            },
            requests: self.requests,
            limit: self.limit,
            sharing: self.sharing,
            positioning: self.positioning,
            route: self.route,
            gap: !self.no_gap,
            joint: !self.no_joint,
            exact_limit: self.exact_limit,
            exact: ExactChoices {
                backend: self.backend,
                hop_time_limit_s: self.hop_time_limit_s,
                hop_node_limit: self.hop_node_limit,
                period_min: self.period_min,
                reorder: self.reorder,
            },
            node_limit: self.node_limit,
            distance_bucket_km: self.distance_bucket_km,
            shard: self.shard.unwrap_or(Shard::WHOLE),
            threads: self.threads,
            time_budget_s: self.time_budget,
            out: self.out.expect("clap requires --out"),
            force: self.force,
            command,
        }
    }
}

/// Runs the subcommand.
pub fn run(args: BenchArgs) -> Result<i32> {
    let command: Vec<String> = std::env::args().collect();
    match args.command {
        Some(BenchCommand::Merge(m)) => {
            let dirs: Vec<&Path> = m.dirs.iter().map(PathBuf::as_path).collect();
            // The inputs are read and verified whole before the output is touched.
            let (config, data) = bench::merge(&dirs)?;
            if let Some(shard) = dirs.iter().find(|d| same_dir(d, &m.out)) {
                return Err(Error::invalid(
                    "E7010",
                    "--out",
                    format!("{} is one of the shards merged", shard.display()),
                    "give a new directory for the merged run, such as sweep/merged",
                ));
            }
            bench::may_write(&m.out, m.force)?;
            bench::unmark_complete(&m.out)?;
            let summary = bench::write_outputs(&m.out, &config, &data, command)?;
            report(&summary, &m.out, m.json)
        }
        None => run_grid(args.run, command),
    }
}

/// Whether two paths name one directory (both exist and resolve to the same place).
fn same_dir(a: &Path, b: &Path) -> bool {
    match (std::fs::canonicalize(a), std::fs::canonicalize(b)) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// `N requests x M combinations`.
fn what(size: GridSize) -> String {
    format!(
        "{} x {}",
        super::count(size.requests, "request"),
        super::count(size.combinations, "combination")
    )
}

fn run_grid(args: RunArgs, command: Vec<String>) -> Result<i32> {
    let json = args.json;
    let settings = args.settings(command);
    let bar = super::progress::bar(0, "plans");
    let run = bench::run_grid(
        &settings,
        &|size| {
            bar.set_length(size.plans());
            bar.set_message(what(size));
        },
        &|n| bar.inc(n),
    )?;
    bar.finish_and_clear();
    for note in &run.notes {
        eprintln!("{note}");
    }
    if let Some(stop) = run.budget {
        eprintln!("{stop}");
    }
    eprintln!(
        "{} on {} in {:.1} s",
        what(run.size),
        super::count(run.threads, "thread"),
        run.elapsed_s
    );
    report(&run.summary, &settings.out, json)
}

/// Prints the summary: a table on stdout (or the JSON), the files written on stderr.
fn report(summary: &Summary, out: &Path, json: bool) -> Result<i32> {
    if json {
        super::print_json(summary)?;
    } else {
        print_table(summary)?;
    }
    let mut files: Vec<String> = DATA_FILES.iter().map(|f| f.to_string()).collect();
    files.push("summary.json".into());
    files.extend(summary.figures.iter().cloned());
    if summary.config.shard == Shard::WHOLE {
        files.push(bench::report::REPORT_FILE.into());
    }
    eprintln!("wrote {} in {}", files.join(", "), out.display());
    Ok(0)
}

/// The joint optimum and the split table (without `--no-joint`).
fn print_joint(s: &Summary, j: &bench::JointSummary) -> Result<()> {
    outln!("{}", table::joint_line(j));
    let row = |c: &[String]| {
        format!(
            "{:<36} {:>7} {:>7} {:>17} {:>17} {:>17} {:>17}",
            c[0], c[1], c[2], c[3], c[4], c[5], c[6]
        )
    };
    outln!("{}", row(&table::SPLIT_COLUMNS.map(String::from)));
    for cells in s.methods.iter().filter_map(table::split_row) {
        outln!("{}", row(&cells));
    }
    outln!("{}", table::split_note(s));
    Ok(())
}

fn print_table(s: &Summary) -> Result<()> {
    outln!("{}", table::heading(s));
    let row = |c: &[String]| {
        format!(
            "{:<36} {:>13} {:>9} {:>9} {:>7} {:>9} {:>9} {:>9} {:>11}",
            c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]
        )
    };
    outln!("{}", row(&table::METHOD_COLUMNS.map(String::from)));
    for m in &s.methods {
        outln!("{}", row(&table::method_row(m)));
    }
    if s.config.gap {
        outln!("{}", table::ROUTE_GAP_NOTE);
    }
    for line in table::exact_subset_lines(s) {
        outln!("{line}");
    }
    if let Some(j) = &s.joint {
        print_joint(s, j)?;
    }
    outln!("paper's findings:");
    for f in &s.findings {
        outln!("  {:<3} {:<14} {}", f.id, f.verdict.to_string(), f.claim);
        if f.verdict != Verdict::NotMeasured {
            outln!("      ours: {}; paper: {} [{}]", f.ours, f.paper, f.figure);
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::eaas::exact_hop::ExactSettings;
    use clap::Parser;

    #[test]
    fn the_default_arguments_are_the_cores_defaults() {
        let cli = crate::cli::Cli::try_parse_from(["swarmplan", "bench", "--out", "x"]).unwrap();
        let crate::cli::Command::Bench(args) = cli.command else {
            panic!("parsed as bench")
        };
        let s = args.run.settings(vec!["swarmplan".into()]);
        assert_eq!(s.exact, ExactChoices::default());
        assert_eq!(
            ExactChoices::default().settings().unwrap(),
            ExactSettings::default()
        );
        assert_eq!(s.instance, InstanceFiles::default());
        assert_eq!(
            (s.shard, s.gap, s.joint, s.force),
            (Shard::WHOLE, true, true, false)
        );
        assert_eq!(s.out, PathBuf::from("x"));
        assert_eq!(s.command, vec!["swarmplan".to_string()]);
    }
}
