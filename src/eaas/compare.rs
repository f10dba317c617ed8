//! One hop solved by the sharing heuristics and the exact models side by side, each scored by the
//! hop's objective and its gap labelled against the best reference available: the continuous
//! model's optimum (`optimal`, over every continuous-time schedule of the mode) or the infimum it
//! approaches (`infimum`), else the grid MILP's optimum (`optimal`, over grid schedules) or its
//! incumbent after a time limit (`incumbent`), else the fluid LP bound (`bound`). A gap is taken
//! only against a reference whose schedules contain the row's: in `none` re-ordering a PB or FB
//! schedule that swaps slots is outside the model, and its row says `different_policy` instead of
//! a gap. `swarmplan eaas` prints it for one hop; `swarmplan bench` for every hop of its exact
//! subset.

use super::exact::dispatch::{self, Solved};
use super::exact::milp::MilpOptions;
use super::exact::{objective_of, ExactOutcome, ExactStatus, Objective, Reorder};
use super::exact::{BoundOutcome, Formulation};
use super::{
    simulate_with, FreeSchedule, Heuristic, HopPolicy, HopProblem, PolicyOptions, SharingPolicy,
    Transfer,
};
use crate::error::Result;
use crate::solver::{Gap, ReferenceKind};
use serde::{Deserialize, Serialize};

/// A method that can be run on a hop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum HopMethod {
    /// No sharing.
    None,
    /// Priority-based heuristic (Algorithm 2).
    Pb,
    /// Fairness-based heuristic (Algorithm 3).
    Fb,
    /// Continuous-time configuration LP (optimal over every continuous-time schedule).
    Continuous,
    /// Time-indexed MILP (optimal over grid schedules).
    Milp,
    /// Fluid LP bound (valid for every continuous-time schedule).
    Fluid,
    /// Fair QP optimum laid out as a schedule.
    Fair,
}

display_as_value_name!(HopMethod);

impl HopMethod {
    /// The method of a sharing policy on a hop: its simulated heuristic (`idle-support` flies
    /// `none`), or its exact formulation (`exact`: the continuous model; `fair`: the fair QP).
    pub fn of_policy(policy: SharingPolicy) -> HopMethod {
        match policy.on_hop() {
            HopPolicy::Simulated(Heuristic::None) => HopMethod::None,
            HopPolicy::Simulated(Heuristic::Pb) => HopMethod::Pb,
            HopPolicy::Simulated(Heuristic::Fb) => HopMethod::Fb,
            HopPolicy::Solved(p) => HopMethod::of_formulation(p.formulation()),
        }
    }

    /// The method that solves `formulation`.
    pub fn of_formulation(formulation: Formulation) -> HopMethod {
        match formulation {
            Formulation::Continuous => HopMethod::Continuous,
            Formulation::Milp => HopMethod::Milp,
            Formulation::Fluid => HopMethod::Fluid,
            Formulation::Fair => HopMethod::Fair,
        }
    }

    /// The exact formulation the method solves; `None` for the simulated heuristics.
    pub fn formulation(self) -> Option<Formulation> {
        match self {
            HopMethod::None | HopMethod::Pb | HopMethod::Fb => None,
            HopMethod::Continuous => Some(Formulation::Continuous),
            HopMethod::Milp => Some(Formulation::Milp),
            HopMethod::Fluid => Some(Formulation::Fluid),
            HopMethod::Fair => Some(Formulation::Fair),
        }
    }

    /// The simulated heuristic (`none`, `pb`, `fb`); `None` for the models.
    pub fn heuristic(self) -> Option<Heuristic> {
        match self {
            HopMethod::None => Some(Heuristic::None),
            HopMethod::Pb => Some(Heuristic::Pb),
            HopMethod::Fb => Some(Heuristic::Fb),
            _ => None,
        }
    }

    /// Whether the method solves a model (and may run up to its time limit).
    pub fn is_model(self) -> bool {
        self.formulation().is_some()
    }
}

