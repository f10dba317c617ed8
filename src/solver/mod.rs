//! Backend choice and solve outcome, shared by every exact method.
//!
//! Backends are chosen by enum, never by string: `microlp` (pure Rust, default) and, with the
//! `highs` feature, HiGHS. Convex models use clarabel directly. An outcome (optimal, feasible with
//! an incumbent after a limit, infeasible) is data; `Err` is for bad input and broken backends.
//! [`lp_file`] writes a good_lp model in CPLEX LP or free MPS format instead of solving it.

use serde::{Deserialize, Serialize};

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
pub fn no_milp_backend(field: &str) -> crate::Error {
    crate::Error::invalid(
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
pub fn backend_not_built(name: &str) -> Option<String> {
    if MilpBackend::all().iter().any(|b| b.to_string() == name) {
        return None;
    }
    KNOWN_BACKENDS
        .iter()
        .find(|(known, _)| *known == name)
        .map(|(_, how)| {
            format!(
                "[E0012] --backend {name}: this build of swarmplan has no {name} backend; {how}"
            )
        })
}

/// Relative MIP gap at which a backend may stop and call its incumbent optimal (HiGHS stops at
/// `1e-4` by default; microlp proves optimality outright).
pub const MIP_REL_GAP: f64 = 1e-9;

/// A model that can be built and solved on any good_lp MILP solver: what [`run_on`] runs.
pub trait MilpJob {
    /// What a solve gives.
    type Output;

    /// Builds the model and solves it with `solver`, named `backend_name` in errors.
    ///
    /// # Errors
    /// Bad input found while building, and backend failures.
    fn solve_with<S: good_lp::Solver>(
        self,
        solver: S,
        backend_name: &str,
    ) -> crate::error::Result<Self::Output>
    where
        S::Model: good_lp::WithTimeLimit + good_lp::SolverModel<Error = good_lp::ResolutionError>;
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
        MilpBackend::Highs => job.solve_with(
            move |p| {
                let mut model = good_lp::solvers::highs::highs(p)
                    .set_threads(1)
                    .set_option("mip_rel_gap", MIP_REL_GAP)
                    .set_option("mip_abs_gap", 0.0);
                if let Some(n) = node_limit {
                    model = model.set_option("mip_max_nodes", n.min(i32::MAX as u64) as i32);
                }
                model
            },
            "highs",
        ),
        #[cfg(not(any(feature = "microlp", feature = "highs")))]
        MilpBackend::NoBackend => {
            let _ = job;
            Err(no_milp_backend("--backend"))
        }
    }
}

/// Outcome of a solve.
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

/// Relative gap `(heuristic - reference) / reference` with the kind of its reference.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, serde::Deserialize)]
pub struct Gap {
    /// The relative gap; `None` when the reference is zero.
    pub relative: Option<f64>,
    /// What the reference is.
    pub reference: ReferenceKind,
}

impl Gap {
    /// Gap of `heuristic` against `reference` of the given kind.
    pub fn new(heuristic: f64, reference: f64, kind: ReferenceKind) -> Gap {
        let relative = if reference.abs() > 0.0 {
            Some((heuristic - reference) / reference)
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
