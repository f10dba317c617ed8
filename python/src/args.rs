//! The Python arguments read as the core's values: whole numbers (indices, counts, limits,
//! seeds), choices by name, MILP backends, and schedules of transfers.

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyString};
use serde::de::DeserializeOwned;
use swarmplan::evaluate::WrittenTransfer;
use swarmplan::solver::MilpBackend;

use crate::errors::{invalid, to_py_err};

/// A whole-number argument (an index, a count, a limit, a seed) as given, read by
/// [`Whole::get`] with its Python name. PyO3's own conversion would raise a bare
/// `OverflowError` for a negative number and take `True` as 1; here both are E0026 naming the
/// argument. Any integer type is taken (`int`, numpy's); another type is a `TypeError`.
#[derive(Debug, Clone)]
pub(crate) struct Whole(std::result::Result<u64, String>);

impl Whole {
    /// The default of a signature.
    pub(crate) const fn of(n: u64) -> Whole {
        Whole(Ok(n))
    }

    /// The number, or E0026 naming `name` with what it should be (`what`, such as "a hop
    /// index from 0").
    pub(crate) fn get(self, py: Python<'_>, name: &str, what: &str) -> PyResult<u64> {
        self.0
            .map_err(|cause| to_py_err(py, invalid("E0026", name, cause, &format!("give {what}"))))
    }

