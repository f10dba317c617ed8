//! In-flight energy sharing (EaaS) on one hop: the flight between two stops, see
//! `models/eaas.md`.
//! User guide: "In-flight sharing on a hop" (`docs/src/models/eaas.md`) and the command `eaas`
//! (`docs/src/commands/eaas.md`).
//!
//! Time runs over `[0, tt]`, `tt` = the sum of the legs' durations. Drone `d` flying in formation
//! slot `q` on leg `l` consumes `rate[l][d][q]` mAh/min (piecewise constant in time). A support drone
//! `s` shares with one delivery drone `c` at a time, at rate `rho` mAh/min: `s` loses `rho` on top of
//! its own consumption, `c` gains `rho`. The consumer must be within `range_m` of the support drone;
//! if it is not, fixed re-ordering swaps it, for the duration of the transfer, with the drone in the
//! slot nearest the support drone ([`reorder`]). A support drone shares only energy it can spare:
//! its battery at the hop end, after its own consumption, never falls below the reserve `delta`
//! because of sharing.
//!
//! Policies: [`SharingPolicy::None`] (baseline), [`SharingPolicy::Pb`] (priority-based, the paper's
//! Algorithm 2, threshold `gamma`) and [`SharingPolicy::Fb`] (fairness-based, Algorithm 3, round
//! `lambda`). [`simulate`] runs a policy and returns the schedule with every drone's battery; the
//! independent checker in [`crate::check`] re-verifies it from the raw [`HopProblem`].

use crate::error::{show, Error, Result, Violation};
use crate::problem::Role;
use crate::problem::{PbRequest, Readings};
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

pub mod compare;
pub mod exact;
pub mod exact_hop;
mod fb;
pub mod hop_file;
mod none;
mod pb;
pub mod reorder;
mod simulate;

/// Time tolerance, minutes: events closer than this are simultaneous.
pub const TIME_TOL_MIN: f64 = 1e-9;
/// Energy tolerance, mAh: batteries within this of a bound are on it.
pub const ENERGY_TOL_MAH: f64 = 1e-6;
/// Upper bound on the number of planning iterations of PB and FB (each adds at most one transfer);
/// a guard against pathological inputs, far above what a hop needs.
pub const MAX_PLANNING_STEPS: usize = 10_000;
/// Most FB rounds a hop may need (E4015): the support drones times `ceil(tt * rho / lambda)`, the
/// rounds FB gives while the hop lasts. Each round replays the schedule so far, so the work of a
/// hop grows with the square of its rounds: at this bound one FB hop takes some 10 ms, and a
/// request planned by Algorithm 1 about a second (paper-195, fast-sharing with `lambda_mah` = 25).
/// Beyond it FB refuses the hop instead of running for minutes (`lambda_mah` = 0.01 at the
/// paper's rate asks for about 18,000 rounds per support drone on a 30 min hop). The shipped
/// profiles need at most 11 rounds per support drone on a 23 min hop.
pub const MAX_FB_ROUNDS: f64 = 500.0;

/// One hop's sharing problem, in plain numbers (see `models/eaas.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopProblem {
    /// Consecutive legs of the flight between two stops; `tt` = the sum of their durations.
    pub legs: Vec<LegRates>,
    /// Drones; the index is the drone id. Delivery drones first, then support drones.
    pub drones: Vec<DroneState>,
    /// Formation slot positions in the body frame, metres; as many slots as drones.
    #[serde(with = "slots_serde")]
    pub slots_m: Vec<Vector2<f64>>,
    /// `initial_slot[d]` = slot of drone `d` outside transfers; a permutation.
    pub initial_slot: Vec<usize>,
    /// Sharing rate `rho`, mAh/min.
    pub rho_mah_per_min: f64,
    /// Largest support-consumer distance for a transfer, metres (1.2 m in the paper).
    pub range_m: f64,
    /// PB request threshold `gamma`, mAh.
    pub gamma_mah: f64,
    /// FB round energy `lambda`, mAh.
    pub lambda_mah: f64,
    /// Support reserve `delta`, mAh.
    pub delta_mah: f64,
}

