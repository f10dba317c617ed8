//! Long solves on a worker thread, the GIL released, Ctrl-C answered at once.

use pyo3::prelude::*;
use std::time::Duration;
use swarmplan::error::Error;

use crate::errors::{to_py_err, Result, SwarmplanError};

/// Runs `job` on a worker thread with the GIL released, polling every 50 ms for Ctrl-C (a
/// `KeyboardInterrupt` returns at once; the worker runs on to its own limits in the background
/// and its result is dropped) and calling `tick` (progress).
pub(crate) fn run_detached<T: Send + 'static>(
    py: Python<'_>,
    job: impl FnOnce() -> Result<T> + Send + 'static,
    mut tick: impl FnMut(Python<'_>) -> PyResult<()>,
) -> PyResult<T> {
    let (tx, rx) = std::sync::mpsc::channel();
    // A receiver is not `Sync`; the mutex lets the GIL-free wait borrow it.
    let rx = std::sync::Mutex::new(rx);
    std::thread::Builder::new()
        .name("swarmplan".into())
        .spawn(move || {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(job));
            let _ = tx.send(r);
        })
        .map_err(|e| SwarmplanError::new_err(format!("cannot start a worker thread: {e}")))?;
    loop {
        let got = py.detach(|| {
            rx.lock()
                .expect("one waiter")
                .recv_timeout(Duration::from_millis(50))
        });
        match got {
            Ok(Ok(r)) => {
                tick(py)?;
                return r.map_err(|e| to_py_err(py, e));
            }
            Ok(Err(_)) | Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                return Err(to_py_err(
                    py,
                    Error::internal("E0032", "the solve's worker thread stopped (a panic)"),
                ))
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                py.check_signals()?;
                tick(py)?;
            }
        }
    }
}
