//! Backend choice, options and solve outcome, shared by every exact method: the one place that
//! builds a backend, applies its options and maps its own status to [`BackendStatus`].
//! User guide: "HiGHS and the build without MILP" (`docs/src/highs.md`) and "Exact references and
//! gaps" (`docs/src/exact.md`).
//!
//! Backends are chosen by enum, never by string: `microlp` (pure Rust, default) and, with the
//! `highs` feature, HiGHS, both through good_lp ([`run_on`]); convex models go to clarabel
//! ([`conic`]); the pad search's small LPs, which gain a row at each node, to a dense dual
//! simplex of the crate's own ([`dense`]). How a solve ended (optimal, feasible with an
//! incumbent after a limit, stopped without one, infeasible, unbounded) is a
//! [`BackendStatus`], data read from each backend's own status codes, never from its messages;
//! `Err` is for bad input and broken backends. The models' statuses (`ExactStatus` of the hop
//! models, [`SolveStatus`] of the node time) are derived from it by a match. [`lp_file`] writes
//! a good_lp model in CPLEX LP or free MPS format instead of solving it.

use crate::error::Violation;
use serde::{Deserialize, Serialize};

pub mod conic;
pub mod dense;
#[cfg(feature = "highs")]
pub mod highs;
#[cfg(feature = "microlp")]
pub mod limited;
pub mod lp_file;

/// MILP backend.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum MilpBackend {
    /// good_lp's pure-Rust `microlp` branch and bound (default build).
    #[cfg(feature = "microlp")]
    Microlp,
    /// HiGHS through good_lp (feature `highs`).
    #[cfg(feature = "highs")]
    Highs,
    /// No MILP backend in this build (made without the microlp and highs features): a MILP solve
    /// gives E0011, every other method works.
    #[cfg(not(any(feature = "microlp", feature = "highs")))]
    #[cfg_attr(feature = "cli", value(name = "none"))]
    #[serde(rename = "none")]
    NoBackend,
}

impl Default for MilpBackend {
    /// The first backend of [`MilpBackend::all`]; `MilpBackend::NoBackend` in a build without one.
    fn default() -> Self {
        #[cfg(feature = "microlp")]
        return MilpBackend::Microlp;
        #[cfg(all(feature = "highs", not(feature = "microlp")))]
        return MilpBackend::Highs;
        #[cfg(not(any(feature = "microlp", feature = "highs")))]
        return MilpBackend::NoBackend;
    }
}

/// `E0011`: this build has no MILP backend (made without the `microlp` and `highs` features).
pub fn no_milp_backend(field: &str) -> crate::error::Error {
    crate::error::Error::invalid(
        "E0011",
        field,
        "this build of swarmplan has no MILP backend (built without the microlp and highs features)",
        "rebuild with the default features (cargo build --release) or --features highs, or use a \
         method without a MILP (node-time --method exact, --sharing pb|fb, eaas --methods \
         pb,fb,fluid,fair, --sharing fair)",
    )
}

impl MilpBackend {
    /// Every backend compiled into this build, in a fixed order; empty in a build without one.
    pub fn all() -> Vec<MilpBackend> {
        vec![
            #[cfg(feature = "microlp")]
            MilpBackend::Microlp,
            #[cfg(feature = "highs")]
            MilpBackend::Highs,
        ]
    }
}

display_as_value_name!(MilpBackend);

/// Every MILP backend swarmplan knows, built into this build or not: its name on the command
/// line and how to get a build with it.
const KNOWN_BACKENDS: [(&str, &str); 2] = [
    (
        "microlp",
        "rebuild with the default features: cargo build --release",
    ),
    (
        "highs",
        "rebuild with the feature highs: cargo build --release --features highs (building HiGHS \
         needs cmake and libclang: apt-get install cmake libclang-dev)",
    ),
];

/// The name of every MILP backend swarmplan knows, built into this build or not.
pub fn known_backend_names() -> impl Iterator<Item = &'static str> {
    KNOWN_BACKENDS.iter().map(|(name, _)| *name)
}

