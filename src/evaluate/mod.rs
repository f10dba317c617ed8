//! Scoring schedules and routes written outside the planner (a researcher's own heuristic, in
//! Rust or through the Python package) against the exact references, with the independent
//! checker as the judge of what is allowed.
//! User guide: "Evaluating outside schedules and routes" (`docs/src/models/evaluate.md`) and
//! "Python" (`docs/src/python.md`).
//!
//! - [`evaluate_hop`]: a hop schedule (timed transfers) flown exactly as written; its rule
//!   breaks (the checker's `C3001`-`C3013`) are an error, running out of battery is a result; its
//!   objective (node time at the hop's end, or lowest delivery arrival battery) against the
//!   continuous-time optimum of a re-ordering mode that contains it.
//! - [`evaluate_route`]: a stop sequence with a schedule per hop, every hop from full batteries
//!   along the rule path, the exact node time at each stop; its delivery time against the joint
//!   optimum of the same swarm (`--route optimal --sharing exact`).
//!
//! See `models/evaluate.md` for what each gap is taken against and when none is taken.

use crate::check::fly_as_written;
use crate::compose::{Context, PlanOptions, RouteMethod, Stop};
use crate::eaas::compare::{reference, run_method, HopMethod};
use crate::eaas::exact::milp::MilpOptions;
use crate::eaas::exact::EndPads;
use crate::eaas::exact::{objective_of, ExactStatus, Objective, Reorder};
use crate::eaas::hop_file::{HopFile, HOP_FILE_SCHEMA_VERSION};
use crate::eaas::{
    travel_time_min, HopOutcome, HopProblem, PolicyOptions, SharingPolicy, Transfer,
};
use crate::error::{Error, Result, Violation};
use crate::precompose::Positioning;
use crate::problem::Request;
use crate::solver::{Gap, GapLabel, ReferenceKind, Sense};
use serde::{Deserialize, Serialize};

/// One transfer of a schedule as a user writes it: `energy_mah` and `consumer_slot` may be left
/// out (`rho x duration`, and the consumer's own slot).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WrittenTransfer {
    /// Giving support drone.
    pub support: usize,
    /// Receiving delivery drone.
    pub consumer: usize,
    /// Start, minutes from the hop start.
    pub start_min: f64,
    /// End, minutes from the hop start.
    pub end_min: f64,
    /// Energy moved, mAh; checked against `rho x duration` when given (C3005).
    #[serde(default)]
    pub energy_mah: Option<f64>,
    /// Slot the consumer flies in during the transfer; its own slot when left out.
    #[serde(default)]
    pub consumer_slot: Option<usize>,
}

impl WrittenTransfer {
    /// The transfer with its defaults filled in from `problem` (a consumer index out of range
    /// keeps slot `usize::MAX`, for the checker's C3001).
    pub fn complete(&self, problem: &HopProblem) -> Transfer {
        Transfer {
            support: self.support,
            consumer: self.consumer,
            start_min: self.start_min,
            end_min: self.end_min,
            energy_mah: self
                .energy_mah
                .unwrap_or(problem.rho_mah_per_min * (self.end_min - self.start_min)),
            consumer_slot: self.consumer_slot.unwrap_or_else(|| {
                problem
                    .initial_slot
                    .get(self.consumer)
                    .copied()
                    .unwrap_or(usize::MAX)
            }),
        }
    }
}

impl From<&Transfer> for WrittenTransfer {
    fn from(t: &Transfer) -> Self {
        WrittenTransfer {
            support: t.support,
            consumer: t.consumer,
            start_min: t.start_min,
            end_min: t.end_min,
            energy_mah: Some(t.energy_mah),
            consumer_slot: Some(t.consumer_slot),
        }
    }
}

/// The default settings of a hop's exact reference: `paper` re-ordering, the default backend,
/// no wall-clock limit, [`crate::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT`] nodes per MILP call
/// (the same on every machine).
pub fn default_reference() -> MilpOptions {
    MilpOptions {
        time_limit_s: f64::INFINITY,
        node_limit: Some(crate::eaas::exact_hop::DEFAULT_HOP_NODE_LIMIT),
        ..MilpOptions::default()
    }
}

