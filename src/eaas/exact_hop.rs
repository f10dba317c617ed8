//! The exact and fair sharing policies on a hop of a route: the continuous-time configuration
//! LP's optimal schedule ([`SharingPolicy::Exact`], `models/eaas_config.md`) or the fair QP's
//! schedule ([`SharingPolicy::Fair`]) in place of PB or FB, see `models/eaas.md`, "Exact and fair", and `models/compose.md`, "Exact and fair sharing on a
//! route".
//!
//! The objective follows from where the hop ends: at a recharging stop, the node time there
//! ([`Objective::NodeTime`]); at the destination, or at a node passed without charging, any
//! schedule that flies ([`Objective::Feasible`], Algorithm 1's line 8 answered exactly over
//! continuous-time schedules). A hop that flies without sharing always has a schedule: the empty
//! one is the continuous model's first incumbent, and when the fair layout does not fly the empty
//! schedule is flown and the fallback is recorded ([`HopSolve::fallback`]).

use super::exact::dispatch::{self, Solved};
use super::exact::milp::MilpOptions;
use super::exact::EndPads;
use super::exact::{ExactStatus, Objective, Reorder};
use super::{
    simulate_with, ExactPolicy, Heuristic, HopOutcome, HopProblem, PolicyOptions, SharingPolicy,
};
use crate::error::{show, Error, Result, Violation};
use crate::solver::MilpBackend;
use serde::{Deserialize, Serialize};

/// Default branch-and-bound node limit of each hop solve's MILP call on a route
/// (`--hop-node-limit`): deterministic, unlike a wall-clock limit, and above what every hop of
/// the shipped instances needs (models/experiments/eaas_config.md).
pub const DEFAULT_HOP_NODE_LIMIT: u64 = 20_000;

/// Settings of the exact and fair policies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactSettings {
    /// Re-ordering (`paper` or `none`: a `free` schedule is not always a set of transfers),
    /// backend and the time limit of each hop solve (the fair QP uses re-ordering and time limit;
    /// the grid step is not used: the exact policy solves the continuous-time model).
    pub milp: MilpOptions,
    /// Algorithm 1: skip candidate stops whose lower bound (`tt` + the fluid LP's node-time
    /// bound) exceeds the best cost found (default). `false` solves every candidate, the
    /// brute-force cross-check of the pruning (`models/compose.md`).
    pub prune_candidates: bool,
}

impl Default for ExactSettings {
    fn default() -> Self {
        ExactSettings {
            milp: MilpOptions {
                time_limit_s: f64::INFINITY,
                node_limit: Some(DEFAULT_HOP_NODE_LIMIT),
                ..MilpOptions::default()
            },
            prune_candidates: true,
        }
    }
}

/// The exact and fair policies' settings as a front end gives them (the command line's
/// `--backend`, `--hop-time-limit`, `--hop-node-limit`, `--period-min` and `--reorder`), before
/// they are checked into [`ExactSettings`]. The default is the command line's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExactChoices {
    /// MILP backend of every hop solve.
    pub backend: MilpBackend,
    /// Wall-clock limit of each hop solve, seconds (`None`: none).
    pub hop_time_limit_s: Option<f64>,
    /// Branch-and-bound nodes of each hop solve's MILP call.
    pub hop_node_limit: u64,
    /// Longest period of the hop MILP's grid, minutes.
    pub period_min: f64,
    /// Re-ordering allowed.
    pub reorder: Reorder,
}

impl Default for ExactChoices {
    fn default() -> Self {
        ExactChoices {
            backend: MilpBackend::default(),
            hop_time_limit_s: None,
            hop_node_limit: DEFAULT_HOP_NODE_LIMIT,
            period_min: 1.0,
            reorder: Reorder::Paper,
        }
    }
}