/// `E0012`: `name` is a backend swarmplan knows but this build was made without; `None` for a
/// backend of this build or a name swarmplan does not know.
pub fn backend_not_built(name: &str) -> Option<Violation> {
    if MilpBackend::all().iter().any(|b| b.to_string() == name) {
        return None;
    }
    KNOWN_BACKENDS
        .iter()
        .find(|(known, _)| *known == name)
        .map(|(_, how)| {
            Violation::new(
                "E0012",
                format!("--backend {name}"),
                format!("this build of swarmplan has no {name} backend"),
                *how,
            )
        })
}

/// Relative MIP gap at which a backend may stop and call its incumbent optimal (HiGHS stops at
/// `1e-4` by default; microlp proves optimality outright).
pub const MIP_REL_GAP: f64 = 1e-9;

/// How a backend's solve ended: the one status every backend (microlp, HiGHS, clarabel) maps its
/// own to, in this module. The models' statuses are derived from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum BackendStatus {
    /// Proven optimal.
    Optimal,
    /// Optimal within the relative gap asked for ([`MIP_REL_GAP`]), where the backend stopped
    /// (HiGHS): a proof within that gap.
    OptimalWithinGap,
    /// An incumbent; a limit (time, nodes, iterations) stopped the search before the proof.
    Feasible,
    /// A limit stopped the search before any incumbent (for clarabel: before convergence).
    LimitNoSolution,
    /// Proven infeasible.
    Infeasible,
    /// Unbounded (for clarabel: dual infeasible).
    Unbounded,
}

impl BackendStatus {
    /// Optimality is proven: [`BackendStatus::Optimal`], or [`BackendStatus::OptimalWithinGap`]
    /// (within [`MIP_REL_GAP`]).
    pub fn proven(self) -> bool {
        matches!(
            self,
            BackendStatus::Optimal | BackendStatus::OptimalWithinGap
        )
    }

    /// The solve ended with values: the optimum or an incumbent.
    pub fn has_solution(self) -> bool {
        matches!(
            self,
            BackendStatus::Optimal | BackendStatus::OptimalWithinGap | BackendStatus::Feasible
        )
    }
}

/// How a MILP solve ended, with the values when there are any.
#[derive(Debug)]
pub enum MilpOutcome<S> {
    /// The optimum or an incumbent: `status` is [`BackendStatus::Optimal`],
    /// [`BackendStatus::OptimalWithinGap`] or [`BackendStatus::Feasible`].
    Solved {
        /// How the search ended.
        status: BackendStatus,
        /// The values.
        solution: S,
    },
    /// No values: `status` is [`BackendStatus::Infeasible`], [`BackendStatus::Unbounded`] or
    /// [`BackendStatus::LimitNoSolution`].
    NoSolution {
        /// How the search ended.
        status: BackendStatus,
        /// The backend's report of it, in the words good_lp gives the same end: for messages
        /// only, never read for the status.
        report: good_lp::ResolutionError,
    },
}

impl<S> MilpOutcome<S> {
    /// How the search ended.
    pub fn status(&self) -> BackendStatus {
        match self {
            MilpOutcome::Solved { status, .. } | MilpOutcome::NoSolution { status, .. } => *status,
        }
    }

    /// The values, or the backend's report when there are none: what good_lp's `solve` answers
    /// for the models of [`run_on`].
    ///
    /// # Errors
    /// The report of a solve without values.
    pub fn into_solution(self) -> std::result::Result<S, good_lp::ResolutionError> {
        match self {
            MilpOutcome::Solved { solution, .. } => Ok(solution),
            MilpOutcome::NoSolution { report, .. } => Err(report),
        }
    }
}

