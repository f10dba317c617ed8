//! What the figure of a plan shows, computed from the plan document and the raw instance before
//! anything is drawn: the route on the network, every drone's battery against time over the
//! whole request, the in-flight transfers, the pad schedule of every stop and where the plan
//! fails. The drawing ([`super::draw`]) only places these numbers.
//!
//! Time runs in minutes since departure over the whole request: hops and node times back to
//! back. Within a hop the batteries are the independent checker's re-integration of the plan's
//! transfers as written ([`crate::check::battery_trajectory`]) on the hop problem rebuilt
//! from the instance ([`crate::check::rebuilt_hop_problem`]), exact at its breakpoints
//! and linear between them; at a stop each drone waits at its arrival battery until its pad
//! slot, then charges linearly to its capacity over its charge time `ct`, then waits full until
//! the node time `nt` ends.

use crate::check::battery_trajectory;
use crate::check::{optimal_makespan_min, rebuilt_hop_problem, OPTIMALITY_CHECK_DRONES};
use crate::compose::{Hop, Plan, PlanOutcome, RequestReport, Stop};
use crate::eaas::HopFailure;
use crate::error::{Error, Result};
use crate::problem::{Network, Profile, Role, Swarm};
use crate::solver::SolveStatus;
use std::collections::HashMap;

/// The unit of the battery axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BatteryUnit {
    /// mAh.
    Mah,
    /// Percent of the drone's capacity.
    Percent,
}

/// A figure: the network, one or two plans of the same request, and the ranges their panels
/// share.
#[derive(Debug, Clone, PartialEq)]
pub struct Figure {
    /// The network drawn under the routes.
    pub map: MapData,
    /// The plan, then the plan compared with it (`--compare`), if any.
    pub plans: Vec<PlanData>,
    /// The battery axis' unit.
    pub unit: BatteryUnit,
    /// Time axis of the battery panels, min since departure: `[0, end]` holding every point.
    pub time_range_min: (f64, f64),
    /// Battery axis of the battery panels (in `unit`), holding every point, 0 and every
    /// capacity.
    pub battery_range: (f64, f64),
    /// Time axis of the pad schedules, min since arrival at the stop: `[0, longest nt]`.
    pub stop_range_min: (f64, f64),
}

/// The network: every node and edge, to scale.
#[derive(Debug, Clone, PartialEq)]
pub struct MapData {
    /// `(id, x_m, y_m, pads)` of every node.
    pub nodes: Vec<(String, f64, f64, u32)>,
    /// Both ends of every edge, m.
    pub edges: Vec<((f64, f64), (f64, f64))>,
}

/// One plan's part of the figure.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanData {
    /// `sharing/positioning/route`.
    pub combination: String,
    /// The request's id.
    pub request_id: String,
    /// Source node id.
    pub source: String,
    /// Destination node id.
    pub destination: String,
    /// Delivery time, min (of the part flown, for a failed plan).
    pub dt_min: f64,
    /// Whether the swarm reaches the destination.
    pub delivered: bool,
    /// The outcome's kind (`delivered`, `dead-end`, ...).
    pub outcome_kind: String,
    /// The outcome as a sentence.
    pub outcome: String,
    /// Every hop's path as node coordinates, m.
    pub route: Vec<Vec<(f64, f64)>>,
    /// Every stop on the map: `(node, x_m, y_m, pads)`.
    pub stop_marks: Vec<(String, f64, f64, u32)>,
    /// Every drone's battery against time.
    pub drones: Vec<DroneSeries>,
    /// The in-flight transfers, on the request's time axis.
    pub transfers: Vec<TransferBand>,
    /// The stops, in order.
    pub stops: Vec<StopSchedule>,
    /// Where the plan fails, when a drone runs dry.
    pub failure: Option<FailureMark>,
    /// The node where a failed plan ends, with its coordinates, m.
    pub failed_at: Option<(String, f64, f64)>,
}

/// One drone's battery against time.
#[derive(Debug, Clone, PartialEq)]
pub struct DroneSeries {
    /// Drone id.
    pub drone: usize,
    /// Delivery or support.
    pub role: Role,
    /// Capacity in the figure's unit (100 in percent).
    pub capacity: f64,
    /// `(t, battery)`: min since departure, the figure's unit; linear in between.
    pub points: Vec<(f64, f64)>,
}

