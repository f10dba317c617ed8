//! The exact hop models and their shared vocabulary, see `models/eaas_milp.md`,
//! `models/eaas_config.md` and `models/eaas_fluid.md`.
//!
//! Every model takes a [`HopProblem`], an [`Objective`] (what it optimises at the hop's end) and a
//! re-ordering mode ([`Reorder`]); a model with a schedule answers an [`ExactOutcome`], the bound
//! a [`BoundOutcome`]. The [`Formulation`]s:
//! - [`continuous`]: the configuration LP, the optimum over every continuous-time schedule (the
//!   hop reference of the tool);
//! - [`milp`]: the time-indexed MILP, the optimum over full-period schedules on a time grid (a
//!   cross-check);
//! - [`fluid`]: the fluid LP bound and the fair QP.
//!
//! [`dispatch::solve`] is the one place that runs a formulation by name: adding one is its file
//! here, a [`Formulation`] variant and its arm there (and its [`crate::eaas::compare::HopMethod`]
//! for `swarmplan eaas`).
//!
//! The root holds what they share: the objective, the re-ordering modes, the status and outcome
//! types, input validation, the objective of a replayed schedule and the moves of a mode.

use super::{reorder, validate, HopOutcome, HopProblem, Role, Transfer};
use crate::error::{show, BackendFailure, Error, Result, Violation};
use crate::node_time;
use crate::solver::{BackendStatus, MilpOutcome, SolveStatus};
use serde::{Deserialize, Serialize};

pub mod continuous;
pub mod dispatch;
pub mod fluid;
pub mod milp;

/// An exact hop formulation: what [`dispatch::solve`] runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Formulation {
    /// The configuration LP ([`continuous`]): the optimum over every continuous-time schedule.
    Continuous,
    /// The time-indexed MILP ([`milp`]): the optimum over full-period schedules on a grid.
    Milp,
    /// The fluid LP ([`fluid::bound`]): a bound valid for every continuous-time schedule, no
    /// schedule.
    Fluid,
    /// The fair QP ([`fluid::fair`]) laid out as a schedule: FB's exact counterpart, a layout,
    /// not an optimum of the hop's objective.
    Fair,
}

impl Formulation {
    /// Every formulation, in the order `swarmplan eaas` lists them.
    pub const ALL: [Formulation; 4] = [
        Formulation::Continuous,
        Formulation::Milp,
        Formulation::Fluid,
        Formulation::Fair,
    ];

    /// What its result is, as the `kind` of a comparison row: `exact_continuous`, `exact_grid`,
    /// `bound` or `fair_layout`.
    pub fn kind(self) -> &'static str {
        match self {
            Formulation::Continuous => "exact_continuous",
            Formulation::Milp => "exact_grid",
            Formulation::Fluid => "bound",
            Formulation::Fair => "fair_layout",
        }
    }

    /// Whether its schedules are the full periods of a time grid (the MILP) rather than
    /// continuous in time.
    pub fn on_grid(self) -> bool {
        self == Formulation::Milp
    }
}

/// What a bound formulation ([`Formulation::Fluid`]) answers: a proven bound on the hop's
/// optimum over every continuous-time schedule of the mode, and no schedule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoundOutcome {
    /// `optimal` (the bound is the relaxation's optimum) or `infeasible` (no continuous-time
    /// schedule of the mode flies).
    pub status: ExactStatus,
    /// The bound (lower when minimising the node time, upper when maximising the lowest arrival
    /// battery): the safer of the relaxation's primal and dual values. `None` when infeasible.
    pub bound: Option<f64>,
    /// The relaxation's primal value.
    pub model_objective: Option<f64>,
    /// Legs of the relaxation (the legs of positive duration).
    pub legs: usize,
    /// Wall-clock time of the solve, milliseconds.
    pub solve_ms: f64,
}

/// How drones may change formation slots while sharing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Reorder {
    /// The paper's fixed re-ordering: an out-of-range consumer swaps with the delivery drone of an
    /// in-range slot (any such slot, not only the nearest) for the transfer; in-range consumers
    /// stay.
    Paper,
    /// Any permutation of the delivery drones over the non-support slots in each period.
    Free,
    /// No movement: only consumers within range in their own slots are served.
    None,
}

display_as_value_name!(Reorder);

/// The pads at the node ending a hop, where the node time is charged: the end of
/// [`Objective::NodeTime`] and of a hop file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EndPads {
    /// Number of pads `k`.
    pub pads: usize,
    /// Charging rate of a pad, mAh/min.
    pub pad_rate_mah_per_min: f64,
}

