//! The output of route composition.

use crate::eaas::exact_hop::{HopSolve, HopSolveCounts};
use crate::eaas::{HopFailure, Transfer};
use crate::problem::Candidates;
use crate::solver::SolveStatus;
use serde::{Deserialize, Serialize};
use std::fmt;

/// A composed delivery plan for one request.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// Source node id.
    pub source: String,
    /// Destination node id.
    pub destination: String,
    /// Whether the swarm reaches the destination, and if not, why: see [`PlanOutcome`].
    pub outcome: PlanOutcome,
    /// Hops flown, each from one stop (or the source) to the next stop (or the destination).
    pub hops: Vec<Hop>,
    /// Total travel time, min: sum of the hops' `tt`.
    pub tt_min: f64,
    /// Total node time, min: sum of the stops' `nt`.
    pub nt_min: f64,
    /// Delivery time `dt = tt + nt`, min (of the part flown, for a failed plan).
    pub dt_min: f64,
    /// Energy shared in flight over the whole plan, mAh.
    pub shared_mah: f64,
    /// Exact and fair policies: how every hop solve made while composing ended, candidate hops
    /// included (a hop flown twice from full batteries is solved once and counted twice).
    /// `all_proven` in these counts is what makes the route's schedules optimal over
    /// continuous-time schedules.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hop_solves: Option<HopSolveCounts>,
    /// `--route optimal`: the search of the stop graph, and whether the route is proven optimal.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub route_optimality: Option<RouteOptimality>,
}

/// What the optimal route's search of the stop graph did (`--route optimal`,
/// models/compose.md): the route is the least delivery time over stop sequences when every
/// stop solved while searching was solved to optimality (`stops_unproven == 0`) and, under
/// `--sharing exact`, every hop solve was proven (`hop_solves_unproven == 0`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RouteOptimality {
    /// Nodes with pads settled before the destination (their out-arcs flown).
    pub stops_settled: usize,
    /// Hops flown while searching (arcs evaluated), the route's included.
    pub arcs_flown: usize,
    /// Exact node times solved at the heads of flyable arcs.
    pub stops_solved: usize,
    /// Of those, the stops whose solve the node limit stopped (an incumbent, status
    /// `feasible`): when not 0 the route is optimal only for the node times found.
    pub stops_unproven: usize,
    /// The paths the hops could follow: `rule` (the shortest path by distance between the two
    /// stops) or `any` (every path flyable from full batteries).
    #[serde(default)]
    pub hop_paths: super::HopPaths,
    /// `any`: labels created by the searches of hop paths (one search per settled stop).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub hop_path_labels: usize,
    /// `--sharing exact`: rounds of the lazy search (a Dijkstra on the stop graph each).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub rounds: usize,
    /// `--sharing exact`: arcs whose lower bound was taken from their path's legs.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub arcs_bounded: usize,
    /// `--sharing exact`: arcs into a stop whose lower bound was then taken from an LP (`l2`:
    /// the configuration LP with its pads relaxed, or the fluid LP where that tells nothing; the
    /// name is the field's first meaning).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub arcs_fluid_bounded: usize,
    /// `--sharing exact`: arcs of the stop graph (`arcs_flown` of them were flown).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub arcs_total: usize,
    /// `--sharing exact`: hop solves of the search that ended unproven (a time limit, a backend
    /// failure, a fallback to the empty schedule, or a node time the node limit stopped).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub hop_solves_unproven: usize,
    /// `--sharing exact --hop-paths any`: arcs whose search of walks reached
    /// [`super::MAX_HOP_PATH_LABELS`] partial walks and stopped: when not 0 the route is
    /// optimal only over the walks those searches built.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub arcs_capped: usize,
    /// `--sharing exact`: the certified distance of the route's `dt` to the infimum over
    /// continuous-time schedules, min: the sum over its hops of the distance of each hop's node
    /// time to its infimum (0 when every optimum is attained, written only when not 0).
    #[serde(default, skip_serializing_if = "is_zero_min")]
    pub epsilon_min: f64,
}

