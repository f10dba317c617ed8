//! Planning one request end to end: pre-composition (formation, support drones, positions) then
//! route composition.

use super::{BaselineCosts, EdgeFactorCache, HopPaths, IntoShared, Plan, Planner, RouteMethod};
use crate::eaas::exact_hop::ExactSettings;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::{self, Positioning, SupportDecision};
use crate::problem::fingerprint::Fingerprint;
use crate::problem::FormationKind;
use crate::problem::SkywayGraph;
use crate::problem::Swarm;
use crate::problem::Wind;
use crate::problem::{Network, Profile, Request, MAX_SUPPORT_DRONES, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Instant;

/// The method combination a request is planned with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanOptions {
    /// In-flight sharing policy on every hop.
    pub sharing: SharingPolicy,
    /// Initial positioning of the support drones.
    pub positioning: Positioning,
    /// Route composition method.
    pub route: RouteMethod,
    /// Number of support drones; `None` lets the redundancy table decide. Ignored by
    /// [`SharingPolicy::None`], the paper's baseline, which flies no support drone.
    pub support: Option<usize>,
}

impl PlanOptions {
    /// Checks that the combination can be planned: `--route optimal` with a simulated sharing
    /// policy (none, idle-support, pb, fb).
    ///
    /// # Errors
    /// [`Error::Invalid`] E0015 for [`RouteMethod::Optimal`] with `fair`.
    ///
    /// # Complexity
    /// O(1).
    pub fn validate(&self) -> Result<()> {
        if self.route == RouteMethod::Optimal && self.sharing == SharingPolicy::Fair {
            return Err(super::optimal::optimal_with_solved_sharing(self.sharing));
        }
        Ok(())
    }
}

/// The largest network `--route floyd-warshall` plans on: its all-pairs tables take
/// [`ALL_PAIRS_BYTES_PER_PAIR`] bytes a pair (1.1 GiB at 10,000 nodes) and its time grows as
/// n^3; beyond, E0029 (use Dijkstra on the same costs).
pub const FLOYD_WARSHALL_MAX_NODES: usize = 10_000;

/// Bytes a pair of nodes of Floyd-Warshall's tables: the distance (`f64`) and the predecessor
/// (`u32`), [`crate::network::floyd_warshall`].
pub const ALL_PAIRS_BYTES_PER_PAIR: f64 = 12.0;

/// The settings behind the numbers of a plan besides its method combination: the hop model of
/// the exact and fair policies, the node limit of every stop and the paths of an optimal
/// route's hops. With them `check` plans the request again and compares the numbers only the
/// method's run defines (its search report, `models/plan_file.md`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanSettings {
    /// The hop model's settings: re-ordering, backend, wall-clock and node limits of each hop
    /// solve (the grid step is not used by the continuous-time model).
    pub hop_model: crate::eaas::exact::milp::MilpOptions,
    /// Algorithm 1 under `exact`: candidates pruned by their lower bound (the default).
    pub prune_candidates: bool,
    /// Node limit of the exact node time at every stop (`None`: no limit).
    pub node_limit: Option<u64>,
    /// The paths the hops of `--route optimal` may follow.
    pub hop_paths: HopPaths,
}

impl PlanSettings {
    /// Whether a plan made with these settings is the same on every machine: no solve looks at
    /// the clock.
    pub fn deterministic(&self) -> bool {
        !self.hop_model.time_limit_s.is_finite()
    }
}

/// What is fixed for every request on one network with one profile.
pub struct Context {
    graph: Arc<SkywayGraph>,
    profile: Arc<Profile>,
    /// The fixed formation, selected from the network's averaged wind.
    pub formation: FormationKind,
    /// The network's averaged wind.
    pub average_wind: Wind,
    /// Solver settings of the exact and fair sharing policies.
    pub exact: ExactSettings,
    /// Node limit of the exact node time at every stop (`None`: no limit), default
    /// [`crate::node_time::DEFAULT_STOP_NODE_LIMIT`].
    pub node_limit: Option<u64>,
    /// The paths the hops of `--route optimal` may follow (default [`HopPaths::Rule`]).
    pub hop_paths: HopPaths,
    /// A whole run's wall-clock budget (`--time-budget`): [`Context::plan_grid_rows`] starts no
    /// request after it (default `None`). Every limit inside a request counts work, so the
    /// requests planned get the same numbers on any machine; how many there are does not.
    pub deadline: Option<std::time::Instant>,
    /// The energy model's leg factors, shared by every request's planner.
    factors: EdgeFactorCache,
    /// The network and profile, fingerprinted for the plans made here.
    fingerprint: Fingerprint,
}