/// One method's result on the hop.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRow {
    /// The method.
    pub method: HopMethod,
    /// `heuristic`, `exact_continuous` (configuration LP), `exact_grid` (MILP), `bound` (fluid
    /// LP) or `fair_layout` (QP schedule).
    pub kind: &'static str,
    /// Solve status of the exact models; `None` for the heuristics.
    pub status: Option<ExactStatus>,
    /// Whether the method's schedule flies (`None` without a schedule).
    pub feasible: Option<bool>,
    /// Objective of the schedule (node time, min, or lowest delivery arrival battery, mAh); the
    /// bound itself for `fluid`.
    pub objective: Option<f64>,
    /// False when `objective` is a node time not proven within the node limit of a stop (an
    /// upper bound on the schedule's node time; printed with `<=`).
    pub objective_proven: bool,
    /// The model's proven bound on the objective (MILP, fluid LP).
    pub bound: Option<f64>,
    /// `fair` only: the QP optimum, sum of squared end deficits over every drone, mAh^2 (a lower
    /// bound on that sum for every continuous-time schedule).
    pub qp_squared_deficits_mah2: Option<f64>,
    /// Gap against the reference, with its kind.
    pub gap: Option<Gap>,
    /// `different_policy` when the row's schedule lies outside the reference's model (a
    /// swapping PB or FB schedule against a `none` reference): no gap is taken.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gap_label: Option<crate::solver::GapLabel>,
    /// `continuous`: the certified distance of the schedule to the model's optimum, in the
    /// objective's unit (0 when attained).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub epsilon: Option<f64>,
    /// MILP grid step, minutes.
    pub grid_step_min: Option<f64>,
    /// Wall-clock time, ms.
    pub solve_ms: f64,
    /// The schedule.
    pub transfers: Vec<Transfer>,
    /// `continuous` with `free` re-ordering: the schedule as slot intervals (every drone's slot)
    /// and its final batteries, which `transfers` alone cannot carry.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub free_schedule: Option<FreeSchedule>,
}

/// The row of a formulation's schedule.
fn schedule_row(method: HopMethod, formulation: Formulation, o: ExactOutcome) -> MethodRow {
    let fair = formulation == Formulation::Fair;
    MethodRow {
        method,
        kind: formulation.kind(),
        status: Some(o.status),
        feasible: o
            .outcome
            .as_ref()
            .map(|x| x.feasible)
            .or(o.intervals.as_ref().map(|_| true)),
        objective: o.objective,
        objective_proven: o.objective_proven,
        bound: o.bound,
        qp_squared_deficits_mah2: if fair { o.model_objective } else { None },
        gap: None,
        gap_label: None,
        epsilon: o.epsilon,
        grid_step_min: formulation.on_grid().then_some(o.grid_step_min),
        solve_ms: o.solve_ms,
        transfers: o.transfers,
        free_schedule: o.intervals,
    }
}

/// The row of a bound: its value stands in the objective column, proven, with no schedule.
fn bound_row(method: HopMethod, formulation: Formulation, o: BoundOutcome) -> MethodRow {
    MethodRow {
        method,
        kind: formulation.kind(),
        status: Some(o.status),
        feasible: None,
        objective: o.bound,
        objective_proven: true,
        bound: o.bound,
        qp_squared_deficits_mah2: None,
        gap: None,
        gap_label: None,
        epsilon: None,
        grid_step_min: None,
        solve_ms: o.solve_ms,
        transfers: Vec::new(),
        free_schedule: None,
    }
}

