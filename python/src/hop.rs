//! `swarmplan.Hop`: one hop's in-flight sharing problem, its arrays, moves, exact solves and
//! the scoring of a schedule written in Python.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::pythonize;
use std::sync::Arc;
use swarmplan::eaas::compare::{label_gaps, run_method, HopMethod, MethodRow};
use swarmplan::eaas::exact::milp::MilpOptions;
use swarmplan::eaas::exact::Reorder;
use swarmplan::eaas::hop_file::{parse_hop_file, HopFile};
use swarmplan::eaas::PolicyOptions;
use swarmplan::error::{Error, Violation};
use swarmplan::evaluate;

use crate::args::{backend_of, choice, node_limit_arg, schedule_of, Whole, TRANSFERS_ACTION};
use crate::convert::{numpy, py_of};
use crate::errors::{invalid, to_py_err};
use crate::instance::load_profile;
use crate::results::{HopEvaluation, HopResult};
use crate::worker::run_detached;

/// One hop's in-flight sharing problem and what it is scored by.
///
/// Its legs (durations, consumption rates per drone and slot), drones (roles, capacities,
/// departure batteries), formation slots, sharing rate and range, and its objective: the node
/// time on the pads at its end, or the lowest delivery arrival battery into a destination. Take
/// one from a plan (`Instance.hop`) or a hop file (`Hop.from_file`, `Hop.from_json`); solve it
/// (`solve`, `compare`) or score a schedule of one's own (`evaluate`).
///
/// Attributes
/// ----------
/// request_id : str
///     The request whose plan holds the hop.
/// index : int
///     Index of the hop in that plan.
/// path : list of str
///     Node ids flown over.
/// drones : int
///     Number of drones (delivery drones first).
/// roles : list of str
///     `"delivery"` or `"support"` per drone.
/// capacity_mah, battery_mah, durations_min, rates_mah_per_min, slots_m : numpy.ndarray
///     Capacities and departure batteries per drone (mAh), leg durations (min), consumption
///     rates `[leg, drone, slot]` (mAh/min), slot positions `[slot, 2]` (m).
/// initial_slot : list of int
///     Slot of every drone outside transfers.
/// rho_mah_per_min, range_m, delta_mah, tt_min : float
///     Sharing rate, largest transfer distance, support reserve, travel time.
/// end, objective, problem
///     The pads at the end (or `None`), what the hop is scored by, the whole problem.
#[pyclass(frozen, module = "swarmplan")]
pub(crate) struct Hop {
    pub(crate) file: Arc<HopFile>,
    pub(crate) readings: PolicyOptions,
}

/// Settings of the exact hop models, read as the command line reads them.
pub(crate) fn milp_options(
    py: Python<'_>,
    reorder: &str,
    time_limit_s: Option<f64>,
    node_limit: Option<u64>,
    period_min: f64,
    backend: Option<&str>,
) -> PyResult<MilpOptions> {
    let backend = backend_of(py, backend)?;
    let mut v = Vec::new();
    if let Some(t) = time_limit_s.filter(|t| !(*t > 0.0 && *t <= 1e6)) {
        v.push(Violation::new(
            "E4105",
            "time_limit_s",
            format!("{t} is not a time in (0, 1e6] seconds"),
            "give the time limit in seconds, or None for none",
        ));
    }
    if let Err(Error::Invalid(list)) = swarmplan::eaas::exact::milp::validate_period_min(period_min)
    {
        v.extend(list);
    }
    if !v.is_empty() {
        return Err(to_py_err(py, Error::Invalid(v)));
    }
    Ok(MilpOptions {
        period_min,
        reorder: choice(py, "reorder", reorder)?,
        backend,
        time_limit_s: time_limit_s.unwrap_or(f64::INFINITY),
        node_limit,
    })
}

impl Hop {
    /// The rows of `methods` on the hop, their gaps labelled against the best reference
    /// among them when `label`.
    fn rows(
        &self,
        py: Python<'_>,
        methods: Vec<HopMethod>,
        milp: MilpOptions,
        label: bool,
    ) -> PyResult<Vec<MethodRow>> {
        let file = self.file.clone();
        let readings = self.readings;
        run_detached(
            py,
            move || {
                let objective = file.objective();
                let mut rows = Vec::new();
                for m in methods {
                    rows.push(run_method(&file.hop, &objective, m, &milp, &readings)?);
                }
                if label {
                    label_gaps(&mut rows, &file.hop, &objective, milp.reorder);
                }
                Ok(rows)
            },
            |_| Ok(()),
        )
    }
}