impl ExactChoices {
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
                format!("{} is not a finite duration > 0", show(self.period_min)),
                "give the grid step in minutes, such as 1.0",
            ));
        }
        if let Some(t) = self.hop_time_limit_s.filter(|t| !(*t > 0.0 && *t <= 1e6)) {
            v.push(Violation::new(
                "E4105",
                "--hop-time-limit",
                format!("{} is not a time in (0, 1e6] seconds", show(t)),
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

/// What a hop's exact or fair solve optimises, decided by where the hop ends: the one name of a
/// hop's end the planner flies with ([`crate::compose::Planner::fly`]) and a plan records
/// ([`HopSolve::goal`]); the model's [`Objective`] adds the end's pads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum HopGoal {
    /// The node time at the stop ending the hop, minutes (any schedule that flies when the node
    /// has no pads).
    NodeTimeMin,
    /// Any schedule that flies (the hop ends at the destination or passes a node).
    Feasible,
}

/// Why the hop flies the empty schedule instead of the solver's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fallback {
    /// The model stopped at its limit with no schedule; the hop flies without sharing.
    NoSolutionInTime,
    /// The fair QP's schedule, laid out and replayed, does not fly; the hop flies without sharing.
    FairLayoutDoesNotFly,
    /// The backend failed on the hop; the hop flies without sharing.
    BackendError,
    /// The model found no schedule although the empty one flies (a battery within the
    /// evaluation's tolerance `1e-6` mAh below zero at a grid point); the hop flies without
    /// sharing.
    ModelRejectsEmptySchedule,
}

fn proven() -> bool {
    true
}

fn is_proven(proven: &bool) -> bool {
    *proven
}

fn is_zero(count: &usize) -> bool {
    *count == 0
}

/// How the exact or fair solve of one hop ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopSolve {
    /// `exact` (the continuous-time configuration LP) or `fair` (the QP).
    pub policy: SharingPolicy,
    /// What was optimised.
    pub goal: HopGoal,
    /// The solver's status: for `exact`, `optimal` is optimal over every continuous-time
    /// schedule of the re-ordering mode; `optimal_within` within a certified distance of that
    /// optimum, an infimum not attained; `feasible` an incumbent after the time limit;
    /// `infeasible` no continuous-time schedule flies; `time_limit_no_solution` or
    /// `no_schedule_found` none found. For `fair`, `optimal` means
    /// the QP was solved (its schedule is a layout, not an optimum) and `infeasible` that no
    /// continuous-time schedule flies. `None` when the backend failed (see `backend_error`).
    pub status: Option<ExactStatus>,
    /// The backend's message when it failed on this hop (microlp can fail numerically).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub backend_error: Option<String>,
    /// The flown schedule's node time (goal `node_time_min`), minutes.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub objective: Option<f64>,
    /// False when `objective` was not proven within the node limit of a stop
    /// ([`crate::node_time::DEFAULT_STOP_NODE_LIMIT`]): it is then an upper bound. Written only
    /// when false.
    #[serde(default = "proven", skip_serializing_if = "is_proven")]
    pub objective_proven: bool,
    /// A proven lower bound on the node time over the solver's schedules (the optimum when
    /// `optimal`; the LP relaxation or fluid bound after a limit; the fair QP has none).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub bound: Option<f64>,
    /// `exact`, status `optimal_within`: the certified distance of the flown schedule's model
    /// value to the infimum (`bound`), in the objective's unit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub epsilon: Option<f64>,
    /// Longest grid period, minutes (0 for both models, which are continuous in time).
    pub grid_step_min: f64,
    /// Whether the solver's own schedule flies (always for an `exact` schedule; the fair QP's
    /// layout may not).
    pub schedule_flies: bool,
    /// Set when the empty schedule is flown instead of the solver's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub fallback: Option<Fallback>,
}

/// Counts of the hop solves made while composing one route (every candidate hop, not only the
/// hops flown).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopSolveCounts {
    /// Hop solves made.
    pub solves: usize,
    /// Proven optimal (the fair QP: solved).
    pub optimal: usize,
    /// Within a certified distance of an infimum the continuous model does not attain (see
    /// `models/eaas_config.md`); written only when not zero.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub optimal_within: usize,
    /// Stopped at the time limit with an incumbent.
    pub time_limit_incumbent: usize,
    /// Proven: no schedule of the model flies.
    pub infeasible: usize,
    /// Stopped at the time limit without a schedule.
    pub time_limit_no_solution: usize,
    /// The continuous model has a value but no schedule was found (see
    /// [`ExactStatus::NoScheduleFound`]); written only when not zero.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub no_schedule_found: usize,
    /// Solves on which the backend failed.
    pub backend_errors: usize,
    /// Solves that returned a schedule that does not fly (the fair QP's layout).
    pub schedule_does_not_fly: usize,
    /// Hops that flew the empty schedule instead (see [`Fallback`]).
    pub fallbacks: usize,
}

impl HopSolve {
    /// Whether the solve is proven: `optimal`, `optimal_within` (within `epsilon`) or
    /// `infeasible`, with the flown schedule's node time proven at the stop and no fallback to
    /// the empty schedule.
    pub fn proven(&self) -> bool {
        matches!(
            self.status,
            Some(ExactStatus::Optimal | ExactStatus::OptimalWithin | ExactStatus::Infeasible)
        ) && self.objective_proven
            && self.fallback.is_none()
    }
}

impl HopSolveCounts {
    /// Adds one solve.
    pub fn add(&mut self, solve: &HopSolve) {
        self.solves += 1;
        match solve.status {
            Some(ExactStatus::Optimal) => self.optimal += 1,
            Some(ExactStatus::OptimalWithin) => self.optimal_within += 1,
            Some(ExactStatus::NoScheduleFound) => self.no_schedule_found += 1,
            Some(ExactStatus::Feasible) => self.time_limit_incumbent += 1,
            Some(ExactStatus::Infeasible) => self.infeasible += 1,
            Some(ExactStatus::TimeLimitNoSolution) => self.time_limit_no_solution += 1,
            None => self.backend_errors += 1,
        }
        if matches!(
            solve.status,
            Some(ExactStatus::Optimal | ExactStatus::OptimalWithin | ExactStatus::Feasible)
        ) && !solve.schedule_flies
        {
            self.schedule_does_not_fly += 1;
        }
        if solve.fallback.is_some() {
            self.fallbacks += 1;
        }
    }

