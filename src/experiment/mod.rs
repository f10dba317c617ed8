//! The experiment core shared by `swarmplan batch` and `swarmplan bench`: which method
//! combinations a run plans ([`Methods`]), what each is compared with ([`Experiment`]: the
//! optimal route of the same sharing policy for the route gap, the exact node time for LPT's gap
//! at every stop, the joint optimum for the gap split), the per-combination summaries of a
//! planned grid ([`summarise_grid`]), and tables written as CSV through serde ([`write_csv`]).
//! User guide: the command `batch` (`docs/src/commands/batch.md`) and "The bench report"
//! (`docs/src/bench-report.md`).
//!
//! It sits above [`crate::compose`], which plans the grid, and below [`crate::bench`] and the
//! command line, which give it their arguments and print or write what it returns; it knows
//! nothing of how the arguments were read.

mod summary;

pub use summary::{
    summarise_grid, write_summaries, GridSummary, Outcome, RouteGapCells, Summary, SummaryRow,
};

use crate::compose::{lpt_gap, Plan, PlanOptions, RouteMethod, RoutePair};
use crate::eaas::SharingPolicy;
use crate::error::{show, Error, Result};
use crate::precompose::Positioning;
use crate::problem::Request;
use serde::{Serialize, Serializer};

/// The method lists a run is asked for: every combination of a sharing policy, a support
/// positioning and a route method.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Methods {
    /// Sharing policies.
    pub sharing: Vec<SharingPolicy>,
    /// Support positionings.
    pub positioning: Vec<Positioning>,
    /// Route methods.
    pub route: Vec<RouteMethod>,
    /// Support drones of every combination (`None`: the redundancy table decides).
    pub support: Option<usize>,
}

/// How [`Methods::combinations`] treats the baseline `none`, which flies no support drone and
/// so plans the same under every positioning.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Baseline {
    /// Every combination of the lists, in their order, repeats included (`batch`).
    UnderEveryPositioning,
    /// `none` only under location-aware when that positioning is asked, and each combination
    /// once (`bench`).
    Once,
}

impl Methods {
    /// The paper's grid (`batch --all`): sharing `none`, `pb`, `fb`; both positionings; every
    /// route method but `optimal`.
    pub fn paper_grid(support: Option<usize>) -> Methods {
        Methods {
            sharing: vec![SharingPolicy::None, SharingPolicy::Pb, SharingPolicy::Fb],
            positioning: vec![Positioning::LocationAware, Positioning::EnergyAware],
            route: RouteMethod::ALL.to_vec(),
            support,
        }
    }

    /// The combinations, in the order route, sharing, positioning.
    pub fn combinations(&self, baseline: Baseline) -> Vec<PlanOptions> {
        let location_aware = self.positioning.contains(&Positioning::LocationAware);
        let mut combos = Vec::new();
        for &route in &self.route {
            for &sharing in &self.sharing {
                for &positioning in &self.positioning {
                    let o = PlanOptions {
                        sharing,
                        positioning,
                        route,
                        support: self.support,
                    };
                    match baseline {
                        Baseline::UnderEveryPositioning => combos.push(o),
                        Baseline::Once => {
                            if !sharing.flies_support()
                                && location_aware
                                && positioning != Positioning::LocationAware
                            {
                                continue;
                            }
                            if !combos.contains(&o) {
                                combos.push(o);
                            }
                        }
                    }
                }
            }
        }
        combos
    }
}

/// Whether a run's options apply to its combinations, the same in `solve`, `batch` and `bench`:
/// an option that applies to none of them is refused, one that applies to some only is noted
/// (the notes returned, for stderr).
///
/// - `--gap` (`route_gap`): no route gap under `fair` (the fair QP's layout is no optimum of any
///   hop, so `--route optimal` does not take it): E0015 when every combination is `fair`;
/// - `--support` above 0: `none`, the paper's baseline, flies no support drone: E0030 when every
///   combination is `none`.
///
/// # Errors
/// [`Error::Invalid`] E0015, E0030.
pub fn applicable_options(
    combos: &[PlanOptions],
    route_gap: bool,
    support: Option<usize>,
) -> Result<Vec<String>> {
    let mut notes = Vec::new();
    let fair = combos
        .iter()
        .filter(|c| c.sharing == SharingPolicy::Fair)
        .count();
    if route_gap && fair > 0 {
        if fair == combos.len() {
            return Err(Error::invalid(
                "E0015",
                "--gap",
                "--gap compares with --route optimal, which supports the simulated sharing \
                 policies (none, idle-support, pb, fb) and exact, not fair",
                "use --gap with --sharing none, idle-support, pb, fb or exact",
            ));
        }
        notes.push(format!(
            "note: --gap: the {fair} combination(s) with --sharing fair have no route gap (the \
             fair QP's layout is no optimum of any hop); their gap cells stay empty"
        ));
    }
    let none = combos
        .iter()
        .filter(|c| c.sharing == SharingPolicy::None)
        .count();
    // `--support 0` agrees with `none`, which flies no support drone.
    if let (Some(k @ 1..), true) = (support, none > 0) {
        if none == combos.len() {
            return Err(Error::invalid(
                "E0030",
                "--support",
                format!(
                    "--support {k} with --sharing none: the paper's baseline flies no support \
                     drone"
                ),
                "leave --support out, or use a sharing policy that flies support drones \
                 (idle-support, pb, fb, exact, fair)",
            ));
        }
        notes.push(format!(
            "note: --support {k} does not apply to the {none} combination(s) with --sharing none \
             (the paper's baseline flies no support drone)"
        ));
    }
    Ok(notes)
}

