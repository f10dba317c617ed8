//! The joint optimum of a request over swarms, stop sequences, sharing schedules and pads, and
//! every heuristic plan's gap to it split into its causes: sharing schedule, route, swarm. See
//! models/compose.md, "Gap split".

use super::optimal::least_unsettled;
use super::plan::{Plan, PlanOutcome, RouteOptimality};
use super::request::{elapsed_ms, Context, RequestReport};
use super::{PlanOptions, Planner, RouteMethod};
use crate::eaas::exact::Reorder;
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::HopSolveCounts;
use crate::eaas::SharingPolicy;
use crate::error::Result;
use crate::precompose::Positioning;
use crate::problem::Request;
use serde::{Deserialize, Serialize};
use std::time::Instant;

/// One swarm the joint optimum considers, and its optimum under `--sharing exact`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwarmOptimum {
    /// The support positioning the swarm was pre-composed with.
    pub positioning: Positioning,
    /// Support drones flown.
    pub support_drones: usize,
    /// The optimal route of the swarm under `--sharing exact` (`--route optimal`).
    pub plan: Plan,
}

impl SwarmOptimum {
    /// The optimum's delivery time, when it delivers.
    pub fn dt_min(&self) -> Option<f64> {
        self.plan.delivered().then_some(self.plan.dt_min)
    }

    fn optimality(&self) -> RouteOptimality {
        self.plan.route_optimality.unwrap_or_default()
    }
}

/// The joint optimum of one request: the least delivery time over the swarms of
/// pre-composition (each positioning, and the swarm without support drones), stop sequences
/// (hops along the hop-path rule), continuous-time sharing schedules and pad assignments.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointOptimum {
    /// Every swarm's optimum, in the order location-aware, energy-aware (for each support
    /// count asked), then without support drones; a swarm equal to an earlier one is left out.
    pub swarms: Vec<SwarmOptimum>,
    /// Index in `swarms` of the least delivery time (the first among equals); `None` when no
    /// swarm delivers.
    pub best: Option<usize>,
    /// Whether every swarm's optimum is proven (every node time and hop solve of every search).
    pub proven: bool,
    /// The certified distance of the best swarm's `dt` to its infimum, min (0 when attained).
    pub epsilon_min: f64,
    /// Wall-clock time of the searches and the replays, ms (not reproducible).
    pub execution_ms: f64,
}

impl JointOptimum {
    /// The joint optimum's delivery time, when some swarm delivers.
    pub fn dt_min(&self) -> Option<f64> {
        self.best.and_then(|b| self.swarms[b].dt_min())
    }
}

/// The swarms an optimum ranged over (`solve --swarm best`) and each one's optimum: the plan
/// printed is the best one's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwarmsCompared {
    /// The support drones asked (`--support`; `None`: the redundancy table's count), with which
    /// both positionings were pre-composed.
    pub support: Option<usize>,
    /// Every swarm, in [`JointOptimum::swarms`]' order.
    pub swarms: Vec<SwarmDt>,
    /// Index in `swarms` of the least delivery time (the first among equals); `None` when no
    /// swarm delivers.
    pub best: Option<usize>,
}

/// One swarm's optimum under `--route optimal --sharing exact`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SwarmDt {
    /// The support positioning the swarm was pre-composed with.
    pub positioning: Positioning,
    /// Support drones flown.
    pub support_drones: usize,
    /// The optimum's delivery time, min; `None` when the swarm does not deliver.
    pub dt_min: Option<f64>,
    /// Whether every solve of the swarm's search is proven.
    pub proven: bool,
    /// The certified distance of `dt_min` to the swarm's infimum, min (0 when attained).
    pub epsilon_min: f64,
}

impl SwarmsCompared {
    /// The swarms of `j`, the joint optimum of [`Context::joint_optimum`] with `support`.
    pub fn new(j: &JointOptimum, support: Option<usize>) -> SwarmsCompared {
        SwarmsCompared {
            support,
            swarms: j
                .swarms
                .iter()
                .map(|s| SwarmDt {
                    positioning: s.positioning,
                    support_drones: s.support_drones,
                    dt_min: s.dt_min(),
                    proven: s.optimality().proven(),
                    epsilon_min: s.optimality().epsilon_min,
                })
                .collect(),
            best: j.best,
        }
    }
}

