//! HiGHS through good_lp, with our options and its model status read as a [`BackendStatus`].
//!
//! The model is built by good_lp (`good_lp::solvers::highs::highs`), so variables and
//! constraints are exactly good_lp's; [`HighsLimited`] takes the HiGHS model good_lp builds
//! (`HighsProblem::try_into_inner`), sets the options of [`super::run_on`] on it and solves it.
//! good_lp's own solve turns some ends into error text (a stop without a primal solution is
//! `Other("NoSolutionFound")`); here the end is read from HiGHS's model status and primal
//! solution status instead. A status good_lp reports as an error is reported with good_lp's
//! words, so messages are unchanged.

use super::{variable_index, BackendStatus, MilpModel, MilpOutcome, MIP_REL_GAP};
use good_lp::solvers::highs::HighsProblem;
use good_lp::solvers::{ResolutionError, Solution, SolutionStatus, SolverModel, WithTimeLimit};
use good_lp::{Constraint, Variable};
use highs::{HighsModelStatus, HighsSolutionStatus};

/// good_lp's HiGHS model with the options of [`super::run_on`]: one thread, the relative gap
/// [`MIP_REL_GAP`], no absolute gap, a node limit and a time limit.
pub struct HighsLimited {
    inner: HighsProblem,
    node_limit: Option<u64>,
    time_limit_s: Option<f64>,
}

/// The solver for good_lp's `using`: HiGHS stopping after `node_limit` branch-and-bound nodes
/// (`None`: none).
pub fn highs_limited(
    node_limit: Option<u64>,
) -> impl FnMut(good_lp::variable::UnsolvedProblem) -> HighsLimited {
    move |problem| HighsLimited {
        inner: good_lp::solvers::highs::highs(problem),
        node_limit,
        time_limit_s: None,
    }
}

impl WithTimeLimit for HighsLimited {
    /// Passed to HiGHS as given (its default, infinity, means none).
    fn with_time_limit<T: Into<f64>>(mut self, seconds: T) -> Self {
        self.time_limit_s = Some(seconds.into());
        self
    }
}

/// A solution: every column's value, and how the search ended in good_lp's terms.
pub struct HighsValues {
    values: Vec<f64>,
    status: SolutionStatus,
}

impl Solution for HighsValues {
    fn status(&self) -> SolutionStatus {
        self.status
    }

    fn value(&self, variable: Variable) -> f64 {
        self.values[variable_index(variable)]
    }
}

/// How a solve ended, from HiGHS's model status, whether it holds a primal feasible solution and
/// its MIP gap. `Err`: a status that is a failure, in good_lp's words.
///
/// Every status with values is kept only with a primal feasible solution; without one it is
/// [`BackendStatus::LimitNoSolution`], as for a limit reached before any incumbent.
/// `UnboundedOrInfeasible` (HiGHS's presolve cannot tell which) counts as infeasible, as good_lp
/// counts it.
pub fn status_of(
    model_status: HighsModelStatus,
    primal_feasible: bool,
    mip_gap: f64,
) -> Result<BackendStatus, ResolutionError> {
    use HighsModelStatus as M;
    let status = match model_status {
        M::NotSet => return Err(ResolutionError::Other("NotSet")),
        M::LoadError => return Err(ResolutionError::Other("LoadError")),
        M::ModelError => return Err(ResolutionError::Other("ModelError")),
        M::PresolveError => return Err(ResolutionError::Other("PresolveError")),
        M::SolveError => return Err(ResolutionError::Other("SolveError")),
        M::PostsolveError => return Err(ResolutionError::Other("PostsolveError")),
        M::ModelEmpty => return Err(ResolutionError::Other("ModelEmpty")),
        M::Infeasible | M::UnboundedOrInfeasible => return Ok(BackendStatus::Infeasible),
        M::Unbounded => return Ok(BackendStatus::Unbounded),
        M::ReachedTimeLimit
        | M::ReachedSolutionLimit
        | M::ReachedInterrupt
        | M::ReachedIterationLimit
        | M::ReachedMemoryLimit => BackendStatus::Feasible,
        M::Optimal | M::ObjectiveBound | M::ObjectiveTarget => {
            if mip_gap.is_finite() && mip_gap > 0.0 {
                BackendStatus::OptimalWithinGap
            } else {
                BackendStatus::Optimal
            }
        }
        // `Unknown`, and any status a later HiGHS adds.
        _ => return Err(ResolutionError::Other("Unknown")),
    };
    Ok(if primal_feasible {
        status
    } else {
        BackendStatus::LimitNoSolution
    })
}

impl MilpModel for HighsLimited {
    fn solve_outcome(self) -> Result<MilpOutcome<HighsValues>, ResolutionError> {
        let mut model = self.inner.try_into_inner()?;
        let set = |key: &str, result: Result<(), highs::TrySetOptionError>| {
            result.map_err(|_| {
                ResolutionError::Str(format!("HiGHS error while setting option {key}"))
            })
        };
        set("threads", model.try_set_option("threads", 1))?;
        set(
            "mip_rel_gap",
            model.try_set_option("mip_rel_gap", MIP_REL_GAP),
        )?;
        set("mip_abs_gap", model.try_set_option("mip_abs_gap", 0.0))?;
        if let Some(n) = self.node_limit {
            let n = n.min(i32::MAX as u64) as i32;
            set("mip_max_nodes", model.try_set_option("mip_max_nodes", n))?;
        }
        if let Some(s) = self.time_limit_s {
            set("time_limit", model.try_set_option("time_limit", s))?;
        }
        let solved = model
            .try_solve()
            .map_err(|e| ResolutionError::Str(format!("HiGHS error while solving model: {e:?}")))?;
        let primal_feasible = solved.primal_solution_status() == HighsSolutionStatus::Feasible;
        let status = status_of(solved.status(), primal_feasible, solved.mip_gap())?;
        // Each end in good_lp's terms: a solution's status, or the error good_lp reports.
        let no_solution = |report| Ok(MilpOutcome::NoSolution { status, report });
        let good_lp_status = match status {
            BackendStatus::Optimal => SolutionStatus::Optimal,
            BackendStatus::OptimalWithinGap => SolutionStatus::GapLimit,
            BackendStatus::Feasible => SolutionStatus::TimeLimit,
            BackendStatus::Infeasible => return no_solution(ResolutionError::Infeasible),
            BackendStatus::Unbounded => return no_solution(ResolutionError::Unbounded),
            BackendStatus::LimitNoSolution => {
                return no_solution(ResolutionError::Other("NoSolutionFound"))
            }
        };
        Ok(MilpOutcome::Solved {
            status,
            solution: HighsValues {
                values: solved.get_solution().columns().to_vec(),
                status: good_lp_status,
            },
        })
    }
}

impl SolverModel for HighsLimited {
    type Solution = HighsValues;
    type Error = ResolutionError;

    fn solve(self) -> Result<HighsValues, ResolutionError> {
        self.solve_outcome()?.into_solution()
    }

    fn add_constraint(&mut self, c: Constraint) -> good_lp::constraint::ConstraintReference {
        self.inner.add_constraint(c)
    }

    fn name() -> &'static str {
        "Highs"
    }
}
