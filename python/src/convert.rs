//! Serde data <-> Python objects.

use pyo3::prelude::*;
use pythonize::{depythonize, pythonize};
use serde::Serialize;

use crate::errors::{invalid, to_py_err};

/// Serde data as Python objects (dicts, lists, floats; `None` for JSON null).
pub(crate) fn py_of<T: Serialize>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    Ok(pythonize(py, &json(value))?.unbind())
}

/// Serde data as JSON's data model, so that sequences become lists (as `json.loads` of the
/// command line's output gives), never tuples.
pub(crate) fn json<T: Serialize>(value: &T) -> serde_json::Value {
    serde_json::to_value(value).expect("plain data serialises")
}

/// A Python object read as serde data, E0026 naming `field` when it has the wrong shape.
pub(crate) fn read<T: serde::de::DeserializeOwned>(
    py: Python<'_>,
    obj: &Bound<'_, PyAny>,
    field: &str,
    shape: &str,
) -> PyResult<T> {
    depythonize(obj).map_err(|e| {
        to_py_err(
            py,
            invalid(
                "E0026",
                field,
                format!("cannot be read: {e}"),
                &format!("give {shape}"),
            ),
        )
    })
}

pub(crate) fn numpy<'py>(py: Python<'py>, list: Bound<'py, PyAny>) -> PyResult<Py<PyAny>> {
    Ok(py
        .import("numpy")?
        .getattr("asarray")?
        .call1((list,))?
        .unbind())
}