/// What an exact hop model optimises.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Objective {
    /// Minimise the node time at the hop's end, minutes: the makespan of charging every drone
    /// (delivery and support) to full on `pads` identical pads, drone `d` taking
    /// `ct_d = (C_d - b_d(tt)) / pad_rate_mah_per_min` minutes.
    NodeTime(EndPads),
    /// Maximise the lowest arrival battery `min_{d in D_d} b_d(tt)` over the delivery drones, mAh.
    MaxMinArrival,
    /// Any schedule with no drone below zero; objective value 0.
    Feasible,
}

impl Objective {
    /// Whether the objective is minimised (the node time; `Feasible`, whose value is always 0)
    /// or maximised (the lowest delivery arrival battery).
    pub fn sense(&self) -> crate::solver::Sense {
        match self {
            Objective::NodeTime(_) | Objective::Feasible => crate::solver::Sense::Minimise,
            Objective::MaxMinArrival => crate::solver::Sense::Maximise,
        }
    }
}

/// Outcome of an exact hop solve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExactStatus {
    /// Proven optimal (over the model's schedules: grid schedules for the MILP).
    Optimal,
    /// A schedule within a certified distance of the optimum ([`ExactOutcome::epsilon`]): the
    /// continuous model's value is an infimum the returned schedule approaches but does not reach
    /// (`models/eaas_config.md`).
    OptimalWithin,
    /// An incumbent; the time limit stopped the proof. The bound is reported separately.
    Feasible,
    /// Proven: no schedule of the model keeps every drone at or above zero.
    Infeasible,
    /// The time limit expired before any feasible schedule was found.
    TimeLimitNoSolution,
    /// The continuous model has a value (a lower bound on every schedule, [`ExactOutcome::bound`])
    /// but no schedule that flies was found: either none exists (a hop without a Slater point,
    /// `models/eaas_config.md`) or the realisation's work limit did not reach one.
    NoScheduleFound,
}

/// What a formulation with a schedule answers ([`continuous::solve_continuous`],
/// [`milp::solve_milp`], [`fluid::fair`]): the schedule, its objective and how the solve ended.
/// The bound formulation answers a [`BoundOutcome`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExactOutcome {
    /// Optimal, feasible (time limit), infeasible or no solution in time.
    pub status: ExactStatus,
    /// Objective of the returned schedule, re-evaluated from its replay (node time in minutes,
    /// lowest delivery arrival battery in mAh, or 0 for feasibility); `None` without a schedule.
    pub objective: Option<f64>,
    /// False when `objective` is a node time the exact search did not prove within
    /// [`node_time::DEFAULT_STOP_NODE_LIMIT`] nodes (then an upper bound on the schedule's node
    /// time); true otherwise.
    pub objective_proven: bool,
    /// Objective value reported by the model itself (grid MILP, LP or QP).
    pub model_objective: Option<f64>,
    /// A proven bound on the model's optimum (lower for minimisation, upper for maximisation):
    /// the optimum itself when optimal; after a time limit the better of the LP relaxation's
    /// value and the fluid LP bound. `None` for the fair QP, whose optimum is not one of the
    /// hop's objective (its value is `model_objective`).
    pub bound: Option<f64>,
    /// The certified distance of the returned schedule's objective to the model's optimum
    /// (`objective - bound` when minimising, `bound - objective` when maximising): set by the
    /// continuous model when it returns a schedule, `None` for the others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub epsilon: Option<f64>,
    /// Longest period of the grid, minutes: the MILP is optimal over schedules whose transfers
    /// occupy whole periods of this grid. `0` for the continuous-time fluid models.
    pub grid_step_min: f64,
    /// Number of periods of the grid (legs for the fluid models).
    pub periods: usize,
    /// Wall-clock time of the solve, milliseconds.
    pub solve_ms: f64,
    /// The schedule, consecutive periods of the same (support, consumer, slot) within a leg
    /// merged.
    pub transfers: Vec<Transfer>,
    /// The schedule replayed by the hop evaluation; passes [`crate::check::check_hop`].
    /// `None` without a schedule, or for a `free` schedule whose slot permutation is not a set of
    /// consumer swaps (see [`ExactOutcome::slots`]).
    pub outcome: Option<HopOutcome>,
    /// `free` only: the slot of every drone in every period.
    pub slots: Option<Vec<Vec<usize>>>,
    /// `free`, continuous model: the schedule as intervals with every drone's slot (its replay
    /// by [`crate::check::check_free_hop`]); `transfers` lists the same sharing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub intervals: Option<crate::eaas::FreeSchedule>,
}