/// The combinations a run reports and what each is compared with:
///
/// - the route gap (with `route_gap`): a combination with a heuristic route and a simulated or
///   exact (not `fair`) sharing policy, against the optimal route of the same sharing policy,
///   positioning and support drones ([`Experiment::route_reference`]), planned with it;
/// - LPT's gap at every recharging stop, always, against the stop's exact node time when proven
///   ([`lpt_gaps`]);
/// - the joint optimum (with `joint`, `bench`): every heuristic combination's gap to the
///   request's joint optimum, split into sharing, route and swarm parts
///   ([`crate::compose::Context::joint_split`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Experiment {
    /// The combinations reported, in the order of the rows.
    pub combos: Vec<PlanOptions>,
    /// Whether the route gaps are measured.
    pub route_gap: bool,
    /// Whether each request's joint optimum is computed and the gaps to it split.
    pub joint: bool,
}

impl Experiment {
    /// The optimal route `combo`'s route gap is measured against, when there is one.
    pub fn route_reference(&self, combo: &PlanOptions) -> Option<PlanOptions> {
        (self.route_gap
            && combo.route != RouteMethod::Optimal
            && combo.sharing != SharingPolicy::Fair)
            .then_some(PlanOptions {
                route: RouteMethod::Optimal,
                ..*combo
            })
    }

    /// The combinations planned: those reported, then the references of the route gaps that
    /// are not among them, each once.
    pub fn planned(&self) -> Vec<PlanOptions> {
        let mut combos = self.combos.clone();
        for c in self.combos.iter().filter_map(|c| self.route_reference(c)) {
            if !combos.contains(&c) {
                combos.push(c);
            }
        }
        combos
    }

    /// For each reported combination, the position in [`Experiment::planned`] of its route gap
    /// reference.
    pub fn route_reference_positions(&self) -> Vec<Option<usize>> {
        let planned = self.planned();
        self.combos
            .iter()
            .map(|c| {
                let reference = self.route_reference(c)?;
                planned.iter().position(|x| *x == reference)
            })
            .collect()
    }
}

/// The worker threads of a grid: `asked`, or the number of available cores.
///
/// # Errors
/// E0004 for 0 threads or more than [`MAX_THREADS`].
pub fn threads(asked: Option<usize>) -> Result<usize> {
    let threads = asked.unwrap_or_else(|| {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    });
    if threads == 0 || threads > MAX_THREADS {
        return Err(Error::invalid(
            "E0004",
            "--threads",
            format!("{threads} worker threads"),
            format!(
                "give --threads from 1 to {MAX_THREADS} (the cores of the machine are the most \
                 that help)"
            ),
        ));
    }
    Ok(threads)
}

/// The most worker threads a run may ask for: far above any machine's cores, and low enough
/// that starting them costs nothing to speak of.
pub const MAX_THREADS: usize = 1024;

/// The requests a run plans: the first `limit` of the set (all without one).
///
/// # Errors
/// E0005 when none is left.
pub fn first_requests(mut requests: Vec<Request>, limit: Option<usize>) -> Result<Vec<Request>> {
    requests.truncate(limit.unwrap_or(usize::MAX));
    if requests.is_empty() {
        return Err(Error::invalid(
            "E0005",
            "--request-limit / --requests",
            "no request to plan",
            "give a request file with requests and a --request-limit of 1 or more",
        ));
    }
    Ok(requests)
}

