//! The continuous-time configuration LP of one hop, see `models/eaas_config.md`.
//!
//! Inside a leg every rate is constant. A configuration `σ` is a set of moves that can run at the
//! same time (at most one consumer per support drone, a delivery drone in at most one move as
//! consumer or swap partner), the empty set included; while it runs, drone `d` changes its battery
//! at the constant rate `v[l][σ][d]`. Only the time spent in each configuration matters to the
//! leg-end batteries:
//!
//! ```text
//! θ[l][σ] >= 0                       minutes of leg l spent in configuration σ
//! sum_σ θ[l][σ] = τ_l
//! b[d][l+1] = b[d][l] + sum_σ v[l][σ][d] θ[l][σ],   m <= b[d][l+1] <= C_d - m
//! rho sum_{l, σ : s serves in σ} θ[l][σ] <= B_s      support reserve
//! ```
//!
//! plus the objective's rows (the exact `k`-pad assignment for the node time). With margin
//! `m = 0` its value is the infimum of the objective over every continuous-time schedule of the
//! mode (under the Slater condition of the write-up) and a lower bound on every schedule in any
//! case. A schedule is realised from `θ` by playing each leg's configurations in rounds of
//! adaptive length (each round the same fraction of every share, so its end lies on the line
//! between the leg-end batteries), in an order chosen round by round so that every battery stays
//! in `[0, C_d]`; when that fails within [`MAX_ROUNDS`] rounds, the model is solved again with a
//! margin `m > 0` and a short start in the empty configuration, whose schedule is realisable and
//! within a certified `ε` of the infimum. The empty schedule and the heuristics' schedules (when
//! the mode contains them) are incumbents from the start, so a hop that flies without sharing
//! always has a schedule. In `free` re-ordering a configuration is a slot assignment of the
//! delivery drones with a matching, and a schedule is a list of [`SlotInterval`]s.

use super::EndPads;
use super::{
    backend_end, moves, objective_of, validate_inputs, BackendEnd, ExactOutcome, ExactStatus, Move,
    Objective, PadRows, Reorder,
};
use crate::eaas::simulate::evaluate;
use crate::eaas::simulate::leg_at;
use crate::eaas::{
    reorder, sharing_budget_mah, simulate_with, FreeSchedule, Heuristic, HopOutcome, HopProblem,
    PolicyOptions, Role, SlotInterval, Transfer, ENERGY_TOL_MAH, TIME_TOL_MIN,
};
use crate::error::{BackendFailure, Error, Result};
#[cfg(feature = "microlp")]
use crate::solver::dense::{DenseLp, Sense};
use crate::solver::{run_on, BackendStatus, MilpBackend, MilpJob, MilpModel, MIP_REL_GAP};
use good_lp::{
    constraint, variable, Expression, ProblemVariables, Solution, SolverModel, Variable,
    WithTimeLimit,
};
use serde::{Deserialize, Serialize};
use std::time::Instant;

#[cfg(feature = "microlp")]
mod pad_search;

/// Where a model's rows go: a good_lp model, or the pad search's dense LP ([`DenseRows`]).
trait Rows {
    fn row(&mut self, c: good_lp::Constraint);
}

impl<M: SolverModel> Rows for M {
    fn row(&mut self, c: good_lp::Constraint) {
        self.add_constraint(c);
    }
}

/// The rows of a model written into a [`DenseLp`] whose columns are good_lp's variables in
/// their order (column `i` is variable `i`).
#[cfg(feature = "microlp")]
struct DenseRows(DenseLp);

#[cfg(feature = "microlp")]
impl Rows for DenseRows {
    fn row(&mut self, c: good_lp::Constraint) {
        use good_lp::IntoAffineExpression;
        let e = c.expression();
        let terms: Vec<(usize, f64)> = e
            .linear_coefficients()
            .map(|(v, a)| (crate::solver::variable_index(v), a))
            .collect();
        // good_lp keeps `expression <= 0` (or `= 0`).
        let sense = if c.is_equality() {
            Sense::Eq
        } else {
            Sense::Le
        };
        self.0.add_row(terms, sense, -e.constant());
    }
}

/// Default largest number of configurations a hop may have (E4117 above it).
pub const DEFAULT_MAX_CONFIGURATIONS: usize = 20_000;
/// The margin search stops at the first schedule within this relative distance of the optimum.
pub const MARGIN_REL_EPSILON: f64 = 1e-6;
/// Largest number of rounds a leg's configurations are played in.
pub const MAX_ROUNDS: usize = 8192;
/// Shortest round, as a fraction of the leg's time shares.
pub const MIN_ROUND_FRACTION: f64 = 1e-9;
/// Relative tolerance under which a schedule's objective equals the model's optimum
/// (status `optimal`); above it the status is `optimal_within` with the distance.
pub const OPTIMAL_REL_TOL: f64 = 1e-9;
/// Absolute part of that tolerance (minutes or mAh).
pub const OPTIMAL_ABS_TOL: f64 = 1e-7;
/// How far, relative to `max(1, |V|)`, a replayed schedule may beat the model's value `V`
/// before that is a bug (`E4119`): `V` is a simplex value, exact only up to the solver's
/// round-off, which the pad search's chains of warm re-solves accumulate. Measured: r00338 of
/// findings-195 (`solve --route optimal --sharing exact`, paper-findings profile), a leaf's
/// value 67.97234731853423 min against its replayed schedule's 67.97234707591778 (3.6e-9
/// relative); 1e-8 leaves a margin of about three.
pub const SOLVER_ROUNDOFF_REL: f64 = 1e-8;
/// Energy tolerance of the realisation's bound checks, mAh.
const REALISE_TOL_MAH: f64 = 1e-7;
/// Margins tried, in this order, when the optimum is not attained: fractions of the smallest
/// capacity. Each is a further LP solve and realisation; the best realised schedule is kept, and
/// the first margin that cannot be realised after one that could ends the search (a smaller one
/// needs still more rounds).
const MARGIN_FRACTIONS: [f64; 5] = [1e-4, 1e-5, 1e-6, 1e-7, 1e-8];

/// Settings of a continuous solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContinuousOptions {
    /// Re-ordering mode (default [`Reorder::Paper`]).
    pub reorder: Reorder,
    /// Backend of the LP (a MILP with the node-time objective's pad rows).
    pub backend: MilpBackend,
    /// Wall-clock limit of each backend call, seconds (default 60); `f64::INFINITY`: none.
    #[serde(with = "crate::solver::seconds_or_none")]
    pub time_limit_s: f64,
    /// Branch-and-bound nodes of each backend call (default `None`: no limit), the same on every
    /// machine.
    #[serde(default)]
    pub node_limit: Option<u64>,
    /// Largest number of configurations (default [`DEFAULT_MAX_CONFIGURATIONS`]).
    pub max_configurations: usize,
    /// Readings of PB and FB, whose schedules are incumbents.
    pub readings: PolicyOptions,
    /// How the node time's pad assignment is solved when the relaxation does not settle it
    /// (default [`PadMethod::Search`]).
    #[serde(default)]
    pub pad_method: PadMethod,
}

/// How the continuous model's pad assignment (node-time objective) is solved once its relaxation
/// and the relaxation's assignment leave a gap.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum PadMethod {
    /// The branch and bound over the assignment on microlp's warm re-solves
    /// (`models/eaas_config.md`, "The pad search"); on the `highs` backend, or when microlp
    /// fails on a node, the pad MILP.
    #[default]
    Search,
    /// The pad MILP with the backend's own branch and bound: the reference the search is tested
    /// against.
    Milp,
}

impl ContinuousOptions {
    /// The options of a caller that also runs the grid MILP: its re-ordering, backend, time and
    /// node limits, the default largest number of configurations, and the heuristics' readings.
    pub fn like(milp: &super::milp::MilpOptions, readings: PolicyOptions) -> ContinuousOptions {
        ContinuousOptions {
            reorder: milp.reorder,
            backend: milp.backend,
            time_limit_s: milp.time_limit_s,
            node_limit: milp.node_limit,
            max_configurations: DEFAULT_MAX_CONFIGURATIONS,
            readings,
            pad_method: PadMethod::default(),
        }
    }
}

impl Default for ContinuousOptions {
    fn default() -> Self {
        ContinuousOptions {
            reorder: Reorder::Paper,
            backend: MilpBackend::default(),
            time_limit_s: 60.0,
            node_limit: None,
            max_configurations: DEFAULT_MAX_CONFIGURATIONS,
            readings: PolicyOptions::default(),
            pad_method: PadMethod::default(),
        }
    }
}

/// A set of moves that can run at the same time.
#[derive(Debug, Clone, PartialEq)]
pub struct Configuration {
    /// `(support, consumer, consumer's slot)` of every move.
    pub moves: Vec<(usize, usize, usize)>,
    /// Slot of every drone while the configuration runs.
    pub slot: Vec<usize>,
}

impl Configuration {
    fn serves(&self, s: usize) -> bool {
        self.moves.iter().any(|m| m.0 == s)
    }

    /// Battery rate of every drone on a leg with consumption `rates`, mAh/min.
    fn rates(&self, problem: &HopProblem, rates: &[Vec<f64>]) -> Vec<f64> {
        let rho = problem.rho_mah_per_min;
        let mut v: Vec<f64> = (0..problem.drones.len())
            .map(|d| -rates[d][self.slot[d]])
            .collect();
        for &(s, c, _) in &self.moves {
            v[s] -= rho;
            v[c] += rho;
        }
        v
    }
}