/// A model of one of [`run_on`]'s backends (or the capture of [`lp_file`]): built like any good_lp
/// model, solved to a [`MilpOutcome`] read from the backend's status codes.
pub trait MilpModel:
    good_lp::SolverModel<Error = good_lp::ResolutionError> + good_lp::WithTimeLimit
{
    /// Solves the model.
    ///
    /// # Errors
    /// A backend failure (an invalid model, a numerical or internal error), in good_lp's words;
    /// every other end is a [`MilpOutcome`].
    fn solve_outcome(
        self,
    ) -> std::result::Result<MilpOutcome<Self::Solution>, good_lp::ResolutionError>;
}

/// The creation index of a good_lp variable: its position among its problem's variables, which
/// the backends' columns follow.
///
/// good_lp keeps the index private, but a `Variable` is nothing more than it (a `Copy` value
/// compared by index), so the `i`-th variable added to any problem equals the `i`-th added to a
/// fresh one. The index is looked up among such fresh variables, a table each thread grows as
/// far as the largest index asked for.
#[cfg(any(feature = "microlp", feature = "highs"))]
pub(crate) fn variable_index(variable: good_lp::Variable) -> usize {
    use std::cell::RefCell;
    use std::collections::HashMap;
    thread_local! {
        static FRESH: RefCell<(good_lp::ProblemVariables, HashMap<good_lp::Variable, usize>)> =
            RefCell::new((good_lp::ProblemVariables::new(), HashMap::new()));
    }
    FRESH.with(|fresh| {
        let (variables, index) = &mut *fresh.borrow_mut();
        loop {
            if let Some(&i) = index.get(&variable) {
                return i;
            }
            let next = variables.add_variable();
            index.insert(next, index.len());
        }
    })
}

/// A model that can be built and solved on any of [`run_on`]'s backends: what [`run_on`] runs.
pub trait MilpJob {
    /// What a solve gives.
    type Output;

    /// Builds the model with `solver`, named `backend_name` in errors, and solves it
    /// ([`MilpModel::solve_outcome`]).
    ///
    /// # Errors
    /// Bad input found while building, and backend failures.
    fn solve_with<S: good_lp::Solver>(
        self,
        solver: S,
        backend_name: &str,
    ) -> crate::error::Result<Self::Output>
    where
        S::Model: MilpModel;
}

/// Runs `job` on `backend`, with the options every exact method uses: the relative gap
/// [`MIP_REL_GAP`] and no absolute gap, HiGHS on one thread (the same answer on any machine),
/// and at most `node_limit` branch-and-bound nodes (`None`: no limit), a limit that stops the
/// search at the same point on every machine and under any load, unlike the job's wall-clock
/// limit (an infinite one means none).
///
/// # Errors
/// Those of the job; `E0011` in a build without a MILP backend.
pub fn run_on<J: MilpJob>(
    backend: MilpBackend,
    node_limit: Option<u64>,
    job: J,
) -> crate::error::Result<J::Output> {
    let _ = node_limit;
    match backend {
        #[cfg(feature = "microlp")]
        MilpBackend::Microlp => job.solve_with(limited::microlp_limited(node_limit), "microlp"),
        #[cfg(feature = "highs")]
        MilpBackend::Highs => job.solve_with(highs::highs_limited(node_limit), "highs"),
        #[cfg(not(any(feature = "microlp", feature = "highs")))]
        MilpBackend::NoBackend => {
            let _ = job;
            Err(no_milp_backend("--backend"))
        }
    }
}

/// Outcome of a node-time solve (and of a planner's stop), the model-level vocabulary written in
/// outputs; a MILP's is derived from its [`BackendStatus`] by a match.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SolveStatus {
    /// Proven optimal.
    Optimal,
    /// A feasible incumbent; a time or node limit stopped the proof.
    Feasible,
    /// Proven infeasible.
    Infeasible,
}

/// Kind of reference a gap is measured against; never mix them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ReferenceKind {
    /// A proven optimum.
    Optimal,
    /// An incumbent of a solve stopped early.
    Incumbent,
    /// A lower bound (such as a convex relaxation).
    Bound,
    /// The infimum over continuous-time schedules, approached within a certified distance by
    /// the schedule returned but not attained.
    Infimum,
}