/// Runs one method on the hop. The exact models use `milp`'s re-ordering and time limit (and
/// its grid and backend for the MILP); the heuristics use the readings `readings`.
///
/// # Errors
/// Those of the simulation, the objective's node time, and the models' options and backends.
pub fn run_method(
    problem: &HopProblem,
    objective: &Objective,
    method: HopMethod,
    milp: &MilpOptions,
    readings: &PolicyOptions,
) -> Result<MethodRow> {
    let start = std::time::Instant::now();
    if let Some(formulation) = method.formulation() {
        return Ok(
            match dispatch::solve(formulation, problem, objective, milp, readings)? {
                Solved::Schedule(o) => schedule_row(method, formulation, *o),
                Solved::Bound(o) => bound_row(method, formulation, o),
            },
        );
    }
    let heuristic = method.heuristic().unwrap_or(Heuristic::None);
    let o = simulate_with(problem, heuristic, readings)?;
    let value = if o.feasible {
        Some(objective_of(problem, objective, &o.final_battery_mah)?)
    } else {
        None
    };
    Ok(MethodRow {
        method,
        kind: "heuristic",
        status: None,
        feasible: Some(o.feasible),
        objective: value.map(|v| v.value),
        objective_proven: value.is_none_or(|v| v.proven),
        bound: None,
        qp_squared_deficits_mah2: None,
        gap: None,
        gap_label: None,
        epsilon: None,
        grid_step_min: None,
        solve_ms: start.elapsed().as_secs_f64() * 1e3,
        transfers: o.transfers,
        free_schedule: None,
    })
}

/// The best reference among the rows, with its kind and the method it comes from: the
/// continuous model's optimum (`optimal` when attained and its node time proven, `infimum` when
/// only approached: the model's value, which every schedule of the mode is at or above), else
/// the MILP's objective (`optimal` when the solve and the node time of its schedule are proven,
/// else `incumbent`), else the fluid bound.
pub fn reference(rows: &[MethodRow]) -> Option<(f64, ReferenceKind)> {
    reference_of(rows).map(|(v, k, _)| (v, k))
}

fn reference_of(rows: &[MethodRow]) -> Option<(f64, ReferenceKind, HopMethod)> {
    let continuous = rows.iter().find_map(|r| match (r.method, r.status) {
        (HopMethod::Continuous, Some(ExactStatus::Optimal)) if r.objective_proven => r
            .objective
            .map(|v| (v, ReferenceKind::Optimal, HopMethod::Continuous)),
        (HopMethod::Continuous, Some(ExactStatus::Optimal | ExactStatus::OptimalWithin)) => r
            .bound
            .map(|b| (b, ReferenceKind::Infimum, HopMethod::Continuous)),
        _ => None,
    });
    continuous
        .or_else(|| {
            rows.iter()
                .find_map(|r| match (r.method, r.status, r.objective) {
                    // The MILP's schedule is optimal over the grid; its node time is the reference
                    // only when the exact node time proved it.
                    (HopMethod::Milp, Some(ExactStatus::Optimal), Some(v))
                        if r.objective_proven =>
                    {
                        Some((v, ReferenceKind::Optimal, HopMethod::Milp))
                    }
                    (
                        HopMethod::Milp,
                        Some(ExactStatus::Optimal | ExactStatus::Feasible),
                        Some(v),
                    ) => Some((v, ReferenceKind::Incumbent, HopMethod::Milp)),
                    _ => None,
                })
        })
        .or_else(|| {
            rows.iter()
                .find(|r| r.method == HopMethod::Fluid && r.status == Some(ExactStatus::Optimal))
                .and_then(|r| r.bound.map(|b| (b, ReferenceKind::Bound, HopMethod::Fluid)))
        })
}

/// Labels every row but the reference's own and the fluid bound's with its gap against
/// [`reference()`]; the grid MILP's row too when the reference is the continuous model (every grid
/// schedule is a continuous one). In `none` re-ordering (`reorder`) a heuristic row whose
/// schedule swaps slots is outside the model: it gets `different_policy` and no gap.
pub fn label_gaps(
    rows: &mut [MethodRow],
    problem: &HopProblem,
    objective: &Objective,
    reorder: Reorder,
) {
    let Some((v, kind, from)) = reference_of(rows) else {
        return;
    };
    for r in rows.iter_mut() {
        if r.method == from || r.method == HopMethod::Fluid {
            continue;
        }
        let swaps = r
            .transfers
            .iter()
            .any(|t| t.consumer_slot != problem.initial_slot[t.consumer]);
        if reorder == Reorder::None && swaps && !r.method.is_model() {
            r.gap_label = Some(crate::solver::GapLabel::DifferentPolicy);
            continue;
        }
        r.gap = r.objective.map(|h| Gap::new(h, v, kind, objective.sense()));
    }
}
