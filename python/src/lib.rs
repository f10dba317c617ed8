//! `swarmplan._swarmplan`: the Python binding of the swarmplan crate. Every result is the
//! crate's own serde data turned into Python objects (the same fields as the command line's
//! `--json`); every error a `swarmplan.SwarmplanError` carrying the crate's code. Long solves run
//! on a worker thread with the GIL released, and Ctrl-C returns at once (see [`run_detached`]).

use clap::Parser;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pythonize::{depythonize, pythonize};
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use swarmplan::bench::{run_grid, GridRun};
use swarmplan::compose::{Context, HopPaths, PlanOptions, RequestReport};
use swarmplan::eaas::compare::{label_gaps, run_method, HopMethod};
use swarmplan::eaas::exact_hop::ExactChoices;
use swarmplan::eaas::hop_file::{parse_hop_file, HopFile};
use swarmplan::eaas::milp::{MilpOptions, Reorder};
use swarmplan::eaas::PolicyOptions;
use swarmplan::error::{Error, Violation};
use swarmplan::evaluate::{self, WrittenTransfer};
use swarmplan::precompose::Positioning;
use swarmplan::problem::{io, shipped, Instance as Problem, Request, RequestSet};
use swarmplan::solver::MilpBackend;

pyo3::create_exception!(
    swarmplan,
    SwarmplanError,
    PyException,
    "An error of swarmplan: `code` (such as \"E4111\" or a checker code \"C3006\"), `field`, \
     `cause`, `action`, and `violations` (every broken rule as a dict with those four keys)."
);

/// Result of the crate.
type Result<T> = swarmplan::error::Result<T>;

/// One coded violation, for a Python-side input the crate's serde could not read.
fn invalid(code: &'static str, field: &str, cause: String, action: &str) -> Error {
    Error::Invalid(vec![Violation::new(code, field, cause, action)])
}

/// The crate's error as a `SwarmplanError` with its code, field, cause, action and every
/// violation.
fn to_py_err(py: Python<'_>, e: Error) -> PyErr {
    let violations = match &e {
        Error::Invalid(list) => list.clone(),
        Error::Io { path, source } => vec![Violation::new(
            "E0010",
            path.clone(),
            source.to_string(),
            "check that the directory exists and is writable",
        )],
        Error::Output(source) => vec![Violation::new(
            "E0010",
            "output",
            source.to_string(),
            "check the output stream",
        )],
        Error::Backend { backend, message } => {
            let code = if message.starts_with("E0019") {
                "E0019"
            } else {
                "E0027"
            };
            vec![Violation::new(
                code,
                backend.clone(),
                message.clone(),
                "report it with the instance and the call",
            )]
        }
    };
    let err = SwarmplanError::new_err(e.to_string());
    let value = err.value(py);
    let first = violations.first();
    let set = || -> PyResult<()> {
        value.setattr("code", first.map(|v| v.code))?;
        value.setattr("field", first.map(|v| v.field.clone()))?;
        value.setattr("cause", first.map(|v| v.cause.clone()))?;
        value.setattr("action", first.map(|v| v.action.clone()))?;
        value.setattr("violations", pythonize(py, &violations)?)?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(other) => other,
    }
}

/// Runs `job` on a worker thread with the GIL released, polling every 50 ms for Ctrl-C (a
/// `KeyboardInterrupt` returns at once; the worker runs on to its own limits in the background
/// and its result is dropped) and calling `tick` (progress).
fn run_detached<T: Send + 'static>(
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
                    Error::Backend {
                        backend: "swarmplan".into(),
                        message: "E0019: the solve stopped on an internal error (a bug: \
                                  report it with the instance and the call)"
                            .into(),
                    },
                ))
            }
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                py.check_signals()?;
                tick(py)?;
            }
        }
    }
}

/// Serde data as Python objects (dicts, lists, floats; `None` for JSON null).
fn py_of<T: Serialize>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    Ok(pythonize(py, &json(value))?.unbind())
}