/// A leg of a hop: constant consumption rates for a duration.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LegRates {
    /// Duration of the leg, minutes.
    pub duration_min: f64,
    /// `rate_mah_per_min[d][q]` = consumption of drone `d` flying in slot `q`, mAh/min. Shared:
    /// every hop over the same directed edge with the same swarm uses one matrix.
    pub rate_mah_per_min: Arc<Vec<Vec<f64>>>,
}

/// A drone's battery at the start of the hop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DroneState {
    /// Delivery or support.
    pub role: Role,
    /// Battery capacity, mAh.
    pub capacity_mah: f64,
    /// Battery at the hop start, mAh.
    pub battery_mah: f64,
}

/// Which sharing policy runs on a hop.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "kebab-case")]
pub enum SharingPolicy {
    /// The paper's baseline: no in-flight sharing and no support drones in the swarm.
    None,
    /// Ablation: the support drones fly (and are charged at every stop) but never share.
    IdleSupport,
    /// Priority-based sharing (the paper's Algorithm 2).
    Pb,
    /// Fairness-based sharing (the paper's Algorithm 3).
    Fb,
    /// The optimal continuous-time schedule on every hop (`models/eaas_config.md`): least node
    /// time at a stop, any flying schedule into the destination.
    Exact,
    /// The fair QP's schedule on every hop (`models/eaas_fluid.md`), FB's exact counterpart.
    Fair,
}

display_as_value_name!(SharingPolicy);

impl SharingPolicy {
    /// Whether the policy moves energy in flight (PB, FB, exact, fair); `none` and `idle-support`
    /// do not.
    pub fn shares(self) -> bool {
        matches!(
            self,
            SharingPolicy::Pb | SharingPolicy::Fb | SharingPolicy::Exact | SharingPolicy::Fair
        )
    }

    /// Whether the schedule comes from an exact model (the MILP or the fair QP) rather than
    /// from simulating a policy; see [`exact_hop::fly_exact`].
    pub fn is_exact(self) -> bool {
        matches!(self, SharingPolicy::Exact | SharingPolicy::Fair)
    }

    /// Whether the swarm flies support drones: every policy but the paper's baseline `none`.
    pub fn flies_support(self) -> bool {
        self != SharingPolicy::None
    }

    /// How a hop flies under this policy: simulated with a heuristic (`idle-support` flies
    /// `none`), or with a model's schedule (`exact`, `fair`).
    pub fn on_hop(self) -> HopPolicy {
        match self {
            SharingPolicy::None | SharingPolicy::IdleSupport => {
                HopPolicy::Simulated(Heuristic::None)
            }
            SharingPolicy::Pb => HopPolicy::Simulated(Heuristic::Pb),
            SharingPolicy::Fb => HopPolicy::Simulated(Heuristic::Fb),
            SharingPolicy::Exact => HopPolicy::Solved(ExactPolicy::Exact),
            SharingPolicy::Fair => HopPolicy::Solved(ExactPolicy::Fair),
        }
    }

    /// The heuristic a hop is simulated with under this policy; `None` for `exact` and `fair`.
    pub fn heuristic(self) -> Option<Heuristic> {
        match self.on_hop() {
            HopPolicy::Simulated(h) => Some(h),
            HopPolicy::Solved(_) => None,
        }
    }
}

/// How a hop flies under a [`SharingPolicy`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum HopPolicy {
    /// Simulated with a heuristic ([`simulate`]).
    Simulated(Heuristic),
    /// A model's schedule ([`exact_hop::fly_exact`]).
    Solved(ExactPolicy),
}

/// A sharing heuristic simulated on a hop ([`simulate`]): the paper's Algorithms 2 and 3 and the
/// flight without sharing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Heuristic {
    /// No sharing.
    None,
    /// Priority-based sharing (Algorithm 2).
    Pb,
    /// Fairness-based sharing (Algorithm 3).
    Fb,
}

display_as_value_name!(Heuristic);