/// The planned request: the document `solve --json` prints and `check --plan` reads back.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RequestReport {
    /// Version of the document's schema, [`SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The request planned.
    pub request: Request,
    /// The method combination.
    pub options: PlanOptions,
    /// The fixed formation.
    pub formation: FormationKind,
    /// What the redundancy table decided.
    pub support_decision: SupportDecision,
    /// Support drones flown (the decision or the override).
    pub support_drones: usize,
    /// The swarm: drones, slots, initial positions.
    pub swarm: Swarm,
    /// The composed plan.
    pub plan: Plan,
    /// Wall-clock time of pre-composition and composition, ms (not reproducible, unlike the rest).
    pub execution_ms: f64,
    /// The network and profile the plan was made on (absent in plans of earlier versions);
    /// `check` compares it with the instance it is given before any model check.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub made_on: Option<Fingerprint>,
    /// `solve --gap`: the plan against the optimal route of the same request and combination.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub route_gap: Option<RouteGap>,
    /// The settings the plan was made with (absent in plans of earlier versions).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settings: Option<PlanSettings>,
    /// `solve --swarm best`: the swarms the optimum ranged over, each one's optimum; the plan
    /// is the best swarm's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub swarms_compared: Option<super::SwarmsCompared>,
}

/// A plan's delivery time against the optimal route (`--route optimal`) of the same request,
/// sharing policy, positioning and support drones.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RouteGap {
    /// `optimal`: over stop sequences, hops along the shortest path between stops.
    pub reference: crate::solver::ReferenceKind,
    /// The hop paths of the optimum: `rule` (the shortest path between stops) or `any` (every
    /// flyable path; then a Dijkstra or Floyd–Warshall gap is never negative).
    #[serde(default, skip_serializing_if = "is_rule")]
    pub hop_paths: HopPaths,
    /// The optimum's delivery time, min; `None` when it does not deliver.
    pub optimal_dt_min: Option<f64>,
    /// `(dt - dt_opt) / dt_opt` when both deliver (negative only for a route whose hops follow
    /// other paths: Dijkstra, Floyd–Warshall).
    pub gap: Option<f64>,
    /// Whether every node time of the optimum's search was proven.
    pub optimal_proven: bool,
}

fn is_rule(h: &HopPaths) -> bool {
    *h == HopPaths::Rule
}

/// The swarm pre-composition gives a request.
#[derive(Debug, Clone)]
pub struct SwarmChoice {
    /// Source node index.
    pub source: usize,
    /// Destination node index.
    pub destination: usize,
    /// Shortest-path distance from source to destination, m (`d(alpha, beta)` of Eq. 2).
    pub route_distance_m: f64,
    /// What the redundancy table decided.
    pub support_decision: SupportDecision,
    /// Support drones flown (the decision or the override).
    pub support_drones: usize,
    /// The swarm with its initial positions.
    pub swarm: Swarm,
}

impl Context {
    /// Selects the formation from the network's averaged wind.
    pub fn new(
        network: &Network,
        graph: impl IntoShared<SkywayGraph>,
        profile: impl IntoShared<Profile>,
    ) -> Context {
        let (graph, profile) = (graph.into_shared(), profile.into_shared());
        let (formation, average_wind) = precompose::select_formation(network, &profile);
        Context {
            formation,
            average_wind,
            exact: ExactSettings::default(),
            node_limit: Some(crate::node_time::DEFAULT_STOP_NODE_LIMIT),
            hop_paths: HopPaths::Rule,
            deadline: None,
            factors: EdgeFactorCache::new(&graph),
            fingerprint: Fingerprint::of(network, &profile),
            graph,
            profile,
        }
    }