/// Why a heuristic plan's gap is not split.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SplitLabel {
    /// The heuristic plan does not deliver.
    NotDelivered,
    /// The plan's route flown with exact schedules ended unproven and did not deliver, or its
    /// swarm's optimum did not deliver what the replay delivered (a hop solve stopped by a
    /// limit): no part is taken.
    Unproven,
    /// The joint optimum does not deliver (nor, then, does the heuristic).
    NoReference,
    /// A hop of the plan swaps slots, which `--reorder none` does not contain: no part is taken.
    DifferentPolicy,
    /// A hop of the plan follows another path than the hop-path rule's (Dijkstra and
    /// Floyd–Warshall can): only the sharing part is taken, the route is outside the joint
    /// optimum's routes.
    OutsideReference,
}

/// A heuristic plan's gap to the joint optimum, `total = sharing + route + swarm` (min).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GapSplit {
    /// Set when some part is not taken, and why.
    pub label: Option<SplitLabel>,
    /// The plan's stop sequence flown again with the exact schedule on every hop (same hop
    /// paths, the exact node time at each stop), its `dt`, min.
    pub exact_schedule_dt_min: Option<f64>,
    /// The optimum of the plan's own swarm under `--sharing exact`, min.
    pub swarm_optimum_dt_min: Option<f64>,
    /// The joint optimum, min.
    pub joint_dt_min: Option<f64>,
    /// `dt - dt_joint`.
    pub total_min: Option<f64>,
    /// `dt - exact_schedule_dt`: what the heuristic's sharing schedules cost on its own route.
    pub sharing_min: Option<f64>,
    /// `exact_schedule_dt - swarm_optimum_dt`: what the route choice costs once every hop is
    /// flown optimally.
    pub route_min: Option<f64>,
    /// `swarm_optimum_dt - joint_dt`: what pre-composition's swarm (positioning, support
    /// drones) costs against the best of the swarms considered.
    pub swarm_min: Option<f64>,
    /// The parts are `>= -epsilon_min` (0 when every hop optimum is attained): the certified
    /// distances of the exact-schedule replay, of the plan's swarm's optimum and of the best
    /// swarm's, summed.
    pub epsilon_min: f64,
    /// Whether every solve behind the three references (the replay, the plan's swarm's optimum,
    /// the best swarm's) is proven.
    pub proven: bool,
}

/// The joint optimum of a request and each report's gap split against it.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSplit {
    /// The joint optimum.
    pub joint: JointOptimum,
    /// One per report: `None` for a report planned with `exact` or `fair` sharing or with
    /// `--route optimal` (a reference, not a heuristic).
    pub splits: Vec<Option<GapSplit>>,
}

/// Every swarm's optimum, with what made it: the swarms' choices and their planners under
/// `exact` (which the replays of the gap split reuse).
struct Optima {
    choices: Vec<(Positioning, super::SwarmChoice)>,
    planners: Vec<Planner>,
    swarms: Vec<SwarmOptimum>,
    best: Option<usize>,
}

impl Optima {
    /// The joint optimum, `execution_ms` the time it took.
    fn joint(self, execution_ms: f64) -> JointOptimum {
        let proven = self.swarms.iter().all(|s| s.optimality().proven());
        let epsilon_min = self
            .best
            .map_or(0.0, |b| self.swarms[b].optimality().epsilon_min);
        JointOptimum {
            swarms: self.swarms,
            best: self.best,
            proven,
            epsilon_min,
            execution_ms,
        }
    }
}