/// The exact reference of one hop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct HopReference {
    /// The continuous model's status.
    pub status: ExactStatus,
    /// The reference value (node time, min, or lowest delivery arrival battery, mAh), or `None`
    /// when the model has none (infeasible hop, or stopped without an incumbent).
    pub value: Option<f64>,
    /// `optimal` (attained, node time proven) or `infimum` (approached, not attained).
    pub kind: Option<ReferenceKind>,
    /// Certified distance of the model's own schedule to the reference, in the objective's unit.
    pub epsilon: Option<f64>,
    /// The mode the reference optimises over.
    pub reorder: Reorder,
}

/// A hop schedule flown as written and scored.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HopEvaluation {
    /// The flight as written: feasibility, first failure, the transfers (defaults filled in),
    /// final and lowest batteries, shared total (flattened into the same object in JSON).
    #[serde(flatten)]
    pub outcome: HopOutcome,
    /// What the hop is scored by.
    pub objective: Objective,
    /// The schedule's objective when feasible: node time (min, by the exact pad assignment) or
    /// lowest delivery arrival battery (mAh).
    pub value: Option<f64>,
    /// False when the node time stopped at the stop's node limit (`value` is then an upper
    /// bound).
    pub value_proven: bool,
    /// The smallest re-ordering mode whose schedules include this one (`none` ⊂ `paper` ⊂
    /// `free`).
    pub mode: Reorder,
    /// The exact reference, when asked for.
    pub reference: Option<HopReference>,
    /// `(value - reference) / reference`, when both exist and the reference's mode contains the
    /// schedule.
    pub gap: Option<Gap>,
    /// Why no gap is given: `infeasible` (the schedule does not fly), `outside_reference` (its
    /// mode is larger than the reference's), `no_reference` (the model gave no value).
    pub gap_label: Option<GapLabel>,
}

/// The smallest re-ordering mode containing a schedule (checked valid): `none` when every
/// consumer is served in its own slot within range, `paper` when every transfer is one of the
/// paper's moves (an in-range consumer stays, an out-of-range one swaps with the delivery drone
/// of an in-range slot), else `free`.
pub fn smallest_mode(problem: &HopProblem, transfers: &[Transfer]) -> Reorder {
    let moves = crate::eaas::exact::moves(problem, Reorder::Paper);
    let is_move = |t: &Transfer, own_only: bool| {
        moves.iter().any(|m| {
            m.support == t.support
                && m.consumer == t.consumer
                && m.slot == t.consumer_slot
                && (!own_only || m.partner.is_none())
        })
    };
    if transfers.iter().all(|t| is_move(t, true)) {
        Reorder::None
    } else if transfers.iter().all(|t| is_move(t, false)) {
        Reorder::Paper
    } else {
        Reorder::Free
    }
}

fn contains(outer: Reorder, inner: Reorder) -> bool {
    let rank = |r: Reorder| match r {
        Reorder::None => 0,
        Reorder::Paper => 1,
        Reorder::Free => 2,
    };
    rank(inner) <= rank(outer)
}

/// Flies `transfers` on the hop exactly as written and scores them by `objective`.
///
/// # Arguments
/// * `problem`, `objective` - the hop and what it is scored by (see
///   [`crate::eaas::hop_file::HopFile::objective`]).
/// * `transfers` - the schedule.
/// * `reference` - the exact reference's settings (its re-ordering mode, backend and limits;
///   [`default_reference`]), or `None` for no reference (no solve).
///
/// # Errors
/// [`Error::Invalid`] with E4103/E4104 for an objective with no pads or a pad rate that is not
/// a finite number > 0; with the checker's codes (`C3001`-`C3013`, each naming `transfers[i]`)
/// when the schedule breaks a rule of the hop model; those of the hop's validation and of the
/// continuous model.
pub fn evaluate_hop(
    problem: &HopProblem,
    objective: &Objective,
    transfers: &[WrittenTransfer],
    reference: Option<&MilpOptions>,
) -> Result<HopEvaluation> {
    crate::eaas::validate(problem)?;
    crate::eaas::exact::validate_objective(objective)?;
    let transfers: Vec<Transfer> = transfers.iter().map(|t| t.complete(problem)).collect();
    let (outcome, violations) = fly_as_written(problem, &transfers);
    let outcome = match outcome {
        Some(o) if violations.is_empty() => o,
        _ => {
            // The checker's own action reads as a planner's bug; here the schedule is the user's.
            let mut violations = violations;
            for v in &mut violations {
                v.action = "change the schedule so that it keeps the rules of the hop model \
                     (models/eaas.md; the codes in docs/src/errors.md)"
                    .into();
            }
            return Err(Error::Invalid(violations));
        }
    };
    let value = if outcome.feasible {
        Some(objective_of(
            problem,
            objective,
            &outcome.final_battery_mah,
        )?)
    } else {
        None
    };
    let mode = smallest_mode(problem, &transfers);
    let reference = match reference {
        Some(r) => Some(hop_reference(problem, objective, r)?),
        None => None,
    };
    let (gap, gap_label) = match (&value, &reference) {
        (_, None) => (None, None),
        (None, Some(_)) => (None, Some(GapLabel::Infeasible)),
        (Some(_), Some(r)) if !contains(r.reorder, mode) => {
            (None, Some(GapLabel::OutsideReference))
        }
        (Some(v), Some(r)) => match (r.value, r.kind) {
            (Some(x), Some(kind)) => (Some(Gap::new(v.value, x, kind, objective.sense())), None),
            _ => (None, Some(GapLabel::NoReference)),
        },
    };
    Ok(HopEvaluation {
        outcome,
        objective: *objective,
        value: value.map(|v| v.value),
        value_proven: value.is_none_or(|v| v.proven),
        mode,
        reference,
        gap,
        gap_label,
    })
}