    /// The settings recorded in every plan made here.
    pub fn settings(&self) -> PlanSettings {
        PlanSettings {
            hop_model: self.exact.milp,
            prune_candidates: self.exact.prune_candidates,
            node_limit: self.node_limit,
            hop_paths: self.hop_paths,
        }
    }

    /// A context with `settings` (those a plan records, see [`Context::settings`]).
    pub fn with_settings(mut self, settings: &PlanSettings) -> Context {
        self.exact = ExactSettings {
            milp: settings.hop_model,
            prune_candidates: settings.prune_candidates,
        };
        self.node_limit = settings.node_limit;
        self.hop_paths = settings.hop_paths;
        self
    }

    /// The fingerprint of the network and the profile, recorded in every plan made here.
    pub fn fingerprint(&self) -> &Fingerprint {
        &self.fingerprint
    }

    /// The profile.
    pub fn profile(&self) -> &Profile {
        &self.profile
    }

    /// The network's graph.
    pub fn graph(&self) -> &SkywayGraph {
        &self.graph
    }

    /// A planner of `swarm` under `sharing` with this context's leg factors, exact settings and
    /// node limit: the one [`Context::plan`] composes with, for looking at a plan's hops again.
    pub fn planner(&self, swarm: &Swarm, sharing: SharingPolicy) -> Planner {
        Planner::new(&self.graph, &self.profile, swarm, sharing)
            .with_exact(self.exact)
            .with_node_limit(self.node_limit)
            .with_hop_paths(self.hop_paths)
            .with_edge_factors(&self.factors)
    }

    /// Pre-composition of one request: support drones from the redundancy table (or `support`),
    /// then the initial positions.
    ///
    /// # Errors
    /// [`Error::Invalid`] when the request names an unknown node.
    pub fn swarm_for(
        &self,
        request: &Request,
        positioning: Positioning,
        support: Option<usize>,
    ) -> Result<SwarmChoice> {
        let index = |id: &str, field: &str| {
            self.graph.index_of(id).ok_or_else(|| {
                Error::invalid(
                    "E3201",
                    format!("request {}.{field}", request.id),
                    format!("unknown node id `{id}`"),
                    "use a node id of the network",
                )
            })
        };
        let source = index(&request.source, "source")?;
        let destination = index(&request.destination, "destination")?;
        let route_distance_m = self
            .graph
            .shortest_path(source, destination)
            .map(|p| p.distance_m)
            .unwrap_or(f64::INFINITY);
        let support_decision = precompose::support_count(
            &self.profile,
            &request.packages_kg,
            route_distance_m,
            &self.average_wind,
        );
        if let Some(n) = support.filter(|&n| n > MAX_SUPPORT_DRONES) {
            return Err(Error::invalid(
                "E0006",
                "--support",
                format!("{n} support drones, more than the {MAX_SUPPORT_DRONES} a swarm may have"),
                "give --support 32 or fewer, or leave it to the redundancy table",
            ));
        }
        let support_drones = support.unwrap_or(support_decision.count);
        let swarm = precompose::build_swarm(
            &self.profile,
            self.formation,
            &request.packages_kg,
            support_drones,
            positioning,
        );
        Ok(SwarmChoice {
            source,
            destination,
            route_distance_m,
            support_decision,
            support_drones,
            swarm,
        })
    }