/// Serde data as JSON's data model, so that sequences become lists (as `json.loads` of the
/// command line's output gives), never tuples.
fn json<T: Serialize>(value: &T) -> serde_json::Value {
    serde_json::to_value(value).expect("plain data serialises")
}

/// A Python object read as serde data, E0026 naming `field` when it has the wrong shape.
fn read<T: serde::de::DeserializeOwned>(
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

/// A choice by its command-line name (`"pb"`, `"location-aware"`), E0026 with the names.
fn choice<T: clap::ValueEnum>(py: Python<'_>, field: &str, name: &str) -> PyResult<T> {
    T::from_str(name, false).map_err(|_| {
        let names: Vec<String> = T::value_variants()
            .iter()
            .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
            .collect();
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

/// A MILP backend by name; one not in this build says which feature builds it.
fn backend_of(py: Python<'_>, name: &str) -> PyResult<MilpBackend> {
    match swarmplan::solver::backend_not_built(name) {
        Some(cause) => Err(to_py_err(
            py,
            invalid(
                "E0026",
                "backend",
                cause,
                "give microlp, or build the package with the highs feature",
            ),
        )),
        None => choice(py, "backend", name),
    }
}

fn numpy<'py>(py: Python<'py>, list: Bound<'py, PyAny>) -> PyResult<Py<PyAny>> {
    Ok(py
        .import("numpy")?
        .getattr("asarray")?
        .call1((list,))?
        .unbind())
}

/// A network, a profile and a request set, validated together.
struct InstanceData {
    instance: Problem,
    network_name: String,
    profile_name: String,
    requests_name: String,
}

/// A planning instance: a skyway network, a parameter profile and a request set, validated
/// together (the same rules and codes as the command line).
#[pyclass(frozen, module = "swarmplan")]
struct Instance {
    inner: Arc<InstanceData>,
}

/// The exact-sharing settings of `--sharing exact|fair` and of the references, as the command
/// line reads them (E4101, E4105, E4113).
struct ExactKw {
    backend: String,
    hop_time_limit_s: Option<f64>,
    hop_node_limit: u64,
    period_min: f64,
    reorder: String,
}

impl ExactKw {
    fn context(&self, py: Python<'_>, data: &InstanceData, node_limit: u64) -> PyResult<Context> {
        let choices = ExactChoices {
            backend: backend_of(py, &self.backend)?,
            hop_time_limit_s: self.hop_time_limit_s,
            hop_node_limit: self.hop_node_limit,
            period_min: self.period_min,
            reorder: choice(py, "reorder", &self.reorder)?,
        };
        let i = &data.instance;
        let mut context = Context::new(&i.network, &i.graph, &i.profile);
        context.exact = choices.settings().map_err(|e| to_py_err(py, e))?;
        context.node_limit = Some(node_limit);
        Ok(context)
    }
}

impl Instance {
    fn new(instance: Problem, network: String, profile: String, requests: String) -> Instance {
        Instance {
            inner: Arc::new(InstanceData {
                instance,
                network_name: network,
                profile_name: profile,
                requests_name: requests,
            }),
        }
    }

    /// A request by id (E3401) or from a dict `{"source", "destination", "packages_kg"}`
    /// (checked against the network, E3xxx).
    fn resolve_request(&self, py: Python<'_>, request: &Bound<'_, PyAny>) -> PyResult<Request> {
        if let Ok(id) = request.extract::<String>() {
            return self
                .inner
                .instance
                .requests
                .iter()
                .find(|r| r.id == id)
                .cloned()
                .ok_or_else(|| {
                    let hint = if id.starts_with('r') && id.len() < 6 {
                        " (ids of the shipped set are written r00042)"
                    } else {
                        ""
                    };
                    to_py_err(
                        py,
                        invalid(
                            "E3401",
                            "request",
                            format!("no request with id `{id}` in {}{hint}", self.inner.requests_name),
                            "give an id of Instance.request_ids, or a dict with source, destination \
                             and packages_kg",
                        ),
                    )
                });
        }
        #[derive(serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Given {
            #[serde(default)]
            id: Option<String>,
            source: String,
            destination: String,
            packages_kg: Vec<f64>,
        }
        let given: Given = read(
            py,
            request,
            "request",
            "a request id (str) or a dict with source, destination and packages_kg",
        )?;
        let r = Request {
            id: given
                .id
                .unwrap_or_else(|| swarmplan::problem::request::PYTHON_REQUEST_ID.into()),
            source: given.source,
            destination: given.destination,
            packages_kg: given.packages_kg,
        };
        let checked = self
            .inner
            .instance
            .clone()
            .with_requests(vec![r])
            .map_err(|e| to_py_err(py, e))?;
        Ok(checked.requests[0].clone())
    }
}

fn load_profile(
    py: Python<'_>,
    profile: Option<&str>,
    fallback: &str,
    literal: bool,
) -> PyResult<(swarmplan::problem::Profile, String)> {
    let name = profile.unwrap_or(fallback);
    let (mut p, label) = if shipped::PROFILES.iter().any(|(n, _)| *n == name) {
        (
            shipped::profile(name).map_err(|e| to_py_err(py, e))?,
            format!("embedded {name} profile"),
        )
    } else if name.ends_with(".toml") || std::path::Path::new(name).exists() {
        (
            io::read_toml(std::path::Path::new(name)).map_err(|e| to_py_err(py, e))?,
            name.to_string(),
        )
    } else {
        return Err(to_py_err(py, shipped::profile(name).unwrap_err()));
    };
    if literal {
        p.readings = swarmplan::problem::profile::Readings::literal();
    }
    let label = if literal {
        format!("{label} (literal)")
    } else {
        label
    };
    Ok((p, label))
}

#[pymethods]
impl Instance {
    /// A shipped network by name (`paper-195`, `findings-195`, `sparse-195`) with a shipped
    /// profile (`paper`, `paper-findings`, `fast-sharing`, `redundancy-levels`, or a TOML
    /// file; default: the network's own, `paper-findings` for findings-195, else `paper`) and
    /// the shipped 10,000 requests. `literal` reads the paper word for word (`--literal`).
    #[staticmethod]
    #[pyo3(signature = (network = "paper-195", profile = None, literal = false))]
    fn embedded(
        py: Python<'_>,
        network: &str,
        profile: Option<&str>,
        literal: bool,
    ) -> PyResult<Instance> {
        let net = shipped::network(network).map_err(|e| to_py_err(py, e))?;
        let fallback = shipped::default_profile(network).unwrap_or("paper");
        let (p, profile_label) = load_profile(py, profile, fallback, literal)?;
        let set = shipped::requests().map_err(|e| to_py_err(py, e))?;
        let instance = Problem::new(net, p)
            .and_then(|i| i.with_request_set(set))
            .map_err(|e| to_py_err(py, e))?;
        Ok(Instance::new(
            instance,
            format!("embedded {network} network"),
            profile_label,
            shipped::REQUESTS_NAME.into(),
        ))
    }

    /// A network file (JSON), a profile (a shipped name or a TOML file; default `paper`) and
    /// requests: a request file (JSON), a list of request dicts, or `None` for the shipped
    /// requests.
    #[staticmethod]
    #[pyo3(signature = (network, profile = None, requests = None, literal = false))]
    fn from_files(
        py: Python<'_>,
        network: std::path::PathBuf,
        profile: Option<&str>,
        requests: Option<&Bound<'_, PyAny>>,
        literal: bool,
    ) -> PyResult<Instance> {
        let net = io::read_json(&network).map_err(|e| to_py_err(py, e))?;
        let (p, profile_label) = load_profile(py, profile, "paper", literal)?;
        let (set, requests_name) = match requests {
            None => (
                shipped::requests().map_err(|e| to_py_err(py, e))?,
                shipped::REQUESTS_NAME.to_string(),
            ),
            Some(r)
                if r.extract::<std::path::PathBuf>().is_ok() && !r.is_instance_of::<PyList>() =>
            {
                let path: std::path::PathBuf = r.extract()?;
                let set: RequestSet = io::read_json(&path)
                    .and_then(shipped::checked_set)
                    .map_err(|e| to_py_err(py, e))?;
                (set, path.display().to_string())
            }
            Some(r) => {
                let requests: Vec<Request> = read(
                    py,
                    r,
                    "requests",
                    "a list of dicts with id, source, destination and packages_kg",
                )?;
                let set = RequestSet {
                    schema_version: swarmplan::problem::SCHEMA_VERSION,
                    seed: None,
                    requests,
                };
                (
                    shipped::checked_set(set).map_err(|e| to_py_err(py, e))?,
                    "requests given".to_string(),
                )
            }
        };
        let instance = Problem::new(net, p)
            .and_then(|i| i.with_request_set(set))
            .map_err(|e| to_py_err(py, e))?;
        Ok(Instance::new(
            instance,
            network.display().to_string(),
            profile_label,
            requests_name,
        ))
    }

    /// A seeded synthetic network and request set, as `swarmplan generate network` and
    /// `generate requests` write them (the same seed gives the same instance).
    #[staticmethod]
    #[pyo3(signature = (seed, nodes = 195, spacing_m = 500.0, requests = 100, requests_seed = None, max_package_kg = 1.4, profile = None))]
    #[allow(clippy::too_many_arguments)]
    fn generate(
        py: Python<'_>,
        seed: u64,
        nodes: usize,
        spacing_m: f64,
        requests: usize,
        requests_seed: Option<u64>,
        max_package_kg: f64,
        profile: Option<&str>,
    ) -> PyResult<Instance> {
        use swarmplan::generate::{
            generate_network, generate_requests, NetworkParams, RequestParams,
        };
        let net = generate_network(&NetworkParams {
            nodes,
            seed,
            spacing_m,
        })
        .map_err(|e| to_py_err(py, e))?;
        let (p, profile_label) = load_profile(py, profile, "paper", false)?;
        let instance = Problem::new(net, p).map_err(|e| to_py_err(py, e))?;
        let requests_seed = requests_seed.unwrap_or(seed);
        let set = generate_requests(
            &instance.graph,
            &RequestParams {
                count: requests,
                seed: requests_seed,
                max_package_kg,
            },
        )
        .and_then(|set| instance.clone().with_request_set(set))
        .map_err(|e| to_py_err(py, e))?;
        Ok(Instance::new(
            set,
            format!("generated network (nodes {nodes}, seed {seed}, spacing {spacing_m} m)"),
            profile_label,
            format!("generated requests ({requests}, seed {requests_seed})"),
        ))
    }

    /// The network's name (`embedded paper-195 network`, or its file).
    #[getter]
    fn network_name(&self) -> String {
        self.inner.network_name.clone()
    }

    /// The profile's name.
    #[getter]
    fn profile_name(&self) -> String {
        self.inner.profile_name.clone()
    }

    /// The request set's name.
    #[getter]
    fn requests_name(&self) -> String {
        self.inner.requests_name.clone()
    }

    /// Ids of the requests, in the set's order.
    #[getter]
    fn request_ids(&self) -> Vec<String> {
        self.inner
            .instance
            .requests
            .iter()
            .map(|r| r.id.clone())
            .collect()
    }

    /// The network as its JSON reads (nodes with pads, edges with wind).
    #[getter]
    fn network(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        py_of(py, &self.inner.instance.network)
    }

    /// The profile as its TOML reads.
    #[getter]
    fn profile(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        py_of(py, &self.inner.instance.profile)
    }

    /// One request as a dict (`id`, `source`, `destination`, `packages_kg`).
    fn request(&self, py: Python<'_>, id: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let r = Instance::resolve_request(self, py, id)?;
        py_of(py, &r)
    }

    /// Plans one request, as `swarmplan solve --json` does, and returns the same document as a
    /// dict. `request` is an id or a dict with source, destination and packages_kg.
    #[pyo3(signature = (request, sharing = "pb", positioning = "location-aware", route = "sequential", support = None, hop_paths = "rule", node_limit = 20_000_000, gap = false, backend = "microlp".to_string(), hop_time_limit_s = None, hop_node_limit = 20_000, period_min = 1.0, reorder = "paper".to_string()))]
    #[allow(clippy::too_many_arguments)]
    fn plan(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        sharing: &str,
        positioning: &str,
        route: &str,
        support: Option<usize>,
        hop_paths: &str,
        node_limit: u64,
        gap: bool,
        backend: String,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: u64,
        period_min: f64,
        reorder: String,
    ) -> PyResult<Py<PyAny>> {
        let request = Instance::resolve_request(self, py, request)?;
        let options = PlanOptions {
            sharing: choice(py, "sharing", sharing)?,
            positioning: choice(py, "positioning", positioning)?,
            route: choice(py, "route", route)?,
            support,
        };
        let hop_paths: HopPaths = choice(py, "hop_paths", hop_paths)?;
        let exact = ExactKw {
            backend,
            hop_time_limit_s,
            hop_node_limit,
            period_min,
            reorder,
        };
        // Checked here, reported before any work.
        let settings = {
            let mut context = exact.context(py, &self.inner, node_limit)?;
            context.hop_paths = hop_paths;
            context.validate(&options).map_err(|e| to_py_err(py, e))?;
            context.exact
        };
        let data = self.inner.clone();
        let report = run_detached(
            py,
            move || {
                let i = &data.instance;
                let mut context = Context::new(&i.network, &i.graph, &i.profile);
                context.exact = settings;
                context.node_limit = Some(node_limit);
                context.hop_paths = hop_paths;
                plan_with_gap(&context, &request, &options, gap)
            },
            |_| Ok(()),
        )?;
        py_of(py, &report)
    }

    /// Re-verifies a plan (a dict as `plan` returns, or its JSON text) with the independent
    /// checker; returns every violation (dicts with code, field, cause, action), empty when the
    /// plan passes.
    fn check(&self, py: Python<'_>, plan: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let text = match plan.extract::<String>() {
            Ok(t) => t,
            Err(_) => py
                .import("json")?
                .getattr("dumps")?
                .call1((plan,))?
                .extract()?,
        };
        let report = swarmplan::check::plan_file::parse_plan_file(&text, "the plan given")
            .map_err(|e| to_py_err(py, e))?;
        let i = &self.inner.instance;
        let violations =
            swarmplan::check::check_report(&i.network, &i.profile, &i.requests, &report);
        py_of(py, &violations)
    }

    /// Hop `index` of a request's plan (as `swarmplan eaas` takes it: by default the plan of
    /// PB sharing, location-aware positioning and Algorithm 1).
    #[pyo3(signature = (request, index = 0, sharing = "pb", positioning = "location-aware", route = "sequential", support = None))]
    #[allow(clippy::too_many_arguments)]
    fn hop(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        index: usize,
        sharing: &str,
        positioning: &str,
        route: &str,
        support: Option<usize>,
    ) -> PyResult<Hop> {
        let request = Instance::resolve_request(self, py, request)?;
        let options = PlanOptions {
            sharing: choice(py, "sharing", sharing)?,
            positioning: choice(py, "positioning", positioning)?,
            route: choice(py, "route", route)?,
            support,
        };
        let data = &self.inner;
        let i = &data.instance;
        let context = Context::new(&i.network, &i.graph, &i.profile);
        let file = py
            .detach(|| context.hop_file(&request, &options, index, &i.profile.name))
            .map_err(|e| to_py_err(py, e))?;
        Ok(Hop {
            file: Arc::new(file),
            readings: PolicyOptions::from(&i.profile.readings),
        })
    }

    /// Flies a request along `stops` (node ids, source first, destination last) with a
    /// schedule per hop, every hop from full batteries along the shortest path, the exact node
    /// time at every stop, and measures it against the joint optimum of the same swarm
    /// (`reference=True`). `policy` is a callable `policy(hop) -> schedule` called with each
    /// hop in turn (a `Hop`), or a list of schedules, one per hop.
    #[pyo3(signature = (request, stops, policy, positioning = "location-aware", support = None, reference = true, reorder = "paper".to_string(), backend = "microlp".to_string(), hop_time_limit_s = None, hop_node_limit = 20_000, node_limit = 20_000_000))]
    #[allow(clippy::too_many_arguments)]
    fn evaluate_route(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        stops: Vec<String>,
        policy: &Bound<'_, PyAny>,
        positioning: &str,
        support: Option<usize>,
        reference: bool,
        reorder: String,
        backend: String,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: u64,
        node_limit: u64,
    ) -> PyResult<Py<PyAny>> {
        let request = Instance::resolve_request(self, py, request)?;
        let positioning: Positioning = choice(py, "positioning", positioning)?;
        let exact = ExactKw {
            backend,
            hop_time_limit_s,
            hop_node_limit,
            period_min: 1.0,
            reorder,
        };
        let context = exact.context(py, &self.inner, node_limit)?;
        let readings = PolicyOptions::from(&self.inner.instance.profile.readings);
        let callable = policy.is_callable();
        let listed: Option<Vec<Bound<'_, PyAny>>> = if callable {
            None
        } else {
            Some(
                policy
                    .try_iter()
                    .and_then(|it| it.collect::<PyResult<Vec<_>>>())
                    .map_err(|_| {
                        to_py_err(
                            py,
                            invalid(
                                "E0026",
                                "policy",
                                "is neither callable nor a list of schedules".into(),
                                "give a function policy(hop) -> schedule, or one schedule per hop",
                            ),
                        )
                    })?,
            )
        };
        let mut py_error: Option<PyErr> = None;
        let mut schedule = |file: &HopFile| -> Result<Vec<WrittenTransfer>> {
            let field = format!("policy (hop {})", file.hop_index);
            let written = if let Some(list) = &listed {
                list.get(file.hop_index).cloned().ok_or_else(|| {
                    invalid(
                        "E0026",
                        "policy",
                        format!("{} schedule(s) for a route of more hops", list.len()),
                        "give one schedule per hop",
                    )
                })?
            } else {
                let hop = Hop {
                    file: Arc::new(file.clone()),
                    readings,
                };
                match policy.call1((hop,)) {
                    Ok(s) => s,
                    Err(e) => {
                        py_error = Some(e);
                        return Err(invalid(
                            "E0026",
                            &field,
                            "raised".into(),
                            "see the exception",
                        ));
                    }
                }
            };
            schedule_of(&written).map_err(|cause| {
                invalid(
                    "E0026",
                    &field,
                    cause,
                    "give a list of transfers: dicts (or tuples) of support, consumer, start_min, \
                     end_min, and optionally consumer_slot and energy_mah",
                )
            })
        };
        let evaluation = evaluate::evaluate_route(
            &context,
            &request,
            positioning,
            support,
            &stops,
            &mut schedule,
            false,
        );
        if let Some(e) = py_error {
            return Err(e);
        }
        let mut evaluation = evaluation.map_err(|e| to_py_err(py, e))?;
        if reference {
            let data = self.inner.clone();
            let settings = context.exact;
            let node_limit = context.node_limit;
            let request = request.clone();
            let found = run_detached(
                py,
                move || {
                    let i = &data.instance;
                    let mut context = Context::new(&i.network, &i.graph, &i.profile);
                    context.exact = settings;
                    context.node_limit = node_limit;
                    evaluate::route_reference(&context, &request, positioning, support)
                },
                |_| Ok(()),
            )?;
            evaluation.measure_against(found);
        }
        py_of(py, &evaluation)
    }

    fn __repr__(&self) -> String {
        format!(
            "Instance({}, {}, {} request(s) of {})",
            self.inner.network_name,
            self.inner.profile_name,
            self.inner.instance.requests.len(),
            self.inner.requests_name
        )
    }
}