    /// [`Whole::get`] as an index or a count.
    pub(crate) fn index(self, py: Python<'_>, name: &str, what: &str) -> PyResult<usize> {
        let n = self.get(py, name, what)?;
        usize::try_from(n).map_err(|_| {
            to_py_err(
                py,
                invalid(
                    "E0026",
                    name,
                    format!("{n} is too large"),
                    &format!("give {what}"),
                ),
            )
        })
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for Whole {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Whole> {
        Ok(Whole(whole_of(&obj)?))
    }
}

/// A Python integer as a whole number: `Ok(Err(cause))` for a bool, a negative number or one
/// above `u64`; `Err` (a `TypeError`) for a value that is no integer.
pub(crate) fn whole_of(obj: &Bound<'_, PyAny>) -> PyResult<std::result::Result<u64, String>> {
    let type_name = obj.get_type().name()?.to_string();
    if obj.is_instance_of::<PyBool>() || matches!(type_name.as_str(), "bool" | "bool_") {
        return Ok(Err(format!(
            "{} is a bool, not a whole number",
            obj.repr()?
        )));
    }
    let int = obj.py().import("operator")?.call_method1("index", (obj,))?;
    if int.lt(0)? {
        return Ok(Err(format!("{int} is negative")));
    }
    Ok(int
        .extract::<u64>()
        .map_err(|_| format!("{int} is above 2**64 - 1")))
}

/// The names of a choice (`"pb"`, `"location-aware"`), as its serde form reads them: those
/// that serde's error for a name that is none lists (`expected one of `a`, `b`` or `expected
/// `a` or `b``), so the list follows the enum.
pub(crate) fn value_names<T: DeserializeOwned>() -> Vec<String> {
    match serde_json::from_value::<T>(serde_json::Value::String(String::new())) {
        Ok(_) => Vec::new(),
        Err(e) => {
            let text = e.to_string();
            let expected = text.split_once("expected").map_or("", |(_, rest)| rest);
            expected
                .split('`')
                .skip(1)
                .step_by(2)
                .map(String::from)
                .collect()
        }
    }
}

/// A choice by its name (`"pb"`, `"location-aware"`, the command line's names), read through
/// serde; E0026 naming `field` and listing the names.
pub(crate) fn choice<T: DeserializeOwned>(py: Python<'_>, field: &str, name: &str) -> PyResult<T> {
    serde_json::from_value(serde_json::Value::String(name.to_string())).map_err(|_| {
        let names = value_names::<T>();
        to_py_err(
            py,
            invalid(
                "E0026",
                field,
                format!("`{name}` is not a choice"),
                &format!("give one of {}", names.join(", ")),
            ),
        )
    })
}

/// A MILP backend by name (`None`: the default, [`MilpBackend::default`], `microlp` in the
/// default build); one swarmplan knows but this package was built without is E0012, saying how
/// to build the package with it.
pub(crate) fn backend_of(py: Python<'_>, name: Option<&str>) -> PyResult<MilpBackend> {
    let Some(name) = name else {
        return Ok(MilpBackend::default());
    };
    match swarmplan::solver::backend_not_built(name) {
        Some(_) => Err(to_py_err(
            py,
            invalid(
                "E0012",
                "backend",
                format!(
                    "this build of the swarmplan package has no {name} backend (it was built \
                     without the feature {name})"
                ),
                &format!(
                    "give backend=\"microlp\", or install the package from a clone of swarmplan \
                     with the feature: `MATURIN_PEP517_ARGS=\"--features {name}\" pip install .` \
                     (building HiGHS needs cmake and libclang: apt-get install cmake libclang-dev)"
                ),
            ),
        )),
        None => choice(py, "backend", name),
    }
}

/// The search-node limit's description in its errors.
pub(crate) const NODE_LIMIT_WHAT: &str = "a number of search nodes (a whole number >= 0)";

/// A node limit, checked ([`Whole`]); `None` is `default`.
pub(crate) fn limit_or(
    py: Python<'_>,
    n: Option<Whole>,
    name: &str,
    default: u64,
) -> PyResult<u64> {
    n.map_or(Ok(default), |n| n.get(py, name, NODE_LIMIT_WHAT))
}

/// An optional node limit, checked ([`Whole`]).
pub(crate) fn node_limit_arg(py: Python<'_>, node_limit: Option<Whole>) -> PyResult<Option<u64>> {
    node_limit
        .map(|n| n.get(py, "node_limit", NODE_LIMIT_WHAT))
        .transpose()
}

/// An optional number of support drones, checked ([`Whole`]).
pub(crate) fn support_arg(py: Python<'_>, support: Option<Whole>) -> PyResult<Option<usize>> {
    support
        .map(|n| {
            n.index(
                py,
                "support",
                "a number of support drones from 0 to 32, or None",
            )
        })
        .transpose()
}

/// A schedule written in Python: a sequence of transfers, each a dict (`support`, `consumer`,
/// `start_min`, `end_min`, optional `consumer_slot` and `energy_mah`) or a sequence of numbers
/// in the order `(support, consumer, start_min, end_min[, consumer_slot])` (a tuple, a list, a
/// numpy row); the cause, naming `schedule[i]`, when it cannot be read.
pub(crate) fn schedule_of(
    obj: &Bound<'_, PyAny>,
) -> std::result::Result<Vec<WrittenTransfer>, String> {
    if obj.is_instance_of::<PyDict>() || is_text(obj) {
        return Err("the schedule is not a sequence of transfers".into());
    }
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .and_then(|it| it.collect::<PyResult<Vec<_>>>())
        .map_err(|_| "the schedule is not a sequence of transfers".to_string())?;
    items
        .iter()
        .enumerate()
        .map(|(i, item)| transfer_of(item).map_err(|cause| format!("schedule[{i}]: {cause}")))
        .collect()
}

/// Whether `obj` is text (a `str` or `bytes`), which iterates but is no sequence of numbers.
pub(crate) fn is_text(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>()
}

/// What to give for a schedule.
pub(crate) const TRANSFERS_ACTION: &str =
    "give a list of transfers, each a dict of support, consumer, \
     start_min, end_min (and optionally consumer_slot, energy_mah) or a sequence of numbers \
     (support, consumer, start_min, end_min[, consumer_slot])";

/// The names of a transfer's numbers, in the order of a transfer written as a sequence.
pub(crate) const TRANSFER_ORDER: [&str; 5] = [
    "support",
    "consumer",
    "start_min",
    "end_min",
    "consumer_slot",
];

/// One transfer: a dict, or a sequence of 4 or 5 numbers in [`TRANSFER_ORDER`].
pub(crate) fn transfer_of(item: &Bound<'_, PyAny>) -> std::result::Result<WrittenTransfer, String> {
    let shape = "a dict, or a sequence (support, consumer, start_min, end_min[, consumer_slot])";
    if let Ok(dict) = item.cast::<PyDict>() {
        let mut got: [Option<Bound<'_, PyAny>>; 6] = Default::default();
        for (key, value) in dict.iter() {
            let key: String = key
                .extract()
                .map_err(|_| format!("the key {key} is not a str"))?;
            let at = TRANSFER_ORDER
                .iter()
                .chain(&["energy_mah"])
                .position(|k| *k == key)
                .ok_or_else(|| {
                    format!(
                        "unknown key `{key}`; the keys are support, consumer, start_min, \
                         end_min, consumer_slot and energy_mah"
                    )
                })?;
            got[at] = Some(value).filter(|v| !v.is_none());
        }
        let need = |k: usize| {
            got[k]
                .as_ref()
                .ok_or_else(|| format!("no `{}`", TRANSFER_ORDER[k]))
        };
        return Ok(WrittenTransfer {
            support: index_in_transfer(need(0)?, "support")?,
            consumer: index_in_transfer(need(1)?, "consumer")?,
            start_min: number_in_transfer(need(2)?, "start_min")?,
            end_min: number_in_transfer(need(3)?, "end_min")?,
            consumer_slot: got[4]
                .as_ref()
                .map(|v| index_in_transfer(v, "consumer_slot"))
                .transpose()?,
            energy_mah: got[5]
                .as_ref()
                .map(|v| number_in_transfer(v, "energy_mah"))
                .transpose()?,
        });
    }
    if is_text(item) {
        return Err(format!("is text, not {shape}"));
    }
    let numbers: Vec<Bound<'_, PyAny>> = item
        .try_iter()
        .and_then(|it| it.collect::<PyResult<Vec<_>>>())
        .map_err(|_| format!("is neither {shape}"))?;
    if !(4..=5).contains(&numbers.len()) {
        return Err(format!(
            "has {} numbers, not 4 or 5: (support, consumer, start_min, end_min[, consumer_slot])",
            numbers.len()
        ));
    }
    Ok(WrittenTransfer {
        support: index_in_transfer(&numbers[0], "support")?,
        consumer: index_in_transfer(&numbers[1], "consumer")?,
        start_min: number_in_transfer(&numbers[2], "start_min")?,
        end_min: number_in_transfer(&numbers[3], "end_min")?,
        consumer_slot: numbers
            .get(4)
            .map(|v| index_in_transfer(v, "consumer_slot"))
            .transpose()?,
        energy_mah: None,
    })
}

/// A drone or slot index of a transfer: a whole number >= 0 (an integer, or a float with no
/// fraction, as a row of a numpy float array holds it), never a bool.
pub(crate) fn index_in_transfer(
    v: &Bound<'_, PyAny>,
    name: &str,
) -> std::result::Result<usize, String> {
    let whole = match whole_of(v) {
        Ok(w) => w,
        Err(_) => match v.extract::<f64>() {
            Ok(x) if x.fract() == 0.0 && x >= 0.0 && x < 2f64.powi(53) => Ok(x as u64),
            Ok(x) => Err(format!("{x} is not a whole number >= 0")),
            Err(_) => Err(format!("{} is not a number", repr_of(v))),
        },
    };
    whole
        .and_then(|n| usize::try_from(n).map_err(|_| format!("{n} is too large")))
        .map_err(|cause| format!("{name}: {cause}"))
}

/// A time or an energy of a transfer: a number (NaN and infinities pass, for the checker to
/// refuse with its code), never a bool.
pub(crate) fn number_in_transfer(
    v: &Bound<'_, PyAny>,
    name: &str,
) -> std::result::Result<f64, String> {
    if v.is_instance_of::<PyBool>() {
        return Err(format!("{name}: {} is a bool, not a number", repr_of(v)));
    }
    v.extract::<f64>()
        .map_err(|_| format!("{name}: {} is not a number", repr_of(v)))
}

pub(crate) fn repr_of(v: &Bound<'_, PyAny>) -> String {
    v.repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "the value".into())
}