/// Every configuration of `mode`, the empty one first; in `free` mode every slot permutation of
/// the delivery drones with every matching of support drones to consumers within range.
///
/// # Errors
/// `E4117` when there are more than `max` of them.
pub fn configurations(
    problem: &HopProblem,
    mode: Reorder,
    max: usize,
) -> Result<Vec<Configuration>> {
    let n = problem.drones.len();
    let supports: Vec<usize> = (0..n)
        .filter(|&d| problem.drones[d].role == Role::Support)
        .collect();
    let mut out = Vec::new();
    let too_many = || {
        Error::invalid(
            "E4117",
            "max_configurations",
            format!("the hop has more than {max} configurations in {mode} re-ordering"),
            "raise --max-configurations, or use --reorder paper or none (fewer moves)",
        )
    };
    let slots_list: Vec<Vec<usize>> = if mode == Reorder::Free {
        free_slot_assignments(problem, max).ok_or_else(too_many)?
    } else {
        vec![problem.initial_slot.clone()]
    };
    let mv = moves(problem, mode);
    for slot in &slots_list {
        // The moves of this slot assignment.
        let here: Vec<Move> = if mode == Reorder::Free {
            mv.iter()
                .filter(|m| {
                    reorder::slot_distance_m(problem, slot[m.support], slot[m.consumer])
                        <= problem.range_m
                })
                .map(|m| Move {
                    slot: slot[m.consumer],
                    partner: None,
                    ..*m
                })
                .collect()
        } else {
            mv.clone()
        };
        let mut used = vec![false; n];
        let mut chosen = Vec::new();
        let mut ctx = Enumeration {
            problem,
            supports: &supports,
            moves: &here,
            slot,
            max,
            out: &mut out,
        };
        if !ctx.walk(0, &mut used, &mut chosen) {
            return Err(too_many());
        }
    }
    Ok(out)
}

/// Depth-first enumeration of the drone-disjoint move sets, one support drone at a time.
struct Enumeration<'a> {
    problem: &'a HopProblem,
    supports: &'a [usize],
    moves: &'a [Move],
    slot: &'a [usize],
    max: usize,
    out: &'a mut Vec<Configuration>,
}

impl Enumeration<'_> {
    /// False when the count exceeds `max`.
    fn walk(&mut self, i: usize, used: &mut [bool], chosen: &mut Vec<usize>) -> bool {
        if i == self.supports.len() {
            if self.out.len() >= self.max {
                return false;
            }
            let mut slot = self.slot.to_vec();
            let mut list = Vec::new();
            for &k in chosen.iter() {
                let m = self.moves[k];
                if let Some(p) = m.partner {
                    slot[p] = self.problem.initial_slot[m.consumer];
                }
                slot[m.consumer] = m.slot;
                list.push((m.support, m.consumer, m.slot));
            }
            self.out.push(Configuration { moves: list, slot });
            return true;
        }
        if !self.walk(i + 1, used, chosen) {
            return false;
        }
        let s = self.supports[i];
        for k in 0..self.moves.len() {
            let Move {
                support: ks,
                consumer: c,
                partner: p,
                ..
            } = self.moves[k];
            if ks != s || used[c] || p.is_some_and(|p| used[p]) {
                continue;
            }
            used[c] = true;
            if let Some(p) = p {
                used[p] = true;
            }
            chosen.push(k);
            let ok = self.walk(i + 1, used, chosen);
            chosen.pop();
            used[c] = false;
            if let Some(p) = p {
                used[p] = false;
            }
            if !ok {
                return false;
            }
        }
        true
    }
}

/// Every assignment of the delivery drones to their slots (support drones keep theirs), the
/// initial one first; `None` above `max`.
fn free_slot_assignments(problem: &HopProblem, max: usize) -> Option<Vec<Vec<usize>>> {
    let delivery: Vec<usize> = (0..problem.drones.len())
        .filter(|&d| problem.drones[d].role == Role::Delivery)
        .collect();
    let open: Vec<usize> = delivery.iter().map(|&d| problem.initial_slot[d]).collect();
    let mut count: usize = 1;
    for k in 1..=delivery.len() {
        count = count.checked_mul(k)?;
        if count > max {
            return None;
        }
    }
    let mut out = Vec::with_capacity(count);
    let mut perm: Vec<usize> = (0..open.len()).collect();
    loop {
        let mut slot = problem.initial_slot.clone();
        for (i, &d) in delivery.iter().enumerate() {
            slot[d] = open[perm[i]];
        }
        out.push(slot);
        // Next permutation in lexicographic order.
        let Some(i) = (1..perm.len()).rev().find(|&i| perm[i - 1] < perm[i]) else {
            break;
        };
        let j = (i..perm.len()).rev().find(|&j| perm[j] > perm[i - 1])?;
        perm.swap(i - 1, j);
        perm[i..].reverse();
    }
    Some(out)
}

/// The legs of positive duration, with every configuration's rates on each.
struct Model<'a> {
    problem: &'a HopProblem,
    configs: &'a [Configuration],
    /// Legs of positive duration.
    legs: Vec<usize>,
    /// `v[i][σ][d]`, leg index `i` into `legs`.
    v: Vec<Vec<Vec<f64>>>,
    /// `free` re-ordering: schedules are slot intervals, not transfers.
    free: bool,
}

/// How the node time's pad assignment enters a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Pads<'a> {
    /// The exact assignment rows, binaries in `[0, 1]`: a lower bound.
    Relaxed,
    /// The exact assignment rows with binaries: the model of the theorem; the pads' symmetry
    /// broken along the drones' ranks (see `PadRows::add`).
    Integral(&'a [usize]),
    /// A fixed assignment, the pad of every drone: an LP whose value bounds the optimum from
    /// above.
    Fixed(&'a [usize]),
    /// No assignment yet: every `ct_d <= M` and `sum_d ct_d <= min(k, n) M`, the root of the
    /// pad search ([`pad_search`]), which adds each pad's load rows as it assigns drones.
    #[cfg_attr(not(feature = "microlp"), allow(dead_code))]
    Aggregate,
}

/// One solve of the model: leg-end bounds `[margin, C_d - margin]`, at least `start_min` of the
/// first leg in the empty configuration, and the pads as `pads` says.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Attempt<'a> {
    margin_mah: f64,
    start_min: f64,
    pads: Pads<'a>,
    /// Multiplies the model's energy unit (1 but on a retry after a numerical failure).
    rescale: f64,
}

impl Attempt<'_> {
    /// The model of the theorem (no margin, no empty start) with the pads as `pads` says.
    fn exact(pads: Pads<'_>) -> Attempt<'_> {
        Attempt {
            margin_mah: 0.0,
            start_min: 0.0,
            pads,
            rescale: 1.0,
        }
    }
}

/// The values of one solve.
struct Values {
    /// `θ[i][σ]`, minutes.
    theta: Vec<Vec<f64>>,
    /// The model's objective value.
    value: f64,
    /// A proven bound on the model's optimum (lower for minimisation, upper for max-min): the
    /// value itself when proven optimal, the value less HiGHS's relative gap
    /// ([`MIP_REL_GAP`]) after a stop at that gap, `None` after a time limit.
    bound: Option<f64>,
}

/// How one solve ended.
enum Solved {
    Values(Values),
    Infeasible,
    NoSolution,
}

