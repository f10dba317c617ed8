//! The typed results of the package: a plan, a hop method's result, a hop's and a route's
//! evaluation. Each holds the crate's serde document (the JSON the command line prints) and
//! gives its top-level fields as attributes; nested values are plain Python data (dicts,
//! lists), and `to_dict()` is the whole document, as `json.loads` of the command line's output
//! reads it.

use pyo3::prelude::*;
use pyo3::types::PyAny;
use pythonize::pythonize;
use serde::Serialize;
use std::sync::Arc;
use swarmplan::check::plan_file::parse_plan_file;
use swarmplan::compose::RequestReport;

use crate::convert::json;
use crate::errors::to_py_err;
use crate::instance::InstanceData;

/// The field `name` of a document as Python data (`None` when absent).
fn field(py: Python<'_>, value: &serde_json::Value, name: &str) -> PyResult<Py<PyAny>> {
    let v = value.get(name).unwrap_or(&serde_json::Value::Null);
    Ok(pythonize(py, v)?.unbind())
}

/// A value at a dotted path (`plan.dt_min`) as short text for a `repr`.
fn shown(value: &serde_json::Value, path: &str) -> String {
    let v = path
        .split('.')
        .try_fold(value, |v, k| v.get(k))
        .unwrap_or(&serde_json::Value::Null);
    match v {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Null => "None".into(),
        other => other.to_string(),
    }
}