impl Context {
    /// The joint optimum of `request` and the gap split of every heuristic report among
    /// `reports` (plans of this request in this context).
    ///
    /// The swarms considered: pre-composition's under location- and energy-aware positioning
    /// for every support count the reports ask (`PlanOptions::support`), then the swarm without
    /// support drones (the paper's baseline). Each is planned with `--route optimal --sharing
    /// exact` ([`Planner::compose`]); one planner per swarm serves its optimum and the replays
    /// of the reports flying it, so a hop both fly is solved once.
    ///
    /// # Errors
    /// Those of [`Context::swarm_for`], [`Planner::compose`] and the hop solves.
    pub fn joint_split(&self, request: &Request, reports: &[RequestReport]) -> Result<JointSplit> {
        let start = Instant::now();
        let supports: Vec<Option<usize>> = reports.iter().map(|r| r.options.support).collect();
        let Optima {
            choices,
            planners,
            swarms,
            best,
        } = self.swarm_optima(request, &supports)?;
        let mut splits = Vec::with_capacity(reports.len());
        for report in reports {
            let o = report.options;
            if o.route == RouteMethod::Optimal || o.sharing.is_exact() {
                splits.push(None);
                continue;
            }
            let s = choices
                .iter()
                .position(|(_, c)| c.swarm == report.swarm)
                .expect("every report's swarm is among the swarms considered");
            let best_swarm = best.map(|b| &swarms[b]);
            splits.push(Some(self.split_one(
                report,
                &planners[s],
                &swarms[s],
                best_swarm,
            )?));
        }
        let optima = Optima {
            choices,
            planners,
            swarms,
            best,
        };
        Ok(JointSplit {
            joint: optima.joint(elapsed_ms(start)),
            splits,
        })
    }

    /// The joint optimum of `request` alone: the least delivery time over the swarms of
    /// pre-composition under location- and energy-aware positioning with `support` support
    /// drones (`None`: the redundancy table's count), and the swarm without support drones,
    /// each planned with `--route optimal --sharing exact` (what `solve --swarm best` answers).
    ///
    /// # Errors
    /// Those of [`Context::swarm_for`], [`Planner::compose`] and the hop solves.
    pub fn joint_optimum(&self, request: &Request, support: Option<usize>) -> Result<JointOptimum> {
        let start = Instant::now();
        let optima = self.swarm_optima(request, &[support])?;
        Ok(optima.joint(elapsed_ms(start)))
    }

    /// `solve --swarm best`: the plan of the best swarm of [`Context::joint_optimum`] with
    /// `options.support` (the swarm of `options` when none delivers), every swarm's optimum in
    /// `swarms_compared`. `options` are `--route optimal --sharing exact`'s; the plan's options
    /// name the best swarm's positioning and support drones.
    ///
    /// # Errors
    /// Those of [`Context::joint_optimum`] and [`Context::plan`].
    pub fn plan_best_swarm(
        &self,
        request: &Request,
        options: &PlanOptions,
    ) -> Result<RequestReport> {
        let joint = self.joint_optimum(request, options.support)?;
        let chosen = match joint.best {
            Some(b) => PlanOptions {
                positioning: joint.swarms[b].positioning,
                support: Some(joint.swarms[b].support_drones),
                ..*options
            },
            None => *options,
        };
        let mut report = self.plan(request, &chosen)?;
        report.swarms_compared = Some(SwarmsCompared::new(&joint, options.support));
        Ok(report)
    }

    /// Every swarm's optimum under `--route optimal --sharing exact`: location- and
    /// energy-aware positioning for each support count of `supports` (the redundancy table's
    /// when empty), then the swarm without support drones; a swarm equal to an earlier one is
    /// left out.
    fn swarm_optima(&self, request: &Request, supports: &[Option<usize>]) -> Result<Optima> {
        let mut keys: Vec<(Positioning, Option<usize>)> = Vec::new();
        for &support in supports {
            for positioning in [Positioning::LocationAware, Positioning::EnergyAware] {
                let key = (positioning, support);
                if !keys.contains(&key) {
                    keys.push(key);
                }
            }
        }
        if keys.is_empty() {
            keys.push((Positioning::LocationAware, None));
            keys.push((Positioning::EnergyAware, None));
        }
        keys.push((Positioning::LocationAware, Some(0)));
        let mut choices = Vec::new();
        for (positioning, support) in keys {
            let choice = self.swarm_for(request, positioning, support)?;
            if !choices
                .iter()
                .any(|(_, c): &(Positioning, super::SwarmChoice)| c.swarm == choice.swarm)
            {
                choices.push((positioning, choice));
            }
        }
        let planners: Vec<Planner> = choices
            .iter()
            .map(|(_, c)| self.planner(&c.swarm, SharingPolicy::Exact))
            .collect();
        let mut swarms = Vec::with_capacity(choices.len());
        for ((positioning, choice), planner) in choices.iter().zip(&planners) {
            let plan = planner.compose(choice.source, choice.destination, RouteMethod::Optimal)?;
            swarms.push(SwarmOptimum {
                positioning: *positioning,
                support_drones: choice.support_drones,
                plan,
            });
        }
        // The least dt, the first swarm among equals.
        let dts: Vec<f64> = swarms
            .iter()
            .map(|s| s.dt_min().unwrap_or(f64::INFINITY))
            .collect();
        let best = least_unsettled(&dts, &vec![false; dts.len()]);
        Ok(Optima {
            choices,
            planners,
            swarms,
            best,
        })
    }

