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
use crate::error::{BackendFailure, Error, Result};
use crate::solver::lp_file::{write_model_file, LpCapture, LpSize, ModelFormat};
use crate::solver::{
    run_on, BackendStatus, MilpBackend, MilpJob, MilpModel, MilpOutcome, SolveStatus,
};
use good_lp::{
    constraint, variable, Expression, ProblemVariables, Solution, SolverModel, Variable,
    WithTimeLimit,
};
use std::path::Path;
use std::time::Instant;

/// The assignment MILP for `pads` (`m <= n`) and times sorted in decreasing order, built on any
/// good_lp solver: the model, `C` and `x[j][i]` (variables added in the order `C`, then `x` by
/// job and pad).
fn build<S: good_lp::Solver>(
    solver: S,
    pads: usize,
    sorted_desc: &[f64],
    time_limit_s: Option<f64>,
) -> (S::Model, Vec<Vec<Variable>>)
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
    (model, x)
}

/// Solves the assignment MILP for times sorted in decreasing order on any of
/// [`run_on`]'s backends.
///
/// Returns the pad of each sorted job and how the search ended: [`BackendStatus::Optimal`],
/// [`BackendStatus::OptimalWithinGap`] (a stop at the relative MIP gap asked for, at most
/// [`super::REL_TOL`], a proof within it) or [`BackendStatus::Feasible`] (stopped by a limit).
///
/// # Errors
/// [`Error::Backend`] when the backend fails or stops without any feasible assignment.
pub fn solve_with<S: good_lp::Solver>(
    solver: S,
    backend_name: &str,
    pads: usize,
    sorted_desc: &[f64],
    time_limit_s: Option<f64>,
) -> Result<(Vec<usize>, BackendStatus)>
where
    S::Model: MilpModel,
{
    let n = sorted_desc.len();
    let (model, x) = build(solver, pads, sorted_desc, time_limit_s);
    let fail = |kind, e: good_lp::ResolutionError| {
        Error::backend(
            kind,
            backend_name,
            format!("{e}; if a time limit was set, raise it"),
        )
    };
    // Every end without an assignment is an error, told in the backend's words.
    let (status, solution) = match model
        .solve_outcome()
        .map_err(|e| fail(BackendFailure::Numerical, e))?
    {
        MilpOutcome::Solved { status, solution } => (status, solution),
        MilpOutcome::NoSolution { status, report } => {
            let kind = if status == BackendStatus::LimitNoSolution {
                BackendFailure::Limit
            } else {
                BackendFailure::Numerical
            };
            return Err(fail(kind, report));
        }
    };
    let mut pad_of = vec![0; n];
    for (j, xj) in x.iter().enumerate() {
        let chosen: Vec<usize> = (0..xj.len())
            .filter(|&i| solution.value(xj[i]) > 0.5)
            .collect();
        if chosen.len() != 1 {
            return Err(Error::backend(
                BackendFailure::Numerical,
                backend_name,
                format!("returned job {j} on {} pads, not exactly one", chosen.len()),
            ));
        }
        pad_of[j] = chosen[0];
    }
    Ok((pad_of, status))
}

/// One solve of the assignment MILP, for [`run_on`].
struct PcmaxJob<'a> {
    pads: usize,
    sorted_desc: &'a [f64],
    time_limit_s: Option<f64>,
}

impl MilpJob for PcmaxJob<'_> {
    type Output = (Vec<usize>, BackendStatus);

    fn solve_with<S: good_lp::Solver>(
        self,
        solver: S,
        backend_name: &str,
    ) -> Result<(Vec<usize>, BackendStatus)>
    where
        S::Model: MilpModel,
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
    let (pad_sorted, backend_status) = run_on(backend, limits.node_limit, job)?;
    // An assignment comes with a proof (within the gap) or as a limit's incumbent.
    let optimal = backend_status.proven();
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

