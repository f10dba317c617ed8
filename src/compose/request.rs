//! Planning one request end to end: pre-composition (formation, support drones, positions) then
//! route composition.

use super::{EdgeFactorCache, Plan, Planner, RouteMethod};
use crate::eaas::exact_hop::ExactSettings;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::{self, Positioning, SupportDecision};
use crate::problem::FormationKind;
use crate::problem::SkywayGraph;
use crate::problem::Swarm;
use crate::problem::Wind;
use crate::problem::{Network, Profile, Request, MAX_SUPPORT_DRONES, SCHEMA_VERSION};
use serde::{Deserialize, Serialize};
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

/// What is fixed for every request on one network with one profile.
pub struct Context<'a> {
    graph: &'a SkywayGraph,
    profile: &'a Profile,
    /// The fixed formation, selected from the network's averaged wind.
    pub formation: FormationKind,
    /// The network's averaged wind.
    pub average_wind: Wind,
    /// Solver settings of the exact and fair sharing policies.
    pub exact: ExactSettings,
    /// Node limit of the exact node time at every stop (`None`: no limit), default
    /// [`crate::node_time::DEFAULT_STOP_NODE_LIMIT`].
    pub node_limit: Option<u64>,
    /// The energy model's leg factors, shared by every request's planner.
    factors: EdgeFactorCache,
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

impl<'a> Context<'a> {
    /// Selects the formation from the network's averaged wind.
    pub fn new(network: &Network, graph: &'a SkywayGraph, profile: &'a Profile) -> Context<'a> {
        let (formation, average_wind) = precompose::select_formation(network, profile);
        Context {
            graph,
            profile,
            formation,
            average_wind,
            exact: ExactSettings::default(),
            node_limit: Some(crate::node_time::DEFAULT_STOP_NODE_LIMIT),
            factors: EdgeFactorCache::new(graph),
        }
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
            self.profile,
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
            self.profile,
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

    /// Plans one validated request.
    ///
    /// # Errors
    /// [`Error::Invalid`] when the request names an unknown node (validate requests first to get
    /// every violation at once).
    pub fn plan(&self, request: &Request, options: &PlanOptions) -> Result<RequestReport> {
        let start = Instant::now();
        // The paper's baseline (`none`) is the swarm without support drones.
        let support = if options.sharing.flies_support() {
            options.support
        } else {
            Some(0)
        };
        let choice = self.swarm_for(request, options.positioning, support)?;
        let planner = Planner::new(self.graph, self.profile, &choice.swarm, options.sharing)
            .with_exact(self.exact)
            .with_node_limit(self.node_limit)
            .with_edge_factors(&self.factors);
        let plan = planner.compose(choice.source, choice.destination, options.route)?;
        let execution_ms = start.elapsed().as_secs_f64() * 1e3;
        Ok(RequestReport {
            schema_version: SCHEMA_VERSION,
            request: request.clone(),
            options: *options,
            formation: self.formation,
            support_decision: choice.support_decision,
            support_drones: choice.support_drones,
            swarm: choice.swarm,
            plan,
            execution_ms,
        })
    }
}
