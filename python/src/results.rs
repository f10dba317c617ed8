//! The typed results of the package: a plan, a hop method's result, a hop's and a route's
//! evaluation. Each holds the crate's serde document (the JSON the command line prints) and
//! gives its top-level fields as attributes; nested values are plain Python data (dicts,
//! lists), and `to_dict()` is the whole document, as `json.loads` of the command line's output
//! reads it.

use pyo3::prelude::*;
use pyo3::types::PyAny;
use pythonize::pythonize;
use serde::Serialize;

use crate::convert::json;

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
/// fields at `repr` paths.
macro_rules! result_class {
    (
        $(#[doc = $doc:literal])*
        $rust:ident as $py:literal, repr($($path:literal),*) {
            $( $(#[doc = $fdoc:literal])* $field:ident ),* $(,)?
        }
    ) => {
        $(#[doc = $doc])*
        #[pyclass(frozen, module = "swarmplan", name = $py)]
        pub(crate) struct $rust {
            value: serde_json::Value,
        }

        impl $rust {
            /// The result of the crate's serde data.
            pub(crate) fn of<T: Serialize>(data: &T) -> $rust {
                $rust { value: json(data) }
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
        }
    };
}

result_class! {
    /// A planned request: the document ``swarmplan solve --json`` prints, which
    /// ``Instance.check`` verifies.
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