    /// The gap split of one heuristic report whose swarm `planner` flies under `exact`, with
    /// that swarm's optimum `own` and the best swarm's, the joint optimum (`None` when no swarm
    /// delivers).
    fn split_one(
        &self,
        report: &RequestReport,
        planner: &Planner,
        own: &SwarmOptimum,
        best: Option<&SwarmOptimum>,
    ) -> Result<GapSplit> {
        let plan = &report.plan;
        let joint_dt = best.and_then(SwarmOptimum::dt_min);
        // The references: the own swarm's optimum and, when another, the best swarm's.
        let mut references = vec![own.optimality()];
        if let Some(b) = best.filter(|b| !std::ptr::eq(*b, own)) {
            references.push(b.optimality());
        }
        let mut split = GapSplit {
            label: None,
            exact_schedule_dt_min: None,
            swarm_optimum_dt_min: own.dt_min(),
            joint_dt_min: joint_dt,
            total_min: None,
            sharing_min: None,
            route_min: None,
            swarm_min: None,
            epsilon_min: references.iter().map(|o| o.epsilon_min).sum(),
            proven: references.iter().all(RouteOptimality::proven),
        };
        let Some(joint_dt) = joint_dt else {
            split.label = Some(SplitLabel::NoReference);
            return Ok(split);
        };
        if !plan.delivered() {
            split.label = Some(SplitLabel::NotDelivered);
            return Ok(split);
        }
        let swaps = plan
            .hops
            .iter()
            .flat_map(|h| &h.transfers)
            .any(|t| t.consumer_slot != report.swarm.initial_slot[t.consumer]);
        if swaps && self.exact.milp.reorder == Reorder::None {
            split.label = Some(SplitLabel::DifferentPolicy);
            return Ok(split);
        }
        let replay = planner.replay_exact(plan)?;
        if !replay.plan.delivered() {
            if !replay.proven {
                split.label = Some(SplitLabel::Unproven);
                return Ok(split);
            }
            // The exact model contains the heuristic's schedules: a bug if reached.
            return Err(crate::error::Error::internal(
                "E0019",
                format!(
                    "request {}: the exact schedules do not fly the {} plan's route ({})",
                    report.request.id,
                    o_name(report),
                    replay.plan.outcome
                ),
            ));
        }
        split.exact_schedule_dt_min = Some(replay.plan.dt_min);
        split.sharing_min = Some(plan.dt_min - replay.plan.dt_min);
        split.epsilon_min += replay.epsilon_min;
        split.proven &= replay.proven;
        if !replay.rule_paths {
            split.label = Some(SplitLabel::OutsideReference);
            return Ok(split);
        }
        let Some(own_dt) = own.dt_min() else {
            // The search refused an arc the replay flies: only a limit can do that.
            if !split.proven {
                split.label = Some(SplitLabel::Unproven);
                return Ok(split);
            }
            return Err(crate::error::Error::internal(
                "E0019",
                format!(
                    "request {}: the {} plan's route flies with exact schedules, its swarm's \
                     proven optimum does not deliver",
                    report.request.id,
                    o_name(report)
                ),
            ));
        };
        split.route_min = Some(replay.plan.dt_min - own_dt);
        split.swarm_min = Some(own_dt - joint_dt);
        split.total_min = Some(plan.dt_min - joint_dt);
        Ok(split)
    }
}

