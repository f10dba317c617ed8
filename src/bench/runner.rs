//! A whole bench run, as every front end starts it: the settings checked, the instance and the
//! requests loaded, the [`BenchConfig`] built, the grid planned ([`super::run`]), its files
//! written and read back. The front ends read their arguments into [`BenchSettings`], show the
//! progress [`run_grid`] reports through its callbacks, and print what it returns.

use super::{may_write, Summary, SUMMARY_SCHEMA_VERSION};
use super::{read_data, run, unmark_complete, write_outputs, BenchConfig, BenchData, Shard};
use crate::compose::{Context, RouteMethod};
use crate::eaas::exact_hop::ExactChoices;
use crate::eaas::SharingPolicy;
use crate::error::{both, show, Error, Result};
use crate::experiment::{self, Baseline, BudgetStop, Methods};
use crate::precompose::Positioning;
use crate::problem::inputs::{load_requests, InstanceFiles};
use crate::problem::shipped::{FINDINGS_195, REQUESTS_NAME};
use std::path::PathBuf;
use std::time::Instant;

/// What a bench run is asked, as plain values (the command line's `swarmplan bench` arguments
/// without its output format).
#[derive(Debug, Clone, PartialEq)]
pub struct BenchSettings {
    /// The network and the profile (the shipped findings-195 network and `paper-findings`
    /// profile when not given).
    pub instance: InstanceFiles,
    /// Request set (JSON); `None`: the shipped paper-195 requests.
    pub requests: Option<PathBuf>,
    /// Consider only the first N requests of the set (`None`: all).
    pub limit: Option<usize>,
    /// Sharing policies (`none` is planned once, under location-aware, when both positionings
    /// are asked).
    pub sharing: Vec<SharingPolicy>,
    /// Support positionings.
    pub positioning: Vec<Positioning>,
    /// Route methods.
    pub route: Vec<RouteMethod>,
    /// Plan the optimal routes the route gaps are measured against.
    pub gap: bool,
    /// Compute each request's joint optimum and split the gaps to it.
    pub joint: bool,
    /// Requests (the first of the set) whose hops and stops are solved again exactly.
    pub exact_limit: usize,
    /// The hop models' settings, checked by the run.
    pub exact: ExactChoices,
    /// Node limit of the exact node time at every stop.
    pub node_limit: u64,
    /// Width of the distance buckets, km.
    pub distance_bucket_km: f64,
    /// The requests planned.
    pub shard: Shard,
    /// Worker threads (`None`: the number of available cores).
    pub threads: Option<usize>,
    /// Wall-clock budget of the whole run, seconds (`None`: none).
    pub time_budget_s: Option<f64>,
    /// Output directory.
    pub out: PathBuf,
    /// Overwrite the files of an earlier run in `out`.
    pub force: bool,
    /// The command recorded in `summary.json`.
    pub command: Vec<String>,
}

impl BenchSettings {
    /// The settings of `swarmplan bench --out OUT` with every other option at its default: the
    /// whole shipped request set, sharing `none,pb,fb`, both positionings, the four heuristic
    /// route methods, the route gaps, the joint optimum and the gap split, 5 exact requests, the
    /// default hop settings ([`ExactChoices::default`]),
    /// [`crate::node_time::DEFAULT_STOP_NODE_LIMIT`] nodes per stop, 1 km buckets, the whole run,
    /// every core, no time budget.
    pub fn new(out: PathBuf) -> BenchSettings {
        BenchSettings {
            instance: InstanceFiles::default(),
            requests: None,
            limit: None,
            sharing: vec![SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb],
            positioning: vec![Positioning::LocationAware, Positioning::EnergyAware],
            route: vec![
                RouteMethod::Sequential,
                RouteMethod::Astar,
                RouteMethod::Dijkstra,
                RouteMethod::FloydWarshall,
            ],
            gap: true,
            joint: true,
            exact_limit: DEFAULT_EXACT_LIMIT,
            exact: ExactChoices::default(),
            node_limit: crate::node_time::DEFAULT_STOP_NODE_LIMIT,
            distance_bucket_km: DEFAULT_DISTANCE_BUCKET_KM,
            shard: Shard::WHOLE,
            threads: None,
            time_budget_s: None,
            out,
            force: false,
            command: Vec::new(),
        }
    }
}

/// Requests (the first of the set) whose hops and stops a bench run solves again exactly, by
/// default.
pub const DEFAULT_EXACT_LIMIT: usize = 5;

