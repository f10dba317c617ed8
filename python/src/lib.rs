//! `swarmplan._swarmplan`: the Python binding of the swarmplan crate. Every result is the
//! crate's own serde data turned into Python objects (the same fields as the command line's
//! `--json`); every error a `swarmplan.SwarmplanError` carrying the crate's code, its field and
//! texts in the package's names (see [`in_python_words`]). Long solves run on a worker thread
//! with the GIL released, and Ctrl-C returns at once (see [`run_detached`]).

use clap::Parser;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyBytes, PyDict, PyList, PyString};
use pythonize::{depythonize, pythonize};
use serde::Serialize;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use swarmplan::bench::{run_grid, GridRun};
use swarmplan::compose::{Context, HopPaths, PlanOptions, RequestReport, RouteMethod};
use swarmplan::eaas::compare::{label_gaps, run_method, HopMethod};
use swarmplan::eaas::exact_hop::ExactChoices;
use swarmplan::eaas::hop_file::{parse_hop_file, HopFile};
use swarmplan::eaas::milp::{MilpOptions, Reorder};
use swarmplan::eaas::{PolicyOptions, SharingPolicy};
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
        Error::Backend { backend, message } => vec![Violation::new(
            "E0027",
            backend.clone(),
            message.clone(),
            "report it with the instance and the call",
        )],
        Error::Internal { code, context } => vec![Violation::new(
            code,
            "internal",
            context.clone(),
            "a bug: report it with the instance and the call",
        )],
    };
    let violations: Vec<Violation> = violations.into_iter().map(in_python_words).collect();
    let message = match &e {
        Error::Invalid(_) => Error::Invalid(violations.clone()).to_string(),
        other => in_python_text(&other.to_string()),
    };
    let err = SwarmplanError::new_err(message);
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

/// The Python name of a command-line option of the core's messages: the keyword of the same
/// meaning (`--hop-time-limit` is `hop_time_limit_s`, `--hop` the hop's `index`, `--count` the
/// number of `requests` of `Instance.generate`, `--request-limit` the `limit` of `bench`), else
/// the option with underscores (`--hop-paths` is `hop_paths`).
fn python_name(flag: &str) -> String {
    match flag {
        "hop-time-limit" => "hop_time_limit_s".into(),
        "time-limit" => "time_limit_s".into(),
        "hop" => "index".into(),
        "count" => "requests".into(),
        "request-limit" => "limit".into(),
        other => other.replace('-', "_"),
    }
}

/// The names a choice takes (`"pb"`, `"optimal"`), for the options whose value a message
/// quotes.
fn choice_names(flag: &str) -> Vec<String> {
    match flag {
        "route" => value_names::<RouteMethod>(),
        "sharing" => value_names::<SharingPolicy>(),
        "positioning" => value_names::<Positioning>(),
        "hop-paths" => value_names::<HopPaths>(),
        "reorder" => value_names::<Reorder>(),
        "backend" => swarmplan::solver::known_backend_names()
            .map(String::from)
            .collect(),
        _ => Vec::new(),
    }
}

/// A message of the core in the package's words: every command-line option outside backticks
/// becomes its keyword, with its value when one follows (`--route optimal` is
/// `route="optimal"`, `--support 32` is `support=32`); commands in backticks stay as written.
fn in_python_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut quoted = false;
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if c == '`' {
            quoted = !quoted;
        }
        let after = &rest[c.len_utf8()..];
        let flag_len = after
            .strip_prefix('-')
            .map(|f| {
                f.bytes()
                    .take_while(|b| b.is_ascii_lowercase() || *b == b'-')
                    .count()
            })
            .unwrap_or(0);
        let starts_word = !out.ends_with(|p: char| p.is_alphanumeric() || p == '-');
        if quoted || c != '-' || flag_len == 0 || !starts_word {
            out.push(c);
            rest = after;
            continue;
        }
        let flag = after[1..1 + flag_len].trim_end_matches('-');
        rest = &after[1 + flag.len()..];
        let name = python_name(flag);
        let word_len = rest
            .strip_prefix(' ')
            .map(|w| {
                w.bytes()
                    .take_while(|b| b.is_ascii_alphanumeric() || *b == b'-' || *b == b'.')
                    .count()
            })
            .unwrap_or(0);
        let word = if word_len > 0 {
            &rest[1..1 + word_len]
        } else {
            ""
        };
        let word = word.trim_end_matches('.');
        if !word.is_empty() && choice_names(flag).iter().any(|n| n == word) {
            out.push_str(&format!("{name}=\"{word}\""));
            rest = &rest[1 + word.len()..];
        } else if !word.is_empty() && word.parse::<f64>().is_ok() {
            out.push_str(&format!("{name}={word}"));
            rest = &rest[1 + word.len()..];
        } else {
            out.push_str(&name);
        }
    }
    out
}

