//! Assignment MILP for the node time (see `models/node_time.md`), written once as
//! [`solve_with`] and run on every enabled [`MilpBackend`].
//!
//! Jobs sorted by decreasing charge time `p_0 >= ... >= p_{n-1}`, pads `i in 0..m`, `m = min(k, n)`:
//!
//! ```text
//! min  C
//! s.t. sum_{i <= min(j, m-1)} x[j][i] = 1                 for every job j
//!      sum_{j >= i} p_j x[j][i] <= C                      for every pad i
//!      x[j][i] in {0, 1} (defined for i <= j only),  C >= 0 (minutes)
//! ```
//!
//! Symmetry breaking: number the pads by the first (longest) job they hold; then job `j` sits on a
//! pad `i <= j`, so `x[j][i]` with `i > j` is not created.

use super::{
    elapsed_ms, lists_from_pad_of, lower_bound_sorted, sort_desc, validate, validate_limits,
    Limits, NodeTimeMethod, NodeTimeSolution,
};
use crate::error::{Error, Result};
use crate::solver::{run_on, MilpBackend, MilpJob, SolveStatus};
use good_lp::{
    constraint, variable, Expression, ProblemVariables, Solution, SolutionStatus, SolverModel,
    Variable, WithTimeLimit,
};
use std::time::Instant;

/// Solves the assignment MILP for times sorted in decreasing order on any good_lp solver.
///
/// Returns the pad of each sorted job and whether the backend proved optimality (a stop at the
/// relative MIP gap asked for, at most [`super::REL_TOL`], counts as proven).
///
/// # Errors
/// [`Error::Backend`] when the backend fails or stops without any feasible assignment.
pub fn solve_with<S: good_lp::Solver>(
    solver: S,
    backend_name: &str,
    pads: usize,
    sorted_desc: &[f64],
    time_limit_s: Option<f64>,
) -> Result<(Vec<usize>, bool)>
where
    S::Model: WithTimeLimit,
{
    let n = sorted_desc.len();
    let m = pads.min(n);
    let mut vars = ProblemVariables::new();
    let c = vars.add(variable().min(0.0));
    // x[j][i] for i <= min(j, m-1).
    let x: Vec<Vec<Variable>> = (0..n)
        .map(|j| {
            (0..=j.min(m - 1))
                .map(|_| vars.add(variable().binary()))
                .collect()
        })
        .collect();
    let mut model = vars.minimise(c).using(solver);
    if let Some(t) = time_limit_s {
        model = model.with_time_limit(t);
    }
    for xj in &x {
        let once: Expression = xj.iter().copied().sum();
        model.add_constraint(constraint!(once == 1.0));
    }
    for i in 0..m {
        let load: Expression = x
            .iter()
            .zip(sorted_desc)
            .skip(i)
            .map(|(xj, &p)| p * xj[i])
            .sum();
        model.add_constraint(constraint!(load <= c));
    }
    let solution = model.solve().map_err(|e| Error::Backend {
        backend: backend_name.to_string(),
        message: format!("{e}; if a time limit was set, raise it"),
    })?;
    // A gap stop is a proof within the gap asked for, at most REL_TOL (HiGHS); a time stop is not.
    let optimal = matches!(
        solution.status(),
        SolutionStatus::Optimal | SolutionStatus::GapLimit
    );
    let mut pad_of = vec![0; n];
    for (j, xj) in x.iter().enumerate() {
        let chosen: Vec<usize> = (0..xj.len())
            .filter(|&i| solution.value(xj[i]) > 0.5)
            .collect();
        if chosen.len() != 1 {
            return Err(Error::Backend {
                backend: backend_name.to_string(),
                message: format!("returned job {j} on {} pads, not exactly one", chosen.len()),
            });
        }
        pad_of[j] = chosen[0];
    }
    Ok((pad_of, optimal))
}

/// One solve of the assignment MILP, for [`run_on`].
struct PcmaxJob<'a> {
    pads: usize,
    sorted_desc: &'a [f64],
    time_limit_s: Option<f64>,
}

impl MilpJob for PcmaxJob<'_> {
    type Output = (Vec<usize>, bool);

    fn solve_with<S: good_lp::Solver>(
        self,
        solver: S,
        backend_name: &str,
    ) -> Result<(Vec<usize>, bool)>
    where
        S::Model: WithTimeLimit + good_lp::SolverModel<Error = good_lp::ResolutionError>,
    {
        solve_with(
            solver,
            backend_name,
            self.pads,
            self.sorted_desc,
            self.time_limit_s,
        )
    }
}

/// Node time by the assignment MILP on `backend`.
///
/// # Arguments
/// * `pads`, `charge_times_min` - the instance, as in [`validate`].
/// * `backend` - the MILP backend.
/// * `limits` - the time limit is passed to the backend; the node limit is ignored.
///
/// # Returns
/// `Optimal` when the backend proves optimality; otherwise `Feasible` with its incumbent and the
/// combinatorial root bound as `lower_bound_min`. The makespan is recomputed from the raw times.
///
/// # Errors
/// Those of [`validate`]; `E5006` for a bad time limit; [`Error::Backend`] when the backend fails.
///
/// # Complexity
/// `n * min(k, n)` binaries; exponential worst case.
///
/// # Example
/// ```
/// use swarmplan::node_time::{milp, Limits};
/// use swarmplan::solver::MilpBackend;
/// let times = [60.0, 50.0, 40.0, 30.0, 20.0];
/// for backend in MilpBackend::all() {
///     let s = milp(3, &times, backend, &Limits::default()).unwrap();
///     assert!((s.makespan_min - 70.0).abs() < 1e-9);
/// }
/// ```
pub fn milp(
    pads: usize,
    charge_times_min: &[f64],
    backend: MilpBackend,
    limits: &Limits,
) -> Result<NodeTimeSolution> {
    validate(pads, charge_times_min)?;
    validate_limits(limits)?;
    let start = Instant::now();
    let n = charge_times_min.len();
    let m = pads.min(n);
    let (order, sorted) = sort_desc(charge_times_min);
    let t = limits.time_limit_s;
    let job = PcmaxJob {
        pads: m,
        sorted_desc: &sorted,
        time_limit_s: t,
    };
    let (pad_sorted, optimal) = run_on(backend, limits.node_limit, job)?;
    let mut pad_of = vec![0; n];
    for (pos, &j) in order.iter().enumerate() {
        pad_of[j] = pad_sorted[pos];
    }
    let assignment = lists_from_pad_of(&pad_of, m);
    let makespan = super::makespan_of(charge_times_min, &assignment);
    let lb = lower_bound_sorted(m, &sorted, super::all_integral(charge_times_min));
    Ok(NodeTimeSolution {
        method: NodeTimeMethod::Milp,
        makespan_min: makespan,
        lower_bound_min: if optimal { makespan } else { lb.min(makespan) },
        status: if optimal {
            SolveStatus::Optimal
        } else {
            SolveStatus::Feasible
        },
        assignment,
        solve_ms: elapsed_ms(start),
    })
}