/// Plans a request and, with `gap`, its gap against the optimal route of the same combination
/// (as `solve --gap`).
fn plan_with_gap(
    context: &Context,
    request: &Request,
    options: &PlanOptions,
    gap: bool,
) -> Result<RequestReport> {
    let mut report = context.plan(request, options)?;
    if gap {
        report.route_gap = Some(context.route_gap(request, &report)?);
    }
    Ok(report)
}

/// A schedule written in Python: a list of dicts (`support`, `consumer`, `start_min`,
/// `end_min`, optional `consumer_slot`, `energy_mah`) or tuples `(support, consumer, start_min,
/// end_min[, consumer_slot])`; the cause when it cannot be read.
fn schedule_of(obj: &Bound<'_, PyAny>) -> std::result::Result<Vec<WrittenTransfer>, String> {
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .and_then(|it| it.collect::<PyResult<Vec<_>>>())
        .map_err(|_| "the schedule is not a list".to_string())?;
    if obj.is_instance_of::<PyDict>() || obj.extract::<String>().is_ok() {
        return Err("the schedule is not a list".into());
    }
    let mut out = Vec::with_capacity(items.len());
    for (i, item) in items.iter().enumerate() {
        if item.is_instance_of::<PyDict>() {
            out.push(
                depythonize::<WrittenTransfer>(item)
                    .map_err(|e| format!("transfers[{i}] cannot be read: {e}"))?,
            );
        } else if let Ok((support, consumer, start_min, end_min)) =
            item.extract::<(usize, usize, f64, f64)>()
        {
            out.push(WrittenTransfer {
                support,
                consumer,
                start_min,
                end_min,
                energy_mah: None,
                consumer_slot: None,
            });
        } else if let Ok((support, consumer, start_min, end_min, slot)) =
            item.extract::<(usize, usize, f64, f64, usize)>()
        {
            out.push(WrittenTransfer {
                support,
                consumer,
                start_min,
                end_min,
                energy_mah: None,
                consumer_slot: Some(slot),
            });
        } else {
            return Err(format!(
                "transfers[{i}] is neither a dict nor a tuple (support, consumer, start_min, \
                 end_min[, consumer_slot]) of whole numbers and numbers"
            ));
        }
    }
    Ok(out)
}