/// The deadline of a run's wall-clock budget of `budget_s` seconds from now (`None`: none).
///
/// # Errors
/// E0028 when `budget_s` is not a time in (0, 1e7] seconds.
pub fn deadline(budget_s: Option<f64>) -> Result<Option<std::time::Instant>> {
    let Some(s) = budget_s else {
        return Ok(None);
    };
    if !(s > 0.0 && s <= 1e7) {
        return Err(Error::invalid(
            "E0028",
            "--time-budget",
            format!("{} is not a time in (0, 1e7] seconds", show(s)),
            "give the run's budget in seconds, such as 600, or leave it out for none",
        ));
    }
    Ok(Some(
        std::time::Instant::now() + std::time::Duration::from_secs_f64(s),
    ))
}

/// A run its time budget stopped: `planned` of the `asked` requests were planned, and the output
/// is the one `--request-limit limit` gives. Its `Display` is the message the front ends print.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct BudgetStop {
    /// Requests planned.
    pub planned: usize,
    /// Requests asked.
    pub asked: usize,
    /// The request limit whose output the run's is.
    pub limit: usize,
}

impl BudgetStop {
    /// The stop, when fewer requests than asked were planned.
    pub fn new(planned: usize, asked: usize, limit: usize) -> Option<BudgetStop> {
        (planned < asked).then_some(BudgetStop {
            planned,
            asked,
            limit,
        })
    }
}

impl std::fmt::Display for BudgetStop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "time budget reached: {} of {} requests planned (the output is the one \
             --request-limit {} gives); {} requests remain: run again without --time-budget, or \
             with a larger one, to plan them",
            self.planned,
            self.asked,
            self.limit,
            self.asked - self.planned
        )
    }
}

/// What a gap needs of one planned request: its delivery time when delivered, and whether every
/// node time behind it was proven (true but for an `optimal` route whose search a node limit
/// stopped at some stop).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Delivery {
    /// Delivery time, min, when delivered.
    pub dt_min: Option<f64>,
    /// Whether every node time of the route's search was proven.
    pub proven: bool,
}

impl Delivery {
    /// The delivery of `plan`.
    pub fn of(plan: &Plan) -> Delivery {
        Delivery {
            dt_min: plan.delivered().then_some(plan.dt_min),
            proven: plan.route_optimality.is_none_or(|o| o.proven()),
        }
    }

    /// The pair of a route gap: this plan against its `reference` (the optimal route).
    pub fn against(self, reference: Delivery) -> RoutePair {
        RoutePair {
            heuristic_dt_min: self.dt_min,
            optimal_dt_min: reference.dt_min,
            optimal_proven: reference.proven,
        }
    }
}

/// LPT's relative gap at every recharging stop of a delivered plan, in flight order, against the
/// stop's exact node time (`None` where that is only an incumbent); empty for a plan that does
/// not deliver.
///
/// # Errors
/// Only for a stop whose charge times are not valid node-time input.
pub fn lpt_gaps(plan: &Plan) -> Result<Vec<Option<f64>>> {
    if !plan.delivered() {
        return Ok(Vec::new());
    }
    plan.hops
        .iter()
        .filter_map(|h| h.stop.as_ref())
        .map(lpt_gap)
        .collect()
}

/// Writes `rows` as CSV to `out`: a header of the first row's field names, then a line per row
/// (nothing at all without rows).
///
/// # Errors
/// The writer's error, or one for a row that is not a flat record.
pub fn write_csv<W: std::io::Write, T: Serialize>(
    out: W,
    rows: impl IntoIterator<Item = T>,
) -> std::io::Result<()> {
    let mut w = csv::Writer::from_writer(out);
    for row in rows {
        w.serialize(row).map_err(|e| {
            let text = e.to_string();
            match e.into_kind() {
                csv::ErrorKind::Io(e) => e,
                _ => std::io::Error::other(text),
            }
        })?;
    }
    w.flush()
}

/// A number as Rust's `Display` writes it (`0`, not ryu's `0.0`; `0.0000001`, not `1e-7`): the
/// cells of `batch`'s CSV, which are those of its JSON read by eye.
///
/// # Errors
/// The serializer's.
pub fn display_f64<S: Serializer>(value: &f64, s: S) -> std::result::Result<S::Ok, S::Error> {
    s.collect_str(value)
}

/// [`display_f64`] of a number that may be absent (an empty cell).
///
/// # Errors
/// The serializer's.
pub fn display_opt_f64<S: Serializer>(
    value: &Option<f64>,
    s: S,
) -> std::result::Result<S::Ok, S::Error> {
    match value {
        Some(v) => s.collect_str(v),
        None => s.serialize_none(),
    }
}