/// One in-flight transfer on the request's time axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TransferBand {
    /// Index of the hop.
    pub hop: usize,
    /// Giving support drone.
    pub support: usize,
    /// Receiving delivery drone.
    pub consumer: usize,
    /// Start, min since departure.
    pub start_min: f64,
    /// End, min since departure.
    pub end_min: f64,
    /// Energy moved, mAh.
    pub energy_mah: f64,
    /// Lowest and highest battery of the two drones over the transfer, the figure's unit.
    pub battery_span: (f64, f64),
}

/// A stop's pad schedule.
#[derive(Debug, Clone, PartialEq)]
pub struct StopSchedule {
    /// Node id.
    pub node: String,
    /// Pads at the node.
    pub pads: u32,
    /// Arrival, min since departure.
    pub arrival_min: f64,
    /// Node time `nt`, min.
    pub nt_min: f64,
    /// Status of the node-time solve.
    pub status: SolveStatus,
    /// The optimal node time, when known: `nt` itself for a stop solved to optimality, else
    /// found by exhaustive search for at most [`OPTIMALITY_CHECK_DRONES`] drones.
    pub optimum_min: Option<f64>,
    /// One bar per drone.
    pub bars: Vec<PadBar>,
}

/// A drone charging on a pad, min since arrival at the stop.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PadBar {
    /// Pad index (0-based).
    pub pad: usize,
    /// Drone id.
    pub drone: usize,
    /// Start of the charge.
    pub start_min: f64,
    /// End of the charge: start + `ct`.
    pub end_min: f64,
}

/// A drone running dry.
#[derive(Debug, Clone, PartialEq)]
pub struct FailureMark {
    /// The drone.
    pub drone: usize,
    /// When, min since departure.
    pub time_min: f64,
    /// What it was flying: "flying A -> B", "flying straight to B".
    pub flight: String,
}

/// `sharing/positioning/route`, with the support drones when the combination fixes them.
pub fn combination(report: &RequestReport) -> String {
    let o = &report.options;
    match o.support {
        Some(k) => format!("{}/{}/{}/{k} support", o.sharing, o.positioning, o.route),
        None => format!("{}/{}/{}", o.sharing, o.positioning, o.route),
    }
}

fn unfit(k: usize, what: &str) -> Error {
    Error::invalid(
        "E8003",
        format!("plan: hops[{k}]"),
        format!("the plan does not fit the instance given: {what}"),
        "plot the plan with the network and profile it was made on; `swarmplan check --plan` \
         with them names every rule it breaks",
    )
}

/// The plans of one figure, checked before anything is computed: each made on `network` and
/// `profile` (its `made_on` fingerprint, when it has one), and a compared plan answering the
/// same request as the plan.
///
/// # Errors
/// [`Error::Invalid`] E6004, E6005 for a plan made on another network, with another profile
/// (the checker's [`crate::check::made_on_another_instance`]); E8001 (field
/// `--compare`) for a second plan of another request (its id, ends or packages differ).
pub fn check_plans(network: &Network, profile: &Profile, reports: &[&RequestReport]) -> Result<()> {
    for r in reports {
        let mismatch = crate::check::made_on_another_instance(network, profile, r);
        if !mismatch.is_empty() {
            return Err(Error::Invalid(mismatch));
        }
    }
    match reports {
        [a, b] => same_request(a, b),
        _ => Ok(()),
    }
}

/// E8001 when the compared plan answers another request (its id, ends or packages differ).
fn same_request(a: &RequestReport, b: &RequestReport) -> Result<()> {
    if a.request == b.request {
        return Ok(());
    }
    let (x, y) = (&a.request, &b.request);
    Err(Error::invalid(
        "E8001",
        "--compare",
        format!(
            "a plan of another request: {} {} -> {} ({:?} kg) against {} {} -> {} ({:?} kg)",
            x.id,
            x.source,
            x.destination,
            x.packages_kg,
            y.id,
            y.source,
            y.destination,
            y.packages_kg
        ),
        "compare two plans of the same request, such as `solve ... --sharing pb --json` and \
         `solve ... --route optimal --sharing exact --json`",
    ))
}

