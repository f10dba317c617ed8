//! clarabel for the convex models (the fluid LP and QP of a hop, the bin-packing LP of the node
//! time): one call that sets clarabel up, solves `min 1/2 x'Px + q'x` subject to `A x + s = b`,
//! `s in K`, and reads clarabel's status as a [`BackendStatus`].
//!
//! The conic subset of [`BackendStatus`]: `Solved` and `AlmostSolved` (solved to clarabel's
//! reduced accuracy) are [`BackendStatus::Optimal`]; `PrimalInfeasible` and
//! `AlmostPrimalInfeasible` [`BackendStatus::Infeasible`]; `DualInfeasible` and
//! `AlmostDualInfeasible` [`BackendStatus::Unbounded`]; `MaxTime` and `MaxIterations` (stopped
//! before convergence, no answer) [`BackendStatus::LimitNoSolution`]. clarabel never gives
//! [`BackendStatus::OptimalWithinGap`] or [`BackendStatus::Feasible`]. Its other statuses
//! (a numerical error, insufficient progress) are failures: `Err`.

use super::BackendStatus;
use crate::error::{BackendFailure, Error, Result};
pub use clarabel::algebra::CscMatrix;
use clarabel::solver::{DefaultSettings, DefaultSolver, IPSolver, SolverStatus};
pub use clarabel::solver::{NonnegativeConeT, SupportedConeT, ZeroConeT};

/// The options of a conic solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConicSettings {
    /// clarabel's absolute and relative gap tolerances and its feasibility tolerance.
    pub tolerance: f64,
    /// clarabel's time limit, seconds (`None`: clarabel's default, none).
    pub time_limit_s: Option<f64>,
}

/// The answer of a solve that ended [`BackendStatus::Optimal`].
#[derive(Debug, Clone, PartialEq)]
pub struct ConicValues {
    /// The primal solution `x`.
    pub x: Vec<f64>,
    /// The dual solution `z`, one value per row of `A` (the multipliers of `A x + s = b`).
    pub z: Vec<f64>,
    /// The primal objective value.
    pub primal: f64,
    /// The dual objective value.
    pub dual: f64,
}

/// How a conic solve ended.
#[derive(Debug, Clone, PartialEq)]
pub struct ConicOutcome {
    /// [`BackendStatus::Optimal`], [`BackendStatus::Infeasible`], [`BackendStatus::Unbounded`]
    /// or [`BackendStatus::LimitNoSolution`].
    pub status: BackendStatus,
    /// The answer: `Some` exactly when `status` is [`BackendStatus::Optimal`].
    pub values: Option<ConicValues>,
}

/// clarabel's status as a [`BackendStatus`] (see the module); `None` for a failure.
pub fn status_of(status: SolverStatus) -> Option<BackendStatus> {
    match status {
        SolverStatus::Solved | SolverStatus::AlmostSolved => Some(BackendStatus::Optimal),
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            Some(BackendStatus::Infeasible)
        }
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => {
            Some(BackendStatus::Unbounded)
        }
        SolverStatus::MaxTime | SolverStatus::MaxIterations => Some(BackendStatus::LimitNoSolution),
        SolverStatus::Unsolved
        | SolverStatus::NumericalError
        | SolverStatus::InsufficientProgress
        | SolverStatus::CallbackTerminated => None,
    }
}

