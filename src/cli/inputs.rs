//! Loading and validating the instance files shared by several subcommands. Without a path, the
//! shipped paper-195 instance and `paper` profile embedded in the binary are used.

use crate::eaas::exact::Reorder;
use crate::eaas::exact_hop::{ExactChoices, ExactSettings, DEFAULT_HOP_NODE_LIMIT};
use crate::error::{Error, Result};
use crate::experiment::BudgetStop;
use crate::problem::inputs::InstanceFiles;
use crate::problem::shipped::Shipped;
use crate::problem::{Instance, Profile, RequestSet};
use crate::solver::MilpBackend;
use std::path::{Path, PathBuf};

/// File arguments shared by the planning subcommands.
#[derive(Debug, Clone, clap::Args)]
pub struct InstanceArgs {
    /// Skyway network (JSON) [default: the shipped instances/paper-195/network.json].
    #[arg(long, value_name = "FILE")]
    pub network: Option<PathBuf>,
    /// Parameter profile (TOML) [default: the shipped instances/profiles/paper.toml].
    #[arg(long, value_name = "FILE")]
    pub profile: Option<PathBuf>,
    /// Read the paper word for word where it can be read several ways: the profile's
    /// `[readings]` become PB skipping requests before its support drone is free and filling
    /// batteries, FB charging rounds for full drones, Algorithm 1 looking at adjacent nodes only.
    #[arg(long)]
    pub literal: bool,
}

/// Solver settings of the exact and fair sharing policies (`--sharing exact|fair`).
#[derive(Debug, Clone, clap::Args)]
pub struct ExactArgs {
    /// Exact policy: MILP backend of every hop solve.
    #[arg(
        long,
        value_parser = backend_value_parser(),
        default_value_t = MilpBackend::default()
    )]
    pub backend: MilpBackend,
    /// Exact and fair policies: wall-clock limit of each hop solve, seconds [default: none]. A
    /// solve it stops depends on the machine and its load; without it every number is the same
    /// on any machine.
    #[arg(long = "hop-time-limit", allow_negative_numbers = true)]
    pub hop_time_limit_s: Option<f64>,
    /// Exact policy: branch-and-bound nodes of each hop solve's MILP call, the same on every
    /// machine (a solve it stops keeps its incumbent, status `feasible`).
    #[arg(long = "hop-node-limit", value_name = "N", default_value_t = DEFAULT_HOP_NODE_LIMIT)]
    pub hop_node_limit: u64,
    /// Exact policy: longest period of the hop MILP's grid, minutes.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub period_min: f64,
    /// Exact and fair policies: re-ordering allowed (`paper` or `none`).
    #[arg(long, value_enum, default_value_t = Reorder::Paper)]
    pub reorder: Reorder,
}

impl ExactArgs {
    /// The settings as given, unchecked.
    pub fn choices(&self) -> ExactChoices {
        ExactChoices {
            backend: self.backend,
            hop_time_limit_s: self.hop_time_limit_s,
            hop_node_limit: self.hop_node_limit,
            period_min: self.period_min,
            reorder: self.reorder,
        }
    }

    /// The settings, checked ([`ExactChoices::settings`]).
    ///
    /// # Errors
    /// [`crate::error::Error::Invalid`] with every violation.
    pub fn settings(&self) -> Result<ExactSettings> {
        self.choices().settings()
    }
}

impl InstanceArgs {
    /// The files given.
    pub fn files(&self) -> InstanceFiles {
        InstanceFiles {
            network: self.network.clone(),
            profile: self.profile.clone(),
            literal: self.literal,
        }
    }

    /// Reads and validates the network and the profile, reporting every violation of both: a
    /// file that cannot be read or parsed does not hide a problem of the other.
    pub fn load(&self) -> Result<Instance> {
        self.files().load()
    }

    /// [`InstanceArgs::load`] with `shipped` for the files not given.
    pub fn load_or(&self, shipped: &Shipped) -> Result<Instance> {
        self.files().load_or(shipped)
    }

    /// [`InstanceArgs::load`] and [`load_requests`](crate::problem::inputs::load_requests) together, reporting the violations of the
    /// network, the profile and the request set at once.
    pub fn load_with_requests(&self, requests: Option<&Path>) -> Result<(Instance, RequestSet)> {
        self.files().load_with_requests(requests)
    }

    /// Reads and validates the profile alone, for a command that needs no network.
    pub fn load_profile(&self) -> Result<Profile> {
        self.files().load_profile()
    }
}

/// Parses a comma-separated list of numbers, reporting every unreadable entry under `code`;
/// `field` names the option in messages. Empty text gives an empty list.
pub fn parse_list(text: &str, field: &str, code: &'static str) -> Result<Vec<f64>> {
    let mut values = Vec::new();
    let mut violations = Vec::new();
    if text.trim().is_empty() {
        // An empty list is for the caller's own rule (an empty package or time list).
        return Ok(values);
    }
    for (i, part) in text.split(',').enumerate() {
        match part.trim().parse::<f64>() {
            Ok(v) => values.push(v),
            Err(_) => violations.push(crate::error::Violation::new(
                code,
                format!("{field}[{i}]"),
                format!("`{}` is not a number", part.trim()),
                format!("give comma-separated numbers after {field}, such as 60,50,40"),
            )),
        }
    }
    if violations.is_empty() {
        Ok(values)
    } else {
        Err(Error::Invalid(violations))
    }
}

/// Says on stderr, when `--time-budget` stopped a run after `planned` of `asked` requests,
/// what was planned (the output of `--request-limit limit`) and what remains.
pub fn report_budget(planned: usize, asked: usize, limit: usize) {
    if let Some(stop) = BudgetStop::new(planned, asked, limit) {
        eprintln!("{stop}");
    }
}

/// The value parser of `--backend`: a backend of this build, E0012 with the way to build it for
/// a backend this build lacks (`highs` without the feature), and clap's own error (E0007) for any
/// other name. The help lists every known backend, each one missing marked as such.
///
/// # Example
/// ```
/// use clap::Parser;
/// let e = swarmplan::cli::Cli::try_parse_from(["swarmplan", "node-time", "--backend", "glpk",
///     "--pads", "1", "--times", "1"]).unwrap_err();
/// assert!(swarmplan::cli::coded_usage_error(&e).unwrap().contains("[E0007]"));
/// ```
pub fn backend_value_parser(
) -> impl clap::builder::TypedValueParser<Value = crate::solver::MilpBackend> {
    use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
    use clap::ValueEnum;
    let mut values: Vec<PossibleValue> = crate::solver::MilpBackend::value_variants()
        .iter()
        .filter_map(|b| b.to_possible_value())
        .collect();
    for name in crate::solver::known_backend_names() {
        if !values.iter().any(|v| v.get_name() == name) {
            values.push(
                PossibleValue::new(name)
                    .help(format!("not in this build (cargo build --features {name})")),
            );
        }
    }
    PossibleValuesParser::new(values).try_map(|name: String| {
        if let Some(message) = crate::solver::backend_not_built(&name) {
            return Err(message.to_string());
        }
        crate::solver::MilpBackend::from_str(&name, false)
    })
}