impl Model<'_> {
    /// Solves the model of `attempt`; after a numerical failure of the backend, again in
    /// energy units 4 and 1/4 times as large.
    fn solve(
        &self,
        objective: &Objective,
        options: &ContinuousOptions,
        attempt: Attempt,
    ) -> Result<Solved> {
        let mut answer = self.solve_once(objective, options, attempt);
        for rescale in [4.0, 0.25] {
            if !matches!(
                answer,
                Err(Error::Backend {
                    kind: BackendFailure::Numerical,
                    ..
                })
            ) {
                break;
            }
            answer = self.solve_once(objective, options, Attempt { rescale, ..attempt });
        }
        answer
    }

    fn solve_once(
        &self,
        objective: &Objective,
        options: &ContinuousOptions,
        attempt: Attempt,
    ) -> Result<Solved> {
        let job = ModelJob {
            model: self,
            objective,
            attempt,
            time_limit_s: options.time_limit_s,
        };
        run_on(options.backend, options.node_limit, job)
    }

    fn solve_with<S: good_lp::Solver>(
        &self,
        solver: S,
        backend_name: &str,
        objective: &Objective,
        attempt: Attempt,
        time_limit_s: f64,
    ) -> Result<Solved>
    where
        S::Model: MilpModel,
    {
        let Built {
            model,
            theta,
            goal,
            scale,
        } = self.build(solver, objective, attempt, time_limit_s);
        let (status, solution) = match backend_end(model.solve_outcome(), backend_name)? {
            BackendEnd::Solved(status, s) => (status, s),
            BackendEnd::Infeasible => return Ok(Solved::Infeasible),
            BackendEnd::NoSolution => return Ok(Solved::NoSolution),
        };
        let value = goal.map_or(0.0, |g| match objective {
            Objective::MaxMinArrival => solution.value(g) / scale,
            _ => solution.value(g),
        });
        let bound = match status {
            BackendStatus::Optimal => Some(value),
            // HiGHS's relative gap is (incumbent - bound) / max(|incumbent|, a tiny guard), so
            // the bound is at least the incumbent less the gap times max(|incumbent|, 1); only
            // the node time (a minimisation) has integer variables.
            BackendStatus::OptimalWithinGap => Some(value - MIP_REL_GAP * value.abs().max(1.0)),
            BackendStatus::Feasible
            | BackendStatus::LimitNoSolution
            | BackendStatus::Infeasible
            | BackendStatus::Unbounded => None,
        };
        Ok(Solved::Values(Values {
            theta: theta
                .iter()
                .map(|row| row.iter().map(|&t| solution.value(t).max(0.0)).collect())
                .collect(),
            value,
            bound,
        }))
    }

    /// Builds the model of `attempt` with `solver` (rows 1-4 of `models/eaas_config.md`, the
    /// margin and empty start of row 5, the objective's rows as `attempt.pads` says).
    fn build<S: good_lp::Solver>(
        &self,
        solver: S,
        objective: &Objective,
        attempt: Attempt,
        time_limit_s: f64,
    ) -> Built<S::Model>
    where
        S::Model: SolverModel + WithTimeLimit,
    {
        let scale = self.energy_scale(objective, attempt.rescale);
        let columns = self.columns(objective, attempt, scale);
        let mut model = match (objective, columns.goal) {
            (Objective::MaxMinArrival, Some(g)) => columns.vars.maximise(g),
            (_, Some(g)) => columns.vars.minimise(g),
            _ => columns.vars.minimise(Expression::from(0.0)),
        }
        .using(solver)
        .with_time_limit(time_limit_s);
        let (theta, b, goal) = (columns.theta, columns.b, columns.goal);
        self.add_flow_rows(&mut model, &theta, &b, scale, attempt.start_min);
        self.add_sharing_budgets(&mut model, &theta, scale);
        let final_battery = self.final_battery_expressions(&b, scale);
        if let Some(g) = goal {
            self.add_objective_rows(
                &mut model,
                objective,
                g,
                (columns.pads.as_ref(), attempt.pads),
                &final_battery,
                scale,
            );
        }
        if let (Objective::NodeTime(end), Some(g), Pads::Aggregate) =
            (*objective, goal, attempt.pads)
        {
            self.add_pad_search_root(&mut model, end, g, &b, &final_battery, scale);
        }
        Built {
            model,
            theta,
            goal,
            scale,
        }
    }

    /// Energies enter the model in a unit of `1 / scale` mAh: minutes of pad charging for the
    /// node time (so charge times, batteries and rates are of like size, which microlp's branch
    /// and bound needs), hundredths of the largest capacity otherwise; times `rescale`.
    fn energy_scale(&self, objective: &Objective, rescale: f64) -> f64 {
        rescale
            * match *objective {
                Objective::NodeTime(EndPads {
                    pad_rate_mah_per_min,
                    ..
                }) => 1.0 / pad_rate_mah_per_min,
                _ => {
                    100.0
                        / self
                            .problem
                            .drones
                            .iter()
                            .map(|d| d.capacity_mah)
                            .fold(1e-9, f64::max)
                }
            }
    }

    /// The variables, in this order: the time shares `θ`, the leg-end batteries `b` (within the
    /// margin), the goal (`M` or `g`) and the pad rows as `attempt.pads` says.
    fn columns(&self, objective: &Objective, attempt: Attempt, scale: f64) -> Columns {
        let problem = self.problem;
        let n = problem.drones.len();
        let mut vars = ProblemVariables::new();
        let theta: Vec<Vec<Variable>> = self
            .legs
            .iter()
            .map(|&l| {
                (0..self.configs.len())
                    .map(|k| vars.add(variable().min(0.0).name(format!("theta_l{l}_k{k}"))))
                    .collect()
            })
            .collect();
        let margin_mah = attempt.margin_mah;
        let b: Vec<Vec<Variable>> = problem
            .drones
            .iter()
            .enumerate()
            .map(|(d, drone)| {
                let (lo, hi) = (
                    scale * margin_mah,
                    scale * (drone.capacity_mah - margin_mah),
                );
                self.legs
                    .iter()
                    .map(|&l| vars.add(variable().min(lo).max(hi).name(format!("b_d{d}_l{l}"))))
                    .collect()
            })
            .collect();
        let (goal, pads) = match *objective {
            Objective::NodeTime(EndPads { pads, .. }) => (
                Some(vars.add(variable().min(0.0).name("M"))),
                match attempt.pads {
                    Pads::Fixed(_) | Pads::Aggregate => None,
                    Pads::Relaxed => Some(PadRows::add(&mut vars, n, pads, true, None)),
                    Pads::Integral(rank) => {
                        Some(PadRows::add(&mut vars, n, pads, false, Some(rank)))
                    }
                },
            ),
            Objective::MaxMinArrival => (Some(vars.add(variable().name("g"))), None),
            Objective::Feasible => (None, None),
        };
        Columns {
            vars,
            theta,
            b,
            goal,
            pads,
        }
    }

    /// Rows 1-2 of every leg: its time shares fill it, and each battery changes by the
    /// configurations' rates; the empty start (row 5) when `start_min > 0`.
    fn add_flow_rows<R: Rows>(
        &self,
        model: &mut R,
        theta: &[Vec<Variable>],
        b: &[Vec<Variable>],
        scale: f64,
        start_min: f64,
    ) {
        let problem = self.problem;
        for (i, &l) in self.legs.iter().enumerate() {
            let tau = problem.legs[l].duration_min;
            let all: Expression = theta[i].iter().copied().sum();
            model.row(constraint!(all == tau));
            for (d, bd) in b.iter().enumerate() {
                let prev = if i == 0 {
                    Expression::from(scale * problem.drones[d].battery_mah)
                } else {
                    Expression::from(bd[i - 1])
                };
                let change: Expression = (0..self.configs.len())
                    .filter(|&k| self.v[i][k][d] != 0.0)
                    .map(|k| scale * self.v[i][k][d] * theta[i][k])
                    .sum();
                model.row(constraint!(bd[i] == prev + change));
            }
        }
        if start_min > 0.0 && !theta.is_empty() {
            model.row(constraint!(theta[0][0] >= start_min));
        }
    }

    /// Row 3: what each support drone gives stays within its sharing budget.
    fn add_sharing_budgets<R: Rows>(&self, model: &mut R, theta: &[Vec<Variable>], scale: f64) {
        let problem = self.problem;
        let rho = problem.rho_mah_per_min;
        for s in (0..problem.drones.len()).filter(|&s| problem.drones[s].role == Role::Support) {
            let given: Expression = theta
                .iter()
                .flat_map(|row| {
                    row.iter()
                        .enumerate()
                        .filter(|(k, _)| self.configs[*k].serves(s))
                        .map(|(_, &t)| scale * rho * t)
                })
                .sum();
            model.row(constraint!(given <= scale * sharing_budget_mah(problem, s)));
        }
    }

    /// The objective's rows on the goal `g`: the node time's pad rows (exact or relaxed
    /// assignment, or each pad's load under a fixed one), or the least delivery battery.
    fn add_objective_rows<M: SolverModel>(
        &self,
        model: &mut M,
        objective: &Objective,
        g: Variable,
        (rows, pad_mode): (Option<&PadRows>, Pads<'_>),
        final_battery: &[Expression],
        scale: f64,
    ) {
        let problem = self.problem;
        let n = problem.drones.len();
        match (*objective, rows) {
            (
                Objective::NodeTime(EndPads {
                    pad_rate_mah_per_min,
                    ..
                }),
                Some(rows),
            ) => {
                let caps: Vec<f64> = problem
                    .drones
                    .iter()
                    .map(|d| scale * d.capacity_mah)
                    .collect();
                rows.constrain(model, &caps, final_battery, scale * pad_rate_mah_per_min, g)
            }
            (
                Objective::NodeTime(EndPads {
                    pad_rate_mah_per_min,
                    ..
                }),
                None,
            ) => {
                if let Pads::Fixed(pad_of) = pad_mode {
                    // Each pad's load, in minutes: sum of (C_d - b_d(tt)) / pad rate.
                    let per_min = 1.0 / (scale * pad_rate_mah_per_min);
                    let pads_used = pad_of.iter().copied().max().map_or(0, |p| p + 1);
                    for pad in 0..pads_used {
                        let load: Expression = (0..n)
                            .filter(|&d| pad_of[d] == pad)
                            .map(|d| {
                                (scale * problem.drones[d].capacity_mah - final_battery[d].clone())
                                    * per_min
                            })
                            .sum();
                        model.add_constraint(constraint!(load <= g));
                    }
                }
            }
            (Objective::MaxMinArrival, _) => {
                for d in (0..n).filter(|&d| problem.drones[d].role == Role::Delivery) {
                    model.add_constraint(constraint!(g <= final_battery[d].clone()));
                }
            }
            _ => {}
        }
    }

    /// The pad search's root (node time): every `ct_d <= M` and `sum_d ct_d <= min(k, n) M`;
    /// returns each drone's charge time in the model's variables.
    fn add_pad_search_root<R: Rows>(
        &self,
        model: &mut R,
        end: EndPads,
        g: Variable,
        b: &[Vec<Variable>],
        final_battery: &[Expression],
        scale: f64,
    ) -> Vec<ChargeTime> {
        let problem = self.problem;
        let n = problem.drones.len();
        let per_min = 1.0 / (scale * end.pad_rate_mah_per_min);
        let mut charge_times = Vec::new();
        for (d, drone) in problem.drones.iter().enumerate() {
            let ct = (scale * drone.capacity_mah - final_battery[d].clone()) * per_min;
            model.row(constraint!(ct <= g));
            charge_times.push(match b[d].last() {
                Some(&var) => ChargeTime {
                    battery: Some(var),
                    per_min,
                    constant: scale * drone.capacity_mah * per_min,
                },
                None => ChargeTime {
                    battery: None,
                    per_min,
                    constant: (scale * (drone.capacity_mah - drone.battery_mah)) * per_min,
                },
            });
        }
        let total: Expression = (0..n)
            .map(|d| (scale * problem.drones[d].capacity_mah - final_battery[d].clone()) * per_min)
            .sum();
        let m = end.pads.min(n).max(1) as f64;
        model.row(constraint!(total <= m * g));
        charge_times
    }
}