    /// Adds every solve of `other`.
    pub fn merge(&mut self, other: &HopSolveCounts) {
        self.solves += other.solves;
        self.optimal += other.optimal;
        self.optimal_within += other.optimal_within;
        self.no_schedule_found += other.no_schedule_found;
        self.time_limit_incumbent += other.time_limit_incumbent;
        self.infeasible += other.infeasible;
        self.time_limit_no_solution += other.time_limit_no_solution;
        self.backend_errors += other.backend_errors;
        self.schedule_does_not_fly += other.schedule_does_not_fly;
        self.fallbacks += other.fallbacks;
    }

    /// Whether every solve ended proven (optimal or infeasible), so the route's hop schedules are
    /// optimal over the solver's schedules.
    pub fn all_proven(&self) -> bool {
        self.time_limit_incumbent == 0
            && self.time_limit_no_solution == 0
            && self.no_schedule_found == 0
            && self.backend_errors == 0
    }
}

/// Flies a hop under [`SharingPolicy::Exact`] or [`SharingPolicy::Fair`].
///
/// # Arguments
/// * `problem` - the hop.
/// * `policy` - `exact` or `fair`.
/// * `objective` - [`Objective::NodeTime`] when the hop ends at a stop, else
///   [`Objective::Feasible`].
/// * `settings` - grid, re-ordering, backend, time limit.
/// * `readings` - the readings of PB and FB, whose schedules are the solve's first incumbents.
///
/// # Returns
/// The flown schedule replayed by the hop evaluation (infeasible when no schedule of the
/// model flies, or none was found in time and the hop does not fly without sharing either), and
/// how the solve ended.
///
/// # Errors
/// `E4113` for `free` re-ordering; those of
/// [`dispatch::solve`] for bad input. A backend failure is not an error here: it
/// is recorded in [`HopSolve::backend_error`] and the hop flies without sharing if it can.
///
/// # Complexity
/// One MILP (exponential worst case, bounded by the time limit) or one QP (interior point).
pub fn fly_exact(
    problem: &HopProblem,
    policy: ExactPolicy,
    objective: &Objective,
    settings: &ExactSettings,
    readings: &PolicyOptions,
) -> Result<(HopOutcome, HopSolve)> {
    let milp = &settings.milp;
    if milp.reorder == Reorder::Free {
        return Err(Error::invalid(
            "E4113",
            "--reorder",
            "free re-ordering on a route",
            "use --reorder paper or none: a free schedule is not always a set of transfers a \
             plan can carry (use `swarmplan eaas --reorder free` on one hop)",
        ));
    }
    // The grid step is the grid MILP's; a bad one is still bad input.
    super::exact::milp::validate_period_min(milp.period_min)?;
    let goal = match objective {
        Objective::NodeTime(EndPads { .. }) => HopGoal::NodeTimeMin,
        _ => HopGoal::Feasible,
    };
    let formulation = policy.formulation();
    let solved = match dispatch::solve(formulation, problem, objective, milp, readings) {
        Ok(Solved::Schedule(o)) => Ok(*o),
        // Both formulations of an exact policy give schedules; a bound alone is no flight.
        Ok(Solved::Bound(_)) => Err(format!("{formulation:?} gives no schedule")),
        Err(Error::Backend {
            backend, message, ..
        }) => Err(format!("{backend}: {message}")),
        Err(e) => return Err(e),
    };
    let (status, bound, epsilon, grid_step_min, schedule, backend_error) = match solved {
        Ok(o) => (
            Some(o.status),
            o.bound,
            o.epsilon.filter(|_| o.status == ExactStatus::OptimalWithin),
            o.grid_step_min,
            o.outcome,
            None,
        ),
        Err(message) => (None, None, None, 0.0, None, Some(message)),
    };
    let exact_node_time = goal == HopGoal::NodeTimeMin && policy == ExactPolicy::Exact;
    let mut solve = HopSolve {
        policy: policy.into(),
        goal,
        status,
        backend_error,
        objective: None,
        objective_proven: true,
        bound: bound.filter(|_| exact_node_time),
        epsilon: epsilon.filter(|_| exact_node_time),
        grid_step_min,
        schedule_flies: schedule.as_ref().is_some_and(|o| o.feasible),
        fallback: None,
    };
    let outcome = match schedule.filter(|o| o.feasible) {
        Some(o) => o,
        None => {
            let empty = simulate_with(problem, Heuristic::None, &PolicyOptions::default())?;
            if empty.feasible {
                solve.fallback = Some(match (policy, status) {
                    (_, None) => Fallback::BackendError,
                    (ExactPolicy::Fair, Some(ExactStatus::Optimal)) => {
                        Fallback::FairLayoutDoesNotFly
                    }
                    (_, Some(ExactStatus::TimeLimitNoSolution)) => Fallback::NoSolutionInTime,
                    _ => Fallback::ModelRejectsEmptySchedule,
                });
            }
            empty
        }
    };
    if goal == HopGoal::NodeTimeMin && outcome.feasible {
        let value = super::exact::objective_of(problem, objective, &outcome.final_battery_mah)?;
        solve.objective = Some(value.value);
        solve.objective_proven = value.proven;
    }
    Ok((outcome, solve))
}