    /// Checks that `options` can be planned in this context: [`PlanOptions::validate`], and
    /// `--hop-paths any` with an optimal route only for a policy that does not share in flight
    /// or the exact one (the joint optimum).
    ///
    /// # Errors
    /// E0015 ([`PlanOptions::validate`]); E0016 for [`RouteMethod::Optimal`] with
    /// [`HopPaths::Any`] and a simulated policy that shares (pb, fb); E0029 for
    /// [`RouteMethod::FloydWarshall`] on more than [`FLOYD_WARSHALL_MAX_NODES`] nodes.
    ///
    /// # Complexity
    /// O(1).
    pub fn validate(&self, options: &PlanOptions) -> Result<()> {
        options.validate()?;
        let nodes = self.graph().node_count();
        if options.route == RouteMethod::FloydWarshall && nodes > FLOYD_WARSHALL_MAX_NODES {
            let gib =
                |n: usize| (n as f64).powi(2) * ALL_PAIRS_BYTES_PER_PAIR / (1u64 << 30) as f64;
            return Err(Error::invalid(
                "E0029",
                "--route floyd-warshall",
                format!(
                    "Floyd-Warshall's all-pairs tables on {nodes} nodes take {:.0} GiB ({} bytes \
                     a pair) and O(n^3) time; it is meant for networks up to {} nodes ({:.1} GiB)",
                    gib(nodes),
                    ALL_PAIRS_BYTES_PER_PAIR,
                    FLOYD_WARSHALL_MAX_NODES,
                    gib(FLOYD_WARSHALL_MAX_NODES)
                ),
                "use --route dijkstra: the same edge costs, one source at a time",
            ));
        }
        if options.route == RouteMethod::Optimal
            && self.hop_paths == HopPaths::Any
            && options.sharing.shares()
            && options.sharing != SharingPolicy::Exact
        {
            return Err(super::any_path::any_path_with_sharing(options.sharing));
        }
        Ok(())
    }

    /// Plans one validated request.
    ///
    /// # Errors
    /// [`Error::Invalid`] when the request names an unknown node (validate requests first to get
    /// every violation at once), E0015 when `options` cannot be planned
    /// ([`PlanOptions::validate`]).
    pub fn plan(&self, request: &Request, options: &PlanOptions) -> Result<RequestReport> {
        let mut reports = self.plan_each(request, std::slice::from_ref(options))?;
        Ok(reports.pop().expect("one report per combination"))
    }

    /// The gap of a planned request against the optimal route of the same combination (`solve
    /// --gap`): the request planned again with `--route optimal`, same sharing, positioning and
    /// support drones.
    ///
    /// # Errors
    /// E0015 for `fair` ([`PlanOptions::validate`]); those of [`Context::plan`].
    pub fn route_gap(&self, request: &Request, report: &RequestReport) -> Result<RouteGap> {
        let optimal = PlanOptions {
            route: super::RouteMethod::Optimal,
            ..report.options
        };
        self.validate(&optimal)?;
        let best = self.plan(request, &optimal)?.plan;
        let pair = super::RoutePair {
            heuristic_dt_min: report.plan.delivered().then_some(report.plan.dt_min),
            optimal_dt_min: best.delivered().then_some(best.dt_min),
            optimal_proven: best.route_optimality.is_none_or(|o| o.proven()),
        };
        Ok(RouteGap {
            reference: crate::solver::ReferenceKind::Optimal,
            hop_paths: self.hop_paths,
            optimal_dt_min: pair.optimal_dt_min,
            gap: pair.gap(),
            optimal_proven: pair.optimal_proven,
        })
    }

    /// Plans one validated request with each of several method combinations, doing once the work
    /// they share: the swarm of each (positioning, support drones) pair; one [`Planner`], with its
    /// cache of consumption rates per edge, for each swarm and sharing policy, whatever the route
    /// method; and the fixed-route baselines' edge costs `tt + nt` of each distinct swarm (the
    /// same for every sharing policy that flies it, and for Dijkstra and Floyd–Warshall), with
    /// Floyd–Warshall's all-pairs result on them.
    ///
    /// # Returns
    /// One report per combination, in the order of `options`, each equal to the one
    /// [`Context::plan`] gives, except `execution_ms`: the combination's own time plus an equal
    /// share of each piece of shared work it uses (a swarm among the combinations flying it; a
    /// swarm's edge costs among its Dijkstra and Floyd–Warshall combinations; the all-pairs
    /// result among its Floyd–Warshall combinations). A consumption rate counts in the
    /// combination that computes it first. The times add up to the call's.
    ///
    /// # Errors
    /// As [`Context::plan`]; E0015 ([`PlanOptions::validate`]) before any work when a
    /// combination cannot be planned.
    ///
    /// # Complexity
    /// Per combination that of [`Planner::compose`], except that the edge costs (one hop
    /// simulation and one exact node time per directed edge) and Floyd–Warshall's O(|V|^3) are
    /// paid once per distinct swarm, and a rate matrix once per edge, swarm and sharing policy.
    pub fn plan_each(
        &self,
        request: &Request,
        options: &[PlanOptions],
    ) -> Result<Vec<RequestReport>> {
        for o in options {
            self.validate(o)?;
        }
        let swarms = self.precompose_each(request, options)?;
        let mut baselines = Baselines::of(options, &swarms);
        let (plans, own_ms) = self.compose_each(options, &swarms, &mut baselines)?;
        let execution_ms = shared_out(own_ms, &swarms, &baselines);
        Ok(options
            .iter()
            .zip(plans)
            .zip(execution_ms)
            .enumerate()
            .map(|(i, ((o, plan), execution_ms))| {
                let choice = &swarms.choices[swarms.choice_of[i]];
                RequestReport {
                    schema_version: SCHEMA_VERSION,
                    request: request.clone(),
                    options: *o,
                    formation: self.formation,
                    support_decision: choice.support_decision.clone(),
                    support_drones: choice.support_drones,
                    swarm: choice.swarm.clone(),
                    plan,
                    execution_ms,
                    made_on: Some(self.fingerprint.clone()),
                    route_gap: None,
                    settings: Some(self.settings()),
                    swarms_compared: None,
                }
            })
            .collect())
    }