/// The variables of one model, before the objective is set.
struct Columns {
    vars: ProblemVariables,
    /// `θ[i][σ]`.
    theta: Vec<Vec<Variable>>,
    /// `b[d][i]`.
    b: Vec<Vec<Variable>>,
    /// `M` (node time) or `g` (least delivery battery); none for feasibility.
    goal: Option<Variable>,
    /// The exact or relaxed assignment rows of the node time.
    pads: Option<PadRows>,
}

/// What the pad search found, in the model's terms.
struct Searched {
    /// The best leaf below the incumbent: the pad of every drone and its time shares.
    leaf: Option<(Vec<usize>, Vec<Vec<f64>>)>,
    value: f64,
    bound: f64,
    complete: bool,
}

/// The pad search's root solved (node time, microlp's build, [`PadMethod::Search`]): the
/// relaxation of the pad assignment, whose basis the fixed assignment and the search start from.
#[cfg(feature = "microlp")]
struct SearchRoot {
    theta: Vec<Vec<Variable>>,
    /// The column of `M`.
    makespan: usize,
    charges: Vec<pad_search::Charge>,
    pads: usize,
    tableau: crate::solver::dense::Tableau,
}

/// No pad search in a build without microlp: never built.
#[cfg(not(feature = "microlp"))]
enum SearchRoot {}

#[cfg(feature = "microlp")]
impl SearchRoot {
    /// The time shares `θ` at the optimum of `node`, minutes.
    fn theta_of(&self, node: &crate::solver::dense::Tableau) -> Vec<Vec<f64>> {
        self.theta
            .iter()
            .map(|row| {
                row.iter()
                    .map(|&t| node.value(crate::solver::variable_index(t)).max(0.0))
                    .collect()
            })
            .collect()
    }

    /// The relaxation's values: an LP optimum, so its value is a proven bound.
    fn values(&self) -> Values {
        let value = self.tableau.objective();
        Values {
            theta: self.theta_of(&self.tableau),
            value,
            bound: Some(value),
        }
    }

    /// The LP of the assignment `pad_of` (every pad's load row added to the root): its value and
    /// time shares; `None` when the simplex fails on it.
    fn fixed(&self, pad_of: &[usize]) -> Option<(f64, Vec<Vec<f64>>)> {
        let mut node = self.tableau.clone();
        let pads_used = pad_of.iter().copied().max().map_or(0, |p| p + 1);
        for pad in 0..pads_used {
            let drones: Vec<usize> = (0..pad_of.len()).filter(|&d| pad_of[d] == pad).collect();
            let (terms, rhs) = pad_search::load_row(&self.charges, self.makespan, &drones);
            node.add_row(&terms, crate::solver::dense::Sense::Le, rhs)
                .ok()?;
        }
        Some((node.objective(), self.theta_of(&node)))
    }

    /// The pad search ([`pad_search`]) below the upper bound `incumbent`, drones in the order of
    /// `rank`; `None` when the simplex fails on one of its LPs: the caller then solves the pad
    /// MILP.
    fn search(
        &self,
        options: &ContinuousOptions,
        rank: &[usize],
        incumbent: f64,
    ) -> Option<Searched> {
        let mut order: Vec<usize> = (0..rank.len()).collect();
        order.sort_by_key(|&d| rank[d]);
        let deadline = (options.time_limit_s.is_finite() && options.time_limit_s > 0.0)
            .then(|| Instant::now() + std::time::Duration::from_secs_f64(options.time_limit_s));
        let end = pad_search::search(
            self.tableau.clone(),
            &self.charges,
            self.makespan,
            &order,
            self.pads,
            incumbent,
            options.node_limit,
            deadline,
        )
        .ok()?;
        let leaf = end
            .leaf
            .map(|(pad_of, node)| (pad_of, self.theta_of(&node)));
        Some(Searched {
            leaf,
            value: end.value,
            bound: end.bound,
            complete: end.complete,
        })
    }
}

#[cfg(not(feature = "microlp"))]
impl SearchRoot {
    fn values(&self) -> Values {
        match *self {}
    }

    fn fixed(&self, _: &[usize]) -> Option<(f64, Vec<Vec<f64>>)> {
        match *self {}
    }

    fn search(&self, _: &ContinuousOptions, _: &[usize], _: f64) -> Option<Searched> {
        match *self {}
    }
}

impl Model<'_> {
    /// The pad search's root, solved: where the search applies (node time, microlp,
    /// [`PadMethod::Search`]) and the dense simplex solves it; else `None`, and the backend
    /// solves the relaxation with the pad binaries in `[0, 1]`.
    fn search_root(
        &self,
        objective: &Objective,
        options: &ContinuousOptions,
    ) -> Option<SearchRoot> {
        #[cfg(feature = "microlp")]
        {
            let Objective::NodeTime(EndPads { pads, .. }) = *objective else {
                return None;
            };
            if options.pad_method != PadMethod::Search || options.backend != MilpBackend::Microlp {
                return None;
            }
            let root = self.dense_root(objective)?;
            let tableau = root.lp.solve().ok()?;
            Some(SearchRoot {
                charges: root
                    .charge_times
                    .iter()
                    .map(pad_search::Charge::of)
                    .collect(),
                makespan: crate::solver::variable_index(root.goal),
                theta: root.theta,
                pads,
                tableau,
            })
        }
        #[cfg(not(feature = "microlp"))]
        {
            let _ = (objective, options);
            None
        }
    }
}

/// The pad search's root as a dense LP, and its handles.
#[cfg(feature = "microlp")]
struct DenseRoot {
    lp: DenseLp,
    theta: Vec<Vec<Variable>>,
    goal: Variable,
    charge_times: Vec<ChargeTime>,
}

impl Model<'_> {
    /// The model of [`Pads::Aggregate`] (no margin, no empty start) as a [`DenseLp`]: the same
    /// columns and rows [`Model::build`] gives microlp, column `i` good_lp's variable `i`;
    /// `None` for another objective than the node time.
    #[cfg(feature = "microlp")]
    fn dense_root(&self, objective: &Objective) -> Option<DenseRoot> {
        let Objective::NodeTime(end) = *objective else {
            return None;
        };
        let attempt = Attempt::exact(Pads::Aggregate);
        let scale = self.energy_scale(objective, attempt.rescale);
        let columns = self.columns(objective, attempt, scale);
        let goal = columns.goal?;
        let mut rows = DenseRows(DenseLp::new());
        for (i, (v, def)) in columns.vars.iter_variables_with_def().enumerate() {
            debug_assert_eq!(crate::solver::variable_index(v), i);
            let cost = if v == goal { 1.0 } else { 0.0 };
            rows.0.add_column(cost, def.get_min(), def.get_max());
        }
        self.add_flow_rows(
            &mut rows,
            &columns.theta,
            &columns.b,
            scale,
            attempt.start_min,
        );
        self.add_sharing_budgets(&mut rows, &columns.theta, scale);
        let final_battery = self.final_battery_expressions(&columns.b, scale);
        let charge_times =
            self.add_pad_search_root(&mut rows, end, goal, &columns.b, &final_battery, scale);
        Some(DenseRoot {
            lp: rows.0,
            theta: columns.theta,
            goal,
            charge_times,
        })
    }

    /// Every drone's battery at the hop's end in the model's unit: its last leg-end variable,
    /// or its battery now when the hop has no leg.
    fn final_battery_expressions(&self, b: &[Vec<Variable>], scale: f64) -> Vec<Expression> {
        (0..self.problem.drones.len())
            .map(|d| match b[d].last() {
                Some(&v) => Expression::from(v),
                None => Expression::from(scale * self.problem.drones[d].battery_mah),
            })
            .collect()
    }
}

/// A built model and its handles.
struct Built<M> {
    model: M,
    /// `θ[i][σ]`.
    theta: Vec<Vec<Variable>>,
    /// `M` (node time) or `g` (max-min); `None` for feasibility.
    goal: Option<Variable>,
    /// The model's energy unit is `1 / scale` mAh.
    scale: f64,
}