/// Gaps within this of 0 (relative) count as 0: in the bench's `gap = 0` counts and histograms,
/// and printed as `0%` in human output.
pub const ZERO_GAP_TOL: f64 = 1e-9;

/// Whether an objective is minimised (node time, delivery time) or maximised (the lowest
/// delivery arrival battery); a [`Gap`] reads a loss as positive under either.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Sense {
    /// Smaller is better.
    Minimise,
    /// Larger is better.
    Maximise,
}

/// Why a value has no gap: its schedule or route lies outside what the reference is exact over,
/// or one of the two has no value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GapLabel {
    /// A swapping PB or FB schedule against a reference of re-ordering `none` (`eaas`).
    DifferentPolicy,
    /// A schedule that lies outside the reference's re-ordering mode (`evaluate`).
    OutsideReference,
    /// The schedule does not fly.
    Infeasible,
    /// The route does not deliver.
    NotDelivered,
    /// The reference gave no value.
    NoReference,
}

/// A relative gap with the kind of its reference: the relative **loss** of a value against the
/// reference, `(value - reference) / |reference|` for a minimised objective and
/// `(reference - value) / |reference|` for a maximised one, so a loss is positive under either
/// sense. Against a proven optimum whose feasible set contains the value's schedule a negative
/// gap is impossible (a bug); against a bound it is never negative. docs/src/exact.md, "What a gap is".
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Gap {
    /// The relative loss; `None` when the reference is zero.
    pub relative: Option<f64>,
    /// What the reference is.
    pub reference: ReferenceKind,
}

impl Gap {
    /// Gap of `value` against `reference` of the given kind, for an objective of `sense`.
    ///
    /// # Example
    /// ```
    /// use swarmplan::solver::{Gap, ReferenceKind, Sense};
    /// // A node time of 11 min against an optimum of 10: 10 % lost.
    /// let g = Gap::new(11.0, 10.0, ReferenceKind::Optimal, Sense::Minimise);
    /// assert!((g.relative.unwrap() - 0.1).abs() < 1e-12);
    /// // An arrival battery of 90 mAh against an optimum of 100: 10 % lost too.
    /// let g = Gap::new(90.0, 100.0, ReferenceKind::Optimal, Sense::Maximise);
    /// assert!((g.relative.unwrap() - 0.1).abs() < 1e-12);
    /// ```
    pub fn new(value: f64, reference: f64, kind: ReferenceKind, sense: Sense) -> Gap {
        let relative = if reference.abs() > 0.0 {
            Some(match sense {
                Sense::Minimise => (value - reference) / reference.abs(),
                Sense::Maximise => (reference - value) / reference.abs(),
            })
        } else {
            None
        };
        Gap {
            relative,
            reference: kind,
        }
    }
}

/// Serde of a wall-clock limit in seconds where `f64::INFINITY` means none: written as `null`
/// (JSON has no infinity), and `null` read back as infinity.
pub mod seconds_or_none {
    use serde::{Deserialize, Deserializer, Serializer};

    /// `null` for infinity, else the number.
    pub fn serialize<S: Serializer>(seconds: &f64, s: S) -> Result<S::Ok, S::Error> {
        if seconds.is_infinite() {
            s.serialize_none()
        } else {
            s.serialize_some(seconds)
        }
    }

    /// Infinity for `null`, else the number.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::INFINITY))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use good_lp::{constraint, variable, variables, Solution, SolverModel, WithTimeLimit};

    #[test]
    fn a_variable_index_is_its_position_in_its_problem() {
        // Asked out of order and beyond what was asked before: the positions of creation.
        let mut first = variables!();
        let a: Vec<good_lp::Variable> = (0..5).map(|_| first.add(variable())).collect();
        let mut second = variables!();
        let b = second.add_vector(variable().min(1), 40);
        assert_eq!(variable_index(a[3]), 3);
        assert_eq!(variable_index(b[39]), 39);
        assert_eq!(variable_index(a[0]), 0);
        let all: Vec<usize> = b.iter().map(|&v| variable_index(v)).collect();
        assert_eq!(all, (0..40).collect::<Vec<_>>());
        // On another thread, with a table of its own.
        let v = b[17];
        assert_eq!(
            std::thread::spawn(move || variable_index(v))
                .join()
                .unwrap(),
            17
        );
    }