impl ExactOutcome {
    /// The outcome of a proven infeasible model, filled in by the caller otherwise: no schedule,
    /// no value, the model's grid step (0 for the continuous-time models) and periods (or legs).
    pub fn infeasible(grid_step_min: f64, periods: usize) -> ExactOutcome {
        ExactOutcome {
            status: ExactStatus::Infeasible,
            objective: None,
            objective_proven: true,
            model_objective: None,
            bound: None,
            epsilon: None,
            grid_step_min,
            periods,
            solve_ms: 0.0,
            transfers: Vec::new(),
            outcome: None,
            slots: None,
            intervals: None,
        }
    }
}

/// Checks the objective's numbers.
///
/// # Errors
/// `E4103` for zero pads, `E4104` for a pad rate that is not finite and positive.
pub fn validate_objective(objective: &Objective) -> Result<()> {
    if let Objective::NodeTime(EndPads {
        pads,
        pad_rate_mah_per_min,
    }) = *objective
    {
        let mut v = Vec::new();
        if pads == 0 {
            v.push(Violation::new(
                "E4103",
                "pads",
                "0 pads".to_string(),
                "give at least one pad",
            ));
        }
        if !(pad_rate_mah_per_min.is_finite() && pad_rate_mah_per_min > 0.0) {
            v.push(Violation::new(
                "E4104",
                "pad_rate_mah_per_min",
                format!("{} is not a finite rate > 0", show(pad_rate_mah_per_min)),
                "give the pad charging rate in mAh/min",
            ));
        }
        if !v.is_empty() {
            return Err(Error::Invalid(v));
        }
    }
    Ok(())
}

/// Checks a hop, an objective and a time limit: the inputs of every exact hop model.
pub(crate) fn validate_inputs(
    problem: &HopProblem,
    objective: &Objective,
    time_limit_s: f64,
) -> Result<()> {
    validate(problem)?;
    validate_objective(objective)?;
    validate_time_limit(time_limit_s)
}

fn validate_time_limit(time_limit_s: f64) -> Result<()> {
    // Infinity: no wall-clock limit. A finite one is at most `MAX_TIME_LIMIT_S`, as every time
    // limit (a longer one would overflow the clock's deadline).
    let max = crate::node_time::MAX_TIME_LIMIT_S;
    if time_limit_s == f64::INFINITY || (time_limit_s > 0.0 && time_limit_s <= max) {
        Ok(())
    } else {
        Err(Error::invalid(
            "E4105",
            "time_limit_s",
            format!(
                "{} is not a time in (0, {}] seconds",
                show(time_limit_s),
                show(max)
            ),
            "give the time limit in seconds, or none for no wall-clock limit",
        ))
    }
}

/// The objective of a replayed hop and whether that value is proven.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectiveValue {
    /// Node time (min), lowest delivery arrival battery (mAh), or 0.
    pub value: f64,
    /// False when the exact node time stopped at [`node_time::DEFAULT_STOP_NODE_LIMIT`] nodes:
    /// `value` is then the makespan of the best pad assignment found, an upper bound on the
    /// schedule's node time.
    pub proven: bool,
}

impl ObjectiveValue {
    fn proven(value: f64) -> ObjectiveValue {
        ObjectiveValue {
            value,
            proven: true,
        }
    }
}

/// Objective value of a replayed hop: node time by the exact P||Cmax search on the charge times
/// `(C_d - b_d(tt)) / pad_rate` (a battery above capacity counts as full) under the node limit
/// of a planner's stop ([`node_time::DEFAULT_STOP_NODE_LIMIT`]), lowest delivery arrival
/// battery, or 0.
///
/// # Errors
/// Those of [`node_time::exact()`] (none for valid inputs).
pub fn objective_of(
    problem: &HopProblem,
    objective: &Objective,
    final_battery_mah: &[f64],
) -> Result<ObjectiveValue> {
    match *objective {
        Objective::NodeTime(EndPads {
            pads,
            pad_rate_mah_per_min,
        }) => {
            let times: Vec<f64> = problem
                .drones
                .iter()
                .zip(final_battery_mah)
                .map(|(d, &b)| ((d.capacity_mah - b) / pad_rate_mah_per_min).max(0.0))
                .collect();
            let limits = node_time::Limits {
                time_limit_s: None,
                node_limit: Some(node_time::DEFAULT_STOP_NODE_LIMIT),
            };
            let solution = node_time::exact(pads, &times, &limits)?;
            Ok(ObjectiveValue {
                value: solution.makespan_min,
                proven: solution.status == SolveStatus::Optimal,
            })
        }
        Objective::MaxMinArrival => Ok(ObjectiveValue::proven(
            problem
                .drones
                .iter()
                .zip(final_battery_mah)
                .filter(|(d, _)| d.role == Role::Delivery)
                .map(|(_, &b)| b)
                .fold(f64::INFINITY, f64::min),
        )),
        Objective::Feasible => Ok(ObjectiveValue::proven(0.0)),
    }
}

