//! Loading and validating the instance files shared by several subcommands. Without a path, the
//! shipped paper-195 instance and `paper` profile embedded in the binary are used.

use crate::eaas::exact_hop::{ExactSettings, DEFAULT_HOP_NODE_LIMIT};
use crate::eaas::milp::{MilpOptions, Reorder};
use crate::error::{Error, Result, Violation};
use crate::problem::{io, shipped, Instance, Network, Profile, RequestSet};
use crate::solver::MilpBackend;
use std::path::{Path, PathBuf};

pub use crate::problem::shipped::{Shipped, FINDINGS_195, PAPER_195};

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
    /// The settings, checked: a grid step that is finite and positive (E4101), a time limit, when
    /// given, in `(0, 1e6]` seconds (E4105), re-ordering other than `free` (E4113).
    ///
    /// # Errors
    /// [`Error::Invalid`] with every violation.
    pub fn settings(&self) -> Result<ExactSettings> {
        let mut v = Vec::new();
        if !(self.period_min.is_finite() && self.period_min > 0.0) {
            v.push(Violation::new(
                "E4101",
                "--period-min",
                format!("{} is not a finite duration > 0", self.period_min),
                "give the grid step in minutes, such as 1.0",
            ));
        }
        if let Some(t) = self.hop_time_limit_s.filter(|t| !(*t > 0.0 && *t <= 1e6)) {
            v.push(Violation::new(
                "E4105",
                "--hop-time-limit",
                format!("{t} is not a time in (0, 1e6] seconds"),
                "give the time limit of each hop solve in seconds, such as 10, or leave it out \
                 for none",
            ));
        }
        if self.reorder == Reorder::Free {
            v.push(Violation::new(
                "E4113",
                "--reorder",
                "free re-ordering on a route".to_string(),
                "use --reorder paper or none: a free schedule is not always a set of transfers \
                 a plan can carry (`swarmplan eaas --reorder free` studies one hop)",
            ));
        }
        if !v.is_empty() {
            return Err(Error::Invalid(v));
        }
        Ok(ExactSettings {
            milp: MilpOptions {
                period_min: self.period_min,
                reorder: self.reorder,
                backend: self.backend,
                time_limit_s: self.hop_time_limit_s.unwrap_or(f64::INFINITY),
                node_limit: Some(self.hop_node_limit),
            },
            prune_candidates: true,
        })
    }
}

impl InstanceArgs {
    /// Reads and validates the network and the profile, reporting every violation of both: a
    /// file that cannot be read or parsed does not hide a problem of the other.
    pub fn load(&self) -> Result<Instance> {
        self.load_or(&PAPER_195)
    }

    /// [`InstanceArgs::load`] with `shipped` for the files not given.
    pub fn load_or(&self, shipped: &Shipped) -> Result<Instance> {
        let network: Result<Network> = match &self.network {
            Some(p) => io::read_json(p),
            None => io::parse_json(shipped.network, shipped.network_name),
        };
        let (network, profile) = both(network, self.read_profile(shipped))?;
        Instance::new(network, profile)
    }

    /// [`InstanceArgs::load`] and [`load_requests`] together, reporting the violations of the
    /// network, the profile and the request set at once.
    pub fn load_with_requests(&self, requests: Option<&Path>) -> Result<(Instance, RequestSet)> {
        both(self.load(), load_requests(requests))
    }

    /// Reads and validates the profile alone, for a command that needs no network.
    pub fn load_profile(&self) -> Result<Profile> {
        let profile = self.read_profile(&PAPER_195)?;
        let violations = crate::problem::profile::validate_profile(&profile);
        if violations.is_empty() {
            Ok(profile)
        } else {
            Err(Error::Invalid(violations))
        }
    }

    /// The profile given (or the embedded `paper` profile), `--literal` applied, not validated.
    fn read_profile(&self, shipped: &Shipped) -> Result<Profile> {
        let mut profile: Profile = match &self.profile {
            Some(p) => io::read_toml(p)?,
            None => io::parse_toml(shipped.profile, shipped.profile_name)?,
        };
        if self.literal {
            profile.readings = crate::problem::profile::Readings::literal();
        }
        Ok(profile)
    }
}

/// Reads a request set (the file given, or the embedded paper-195 requests) and checks its
/// header and ids (E3001, E3002, E3102); the requests themselves are checked by the caller
/// against the network.
pub fn load_requests(path: Option<&Path>) -> Result<RequestSet> {
    match path {
        Some(p) => shipped::checked_set(io::read_json(p)?),
        None => shipped::requests(),
    }
}

/// Both results, or every violation of both ([`Error::Invalid`] lists joined, first `a`'s);
/// another error of either is returned alone, `a`'s first.
pub fn both<A, B>(a: Result<A>, b: Result<B>) -> Result<(A, B)> {
    match (a, b) {
        (Ok(a), Ok(b)) => Ok((a, b)),
        (Err(Error::Invalid(mut first)), Err(Error::Invalid(second))) => {
            first.extend(second);
            Err(Error::Invalid(first))
        }
        (Err(e), _) | (_, Err(e)) => Err(e),
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
            Err(_) => violations.push(crate::Violation::new(
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

/// The deadline of `--time-budget S` from now.
///
/// # Errors
/// E0028 when `S` is not a time in (0, 1e7] seconds.
pub fn deadline(budget_s: Option<f64>) -> Result<Option<std::time::Instant>> {
    let Some(s) = budget_s else {
        return Ok(None);
    };
    if !(s > 0.0 && s <= 1e7) {
        return Err(Error::invalid(
            "E0028",
            "--time-budget",
            format!("{s} is not a time in (0, 1e7] seconds"),
            "give the run's budget in seconds, such as 600, or leave it out for none",
        ));
    }
    Ok(Some(
        std::time::Instant::now() + std::time::Duration::from_secs_f64(s),
    ))
}

/// Says on stderr, when `--time-budget` stopped a run after `planned` of `asked` requests,
/// what was planned (the output of `--request-limit limit`) and what remains.
pub fn report_budget(planned: usize, asked: usize, limit: usize) {
    if planned < asked {
        eprintln!(
            "time budget reached: {planned} of {asked} requests planned (the output is the one \
             --request-limit {limit} gives); {} requests remain: run again without --time-budget, or \
             with a larger one, to plan them",
            asked - planned
        );
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
            return Err(message);
        }
        crate::solver::MilpBackend::from_str(&name, false)
    })
}