/// The continuous model's reference on a hop: its optimum (`optimal`) or infimum (`infimum`).
///
/// # Errors
/// Those of the continuous model.
pub fn hop_reference(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
) -> Result<HopReference> {
    let row = run_method(
        problem,
        objective,
        HopMethod::Continuous,
        options,
        &PolicyOptions::default(),
    )?;
    let found = reference(std::slice::from_ref(&row));
    Ok(HopReference {
        status: row.status.unwrap_or(ExactStatus::Infeasible),
        value: found.map(|(v, _)| v),
        kind: found.map(|(_, k)| k),
        epsilon: row.epsilon,
        reorder: options.reorder,
    })
}

/// One hop of an evaluated route.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouteHop {
    /// The hop as a hop file (its problem, departing full; the pads at its end).
    pub hop: HopFile,
    /// Travel time, min.
    pub tt_min: f64,
    /// The schedule flown as written (no reference per hop).
    pub evaluation: HopEvaluation,
    /// The recharging stop at the hop's end (not at the destination).
    pub stop: Option<Stop>,
}

/// The joint optimum of the same swarm, the reference of a route.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RouteReference {
    /// Its delivery time, min; `None` when it does not deliver.
    pub dt_min: Option<f64>,
    /// `optimal` when every hop solve and node time of the search is proven, else
    /// `incumbent` (a delivery time some plan reaches, not proven least).
    pub kind: ReferenceKind,
    /// Summed certified distance of its hop schedules to the continuous infima, min.
    pub epsilon_min: f64,
    /// The re-ordering mode of its hop schedules.
    pub reorder: Reorder,
}

/// A user's route flown and scored.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RouteEvaluation {
    /// The request.
    pub request_id: String,
    /// The stops as given, source first and destination last.
    pub stops: Vec<String>,
    /// The positioning of the support drones of the swarm flown.
    pub positioning: Positioning,
    /// Support drones flown.
    pub support_drones: usize,
    /// Whether every hop flies.
    pub delivered: bool,
    /// Total travel time of the hops flown, min.
    pub tt_min: f64,
    /// Total node time of the stops made, min.
    pub nt_min: f64,
    /// Delivery time `tt + nt`, min, when delivered.
    pub dt_min: Option<f64>,
    /// Whether every node time is proven (else `dt_min` is an upper bound).
    pub dt_proven: bool,
    /// The hops, up to the first that does not fly.
    pub hops: Vec<RouteHop>,
    /// The smallest re-ordering mode containing every hop's schedule.
    pub mode: Reorder,
    /// The joint optimum of the same swarm, when asked for.
    pub reference: Option<RouteReference>,
    /// `(dt - dt_ref) / dt_ref` with the reference's kind (`optimal` or `incumbent`), the same
    /// shape as every gap ([`Gap`]), when both deliver and the reference contains the route.
    pub gap: Option<Gap>,
    /// Why no gap is given: `not_delivered`, `outside_reference` (a hop schedule outside the
    /// reference's re-ordering mode), `no_reference` (the reference does not deliver).
    pub gap_label: Option<GapLabel>,
}