/// A drone's charge time in the model, minutes: `constant - per_min * b_d(tt)` with `b_d(tt)`
/// the model's variable `battery`, or `constant` alone when the hop has no leg to fly.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(not(feature = "microlp"), allow(dead_code))]
pub(super) struct ChargeTime {
    battery: Option<Variable>,
    per_min: f64,
    constant: f64,
}

impl<'a> Model<'a> {
    /// The model of `problem` over `configs` (its configurations in mode `reorder`).
    fn of(problem: &'a HopProblem, configs: &'a [Configuration], reorder: Reorder) -> Model<'a> {
        let legs: Vec<usize> = (0..problem.legs.len())
            .filter(|&l| problem.legs[l].duration_min > TIME_TOL_MIN)
            .collect();
        let v = legs
            .iter()
            .map(|&l| {
                let rates = &problem.legs[l].rate_mah_per_min;
                configs.iter().map(|c| c.rates(problem, rates)).collect()
            })
            .collect();
        Model {
            problem,
            configs,
            legs,
            v,
            free: reorder == Reorder::Free,
        }
    }
}

impl Model<'_> {
    /// Every drone's battery at the hop's end under the time shares `theta`, mAh.
    fn final_battery(&self, theta: &[Vec<f64>]) -> Vec<f64> {
        let mut b: Vec<f64> = self.problem.drones.iter().map(|d| d.battery_mah).collect();
        for (i, shares) in theta.iter().enumerate() {
            for (k, &t) in shares.iter().enumerate() {
                for (d, bd) in b.iter_mut().enumerate() {
                    *bd += self.v[i][k][d] * t;
                }
            }
        }
        b
    }

    /// For the node time, the pad of every drone in the best assignment (the exact P||Cmax
    /// search) of the batteries `theta` leaves; `None` for the other objectives.
    /// Every drone's rank by its charge time under `theta`, longest first (ties: lower index).
    fn rank_by_charge_time(&self, theta: &[Vec<f64>]) -> Vec<usize> {
        let deficit: Vec<f64> = self
            .problem
            .drones
            .iter()
            .zip(self.final_battery(theta))
            .map(|(d, b)| d.capacity_mah - b)
            .collect();
        let mut order: Vec<usize> = (0..deficit.len()).collect();
        order.sort_by(|&a, &b| deficit[b].total_cmp(&deficit[a]).then(a.cmp(&b)));
        let mut rank = vec![0; order.len()];
        for (r, &d) in order.iter().enumerate() {
            rank[d] = r;
        }
        rank
    }

    fn pad_assignment(
        &self,
        objective: &Objective,
        theta: &[Vec<f64>],
    ) -> Result<Option<Vec<usize>>> {
        let Objective::NodeTime(EndPads {
            pads,
            pad_rate_mah_per_min,
        }) = *objective
        else {
            return Ok(None);
        };
        let times: Vec<f64> = self
            .problem
            .drones
            .iter()
            .zip(self.final_battery(theta))
            .map(|(d, b)| ((d.capacity_mah - b) / pad_rate_mah_per_min).max(0.0))
            .collect();
        let limits = crate::node_time::Limits {
            time_limit_s: None,
            node_limit: Some(crate::node_time::DEFAULT_STOP_NODE_LIMIT),
        };
        let solution = crate::node_time::exact(pads, &times, &limits)?;
        let mut pad_of = vec![0; times.len()];
        for (pad, drones) in solution.assignment.iter().enumerate() {
            for &d in drones {
                pad_of[d] = pad;
            }
        }
        Ok(Some(pad_of))
    }
}

/// One solve of the model, for [`run_on`].
struct ModelJob<'a> {
    model: &'a Model<'a>,
    objective: &'a Objective,
    attempt: Attempt<'a>,
    time_limit_s: f64,
}

impl MilpJob for ModelJob<'_> {
    type Output = Solved;

    fn solve_with<S: good_lp::Solver>(self, solver: S, backend_name: &str) -> Result<Solved>
    where
        S::Model: MilpModel,
    {
        self.model.solve_with(
            solver,
            backend_name,
            self.objective,
            self.attempt,
            self.time_limit_s,
        )
    }
}

/// A configuration played over `[start_min, end_min)`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Piece {
    config: usize,
    start_min: f64,
    end_min: f64,
    leg: usize,
}

impl Model<'_> {
    /// Plays every leg's time shares in rounds (after `start_min` of the empty configuration at
    /// the hop start); a round plays the same fraction of every share, so the batteries at its
    /// end lie on the straight line between the leg-end values, and its configurations in an
    /// order that keeps every battery in `[0, C_d]` ([`round_order`]). `None` when a leg needs
    /// more than [`MAX_ROUNDS`] rounds or rounds shorter than [`MIN_ROUND_FRACTION`] of it.
    fn realise(&self, theta: &[Vec<f64>], start_min: f64) -> Option<Vec<Piece>> {
        let problem = self.problem;
        let caps: Vec<f64> = problem.drones.iter().map(|d| d.capacity_mah).collect();
        let mut b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
        let mut pieces = Vec::new();
        let mut at = 0.0;
        let mut leg_start = 0.0;
        for (l, leg) in problem.legs.iter().enumerate() {
            let Some(i) = self.legs.iter().position(|&x| x == l) else {
                leg_start += leg.duration_min;
                continue;
            };
            let tau = leg.duration_min;
            let leg_end = leg_start + tau;
            let mut share: Vec<f64> = theta[i]
                .iter()
                .map(|&t| if t > TIME_TOL_MIN { t } else { 0.0 })
                .collect();
            // The empty configuration absorbs the solver's rounding so the leg lasts τ_l.
            let sum: f64 = share.iter().sum();
            share[0] = (share[0] + tau - sum).max(0.0);
            let play =
                |k: usize, dur: f64, b: &mut Vec<f64>, at: &mut f64, pieces: &mut Vec<Piece>| {
                    for (d, bd) in b.iter_mut().enumerate() {
                        *bd += self.v[i][k][d] * dur;
                    }
                    pieces.push(Piece {
                        config: k,
                        start_min: *at,
                        end_min: *at + dur,
                        leg: l,
                    });
                    *at += dur;
                };
            if i == 0 && start_min > 0.0 {
                let first = start_min.min(share[0]);
                play(0, first, &mut b, &mut at, &mut pieces);
                share[0] -= first;
            }
            let used: Vec<usize> = (0..share.len()).filter(|&k| share[k] > 0.0).collect();
            // Rounds of adaptive length: a round plays the fraction `f` of every share; it is
            // halved when no order fits, doubled after a round that fits.
            let (mut left, mut f, mut rounds) = (1.0_f64, 1.0_f64, 0);
            while left > 1e-15 {
                let take = f.min(left);
                match round_order(&self.v[i], &used, &share, take, &b, &caps) {
                    Some(order) => {
                        for k in order {
                            play(k, share[k] * take, &mut b, &mut at, &mut pieces);
                        }
                        left -= take;
                        f = 2.0 * take;
                        rounds += 1;
                        if rounds > MAX_ROUNDS {
                            return None;
                        }
                    }
                    None if take < MIN_ROUND_FRACTION => return None,
                    None => f = 0.5 * take,
                }
            }
            // Close the leg exactly at its end.
            if let Some(last) = pieces.last_mut() {
                if last.leg == l {
                    last.end_min = leg_end;
                }
            }
            at = leg_end;
            leg_start = leg_end;
        }
        Some(pieces)
    }

    /// The slot intervals of the pieces, consecutive pieces of the same configuration within a
    /// leg merged.
    fn intervals(&self, pieces: &[Piece]) -> Vec<SlotInterval> {
        let mut out: Vec<((usize, usize), SlotInterval)> = Vec::new();
        for p in pieces {
            if p.end_min - p.start_min <= TIME_TOL_MIN {
                continue;
            }
            if let Some((k, last)) = out.last_mut() {
                if *k == (p.config, p.leg) && (last.end_min - p.start_min).abs() <= TIME_TOL_MIN {
                    last.end_min = p.end_min;
                    continue;
                }
            }
            let config = &self.configs[p.config];
            out.push((
                (p.config, p.leg),
                SlotInterval {
                    start_min: p.start_min,
                    end_min: p.end_min,
                    slot: config.slot.clone(),
                    serves: config.moves.iter().map(|&(s, c, _)| (s, c)).collect(),
                },
            ));
        }
        out.into_iter().map(|(_, x)| x).collect()
    }

    /// The transfers of the pieces, consecutive pieces of the same move within a leg merged.
    fn transfers(&self, pieces: &[Piece]) -> Vec<Transfer> {
        let rho = self.problem.rho_mah_per_min;
        let mut out: Vec<Transfer> = Vec::new();
        // Index in `out` of the running transfer of each (support, consumer, slot), with its leg.
        let mut open: Vec<((usize, usize, usize), usize, usize)> = Vec::new();
        for p in pieces {
            if p.end_min - p.start_min <= TIME_TOL_MIN {
                continue;
            }
            let mut still = Vec::new();
            for &(s, c, q) in &self.configs[p.config].moves {
                let running = open.iter().find(|(key, leg, at)| {
                    *key == (s, c, q)
                        && *leg == p.leg
                        && (out[*at].end_min - p.start_min).abs() <= TIME_TOL_MIN
                });
                match running {
                    Some(&(_, _, at)) => {
                        out[at].end_min = p.end_min;
                        out[at].energy_mah = rho * (out[at].end_min - out[at].start_min);
                        still.push(((s, c, q), p.leg, at));
                    }
                    None => {
                        out.push(Transfer {
                            support: s,
                            consumer: c,
                            start_min: p.start_min,
                            end_min: p.end_min,
                            energy_mah: rho * (p.end_min - p.start_min),
                            consumer_slot: q,
                        });
                        still.push(((s, c, q), p.leg, out.len() - 1));
                    }
                }
            }
            open = still;
        }
        out.sort_by(|a, b| {
            a.start_min
                .total_cmp(&b.start_min)
                .then(a.support.cmp(&b.support))
        });
        out
    }
}

