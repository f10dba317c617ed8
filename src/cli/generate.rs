//! `swarmplan generate network|requests|node-time`: write a seeded synthetic network, request set,
//! or node-time instance of a classical P||Cmax benchmark class.

use crate::error::both;
use crate::error::{Result, Violation};
use crate::generate::pcmax::{generate_pcmax, PcmaxClass, PcmaxParams, MAX_JOBS, MAX_PADS};
use crate::generate::{generate_network, generate_requests, NetworkParams, RequestParams};
use crate::generate::{DEFAULT_MAX_PACKAGE_KG, DEFAULT_REQUESTS, MAX_REQUESTS};
use crate::generate::{DEFAULT_NODES, DEFAULT_SPACING_M, MAX_NODES, MIN_NODES};
use crate::problem::io::write_json;
use crate::problem::read_network;
use std::path::PathBuf;

/// What to generate.
#[derive(Debug, clap::Subcommand)]
pub enum GenerateCommand {
    /// A seeded synthetic rooftop network (connected, node degree 2-4, 0-4 pads, wind < 13.8 m/s).
    Network(NetworkArgs),
    /// A seeded request set over a network (connected source/destination, 2-8 packages each).
    Requests(RequestsArgs),
    /// A seeded node-time instance (P||Cmax) of a classical benchmark class, in the file format
    /// `swarmplan node-time --file` reads; classes and sources in models/generate.md.
    NodeTime(NodeTimeArgs),
}

/// Arguments of `generate node-time`.
#[derive(Debug, clap::Args)]
pub struct NodeTimeArgs {
    /// Benchmark class: u1-u3 (França et al. 1994), nu1-nu3 (Frangioni et al. 2004), l1-l7
    /// (Lawrinenko 2017), e1-1-20, e1-20-50, e2-100-800, e3-1-100, e3-100-200, e4-1-20,
    /// e4-20-50, e4-1-100, e4-50-100, e4-100-200, e4-100-800 (Berndt et al. 2022).
    #[arg(long, value_parser = parse_class)]
    pub class: PcmaxClass,
    /// Number of jobs (drones).
    #[arg(long, value_parser = parse_jobs, allow_hyphen_values = true)]
    pub jobs: usize,
    /// Number of machines (pads).
    #[arg(long, value_parser = parse_pads, allow_hyphen_values = true)]
    pub pads: usize,
    /// Seed of the random generator; the same seed writes the same file.
    #[arg(long, value_parser = parse_node_time_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Output JSON file; the instance goes to stdout without it.
    #[arg(short = 'o', long = "output")]
    pub output: Option<PathBuf>,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `generate network`.
#[derive(Debug, clap::Args)]
pub struct NetworkArgs {
    /// Number of rooftop nodes.
    #[arg(long, default_value_t = DEFAULT_NODES, value_parser = parse_nodes, allow_hyphen_values = true)]
    pub nodes: usize,
    /// Seed of the random generator; the same seed writes the same file.
    #[arg(long, value_parser = parse_network_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Street-grid spacing in metres.
    #[arg(long, default_value_t = DEFAULT_SPACING_M, value_parser = parse_spacing, allow_hyphen_values = true)]
    pub spacing_m: f64,
    /// Output JSON file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub force: bool,
}

/// Arguments of `generate requests`.
#[derive(Debug, clap::Args)]
pub struct RequestsArgs {
    /// Network JSON file the requests run on.
    #[arg(long)]
    pub network: PathBuf,
    /// Number of requests.
    #[arg(long, default_value_t = DEFAULT_REQUESTS, value_parser = parse_count, allow_hyphen_values = true)]
    pub count: usize,
    /// Seed of the random generator; the same seed writes the same file.
    #[arg(long, value_parser = parse_requests_seed, allow_hyphen_values = true)]
    pub seed: u64,
    /// Largest package mass in kg (the drone's max payload).
    #[arg(long, default_value_t = DEFAULT_MAX_PACKAGE_KG, value_parser = parse_max_package, allow_hyphen_values = true)]
    pub max_package_kg: f64,
    /// Output JSON file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub force: bool,
}

fn parse_nodes(s: &str) -> std::result::Result<usize, Violation> {
    match s.trim().parse::<usize>() {
        Ok(n) if (MIN_NODES..=MAX_NODES).contains(&n) => Ok(n),
        _ => Err(Violation::new(
            "E1901",
            "--nodes",
            format!("'{s}' is not a whole number from {MIN_NODES} to {MAX_NODES}"),
            "give one",
        )),
    }
}

fn parse_spacing(s: &str) -> std::result::Result<f64, Violation> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (1.0..=100_000.0).contains(&v) => Ok(v),
        _ => Err(Violation::new(
            "E1902",
            "--spacing-m",
            format!("'{s}' is not a number from 1 to 100000"),
            "give a spacing in metres",
        )),
    }
}

fn parse_network_seed(s: &str) -> std::result::Result<u64, Violation> {
    parse_seed(s, "E1903")
}

fn parse_requests_seed(s: &str) -> std::result::Result<u64, Violation> {
    parse_seed(s, "E3904")
}

