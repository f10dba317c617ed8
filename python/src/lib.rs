//! `swarmplan._swarmplan`: the Python binding of the swarmplan crate. Every result is the
//! crate's own serde data turned into Python objects (the same fields as the command line's
//! `--json`); every error a `swarmplan.SwarmplanError` carrying the crate's code, its field and
//! texts in the package's names (see [`errors::in_python_words`]). Long solves run on a worker thread
//! with the GIL released, and Ctrl-C returns at once (see [`worker::run_detached`]).
//!
//! One module per concern: [`errors`] (the exception and the core's messages in the package's
//! words), [`args`] (arguments read as the core's values), [`convert`] (serde data <-> Python),
//! [`worker`] (solves off the GIL), [`results`] (the typed results), [`instance`], [`hop`],
//! [`plot`] and [`bench`] (the classes and functions of the package).

mod args;
mod bench;
mod convert;
mod errors;
mod hop;
mod instance;
mod plot;
mod results;
mod worker;

use pyo3::prelude::*;
use pyo3::types::PyDict;
use swarmplan::problem::shipped;

use bench::run_bench;
use errors::SwarmplanError;
use hop::Hop;
use instance::Instance;
use results::{HopEvaluation, HopResult, Plan, RouteEvaluation};

/// The names of the shipped networks and profiles.
///
/// Returns
/// -------
/// dict
///     `{"networks": [...], "profiles": [...]}`.
#[pyfunction]
fn shipped_names(py: Python<'_>) -> PyResult<Py<PyAny>> {
    let d = PyDict::new(py);
    d.set_item("networks", shipped::NETWORKS.map(|x| x.0).to_vec())?;
    d.set_item("profiles", shipped::PROFILES.map(|x| x.0).to_vec())?;
    Ok(d.into_any().unbind())
}

/// The native part of the `swarmplan` package.
#[pymodule]
fn _swarmplan(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("SwarmplanError", m.py().get_type::<SwarmplanError>())?;
    m.add_class::<Instance>()?;
    m.add_class::<Hop>()?;
    m.add_class::<Plan>()?;
    m.add_class::<HopResult>()?;
    m.add_class::<HopEvaluation>()?;
    m.add_class::<RouteEvaluation>()?;
    m.add_function(wrap_pyfunction!(run_bench, m)?)?;
    m.add_function(wrap_pyfunction!(plot::plot, m)?)?;
    m.add_function(wrap_pyfunction!(shipped_names, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // The crate's defaults, which the keywords left as `None` take.
    m.add(
        "DEFAULT_NODE_LIMIT",
        swarmplan::node_time::DEFAULT_STOP_NODE_LIMIT,
    )?;
    m.add(
        "DEFAULT_HOP_NODE_LIMIT",
        swarmplan::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT,
    )?;
    m.add(
        "DEFAULT_BACKEND",
        swarmplan::solver::MilpBackend::default().to_string(),
    )?;
    m.add("DEFAULT_EXACT_LIMIT", swarmplan::bench::DEFAULT_EXACT_LIMIT)?;
    m.add(
        "DEFAULT_DISTANCE_BUCKET_KM",
        swarmplan::bench::DEFAULT_DISTANCE_BUCKET_KM,
    )?;
    m.add("DEFAULT_NODES", swarmplan::generate::DEFAULT_NODES)?;
    m.add("DEFAULT_SPACING_M", swarmplan::generate::DEFAULT_SPACING_M)?;
    m.add(
        "DEFAULT_MAX_PACKAGE_KG",
        swarmplan::generate::DEFAULT_MAX_PACKAGE_KG,
    )?;
    Ok(())
}