/// The figure of `reports` (a plan, and the plan compared with it) on the instance.
///
/// # Arguments
/// * `network`, `profile` - the instance the plans were made on.
/// * `reports` - one or two plan documents of the same request.
/// * `unit` - the battery axis' unit.
///
/// # Errors
/// [`Error::Invalid`] E8003 when a hop cannot be re-flown on the instance (a path that is not
/// one of the network, a swarm or a schedule that names drones it does not have, a stop with
/// another number of drones).
///
/// # Complexity
/// Per hop that of the re-integration, plus the exhaustive search of each stop's optimum for
/// small swarms (at most `pads^n / pads!` assignments of `n` drones).
pub fn figure_data(
    network: &Network,
    profile: &Profile,
    reports: &[&RequestReport],
    unit: BatteryUnit,
) -> Result<Figure> {
    let plans = reports
        .iter()
        .map(|r| plan_data(network, profile, r, unit))
        .collect::<Result<Vec<_>>>()?;
    let all = || plans.iter().flat_map(|p| p.drones.iter());
    let end = plans
        .iter()
        .flat_map(|p| {
            let failure = p.failure.as_ref().map(|f| f.time_min);
            [Some(p.dt_min), failure]
        })
        .flatten()
        .chain(all().flat_map(|d| d.points.iter().map(|q| q.0)))
        .fold(0.0, f64::max);
    let lowest = all()
        .flat_map(|d| d.points.iter().map(|q| q.1))
        .fold(0.0, f64::min);
    let highest = all()
        .flat_map(|d| d.points.iter().map(|q| q.1).chain([d.capacity]))
        .fold(0.0, f64::max);
    let longest_nt = plans
        .iter()
        .flat_map(|p| p.stops.iter())
        .flat_map(|s| s.bars.iter().map(|b| b.end_min).chain([s.nt_min]))
        .fold(0.0, f64::max);
    let headroom = |x: f64| if x > 0.0 { x * 1.04 } else { 1.0 };
    Ok(Figure {
        map: MapData {
            nodes: network
                .nodes
                .iter()
                .map(|n| (n.id.clone(), n.x_m, n.y_m, n.pads))
                .collect(),
            edges: {
                let at = node_at(network);
                network
                    .edges
                    .iter()
                    .filter_map(|e| Some((*at.get(e.from.as_str())?, *at.get(e.to.as_str())?)))
                    .collect()
            },
        },
        plans,
        unit,
        time_range_min: (0.0, headroom(end)),
        battery_range: (
            lowest - 0.04 * (highest - lowest),
            highest + 0.06 * (highest - lowest).max(1.0),
        ),
        stop_range_min: (0.0, headroom(longest_nt)),
    })
}

impl Figure {
    /// The gap of the plan against the plan compared with it, the reference:
    /// `(dt_plan - dt_ref) / dt_ref`; `None` without a second plan, or when either is not
    /// delivered or the reference's `dt` is 0.
    pub fn gap(&self) -> Option<f64> {
        let [plan, reference] = self.plans.as_slice() else {
            return None;
        };
        (plan.delivered && reference.delivered && reference.dt_min > 0.0)
            .then(|| (plan.dt_min - reference.dt_min) / reference.dt_min)
    }
}

/// The lowest and highest battery of a transfer's two drones over the transfer, `scale`d:
/// the band drawn behind it; `(0, 0)` when no point of `trajectory` falls in it.
pub(super) fn battery_span(
    trajectory: &[(f64, Vec<f64>)],
    x: &crate::eaas::Transfer,
    scale: impl Fn(usize, f64) -> f64,
) -> (f64, f64) {
    let span = trajectory
        .iter()
        .filter(|(t, _)| *t >= x.start_min - 1e-9 && *t <= x.end_min + 1e-9)
        .flat_map(|(_, b)| {
            [x.support, x.consumer]
                .into_iter()
                .filter_map(|d| b.get(d).map(|&v| scale(d, v)))
        })
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if span.0 <= span.1 {
        span
    } else {
        (0.0, 0.0)
    }
}

fn node_at(network: &Network) -> HashMap<&str, (f64, f64)> {
    network
        .nodes
        .iter()
        .map(|n| (n.id.as_str(), (n.x_m, n.y_m)))
        .collect()
}

