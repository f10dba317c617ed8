//! microlp through good_lp with a deterministic branch-and-bound node limit.
//!
//! good_lp's microlp model passes a wall-clock limit to microlp and nothing else, while microlp
//! itself can stop after a number of branch-and-bound nodes, the same on every machine and under
//! any load. [`NodeLimited`] is good_lp's model with microlp's `SolveOptions` filled in here: the
//! node limit and the wall-clock limit only when one is asked for (finite); microlp proves
//! optimality outright (no relative gap), as through good_lp. The model is built by good_lp (`good_lp::solvers::microlp::microlp`),
//! so variables and constraints are exactly good_lp's; only the call to microlp's solver is ours.
//! One check of good_lp's is skipped with it: an integer variable whose bounds hold no integer,
//! or lie outside `i32`, which good_lp reports when solving. The models here use binaries and
//! continuous variables only.
//!
//! The search's end is read from microlp's own types ([`NodeLimited::solve_outcome`]): its
//! errors `Infeasible` and `Unbounded`, an interrupted search without an incumbent, and its
//! termination reason.

use super::{variable_index, BackendStatus, MilpModel, MilpOutcome};
use good_lp::solvers::microlp::MicroLpProblem;
use good_lp::solvers::{ResolutionError, Solution, SolutionStatus, SolverModel, WithTimeLimit};
use good_lp::{Constraint, Variable};
use std::time::Duration;

/// good_lp's microlp model, solved with a node limit; see the module.
pub struct NodeLimited {
    inner: MicroLpProblem,
    node_limit: Option<u64>,
    time_limit_s: Option<f64>,
}

/// The solver for good_lp's `using`: microlp stopping after `node_limit` branch-and-bound nodes
/// (`None`: none).
pub fn microlp_limited(
    node_limit: Option<u64>,
) -> impl FnMut(good_lp::variable::UnsolvedProblem) -> NodeLimited {
    move |problem| NodeLimited {
        inner: good_lp::solvers::microlp::microlp(problem),
        node_limit,
        time_limit_s: None,
    }
}

impl WithTimeLimit for NodeLimited {
    /// A finite positive limit is passed to microlp; an infinite one means none.
    fn with_time_limit<T: Into<f64>>(mut self, seconds: T) -> Self {
        let s = seconds.into();
        self.time_limit_s = (s.is_finite() && s > 0.0).then_some(s);
        self
    }
}

/// A solution: every variable's value by its index, and how the search ended.
pub struct LimitedSolution {
    values: Vec<f64>,
    status: SolutionStatus,
}

impl Solution for LimitedSolution {
    fn status(&self) -> SolutionStatus {
        self.status
    }

    fn value(&self, variable: Variable) -> f64 {
        self.values[variable_index(variable)]
    }
}

impl SolverModel for NodeLimited {
    type Solution = LimitedSolution;
    type Error = ResolutionError;

    fn solve(self) -> Result<LimitedSolution, ResolutionError> {
        self.solve_outcome()?.into_solution()
    }

    fn add_constraint(&mut self, c: Constraint) -> good_lp::constraint::ConstraintReference {
        self.inner.add_constraint(c)
    }

    fn name() -> &'static str {
        "Microlp"
    }
}

impl MilpModel for NodeLimited {
    fn solve_outcome(self) -> Result<MilpOutcome<LimitedSolution>, ResolutionError> {
        let mut options = microlp::SolveOptions::default();
        options.node_limit = self.node_limit;
        options.time_limit = self.time_limit_s.map(Duration::from_secs_f64);
        let no_solution = |status, report| Ok(MilpOutcome::NoSolution { status, report });
        let outcome = match self.inner.as_inner().solve_with(options) {
            Ok(outcome) => outcome,
            Err(microlp::Error::Infeasible) => {
                return no_solution(BackendStatus::Infeasible, ResolutionError::Infeasible)
            }
            Err(microlp::Error::Unbounded) => {
                return no_solution(BackendStatus::Unbounded, ResolutionError::Unbounded)
            }
            Err(other) => return Err(ResolutionError::Str(other.to_string())),
        };
        let reason = outcome.termination_reason();
        let Ok(solution) = outcome.into_solution() else {
            // An interrupted search without an incumbent, reported as good_lp reports it.
            return no_solution(
                BackendStatus::LimitNoSolution,
                ResolutionError::Other("Time limit reached before finding a feasible solution"),
            );
        };
        let (status, good_lp_status) = match reason {
            microlp::TerminationReason::ProvenOptimal => {
                (BackendStatus::Optimal, SolutionStatus::Optimal)
            }
            microlp::TerminationReason::MipGap => {
                (BackendStatus::OptimalWithinGap, SolutionStatus::GapLimit)
            }
            // The time or node limit (and any limit a later microlp adds).
            _ => (BackendStatus::Feasible, SolutionStatus::TimeLimit),
        };
        Ok(MilpOutcome::Solved {
            status,
            solution: LimitedSolution {
                values: solution.iter().map(|(_, v)| v).collect(),
                status: good_lp_status,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use good_lp::{constraint, variable, variables};

    #[test]
    fn values_follow_good_lps_variables_and_the_node_limit_stops_the_search() {
        // max x + 2y over integers with x + y <= 3.5, y <= 1.5: y <= 1, then x <= 2.5 so x <= 2;
        // (2, 1) gives 4, the only other maximal point (3, 0) gives 3.
        let mut vars = variables!();
        let x = vars.add(variable().integer().min(0).max(10));
        let y = vars.add(variable().integer().min(0).max(10));
        let solution = vars
            .maximise(x + 2 * y)
            .using(microlp_limited(None))
            .with(constraint!(x + y <= 3.5))
            .with(constraint!(y <= 1.5))
            .solve()
            .unwrap();
        assert!(matches!(solution.status(), SolutionStatus::Optimal));
        assert!((solution.value(x) - 2.0).abs() < 1e-9);
        assert!((solution.value(y) - 1.0).abs() < 1e-9);
        // With no node beyond the root, whose relaxation (2.5, 1) is fractional, the search
        // stops without proving: no incumbent, or one at the limit.
        let mut vars = variables!();
        let x = vars.add(variable().integer().min(0).max(10));
        let y = vars.add(variable().integer().min(0).max(10));
        let stopped = vars
            .maximise(x + 2 * y)
            .using(microlp_limited(Some(0)))
            .with(constraint!(x + y <= 3.5))
            .with(constraint!(y <= 1.5))
            .solve();
        match stopped {
            Ok(s) => assert!(matches!(s.status(), SolutionStatus::TimeLimit)),
            Err(e) => assert!(e.to_string().contains("Time limit"), "{e}"),
        }
    }
}