impl From<Heuristic> for SharingPolicy {
    fn from(h: Heuristic) -> SharingPolicy {
        match h {
            Heuristic::None => SharingPolicy::None,
            Heuristic::Pb => SharingPolicy::Pb,
            Heuristic::Fb => SharingPolicy::Fb,
        }
    }
}

/// A sharing policy whose schedule a model gives ([`exact_hop::fly_exact`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ExactPolicy {
    /// The continuous model's optimal schedule.
    Exact,
    /// The fair QP's layout.
    Fair,
}

display_as_value_name!(ExactPolicy);

impl ExactPolicy {
    /// The formulation that gives the schedule: the continuous model, or the fair QP.
    pub fn formulation(self) -> exact::Formulation {
        match self {
            ExactPolicy::Exact => exact::Formulation::Continuous,
            ExactPolicy::Fair => exact::Formulation::Fair,
        }
    }
}

impl From<ExactPolicy> for SharingPolicy {
    fn from(p: ExactPolicy) -> SharingPolicy {
        match p {
            ExactPolicy::Exact => SharingPolicy::Exact,
            ExactPolicy::Fair => SharingPolicy::Fair,
        }
    }
}

/// Readings of the paper where it can be taken two ways; [`Default`] gives ours, the same as the
/// profile's [`Readings`] default (`[readings]` table, models/eaas.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PolicyOptions {
    /// PB: a request whose start `st` is earlier than its support drone's next free time starts
    /// when the support drone becomes free (`true`, default); `false` skips it, as Algorithm 2's
    /// literal test `er.st >= SD.st` does.
    pub pb_wait_for_support: bool,
    /// PB: the size `re` of a request.
    pub pb_request: PbRequest,
    /// FB: a full drone's round still costs the support drone `lambda` of its sharing budget and
    /// one round of time, as Algorithm 3's literal pseudo-code does (`true`); default `false`
    /// skips it at no cost.
    pub fb_charge_skipped: bool,
}

impl Default for PolicyOptions {
    fn default() -> Self {
        PolicyOptions::from(&Readings::default())
    }
}

impl From<&Readings> for PolicyOptions {
    fn from(r: &Readings) -> Self {
        PolicyOptions {
            pb_wait_for_support: r.pb_wait_for_support,
            pb_request: r.pb_request,
            fb_charge_skipped: r.fb_charge_skipped,
        }
    }
}

/// One energy transfer of a schedule.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Transfer {
    /// Giving support drone.
    pub support: usize,
    /// Receiving delivery drone.
    pub consumer: usize,
    /// Start, minutes from the hop start.
    pub start_min: f64,
    /// End, minutes from the hop start.
    pub end_min: f64,
    /// Energy moved, mAh: `rho * (end_min - start_min)`.
    pub energy_mah: f64,
    /// Slot the consumer occupied during the transfer; when it differs from the consumer's
    /// initial slot, the drone initially there holds the consumer's initial slot meanwhile.
    pub consumer_slot: usize,
}

/// A stretch of a `free` schedule in which every drone keeps one slot and the same support
/// drones serve the same consumers (`models/eaas_config.md`): what a list of [`Transfer`]s cannot
/// carry when drones that do not share change slots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlotInterval {
    /// Start, minutes from the hop start.
    pub start_min: f64,
    /// End, minutes from the hop start.
    pub end_min: f64,
    /// Slot of every drone during the interval (support drones in their own slots).
    pub slot: Vec<usize>,
    /// `(support, consumer)` pairs sharing at `rho` during the interval.
    pub serves: Vec<(usize, usize)>,
}

/// A `free` schedule as slot intervals, with every drone's battery at the hop's end as the
/// schedule states it (re-verified by [`crate::check::check_free_hop`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FreeSchedule {
    /// The intervals, back to back over `[0, tt]`.
    pub intervals: Vec<SlotInterval>,
    /// Every drone's battery at `tt`, mAh.
    pub final_battery_mah: Vec<f64>,
}

/// Why a hop is infeasible.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum FailureReason {
    /// The drone's battery fell below zero in flight.
    BatteryDepleted,
}