impl Model<'_> {
    /// The schedule realised from `theta`, scored; `None` when it cannot be realised or its
    /// replay does not fly.
    fn realised(
        &self,
        objective: &Objective,
        theta: &[Vec<f64>],
        start_min: f64,
    ) -> Result<Option<FlyingSchedule>> {
        match self.realise(theta, start_min) {
            Some(pieces) if self.free => {
                free_candidate(self.problem, objective, self.intervals(&pieces))
            }
            Some(pieces) => candidate(self.problem, objective, &self.transfers(&pieces)),
            None => Ok(None),
        }
    }
}

/// An order of the configurations `used`, each played for `share[k] * fraction` minutes from the
/// batteries `b`, that keeps every battery in `[0, C_d]`: at each step the configuration leaving
/// the largest smallest distance to a bound among those that fit (ties: the lower index).
fn round_order(
    v: &[Vec<f64>],
    used: &[usize],
    share: &[f64],
    fraction: f64,
    b: &[f64],
    caps: &[f64],
) -> Option<Vec<usize>> {
    let mut b = b.to_vec();
    let mut left = used.to_vec();
    let mut order = Vec::with_capacity(used.len());
    while !left.is_empty() {
        let mut best: Option<(usize, f64)> = None;
        for (j, &k) in left.iter().enumerate() {
            let dur = share[k] * fraction;
            let mut slack = f64::INFINITY;
            for d in 0..b.len() {
                let after = b[d] + v[k][d] * dur;
                if after < -REALISE_TOL_MAH || after > caps[d] + REALISE_TOL_MAH {
                    slack = f64::NEG_INFINITY;
                    break;
                }
                slack = slack.min(after.min(caps[d] - after));
            }
            if slack > f64::NEG_INFINITY && best.is_none_or(|(_, s)| slack > s) {
                best = Some((j, slack));
            }
        }
        let (j, _) = best?;
        let k = left.remove(j);
        for d in 0..b.len() {
            b[d] += v[k][d] * share[k] * fraction;
        }
        order.push(k);
    }
    Some(order)
}

/// A schedule that flies, with its objective.
#[derive(Debug, Clone)]
struct FlyingSchedule {
    value: f64,
    proven: bool,
    /// The replay by the hop evaluation (`none`, `paper`, and the heuristics' schedules).
    outcome: Option<HopOutcome>,
    /// `free`: the schedule as slot intervals, with its transfers.
    intervals: Option<(FreeSchedule, Vec<Transfer>)>,
    /// Realised from a margin attempt (an infimum approached, not attained).
    approached: bool,
}

/// `a` is better than `b` under the objective.
fn better(objective: &Objective, a: f64, b: f64) -> bool {
    match objective {
        Objective::MaxMinArrival => a > b,
        _ => a < b,
    }
}

/// Replays `transfers` and scores them; `None` when the schedule does not fly.
fn candidate(
    problem: &HopProblem,
    objective: &Objective,
    transfers: &[Transfer],
) -> Result<Option<FlyingSchedule>> {
    let outcome = evaluate(problem, transfers).into_outcome();
    if !outcome.feasible {
        return Ok(None);
    }
    let value = objective_of(problem, objective, &outcome.final_battery_mah)?;
    Ok(Some(FlyingSchedule {
        value: value.value,
        proven: value.proven,
        outcome: Some(outcome),
        intervals: None,
        approached: false,
    }))
}

/// Integrates a `free` schedule and scores it; `None` when a battery leaves `[0, C_d]` (beyond
/// [`ENERGY_TOL_MAH`]).
fn free_candidate(
    problem: &HopProblem,
    objective: &Objective,
    intervals: Vec<SlotInterval>,
) -> Result<Option<FlyingSchedule>> {
    let rho = problem.rho_mah_per_min;
    let mut b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
    let mut transfers = Vec::new();
    for x in &intervals {
        let dur = x.end_min - x.start_min;
        let Some(l) = leg_at(problem, 0.5 * (x.start_min + x.end_min)) else {
            continue;
        };
        let rates = &problem.legs[l].rate_mah_per_min;
        for (d, bd) in b.iter_mut().enumerate() {
            *bd -= dur * rates[d][x.slot[d]];
        }
        for &(s, c) in &x.serves {
            b[s] -= rho * dur;
            b[c] += rho * dur;
            transfers.push(Transfer {
                support: s,
                consumer: c,
                start_min: x.start_min,
                end_min: x.end_min,
                energy_mah: rho * dur,
                consumer_slot: x.slot[c],
            });
        }
        let outside = b
            .iter()
            .zip(&problem.drones)
            .any(|(&bd, d)| bd < -ENERGY_TOL_MAH || bd > d.capacity_mah + ENERGY_TOL_MAH);
        if outside {
            return Ok(None);
        }
    }
    let value = objective_of(problem, objective, &b)?;
    Ok(Some(FlyingSchedule {
        value: value.value,
        proven: value.proven,
        outcome: None,
        intervals: Some((
            FreeSchedule {
                intervals,
                final_battery_mah: b,
            },
            transfers,
        )),
        approached: false,
    }))
}

/// Keeps the better of `best` and `new`.
fn keep(objective: &Objective, best: &mut Option<FlyingSchedule>, new: Option<FlyingSchedule>) {
    if let Some(c) = new {
        if best
            .as_ref()
            .is_none_or(|b| better(objective, c.value, b.value))
        {
            *best = Some(c);
        }
    }
}

/// Whether every transfer of a schedule is a move of `mode` (the `none` mode has no swaps).
fn in_mode(problem: &HopProblem, mode: Reorder, transfers: &[Transfer]) -> bool {
    mode != Reorder::None
        || transfers
            .iter()
            .all(|t| t.consumer_slot == problem.initial_slot[t.consumer])
}

/// Solves the continuous-time configuration LP of one hop and returns a schedule at (or within a
/// certified distance of) its optimum.
///
/// # Arguments
/// * `problem` - the hop.
/// * `objective` - node time at the hop's end, lowest delivery arrival battery, or feasibility.
/// * `options` - re-ordering mode (`none`, `paper`, `free`: its schedule comes as slot intervals,
///   [`ExactOutcome::intervals`], with no replay by the hop evaluation),
///   backend, time limit of each backend call, largest number of configurations, readings of
///   the heuristics whose schedules are incumbents.
///
/// # Returns
/// An [`ExactOutcome`]: status `optimal` (the schedule's objective equals the model's optimum
/// within [`OPTIMAL_REL_TOL`]), `optimal_within` (the optimum is approached; `epsilon` is the
/// schedule's certified distance to it), `infeasible` (proven: no continuous-time schedule of
/// the mode flies), `no_schedule_found` (a bound but no schedule) or a time-limit status;
/// `bound` is the model's optimum, a lower bound (upper for max-min) on every continuous-time
/// schedule of the mode; the schedule and its replay.
///
/// # Errors
/// Those of [`super::milp::solve_milp`] for bad input; `E4117` for more configurations than
/// `max_configurations`; `E4119` when a replayed schedule beats the
/// model's proven optimum (a bug: report it); [`Error::Backend`] when the backend fails.
///
/// # Complexity
/// One LP over `L |Σ|` time shares (a MILP with the node-time objective's `n min(k, n)` pad
/// binaries), `|Σ| <= Π_s (1 + |K_s|)` configurations; realisation `O(N L |Σ|^2 n)` for `N`
/// rounds; at most five further solves (margins of 1e-4 to 1e-8 of the smallest capacity) when the optimum is not attained.
///
/// # Example
/// ```
/// use swarmplan::eaas::*;
/// use swarmplan::problem::Role;
/// use swarmplan::eaas::exact::continuous::{solve_continuous, ContinuousOptions};
/// use swarmplan::eaas::exact::{ExactStatus, Objective};
/// use nalgebra::Vector2;
/// // One delivery drone (80 mAh, 10 mAh/min) next to a support drone, 10 minutes.
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
/// let o = solve_continuous(&p, &Objective::MaxMinArrival, &ContinuousOptions::default()).unwrap();
/// assert_eq!(o.status, ExactStatus::Optimal);
/// // 80 - 100 + 4 * 10 = 20 mAh with sharing during the whole hop.
/// assert!((o.objective.unwrap() - 20.0).abs() < 1e-6);
/// ```
pub fn solve_continuous(
    problem: &HopProblem,
    objective: &Objective,
    options: &ContinuousOptions,
) -> Result<ExactOutcome> {
    validate_inputs(problem, objective, options.time_limit_s)?;
    let start = Instant::now();
    let configs = configurations(problem, options.reorder, options.max_configurations)?;
    let model = Model::of(problem, &configs, options.reorder);
    let mut out = ExactOutcome::infeasible(0.0, model.legs.len());
    solve_in_phases(&model, objective, options, &mut out)?;
    out.solve_ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(out)
}

