//! `swarmplan.Instance`: a network, a profile and a request set; plans, checks, hops and
//! route evaluations.

use pyo3::prelude::*;
use pyo3::types::PyList;
use std::sync::Arc;
use swarmplan::compose::{Context, HopPaths, PlanOptions, RequestReport};
use swarmplan::eaas::exact_hop::ExactChoices;
use swarmplan::eaas::hop_file::HopFile;
use swarmplan::eaas::PolicyOptions;
use swarmplan::evaluate::{self, RouteReference, WrittenTransfer};
use swarmplan::precompose::Positioning;
use swarmplan::problem::{io, shipped, Instance as Problem, Request, RequestSet};

use crate::args::{
    backend_of, choice, limit_or, schedule_of, support_arg, Whole, TRANSFERS_ACTION,
};
use crate::convert::{py_of, read};
use crate::errors::{invalid, to_py_err, Result};
use crate::hop::Hop;
use crate::plot::svg_on;
use crate::results::{read_plan, Plan, RouteEvaluation};
use crate::worker::run_detached;

/// A network, a profile and a request set, validated together.
pub(crate) struct InstanceData {
    instance: Problem,
    network_name: String,
    profile_name: String,
    requests_name: String,
}

/// A planning instance: a skyway network, a parameter profile and a request set, validated
/// together (the same rules and codes as the command line).
///
/// Make one with `Instance.embedded`, `Instance.from_files` or `Instance.generate`; plan its
/// requests (`plan`), check plans (`check`), draw them (`plot`), take out a hop (`hop`) or fly a
/// route of one's own (`evaluate_route`).
///
/// Attributes
/// ----------
/// network_name, profile_name, requests_name : str
///     Where the network, the profile and the requests come from.
/// request_ids : list of str
///     Ids of the requests, in the set's order.
/// network, profile : dict
///     The network as its JSON reads, the profile as its TOML reads.
#[pyclass(frozen, module = "swarmplan")]
pub(crate) struct Instance {
    inner: Arc<InstanceData>,
}

/// The exact-sharing settings of `--sharing exact|fair` and of the references, as the command
/// line reads them (E4101, E4105, E4113).
pub(crate) struct ExactKw {
    backend: Option<String>,
    hop_time_limit_s: Option<f64>,
    hop_node_limit: u64,
    period_min: f64,
    reorder: String,
}