/// The first failure on a hop.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopFailure {
    /// Failing drone.
    pub drone: usize,
    /// When it fails, minutes from the hop start.
    pub time_min: f64,
    /// Why.
    pub reason: FailureReason,
}

/// Result of flying one hop under a sharing policy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopOutcome {
    /// No drone's battery below zero at any instant.
    pub feasible: bool,
    /// The first failure (earliest time, then lowest drone id), when infeasible.
    pub failure: Option<HopFailure>,
    /// Transfers, by start time then support drone.
    pub transfers: Vec<Transfer>,
    /// Every drone's battery at `tt`, mAh (negative for a drone that failed: the flight is
    /// evaluated to the end so the shortfall is visible).
    pub final_battery_mah: Vec<f64>,
    /// Every drone's lowest battery over `[0, tt]`, mAh.
    pub min_battery_mah: Vec<f64>,
    /// Total energy shared, mAh.
    pub shared_mah: f64,
}

/// Flies a hop under a sharing policy, with the default [`PolicyOptions`].
///
/// # Arguments
/// * `problem` - the hop: legs with rates, drones, formation, `rho`, `range_m`, `gamma`,
///   `lambda`, `delta`.
/// * `heuristic` - none, PB or FB (the exact and fair policies fly with
///   [`exact_hop::fly_exact`]).
///
/// # Returns
/// The schedule and every drone's final and lowest battery; infeasibility is data
/// ([`HopOutcome::feasible`], [`HopOutcome::failure`]).
///
/// # Errors
/// [`Error::Invalid`] (codes `E4001`-`E4012`, every violation at once) for a malformed problem:
/// mismatched sizes, non-finite or negative numbers, a non-permutation `initial_slot`.
///
/// # Complexity
/// One evaluation costs `O(P * D)` for `P` pieces (legs + 2 x transfers) and `D` drones. None
/// evaluates once; PB and FB evaluate once per transfer they add, plus candidate scans, so
/// `O(T * (P * D + D * S))` for `T` transfers and `S` slots.
///
/// # Example
/// ```
/// use swarmplan::eaas::*;
/// use swarmplan::problem::Role;
/// use nalgebra::Vector2;
/// let p = HopProblem {
///     legs: vec![LegRates { duration_min: 10.0, rate_mah_per_min: vec![vec![10.0, 10.0], vec![5.0, 5.0]].into() }],
///     drones: vec![
///         DroneState { role: Role::Delivery, capacity_mah: 200.0, battery_mah: 80.0 },
///         DroneState { role: Role::Support, capacity_mah: 500.0, battery_mah: 500.0 },
///     ],
///     slots_m: vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)],
///     initial_slot: vec![0, 1],
///     rho_mah_per_min: 4.0, range_m: 1.2, gamma_mah: 50.0, lambda_mah: 20.0, delta_mah: 100.0,
/// };
/// let none = simulate(&p, Heuristic::None).unwrap();
/// assert!(!none.feasible); // 80 - 10 * 10 = -20
/// let pb = simulate(&p, Heuristic::Pb).unwrap();
/// assert!(pb.feasible);
/// ```
pub fn simulate(problem: &HopProblem, heuristic: Heuristic) -> Result<HopOutcome> {
    simulate_with(problem, heuristic, &PolicyOptions::default())
}

/// [`simulate`] with explicit [`PolicyOptions`] (the paper's literal readings).
///
/// # Arguments
/// * `problem`, `heuristic` - as [`simulate`].
/// * `options` - which reading of Algorithms 2 and 3 to follow where the paper is ambiguous.
///
/// # Returns
/// As [`simulate`].
///
/// # Errors
/// As [`simulate`].
///
/// # Complexity
/// As [`simulate`].
pub fn simulate_with(
    problem: &HopProblem,
    heuristic: Heuristic,
    options: &PolicyOptions,
) -> Result<HopOutcome> {
    validate(problem)?;
    simulate_valid(problem, heuristic, options)
}

