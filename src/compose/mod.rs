//! Route composition (level 2): Algorithm 1 of the paper (sequential composition) and its A*-style
//! variant, the Dijkstra and Floyd–Warshall baselines with edge cost `tt + nt`, and the optimal
//! route over stop sequences (Dijkstra on the stop graph). See models/compose.md.
//! User guide: "Methods" (`docs/src/methods.md`) and the chapter "Route composition and the joint
//! optimum" (`docs/src/models/compose.md`).
//!
//! Every method produces a [`Plan`]: the hops flown between stops, the in-flight sharing schedule of
//! each hop, the node time and pad assignment at every recharging stop, and the delivery time
//! `dt = sum tt + sum nt`. A request the swarm cannot complete is a failed plan with its typed
//! outcome ([`PlanOutcome`]), never an error.
//!
//! Where a method of [`Planner`] goes: one file per route method (`sequential.rs`: Algorithm 1
//! and A*; `adjacent.rs`: Algorithm 1's literal candidates; `baselines.rs`: Dijkstra and
//! Floyd–Warshall; `optimal.rs`: the optimal route under the hop-path rule; `any_path.rs` and
//! `walks.rs`: over any hop path; `joint.rs`: the joint optimum under `exact`), or one per phase
//! that several methods share (`flight.rs`: flying one hop and the node time at its stop;
//! `split.rs`: the replays of a plan and the gap split; `studied.rs`: a hop taken out as a hop
//! file). A new route method gets a file of its own; a step two methods share goes to the file of
//! its phase. [`Context`] (`request.rs`, `grid.rs`) plans requests end to end with the planners.

mod adjacent;
mod any_path;
mod baselines;
mod factors;
mod flight;
mod gaps;
mod grid;
mod joint;
mod optimal;
mod plan;
mod request;
mod sequential;
mod split;
mod studied;
mod walks;

pub use any_path::MAX_HOP_PATH_LABELS;
pub use baselines::BaselineCosts;
pub use factors::{EdgeFactorCache, EdgeFactors};
pub use flight::{Flight, IntoShared, Planner};
pub use gaps::{lpt_gap, lpt_node_time_gaps, LptGapSummary, RouteGapSummary, RoutePair};
pub use plan::{Hop, LegFlown, Plan, PlanOutcome, RouteOptimality, Stop};
pub use request::{
    Context, PlanOptions, PlanSettings, RequestReport, RouteGap, SwarmChoice,
    ALL_PAIRS_BYTES_PER_PAIR, FLOYD_WARSHALL_MAX_NODES,
};
pub use split::{
    GapSplit, JointOptimum, JointSplit, SplitLabel, SwarmDt, SwarmOptimum, SwarmsCompared,
};

use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::problem::Candidates;
use serde::{Deserialize, Serialize};

/// How the route is composed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum RouteMethod {
    /// Algorithm 1: go straight to the destination if possible (without, then with sharing), else
    /// stop at the reachable recharging node with the least `tt + nt`.
    Sequential,
    /// Algorithm 1 with the remaining shortest-path travel time to the destination added to each
    /// candidate's `tt + nt` (A*-style look-ahead).
    Astar,
    /// Fixed route: Dijkstra on edge cost `tt + nt`.
    Dijkstra,
    /// Fixed route: Floyd–Warshall all-pairs on edge cost `tt + nt`.
    FloydWarshall,
    /// The least delivery time over every sequence of stops (Dijkstra on the stop graph, each
    /// hop along the shortest path between its stops, under the sharing policy): the proven
    /// optimum the heuristics are measured against; under `exact`, the joint optimum over stop
    /// sequences, sharing schedules and pad assignments. Not with `fair`. Not part of `--all`
    /// (the paper's grid): asked for by name.
    Optimal,
}

display_as_value_name!(RouteMethod);

/// Which paths the hops of `--route optimal` may follow between two stops (models/compose.md,
/// "Optimal route").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum HopPaths {
    /// The shortest path by distance between the two stops, as Algorithm 1 and A* fly.
    #[default]
    Rule,
    /// Every walk the swarm can fly from full batteries: a resource-constrained shortest path
    /// per stop without in-flight sharing (policies `none` and `idle-support`), a best-first
    /// search of walks per arc of the joint optimum (`exact`).
    Any,
}

display_as_value_name!(HopPaths);

/// Algorithm 1's cost of a candidate stop: `tt + nt`, or with A* also the remaining
/// shortest-path travel time to the destination.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LookAhead {
    /// `tt + nt` (Algorithm 1).
    None,
    /// `tt + nt` plus the remaining shortest-path travel time (A*).
    RemainingTravelTime,
}

/// How a fixed baseline route is found on edge cost `tt + nt`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum FixedRoute {
    /// One-pair shortest path (Dijkstra).
    Dijkstra,
    /// All-pairs shortest paths (Floyd–Warshall), read for the one pair.
    FloydWarshall,
}

display_as_value_name!(FixedRoute);