fn parse_seed(s: &str, code: &'static str) -> std::result::Result<u64, Violation> {
    s.trim().parse::<u64>().map_err(|_| {
        Violation::new(
            code,
            "--seed",
            format!("'{s}' is not a whole number from 0 to {}", u64::MAX),
            "give one",
        )
    })
}

fn parse_node_time_seed(s: &str) -> std::result::Result<u64, Violation> {
    parse_seed(s, "E3908")
}

fn parse_class(s: &str) -> std::result::Result<PcmaxClass, Violation> {
    PcmaxClass::from_name(s).ok_or_else(|| {
        let names: Vec<&str> = PcmaxClass::ALL.iter().map(|c| c.name()).collect();
        Violation::new(
            "E3905",
            "--class",
            format!("'{s}' is not a benchmark class"),
            format!("give one of {}", names.join(", ")),
        )
    })
}

fn parse_jobs(s: &str) -> std::result::Result<usize, Violation> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_JOBS).contains(&n) => Ok(n),
        _ => Err(Violation::new(
            "E3906",
            "--jobs",
            format!("'{s}' is not a whole number from 1 to {MAX_JOBS}"),
            "give one",
        )),
    }
}

fn parse_pads(s: &str) -> std::result::Result<usize, Violation> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_PADS).contains(&n) => Ok(n),
        _ => Err(Violation::new(
            "E3907",
            "--pads",
            format!("'{s}' is not a whole number from 1 to {MAX_PADS}"),
            "give one",
        )),
    }
}

fn parse_count(s: &str) -> std::result::Result<usize, Violation> {
    match s.trim().parse::<usize>() {
        Ok(n) if (1..=MAX_REQUESTS).contains(&n) => Ok(n),
        _ => Err(Violation::new(
            "E3901",
            "--count",
            format!("'{s}' is not a whole number from 1 to {MAX_REQUESTS}"),
            "give one",
        )),
    }
}

fn parse_max_package(s: &str) -> std::result::Result<f64, Violation> {
    match s.trim().parse::<f64>() {
        Ok(v) if v.is_finite() && (0.001..=1000.0).contains(&v) => Ok(v),
        _ => Err(Violation::new(
            "E3902",
            "--max-package-kg",
            format!("'{s}' is not a mass from 0.001 to 1000 kg"),
            "give one (paper: 1.4)",
        )),
    }
}

/// Runs the subcommand: writes the file and reports what it wrote on stderr.
///
/// # Errors
/// [`crate::error::Error::Invalid`] for parameters out of range or an invalid network file (exit code 2);
/// E0008, E0009 when a file cannot be read; E0013 when the output file exists and `--force` is not
/// given; [`crate::error::Error::Io`] (E0010) when one cannot be written.
pub fn run(cmd: GenerateCommand) -> Result<i32> {
    match cmd {
        GenerateCommand::Network(a) => {
            super::may_write(&a.output, a.force)?;
            let network = generate_network(&NetworkParams {
                nodes: a.nodes,
                seed: a.seed,
                spacing_m: a.spacing_m,
            })?;
            write_json(&a.output, &network)?;
            eprintln!(
                "wrote {} nodes, {} edges (seed {}) to {}",
                network.nodes.len(),
                network.edges.len(),
                a.seed,
                super::output_name(&a.output)
            );
        }
        GenerateCommand::Requests(a) => {
            super::distinct_from_inputs(&[&a.output], &[&a.network])?;
            let (_, (_, graph)) = both(
                super::may_write(&a.output, a.force),
                read_network(&a.network),
            )?;
            let set = generate_requests(
                &graph,
                &RequestParams {
                    count: a.count,
                    seed: a.seed,
                    max_package_kg: a.max_package_kg,
                },
            )?;
            write_json(&a.output, &set)?;
            eprintln!(
                "wrote {} requests (seed {}) to {}",
                set.requests.len(),
                a.seed,
                super::output_name(&a.output)
            );
        }
        GenerateCommand::NodeTime(a) => {
            if let Some(out) = &a.output {
                super::may_write(out, a.force)?;
            }
            let file = generate_pcmax(&PcmaxParams {
                class: a.class,
                jobs: a.jobs,
                pads: a.pads,
                seed: a.seed,
            })?;
            let grid = if a.class.published_grid(a.jobs, a.pads) {
                "in the published grid"
            } else {
                "outside the published grid"
            };
            let what = format!(
                "class {} ({}), {} jobs, {} pads ({grid}), seed {}",
                a.class,
                a.class.source(),
                a.jobs,
                a.pads,
                a.seed
            );
            match &a.output {
                Some(out) => {
                    write_json(out, &file)?;
                    eprintln!("wrote {what} to {}", super::output_name(out));
                    eprintln!("solve with: swarmplan node-time --file {}", out.display());
                }
                None => {
                    crate::cli::print_json(&file)?;
                    eprintln!(
                        "wrote {what} to stdout; solve with: swarmplan node-time --file FILE"
                    );
                }
            }
            if !a.class.note().is_empty() {
                eprintln!("note: {}", a.class.note());
            }
        }
    }
    Ok(0)
}