/// [`simulate_with`] for a problem that passed [`validate`] (the route planner validates its
/// hop problems once, not at every hop).
///
/// # Errors
/// Those of [`simulate_with`] other than the validation's.
pub(crate) fn simulate_valid(
    problem: &HopProblem,
    heuristic: Heuristic,
    options: &PolicyOptions,
) -> Result<HopOutcome> {
    let plan = match heuristic {
        Heuristic::None => none::plan(problem),
        Heuristic::Pb => match pb::plan(problem, options) {
            // Realising no transfer again would repeat the same arithmetic.
            (_, Some(run)) => return Ok(run.into_outcome()),
            (plan, None) => plan,
        },
        Heuristic::Fb => {
            fb_work_bound(problem)?;
            fb::plan(problem, options)
        }
    };
    let run = simulate::evaluate(problem, &plan);
    Ok(run.into_outcome())
}

/// E4015: the rounds FB would give on this hop, `supports * ceil(tt * rho / lambda)`, must not
/// exceed [`MAX_FB_ROUNDS`].
///
/// # Errors
/// [`Error::Invalid`] with `E4015` on `lambda_mah`, stating the rounds and the smallest
/// `lambda_mah` that keeps them within the bound.
fn fb_work_bound(problem: &HopProblem) -> Result<()> {
    let supports = problem
        .drones
        .iter()
        .filter(|d| d.role == Role::Support)
        .count() as f64;
    let tt = travel_time_min(problem);
    let per_support = (tt * problem.rho_mah_per_min / problem.lambda_mah).ceil();
    let rounds = supports * per_support;
    if rounds <= MAX_FB_ROUNDS {
        return Ok(());
    }
    let per_support_max = (MAX_FB_ROUNDS / supports).floor().max(1.0);
    let lambda_min = tt * problem.rho_mah_per_min / per_support_max;
    Err(Error::invalid(
        "E4015",
        "lambda_mah",
        format!(
            "FB would give {} rounds of {} mAh on this hop ({} support drone(s), {} min at {} \
             mAh/min), more than the bound of {MAX_FB_ROUNDS} rounds per hop",
            show(rounds),
            show(problem.lambda_mah),
            supports,
            show((tt * 100.0).round() / 100.0),
            show(problem.rho_mah_per_min)
        ),
        format!(
            "raise sharing.lambda_mah to at least {} mAh, or use PB (see models/eaas.md, \
             \"FB's work bound\")",
            show(lambda_min.ceil())
        ),
    ))
}

/// Every drone's battery at every breakpoint (leg ends, transfer starts and ends, consumers
/// filling up, support drones reaching their reserve) of the schedule `transfers`; between
/// breakpoints batteries are linear.
///
/// # Arguments
/// * `problem` - the hop.
/// * `transfers` - a schedule, typically [`HopOutcome::transfers`].
///
/// # Returns
/// `(t_min, battery_mah per drone)` pairs, `t` ascending from 0 to `tt`.
///
/// # Errors
/// [`Error::Invalid`] for a malformed problem, or a transfer naming a drone or slot that does not
/// exist (`E4013`).
///
/// # Complexity
/// `O(P * D)` plus sorting the transfers.
pub fn battery_trace(problem: &HopProblem, transfers: &[Transfer]) -> Result<Vec<(f64, Vec<f64>)>> {
    validate(problem)?;
    let n = problem.drones.len();
    let bad: Vec<Violation> = transfers
        .iter()
        .enumerate()
        .filter(|(_, x)| x.support >= n || x.consumer >= n || x.consumer_slot >= n)
        .map(|(i, x)| {
            Violation::new(
                "E4013",
                format!("transfers[{i}]"),
                format!(
                    "support {}, consumer {} or slot {} out of range (0..{n})",
                    x.support, x.consumer, x.consumer_slot
                ),
                "name existing drones and slots",
            )
        })
        .collect();
    if !bad.is_empty() {
        return Err(Error::Invalid(bad));
    }
    Ok(simulate::evaluate(problem, transfers).trace())
}

/// Edge travel time `tt`, minutes: the sum of the legs' durations.
pub fn travel_time_min(problem: &HopProblem) -> f64 {
    problem.legs.iter().map(|l| l.duration_min).sum()
}