impl RouteMethod {
    /// The paper's methods, in a fixed order: the grid of `batch --all`. [`RouteMethod::Optimal`]
    /// is not one of them and is asked for by name (`--route optimal`).
    pub const ALL: [RouteMethod; 4] = [
        RouteMethod::Sequential,
        RouteMethod::Astar,
        RouteMethod::Dijkstra,
        RouteMethod::FloydWarshall,
    ];
}

impl Planner {
    /// Composes the route of one request from node index `source` to `destination`.
    ///
    /// # Arguments
    /// * `source`, `destination`: node indices of the planner's graph.
    /// * `method`: the route method.
    ///
    /// # Returns
    /// A [`Plan`]; `plan.outcome` says why when the swarm cannot deliver ([`PlanOutcome`]).
    ///
    /// # Errors
    /// [`crate::error::Error::Invalid`] E0015 for [`RouteMethod::Optimal`] with the fair policy; else
    /// only for malformed internal problems (a bug or inconsistent input that escaped
    /// validation).
    ///
    /// # Complexity
    /// Sequential/A*: at most one step per recharging node, each step one Dijkstra tree and one
    /// hop simulation per recharging node. Dijkstra and Floyd–Warshall: one hop simulation and one
    /// exact node time per directed edge for the `tt + nt` costs, then one Dijkstra, or
    /// Floyd–Warshall's O(|V|^3). Optimal: see [`RouteMethod::Optimal`] and models/compose.md;
    /// at most one hop simulation and one exact node time per pair of recharging nodes.
    pub fn compose(
        &self,
        source: usize,
        destination: usize,
        method: RouteMethod,
    ) -> crate::error::Result<Plan> {
        self.compose_with(source, destination, method, None)
    }

    /// [`Planner::compose`] with the fixed-route baselines' edge costs given instead of computed:
    /// the same plan, for the price of the route alone. The costs of one swarm serve every planner
    /// of that swarm, whatever its sharing policy, and both Dijkstra and Floyd–Warshall
    /// (Floyd–Warshall's all-pairs result is kept in `costs` and read for every later pair).
    ///
    /// # Arguments
    /// * `source`, `destination`, `method`: as [`Planner::compose`].
    /// * `costs`: from [`Planner::baseline_costs`] of a planner on the same graph and profile,
    ///   with the same swarm and node limit; used only by the fixed-route methods.
    ///
    /// # Errors
    /// As [`Planner::compose`]; E0018 when `costs` belong to another swarm.
    ///
    /// # Complexity
    /// As [`Planner::compose`], without the edge costs of the fixed routes: Dijkstra O(|E| log |V|);
    /// Floyd–Warshall O(|V|^3) for the first route on `costs`, O(|V|) for the others.
    pub fn compose_with_baseline_costs(
        &self,
        source: usize,
        destination: usize,
        method: RouteMethod,
        costs: &BaselineCosts,
    ) -> crate::error::Result<Plan> {
        if costs.swarm() != self.swarm() {
            return Err(crate::error::Error::invalid(
                "E0018",
                "costs",
                "the baseline costs were computed for another swarm",
                "compute them with Planner::baseline_costs of a planner with this planner's swarm",
            ));
        }
        self.compose_with(source, destination, method, Some(costs))
    }

    fn compose_with(
        &self,
        source: usize,
        destination: usize,
        method: RouteMethod,
        costs: Option<&BaselineCosts>,
    ) -> crate::error::Result<Plan> {
        let adjacent = self.readings().candidates == Candidates::Adjacent;
        let mut solves = HopSolveCounts::default();
        let solves = &mut solves;
        let mut plan = match method {
            RouteMethod::Sequential if adjacent => {
                self.compose_adjacent(source, destination, LookAhead::None, solves)
            }
            RouteMethod::Astar if adjacent => {
                self.compose_adjacent(source, destination, LookAhead::RemainingTravelTime, solves)
            }
            RouteMethod::Sequential => {
                self.compose_sequential(source, destination, LookAhead::None, solves)
            }
            RouteMethod::Astar => {
                self.compose_sequential(source, destination, LookAhead::RemainingTravelTime, solves)
            }
            RouteMethod::Dijkstra => {
                self.compose_fixed_route(source, destination, FixedRoute::Dijkstra, costs, solves)
            }
            RouteMethod::FloydWarshall => self.compose_fixed_route(
                source,
                destination,
                FixedRoute::FloydWarshall,
                costs,
                solves,
            ),
            RouteMethod::Optimal if self.sharing() == SharingPolicy::Exact => {
                self.compose_joint(source, destination, self.hop_paths(), solves)
            }
            RouteMethod::Optimal if self.hop_paths() == HopPaths::Any => {
                self.compose_optimal_any_path(source, destination, solves)
            }
            RouteMethod::Optimal => self.compose_optimal(source, destination, solves),
        }?;
        if self.sharing().is_exact() {
            plan.hop_solves = Some(*solves);
        }
        Ok(plan)
    }
}