/// One hop's in-flight sharing problem: its legs (durations, consumption rates per drone and
/// slot), drones (roles, capacities, departure batteries), formation slots, sharing rate and
/// range, and what it is scored by (the node time on the pads at its end, or the lowest delivery
/// arrival battery into a destination).
#[pyclass(frozen, module = "swarmplan")]
struct Hop {
    file: Arc<HopFile>,
    readings: PolicyOptions,
}

/// Settings of the exact hop models, read as the command line reads them.
fn milp_options(
    py: Python<'_>,
    reorder: &str,
    time_limit_s: Option<f64>,
    node_limit: Option<u64>,
    period_min: f64,
    backend: &str,
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
    if let Err(Error::Invalid(list)) = swarmplan::eaas::milp::validate_period_min(period_min) {
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

#[pymethods]
impl Hop {
    /// Reads a hop file (JSON, as `swarmplan eaas --write-hop` and `Hop.write` write it).
    /// `profile` (a shipped name or a TOML file, default `paper`) gives PB's and FB's readings.
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
    fn to_json(&self) -> String {
        serde_json::to_string_pretty(&*self.file).expect("serialising plain data cannot fail")
    }

    /// Writes the hop file (JSON).
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

    /// The moves of a re-ordering mode (`none` or `paper`): every `(support, consumer,
    /// consumer_slot, partner)` a transfer may use, `partner` the delivery drone holding the
    /// consumer's slot meanwhile (`None` when the consumer stays in its own slot).
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

    /// Solves the hop with one method (`pb`, `fb`, `none` simulate a heuristic; `continuous`,
    /// `milp`, `fluid`, `fair` solve a model), as one row of `swarmplan eaas --json`: status,
    /// feasible, objective, bound, epsilon, grid step, schedule (`transfers`). The same defaults
    /// as `swarmplan eaas`: `paper` re-ordering, 60 s per solve, no node limit.
    #[pyo3(signature = (method = "continuous", reorder = "paper", time_limit_s = Some(60.0), node_limit = None, period_min = 1.0, backend = "microlp"))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        method: &str,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<u64>,
        period_min: f64,
        backend: &str,
    ) -> PyResult<Py<PyAny>> {
        let rows = self.compare(
            py,
            vec![method.to_string()],
            reorder,
            time_limit_s,
            node_limit,
            period_min,
            backend,
            false,
        )?;
        let first = rows.bind(py).get_item(0)?;
        Ok(first.unbind())
    }

    /// Solves the hop with several methods side by side and labels each row's gap against the
    /// best reference, as `swarmplan eaas --json` prints its rows.
    #[pyo3(signature = (methods = vec!["pb".to_string(), "fb".to_string(), "continuous".to_string(), "milp".to_string(), "fluid".to_string(), "fair".to_string()], reorder = "paper", time_limit_s = Some(60.0), node_limit = None, period_min = 1.0, backend = "microlp", label = true))]
    #[allow(clippy::too_many_arguments)]
    fn compare(
        &self,
        py: Python<'_>,
        methods: Vec<String>,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<u64>,
        period_min: f64,
        backend: &str,
        label: bool,
    ) -> PyResult<Py<PyAny>> {
        let methods: Vec<HopMethod> = methods
            .iter()
            .map(|m| choice(py, "method", m))
            .collect::<PyResult<_>>()?;
        let milp = milp_options(py, reorder, time_limit_s, node_limit, period_min, backend)?;
        let file = self.file.clone();
        let readings = self.readings;
        let rows = run_detached(
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
        )?;
        py_of(py, &rows)
    }

    /// Flies a schedule written in Python exactly as written and scores it: the independent
    /// checker judges it (a rule broken raises `SwarmplanError` with the checker's code, such as
    /// C3006 for a consumer out of range), running out of battery is a result (`feasible`
    /// False), and its objective is measured against the continuous-time optimum of the
    /// `reorder` mode (`reference=True`; a schedule outside that mode gets `gap_label`
    /// `outside_reference`). The reference solve is deterministic by default (a node limit, no
    /// wall-clock limit).
    #[pyo3(signature = (schedule, reference = true, reorder = "paper", time_limit_s = None, node_limit = Some(20_000), backend = "microlp"))]
    #[allow(clippy::too_many_arguments)]
    fn evaluate(
        &self,
        py: Python<'_>,
        schedule: &Bound<'_, PyAny>,
        reference: bool,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<u64>,
        backend: &str,
    ) -> PyResult<Py<PyAny>> {
        let written = schedule_of(schedule).map_err(|cause| {
            to_py_err(
                py,
                invalid(
                    "E0026",
                    "schedule",
                    cause,
                    "give a list of transfers: dicts (or tuples) of support, consumer, start_min, \
                     end_min, and optionally consumer_slot and energy_mah",
                ),
            )
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
        py_of(py, &evaluation)
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

/// Runs `swarmplan bench` with the command-line arguments `args` (without `swarmplan bench`),
/// writing its files to `--out`, and returns `{"summary", "config", "tables"}` (tables: lists
/// of records, one list per CSV). `progress(done, total)` is called as plans are made.
#[pyfunction]
#[pyo3(signature = (args, progress = None))]
fn run_bench(
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
            .trim()
            .to_string();
        to_py_err(
            py,
            invalid(
                "E0007",
                "bench arguments",
                cause,
                "see `swarmplan bench --help`",
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

/// The names of the shipped networks and profiles.
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
    m.add_function(wrap_pyfunction!(run_bench, m)?)?;
    m.add_function(wrap_pyfunction!(shipped_names, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