/// What the configuration LP with its pads relaxed says of a hop's node time
/// ([`relaxed_node_time`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RelaxedNodeTime {
    /// A lower bound on the node time of every continuous-time schedule, minutes.
    Bound(f64),
    /// No schedule flies the hop: the LP is infeasible, as the dense simplex found it and the
    /// backend's solve of the same relaxation confirmed (what [`solve_continuous`] tests when the
    /// hop has more than the empty configuration), and the empty schedule does not fly in the
    /// simulation either (what a hop's exact flight falls back to when the model finds no
    /// schedule, [`crate::eaas::exact_hop::fly_exact`], and what [`solve_continuous`] tests when
    /// the empty configuration is the only one).
    Infeasible,
    /// Nothing: another objective than the node time, more configurations than allowed, a
    /// simplex failure, or an infeasibility the backend did not confirm.
    Unknown,
}

/// A lower bound on the node time of every continuous-time schedule of `problem` in the mode of
/// `options`: the value of the pad search's root (the configuration LP with every `ct_d <= M`
/// and `sum_d ct_d <= min(k, n) M`, valid under every pad assignment), by the dense simplex.
/// When the dense simplex finds the LP infeasible, the backend solves the relaxation of the pad
/// binaries (what [`solve_continuous`] solves when the root does not) and decides; the hop is
/// infeasible only when the empty schedule does not fly either (the simulation's tolerances are
/// not the LP's).
///
/// The configuration LP's feasible set lies within the fluid LP's (`models/eaas_fluid.md`), so
/// this bound is at least [`super::fluid::bound`]'s.
#[cfg(feature = "microlp")]
pub fn relaxed_node_time(
    problem: &HopProblem,
    objective: &Objective,
    options: &ContinuousOptions,
) -> RelaxedNodeTime {
    let Ok(configs) = configurations(problem, options.reorder, options.max_configurations) else {
        return RelaxedNodeTime::Unknown;
    };
    let model = Model::of(problem, &configs, options.reorder);
    let Some(root) = model.dense_root(objective) else {
        return RelaxedNodeTime::Unknown;
    };
    match root.lp.solve() {
        Ok(t) => RelaxedNodeTime::Bound(t.objective()),
        Err(crate::solver::dense::DenseFailure::Infeasible) => {
            let confirmed = matches!(
                model.solve(objective, options, Attempt::exact(Pads::Relaxed)),
                Ok(Solved::Infeasible)
            );
            let empty = crate::eaas::simulate_with(
                problem,
                crate::eaas::Heuristic::None,
                &crate::eaas::PolicyOptions::default(),
            );
            if confirmed && empty.is_ok_and(|e| !e.feasible) {
                RelaxedNodeTime::Infeasible
            } else {
                RelaxedNodeTime::Unknown
            }
        }
        Err(_) => RelaxedNodeTime::Unknown,
    }
}

/// The phases of [`solve_continuous`] (`models/eaas_continuous.md`): incumbents, the relaxation
/// of the pad binaries, its assignment fixed, the pad search, the pad MILP, margins, and the
/// outcome. Leaves `out` as it is (infeasible) when the model is proven infeasible.
fn solve_in_phases(
    model: &Model<'_>,
    objective: &Objective,
    options: &ContinuousOptions,
    out: &mut ExactOutcome,
) -> Result<()> {
    let problem = model.problem;
    // Incumbents: the empty schedule and the heuristics' schedules of the mode.
    let mut best: Option<FlyingSchedule> = None;
    keep(objective, &mut best, candidate(problem, objective, &[])?);
    if model.configs.len() == 1 {
        return only_the_empty_configuration(objective, best, out);
    }
    keep_heuristics(problem, objective, options, &mut best)?;
    // The relaxation of the pad assignment first: a lower bound, and often a schedule at it.
    // Under the pad search its root; else the pad binaries in [0, 1].
    let root = model.search_root(objective, options);
    let relaxed = match &root {
        Some(root) => root.values(),
        None => match model.solve(objective, options, Attempt::exact(Pads::Relaxed))? {
            Solved::Infeasible => return Ok(()),
            Solved::NoSolution => return finish(out, objective, best, None),
            Solved::Values(v) => v,
        },
    };
    let mut search = BoundedSearch::from_relaxation(model, objective, options, best, &relaxed)?;
    search.root = root;
    search.fix_the_relaxed_assignment()?;
    search.search_pads()?;
    if search.pad_milp()? == Proven::Infeasible {
        return Ok(());
    }
    search.margins()?;
    search.finish(out)
}

/// Only the empty configuration (no support drone, or no move in the mode): the empty schedule
/// is the only schedule, and its value, with the exact node time, the optimum.
fn only_the_empty_configuration(
    objective: &Objective,
    best: Option<FlyingSchedule>,
    out: &mut ExactOutcome,
) -> Result<()> {
    if best.is_some() {
        let bound = best.as_ref().filter(|c| c.proven).map(|c| c.value);
        finish(out, objective, best, bound)?;
        if bound.is_some() {
            out.status = ExactStatus::Optimal;
        }
        out.model_objective = bound;
    }
    Ok(())
}

/// PB's and FB's schedules as incumbents, where they fly in the mode.
fn keep_heuristics(
    problem: &HopProblem,
    objective: &Objective,
    options: &ContinuousOptions,
    best: &mut Option<FlyingSchedule>,
) -> Result<()> {
    for heuristic in [Heuristic::Pb, Heuristic::Fb] {
        // A heuristic refusing the hop (FB's round bound) gives no incumbent.
        if let Ok(o) = simulate_with(problem, heuristic, &options.readings) {
            if o.feasible && in_mode(problem, options.reorder, &o.transfers) {
                keep(
                    objective,
                    best,
                    candidate(problem, objective, &o.transfers)?,
                );
            }
        }
    }
    Ok(())
}

/// Whether the pad MILP proved the model infeasible.
#[derive(Debug, PartialEq)]
enum Proven {
    Infeasible,
    Open,
}

/// The search after the relaxation: the best schedule against the bound.
struct BoundedSearch<'m, 'a> {
    model: &'m Model<'a>,
    objective: &'m Objective,
    options: &'m ContinuousOptions,
    best: Option<FlyingSchedule>,
    /// The bound: the relaxation's value while no better one is proven.
    bound: Option<f64>,
    /// The model's own value: the relaxation's, then the pad MILP's.
    model_value: f64,
    /// The pad assignment the margin attempts fix: the best one for the latest time shares.
    assignment: Option<Vec<usize>>,
    /// The pad MILP's symmetry breaking: the relaxation's longest charge times first.
    rank: Vec<usize>,
    /// The least model value of an assignment solved so far (an upper bound on the model's).
    fixed_value: f64,
    /// The pad search's root, where the search applies.
    root: Option<SearchRoot>,
}

impl<'m, 'a> BoundedSearch<'m, 'a> {
    /// The state after the relaxation, its realised schedule kept.
    fn from_relaxation(
        model: &'m Model<'a>,
        objective: &'m Objective,
        options: &'m ContinuousOptions,
        mut best: Option<FlyingSchedule>,
        relaxed: &Values,
    ) -> Result<Self> {
        keep(
            objective,
            &mut best,
            model.realised(objective, &relaxed.theta, 0.0)?,
        );
        Ok(BoundedSearch {
            model,
            objective,
            options,
            best,
            bound: relaxed.bound,
            model_value: relaxed.value,
            assignment: model.pad_assignment(objective, &relaxed.theta)?,
            rank: model.rank_by_charge_time(&relaxed.theta),
            fixed_value: f64::INFINITY,
            root: None,
        })
    }

    /// How close to the bound `b` a schedule is optimal.
    fn tolerance(b: f64) -> f64 {
        OPTIMAL_ABS_TOL + OPTIMAL_REL_TOL * b.abs()
    }

    /// How far `c` is from the bound `b`, positive when worse.
    fn distance(&self, c: &FlyingSchedule, b: f64) -> f64 {
        match self.objective {
            Objective::MaxMinArrival => b - c.value,
            _ => c.value - b,
        }
    }

    /// Whether the best schedule reaches the bound within the tolerance.
    fn reached(&self) -> bool {
        self.bound.is_some_and(|b| {
            self.best
                .as_ref()
                .is_some_and(|c| self.distance(c, b) <= Self::tolerance(b))
        })
    }

    /// Keeps the schedule realised from the time shares `theta`, if it flies and is better.
    fn keep_realised(&mut self, theta: &[Vec<f64>]) -> Result<()> {
        let realised = self.model.realised(self.objective, theta, 0.0)?;
        keep(self.objective, &mut self.best, realised);
        Ok(())
    }

    /// The relaxation's assignment fixed: an LP whose schedule often reaches the bound.
    fn fix_the_relaxed_assignment(&mut self) -> Result<()> {
        let Some(a) = self.assignment.clone().filter(|_| !self.reached()) else {
            return Ok(());
        };
        // From the search's root: the assignment's pad rows added, re-solved warm.
        if let Some((value, theta)) = self.root.as_ref().and_then(|r| r.fixed(&a)) {
            self.fixed_value = value;
            return self.keep_realised(&theta);
        }
        if let Solved::Values(v) = self.model.solve(
            self.objective,
            self.options,
            Attempt::exact(Pads::Fixed(&a)),
        )? {
            self.fixed_value = v.value;
            self.keep_realised(&v.theta)?;
        }
        Ok(())
    }