/// One possible transfer pattern in a period: `support` serves `consumer` flying in `slot`; when
/// `partner` is set it holds the consumer's initial slot meanwhile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Move {
    /// The giving support drone.
    pub support: usize,
    /// The receiving delivery drone.
    pub consumer: usize,
    /// The slot the consumer flies in.
    pub slot: usize,
    /// The delivery drone holding the consumer's own slot meanwhile, when the consumer moves.
    pub partner: Option<usize>,
}

/// Moves allowed by `reorder` (`free` uses every support-consumer pair; slots come from `z`).
pub fn moves(problem: &HopProblem, mode: Reorder) -> Vec<Move> {
    let n = problem.drones.len();
    let role = |d: usize| problem.drones[d].role;
    let mut out = Vec::new();
    for s in (0..n).filter(|&s| role(s) == Role::Support) {
        let qs = problem.initial_slot[s];
        for c in (0..n).filter(|&c| role(c) == Role::Delivery) {
            let own = problem.initial_slot[c];
            let in_range = reorder::slot_distance_m(problem, qs, own) <= problem.range_m;
            match mode {
                Reorder::Free => out.push(Move {
                    support: s,
                    consumer: c,
                    slot: own,
                    partner: None,
                }),
                _ if in_range => out.push(Move {
                    support: s,
                    consumer: c,
                    slot: own,
                    partner: None,
                }),
                Reorder::None => {}
                Reorder::Paper => {
                    for q in 0..n {
                        let p = reorder::occupant(problem, q);
                        if q != own
                            && role(p) == Role::Delivery
                            && reorder::slot_distance_m(problem, qs, q) <= problem.range_m
                        {
                            out.push(Move {
                                support: s,
                                consumer: c,
                                slot: q,
                                partner: Some(p),
                            });
                        }
                    }
                }
            }
        }
    }
    out
}

/// How a MILP backend's solve ended, in the hop models' terms.
pub(crate) enum BackendEnd<S> {
    /// Values, with how the search ended: [`BackendStatus::Optimal`],
    /// [`BackendStatus::OptimalWithinGap`] or [`BackendStatus::Feasible`].
    Solved(BackendStatus, S),
    /// Proven infeasible.
    Infeasible,
    /// Stopped by its limit before any incumbent.
    NoSolution,
}

/// Reads a MILP backend's outcome ([`crate::solver::MilpModel::solve_outcome`]): infeasibility
/// and a limit without an incumbent are outcomes; an unbounded model and a backend failure are
/// an [`Error::Backend`].
pub(crate) fn backend_end<S>(
    answer: std::result::Result<MilpOutcome<S>, good_lp::ResolutionError>,
    backend_name: &str,
) -> Result<BackendEnd<S>> {
    let fail = |e: good_lp::ResolutionError| {
        Error::backend(BackendFailure::Numerical, backend_name, e.to_string())
    };
    match answer.map_err(fail)? {
        MilpOutcome::Solved { status, solution } => Ok(BackendEnd::Solved(status, solution)),
        MilpOutcome::NoSolution { status, report } => match status {
            BackendStatus::Infeasible => Ok(BackendEnd::Infeasible),
            BackendStatus::LimitNoSolution => Ok(BackendEnd::NoSolution),
            BackendStatus::Unbounded
            | BackendStatus::Optimal
            | BackendStatus::OptimalWithinGap
            | BackendStatus::Feasible => Err(fail(report)),
        },
    }
}

/// The exact `k`-pad assignment rows of the node-time objective (`models/eaas_milp.md`,
/// "Objectives"): `x[d][i]` drone `d` on pad `i <= min(d, m - 1)`, `w[d][i]` its charge time
/// there, minutes.
pub(crate) struct PadRows {
    x: Vec<Vec<good_lp::Variable>>,
    w: Vec<Vec<good_lp::Variable>>,
}