fn is_zero_min(x: &f64) -> bool {
    *x == 0.0
}

fn is_zero(n: &usize) -> bool {
    *n == 0
}

impl RouteOptimality {
    /// Whether every node time and hop solve of the search was proven optimal and no search of
    /// walks was capped, so the route is the proven optimum over stop sequences.
    pub fn proven(&self) -> bool {
        self.stops_unproven == 0 && self.hop_solves_unproven == 0 && self.arcs_capped == 0
    }
}

/// How a plan ends: delivered, or the kind of failure with its data. In JSON a tagged object,
/// `{"kind": "dead-end", "node": "n012", ...}`; [`fmt::Display`] gives a sentence.
///
/// A failed plan keeps the hops flown before the failure (every one of them flyable), so its
/// `dt` is that of the part flown.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum PlanOutcome {
    /// The swarm reaches the destination.
    Delivered,
    /// No path of the network joins the node the swarm is at to the destination.
    NoRoute {
        /// Node id the swarm is at (the source, for a route never started).
        from: String,
        /// The destination.
        to: String,
    },
    /// Algorithm 1 (`sequential`, `astar`): at `node` the swarm can reach neither the destination
    /// nor any candidate stop without stopping.
    DeadEnd {
        /// Node id the swarm is at.
        node: String,
        /// Which candidates were exhausted: recharging nodes not yet stopped at (`pad-nodes`),
        /// or neighbours not yet visited (`adjacent`).
        candidates: Candidates,
        /// The first failure of the direct flight from `node` to the destination (with sharing,
        /// when the policy shares).
        direct: HopFailure,
    },
    /// Fixed route (`dijkstra`, `floyd-warshall`): the next pad node or the destination on the
    /// route cannot be reached from `from` without stopping.
    HopInfeasible {
        /// Node id the swarm is at.
        from: String,
        /// The next pad node, or the destination, on the route.
        to: String,
        /// The hop's first failure: the failing drone and when.
        failure: HopFailure,
    },
    /// Optimal route (`optimal`): no sequence of stops reaches the destination from the source,
    /// though a path of the network joins them. No hop is flown.
    NoStopSequence {
        /// The source.
        from: String,
        /// The destination.
        to: String,
        /// Nodes with pads the swarm can reach from the source with stops on the way.
        stops_reached: usize,
        /// The first failure of the direct flight from the source to the destination (with
        /// sharing, when the policy shares).
        direct: HopFailure,
    },
}

impl PlanOutcome {
    /// The kind as written in JSON (its `kind` tag): `delivered`, `no-route`, `dead-end`,
    /// `hop-infeasible`, `no-stop-sequence`.
    pub fn kind(&self) -> String {
        match serde_json::to_value(self) {
            Ok(serde_json::Value::Object(map)) => match map.get("kind") {
                Some(serde_json::Value::String(kind)) => kind.clone(),
                _ => String::new(),
            },
            _ => String::new(),
        }
    }

    /// Whether the swarm reaches the destination.
    pub fn is_delivered(&self) -> bool {
        *self == PlanOutcome::Delivered
    }
}

impl fmt::Display for PlanOutcome {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let first = |x: &HopFailure| {
            format!(
                "drone {} runs out of energy after {:.2} min",
                x.drone, x.time_min
            )
        };
        match self {
            PlanOutcome::Delivered => write!(f, "delivered"),
            PlanOutcome::NoRoute { from, to } => {
                write!(
                    f,
                    "no route from {from} to {to}: the network does not connect them"
                )
            }
            PlanOutcome::DeadEnd {
                node,
                candidates,
                direct,
            } => {
                let what = match candidates {
                    Candidates::PadNodes => "recharging node not yet stopped at",
                    Candidates::Adjacent => "neighbour not yet visited",
                };
                write!(
                    f,
                    "dead end at {node}: neither the destination nor any {what} is reachable \
                     without stopping (flying straight to the destination, {})",
                    first(direct)
                )
            }
            PlanOutcome::HopInfeasible { from, to, failure } => write!(
                f,
                "cannot reach {to} (next pad node or destination on the fixed route) from {from}: \
                 {}",
                first(failure)
            ),
            PlanOutcome::NoStopSequence {
                from,
                to,
                stops_reached,
                direct,
            } => write!(
                f,
                "no sequence of stops reaches {to} from {from}: {stops_reached} recharging nodes \
                 reached, none of them nor {from} reaches {to} without stopping (flying straight \
                 from {from}, {})",
                first(direct)
            ),
        }
    }
}