/// Width of a bench run's distance buckets by default, km.
pub const DEFAULT_DISTANCE_BUCKET_KM: f64 = 1.0;

/// The size of a run's grid: the requests it plans (those of its shard) and the combinations
/// each is planned with (those reported and the references they need).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GridSize {
    /// Requests planned.
    pub requests: usize,
    /// Combinations planned per request.
    pub combinations: usize,
}

impl GridSize {
    /// Request x combination plans.
    pub fn plans(&self) -> u64 {
        (self.requests * self.combinations) as u64
    }
}

/// A bench run's results, as [`run_grid`] returns them.
#[derive(Debug)]
pub struct GridRun {
    /// Notes on options that apply to some combinations only
    /// ([`experiment::applicable_options`]), for stderr.
    pub notes: Vec<String>,
    /// The summary, as written to `summary.json`.
    pub summary: Summary,
    /// The run's configuration, as written to `config.json`.
    pub config: BenchConfig,
    /// The tables, as written and read back.
    pub data: BenchData,
    /// The grid planned (before the time budget, if it stopped the run).
    pub size: GridSize,
    /// Worker threads.
    pub threads: usize,
    /// Wall-clock time of the planning, s.
    pub elapsed_s: f64,
    /// When the time budget stopped the run: what was planned and what remains.
    pub budget: Option<BudgetStop>,
}