/// Delivery drones each support drone is responsible for (the paper: "each support drone will be
/// responsible for charging a subset of the delivery drones"): every delivery drone goes to the
/// support drone nearest to it in the initial formation, ties to the lower support id. Returns,
/// per drone id, the responsible support drone (`None` for support drones, and for every drone
/// when the swarm has no support drone). Each subset is served in drone id order.
pub fn responsible_support(problem: &HopProblem) -> Vec<Option<usize>> {
    let supports: Vec<usize> = (0..problem.drones.len())
        .filter(|&d| problem.drones[d].role == Role::Support)
        .collect();
    (0..problem.drones.len())
        .map(|d| {
            if problem.drones[d].role == Role::Support {
                return None;
            }
            let mut best: Option<(f64, usize)> = None;
            for &s in &supports {
                let dist = reorder::slot_distance_m(
                    problem,
                    problem.initial_slot[d],
                    problem.initial_slot[s],
                );
                if best.is_none_or(|(bd, _)| dist < bd - 1e-12) {
                    best = Some((dist, s));
                }
            }
            best.map(|(_, s)| s)
        })
        .collect()
}

/// Energy support drone `s` may share on the hop, mAh: its battery at `tt` without sharing
/// (it never moves, so its own consumption is fixed) minus `delta`, floored at zero.
pub fn sharing_budget_mah(problem: &HopProblem, s: usize) -> f64 {
    let q = problem.initial_slot[s];
    let own: f64 = problem
        .legs
        .iter()
        .map(|l| l.rate_mah_per_min[s][q] * l.duration_min)
        .sum();
    (problem.drones[s].battery_mah - own - problem.delta_mah).max(0.0)
}

/// Checks a problem's shape and numbers; every violation at once.
///
/// # Errors
/// [`Error::Invalid`] with codes `E4001`-`E4012`.
pub fn validate(problem: &HopProblem) -> Result<()> {
    let mut v = Vec::new();
    validate_slots(problem, &mut v);
    validate_legs(problem, &mut v);
    validate_drones(problem, &mut v);
    validate_sharing_constants(problem, &mut v);
    if v.is_empty() {
        Ok(())
    } else {
        Err(Error::Invalid(v))
    }
}

/// A finite number at least 0.
fn finite_nonneg(x: f64) -> bool {
    x.is_finite() && x >= 0.0
}

/// E4001-E4004: one slot per drone, the initial slots a permutation, every slot finite.
fn validate_slots(problem: &HopProblem, v: &mut Vec<Violation>) {
    let n = problem.drones.len();
    if problem.slots_m.len() != n {
        v.push(Violation::new(
            "E4001",
            "slots_m",
            format!("{} slots for {n} drones", problem.slots_m.len()),
            "give exactly one formation slot per drone",
        ));
    }
    if problem.initial_slot.len() != n {
        v.push(Violation::new(
            "E4002",
            "initial_slot",
            format!("{} entries for {n} drones", problem.initial_slot.len()),
            "give one initial slot per drone",
        ));
    } else {
        let mut seen = vec![false; n];
        let ok = problem
            .initial_slot
            .iter()
            .all(|&q| q < n && !std::mem::replace(&mut seen[q], true));
        if !ok {
            v.push(Violation::new(
                "E4003",
                "initial_slot",
                format!("{:?} is not a permutation of 0..{n}", problem.initial_slot),
                "assign every drone a distinct slot",
            ));
        }
    }
    for (i, p) in problem.slots_m.iter().enumerate() {
        if !(p.x.is_finite() && p.y.is_finite()) {
            v.push(Violation::new(
                "E4004",
                format!("slots_m[{i}]"),
                format!("({}, {}) is not finite", p.x, p.y),
                "give finite slot coordinates in metres",
            ));
        }
    }
}

