//! `swarmplan.bench`'s native part: a bench run of the core ([`run_grid`] with its
//! [`BenchSettings`] built from the keywords), its progress and its tables. The core alone
//! draws no figures (they are the command line's, feature `cli`): a run from Python writes the
//! tables, `config.json` and `summary.json`.

use pyo3::prelude::*;
use pyo3::types::PyDict;
use pythonize::pythonize;
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use swarmplan::bench::{run_grid, BenchSettings, GridRun, Shard};

use crate::args::{backend_of, choice, Whole, NODE_LIMIT_WHAT};
use crate::convert::json;
use crate::errors::{in_python_text, to_py_err};
use crate::worker::run_detached;

/// Choices by name, each read with [`choice`] (E0026 naming `field`).
fn choices<T: serde::de::DeserializeOwned>(
    py: Python<'_>,
    field: &str,
    names: Option<Vec<String>>,
) -> PyResult<Option<Vec<T>>> {
    names
        .map(|names| names.iter().map(|n| choice(py, field, n)).collect())
        .transpose()
}

/// A count of a bench setting ([`Whole::index`]).
fn count(py: Python<'_>, n: Option<Whole>, name: &str, what: &str) -> PyResult<Option<usize>> {
    n.map(|n| n.index(py, name, what)).transpose()
}

/// A bench run of the core into `out`, the native part of `swarmplan.bench` (which documents
/// every keyword); no SVG figures (they are the command line's).
///
/// Parameters
/// ----------
/// out : str or os.PathLike
///     Output directory.
/// **settings
///     The run's settings by keyword; `None` takes the command line's default.
/// progress : callable or None, default None
///     `progress(done, total)`, called as plans are made.
/// command : list of str or None, default None
///     The call recorded in `summary.json`.
///
/// Returns
/// -------
/// dict
///     `{"summary", "config", "tables", "elapsed_s"}`, `tables` the rows of each CSV as dicts.
///
/// Raises
/// ------
/// SwarmplanError
///     E0026 for an unknown choice or a negative count; the run's codes (E7005, E7006, ...).
#[pyfunction]
#[pyo3(signature = (
    out, *, limit = None, sharing = None, positioning = None, route = None, gap = true,
    joint = true, exact_limit = None, backend = None, hop_time_limit_s = None,
    hop_node_limit = None, period_min = 1.0, reorder = "paper", node_limit = None,
    distance_bucket_km = None, shard = None, threads = None, time_budget_s = None,
    network = None, profile = None, literal = false, requests = None, force = false,
    progress = None, command = None
))]
#[allow(clippy::too_many_arguments)]
pub(crate) fn run_bench(
    py: Python<'_>,
    out: PathBuf,
    limit: Option<Whole>,
    sharing: Option<Vec<String>>,
    positioning: Option<Vec<String>>,
    route: Option<Vec<String>>,
    gap: bool,
    joint: bool,
    exact_limit: Option<Whole>,
    backend: Option<&str>,
    hop_time_limit_s: Option<f64>,
    hop_node_limit: Option<Whole>,
    period_min: f64,
    reorder: &str,
    node_limit: Option<Whole>,
    distance_bucket_km: Option<f64>,
    shard: Option<&str>,
    threads: Option<Whole>,
    time_budget_s: Option<f64>,
    network: Option<PathBuf>,
    profile: Option<PathBuf>,
    literal: bool,
    requests: Option<PathBuf>,
    force: bool,
    progress: Option<Py<PyAny>>,
    command: Option<Vec<String>>,
) -> PyResult<Py<PyAny>> {
    let mut settings = BenchSettings::new(out);
    settings.instance.network = network;
    settings.instance.profile = profile;
    settings.instance.literal = literal;
    settings.requests = requests;
    settings.limit = count(py, limit, "limit", "a number of requests")?;
    if let Some(v) = choices(py, "sharing", sharing)? {
        settings.sharing = v;
    }
    if let Some(v) = choices(py, "positioning", positioning)? {
        settings.positioning = v;
    }
    if let Some(v) = choices(py, "route", route)? {
        settings.route = v;
    }
    settings.gap = gap;
    settings.joint = joint;
    if let Some(n) = count(py, exact_limit, "exact_limit", "a number of requests")? {
        settings.exact_limit = n;
    }
    settings.exact.backend = backend_of(py, backend)?;
    settings.exact.hop_time_limit_s = hop_time_limit_s;
    if let Some(n) = hop_node_limit {
        settings.exact.hop_node_limit = n.get(py, "hop_node_limit", NODE_LIMIT_WHAT)?;
    }
    settings.exact.period_min = period_min;
    settings.exact.reorder = choice(py, "reorder", reorder)?;
    if let Some(n) = node_limit {
        settings.node_limit = n.get(py, "node_limit", NODE_LIMIT_WHAT)?;
    }
    if let Some(km) = distance_bucket_km {
        settings.distance_bucket_km = km;
    }
    if let Some(text) = shard {
        settings.shard = Shard::parse(text).map_err(|e| to_py_err(py, e))?;
    }
    settings.threads = count(py, threads, "threads", "a number of worker threads")?;
    settings.time_budget_s = time_budget_s;
    settings.force = force;
    settings.command = command.unwrap_or_else(|| vec!["swarmplan.bench".into()]);
    let total = Arc::new(AtomicU64::new(0));
    let done = Arc::new(AtomicU64::new(0));
    let (t, d) = (total.clone(), done.clone());
    let mut last = u64::MAX;
    let run: GridRun = run_detached(
        py,
        move || {
            run_grid(
                &settings,
                &|size| t.store(size.plans(), Ordering::Relaxed),
                &|n| {
                    d.fetch_add(n, Ordering::Relaxed);
                },
            )
        },
        |py| {
            let now = done.load(Ordering::Relaxed);
            match &progress {
                Some(cb) if now != last => {
                    last = now;
                    cb.call1(py, (now, total.load(Ordering::Relaxed)))?;
                    Ok(())
                }
                _ => Ok(()),
            }
        },
    )?;
    if let Some(stop) = run.budget {
        eprintln!("{}", in_python_text(&stop.to_string()));
    }
    let out = PyDict::new(py);
    out.set_item("summary", pythonize(py, &json(&run.summary))?)?;
    out.set_item("config", pythonize(py, &json(&run.config))?)?;
    let tables = PyDict::new(py);
    tables.set_item("requests", pythonize(py, &json(&run.data.requests))?)?;
    tables.set_item("hops", pythonize(py, &json(&run.data.hops))?)?;
    tables.set_item("stops", pythonize(py, &json(&run.data.stops))?)?;
    tables.set_item("timings", pythonize(py, &json(&run.data.timings))?)?;
    tables.set_item("joint", pythonize(py, &json(&run.data.joint))?)?;
    out.set_item("tables", tables)?;
    out.set_item("elapsed_s", run.elapsed_s)?;
    Ok(out.into_any().unbind())
}