/// The assignment MILP [`milp`] solves for this instance, in `format`, for any MILP solver.
///
/// The model is built by the same code as for [`milp`]'s backends and handed to
/// [`LpCapture`] instead of a solver. The jobs are the drones sorted by decreasing charge time
/// (the header lists job `j` -> drone and `p_j`); variables are named as in
/// `models/node_time.md`: `C` (the node time, min) and `x_j{j}_i{i}` (job `j` on pad `i`, for
/// `i <= min(j, m - 1)`). The file's optimum is the node time.
///
/// # Arguments
/// * `pads`, `charge_times_min` - the instance, as in [`validate`].
/// * `format` - CPLEX LP or free MPS.
/// * `about` - one line naming the instance for the header.
///
/// # Returns
/// The text, and the model's size: `1 + sum_j (min(j, m - 1) + 1)` variables, all but `C`
/// binary, `n + m` constraints (`m = min(k, n)`).
///
/// # Errors
/// Those of [`validate`]; [`Error::Backend`] if the model cannot be captured.
///
/// # Example
/// ```
/// use swarmplan::node_time::model_text;
/// use swarmplan::solver::lp_file::ModelFormat;
/// let (mps, size) = model_text(2, &[3.0, 5.0, 4.0], ModelFormat::Mps, "example").unwrap();
/// // C, x_j0_i0, x_j1_i0, x_j1_i1, x_j2_i0, x_j2_i1; 3 jobs placed once, 2 pad loads.
/// assert_eq!((size.variables, size.binaries, size.constraints), (6, 5, 5));
/// assert!(mps.contains("x_j2_i1"));
/// ```
pub fn model_text(
    pads: usize,
    charge_times_min: &[f64],
    format: ModelFormat,
    about: &str,
) -> Result<(String, LpSize)> {
    validate(pads, charge_times_min)?;
    let n = charge_times_min.len();
    let m = pads.min(n);
    let (order, sorted) = sort_desc(charge_times_min);
    let capture = LpCapture::new();
    let (model, x) = build(capture.solver(), m, &sorted, None);
    let lost = |what: String| {
        Error::backend(
            BackendFailure::LostModel,
            "lp-file",
            format!("the model was not captured ({what})"),
        )
    };
    model.solve().map_err(|e| lost(e.to_string()))?;
    let mut captured = capture.take().ok_or_else(|| lost("empty capture".into()))?;
    let mut names = vec!["C".to_string()];
    for (j, xj) in x.iter().enumerate() {
        names.extend((0..xj.len()).map(|i| format!("x_j{j}_i{i}")));
    }
    captured.rename(&names)?;
    let size = captured.size();
    let mut header = vec![
        format!("swarmplan node-time assignment MILP (models/node_time.md): {about}"),
        format!("pads: k = {pads}, m = min(k, n) = {m} used; drones: n = {n}"),
        "objective: minimise C, the node time (makespan), min".to_string(),
        "x_j{j}_i{i} = 1 iff job j charges on pad i (i <= min(j, m - 1): pads numbered by their \
         longest job)"
            .to_string(),
        format!(
            "size: {} variables ({} binary), {} constraints",
            size.variables, size.binaries, size.constraints
        ),
        "jobs by decreasing charge time: job j = drone d, p_j min".to_string(),
    ];
    header.extend(
        order
            .iter()
            .zip(&sorted)
            .enumerate()
            .map(|(j, (d, p))| format!("  job {j} = drone {d}, p = {p}")),
    );
    Ok((
        captured.to_text(format, "swarmplan_node_time_milp", &header),
        size,
    ))
}

/// Writes [`model_text`] to `path`: free MPS when its name ends in `.mps`, CPLEX LP otherwise.
///
/// # Returns
/// The size of the model and the format written.
///
/// # Errors
/// Those of [`model_text`]; [`Error::Io`] when the file cannot be written.
pub fn write_model(
    pads: usize,
    charge_times_min: &[f64],
    about: &str,
    path: &Path,
) -> Result<(LpSize, ModelFormat)> {
    let format = ModelFormat::of_path(path);
    let (text, size) = model_text(pads, charge_times_min, format, about)?;
    write_model_file(path, &text)?;
    Ok((size, format))
}