/// E4005-E4007: every leg's duration, the shape of its rate matrix, then its rates.
fn validate_legs(problem: &HopProblem, v: &mut Vec<Violation>) {
    let n = problem.drones.len();
    for (l, leg) in problem.legs.iter().enumerate() {
        if !finite_nonneg(leg.duration_min) {
            v.push(Violation::new(
                "E4005",
                format!("legs[{l}].duration_min"),
                format!("{} is not a finite duration >= 0", leg.duration_min),
                "give leg durations in minutes, >= 0",
            ));
        }
        let shape_ok = leg.rate_mah_per_min.len() == n
            && leg.rate_mah_per_min.iter().all(|row| row.len() == n);
        if !shape_ok {
            v.push(Violation::new(
                "E4006",
                format!("legs[{l}].rate_mah_per_min"),
                format!("not a {n} x {n} matrix [drone][slot]"),
                "give one rate per drone and slot",
            ));
        } else if let Some((d, q)) = (0..n)
            .flat_map(|d| (0..n).map(move |q| (d, q)))
            .find(|&(d, q)| !finite_nonneg(leg.rate_mah_per_min[d][q]))
        {
            v.push(Violation::new(
                "E4007",
                format!("legs[{l}].rate_mah_per_min[{d}][{q}]"),
                format!("{} is not a finite rate >= 0", leg.rate_mah_per_min[d][q]),
                "give consumption rates in mAh/min, >= 0",
            ));
        }
    }
}

/// E4008, E4009: every drone's capacity, then its battery within it.
fn validate_drones(problem: &HopProblem, v: &mut Vec<Violation>) {
    for (d, dr) in problem.drones.iter().enumerate() {
        if !(dr.capacity_mah.is_finite() && dr.capacity_mah > 0.0) {
            v.push(Violation::new(
                "E4008",
                format!("drones[{d}].capacity_mah"),
                format!("{} is not a finite capacity > 0", dr.capacity_mah),
                "give the battery capacity in mAh",
            ));
        } else if !(finite_nonneg(dr.battery_mah) && dr.battery_mah <= dr.capacity_mah) {
            v.push(Violation::new(
                "E4009",
                format!("drones[{d}].battery_mah"),
                format!(
                    "{} is not within [0, capacity {}]",
                    dr.battery_mah, dr.capacity_mah
                ),
                "give a battery between 0 and the capacity",
            ));
        }
    }
}

/// E4010-E4012: the sharing constants `rho`, `lambda`, range, `gamma` and `delta`.
fn validate_sharing_constants(problem: &HopProblem, v: &mut Vec<Violation>) {
    if !(problem.rho_mah_per_min.is_finite() && problem.rho_mah_per_min > 0.0) {
        v.push(Violation::new(
            "E4010",
            "rho_mah_per_min",
            format!("{} is not a finite rate > 0", problem.rho_mah_per_min),
            "give the sharing rate in mAh/min (5.88 in the paper)",
        ));
    }
    if !(problem.lambda_mah.is_finite() && problem.lambda_mah > 0.0) {
        v.push(Violation::new(
            "E4011",
            "lambda_mah",
            format!("{} is not a finite energy > 0", problem.lambda_mah),
            "give the FB round energy in mAh (2240 in the paper)",
        ));
    }
    for (field, x) in [
        ("range_m", problem.range_m),
        ("gamma_mah", problem.gamma_mah),
        ("delta_mah", problem.delta_mah),
    ] {
        if !finite_nonneg(x) {
            v.push(Violation::new(
                "E4012",
                field,
                format!("{x} is not a finite number >= 0"),
                "give a finite value >= 0",
            ));
        }
    }
}

/// Slot positions as `[x, y]` pairs in JSON/TOML (nalgebra's serde support is not enabled).
mod slots_serde {
    use nalgebra::Vector2;
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub fn serialize<S: Serializer>(v: &[Vector2<f64>], s: S) -> Result<S::Ok, S::Error> {
        let pairs: Vec<[f64; 2]> = v.iter().map(|p| [p.x, p.y]).collect();
        pairs.serialize(s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<Vector2<f64>>, D::Error> {
        let pairs = Vec::<[f64; 2]>::deserialize(d)?;
        Ok(pairs.into_iter().map(|[x, y]| Vector2::new(x, y)).collect())
    }
}