    /// A model over two variables, integers or not, for [`run_on`]: the status and, with values,
    /// `(x, y)`.
    struct TwoVariables {
        integer: bool,
        maximise_x_plus_2y: bool,
        rows: fn(good_lp::Variable, good_lp::Variable) -> Vec<good_lp::Constraint>,
    }

    impl MilpJob for TwoVariables {
        type Output = (BackendStatus, Option<(f64, f64)>);

        fn solve_with<S: good_lp::Solver>(
            self,
            solver: S,
            _backend_name: &str,
        ) -> crate::error::Result<Self::Output>
        where
            S::Model: MilpModel,
        {
            let mut vars = variables!();
            let def = || {
                let v = variable().min(0);
                if self.integer {
                    v.integer()
                } else {
                    v
                }
            };
            let x = vars.add(def());
            let y = vars.add(def());
            let goal = if self.maximise_x_plus_2y {
                vars.maximise(x + 2 * y)
            } else {
                vars.minimise(x + y)
            };
            let mut model = goal.using(solver).with_time_limit(f64::INFINITY);
            for row in (self.rows)(x, y) {
                model.add_constraint(row);
            }
            let outcome = model.solve_outcome().unwrap();
            let status = outcome.status();
            Ok(match outcome {
                MilpOutcome::Solved { solution, .. } => {
                    (status, Some((solution.value(x), solution.value(y))))
                }
                MilpOutcome::NoSolution { .. } => (status, None),
            })
        }
    }

    #[test]
    fn the_status_says_how_each_solve_ended() {
        for backend in MilpBackend::all() {
            // max x + 2y over integers with x + y <= 3.5, y <= 1.5: y <= 1, then x <= 2; (2, 1)
            // gives 4, the only other maximal point (3, 0) gives 3.
            let (status, values) = run_on(
                backend,
                None,
                TwoVariables {
                    integer: true,
                    maximise_x_plus_2y: true,
                    rows: |x, y| vec![constraint!(x + y <= 3.5), constraint!(y <= 1.5)],
                },
            )
            .unwrap();
            assert_eq!(status, BackendStatus::Optimal, "{backend}");
            let (x, y) = values.unwrap();
            assert!(
                (x - 2.0).abs() < 1e-9 && (y - 1.0).abs() < 1e-9,
                "{backend}: {x} {y}"
            );
            assert!(status.proven() && status.has_solution());

            // x >= 2 and x <= 1: no point, integer or not.
            let (status, values) = run_on(
                backend,
                None,
                TwoVariables {
                    integer: false,
                    maximise_x_plus_2y: false,
                    rows: |x, _| vec![constraint!(x >= 2), constraint!(x <= 1)],
                },
            )
            .unwrap();
            assert_eq!(status, BackendStatus::Infeasible, "{backend}");
            assert_eq!(values, None);
            assert!(!status.proven() && !status.has_solution());

            // max x + 2y with y <= 1 and nothing above x: x grows without end.
            let (status, values) = run_on(
                backend,
                None,
                TwoVariables {
                    integer: false,
                    maximise_x_plus_2y: true,
                    rows: |_, y| vec![constraint!(y <= 1)],
                },
            )
            .unwrap();
            // HiGHS's presolve may only tell "unbounded or infeasible", which counts as
            // infeasible; microlp's simplex finds the ray.
            assert!(
                matches!(status, BackendStatus::Unbounded | BackendStatus::Infeasible),
                "{backend}: {status:?}"
            );
            #[cfg(feature = "microlp")]
            if backend == MilpBackend::Microlp {
                assert_eq!(status, BackendStatus::Unbounded);
            }
            assert_eq!(values, None);
        }
    }