#[pymethods]
impl Hop {
    /// Reads a hop file (JSON, as `swarmplan eaas --write-hop` and `Hop.write` write it).
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     The hop file.
    /// profile : str or None, default None
    ///     A shipped profile name or a TOML file whose readings PB and FB follow; `None`: `paper`.
    ///
    /// Returns
    /// -------
    /// Hop
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E4112 for another schema version; the hop file's input codes.
    #[staticmethod]
    #[pyo3(signature = (path, profile = None))]
    fn from_file(py: Python<'_>, path: std::path::PathBuf, profile: Option<&str>) -> PyResult<Hop> {
        let file = swarmplan::eaas::hop_file::read_hop_file(&path).map_err(|e| to_py_err(py, e))?;
        let (p, _) = load_profile(py, profile, "paper", false)?;
        Ok(Hop {
            file: Arc::new(file),
            readings: PolicyOptions::from(&p.readings),
        })
    }

    /// A hop from the JSON text of a hop file.
    ///
    /// Parameters
    /// ----------
    /// text : str
    ///     The hop file's JSON text.
    /// profile : str or None, default None
    ///     A shipped profile name or a TOML file whose readings PB and FB follow; `None`: `paper`.
    ///
    /// Returns
    /// -------
    /// Hop
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E4112 for another schema version; the hop file's input codes.
    #[staticmethod]
    #[pyo3(signature = (text, profile = None))]
    fn from_json(py: Python<'_>, text: &str, profile: Option<&str>) -> PyResult<Hop> {
        let file = parse_hop_file(text, "the hop given").map_err(|e| to_py_err(py, e))?;
        let (p, _) = load_profile(py, profile, "paper", false)?;
        Ok(Hop {
            file: Arc::new(file),
            readings: PolicyOptions::from(&p.readings),
        })
    }