/// One hop: a flight without stopping between two stops, possibly over several edges.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Hop {
    /// Node id the hop starts at.
    pub from: String,
    /// Node id the hop ends at.
    pub to: String,
    /// Node ids flown over, `from` and `to` included.
    pub path: Vec<String>,
    /// Length, m.
    pub distance_m: f64,
    /// Travel time `tt`, min.
    pub tt_min: f64,
    /// The legs flown (one per network edge), in order, each with its own travel time and wind.
    pub legs: Vec<LegFlown>,
    /// In-flight energy transfers during the hop.
    pub transfers: Vec<Transfer>,
    /// Energy shared during the hop, mAh.
    pub shared_mah: f64,
    /// Battery of every drone (by drone id) at the start of the hop, mAh.
    pub departure_battery_mah: Vec<f64>,
    /// Battery of every drone at the end of the hop, mAh.
    pub arrival_battery_mah: Vec<f64>,
    /// Exact and fair policies: how the solve of this hop's schedule ended.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sharing_solve: Option<HopSolve>,
    /// The recharging stop at `to`; `None` at the destination.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop: Option<Stop>,
}

/// One leg of a hop: a network edge flown in one direction.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegFlown {
    /// Node id flown from.
    pub from: String,
    /// Node id flown to.
    pub to: String,
    /// Length, m.
    pub distance_m: f64,
    /// Travel time, min.
    pub tt_min: f64,
    /// Direction flown, degrees clockwise from north.
    pub heading_deg: f64,
    /// Wind speed on the edge, m/s.
    pub wind_speed_mps: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    pub wind_from_deg: f64,
}

/// A recharging stop: every drone charges to full on one of the node's pads.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stop {
    /// Node id.
    pub node: String,
    /// Pads at the node.
    pub pads: u32,
    /// Charge time `ct` of every drone (by drone id), min.
    pub charge_times_min: Vec<f64>,
    /// Node time `nt` = makespan of the pad assignment, min.
    pub nt_min: f64,
    /// Drone ids charged on each pad, in order.
    pub assignment: Vec<Vec<usize>>,
    /// Status of the node-time solve.
    pub status: SolveStatus,
}

impl Plan {
    pub(crate) fn new(source: String, destination: String) -> Plan {
        Plan {
            source,
            destination,
            // Replaced by `finish` or `fail` before the plan leaves the composer.
            outcome: PlanOutcome::Delivered,
            hops: Vec::new(),
            tt_min: 0.0,
            nt_min: 0.0,
            dt_min: 0.0,
            shared_mah: 0.0,
            hop_solves: None,
            route_optimality: None,
        }
    }

    pub(crate) fn push(&mut self, hop: Hop) {
        self.tt_min += hop.tt_min;
        self.shared_mah += hop.shared_mah;
        if let Some(stop) = &hop.stop {
            self.nt_min += stop.nt_min;
        }
        self.dt_min = self.tt_min + self.nt_min;
        self.hops.push(hop);
    }

    pub(crate) fn finish(mut self) -> Plan {
        self.outcome = PlanOutcome::Delivered;
        self
    }

    pub(crate) fn fail(mut self, outcome: PlanOutcome) -> Plan {
        self.outcome = outcome;
        self
    }

    /// Whether the swarm reaches the destination.
    pub fn delivered(&self) -> bool {
        self.outcome.is_delivered()
    }

    /// Node ids where the swarm stopped to recharge, in order.
    pub fn stops(&self) -> Vec<&str> {
        self.hops
            .iter()
            .filter_map(|h| h.stop.as_ref().map(|s| s.node.as_str()))
            .collect()
    }
}