impl PadRows {
    /// Adds the variables for `n` drones on `pads` pads (`x` in `[0, 1]` when `relax`). The
    /// pads' symmetry is broken along `rank` (drone `d` may use pads `0..=min(rank[d], m - 1)`:
    /// relabel the pads in the order the ranked drones first use them), the drone index when
    /// `None`; any order is valid, one with the longest charge times first branches best.
    pub(crate) fn add(
        vars: &mut good_lp::ProblemVariables,
        n: usize,
        pads: usize,
        relax: bool,
        rank: Option<&[usize]>,
    ) -> PadRows {
        use good_lp::variable;
        let m = pads.min(n);
        let x: Vec<Vec<good_lp::Variable>> = (0..n)
            .map(|d| {
                (0..=rank.map_or(d, |r| r[d]).min(m.max(1) - 1))
                    .map(|i| {
                        let name = format!("x_d{d}_p{i}");
                        if relax {
                            vars.add(variable().min(0.0).max(1.0).name(name))
                        } else {
                            vars.add(variable().binary().name(name))
                        }
                    })
                    .collect()
            })
            .collect();
        let w = (0..n)
            .map(|d| {
                (0..x[d].len())
                    .map(|i| vars.add(variable().min(0.0).name(format!("w_d{d}_p{i}"))))
                    .collect()
            })
            .collect();
        PadRows { x, w }
    }

    /// Adds `ct_d = (C_d - b_d(tt)) / pad rate` split over the pads, every `ct_d <= M` and every
    /// pad's load `<= M`; `final_battery[d]` is `b_d(tt)` as an expression of the model and
    /// `capacity[d]` is `C_d`, both in the model's energy unit, in which the pad charges
    /// `pad_rate` per minute.
    pub(crate) fn constrain<M: good_lp::SolverModel>(
        &self,
        model: &mut M,
        capacity: &[f64],
        final_battery: &[good_lp::Expression],
        pad_rate_mah_per_min: f64,
        makespan: good_lp::Variable,
    ) {
        use good_lp::{constraint, Expression};
        let m = self.x.iter().map(Vec::len).max().unwrap_or(0);
        for (d, &cap) in capacity.iter().enumerate() {
            let ct = (cap - final_battery[d].clone()) * (1.0 / pad_rate_mah_per_min);
            let big = cap / pad_rate_mah_per_min;
            let once: Expression = self.x[d].iter().copied().sum();
            model.add_constraint(constraint!(once == 1.0));
            // ct_d split over the pads, all of it on the pad x chooses.
            for i in 0..self.x[d].len() {
                model.add_constraint(constraint!(self.w[d][i] <= big * self.x[d][i]));
            }
            let split: Expression = self.w[d].iter().copied().sum();
            model.add_constraint(constraint!(split == ct.clone()));
            model.add_constraint(constraint!(ct <= makespan));
        }
        for i in 0..m {
            let load: Expression = self
                .w
                .iter()
                .filter(|wd| wd.len() > i)
                .map(|wd| wd[i])
                .sum();
            model.add_constraint(constraint!(load <= makespan));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use good_lp::ResolutionError;

    #[test]
    fn backend_ends_follow_the_status_never_the_words() {
        let no_solution = |status, report| {
            backend_end::<()>(Ok(MilpOutcome::NoSolution { status, report }), "microlp")
        };
        // The words do not matter: a limit's stop is no solution, whatever the backend said.
        let stopped = no_solution(BackendStatus::LimitNoSolution, ResolutionError::Other("x"));
        assert!(matches!(stopped, Ok(BackendEnd::NoSolution)));
        let infeasible = no_solution(BackendStatus::Infeasible, ResolutionError::Other("x"));
        assert!(matches!(infeasible, Ok(BackendEnd::Infeasible)));
        // An unbounded model is an error, in the backend's words.
        let unbounded = no_solution(BackendStatus::Unbounded, ResolutionError::Unbounded);
        match unbounded {
            Err(Error::Backend {
                kind,
                backend,
                message,
            }) => {
                assert_eq!(kind, BackendFailure::Numerical);
                assert_eq!(backend, "microlp");
                assert_eq!(message, ResolutionError::Unbounded.to_string());
            }
            _ => panic!("an unbounded model is a backend error"),
        }
        let solved = backend_end(
            Ok(MilpOutcome::Solved {
                status: BackendStatus::Feasible,
                solution: 7,
            }),
            "microlp",
        );
        assert!(matches!(
            solved,
            Ok(BackendEnd::Solved(BackendStatus::Feasible, 7))
        ));
        let failed = backend_end::<()>(Err(ResolutionError::Str("broken".into())), "highs");
        assert!(matches!(failed, Err(Error::Backend { .. })));
    }
}