    /// Pre-composition of [`Context::plan_each`]'s combinations, once per (positioning, support
    /// drones); the paper's baseline (`none`) is the swarm without support drones.
    fn precompose_each(&self, request: &Request, options: &[PlanOptions]) -> Result<Precomposed> {
        let mut keys: Vec<(Positioning, Option<usize>)> = Vec::new();
        let mut swarms = Precomposed {
            choices: Vec::new(),
            work: Vec::new(),
            choice_of: Vec::with_capacity(options.len()),
        };
        for (i, o) in options.iter().enumerate() {
            let key = (
                o.positioning,
                if o.sharing.flies_support() {
                    o.support
                } else {
                    Some(0)
                },
            );
            let c = match keys.iter().position(|k| *k == key) {
                Some(c) => c,
                None => {
                    let start = Instant::now();
                    swarms.choices.push(self.swarm_for(request, key.0, key.1)?);
                    swarms.work.push(Shared {
                        ms: elapsed_ms(start),
                        users: Vec::new(),
                    });
                    keys.push(key);
                    swarms.choices.len() - 1
                }
            };
            swarms.work[c].users.push(i);
            swarms.choice_of.push(c);
        }
        Ok(swarms)
    }

    /// Route composition of each of [`Context::plan_each`]'s combinations, with one planner per
    /// swarm and sharing policy, and each swarm's baseline costs computed by its first
    /// fixed-route combination: the plans, and each one's own time, ms (without the shared work
    /// it did).
    fn compose_each(
        &self,
        options: &[PlanOptions],
        swarms: &Precomposed,
        baselines: &mut Baselines,
    ) -> Result<(Vec<Plan>, Vec<f64>)> {
        let mut own_ms = vec![0.0; options.len()];
        let mut plans = Vec::with_capacity(options.len());
        let mut planners: Vec<((usize, SharingPolicy), Planner)> = Vec::new();
        for (i, o) in options.iter().enumerate() {
            let start = Instant::now();
            let choice = &swarms.choices[swarms.choice_of[i]];
            let key = (swarms.choice_of[i], o.sharing);
            let p = match planners.iter().position(|(k, _)| *k == key) {
                Some(p) => p,
                None => {
                    planners.push((key, self.planner(&choice.swarm, o.sharing)));
                    planners.len() - 1
                }
            };
            let planner = &planners[p].1;
            let (plan, shared_ms) = match baselines.of[i] {
                Some(e) => compose_fixed(planner, &mut baselines.swarms[e], o, choice)?,
                None => (
                    planner.compose(choice.source, choice.destination, o.route)?,
                    0.0,
                ),
            };
            own_ms[i] = elapsed_ms(start) - shared_ms;
            plans.push(plan);
        }
        Ok((plans, own_ms))
    }
}

/// Work shared by several combinations of [`Context::plan_each`]: its time, ms, and the
/// combinations using it.
#[derive(Default)]
struct Shared {
    ms: f64,
    users: Vec<usize>,
}

