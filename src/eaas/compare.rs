//! One hop solved by the sharing heuristics and the exact models side by side, each scored by the
//! hop's objective and its gap labelled against the best reference available: the MILP optimum
//! (`optimal`, over grid schedules), its incumbent after a time limit (`incumbent`), or the fluid
//! LP bound (`bound`). `swarmplan eaas` prints it for one hop; `swarmplan bench` for every hop of
//! its exact subset.

use super::milp::{objective_of, solve_milp, ExactOutcome, ExactStatus, MilpOptions, Objective};
use super::{fluid, simulate_with, HopProblem, PolicyOptions, SharingPolicy, Transfer};
use crate::error::Result;
use crate::solver::{Gap, ReferenceKind};
use serde::Serialize;

/// A method that can be run on a hop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, clap::ValueEnum)]
#[serde(rename_all = "lowercase")]
pub enum HopMethod {
    /// No sharing.
    None,
    /// Priority-based heuristic (Algorithm 2).
    Pb,
    /// Fairness-based heuristic (Algorithm 3).
    Fb,
    /// Time-indexed MILP (optimal over grid schedules).
    Milp,
    /// Fluid LP bound (valid for every continuous-time schedule).
    Fluid,
    /// Fair QP optimum laid out as a schedule.
    Fair,
}

display_as_value_name!(HopMethod);

impl HopMethod {
    /// The heuristic of a simulated sharing policy (`none`, `pb`, `fb`); `None` for the others.
    pub fn of_policy(policy: SharingPolicy) -> Option<HopMethod> {
        match policy {
            SharingPolicy::None => Some(HopMethod::None),
            SharingPolicy::Pb => Some(HopMethod::Pb),
            SharingPolicy::Fb => Some(HopMethod::Fb),
            _ => None,
        }
    }

    /// Whether the method solves a model (and may run up to its time limit).
    pub fn is_model(self) -> bool {
        matches!(self, HopMethod::Milp | HopMethod::Fluid | HopMethod::Fair)
    }
}

/// One method's result on the hop.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRow {
    /// The method.
    pub method: HopMethod,
    /// `heuristic`, `exact_grid` (MILP), `bound` (fluid LP) or `fair_layout` (QP schedule).
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
    /// MILP grid step, minutes.
    pub grid_step_min: Option<f64>,
    /// Wall-clock time, ms.
    pub solve_ms: f64,
    /// The schedule.
    pub transfers: Vec<Transfer>,
}

fn exact_row(method: HopMethod, kind: &'static str, o: ExactOutcome) -> MethodRow {
    MethodRow {
        method,
        kind,
        status: Some(o.status),
        feasible: o.outcome.as_ref().map(|x| x.feasible),
        objective: if method == HopMethod::Fluid {
            o.bound
        } else {
            o.objective
        },
        objective_proven: method == HopMethod::Fluid || o.objective_proven,
        bound: if method == HopMethod::Fair {
            None
        } else {
            o.bound
        },
        qp_squared_deficits_mah2: if method == HopMethod::Fair {
            o.model_objective
        } else {
            None
        },
        gap: None,
        grid_step_min: (method == HopMethod::Milp).then_some(o.grid_step_min),
        solve_ms: o.solve_ms,
        transfers: o.transfers,
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
    Ok(match method {
        HopMethod::None | HopMethod::Pb | HopMethod::Fb => {
            let policy = match method {
                HopMethod::Pb => SharingPolicy::Pb,
                HopMethod::Fb => SharingPolicy::Fb,
                _ => SharingPolicy::None,
            };
            let o = simulate_with(problem, policy, readings)?;
            let value = if o.feasible {
                Some(objective_of(problem, objective, &o.final_battery_mah)?)
            } else {
                None
            };
            MethodRow {
                method,
                kind: "heuristic",
                status: None,
                feasible: Some(o.feasible),
                objective: value.map(|v| v.value),
                objective_proven: value.is_none_or(|v| v.proven),
                bound: None,
                qp_squared_deficits_mah2: None,
                gap: None,
                grid_step_min: None,
                solve_ms: start.elapsed().as_secs_f64() * 1e3,
                transfers: o.transfers,
            }
        }
        HopMethod::Milp => exact_row(method, "exact_grid", solve_milp(problem, objective, milp)?),
        HopMethod::Fluid => exact_row(
            method,
            "bound",
            fluid::bound(problem, objective, milp.reorder, milp.time_limit_s)?,
        ),
        HopMethod::Fair => exact_row(
            method,
            "fair_layout",
            fluid::fair(problem, objective, milp.reorder, milp.time_limit_s)?,
        ),
    })
}

/// The best reference among the rows, with its kind: the MILP's objective (`optimal` when the
/// solve and the node time of its schedule are proven, else `incumbent`), else the fluid bound.
pub fn reference(rows: &[MethodRow]) -> Option<(f64, ReferenceKind)> {
    rows.iter()
        .find_map(|r| match (r.method, r.status, r.objective) {
            // The MILP's schedule is optimal over the grid; its node time is the reference only
            // when the exact node time proved it.
            (HopMethod::Milp, Some(ExactStatus::Optimal), Some(v)) if r.objective_proven => {
                Some((v, ReferenceKind::Optimal))
            }
            (HopMethod::Milp, Some(ExactStatus::Optimal | ExactStatus::Feasible), Some(v)) => {
                Some((v, ReferenceKind::Incumbent))
            }
            _ => None,
        })
        .or_else(|| {
            rows.iter()
                .find(|r| r.method == HopMethod::Fluid && r.status == Some(ExactStatus::Optimal))
                .and_then(|r| r.bound.map(|b| (b, ReferenceKind::Bound)))
        })
}

/// Labels every row but the MILP's and the fluid bound's with its gap against [`reference`].
pub fn label_gaps(rows: &mut [MethodRow]) {
    if let Some((v, kind)) = reference(rows) {
        for r in rows.iter_mut() {
            if matches!(r.method, HopMethod::Milp | HopMethod::Fluid) {
                continue;
            }
            r.gap = r.objective.map(|h| Gap::new(h, v, kind));
        }
    }
}