/// A violation of the core in the package's words: its field the keyword concerned
/// (`--route optimal` is `route`), its cause and action without command-line options
/// ([`in_python_text`]), and the actions that only a command line can follow replaced.
fn in_python_words(v: Violation) -> Violation {
    let field = match (v.code, v.field.as_str()) {
        ("E4110", "hop") => "index".to_string(),
        (_, f) if f.starts_with("--") => {
            let flag = f[2..].split(' ').next().unwrap_or("");
            python_name(flag)
        }
        (_, f) => in_python_text(f),
    };
    let action = match v.code {
        "E4113" => "give reorder=\"paper\" or \"none\": a free schedule is not always a set of \
                    transfers a plan can carry (Hop.solve(reorder=\"free\") studies one hop)"
            .to_string(),
        "E4117" => "give reorder=\"paper\" or \"none\" (fewer moves); the largest number of \
                    configurations is the command line's (swarmplan eaas --max-configurations)"
            .to_string(),
        "E0011" => "install the package built with its default features (a MILP backend), or \
                    use a method without a MILP (sharing=\"pb\" or \"fb\"; Hop.solve with \
                    \"pb\", \"fb\", \"fluid\" or \"fair\")"
            .to_string(),
        _ => in_python_text(&v.action),
    };
    Violation {
        code: v.code,
        field,
        cause: in_python_text(&v.cause),
        action,
    }
}

/// A whole-number argument (an index, a count, a limit, a seed) as given, read by
/// [`Whole::get`] with its Python name. PyO3's own conversion would raise a bare
/// `OverflowError` for a negative number and take `True` as 1; here both are E0026 naming the
/// argument. Any integer type is taken (`int`, numpy's); another type is a `TypeError`.
#[derive(Debug, Clone)]
struct Whole(std::result::Result<u64, String>);

impl Whole {
    /// The default of a signature.
    const fn of(n: u64) -> Whole {
        Whole(Ok(n))
    }

    /// The number, or E0026 naming `name` with what it should be (`what`, such as "a hop
    /// index from 0").
    fn get(self, py: Python<'_>, name: &str, what: &str) -> PyResult<u64> {
        self.0
            .map_err(|cause| to_py_err(py, invalid("E0026", name, cause, &format!("give {what}"))))
    }