fn o_name(report: &RequestReport) -> String {
    let o = report.options;
    format!("{}/{}/{}", o.sharing, o.positioning, o.route)
}

/// A plan's stop sequence flown again under the planner's policy.
pub(crate) struct Replay {
    /// The plan flown again.
    pub(crate) plan: Plan,
    /// Whether every hop follows the hop-path rule between its stops.
    pub(crate) rule_paths: bool,
    /// The summed certified distances of the hops' node times to their infima, min.
    pub(crate) epsilon_min: f64,
    /// Whether every hop solve and node time is proven.
    pub(crate) proven: bool,
}

impl Planner {
    /// Flies the stop sequence and hop paths of `plan` (a plan of this planner's swarm) again
    /// under this planner's policy, every hop from full batteries, with the exact node time at
    /// each stop; into the destination without sharing when that flies, as Algorithm 1 does.
    ///
    /// # Errors
    /// E0019 ([`crate::error::Error::Internal`]) when a hop path of `plan` is not a network path; those of
    /// [`Planner::fly`] and [`Planner::stop_at`].
    pub(crate) fn replay_exact(&self, plan: &Plan) -> Result<Replay> {
        // The replay's solves are not a composition's: counted here and dropped.
        let mut solves = HopSolveCounts::default();
        let solves = &mut solves;
        let graph = self.graph();
        let full = self.full_battery_mah();
        let index = |id: &str| graph.index_of(id);
        let (source, destination) = match (index(&plan.source), index(&plan.destination)) {
            (Some(s), Some(d)) => (s, d),
            _ => return Err(not_a_path(&plan.source)),
        };
        let mut replay = Replay {
            plan: self.empty_plan(source, destination),
            rule_paths: true,
            epsilon_min: 0.0,
            proven: true,
        };
        let mut optimality = RouteOptimality::default();
        for hop in &plan.hops {
            let nodes: Vec<usize> = hop.path.iter().filter_map(|id| index(id)).collect();
            let path = graph
                .path_from_nodes(&nodes)
                .filter(|_| nodes.len() == hop.path.len())
                .ok_or_else(|| not_a_path(&hop.from))?;
            let (u, v) = (nodes[0], *nodes.last().expect("a path has nodes"));
            let rule = match hop.stop {
                Some(_) => graph.shortest_paths_to(u).reversed_path_from(v),
                None => graph.shortest_path(u, v),
            };
            replay.rule_paths &= rule.is_some_and(|r| r.nodes == path.nodes);
            let arc = match hop.stop {
                Some(_) => self
                    .arc_into_stop(u, v, path.clone(), &full, &mut optimality, solves)?
                    .map(|a| (a.flight, a.stop, a.epsilon_min)),
                None => self
                    .fly_to_destination(&path, &full, &mut optimality, solves)?
                    .0
                    .map(|f| (f, None, 0.0)),
            };
            let Some((flight, stop, epsilon_min)) = arc else {
                // The flight that failed, from the planner's cache.
                let goal = match hop.stop {
                    Some(_) => HopGoal::NodeTimeMin,
                    None => HopGoal::Feasible,
                };
                let failure = self
                    .fly_counted(&path, &full, self.sharing(), goal, solves)?
                    .outcome
                    .failure;
                replay.proven &= optimality.proven();
                replay.plan = replay.plan.fail(PlanOutcome::HopInfeasible {
                    from: hop.from.clone(),
                    to: hop.to.clone(),
                    failure: failure.ok_or_else(|| {
                        crate::error::Error::internal(
                            "E0019",
                            format!(
                                "the hop from {} does not fly and reports no failure",
                                hop.from
                            ),
                        )
                    })?,
                });
                return Ok(replay);
            };
            replay.epsilon_min += epsilon_min;
            replay.plan.push(self.hop(&path, &full, flight, stop));
        }
        replay.proven &= optimality.proven();
        replay.plan = replay.plan.finish();
        Ok(replay)
    }
}

fn not_a_path(at: &str) -> crate::error::Error {
    crate::error::Error::internal(
        "E0019",
        format!("the plan's hop from {at} is not a path of the network"),
    )
}