/// Runs a bench run (not a merge): the files are written to [`BenchSettings::out`], nothing is
/// printed. `start(size)` is called once before the planning; `done(n)` as `n` more request x
/// combination plans are made (from worker threads).
///
/// # Errors
/// E0004 (threads), E7006 (bucket width), E7005 (an earlier run in `out` without `force`), the
/// combinations' checks, the instance files' and requests' errors, E0005, the hop settings'
/// (E4101, E4105, E4113), E0028 (time budget), and those of planning and writing the files.
pub fn run_grid(
    settings: &BenchSettings,
    start: &dyn Fn(GridSize),
    done: &(dyn Fn(u64) + Sync),
) -> Result<GridRun> {
    let s = settings;
    let out = &s.out;
    let threads = experiment::threads(s.threads)?;
    if !(s.distance_bucket_km.is_finite() && s.distance_bucket_km > 0.0) {
        return Err(Error::invalid(
            "E7006",
            "--distance-bucket-km",
            format!("{} is not a width > 0", show(s.distance_bucket_km)),
            "give the width of the distance buckets in km, such as 1",
        ));
    }
    let combos = Methods {
        sharing: s.sharing.clone(),
        positioning: s.positioning.clone(),
        route: s.route.clone(),
        support: None,
    }
    .combinations(Baseline::Once);
    for c in &combos {
        c.validate()?;
    }
    // The route gaps are on by default (`--no-gap` skips them), not asked for: `fair`'s empty
    // gap cells need no refusal here, as the guide's tables say.
    let notes = experiment::applicable_options(&combos, false, None)?;
    let (instance, set) = both(
        s.instance.load_or(&FINDINGS_195),
        load_requests(s.requests.as_deref()),
    )?;
    let requests = experiment::first_requests(set.requests, s.limit)?;
    let instance = instance.with_requests(requests)?;
    // The inputs are read and valid: only now is an earlier run's directory touched.
    may_write(out, s.force)?;
    unmark_complete(out)?;
    let mut context = Context::new(&instance.network, &instance.graph, &instance.profile);
    context.exact = s.exact.settings()?;
    context.node_limit = Some(s.node_limit);
    context.deadline = experiment::deadline(s.time_budget_s)?;
    let name = |p: &Option<PathBuf>, shipped: &str| {
        p.as_ref()
            .map_or(shipped.to_string(), |p| p.display().to_string())
    };
    let mut config = BenchConfig {
        schema_version: SUMMARY_SCHEMA_VERSION,
        version: env!("CARGO_PKG_VERSION").to_string(),
        inputs_sha256: super::inputs_sha256(
            &instance.network,
            &instance.profile,
            &instance.requests,
        )?,
        network: name(&s.instance.network, FINDINGS_195.network_name),
        profile: name(&s.instance.profile, FINDINGS_195.profile_name)
            + if s.instance.literal {
                " (--literal)"
            } else {
                ""
            },
        requests: name(&s.requests, REQUESTS_NAME),
        combos,
        gap: s.gap,
        joint: s.joint,
        limit: instance.requests.len(),
        exact_limit: s.exact_limit,
        milp: context.exact.milp,
        node_limit: context.node_limit,
        distance_bucket_m: s.distance_bucket_km * 1000.0,
        shard: s.shard,
    };
    let size = GridSize {
        requests: (0..config.limit).filter(|&i| config.shard.holds(i)).count(),
        combinations: config.planned_combos().len(),
    };
    start(size);
    let clock = Instant::now();
    let data = run(&context, &instance.requests, &config, threads, done)?;
    let elapsed_s = clock.elapsed().as_secs_f64();
    // A run the time budget stopped is the run of the requests before the first left out.
    let positions: std::collections::BTreeSet<usize> =
        data.requests.iter().map(|r| r.request_index).collect();
    let limit = positions.last().map_or(0, |p| p + 1);
    let budget = BudgetStop::new(positions.len(), size.requests, limit);
    if budget.is_some() {
        config.limit = limit;
        config.inputs_sha256 = super::inputs_sha256(
            &instance.network,
            &instance.profile,
            &instance.requests[..limit],
        )?;
    }
    let summary = write_outputs(out, &config, &data, s.command.clone())?;
    let (config, data) = read_data(out)?;
    Ok(GridRun {
        notes,
        summary,
        config,
        data,
        size,
        threads,
        elapsed_s,
        budget,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bench::CONFIG_FILE;
    use std::sync::atomic::{AtomicU64, Ordering};

    fn settings(out: PathBuf) -> BenchSettings {
        BenchSettings {
            instance: InstanceFiles::default(),
            requests: None,
            limit: Some(3),
            sharing: vec![SharingPolicy::None, SharingPolicy::Pb],
            positioning: vec![Positioning::LocationAware],
            route: vec![RouteMethod::Astar],
            gap: false,
            joint: false,
            exact_limit: 0,
            exact: ExactChoices::default(),
            node_limit: crate::node_time::DEFAULT_STOP_NODE_LIMIT,
            distance_bucket_km: 1.0,
            shard: Shard::WHOLE,
            threads: Some(1),
            time_budget_s: None,
            out,
            force: false,
            command: vec!["run_grid".into()],
        }
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("swarmplan-runner-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        dir
    }

    fn code(e: Error) -> &'static str {
        match e {
            Error::Invalid(v) => v[0].code,
            other => panic!("not a coded violation: {other}"),
        }
    }

    #[test]
    fn a_run_reports_its_progress_and_writes_its_files() {
        let out = scratch("run");
        let s = settings(out.clone());
        let started = AtomicU64::new(0);
        let done = AtomicU64::new(0);
        let run = run_grid(
            &s,
            &|size| started.store(size.plans(), Ordering::Relaxed),
            &|n| {
                done.fetch_add(n, Ordering::Relaxed);
            },
        )
        .unwrap();
        assert_eq!(
            run.size,
            GridSize {
                requests: 3,
                combinations: 2
            }
        );
        assert_eq!(started.load(Ordering::Relaxed), 6);
        assert_eq!(done.load(Ordering::Relaxed), 6);
        assert_eq!((run.config.limit, run.threads), (3, 1));
        assert!(run.budget.is_none());
        assert_eq!(run.data.requests.len(), 6);
        assert_eq!(run.summary.command, s.command);
        assert!(out.join(CONFIG_FILE).exists() && out.join("summary.json").exists());
        // The files of a run are not overwritten unasked.
        assert_eq!(code(run_grid(&s, &|_| {}, &|_| {}).unwrap_err()), "E7005");
        std::fs::remove_dir_all(&out).unwrap();
    }

    #[test]
    fn bad_settings_are_coded_errors_and_write_nothing() {
        let out = scratch("bad");
        let bad = |change: &dyn Fn(&mut BenchSettings)| {
            let mut s = settings(out.clone());
            change(&mut s);
            code(run_grid(&s, &|_| panic!("started"), &|_| {}).unwrap_err())
        };
        assert_eq!(bad(&|s| s.threads = Some(0)), "E0004");
        assert_eq!(bad(&|s| s.distance_bucket_km = 0.0), "E7006");
        assert_eq!(bad(&|s| s.limit = Some(0)), "E0005");
        assert_eq!(bad(&|s| s.exact.period_min = f64::NAN), "E4101");
        assert_eq!(bad(&|s| s.time_budget_s = Some(-1.0)), "E0028");
        assert!(!out.exists());
    }
}