/// A distinct swarm's baseline costs, computed by its first fixed-route combination.
struct SwarmCosts {
    choice: usize,
    costs: Option<BaselineCosts>,
    edges: Shared,
    all_pairs: Shared,
    all_pairs_done: bool,
}

/// The swarms of [`Context::plan_each`]'s combinations: each distinct one, pre-composed once,
/// with its work; the swarm of each combination.
struct Precomposed {
    choices: Vec<SwarmChoice>,
    work: Vec<Shared>,
    choice_of: Vec<usize>,
}

/// The baseline costs of [`Context::plan_each`]'s fixed-route combinations (Dijkstra,
/// Floyd–Warshall): one entry per distinct swarm among them, and each combination's entry.
struct Baselines {
    swarms: Vec<SwarmCosts>,
    of: Vec<Option<usize>>,
}

impl Baselines {
    /// The entries of `options`' fixed-route combinations, once per distinct swarm, no cost
    /// computed yet.
    fn of(options: &[PlanOptions], swarms: &Precomposed) -> Baselines {
        let choices = &swarms.choices;
        let mut baselines = Baselines {
            swarms: Vec::new(),
            of: vec![None; options.len()],
        };
        for (i, o) in options.iter().enumerate() {
            let fixed = match o.route {
                RouteMethod::Dijkstra | RouteMethod::FloydWarshall => true,
                RouteMethod::Sequential | RouteMethod::Astar | RouteMethod::Optimal => false,
            };
            if !fixed {
                continue;
            }
            let swarm = &choices[swarms.choice_of[i]].swarm;
            let e = match baselines
                .swarms
                .iter()
                .position(|e| choices[e.choice].swarm == *swarm)
            {
                Some(e) => e,
                None => {
                    baselines.swarms.push(SwarmCosts {
                        choice: swarms.choice_of[i],
                        costs: None,
                        edges: Shared::default(),
                        all_pairs: Shared::default(),
                        all_pairs_done: false,
                    });
                    baselines.swarms.len() - 1
                }
            };
            baselines.swarms[e].edges.users.push(i);
            if o.route == RouteMethod::FloydWarshall {
                baselines.swarms[e].all_pairs.users.push(i);
            }
            baselines.of[i] = Some(e);
        }
        baselines
    }
}

/// A fixed-route combination `o` composed on its swarm's baseline costs `entry`, computing them
/// (and Floyd–Warshall's all-pairs result) first when no combination did: the plan, and the
/// time of that shared work, ms.
fn compose_fixed(
    planner: &Planner,
    entry: &mut SwarmCosts,
    o: &PlanOptions,
    choice: &SwarmChoice,
) -> Result<(Plan, f64)> {
    let mut shared_ms = 0.0;
    if entry.costs.is_none() {
        let at = Instant::now();
        entry.costs = Some(planner.baseline_costs()?);
        entry.edges.ms = elapsed_ms(at);
        shared_ms += entry.edges.ms;
    }
    let costs = entry.costs.as_ref().expect("computed above");
    if o.route == RouteMethod::FloydWarshall && !entry.all_pairs_done {
        let at = Instant::now();
        costs.all_pairs();
        entry.all_pairs.ms = elapsed_ms(at);
        entry.all_pairs_done = true;
        shared_ms += entry.all_pairs.ms;
    }
    let plan =
        planner.compose_with_baseline_costs(choice.source, choice.destination, o.route, costs)?;
    Ok((plan, shared_ms))
}

/// Each combination's `execution_ms`: its own time `own_ms` plus an equal share of each piece of
/// shared work it used (its swarm's pre-composition, baseline costs and all-pairs result).
fn shared_out(own_ms: Vec<f64>, swarms: &Precomposed, baselines: &Baselines) -> Vec<f64> {
    let mut execution_ms = own_ms;
    let shared = swarms.work.iter().chain(
        baselines
            .swarms
            .iter()
            .flat_map(|e| [&e.edges, &e.all_pairs]),
    );
    for work in shared {
        for &i in &work.users {
            execution_ms[i] += work.ms / work.users.len() as f64;
        }
    }
    execution_ms
}

/// Milliseconds since `start`.
pub(super) fn elapsed_ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}