fn stop_error(code: &'static str, field: String, cause: String, fix: &str) -> Error {
    Error::Invalid(vec![Violation::new(code, field, cause, fix)])
}

/// Flies a request along `stops` with the schedules `schedule` writes for each hop, and
/// measures it against the joint optimum of the same swarm.
///
/// Every hop departs with full batteries (the swarm charges to full at every stop) along the
/// rule path (the shortest path by distance, as the optimal route's hops); the node time at each
/// stop is the exact pad assignment under the context's node limit.
///
/// # Arguments
/// * `context` - the instance; its exact settings (re-ordering, limits) set the reference's.
/// * `request` - a request valid on the context's network.
/// * `positioning`, `support` - the swarm, as for `solve`.
/// * `stops` - node ids, the request's source first and destination last; the stops between
///   have pads.
/// * `schedule` - called with each hop in turn (its index, problem and end), returns its
///   transfers.
/// * `with_reference` - whether to solve the joint optimum.
///
/// # Errors
/// E0022 (the stops do not begin at the source and end at the destination), E0023 (an unknown
/// node id), E0024 (a stop between without pads), E0025 (two equal consecutive stops, or two the
/// network does not connect); the
/// checker's codes for a schedule that breaks a rule; those of `schedule` and the models.
pub fn evaluate_route(
    context: &Context,
    request: &Request,
    positioning: Positioning,
    support: Option<usize>,
    stops: &[String],
    schedule: &mut dyn FnMut(&HopFile) -> Result<Vec<WrittenTransfer>>,
    with_reference: bool,
) -> Result<RouteEvaluation> {
    let graph = context.graph();
    let nodes = route_nodes(context, request, stops)?;
    let choice = context.swarm_for(request, positioning, support)?;
    let planner = context.planner(&choice.swarm, SharingPolicy::Exact);
    let full = planner.full_battery_mah();
    let mut out = RouteEvaluation {
        request_id: request.id.clone(),
        stops: stops.to_vec(),
        positioning,
        support_drones: choice.support_drones,
        delivered: true,
        tt_min: 0.0,
        nt_min: 0.0,
        dt_min: None,
        dt_proven: true,
        hops: Vec::new(),
        mode: Reorder::None,
        reference: None,
        gap: None,
        gap_label: None,
    };
    let mut mode = Reorder::None;
    let last = nodes.len() - 1;
    for (i, w) in nodes.windows(2).enumerate() {
        let (u, v) = (w[0], w[1]);
        let into_stop = i + 1 < last;
        let path = if into_stop {
            graph.shortest_paths_to(u).reversed_path_from(v)
        } else {
            graph.shortest_path(u, v)
        }
        .ok_or_else(|| {
            stop_error(
                "E0025",
                format!("stops[{}]", i + 1),
                format!("no path from {} to {}", stops[i], stops[i + 1]),
                "give stops the network connects",
            )
        })?;
        let problem = planner.hop_problem(&path, &full)?;
        let pads = graph.pads(v);
        let end = (into_stop && pads > 0).then(|| EndPads {
            pads: pads as usize,
            pad_rate_mah_per_min: planner.pad_rate_mah_per_min(v),
        });
        let file = HopFile {
            schema_version: HOP_FILE_SCHEMA_VERSION,
            request_id: request.id.clone(),
            hop_index: i,
            from: stops[i].clone(),
            to: stops[i + 1].clone(),
            path: path
                .nodes
                .iter()
                .map(|&n| graph.id_of(n).to_string())
                .collect(),
            profile: Some(context.profile().name.clone()),
            end,
            made_on: Some(context.fingerprint().clone()),
            plan: None,
            hop: problem,
        };
        let written = schedule(&file)?;
        let evaluation =
            evaluate_hop(&file.hop, &file.objective(), &written, None).map_err(|e| match e {
                Error::Invalid(list) => Error::Invalid(
                    list.into_iter()
                        .map(|mut x| {
                            x.field = format!("hops[{i}].{}", x.field);
                            x
                        })
                        .collect(),
                ),
                other => other,
            })?;
        if !contains(mode, evaluation.mode) {
            mode = evaluation.mode;
        }
        let tt_min = travel_time_min(&file.hop);
        out.tt_min += tt_min;
        let feasible = evaluation.outcome.feasible;
        let stop = if feasible && into_stop {
            planner.stop_at(v, &evaluation.outcome.final_battery_mah)?
        } else {
            None
        };
        if let Some(s) = &stop {
            out.nt_min += s.nt_min;
            out.dt_proven &= s.status == crate::solver::SolveStatus::Optimal;
        }
        out.hops.push(RouteHop {
            hop: file,
            tt_min,
            evaluation,
            stop,
        });
        if !feasible {
            out.delivered = false;
            break;
        }
    }
    if out.delivered {
        out.dt_min = Some(out.tt_min + out.nt_min);
    }
    out.mode = mode;
    if with_reference {
        let reference = route_reference(context, request, positioning, support)?;
        out.measure_against(reference);
    }
    Ok(out)
}