impl ExactKw {
    fn context(&self, py: Python<'_>, data: &InstanceData, node_limit: u64) -> PyResult<Context> {
        let choices = ExactChoices {
            backend: backend_of(py, self.backend.as_deref())?,
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

impl InstanceData {
    /// The network, profile and requests.
    pub(crate) fn problem(&self) -> &Problem {
        &self.instance
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
                .unwrap_or_else(|| swarmplan::problem::PYTHON_REQUEST_ID.into()),
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

pub(crate) fn load_profile(
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
        p.readings = swarmplan::problem::Readings::literal();
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
    /// A shipped network with a shipped profile and the shipped 10,000 requests.
    ///
    /// Parameters
    /// ----------
    /// network : str, default "paper-195"
    ///     `paper-195`, `findings-195` or `sparse-195`.
    /// profile : str or None, default None
    ///     A shipped profile (`paper`, `paper-findings`, `fast-sharing`, `redundancy-levels`) or a
    ///     TOML file; `None`: the network's own (`paper-findings` for findings-195, else `paper`).
    /// literal : bool, default False
    ///     Read the paper word for word where it can be read several ways (`--literal`).
    ///
    /// Returns
    /// -------
    /// Instance
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0020 (no shipped network of that name), E0021 (no shipped profile of that name), or the
    ///     codes of an invalid profile file.
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

    /// An instance from a network file, a profile and requests.
    ///
    /// Parameters
    /// ----------
    /// network : str or os.PathLike
    ///     The network file (JSON).
    /// profile : str or None, default None
    ///     A shipped profile name or a TOML file; `None`: `paper`.
    /// requests : str, os.PathLike, list of dict or None, default None
    ///     A request file (JSON), a list of request dicts (`id`, `source`, `destination`,
    ///     `packages_kg`), or `None` for the shipped requests.
    /// literal : bool, default False
    ///     Read the paper word for word (`--literal`).
    ///
    /// Returns
    /// -------
    /// Instance
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     The input codes of the files (E1xxx network, E2xxx profile, E3xxx requests), E0026 for a
    ///     request list of the wrong shape.
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

    /// A seeded synthetic network and request set, as `swarmplan generate network` and `generate
    /// requests` write them (the same seed gives the same instance).
    ///
    /// Parameters
    /// ----------
    /// seed : int
    ///     Seed of the network (and of the requests unless `requests_seed` is given).
    /// nodes : int or None, default None
    ///     Number of rooftop nodes; `None`: `DEFAULT_NODES` (195).
    /// spacing_m : float or None, default None
    ///     Street-grid spacing, m; `None`: `DEFAULT_SPACING_M` (500.0).
    /// requests : int, default 100
    ///     Number of requests.
    /// requests_seed : int or None, default None
    ///     Seed of the requests; `None`: `seed`.
    /// max_package_kg : float or None, default None
    ///     Largest package mass, kg; `None`: `DEFAULT_MAX_PACKAGE_KG` (1.4).
    /// profile : str or None, default None
    ///     A shipped profile name or a TOML file; `None`: `paper`.
    ///
    /// Returns
    /// -------
    /// Instance
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0026 for a negative count or seed or a bool; the generator's codes (E19xx network, E39xx
    ///     requests).
    #[staticmethod]
    #[pyo3(signature = (seed, nodes = None, spacing_m = None, requests = Whole::of(100), requests_seed = None, max_package_kg = None, profile = None))]
    #[pyo3(
        text_signature = "(seed, nodes=None, spacing_m=None, requests=100, requests_seed=None, max_package_kg=None, profile=None)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn generate(
        py: Python<'_>,
        seed: Whole,
        nodes: Option<Whole>,
        spacing_m: Option<f64>,
        requests: Whole,
        requests_seed: Option<Whole>,
        max_package_kg: Option<f64>,
        profile: Option<&str>,
    ) -> PyResult<Instance> {
        let seed = seed.get(py, "seed", "a seed from 0 to 2**64 - 1")?;
        let nodes = nodes
            .map(|n| n.index(py, "nodes", "a node count"))
            .transpose()?
            .unwrap_or(swarmplan::generate::DEFAULT_NODES);
        let spacing_m = spacing_m.unwrap_or(swarmplan::generate::DEFAULT_SPACING_M);
        let max_package_kg = max_package_kg.unwrap_or(swarmplan::generate::DEFAULT_MAX_PACKAGE_KG);
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

    /// One request of the instance.
    ///
    /// Parameters
    /// ----------
    /// id : str or dict
    ///     A request id, or a dict with `source`, `destination` and `packages_kg` (checked against
    ///     the network).
    ///
    /// Returns
    /// -------
    /// dict
    ///     `{"id", "source", "destination", "packages_kg"}`.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E3401 for an unknown id, E3xxx for a request dict the network refuses, E0026 for one of
    ///     the wrong shape.
    fn request(&self, py: Python<'_>, id: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let r = Instance::resolve_request(self, py, id)?;
        py_of(py, &r)
    }

    /// Plans one request, as `swarmplan solve --json` does.
    ///
    /// Parameters
    /// ----------
    /// request : str or dict
    ///     A request id, or a dict with `source`, `destination` and `packages_kg`.
    /// sharing : str, default "pb"
    ///     `none`, `idle-support`, `pb`, `fb`, `exact` or `fair`.
    /// positioning : str, default "location-aware"
    ///     `location-aware` or `energy-aware`.
    /// route : str, default "sequential"
    ///     `sequential`, `astar`, `dijkstra`, `floyd-warshall` or `optimal`.
    /// support : int or None, default None
    ///     Support drones flown; `None`: the redundancy table's decision.
    /// hop_paths : str, default "rule"
    ///     Hop paths of `route="optimal"`: `rule` (shortest paths) or `any`.
    /// node_limit : int or None, default None
    ///     Search nodes of the exact node time at every stop; `None`: `DEFAULT_NODE_LIMIT`
    ///     (20,000,000).
    /// gap : bool, default False
    ///     Also plan the optimal route of the same combination and give `route_gap`.
    /// backend : str or None, default None
    ///     MILP backend of the exact hop models; `None`: `DEFAULT_BACKEND` (`microlp`).
    /// hop_time_limit_s : float or None, default None
    ///     Wall-clock limit of each hop solve, s; `None`: none.
    /// hop_node_limit : int or None, default None
    ///     Branch-and-bound nodes of each MILP call; `None`: `DEFAULT_HOP_NODE_LIMIT` (20,000).
    /// period_min : float, default 1.0
    ///     Longest period of the grid MILP, min.
    /// reorder : str, default "paper"
    ///     Re-ordering of the exact hop models: `paper` or `none`.
    ///
    /// Returns
    /// -------
    /// Plan
    ///     The plan; `to_dict()` is the document `swarmplan solve --json` prints.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0026 for an unknown choice (listing the choices) or a negative number; E0015, E0016
    ///     for combinations that do not apply; E4101, E4105, E4113 for the hop settings; E0006 for
    ///     too many support drones; E3401 for an unknown request.
    #[pyo3(signature = (request, sharing = "pb", positioning = "location-aware", route = "sequential", support = None, hop_paths = "rule", node_limit = None, gap = false, backend = None, hop_time_limit_s = None, hop_node_limit = None, period_min = 1.0, reorder = "paper"))]
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
        node_limit: Option<Whole>,
        gap: bool,
        backend: Option<String>,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: Option<Whole>,
        period_min: f64,
        reorder: &str,
    ) -> PyResult<Plan> {
        let support = support_arg(py, support)?;
        let node_limit = limit_or(
            py,
            node_limit,
            "node_limit",
            swarmplan::node_time::DEFAULT_STOP_NODE_LIMIT,
        )?;
        let hop_node_limit = limit_or(
            py,
            hop_node_limit,
            "hop_node_limit",
            swarmplan::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT,
        )?;
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
            reorder: reorder.to_string(),
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
        Ok(Plan::of(&report, self.inner.clone()))
    }

    /// Re-verifies a plan with the independent checker.
    ///
    /// Parameters
    /// ----------
    /// plan : Plan, dict or str
    ///     A plan as `plan` returns it, its `to_dict()`, or its JSON text.
    ///
    /// Returns
    /// -------
    /// list of dict
    ///     Every violation (`code`, `field`, `cause`, `action`); empty when the plan passes.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E6001 for text that is no plan document.
    fn check(&self, py: Python<'_>, plan: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        let report = read_plan(py, plan, "the plan given")?;
        let i = &self.inner.instance;
        let violations =
            swarmplan::check::check_report(&i.network, &i.profile, &i.requests, &report);
        py_of(py, &violations)
    }

    /// The figure of a plan drawn on this instance as SVG text, the bytes ``swarmplan plot
    /// --network N --profile P --plan F -o out.svg`` writes; ``swarmplan.plot(plan)`` draws a
    /// ``Plan`` on the instance it was made on.
    ///
    /// Parameters
    /// ----------
    /// plan : Plan, dict or str
    ///     A plan as `plan` returns it, its `to_dict()`, or its JSON text (`solve --json`).
    /// compare : Plan, dict, str or None, default None
    ///     A second plan of the same request, drawn beside it as the reference of the gap in
    ///     the title (``--compare``).
    /// percent : bool, default False
    ///     Batteries in percent of each drone's capacity instead of mAh (``--percent``).
    ///
    /// Returns
    /// -------
    /// str
    ///     The SVG document.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E6004, E6005 for a plan made on another network, with another profile; E8001 for a
    ///     ``compare`` plan of another request; E6001-E6003 for text or a dict that is no plan
    ///     document; E8003 for a plan that does not fit the instance.
    #[pyo3(signature = (plan, compare = None, percent = false))]
    fn plot(
        &self,
        py: Python<'_>,
        plan: &Bound<'_, PyAny>,
        compare: Option<&Bound<'_, PyAny>>,
        percent: bool,
    ) -> PyResult<String> {
        svg_on(py, &self.inner, plan, compare, percent)
    }

    /// Hop `index` of a request's plan, as `swarmplan eaas` takes it (by default the plan of PB
    /// sharing, location-aware positioning and Algorithm 1).
    ///
    /// Parameters
    /// ----------
    /// request : str or dict
    ///     A request id, or a dict with `source`, `destination` and `packages_kg`.
    /// index : int, default 0
    ///     The hop's index in the plan (0 = the first).
    /// sharing : str, default "pb"
    ///     The plan's sharing policy.
    /// positioning : str, default "location-aware"
    ///     The plan's positioning.
    /// route : str, default "sequential"
    ///     The plan's route method.
    /// support : int or None, default None
    ///     Support drones flown; `None`: the redundancy table's decision.
    ///
    /// Returns
    /// -------
    /// Hop
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E4110 for an index beyond the plan's hops; E0026 for an unknown choice or a negative
    ///     index.
    #[pyo3(signature = (request, index = Whole::of(0), sharing = "pb", positioning = "location-aware", route = "sequential", support = None))]
    #[pyo3(
        text_signature = "(self, /, request, index=0, sharing='pb', positioning='location-aware', route='sequential', support=None)"
    )]
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

    /// Flies a request along `stops` with a schedule per hop and measures its delivery time against
    /// the joint optimum of the same swarm.
    ///
    /// Every hop departs from full batteries along the shortest path; the node time at every stop is
    /// exact.
    ///
    /// Parameters
    /// ----------
    /// request : str or dict
    ///     A request id, or a dict with `source`, `destination` and `packages_kg`.
    /// stops : list of str
    ///     Node ids, the source first and the destination last.
    /// policy : callable or list of schedules
    ///     `policy(hop) -> schedule`, called with each hop in turn (a `Hop`), or one schedule per
    ///     hop; a schedule is a list of transfers as `Hop.evaluate` takes them.
    /// positioning : str, default "location-aware"
    ///     `location-aware` or `energy-aware`.
    /// support : int or None, default None
    ///     Support drones flown; `None`: the redundancy table's decision.
    /// reference : bool, default True
    ///     Measure against the joint optimum (`route="optimal"`, `sharing="exact"`).
    /// reorder : str, default "paper"
    ///     Re-ordering of the reference: `paper` or `none`.
    /// backend : str or None, default None
    ///     MILP backend; `None`: `DEFAULT_BACKEND` (`microlp`).
    /// hop_time_limit_s : float or None, default None
    ///     Wall-clock limit of each hop solve of the reference, s; `None`: none.
    /// hop_node_limit : int or None, default None
    ///     Branch-and-bound nodes of each MILP call; `None`: `DEFAULT_HOP_NODE_LIMIT` (20,000).
    /// node_limit : int or None, default None
    ///     Search nodes of the exact node time at every stop; `None`: `DEFAULT_NODE_LIMIT`
    ///     (20,000,000).
    ///
    /// Returns
    /// -------
    /// RouteEvaluation
    ///     `gap` is `{"relative", "reference"}` (reference `optimal` or `incumbent`), or `None`
    ///     with `gap_label`.
    ///
    /// Raises
    /// ------
    /// SwarmplanError
    ///     E0022-E0025 for stops that are no route; the checker's codes for a schedule that breaks a
    ///     rule; E0026 for a policy or schedule of the wrong shape.
    /// Exception
    ///     Whatever `policy` raises.
    #[pyo3(signature = (request, stops, policy, positioning = "location-aware", support = None, reference = true, reorder = "paper", backend = None, hop_time_limit_s = None, hop_node_limit = None, node_limit = None))]
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
        reorder: &str,
        backend: Option<String>,
        hop_time_limit_s: Option<f64>,
        hop_node_limit: Option<Whole>,
        node_limit: Option<Whole>,
    ) -> PyResult<RouteEvaluation> {
        let support = support_arg(py, support)?;
        let hop_node_limit = limit_or(
            py,
            hop_node_limit,
            "hop_node_limit",
            swarmplan::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT,
        )?;
        let node_limit = limit_or(
            py,
            node_limit,
            "node_limit",
            swarmplan::node_time::DEFAULT_STOP_NODE_LIMIT,
        )?;
        let request = Instance::resolve_request(self, py, request)?;
        let positioning: Positioning = choice(py, "positioning", positioning)?;
        let exact = ExactKw {
            backend,
            hop_time_limit_s,
            hop_node_limit,
            period_min: 1.0,
            reorder: reorder.to_string(),
        };
        let context = exact.context(py, &self.inner, node_limit)?;
        let readings = PolicyOptions::from(&self.inner.instance.profile.readings);
        let listed = listed_schedules(py, policy)?;
        let mut py_error: Option<PyErr> = None;
        let mut schedule = |file: &HopFile| -> Result<Vec<WrittenTransfer>> {
            policy_schedule(file, listed.as_deref(), policy, readings, &mut py_error)
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
            let found = route_reference_detached(
                py,
                self.inner.clone(),
                &context,
                &request,
                positioning,
                support,
            )?;
            evaluation.measure_against(found);
        }
        Ok(RouteEvaluation::of(&evaluation))
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

/// `evaluate_route`'s policy given as a list: its schedules; `None` for a callable policy.
///
/// # Errors
/// E0026 for a policy neither callable nor iterable.
fn listed_schedules<'py>(
    py: Python<'_>,
    policy: &Bound<'py, PyAny>,
) -> PyResult<Option<Vec<Bound<'py, PyAny>>>> {
    if policy.is_callable() {
        return Ok(None);
    }
    policy
        .try_iter()
        .and_then(|it| it.collect::<PyResult<Vec<_>>>())
        .map(Some)
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
        })
}