    /// [`Whole::get`] as an index or a count.
    fn index(self, py: Python<'_>, name: &str, what: &str) -> PyResult<usize> {
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
fn whole_of(obj: &Bound<'_, PyAny>) -> PyResult<std::result::Result<u64, String>> {
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

/// The names of a choice (`"pb"`, `"location-aware"`).
fn value_names<T: clap::ValueEnum>() -> Vec<String> {
    T::value_variants()
        .iter()
        .filter_map(|v| v.to_possible_value().map(|p| p.get_name().to_string()))
        .collect()
}

/// A choice by its command-line name (`"pb"`, `"location-aware"`), E0026 with the names.
fn choice<T: clap::ValueEnum>(py: Python<'_>, field: &str, name: &str) -> PyResult<T> {
    T::from_str(name, false).map_err(|_| {
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

/// A MILP backend by name; one swarmplan knows but this package was built without is E0012,
/// saying how to build the package with it.
fn backend_of(py: Python<'_>, name: &str) -> PyResult<MilpBackend> {
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
    #[pyo3(signature = (seed, nodes = Whole::of(195), spacing_m = 500.0, requests = Whole::of(100), requests_seed = None, max_package_kg = 1.4, profile = None))]
    #[allow(clippy::too_many_arguments)]
    fn generate(
        py: Python<'_>,
        seed: Whole,
        nodes: Whole,
        spacing_m: f64,
        requests: Whole,
        requests_seed: Option<Whole>,
        max_package_kg: f64,
        profile: Option<&str>,
    ) -> PyResult<Instance> {
        let seed = seed.get(py, "seed", "a seed from 0 to 2**64 - 1")?;
        let nodes = nodes.index(py, "nodes", "a node count")?;
        let requests = requests.index(py, "requests", "a request count")?;
        let requests_seed = requests_seed
            .map(|s| s.get(py, "requests_seed", "a seed from 0 to 2**64 - 1"))
            .transpose()?;
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
    #[pyo3(signature = (request, sharing = "pb", positioning = "location-aware", route = "sequential", support = None, hop_paths = "rule", node_limit = Whole::of(20_000_000), gap = false, backend = "microlp".to_string(), hop_time_limit_s = None, hop_node_limit = Whole::of(20_000), period_min = 1.0, reorder = "paper".to_string()))]
    #[allow(clippy::too_many_arguments)]
    fn plan(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        sharing: &str,
        positioning: &str,
        route: &str,
        support: Option<Whole>,
        hop_paths: &str,
        node_limit: Whole,
        gap: bool,
        backend: String,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: Whole,
        period_min: f64,
        reorder: String,
    ) -> PyResult<Py<PyAny>> {
        let support = support_arg(py, support)?;
        let node_limit = node_limit.get(py, "node_limit", NODE_LIMIT_WHAT)?;
        let hop_node_limit = hop_node_limit.get(py, "hop_node_limit", NODE_LIMIT_WHAT)?;
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
    #[pyo3(signature = (request, index = Whole::of(0), sharing = "pb", positioning = "location-aware", route = "sequential", support = None))]
    #[allow(clippy::too_many_arguments)]
    fn hop(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        index: Whole,
        sharing: &str,
        positioning: &str,
        route: &str,
        support: Option<Whole>,
    ) -> PyResult<Hop> {
        let index = index.index(py, "index", "a hop index from 0")?;
        let support = support_arg(py, support)?;
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
    #[pyo3(signature = (request, stops, policy, positioning = "location-aware", support = None, reference = true, reorder = "paper".to_string(), backend = "microlp".to_string(), hop_time_limit_s = None, hop_node_limit = Whole::of(20_000), node_limit = Whole::of(20_000_000)))]
    #[allow(clippy::too_many_arguments)]
    fn evaluate_route(
        &self,
        py: Python<'_>,
        request: &Bound<'_, PyAny>,
        stops: Vec<String>,
        policy: &Bound<'_, PyAny>,
        positioning: &str,
        support: Option<Whole>,
        reference: bool,
        reorder: String,
        backend: String,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: Whole,
        node_limit: Whole,
    ) -> PyResult<Py<PyAny>> {
        let support = support_arg(py, support)?;
        let hop_node_limit = hop_node_limit.get(py, "hop_node_limit", NODE_LIMIT_WHAT)?;
        let node_limit = node_limit.get(py, "node_limit", NODE_LIMIT_WHAT)?;
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
            schedule_of(&written).map_err(|cause| invalid("E0026", &field, cause, TRANSFERS_ACTION))
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

/// A schedule written in Python: a sequence of transfers, each a dict (`support`, `consumer`,
/// `start_min`, `end_min`, optional `consumer_slot` and `energy_mah`) or a sequence of numbers
/// in the order `(support, consumer, start_min, end_min[, consumer_slot])` (a tuple, a list, a
/// numpy row); the cause, naming `schedule[i]`, when it cannot be read.
fn schedule_of(obj: &Bound<'_, PyAny>) -> std::result::Result<Vec<WrittenTransfer>, String> {
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
fn is_text(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyString>() || obj.is_instance_of::<PyBytes>()
}

/// What to give for a schedule.
const TRANSFERS_ACTION: &str = "give a list of transfers, each a dict of support, consumer, \
     start_min, end_min (and optionally consumer_slot, energy_mah) or a sequence of numbers \
     (support, consumer, start_min, end_min[, consumer_slot])";

/// The names of a transfer's numbers, in the order of a transfer written as a sequence.
const TRANSFER_ORDER: [&str; 5] = [
    "support",
    "consumer",
    "start_min",
    "end_min",
    "consumer_slot",
];

/// One transfer: a dict, or a sequence of 4 or 5 numbers in [`TRANSFER_ORDER`].
fn transfer_of(item: &Bound<'_, PyAny>) -> std::result::Result<WrittenTransfer, String> {
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
fn index_in_transfer(v: &Bound<'_, PyAny>, name: &str) -> std::result::Result<usize, String> {
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
fn number_in_transfer(v: &Bound<'_, PyAny>, name: &str) -> std::result::Result<f64, String> {
    if v.is_instance_of::<PyBool>() {
        return Err(format!("{name}: {} is a bool, not a number", repr_of(v)));
    }
    v.extract::<f64>()
        .map_err(|_| format!("{name}: {} is not a number", repr_of(v)))
}

fn repr_of(v: &Bound<'_, PyAny>) -> String {
    v.repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "the value".into())
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

impl Hop {
    /// The rows of `methods` on the hop, their gaps labelled against the best reference
    /// among them when `label`.
    fn rows(
        &self,
        py: Python<'_>,
        methods: Vec<HopMethod>,
        milp: MilpOptions,
        label: bool,
    ) -> PyResult<Py<PyAny>> {
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
}

/// The search-node limit's description in its errors.
const NODE_LIMIT_WHAT: &str = "a number of search nodes (a whole number >= 0)";

/// An optional node limit, checked ([`Whole`]).
fn node_limit_arg(py: Python<'_>, node_limit: Option<Whole>) -> PyResult<Option<u64>> {
    node_limit
        .map(|n| n.get(py, "node_limit", NODE_LIMIT_WHAT))
        .transpose()
}

/// An optional number of support drones, checked ([`Whole`]).
fn support_arg(py: Python<'_>, support: Option<Whole>) -> PyResult<Option<usize>> {
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

    /// The moves of a re-ordering mode (`none` or `paper`): every move a transfer may use, as a
    /// dict with keys `support`, `consumer`, `consumer_slot` and `partner`, `partner` the
    /// delivery drone holding the consumer's slot meanwhile (`None` when the consumer stays in
    /// its own slot). A transfer written as a sequence takes another order: `(support,
    /// consumer, start_min, end_min[, consumer_slot])`.
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
    ///
    /// `gap` is `{"relative", "reference"}` as everywhere in the package: with `reference=True`
    /// (the default) the row of `none`, `pb`, `fb`, `milp` or `fair` is measured against the
    /// continuous model of the same `reorder` mode, solved alongside with the same limits (as
    /// `swarmplan eaas --methods M,continuous` measures it). `gap` is `None` for `continuous`
    /// itself (it is the reference) and for `fluid` (a bound, not a schedule), with
    /// `reference=False`, when the continuous model gives no value within its limits, and with
    /// `gap_label` `different_policy` for a heuristic schedule that swaps slots under
    /// `reorder="none"`.
    #[pyo3(signature = (method = "continuous", reorder = "paper", time_limit_s = Some(60.0), node_limit = None, period_min = 1.0, backend = "microlp", reference = true))]
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &self,
        py: Python<'_>,
        method: &str,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<Whole>,
        period_min: f64,
        backend: &str,
        reference: bool,
    ) -> PyResult<Py<PyAny>> {
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
        node_limit: Option<Whole>,
        period_min: f64,
        backend: &str,
        label: bool,
    ) -> PyResult<Py<PyAny>> {
        let methods: Vec<HopMethod> = methods
            .iter()
            .map(|m| choice(py, "method", m))
            .collect::<PyResult<_>>()?;
        let node_limit = node_limit_arg(py, node_limit)?;
        let milp = milp_options(py, reorder, time_limit_s, node_limit, period_min, backend)?;
        self.rows(py, methods, milp, label)
    }

    /// Flies a schedule written in Python exactly as written and scores it: the independent
    /// checker judges it (a rule broken raises `SwarmplanError` with the checker's code, such as
    /// C3006 for a consumer out of range), running out of battery is a result (`feasible`
    /// False), and its objective is measured against the continuous-time optimum of the
    /// `reorder` mode (`reference=True`; a schedule outside that mode gets `gap_label`
    /// `outside_reference`). The reference solve is deterministic by default (a node limit, no
    /// wall-clock limit).
    #[pyo3(signature = (schedule, reference = true, reorder = "paper", time_limit_s = None, node_limit = Some(Whole::of(20_000)), backend = "microlp"))]
    #[allow(clippy::too_many_arguments)]
    fn evaluate(
        &self,
        py: Python<'_>,
        schedule: &Bound<'_, PyAny>,
        reference: bool,
        reorder: &str,
        time_limit_s: Option<f64>,
        node_limit: Option<Whole>,
        backend: &str,
    ) -> PyResult<Py<PyAny>> {
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