    /// The pad search (node-time objective), below the best model value known.
    fn search_pads(&mut self) -> Result<()> {
        let has_binaries = matches!(self.objective, Objective::NodeTime(EndPads { .. }));
        if !has_binaries || self.reached() {
            return Ok(());
        }
        let incumbent = self.best.as_ref().map_or(f64::INFINITY, |c| c.value);
        let Some(s) = self
            .root
            .as_ref()
            .and_then(|r| r.search(self.options, &self.rank, self.fixed_value.min(incumbent)))
        else {
            return Ok(());
        };
        if s.complete {
            self.bound = Some(s.bound);
            self.model_value = s.value;
        } else {
            self.bound = self.bound.map(|b| b.max(s.bound));
        }
        if let Some((pad_of, theta)) = &s.leaf {
            self.assignment = Some(pad_of.clone());
            self.keep_realised(theta)?;
            // The leaf's LP solved again from scratch: a warm re-solve's point can sit at a
            // bound by a hair more than a cold one's, which the realisation may not play.
            if !self.reached() {
                if let Solved::Values(v) = self.model.solve(
                    self.objective,
                    self.options,
                    Attempt::exact(Pads::Fixed(pad_of)),
                )? {
                    self.keep_realised(&v.theta)?;
                }
            }
        }
        Ok(())
    }

    /// Where the search's points do not realise at the bound: what the backend's path tries
    /// before its pad MILP, the relaxation with the pad binaries in `[0, 1]` and its assignment
    /// fixed, each realised; the pad MILP then breaks symmetry along that relaxation's charge
    /// times. Another optimal point may realise where the search's did not.
    fn backend_relaxation(&mut self) -> Result<()> {
        let (model, objective, options) = (self.model, self.objective, self.options);
        let Solved::Values(v) = model.solve(objective, options, Attempt::exact(Pads::Relaxed))?
        else {
            return Ok(());
        };
        self.keep_realised(&v.theta)?;
        self.rank = model.rank_by_charge_time(&v.theta);
        if self.reached() {
            return Ok(());
        }
        if let Some(a) = model.pad_assignment(objective, &v.theta)? {
            if let Solved::Values(f) =
                model.solve(objective, options, Attempt::exact(Pads::Fixed(&a)))?
            {
                self.keep_realised(&f.theta)?;
            }
        }
        Ok(())
    }

    /// The pad MILP: where the search does not apply, and where the search's optimum does not
    /// realise (another optimal point of the MILP's may: its schedule is tried before margins).
    /// A microlp failure leaves the relaxation's bound, said so by epsilon. Its symmetry broken
    /// along the charge times first; when microlp fails numerically on that, along the drone
    /// index.
    fn pad_milp(&mut self) -> Result<Proven> {
        let has_binaries = matches!(self.objective, Objective::NodeTime(EndPads { .. }));
        if !has_binaries || self.reached() {
            return Ok(Proven::Open);
        }
        if self.root.is_some() {
            self.backend_relaxation()?;
            if self.reached() {
                return Ok(Proven::Open);
            }
        }
        let (model, objective, options) = (self.model, self.objective, self.options);
        let by_index: Vec<usize> = (0..model.problem.drones.len()).collect();
        let mut answer = model.solve(
            objective,
            options,
            Attempt::exact(Pads::Integral(&self.rank)),
        );
        let numerical = matches!(
            answer,
            Err(Error::Backend {
                kind: BackendFailure::Numerical,
                ..
            })
        );
        if numerical && self.rank != by_index {
            answer = model.solve(
                objective,
                options,
                Attempt::exact(Pads::Integral(&by_index)),
            );
        }
        match answer {
            Ok(Solved::Values(v)) => {
                if v.bound.is_some() {
                    self.bound = v.bound;
                    self.model_value = v.value;
                }
                self.assignment = model.pad_assignment(objective, &v.theta)?;
                self.keep_realised(&v.theta)?;
            }
            Ok(Solved::Infeasible) => return Ok(Proven::Infeasible),
            Ok(Solved::NoSolution)
            | Err(Error::Backend {
                kind: BackendFailure::Numerical,
                ..
            }) => {}
            Err(e) => return Err(e),
        }
        Ok(Proven::Open)
    }

    /// Where the realisation does not attain the bound: margins at leg ends and an empty start,
    /// finer each attempt ([`MARGIN_FRACTIONS`]), their schedules approaching the infimum.
    fn margins(&mut self) -> Result<()> {
        let Some(b) = self.bound.filter(|_| !self.reached()) else {
            return Ok(());
        };
        let (model, objective, options) = (self.model, self.objective, self.options);
        let problem = model.problem;
        let scale = problem
            .drones
            .iter()
            .map(|d| d.capacity_mah)
            .fold(f64::INFINITY, f64::min);
        let slowest = model.legs.first().map_or(0.0, |&l| {
            let rates = &problem.legs[l].rate_mah_per_min;
            (0..problem.drones.len())
                .map(|d| rates[d][problem.initial_slot[d]])
                .filter(|&r| r > 0.0)
                .fold(f64::INFINITY, f64::min)
        });
        let first_leg = model
            .legs
            .first()
            .map_or(0.0, |&l| problem.legs[l].duration_min);
        let mut realised_any = false;
        for fraction in MARGIN_FRACTIONS {
            let margin_mah = fraction * scale;
            let rate = if slowest.is_finite() {
                slowest
            } else {
                problem.rho_mah_per_min
            };
            let start_min = (margin_mah / rate).min(0.5 * first_leg);
            let attempt = Attempt {
                margin_mah,
                start_min,
                pads: match &self.assignment {
                    Some(a) => Pads::Fixed(a),
                    None => Pads::Integral(&self.rank),
                },
                rescale: 1.0,
            };
            let values = match model.solve(objective, options, attempt) {
                Ok(Solved::Values(v)) => v,
                Ok(_)
                | Err(Error::Backend {
                    kind: BackendFailure::Numerical,
                    ..
                }) => continue,
                Err(e) => return Err(e),
            };
            let realised = model.realised(objective, &values.theta, start_min)?;
            if realised.is_none() && realised_any {
                break;
            }
            realised_any |= realised.is_some();
            let approached = realised.map(|c| FlyingSchedule {
                approached: true,
                ..c
            });
            keep(objective, &mut self.best, approached);
            // Close enough: a finer margin costs more rounds (transfers) for a smaller epsilon.
            if self.best.as_ref().is_some_and(|c| {
                self.distance(c, b) <= Self::tolerance(b).max(MARGIN_REL_EPSILON * b.abs())
            }) {
                break;
            }
        }
        Ok(())
    }

    /// The outcome: the best schedule against the bound; `E4119` when a schedule beats the
    /// proven bound by more than the solver's round-off ([`SOLVER_ROUNDOFF_REL`]). Optimal only when a schedule of the model without margin reaches the bound;
    /// a schedule of a margin attempt approaches an infimum and says how closely
    /// (optimal_within, epsilon).
    fn finish(mut self, out: &mut ExactOutcome) -> Result<()> {
        if let (Some(c), Some(b)) = (&self.best, self.bound) {
            let roundoff = Self::tolerance(b).max(SOLVER_ROUNDOFF_REL * b.abs().max(1.0));
            if self.distance(c, b) < -roundoff {
                return Err(Error::internal(
                    "E4119",
                    format!(
                        "{}: a replayed schedule ({}) beats the model's proven bound ({b})",
                        self.options.backend, c.value
                    ),
                ));
            }
            // Beaten within the round-off: the schedule's value is the bound, as proven as `V`.
            if self.distance(c, b) < -Self::tolerance(b) {
                self.bound = Some(c.value);
            }
        }
        let attained = self.reached() && !self.best.as_ref().is_some_and(|c| c.approached);
        finish(out, self.objective, self.best, self.bound)?;
        if attained {
            out.status = ExactStatus::Optimal;
        }
        out.model_objective = self.bound.map(|_| self.model_value);
        Ok(())
    }
}

/// Fills the outcome from the best schedule and the model's bound.
fn finish(
    out: &mut ExactOutcome,
    objective: &Objective,
    best: Option<FlyingSchedule>,
    bound: Option<f64>,
) -> Result<()> {
    out.bound = bound;
    let Some(c) = best else {
        out.status = match bound {
            Some(_) => ExactStatus::NoScheduleFound,
            None => ExactStatus::TimeLimitNoSolution,
        };
        return Ok(());
    };
    out.objective = Some(c.value);
    out.objective_proven = c.proven;
    match (c.outcome, c.intervals) {
        (Some(o), _) => {
            out.transfers = o.transfers.clone();
            out.outcome = Some(o);
        }
        (None, Some((intervals, transfers))) => {
            out.transfers = transfers;
            out.intervals = Some(intervals);
        }
        (None, None) => {}
    }
    match out.bound {
        Some(b) => {
            let eps = match objective {
                Objective::MaxMinArrival => b - c.value,
                _ => c.value - b,
            };
            out.epsilon = Some(eps.max(0.0));
            out.status = ExactStatus::OptimalWithin;
        }
        None => out.status = ExactStatus::Feasible,
    }
    Ok(())
}