/// A typed result: a `#[pyclass]` over a serde document, one getter per top-level field
/// (each with its docstring), `to_dict()`, `to_json()`, equality and a short `repr` of the
/// fields at `repr` paths. After the fields, `with { name: Type }` adds fields of the Rust
/// side (given to `of`, not attributes in Python, not compared by equality) and `methods { ... }`
/// more Python methods.
macro_rules! result_class {
    (
        $(#[doc = $doc:literal])*
        $rust:ident as $py:literal, repr($($path:literal),*) {
            $( $(#[doc = $fdoc:literal])* $field:ident ),* $(,)?
        }
        $(with { $($(#[doc = $xdoc:literal])* $xname:ident: $xty:ty),* $(,)? })?
        $(methods { $($methods:tt)* })?
    ) => {
        $(#[doc = $doc])*
        #[pyclass(frozen, module = "swarmplan", name = $py)]
        pub(crate) struct $rust {
            value: serde_json::Value,
            $($($(#[doc = $xdoc])* $xname: $xty,)*)?
        }

        impl $rust {
            /// The result of the crate's serde data.
            pub(crate) fn of<T: Serialize>(data: &T $($(, $xname: $xty)*)?) -> $rust {
                $rust { value: json(data) $($(, $xname)*)? }
            }

            /// The document (`Instance.check` reads a `Plan`'s).
            #[allow(dead_code)]
            pub(crate) fn document(&self) -> &serde_json::Value {
                &self.value
            }
        }

        #[pymethods]
        impl $rust {
            $(
                $(#[doc = $fdoc])*
                #[getter]
                fn $field(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
                    field(py, &self.value, stringify!($field))
                }
            )*

            /// The whole result as plain data, the document the command line's ``--json``
            /// prints (``json.dumps`` writes it).
            ///
            /// Returns
            /// -------
            /// dict
            ///     Every field, nested values as dicts and lists.
            fn to_dict(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
                Ok(pythonize(py, &self.value)?.unbind())
            }

            /// The whole result as JSON text.
            ///
            /// Returns
            /// -------
            /// str
            ///     The document, indented.
            fn to_json(&self) -> String {
                serde_json::to_string_pretty(&self.value).expect("plain data serialises")
            }

            fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
                other
                    .cast::<$rust>()
                    .map(|o| o.get().value == self.value)
                    .unwrap_or(false)
            }

            fn __repr__(&self) -> String {
                let fields: Vec<String> = [$($path),*]
                    .iter()
                    .map(|p: &&str| format!("{}={}", p, shown(&self.value, p)))
                    .collect();
                format!("{}({})", $py, fields.join(", "))
            }

            $($($methods)*)?
        }
    };
}

result_class! {
    /// A planned request: the document ``swarmplan solve --json`` prints, which
    /// ``Instance.check`` verifies and ``swarmplan.plot`` draws (on the instance that made it;
    /// Jupyter shows a plan as that figure).
    ///
    /// Attributes are the document's top-level fields; nested values are dicts and lists.
    /// ``to_dict()`` is the whole document.
    Plan as "Plan", repr("request.id", "options.sharing", "options.route", "plan.dt_min") {
        /// Version of the document's schema (int).
        schema_version,
        /// The request planned: ``{"id", "source", "destination", "packages_kg"}``.
        request,
        /// The method combination: ``{"sharing", "positioning", "route", "support"}``.
        options,
        /// The fixed formation (str).
        formation,
        /// What the redundancy table decided (dict).
        support_decision,
        /// Support drones flown (int).
        support_drones,
        /// The swarm: drones, slots, initial positions (dict).
        swarm,
        /// The composed plan: ``hops``, ``dt_min``, ``tt_min``, ``nt_min``, ``outcome``, ...
        plan,
        /// Wall-clock time of the planning, ms (float; not reproducible, unlike the rest).
        execution_ms,
        /// The network and profile the plan was made on (dict).
        made_on,
        /// With ``gap=True``: the plan against the optimal route of the same combination
        /// (``{"reference", "optimal_dt_min", "gap", ...}``), else ``None``.
        route_gap,
        /// The settings the plan was made with (dict).
        settings,
    }
    with {
        /// The instance the plan was made on, shared (its network and profile draw the figure).
        made_by: Arc<InstanceData>,
    }
    methods {
        /// The plan's figure as SVG text, so that Jupyter shows a plan as its figure: the same
        /// as ``swarmplan.plot(plan)``.
        ///
        /// Returns
        /// -------
        /// str
        ///     The SVG document.
        fn _repr_svg_(slf: &Bound<'_, Self>) -> PyResult<String> {
            crate::plot::plot(slf.py(), slf, None, false)
        }
    }
}

impl Plan {
    /// The instance the plan was made on.
    pub(crate) fn made_by(&self) -> &InstanceData {
        &self.made_by
    }
}

/// A plan given to a function: a `Plan`, its `to_dict()` or its JSON text, read as the command
/// line reads a plan file (E6001-E6003 naming `origin`).
pub(crate) fn read_plan(
    py: Python<'_>,
    plan: &Bound<'_, PyAny>,
    origin: &str,
) -> PyResult<RequestReport> {
    let text = if let Ok(typed) = plan.cast::<Plan>() {
        typed.get().document().to_string()
    } else if let Ok(t) = plan.extract::<String>() {
        t
    } else {
        py.import("json")?
            .getattr("dumps")?
            .call1((plan,))?
            .extract()?
    };
    parse_plan_file(&text, origin).map_err(|e| to_py_err(py, e))
}

result_class! {
    /// One method's result on a hop: a row of ``swarmplan eaas --json``.
    ///
    /// Attributes are the row's fields; ``transfers`` is a list of dicts. ``to_dict()`` is the
    /// whole row.
    HopResult as "HopResult", repr("method", "status", "objective", "gap") {
        /// The method (``"pb"``, ``"continuous"``, ...).
        method,
        /// ``"heuristic"``, ``"exact_continuous"`` (configuration LP), ``"exact_grid"``
        /// (MILP), ``"bound"`` (fluid LP) or ``"fair_layout"`` (QP schedule).
        kind,
        /// The solver's status (``"optimal"``, ``"feasible"``, ...), ``None`` for a heuristic.
        status,
        /// Whether the schedule keeps every drone above zero (bool or ``None``).
        feasible,
        /// The objective's value: node time (min) or lowest delivery arrival battery (mAh).
        objective,
        /// Whether ``objective`` is proven (bool).
        objective_proven,
        /// The best bound the model proved (float or ``None``).
        bound,
        /// ``fair`` only: the QP optimum, sum of squared end deficits over every drone, mAh^2.
        qp_squared_deficits_mah2,
        /// ``{"relative", "reference"}`` against the reference, or ``None`` (see ``gap_label``).
        gap,
        /// ``"different_policy"`` when the schedule lies outside the reference's model (no gap
        /// taken), else ``None``.
        gap_label,
        /// Certified distance of the schedule to the reference (float or ``None``).
        epsilon,
        /// Grid step of the time-indexed MILP, min (float or ``None``).
        grid_step_min,
        /// Wall-clock time of the solve, ms.
        solve_ms,
        /// The schedule: dicts with ``support``, ``consumer``, ``consumer_slot``,
        /// ``start_min``, ``end_min`` and ``energy_mah``.
        transfers,
        /// ``continuous`` with ``reorder="free"``: the schedule as slot intervals and its final
        /// batteries, else ``None``.
        free_schedule,
    }
}

result_class! {
    /// A hop schedule flown as written and scored against the exact optimum (``Hop.evaluate``,
    /// ``swarmplan.evaluate``).
    ///
    /// Attributes are the evaluation's fields; ``to_dict()`` is the whole document.
    HopEvaluation as "HopEvaluation", repr("feasible", "value", "mode", "gap", "gap_label") {
        /// Whether no drone ran out of battery (bool).
        feasible,
        /// The first failure (``{"drone", "time_min", "reason"}``), or ``None``.
        failure,
        /// The transfers flown, defaults filled in (list of dicts).
        transfers,
        /// Battery of every drone at the hop's end, mAh (list).
        final_battery_mah,
        /// Lowest battery of every drone during the hop, mAh (list).
        min_battery_mah,
        /// Energy shared in flight, mAh.
        shared_mah,
        /// What the hop is scored by (``{"node_time": {...}}`` or ``"max_min_arrival"``).
        objective,
        /// Node time (min) or lowest delivery arrival battery (mAh) when feasible, else
        /// ``None``.
        value,
        /// False when the node time stopped at its node limit (``value`` is an upper bound).
        value_proven,
        /// The smallest re-ordering mode holding the schedule (``"none"``, ``"paper"``,
        /// ``"free"``).
        mode,
        /// The exact reference (``{"status", "value", "kind", "epsilon", "reorder"}``), or
        /// ``None`` with ``reference=False``.
        reference,
        /// ``{"relative", "reference"}``, or ``None`` with ``gap_label``.
        gap,
        /// Why no gap is given (``"infeasible"``, ``"outside_reference"``,
        /// ``"no_reference"``), or ``None``.
        gap_label,
    }
}

result_class! {
    /// A whole route flown with a schedule per hop and measured against the joint optimum
    /// (``Instance.evaluate_route``).
    ///
    /// Attributes are the evaluation's fields; ``to_dict()`` is the whole document.
    RouteEvaluation as "RouteEvaluation", repr("request_id", "delivered", "dt_min", "gap") {
        /// The request flown (str).
        request_id,
        /// The stops, source first and destination last (list of node ids).
        stops,
        /// The support positioning (str).
        positioning,
        /// Support drones flown (int).
        support_drones,
        /// Whether the swarm reached the destination (bool).
        delivered,
        /// Travel time, min.
        tt_min,
        /// Node time at the stops, min.
        nt_min,
        /// Delivery time, min, when delivered, else ``None``.
        dt_min,
        /// False when a stop's node time stopped at its node limit.
        dt_proven,
        /// Every hop: ``{"hop", "tt_min", "evaluation", "stop"}`` (dicts).
        hops,
        /// The smallest re-ordering mode holding every schedule.
        mode,
        /// The joint optimum (``{"dt_min", "kind", "epsilon_min", "reorder"}``), or ``None``.
        reference,
        /// ``{"relative", "reference"}``, or ``None`` with ``gap_label``.
        gap,
        /// Why no gap is given, or ``None``.
        gap_label,
    }
}
