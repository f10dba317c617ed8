//! `swarmplan.bench`'s native part: a bench run of the core, its progress and its tables.

use clap::Parser;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use pythonize::pythonize;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use swarmplan::bench::{run_grid, GridRun};

use crate::convert::json;
use crate::errors::{invalid, python_name, to_py_err};
use crate::worker::run_detached;

/// Runs `swarmplan bench` with the command-line arguments `args` (without `swarmplan bench`),
/// writing its files to `--out`, and returns `{"summary", "config", "tables"}` (tables: lists
/// of records, one list per CSV). `progress(done, total)` is called as plans are made.
#[pyfunction]
#[pyo3(signature = (args, progress = None))]
pub(crate) fn run_bench(
    py: Python<'_>,
    args: Vec<String>,
    progress: Option<Py<PyAny>>,
) -> PyResult<Py<PyAny>> {
    let argv: Vec<String> = ["swarmplan", "bench"]
        .iter()
        .map(|s| s.to_string())
        .chain(args)
        .collect();
    let cli = swarmplan::cli::Cli::try_parse_from(&argv).map_err(|e| {
        let text = e.render().to_string();
        let cause = text
            .strip_prefix("error: ")
            .unwrap_or(&text)
            .split("\n\nFor more information")
            .next()
            .unwrap_or("")
            .trim()
            .to_string();
        // The keyword concerned, when the parser names one (`--threads <N>` is `threads`).
        let field = match e.get(clap::error::ContextKind::InvalidArg) {
            Some(clap::error::ContextValue::String(arg)) if arg.starts_with("--") => {
                python_name(arg[2..].split([' ', '=']).next().unwrap_or(""))
            }
            _ => "bench arguments".to_string(),
        };
        to_py_err(
            py,
            invalid(
                "E0007",
                &field,
                cause,
                "see `swarmplan bench --help` (each keyword of swarmplan.bench is its option)",
            ),
        )
    })?;
    let swarmplan::cli::Command::Bench(bench) = cli.command else {
        unreachable!("parsed as bench")
    };
    if bench.command.is_some() {
        return Err(to_py_err(
            py,
            invalid(
                "E0007",
                "bench arguments",
                "merge is not a run".into(),
                "merge shards with `swarmplan bench merge`",
            ),
        ));
    }
    let settings = bench.run.settings(argv);
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
        eprintln!("{stop}");
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