/// The schedule `evaluate_route`'s policy gives the hop of `file`: the list's entry for the
/// hop (`listed`), or what the callable `policy` returns for it. An exception the policy raises
/// is kept in `py_error`, to be raised once the evaluation returns.
fn policy_schedule(
    file: &HopFile,
    listed: Option<&[Bound<'_, PyAny>]>,
    policy: &Bound<'_, PyAny>,
    readings: PolicyOptions,
    py_error: &mut Option<PyErr>,
) -> Result<Vec<WrittenTransfer>> {
    let field = format!("policy (hop {})", file.hop_index);
    let written = if let Some(list) = listed {
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
                *py_error = Some(e);
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
}

/// The joint optimum `evaluate_route` measures against, planned off the interpreter's thread
/// with the settings of `context`.
fn route_reference_detached(
    py: Python<'_>,
    data: Arc<InstanceData>,
    context: &Context,
    request: &Request,
    positioning: Positioning,
    support: Option<usize>,
) -> PyResult<RouteReference> {
    let settings = context.exact;
    let node_limit = context.node_limit;
    let request = request.clone();
    run_detached(
        py,
        move || {
            let i = &data.instance;
            let mut context = Context::new(&i.network, &i.graph, &i.profile);
            context.exact = settings;
            context.node_limit = node_limit;
            evaluate::route_reference(&context, &request, positioning, support)
        },
        |_| Ok(()),
    )
}

/// Plans a request and, with `gap`, its gap against the optimal route of the same combination
/// (as `solve --gap`).
pub(crate) fn plan_with_gap(
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