/// One plan's data.
fn plan_data(
    network: &Network,
    profile: &Profile,
    report: &RequestReport,
    unit: BatteryUnit,
) -> Result<PlanData> {
    let plan = &report.plan;
    let mut walk = Walk::new(network, profile, report, unit);
    for (k, hop) in plan.hops.iter().enumerate() {
        walk.fly(k, hop)?;
        if let Some(stop) = &hop.stop {
            walk.stop_at(k, hop, stop)?;
        }
    }
    if plan.hops.is_empty() {
        for (d, drone) in report.swarm.drones.iter().enumerate() {
            let full = walk.scale.of(d, drone.capacity_mah);
            walk.drones[d].points.push((0.0, full));
        }
    }
    let last = plan
        .hops
        .last()
        .map_or(plan.source.as_str(), |h| h.to.as_str());
    let failed_at = (!plan.delivered())
        .then(|| walk.at.get(last).map(|&(x, y)| (last.to_string(), x, y)))
        .flatten();
    Ok(PlanData {
        combination: combination(report),
        request_id: report.request.id.clone(),
        source: plan.source.clone(),
        destination: plan.destination.clone(),
        dt_min: plan.dt_min,
        delivered: plan.delivered(),
        outcome_kind: plan.outcome.kind(),
        outcome: plan.outcome.to_string(),
        failure: failure_mark(plan, walk.t0),
        route: walk.route,
        stop_marks: walk.stop_marks,
        drones: walk.drones,
        transfers: walk.transfers,
        stops: walk.stops,
        failed_at,
    })
}

/// A battery in the figure's unit: mAh, or percent of the drone's capacity.
struct Scale {
    unit: BatteryUnit,
    /// Every drone's capacity, mAh.
    capacity: Vec<f64>,
}

impl Scale {
    /// Battery `b` (mAh) of drone `d` in the figure's unit.
    fn of(&self, d: usize, b: f64) -> f64 {
        match self.unit {
            BatteryUnit::Mah => b,
            BatteryUnit::Percent if self.capacity[d] > 0.0 => 100.0 * b / self.capacity[d],
            BatteryUnit::Percent => 0.0,
        }
    }
}

/// A plan walked hop by hop and stop by stop: what is drawn of it so far, and the time reached.
struct Walk<'a> {
    network: &'a Network,
    profile: &'a Profile,
    swarm: &'a Swarm,
    /// Every node's coordinates, m.
    at: HashMap<&'a str, (f64, f64)>,
    scale: Scale,
    /// Minutes since departure at the point reached.
    t0: f64,
    route: Vec<Vec<(f64, f64)>>,
    stop_marks: Vec<(String, f64, f64, u32)>,
    drones: Vec<DroneSeries>,
    transfers: Vec<TransferBand>,
    stops: Vec<StopSchedule>,
}