/// Solves `min 1/2 x'Px + q'x` subject to `A x + s = b`, `s in cones`, with clarabel, quiet.
///
/// # Arguments
/// * `p` - the upper triangle of `P` (`n x n`, positive semidefinite; empty for an LP).
/// * `q` - the linear objective, `n` values.
/// * `a`, `b` - the rows, `m x n` and `m` values.
/// * `cones` - the cones of the rows, in order, their sizes summing to `m`.
/// * `settings` - tolerances and time limit.
///
/// # Errors
/// [`Error::Backend`] (backend `clarabel`) when clarabel refuses the problem (inconsistent
/// dimensions) or fails numerically.
pub fn solve(
    p: &CscMatrix<f64>,
    q: &[f64],
    a: &CscMatrix<f64>,
    b: &[f64],
    cones: &[SupportedConeT<f64>],
    settings: ConicSettings,
) -> Result<ConicOutcome> {
    let fail = |kind, message: String| Error::backend(kind, "clarabel", message);
    let mut clarabel_settings = DefaultSettings {
        verbose: false,
        tol_gap_abs: settings.tolerance,
        tol_gap_rel: settings.tolerance,
        tol_feas: settings.tolerance,
        ..DefaultSettings::default()
    };
    if let Some(s) = settings.time_limit_s {
        clarabel_settings.time_limit = s;
    }
    let mut solver = DefaultSolver::new(p, q, a, b, cones, clarabel_settings)
        .map_err(|e| fail(BackendFailure::Refused, format!("{e:?}")))?;
    solver.solve();
    let s = &solver.solution;
    let status = status_of(s.status).ok_or_else(|| {
        fail(
            BackendFailure::Numerical,
            format!(
                "stopped with status {:?}; report it with the instance",
                s.status
            ),
        )
    })?;
    let values = (status == BackendStatus::Optimal).then(|| ConicValues {
        x: s.x.clone(),
        z: s.z.clone(),
        primal: s.obj_val,
        dual: s.obj_val_dual,
    });
    Ok(ConicOutcome { status, values })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings() -> ConicSettings {
        ConicSettings {
            tolerance: 1e-9,
            time_limit_s: None,
        }
    }

    /// `min -x - y` over `x + y <= rhs_sum`, `x, y >= 0` (rows `A x + s = b`, `s >= 0`).
    fn lp(rhs_sum: f64) -> (CscMatrix<f64>, Vec<f64>, CscMatrix<f64>, Vec<f64>) {
        let p = CscMatrix::new_from_triplets(2, 2, Vec::new(), Vec::new(), Vec::new());
        // Rows: x + y <= rhs_sum, -x <= 0, -y <= 0.
        let a = CscMatrix::new_from_triplets(
            3,
            2,
            vec![0, 0, 1, 2],
            vec![0, 1, 0, 1],
            vec![1.0, 1.0, -1.0, -1.0],
        );
        (p, vec![-1.0, -1.0], a, vec![rhs_sum, 0.0, 0.0])
    }

    #[test]
    fn a_bounded_lp_is_optimal_with_its_value() {
        // Every point of x + y = 1 in the quadrant is optimal: value -1.
        let (p, q, a, b) = lp(1.0);
        let out = solve(&p, &q, &a, &b, &[NonnegativeConeT(3)], settings()).unwrap();
        assert_eq!(out.status, BackendStatus::Optimal);
        let v = out.values.unwrap();
        assert!((v.primal + 1.0).abs() < 1e-7, "{v:?}");
        assert!((v.x[0] + v.x[1] - 1.0).abs() < 1e-7, "{v:?}");
    }

    #[test]
    fn an_empty_region_is_infeasible() {
        // x + y <= -1 with x, y >= 0: no point.
        let (p, q, a, b) = lp(-1.0);
        let out = solve(&p, &q, &a, &b, &[NonnegativeConeT(3)], settings()).unwrap();
        assert_eq!(out.status, BackendStatus::Infeasible);
        assert_eq!(out.values, None);
    }

    #[test]
    fn an_lp_without_a_lower_bound_is_unbounded() {
        // min -x - y with only x, y >= 0: -x - y falls without end.
        let p = CscMatrix::new_from_triplets(2, 2, Vec::new(), Vec::new(), Vec::new());
        let a = CscMatrix::new_from_triplets(2, 2, vec![0, 1], vec![0, 1], vec![-1.0, -1.0]);
        let out = solve(
            &p,
            &[-1.0, -1.0],
            &a,
            &[0.0, 0.0],
            &[NonnegativeConeT(2)],
            settings(),
        )
        .unwrap();
        assert_eq!(out.status, BackendStatus::Unbounded);
        assert_eq!(out.values, None);
    }

    #[test]
    fn every_clarabel_status_has_its_place() {
        use SolverStatus as S;
        let cases = [
            (S::Solved, Some(BackendStatus::Optimal)),
            (S::AlmostSolved, Some(BackendStatus::Optimal)),
            (S::PrimalInfeasible, Some(BackendStatus::Infeasible)),
            (S::AlmostPrimalInfeasible, Some(BackendStatus::Infeasible)),
            (S::DualInfeasible, Some(BackendStatus::Unbounded)),
            (S::AlmostDualInfeasible, Some(BackendStatus::Unbounded)),
            (S::MaxTime, Some(BackendStatus::LimitNoSolution)),
            (S::MaxIterations, Some(BackendStatus::LimitNoSolution)),
            (S::Unsolved, None),
            (S::NumericalError, None),
            (S::InsufficientProgress, None),
            (S::CallbackTerminated, None),
        ];
        for (clarabel, ours) in cases {
            assert_eq!(status_of(clarabel), ours, "{clarabel:?}");
        }
    }

    #[test]
    fn mismatched_dimensions_are_a_backend_error() {
        let (p, q, a, _) = lp(1.0);
        let e = solve(&p, &q, &a, &[1.0], &[NonnegativeConeT(1)], settings()).unwrap_err();
        assert!(matches!(e, Error::Backend { ref backend, .. } if backend == "clarabel"));
    }
}