    /// `2x + 2y = 3` over non-negative integers: the root relaxation is feasible (any point of
    /// the segment, such as (1.5, 0)) but no integer point is (the left side is even).
    fn even_equals_odd() -> TwoVariables {
        TwoVariables {
            integer: true,
            maximise_x_plus_2y: false,
            rows: |x, y| vec![constraint!(2 * x + 2 * y == 3)],
        }
    }

    #[cfg(feature = "microlp")]
    #[test]
    fn microlp_stopped_before_an_incumbent_ends_without_a_solution() {
        // No node beyond the root, whose relaxation is fractional: the search stops with no
        // incumbent, there being no integer point at all.
        let (status, values) = run_on(MilpBackend::Microlp, Some(0), even_equals_odd()).unwrap();
        assert_eq!(status, BackendStatus::LimitNoSolution);
        assert_eq!(values, None);
        assert!(!status.proven() && !status.has_solution());
        // Without the limit the branch and bound proves there is none.
        let (status, _) = run_on(MilpBackend::Microlp, None, even_equals_odd()).unwrap();
        assert_eq!(status, BackendStatus::Infeasible);
    }

    #[cfg(feature = "microlp")]
    #[test]
    fn microlps_ends_keep_good_lps_words_for_messages() {
        use good_lp::ResolutionError;
        let solve = |node_limit, job: TwoVariables| {
            let mut vars = variables!();
            let x = vars.add(variable().integer().min(0));
            let y = vars.add(variable().integer().min(0));
            let mut model = vars
                .minimise(x + y)
                .using(limited::microlp_limited(node_limit));
            for row in (job.rows)(x, y) {
                model.add_constraint(row);
            }
            model.solve_outcome().unwrap()
        };
        match solve(Some(0), even_equals_odd()) {
            MilpOutcome::NoSolution {
                status: BackendStatus::LimitNoSolution,
                report: ResolutionError::Other(words),
            } => assert_eq!(
                words,
                "Time limit reached before finding a feasible solution"
            ),
            other => panic!("{:?}", other.status()),
        }
        match solve(None, even_equals_odd()) {
            MilpOutcome::NoSolution {
                status: BackendStatus::Infeasible,
                report: ResolutionError::Infeasible,
            } => {}
            other => panic!("{:?}", other.status()),
        }
    }

    #[cfg(feature = "highs")]
    #[test]
    fn highs_model_statuses_map_to_one_status_each() {
        use super::highs::status_of;
        use ::highs::HighsModelStatus as M;
        let ok = |m, primal, gap| status_of(m, primal, gap).unwrap();
        assert_eq!(ok(M::Optimal, true, 0.0), BackendStatus::Optimal);
        // A MILP stopped at the relative gap asked for.
        assert_eq!(ok(M::Optimal, true, 1e-10), BackendStatus::OptimalWithinGap);
        // An LP: HiGHS's MIP gap is infinite.
        assert_eq!(ok(M::Optimal, true, f64::INFINITY), BackendStatus::Optimal);
        assert_eq!(ok(M::ReachedTimeLimit, true, 0.5), BackendStatus::Feasible);
        assert_eq!(
            ok(M::ReachedSolutionLimit, true, 0.5),
            BackendStatus::Feasible
        );
        assert_eq!(
            ok(M::ReachedTimeLimit, false, f64::INFINITY),
            BackendStatus::LimitNoSolution
        );
        assert_eq!(ok(M::Infeasible, false, 0.0), BackendStatus::Infeasible);
        assert_eq!(
            ok(M::UnboundedOrInfeasible, false, 0.0),
            BackendStatus::Infeasible
        );
        assert_eq!(ok(M::Unbounded, false, 0.0), BackendStatus::Unbounded);
        for failure in [
            M::NotSet,
            M::LoadError,
            M::ModelError,
            M::SolveError,
            M::ModelEmpty,
        ] {
            assert!(status_of(failure, false, 0.0).is_err(), "{failure:?}");
        }
    }
}