    /// The hop file's JSON text.
    ///
    /// Returns
    /// -------
    /// str
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&*self.file).expect("serialising plain data cannot fail")
    }

    /// Writes the hop file (JSON).
    ///
    /// Parameters
    /// ----------
    /// path : str or os.PathLike
    ///     Where to write it.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0010 when the file cannot be written.
    fn write(&self, py: Python<'_>, path: std::path::PathBuf) -> PyResult<()> {
        swarmplan::eaas::hop_file::write_hop_file(&path, &self.file).map_err(|e| to_py_err(py, e))
    }

    /// Id of the request whose plan holds the hop.
    #[getter]
    fn request_id(&self) -> String {
        self.file.request_id.clone()
    }

    /// Index of the hop in that plan (0 = the first).
    #[getter]
    fn index(&self) -> usize {
        self.file.hop_index
    }

    /// Node ids flown over, the start first and the end last.
    #[getter]
    fn path(&self) -> Vec<String> {
        self.file.path.clone()
    }

    /// The pads at the hop's end (`{"pads", "pad_rate_mah_per_min"}`), or `None` into a
    /// destination.
    #[getter]
    fn end(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        py_of(py, &self.file.end)
    }

    /// What the hop is scored by: `{"node_time": {"pads", "pad_rate_mah_per_min"}}` (minimise,
    /// min) or `"max_min_arrival"` (maximise the lowest delivery arrival battery, mAh).
    #[getter]
    fn objective(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        py_of(py, &self.file.objective())
    }

    /// The whole problem as the hop file's `hop` object.
    #[getter]
    fn problem(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        py_of(py, &self.file.hop)
    }

    /// Number of drones (delivery drones first, then support drones).
    #[getter]
    fn drones(&self) -> usize {
        self.file.hop.drones.len()
    }

    /// Role of every drone: `"delivery"` or `"support"`.
    #[getter]
    fn roles(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let roles: Vec<_> = self.file.hop.drones.iter().map(|d| d.role).collect();
        py_of(py, &roles)
    }

    /// Battery capacity of every drone, mAh (numpy array).
    #[getter]
    fn capacity_mah(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v: Vec<f64> = self
            .file
            .hop
            .drones
            .iter()
            .map(|d| d.capacity_mah)
            .collect();
        numpy(py, PyList::new(py, v)?.into_any())
    }

    /// Battery of every drone at departure, mAh (numpy array).
    #[getter]
    fn battery_mah(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v: Vec<f64> = self.file.hop.drones.iter().map(|d| d.battery_mah).collect();
        numpy(py, PyList::new(py, v)?.into_any())
    }

    /// Duration of every leg, min (numpy array).
    #[getter]
    fn durations_min(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v: Vec<f64> = self.file.hop.legs.iter().map(|l| l.duration_min).collect();
        numpy(py, PyList::new(py, v)?.into_any())
    }

    /// Consumption rates, mAh/min, as a numpy array `[leg, drone, slot]`.
    #[getter]
    fn rates_mah_per_min(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v: Vec<Vec<Vec<f64>>> = self
            .file
            .hop
            .legs
            .iter()
            .map(|l| (*l.rate_mah_per_min).clone())
            .collect();
        numpy(py, pythonize(py, &v)?)
    }

    /// Formation slot positions in the body frame, m, as a numpy array `[slot, 2]`.
    #[getter]
    fn slots_m(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        let v: Vec<[f64; 2]> = self.file.hop.slots_m.iter().map(|p| [p.x, p.y]).collect();
        numpy(py, pythonize(py, &v)?)
    }

    /// Slot of every drone outside transfers.
    #[getter]
    fn initial_slot(&self) -> Vec<usize> {
        self.file.hop.initial_slot.clone()
    }

    /// Sharing rate `rho`, mAh/min.
    #[getter]
    fn rho_mah_per_min(&self) -> f64 {
        self.file.hop.rho_mah_per_min
    }

    /// Largest support-consumer distance of a transfer, m.
    #[getter]
    fn range_m(&self) -> f64 {
        self.file.hop.range_m
    }

    /// Support reserve `delta`, mAh: a sharing support drone stays at or above it.
    #[getter]
    fn delta_mah(&self) -> f64 {
        self.file.hop.delta_mah
    }

    /// Travel time `tt`, min (the sum of the legs).
    #[getter]
    fn tt_min(&self) -> f64 {
        swarmplan::eaas::travel_time_min(&self.file.hop)
    }

    /// The moves a transfer may use in a re-ordering mode.
    ///
    /// Parameters
    /// ----------
    /// reorder : str, default "paper"
    ///     `none` (only consumers in range in their own slots) or `paper` (also swaps).
    ///
    /// Returns
    /// -------
    /// list of dict
    ///     Keys `support`, `consumer`, `consumer_slot` and `partner`, `partner` the delivery drone
    ///     holding the consumer's slot meanwhile (`None` when the consumer stays in its own slot). A
    ///     transfer written as a sequence takes another order: `(support, consumer, start_min,
    ///     end_min[, consumer_slot])`.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0026 for `free` (no fixed list of moves) or an unknown mode.
    #[pyo3(signature = (reorder = "paper"))]
    fn moves(&self, py: Python<'_>, reorder: &str) -> PyResult<Py<PyAny>> {
        let mode: Reorder = choice(py, "reorder", reorder)?;
        if mode == Reorder::Free {
            return Err(to_py_err(
                py,
                invalid(
                    "E0026",
                    "reorder",
                    "free re-ordering has no fixed list of moves".into(),
                    "give none or paper",
                ),
            ));
        }
        let list = py.import("builtins")?.getattr("list")?;
        let out = PyList::empty(py);
        for m in swarmplan::eaas::exact::moves(&self.file.hop, mode) {
            let d = PyDict::new(py);
            d.set_item("support", m.support)?;
            d.set_item("consumer", m.consumer)?;
            d.set_item("consumer_slot", m.slot)?;
            d.set_item("partner", m.partner)?;
            out.append(d)?;
        }
        Ok(list.call1((out,))?.unbind())
    }

    /// Solves the hop with one method, as one row of `swarmplan eaas --json`.
    ///
    /// `pb`, `fb`, `none` simulate a heuristic; `continuous`, `milp`, `fluid`, `fair` solve a
    /// model. The same defaults as `swarmplan eaas`: `paper` re-ordering, 60 s per solve, no node
    /// limit.
    ///
    /// Parameters
    /// ----------
    /// method : str, default "continuous"
    ///     `none`, `pb`, `fb`, `continuous`, `milp`, `fluid` or `fair`.
    /// reorder : str, default "paper"
    ///     `paper`, `none` or `free` (the continuous model only).
    /// time_limit_s : float or None, default 60.0
    ///     Wall-clock limit of each solve, s; `None`: none.
    /// node_limit : int or None, default None
    ///     Branch-and-bound nodes of each MILP call; `None`: none.
    /// period_min : float, default 1.0
    ///     Longest period of the grid MILP, min.
    /// backend : str or None, default None
    ///     MILP backend; `None`: `DEFAULT_BACKEND` (`microlp`).
    /// reference : bool, default True
    ///     Measure the row of `none`, `pb`, `fb`, `milp` or `fair` against the continuous model of
    ///     the same `reorder` mode, solved alongside with the same limits (as `swarmplan eaas
    ///     --methods M,continuous`).
    ///
    /// Returns
    /// -------
    /// HopResult
    ///     Status, feasibility, objective, bound, epsilon, grid step and schedule (`transfers`).
    ///     `gap` is `{"relative", "reference"}`, or `None` for `continuous` (the reference itself),
    ///     `fluid` (a bound), `reference=False`, or when the continuous model gives no value within
    ///     its limits; a heuristic schedule that swaps slots under `reorder="none"` gets
    ///     `gap_label` `different_policy`.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0026 for an unknown method or mode; E4105 (time limit), E4101 (period); E0012 for a
    ///     backend this build lacks.
    #[pyo3(signature = (method = "continuous", reorder = "paper", time_limit_s = Some(60.0), node_limit = None, period_min = 1.0, backend = None, reference = true))]
    #[pyo3(
        text_signature = "(self, /, method='continuous', reorder='paper', time_limit_s=60.0, node_limit=None, period_min=1.0, backend=None, reference=True)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        method: &str,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<Whole>,
        period_min: f64,
        backend: Option<&str>,
        reference: bool,
    ) -> PyResult<HopResult> {
        let method: HopMethod = choice(py, "method", method)?;
        let node_limit = node_limit_arg(py, node_limit)?;
        let milp = milp_options(py, reorder, time_limit_s, node_limit, period_min, backend)?;
        let measured = reference && !matches!(method, HopMethod::Continuous | HopMethod::Fluid);
        let methods = if measured {
            vec![method, HopMethod::Continuous]
        } else {
            vec![method]
        };
        let rows = self.rows(py, methods, milp, measured)?;
        Ok(HopResult::of(&rows[0]))
    }

    /// Solves the hop with several methods side by side, as `swarmplan eaas --json` prints its rows.
    ///
    /// Parameters
    /// ----------
    /// methods : list of str, default ["pb", "fb", "continuous", "milp", "fluid", "fair"]
    ///     The methods, each as `solve` takes it.
    /// reorder : str, default "paper"
    ///     `paper`, `none` or `free`.
    /// time_limit_s : float or None, default 60.0
    ///     Wall-clock limit of each solve, s; `None`: none.
    /// node_limit : int or None, default None
    ///     Branch-and-bound nodes of each MILP call; `None`: none.
    /// period_min : float, default 1.0
    ///     Longest period of the grid MILP, min.
    /// backend : str or None, default None
    ///     MILP backend; `None`: `DEFAULT_BACKEND` (`microlp`).
    /// label : bool, default True
    ///     Label each row's gap against the best reference among the rows.
    ///
    /// Returns
    /// -------
    /// list of HopResult
    ///     One per method, in order.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     As `solve`.
    #[pyo3(signature = (methods = vec!["pb".to_string(), "fb".to_string(), "continuous".to_string(), "milp".to_string(), "fluid".to_string(), "fair".to_string()], reorder = "paper", time_limit_s = Some(60.0), node_limit = None, period_min = 1.0, backend = None, label = true))]
    #[pyo3(
        text_signature = "(self, /, methods=('pb', 'fb', 'continuous', 'milp', 'fluid', 'fair'), reorder='paper', time_limit_s=60.0, node_limit=None, period_min=1.0, backend=None, label=True)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn compare(
        &self,
        py: Python<'_>,
        methods: Vec<String>,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<Whole>,
        period_min: f64,
        backend: Option<&str>,
        label: bool,
    ) -> PyResult<Vec<HopResult>> {
        let methods: Vec<HopMethod> = methods
            .iter()
            .map(|m| choice(py, "method", m))
            .collect::<PyResult<_>>()?;
        let node_limit = node_limit_arg(py, node_limit)?;
        let milp = milp_options(py, reorder, time_limit_s, node_limit, period_min, backend)?;
        let rows = self.rows(py, methods, milp, label)?;
        Ok(rows.iter().map(HopResult::of).collect())
    }

    /// Flies a schedule written in Python exactly as written and scores it.
    ///
    /// The independent checker judges the schedule; running out of battery is a result (`feasible`
    /// False); its objective is measured against the continuous-time optimum of the `reorder` mode.
    /// The reference solve is deterministic by default (a node limit, no wall-clock limit).
    ///
    /// Parameters
    /// ----------
    /// schedule : sequence of transfers
    ///     Each a dict (`support`, `consumer`, `start_min`, `end_min`, optionally `consumer_slot`
    ///     and `energy_mah`) or a sequence of numbers `(support, consumer, start_min, end_min[,
    ///     consumer_slot])` (a tuple, a list, a numpy row).
    /// reference : bool, default True
    ///     Measure against the continuous-time optimum.
    /// reorder : str, default "paper"
    ///     The reference's re-ordering mode (`paper`, `none`, `free`); a schedule outside it gets
    ///     `gap_label` `outside_reference`.
    /// time_limit_s : float or None, default None
    ///     Wall-clock limit of the reference solve, s; `None`: none.
    /// node_limit : int or None, default DEFAULT_HOP_NODE_LIMIT (20,000)
    ///     Branch-and-bound nodes of each MILP call of the reference; `None`: no limit.
    /// backend : str or None, default None
    ///     MILP backend; `None`: `DEFAULT_BACKEND` (`microlp`).
    ///
    /// Returns
    /// -------
    /// HopEvaluation
    ///     `gap` is `{"relative", "reference"}` (reference `optimal` or `infimum`), or `None` with
    ///     `gap_label`.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     The checker's code for a schedule that breaks a rule of the hop model (C3001-C3013, such
    ///     as C3006 for a consumer out of range); E0026 for a schedule of the wrong shape.
    #[pyo3(signature = (schedule, reference = true, reorder = "paper", time_limit_s = None, node_limit = Some(Whole::of(swarmplan::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT)), backend = None))]
    // The default node limit is the crate's constant, not a literal: the signature `help()`
    // shows states its value (tests/test_defaults.py checks it against the constant).
    #[pyo3(
        text_signature = "(self, /, schedule, reference=True, reorder='paper', time_limit_s=None, node_limit=20000, backend=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn evaluate(
        &self,
        py: Python<'_>,
        schedule: &Bound<'_, PyAny>,
        reference: bool,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<Whole>,
        backend: Option<&str>,
    ) -> PyResult<HopEvaluation> {
        let node_limit = node_limit_arg(py, node_limit)?;
        let written = schedule_of(schedule).map_err(|cause| {
            to_py_err(py, invalid("E0026", "schedule", cause, TRANSFERS_ACTION))
        })?;
        let milp = milp_options(py, reorder, time_limit_s, node_limit, 1.0, backend)?;
        let file = self.file.clone();
        let evaluation = run_detached(
            py,
            move || {
                evaluate::evaluate_hop(
                    &file.hop,
                    &file.objective(),
                    &written,
                    reference.then_some(&milp),
                )
            },
            |_| Ok(()),
        )?;
        Ok(HopEvaluation::of(&evaluation))
    }

    fn __repr__(&self) -> String {
        format!(
            "Hop(request {}, hop {}: {}, {} leg(s), {} drones, tt {:.3} min)",
            self.file.request_id,
            self.file.hop_index,
            self.file.path.join(" -> "),
            self.file.hop.legs.len(),
            self.file.hop.drones.len(),
            swarmplan::eaas::travel_time_min(&self.file.hop)
        )
    }
}