impl<'a> Walk<'a> {
    /// At departure: every drone's series empty.
    fn new(
        network: &'a Network,
        profile: &'a Profile,
        report: &'a RequestReport,
        unit: BatteryUnit,
    ) -> Walk<'a> {
        let swarm = &report.swarm;
        let scale = Scale {
            unit,
            capacity: swarm.drones.iter().map(|d| d.capacity_mah).collect(),
        };
        let drones = swarm
            .drones
            .iter()
            .enumerate()
            .map(|(d, drone)| DroneSeries {
                drone: d,
                role: drone.role,
                capacity: scale.of(d, drone.capacity_mah),
                points: Vec::new(),
            })
            .collect();
        Walk {
            network,
            profile,
            swarm,
            at: node_at(network),
            scale,
            t0: 0.0,
            route: Vec::new(),
            stop_marks: Vec::new(),
            drones,
            transfers: Vec::new(),
            stops: Vec::new(),
        }
    }

    /// Hop `k` flown: its path on the map, every drone's battery re-integrated over it, its
    /// transfers.
    fn fly(&mut self, k: usize, hop: &Hop) -> Result<()> {
        let t0 = self.t0;
        let path: Option<Vec<(f64, f64)>> = hop
            .path
            .iter()
            .map(|id| self.at.get(id.as_str()).copied())
            .collect();
        self.route
            .push(path.ok_or_else(|| unfit(k, "a node of its path is not in the network"))?);
        let problem = rebuilt_hop_problem(self.network, self.profile, self.swarm, hop)
            .ok_or_else(|| unfit(k, "its path, swarm or departure batteries"))?;
        let trajectory = battery_trajectory(&problem, &hop.transfers)
            .ok_or_else(|| unfit(k, "a transfer names a drone or slot the swarm lacks"))?;
        let scale = &self.scale;
        for (t, batteries) in &trajectory {
            for (d, &b) in batteries.iter().enumerate() {
                self.drones[d].points.push((t0 + t, scale.of(d, b)));
            }
        }
        for x in &hop.transfers {
            self.transfers.push(TransferBand {
                hop: k,
                support: x.support,
                consumer: x.consumer,
                start_min: t0 + x.start_min,
                end_min: t0 + x.end_min,
                energy_mah: x.energy_mah,
                battery_span: battery_span(&trajectory, x, |d, b| scale.of(d, b)),
            });
        }
        self.t0 += hop.tt_min;
        Ok(())
    }

    /// The stop hop `k` ends in: its mark on the map, its pad schedule, and every drone waiting,
    /// charging, then waiting full until the node time ends.
    fn stop_at(&mut self, k: usize, hop: &Hop, stop: &Stop) -> Result<()> {
        let t0 = self.t0;
        let n = self.swarm.drones.len();
        let (x, y) = self.at[hop.path.last().map_or("", String::as_str)];
        self.stop_marks.push((stop.node.clone(), x, y, stop.pads));
        if stop.charge_times_min.len() != n || hop.arrival_battery_mah.len() != n {
            return Err(unfit(k, "its stop charges another number of drones"));
        }
        let bars = pad_bars(k, stop)?;
        for bar in &bars {
            let d = bar.drone;
            let arrival = self.scale.of(d, hop.arrival_battery_mah[d]);
            let full = self.scale.of(d, self.scale.capacity[d]);
            let series = &mut self.drones[d].points;
            series.push((t0 + bar.start_min, arrival));
            series.push((t0 + bar.end_min, full));
            series.push((t0 + stop.nt_min, full));
        }
        let optimum_min = match stop.status {
            SolveStatus::Optimal => Some(stop.nt_min),
            _ if n <= OPTIMALITY_CHECK_DRONES => Some(optimal_makespan_min(
                &stop.charge_times_min,
                stop.pads as usize,
            )),
            _ => None,
        };
        self.stops.push(StopSchedule {
            node: stop.node.clone(),
            pads: stop.pads,
            arrival_min: t0,
            nt_min: stop.nt_min,
            status: stop.status,
            optimum_min,
            bars,
        });
        self.t0 += stop.nt_min;
        Ok(())
    }
}

/// The pad schedule of the stop hop `k` ends in: every drone's charge on its pad, back to back
/// in the pad's queue, by drone.
fn pad_bars(k: usize, stop: &Stop) -> Result<Vec<PadBar>> {
    let mut bars = Vec::new();
    for (pad, queue) in stop.assignment.iter().enumerate() {
        let mut start = 0.0;
        for &d in queue {
            let ct = *stop
                .charge_times_min
                .get(d)
                .ok_or_else(|| unfit(k, "its stop charges a drone the swarm lacks"))?;
            bars.push(PadBar {
                pad,
                drone: d,
                start_min: start,
                end_min: start + ct,
            });
            start += ct;
        }
    }
    bars.sort_by_key(|b| b.drone);
    Ok(bars)
}

/// Where a failed plan's drone runs dry, `t0` min after departure being where its last hop or
/// stop ended.
fn failure_mark(plan: &Plan, t0: f64) -> Option<FailureMark> {
    let failure = |f: &HopFailure, flight: String| FailureMark {
        drone: f.drone,
        time_min: t0 + f.time_min,
        flight,
    };
    match &plan.outcome {
        PlanOutcome::Delivered | PlanOutcome::NoRoute { .. } => None,
        PlanOutcome::DeadEnd { direct, .. } => Some(failure(
            direct,
            format!("flying straight to {}", plan.destination),
        )),
        PlanOutcome::HopInfeasible {
            from,
            to,
            failure: f,
        } => Some(failure(f, format!("flying {from} -> {to}"))),
        PlanOutcome::NoStopSequence {
            from, to, direct, ..
        } => Some(failure(direct, format!("flying straight {from} -> {to}"))),
    }
}