/// The joint optimum of a request for one swarm (`--route optimal --sharing exact` with the
/// context's exact settings): the reference of [`evaluate_route`].
///
/// # Errors
/// Those of [`Context::plan`].
pub fn route_reference(
    context: &Context,
    request: &Request,
    positioning: Positioning,
    support: Option<usize>,
) -> Result<RouteReference> {
    let optimum = context.plan(
        request,
        &PlanOptions {
            sharing: SharingPolicy::Exact,
            positioning,
            route: RouteMethod::Optimal,
            support,
        },
    )?;
    let optimality = optimum.plan.route_optimality.unwrap_or_default();
    Ok(RouteReference {
        dt_min: optimum.plan.delivered().then_some(optimum.plan.dt_min),
        kind: if optimality.proven() {
            ReferenceKind::Optimal
        } else {
            ReferenceKind::Incumbent
        },
        epsilon_min: optimality.epsilon_min,
        reorder: context.exact.milp.reorder,
    })
}

impl RouteEvaluation {
    /// Sets the reference and the gap against it (or the label saying why there is none).
    pub fn measure_against(&mut self, reference: RouteReference) {
        self.reference = Some(reference);
        (self.gap, self.gap_label) = match (self.dt_min, reference.dt_min) {
            (None, _) => (None, Some(GapLabel::NotDelivered)),
            (Some(_), _) if !contains(reference.reorder, self.mode) => {
                (None, Some(GapLabel::OutsideReference))
            }
            (Some(_), None) => (None, Some(GapLabel::NoReference)),
            (Some(dt), Some(best)) => (
                Some(Gap::new(dt, best, reference.kind, Sense::Minimise)),
                None,
            ),
        };
    }
}

/// The node indices of `stops`, checked (E0022-E0025).
fn route_nodes(context: &Context, request: &Request, stops: &[String]) -> Result<Vec<usize>> {
    let graph = context.graph();
    let mut v = Vec::new();
    if stops.len() < 2
        || stops.first() != Some(&request.source)
        || stops.last() != Some(&request.destination)
    {
        v.push(Violation::new(
            "E0022",
            "stops",
            format!(
                "{stops:?} does not lead from the request's source {} to its destination {}",
                request.source, request.destination
            ),
            "give the node ids of the stops, the source first and the destination last",
        ));
    }
    let mut nodes = Vec::new();
    for (i, id) in stops.iter().enumerate() {
        match graph.index_of(id) {
            Some(n) => nodes.push(n),
            None => v.push(Violation::new(
                "E0023",
                format!("stops[{i}]"),
                format!("no node with id `{id}`"),
                "give node ids of the network, such as n000",
            )),
        }
    }
    if v.is_empty() {
        for (i, &n) in nodes.iter().enumerate().take(nodes.len() - 1).skip(1) {
            if graph.pads(n) == 0 {
                v.push(Violation::new(
                    "E0024",
                    format!("stops[{i}]"),
                    format!("{} has no pads: the swarm cannot recharge there", stops[i]),
                    "stop only at nodes with pads (`swarmplan inspect` lists them)",
                ));
            }
        }
        for (i, w) in nodes.windows(2).enumerate() {
            if w[0] == w[1] {
                v.push(Violation::new(
                    "E0025",
                    format!("stops[{}]", i + 1),
                    format!("{} follows itself", stops[i]),
                    "give each stop once in a row",
                ));
            }
        }
    }
    if v.is_empty() {
        Ok(nodes)
    } else {
        Err(Error::Invalid(v))
    }
}
