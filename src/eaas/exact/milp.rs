//! Time-indexed MILP for one hop's sharing schedule, see `models/eaas_milp.md`.
//!
//! The hop `[0, tt]` is cut into periods `t in 0..P` of length `h_t <= period_min`, every leg end a
//! period boundary (leg `l` of duration `τ_l` gives `ceil(τ_l / period_min)` equal periods). A
//! transfer occupies whole periods: in a period a support drone `s` either serves one consumer for
//! the whole period, moving `rho h_t`, or serves nobody. Batteries are then linear inside a period,
//! so `0 <= b_d <= C_d` at the grid points holds at every instant.
//!
//! ```text
//! y[k][t] in {0,1}   move k = (s, c, q): s serves c, c flying in slot q, during period t
//! b[d][t]  in [0, C_d]  battery of d at grid point t (t = 0..P; b[d][0] = b_d(0))
//! sum_{k: s_k = s} y[k][t] <= 1                                  one consumer per support drone
//! sum_{k: c_k = p} y[k][t] + sum_{k: partner_k = p} y[k][t] <= 1  a delivery drone moves once
//! b[d][t+1] = b[d][t] - h_t r[l(t)][d][π(d)] - h_t sum_k Δr[k][d] y[k][t]
//!             + rho h_t (sum_{k: c_k = d} y[k][t] - sum_{k: s_k = d} y[k][t])
//! rho sum_{k: s_k = s, t} h_t y[k][t] <= B_s                     support reserve (rule 5)
//! ```
//!
//! `Δr[k][d]` is the change of `d`'s rate while move `k` runs (the consumer in `q`, the swap
//! partner in `π(c)`). Re-ordering ([`Reorder`]) decides which moves exist: `none` only in-range
//! consumers in their own slots; `paper` also out-of-range consumers swapped with the delivery
//! drone of any in-range slot; `free` replaces moves by a per-period assignment `z[d][q][t]` of
//! delivery drones to non-support slots. Objectives ([`Objective`]): the node time at the hop's end
//! (pad assignment in the same model), the lowest arrival battery of the delivery drones, or
//! feasibility alone. The optimum is optimal over full-period grid schedules of step `h`, which
//! the outcome carries ([`ExactOutcome::grid_step_min`]).

use super::EndPads;
use super::{backend_end, moves, validate_inputs, BackendEnd, Move, PadRows};
use super::{objective_of, ExactOutcome, ExactStatus, Objective, Reorder};
use crate::eaas::simulate::evaluate;
use crate::eaas::{reorder, sharing_budget_mah, HopProblem, Role, Transfer, TIME_TOL_MIN};
use crate::error::{show, BackendFailure, Error, Result};
use crate::solver::lp_file::{write_model_file, LpCapture};
use crate::solver::lp_file::{LpSize, ModelFormat};
use crate::solver::{run_on, MilpBackend, MilpJob, MilpModel};
use good_lp::{
    constraint, variable, Expression, ProblemVariables, Solution, SolverModel, Variable,
    WithTimeLimit,
};
use serde::{Deserialize, Serialize};
use std::path::Path;
use std::time::Instant;

/// Largest number of periods a grid may have (guards against a tiny `period_min`).
pub const MAX_PERIODS: usize = 100_000;

/// Settings of a MILP solve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MilpOptions {
    /// Longest period of the grid, minutes (default 1.0).
    pub period_min: f64,
    /// Re-ordering mode (default [`Reorder::Paper`]).
    pub reorder: Reorder,
    /// Backend (default: [`MilpBackend::default`]).
    pub backend: MilpBackend,
    /// Wall-clock limit of each backend call, seconds (default 60); `f64::INFINITY`: none, the
    /// run is then the same on every machine.
    #[serde(with = "crate::solver::seconds_or_none")]
    pub time_limit_s: f64,
    /// Branch-and-bound nodes of each MILP backend call (default `None`: no limit): a limit that
    /// stops a solve at the same point on every machine and under any load.
    #[serde(default)]
    pub node_limit: Option<u64>,
}

impl Default for MilpOptions {
    fn default() -> Self {
        MilpOptions {
            period_min: 1.0,
            reorder: Reorder::Paper,
            backend: MilpBackend::default(),
            time_limit_s: 60.0,
            node_limit: None,
        }
    }
}

/// Checks a grid step.
///
/// # Errors
/// `E4101` for a `period_min` that is not finite and positive.
pub fn validate_period_min(period_min: f64) -> Result<()> {
    if period_min.is_finite() && period_min > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "E4101",
            "period_min",
            format!("{} is not a finite duration > 0", show(period_min)),
            "give the grid step in minutes, such as 1.0",
        ))
    }
}

/// The time grid of a hop.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Period start times, minutes, then `tt`: `P + 1` points.
    pub points_min: Vec<f64>,
    /// Leg flown in each period.
    pub leg: Vec<usize>,
}

impl Grid {
    /// Cuts every leg of positive duration into `ceil(τ_l / period_min)` equal periods.
    ///
    /// # Errors
    /// `E4101` for a `period_min` that is not finite and positive, `E4102` for more than
    /// [`MAX_PERIODS`] periods.
    pub fn new(problem: &HopProblem, period_min: f64) -> Result<Grid> {
        validate_period_min(period_min)?;
        let mut points_min = vec![0.0];
        let mut leg = Vec::new();
        let mut at = 0.0;
        for (l, lg) in problem.legs.iter().enumerate() {
            if lg.duration_min <= TIME_TOL_MIN {
                at += lg.duration_min;
                continue;
            }
            let m = (lg.duration_min / period_min - 1e-9).ceil().max(1.0);
            if leg.len() as f64 + m > MAX_PERIODS as f64 {
                return Err(Error::invalid(
                    "E4102",
                    "period_min",
                    format!(
                        "more than {MAX_PERIODS} periods at {} min",
                        show(period_min)
                    ),
                    "choose a longer period",
                ));
            }
            let m = m as usize;
            for i in 1..=m {
                leg.push(l);
                points_min.push(if i == m {
                    at + lg.duration_min
                } else {
                    at + lg.duration_min * i as f64 / m as f64
                });
            }
            at += lg.duration_min;
        }
        Ok(Grid { points_min, leg })
    }

    /// Number of periods `P`.
    pub fn periods(&self) -> usize {
        self.leg.len()
    }

    /// Length `h_t` of period `t`, minutes.
    pub fn len_min(&self, t: usize) -> f64 {
        self.points_min[t + 1] - self.points_min[t]
    }

    /// Longest period, minutes (0 for an empty grid).
    pub fn step_min(&self) -> f64 {
        (0..self.periods())
            .map(|t| self.len_min(t))
            .fold(0.0, f64::max)
    }
}

/// Values of one solve of the model.
struct Raw {
    /// `y[k][t]` rounded.
    on: Vec<Vec<bool>>,
    /// `free`: slot of every drone in every period.
    slots: Option<Vec<Vec<usize>>>,
    /// Objective value in the model.
    value: f64,
    /// The backend proved optimality.
    proven: bool,
    /// Name of every variable, in the order they were added (`y_k{k}_t{t}`, ...).
    names: Vec<String>,
}

/// How a backend call ended.
enum Solved {
    Values(Raw),
    Infeasible,
    NoSolution,
}

/// Builds and solves the MILP (or its LP relaxation when `relax`) on any good_lp solver.
///
/// # Errors
/// [`Error::Backend`] when the backend fails for a reason other than infeasibility or the time
/// limit.
#[allow(clippy::too_many_arguments)]
fn solve_with<S: good_lp::Solver>(
    solver: S,
    backend_name: &str,
    problem: &HopProblem,
    grid: &Grid,
    mode: Reorder,
    objective: &Objective,
    relax: bool,
    time_limit_s: f64,
) -> Result<Solved>
where
    S::Model: MilpModel,
{
    let setting = GridSetting::new(problem, grid, mode);
    let (vars, columns) = setting.columns(objective, relax);
    let names: Vec<String> = vars
        .iter_variables_with_def()
        .map(|(_, def)| def.get_name().to_string())
        .collect();
    let mut model = match (objective, columns.goal) {
        (Objective::MaxMinArrival, Some(g)) => vars.maximise(g),
        (_, Some(g)) => vars.minimise(g),
        _ => vars.minimise(Expression::from(0.0)),
    }
    .using(solver)
    .with_time_limit(time_limit_s);
    for t in 0..grid.periods() {
        setting.add_period_rows(&mut model, &columns, t);
    }
    setting.add_sharing_budgets(&mut model, &columns);
    setting.add_objective_rows(&mut model, &columns, objective);
    if grid.periods() == 0 {
        return setting.empty_grid(objective, &columns, names);
    }
    let (status, solution) = match backend_end(model.solve_outcome(), backend_name)? {
        BackendEnd::Solved(status, s) => (status, s),
        BackendEnd::Infeasible => return Ok(Solved::Infeasible),
        BackendEnd::NoSolution => return Ok(Solved::NoSolution),
    };
    // A stop at the relative gap asked for is a proof within it; a limit's stop is not.
    Ok(Solved::Values(setting.read(
        &solution,
        &columns,
        status.proven(),
        names,
    )))
}

/// What the grid MILP of a hop is built over: the moves of the mode, the delivery drones and
/// their slots (`models/eaas_milp.md`).
struct GridSetting<'a> {
    problem: &'a HopProblem,
    grid: &'a Grid,
    mode: Reorder,
    mv: Vec<Move>,
    delivery: Vec<usize>,
    /// The delivery drones' own slots, open to any of them under `free`.
    open_slots: Vec<usize>,
}

/// The grid MILP's variables.
struct GridColumns {
    /// `y[k][t]`: move `k` during period `t`.
    y: Vec<Vec<Variable>>,
    /// `z[i][j][t]`: delivery drone `delivery[i]` in slot `open_slots[j]` during `t` (`free`
    /// only).
    z: Vec<Vec<Vec<Variable>>>,
    /// `b[d][t]`: the battery at grid point `t + 1` (`b_d(0)` is a constant).
    b: Vec<Vec<Variable>>,
    /// `M` (node time) or `g` (least delivery battery); none for feasibility.
    goal: Option<Variable>,
    /// The exact (or relaxed) assignment rows of the node time.
    pads: Option<PadRows>,
}

impl<'a> GridSetting<'a> {
    fn new(problem: &'a HopProblem, grid: &'a Grid, mode: Reorder) -> Self {
        let delivery: Vec<usize> = (0..problem.drones.len())
            .filter(|&d| problem.drones[d].role == Role::Delivery)
            .collect();
        let open_slots = delivery.iter().map(|&d| problem.initial_slot[d]).collect();
        GridSetting {
            problem,
            grid,
            mode,
            mv: moves(problem, mode),
            delivery,
            open_slots,
        }
    }

    /// The variables, in this order: `y`, `z`, `b`, then the objective's (pad rows, goal);
    /// binaries in `[0, 1]` when `relax`.
    fn columns(&self, objective: &Objective, relax: bool) -> (ProblemVariables, GridColumns) {
        let problem = self.problem;
        let np = self.grid.periods();
        let bin = |vars: &mut ProblemVariables, name: String| {
            if relax {
                vars.add(variable().min(0.0).max(1.0).name(name))
            } else {
                vars.add(variable().binary().name(name))
            }
        };
        let mut vars = ProblemVariables::new();
        let y: Vec<Vec<Variable>> = (0..self.mv.len())
            .map(|k| {
                (0..np)
                    .map(|t| bin(&mut vars, format!("y_k{k}_t{t}")))
                    .collect()
            })
            .collect();
        let z: Vec<Vec<Vec<Variable>>> = if self.mode == Reorder::Free {
            (0..self.delivery.len())
                .map(|i| {
                    (0..self.open_slots.len())
                        .map(|j| {
                            let (c, q) = (self.delivery[i], self.open_slots[j]);
                            (0..np)
                                .map(|t| bin(&mut vars, format!("z_c{c}_q{q}_t{t}")))
                                .collect()
                        })
                        .collect()
                })
                .collect()
        } else {
            Vec::new()
        };
        let b: Vec<Vec<Variable>> = problem
            .drones
            .iter()
            .enumerate()
            .map(|(d, drone)| {
                (0..np)
                    .map(|t| {
                        let name = format!("b_d{d}_t{}", t + 1);
                        vars.add(variable().min(0.0).max(drone.capacity_mah).name(name))
                    })
                    .collect()
            })
            .collect();
        let (goal, pads) = match *objective {
            Objective::NodeTime(EndPads { pads, .. }) => {
                let rows = PadRows::add(&mut vars, problem.drones.len(), pads, relax, None);
                (Some(vars.add(variable().min(0.0).name("M"))), Some(rows))
            }
            Objective::MaxMinArrival => (Some(vars.add(variable().name("g"))), None),
            Objective::Feasible => (None, None),
        };
        (
            vars,
            GridColumns {
                y,
                z,
                b,
                goal,
                pads,
            },
        )
    }

    /// Drone `d`'s battery at grid point `t`: the constant `b_d(0)` at `t = 0`.
    fn battery_at(&self, columns: &GridColumns, d: usize, t: usize) -> Expression {
        if t == 0 {
            Expression::from(self.problem.drones[d].battery_mah)
        } else {
            Expression::from(columns.b[d][t - 1])
        }
    }

    /// The rows of period `t`: a support drone and a delivery drone in one move at most; under
    /// `free`, one slot per delivery drone and one drone per slot, a move only within range;
    /// every battery's change over the period.
    fn add_period_rows<M: SolverModel>(&self, model: &mut M, columns: &GridColumns, t: usize) {
        let problem = self.problem;
        let (mv, y) = (&self.mv, &columns.y);
        for s in (0..problem.drones.len()).filter(|&s| problem.drones[s].role == Role::Support) {
            let once: Expression = (0..mv.len())
                .filter(|&k| mv[k].support == s)
                .map(|k| y[k][t])
                .sum();
            model.add_constraint(constraint!(once <= 1.0));
        }
        for &p in &self.delivery {
            let moved: Expression = (0..mv.len())
                .filter(|&k| mv[k].consumer == p || mv[k].partner == Some(p))
                .map(|k| y[k][t])
                .sum();
            model.add_constraint(constraint!(moved <= 1.0));
        }
        if self.mode == Reorder::Free {
            self.add_slot_rows(model, columns, t);
        }
        for d in 0..problem.drones.len() {
            let used = self.energy_used(columns, d, t);
            let next = Expression::from(columns.b[d][t]);
            let prev = self.battery_at(columns, d, t);
            model.add_constraint(constraint!(next == prev - used));
        }
    }

    /// `free`, period `t`: every delivery drone in one open slot, every open slot holding one,
    /// and a move only while its consumer is within the support drone's range.
    fn add_slot_rows<M: SolverModel>(&self, model: &mut M, columns: &GridColumns, t: usize) {
        let (problem, z) = (self.problem, &columns.z);
        for zi in z {
            let one: Expression = zi.iter().map(|zij| zij[t]).sum();
            model.add_constraint(constraint!(one == 1.0));
        }
        for j in 0..self.open_slots.len() {
            let one: Expression = z.iter().map(|zi| zi[j][t]).sum();
            model.add_constraint(constraint!(one == 1.0));
        }
        for (k, m) in self.mv.iter().enumerate() {
            let i = self
                .delivery
                .iter()
                .position(|&d| d == m.consumer)
                .unwrap_or(0);
            let qs = problem.initial_slot[m.support];
            let near: Expression = (0..self.open_slots.len())
                .filter(|&j| {
                    reorder::slot_distance_m(problem, qs, self.open_slots[j]) <= problem.range_m
                })
                .map(|j| z[i][j][t])
                .sum();
            model.add_constraint(constraint!(columns.y[k][t] <= near));
        }
    }

    /// The energy drone `d` uses in period `t`: flight in its slot (or the slot a move puts it
    /// in), less what it receives, plus what it gives.
    fn energy_used(&self, columns: &GridColumns, d: usize, t: usize) -> Expression {
        let problem = self.problem;
        let h = self.grid.len_min(t);
        let rho = problem.rho_mah_per_min;
        let rates = &problem.legs[self.grid.leg[t]].rate_mah_per_min;
        let y = &columns.y;
        let own = problem.initial_slot[d];
        let mut used = Expression::from(0.0);
        if self.mode == Reorder::Free && problem.drones[d].role == Role::Delivery {
            let i = self.delivery.iter().position(|&x| x == d).unwrap_or(0);
            for (j, &q) in self.open_slots.iter().enumerate() {
                used += h * rates[d][q] * columns.z[i][j][t];
            }
        } else {
            used += h * rates[d][own];
            for (k, m) in self.mv.iter().enumerate() {
                if m.consumer == d && m.slot != own {
                    used += h * (rates[d][m.slot] - rates[d][own]) * y[k][t];
                }
                if m.partner == Some(d) {
                    let to = problem.initial_slot[m.consumer];
                    used += h * (rates[d][to] - rates[d][own]) * y[k][t];
                }
            }
        }
        for (k, m) in self.mv.iter().enumerate() {
            if m.consumer == d {
                used -= rho * h * y[k][t];
            }
            if m.support == d {
                used += rho * h * y[k][t];
            }
        }
        used
    }

    /// What each support drone gives stays within its sharing budget.
    fn add_sharing_budgets<M: SolverModel>(&self, model: &mut M, columns: &GridColumns) {
        let problem = self.problem;
        let (mv, y, grid) = (&self.mv, &columns.y, self.grid);
        let rho = problem.rho_mah_per_min;
        for s in (0..problem.drones.len()).filter(|&s| problem.drones[s].role == Role::Support) {
            let given: Expression = (0..mv.len())
                .filter(|&k| mv[k].support == s)
                .flat_map(|k| (0..grid.periods()).map(move |t| (k, t)))
                .map(|(k, t)| rho * grid.len_min(t) * y[k][t])
                .sum();
            let budget = sharing_budget_mah(problem, s);
            model.add_constraint(constraint!(given <= budget));
        }
    }

    /// The objective's rows: the node time's pad rows, or the least delivery battery.
    fn add_objective_rows<M: SolverModel>(
        &self,
        model: &mut M,
        columns: &GridColumns,
        objective: &Objective,
    ) {
        let problem = self.problem;
        let np = self.grid.periods();
        match (*objective, columns.goal, &columns.pads) {
            (
                Objective::NodeTime(EndPads {
                    pad_rate_mah_per_min,
                    ..
                }),
                Some(g),
                Some(rows),
            ) => {
                let finals: Vec<Expression> = (0..problem.drones.len())
                    .map(|d| self.battery_at(columns, d, np))
                    .collect();
                let caps: Vec<f64> = problem.drones.iter().map(|d| d.capacity_mah).collect();
                rows.constrain(model, &caps, &finals, pad_rate_mah_per_min, g);
            }
            (Objective::MaxMinArrival, Some(g), _) => {
                for &d in &self.delivery {
                    model.add_constraint(constraint!(g <= self.battery_at(columns, d, np)));
                }
            }
            _ => {}
        }
    }

    /// No period: the empty schedule is the only one (and HiGHS refuses an empty model).
    fn empty_grid(
        &self,
        objective: &Objective,
        columns: &GridColumns,
        names: Vec<String>,
    ) -> Result<Solved> {
        let replay = evaluate(self.problem, &[]).into_outcome();
        if !replay.feasible {
            return Ok(Solved::Infeasible);
        }
        let value = objective_of(self.problem, objective, &replay.final_battery_mah)?;
        Ok(Solved::Values(Raw {
            on: columns.y.iter().map(|_| Vec::new()).collect(),
            slots: (self.mode == Reorder::Free).then(Vec::new),
            value: value.value,
            proven: value.proven,
            names,
        }))
    }

    /// The values of a solve: the moves on, and under `free` every drone's slot in every period
    /// (each delivery drone in its likeliest open slot).
    fn read(
        &self,
        solution: &impl Solution,
        columns: &GridColumns,
        proven: bool,
        names: Vec<String>,
    ) -> Raw {
        let value = match columns.goal {
            Some(g) => solution.value(g),
            None => 0.0,
        };
        let on: Vec<Vec<bool>> = columns
            .y
            .iter()
            .map(|yk| yk.iter().map(|&v| solution.value(v) > 0.5).collect())
            .collect();
        let z = &columns.z;
        let slots = (self.mode == Reorder::Free).then(|| {
            (0..self.grid.periods())
                .map(|t| {
                    let mut slot = self.problem.initial_slot.clone();
                    for (i, &d) in self.delivery.iter().enumerate() {
                        if let Some(j) = (0..self.open_slots.len()).max_by(|&a, &b| {
                            solution
                                .value(z[i][a][t])
                                .total_cmp(&solution.value(z[i][b][t]))
                        }) {
                            slot[d] = self.open_slots[j];
                        }
                    }
                    slot
                })
                .collect()
        });
        Raw {
            on,
            slots,
            value,
            proven,
            names,
        }
    }
}

/// One solve of the grid MILP (or its LP relaxation when `relax`), for [`run_on`].
struct GridJob<'a> {
    problem: &'a HopProblem,
    grid: &'a Grid,
    objective: &'a Objective,
    mode: Reorder,
    relax: bool,
    time_limit_s: f64,
}

impl MilpJob for GridJob<'_> {
    type Output = Solved;

    fn solve_with<S: good_lp::Solver>(self, solver: S, backend_name: &str) -> Result<Solved>
    where
        S::Model: MilpModel,
    {
        solve_with(
            solver,
            backend_name,
            self.problem,
            self.grid,
            self.mode,
            self.objective,
            self.relax,
            self.time_limit_s,
        )
    }
}

/// Runs [`solve_with`] on the chosen backend.
fn run(
    problem: &HopProblem,
    grid: &Grid,
    objective: &Objective,
    options: &MilpOptions,
    relax: bool,
) -> Result<Solved> {
    let job = GridJob {
        problem,
        grid,
        objective,
        mode: options.reorder,
        relax,
        time_limit_s: options.time_limit_s,
    };
    run_on(options.backend, options.node_limit, job)
}

/// Merges the consecutive periods of one leg in which a move is on into transfers, by start then
/// support drone.
fn transfers_of(
    problem: &HopProblem,
    grid: &Grid,
    mv: &[Move],
    on: &[Vec<bool>],
    slots: Option<&Vec<Vec<usize>>>,
) -> Vec<Transfer> {
    let rho = problem.rho_mah_per_min;
    let slot_of = |k: usize, t: usize| match slots {
        Some(sl) => sl[t][mv[k].consumer],
        None => mv[k].slot,
    };
    let mut out: Vec<Transfer> = Vec::new();
    for (k, m) in mv.iter().enumerate() {
        let mut t = 0;
        while t < grid.periods() {
            if !on[k][t] {
                t += 1;
                continue;
            }
            let q = slot_of(k, t);
            let mut e = t + 1;
            // Merge within a leg only: at a leg end the consumer's rate changes, and a transfer
            // that filled its consumer may go on only as a new transfer (rule 4).
            while e < grid.periods() && on[k][e] && slot_of(k, e) == q && grid.leg[e] == grid.leg[t]
            {
                e += 1;
            }
            let (a, z) = (grid.points_min[t], grid.points_min[e]);
            out.push(Transfer {
                support: m.support,
                consumer: m.consumer,
                start_min: a,
                end_min: z,
                energy_mah: rho * (z - a),
                consumer_slot: q,
            });
            t = e;
        }
    }
    out.sort_by(|a, b| {
        a.start_min
            .total_cmp(&b.start_min)
            .then(a.support.cmp(&b.support))
    });
    out
}

/// Whether every period's slot permutation is the identity except consumer swaps with delivery
/// drones, so that the transfers alone describe it.
fn swaps_only(
    problem: &HopProblem,
    transfers: &[Transfer],
    grid: &Grid,
    slots: &[Vec<usize>],
) -> bool {
    (0..grid.periods()).all(|t| {
        let mid = 0.5 * (grid.points_min[t] + grid.points_min[t + 1]);
        let active: Vec<Transfer> = transfers
            .iter()
            .filter(|x| x.start_min < mid && mid < x.end_min)
            .copied()
            .collect();
        let partners: Vec<usize> = active
            .iter()
            .filter_map(|x| reorder::swap_partner(problem, x))
            .collect();
        let distinct = partners
            .iter()
            .all(|p| active.iter().all(|x| x.consumer != *p))
            && partners
                .iter()
                .enumerate()
                .all(|(i, p)| !partners[..i].contains(p));
        distinct && reorder::slot_assignment(problem, &active) == slots[t]
    })
}

/// Solves the time-indexed sharing MILP of one hop.
///
/// # Arguments
/// * `problem` - the hop (legs with rates, drones, formation, `rho`, `R`, `delta`).
/// * `objective` - node time at the hop's end, lowest delivery arrival battery, or feasibility.
/// * `options` - grid step, re-ordering mode, backend, time limit.
///
/// # Returns
/// An [`ExactOutcome`]: status, objective of the replayed schedule and of the model, a bound
/// (the optimum when proven, else the better of the LP relaxation and the fluid LP), grid step, solve time, the schedule
/// and its replay through the hop evaluation. Optimal means optimal over full-period grid
/// schedules of step [`ExactOutcome::grid_step_min`].
///
/// # Errors
/// [`Error::Invalid`] for a malformed problem (`E4001`-`E4012`), a bad grid (`E4101`, `E4102`),
/// objective (`E4103`, `E4104`) or time limit (`E4105`); [`Error::Backend`] when the backend
/// fails, or returns a schedule whose replay is not flyable (`E4106` in the message).
///
/// # Complexity
/// `O(M P)` binaries for `M` moves and `P` periods (`free`: also `D^2 P`), plus `n min(k, n)` pad
/// binaries; exponential worst case.
///
/// # Example
/// ```
/// use swarmplan::eaas::*;
/// use swarmplan::problem::Role;
/// use swarmplan::eaas::exact::milp::{solve_milp, MilpOptions};
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
/// let o = solve_milp(&p, &Objective::MaxMinArrival, &MilpOptions::default()).unwrap();
/// assert_eq!(o.status, ExactStatus::Optimal);
/// // 80 - 100 + 4 * 10 = 20 mAh with sharing during the whole hop.
/// assert!((o.objective.unwrap() - 20.0).abs() < 1e-6);
/// ```
pub fn solve_milp(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
) -> Result<ExactOutcome> {
    validate_inputs(problem, objective, options.time_limit_s)?;
    let grid = Grid::new(problem, options.period_min)?;
    let start = Instant::now();
    let solved = run(problem, &grid, objective, options, false)?;
    let mut out = ExactOutcome::infeasible(grid.step_min(), grid.periods());
    let raw = match solved {
        Solved::Values(raw) => raw,
        Solved::Infeasible => {
            out.solve_ms = node_time_ms(start);
            return Ok(out);
        }
        Solved::NoSolution => {
            no_solution_in_time(&mut out, problem, &grid, objective, options)?;
            out.solve_ms = node_time_ms(start);
            return Ok(out);
        }
    };
    let mv = moves(problem, options.reorder);
    let transfers = transfers_of(problem, &grid, &mv, &raw.on, raw.slots.as_ref());
    let representable = raw
        .slots
        .as_ref()
        .is_none_or(|sl| swaps_only(problem, &transfers, &grid, sl));
    let final_battery = if representable {
        let replay = evaluate(problem, &transfers).into_outcome();
        if !replay.feasible && !raw.proven {
            // A backend stopped by the limit may return values that are not a solution (HiGHS
            // reports a time limit without saying whether it has an incumbent).
            no_solution_in_time(&mut out, problem, &grid, objective, options)?;
            out.solve_ms = node_time_ms(start);
            return Ok(out);
        }
        if !replay.feasible {
            return Err(Error::internal(
                "E4106",
                format!(
                    "{}: the schedule returned does not fly (first failure {:?})",
                    options.backend, replay.failure
                ),
            ));
        }
        let fb = replay.final_battery_mah.clone();
        out.outcome = Some(replay);
        fb
    } else {
        replay_free(
            problem,
            &grid,
            &transfers,
            raw.slots.as_deref().unwrap_or(&[]),
        )
    };
    let value = objective_of(problem, objective, &final_battery)?;
    out.objective = Some(value.value);
    out.objective_proven = value.proven;
    out.model_objective = Some(raw.value);
    out.transfers = transfers;
    out.slots = raw.slots;
    if raw.proven {
        out.status = ExactStatus::Optimal;
        out.bound = Some(raw.value);
    } else {
        out.status = ExactStatus::Feasible;
        out.bound = relaxation_bound(problem, &grid, objective, options)?;
    }
    out.solve_ms = node_time_ms(start);
    Ok(out)
}

/// The MILP [`solve_milp`] builds for this hop, objective and options (grid step, re-ordering)
/// in CPLEX LP format, for any MILP solver; [`model_text`] in free MPS too.
///
/// The model is built by the same code as for [`solve_milp`]'s backends and handed to
/// [`crate::solver::lp_file::LpCapture`] instead of a solver. Variables are named after
/// `models/eaas_milp.md`: `y_k{k}_t{t}` (move `k` in period `t`, the moves listed in the
/// header), `z_c{c}_q{q}_t{t}` (`free`: delivery drone `c` in slot `q`), `b_d{d}_t{t}` (battery
/// at grid point `t >= 1`, mAh), `x_d{d}_p{i}`, `w_d{d}_p{i}` (drone `d` on pad `i`, its charge
/// time there, min), `M` (node time, min), `g` (lowest delivery arrival battery, mAh). The
/// objective is the variable `M` or `g` (0 for feasibility) with no constant, so the file's
/// optimum is [`ExactOutcome::model_objective`].
///
/// # Arguments
/// * `problem` - the hop.
/// * `objective` - node time at the hop's end, lowest delivery arrival battery, or feasibility.
/// * `options` - grid step and re-ordering mode (backend and time limit are not used, the time
///   limit must still be valid).
/// * `about` - one line naming the hop for the file's header, such as
///   `request r00001 hop 0: n000 -> n012`.
///
/// # Returns
/// The LP text, whose header comment states the hop, objective, re-ordering, grid, the moves
/// and that the optimum is optimal over full-period schedules on this grid, and its size.
///
/// # Errors
/// Those of [`solve_milp`] for bad input (`E4001`-`E4012`, `E4101`-`E4105`); `E4116` for a hop
/// with no period (every leg of zero duration: the model has no schedule to write);
/// [`Error::Backend`] if the model cannot be captured.
pub fn lp_text(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
    about: &str,
) -> Result<(String, LpSize)> {
    model_text(problem, objective, options, about, ModelFormat::Lp)
}

/// [`lp_text`] in `format`: CPLEX LP or free MPS (the same rows, variables and header, see
/// [`crate::solver::lp_file::CapturedModel::to_mps`]).
///
/// # Errors
/// Those of [`lp_text`].
pub fn model_text(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
    about: &str,
    format: ModelFormat,
) -> Result<(String, LpSize)> {
    validate_inputs(problem, objective, options.time_limit_s)?;
    let grid = Grid::new(problem, options.period_min)?;
    if grid.periods() == 0 {
        return Err(Error::invalid(
            "E4116",
            "hop.legs",
            "every leg has zero duration: the MILP has no period",
            "export a hop that flies for some time",
        ));
    }
    let capture = LpCapture::new();
    let solved = solve_with(
        capture.solver(),
        "lp-file",
        problem,
        &grid,
        options.reorder,
        objective,
        false,
        options.time_limit_s,
    )?;
    let lost = |what: &str| {
        Error::backend(
            BackendFailure::LostModel,
            "lp-file",
            format!("the model was not captured ({what})"),
        )
    };
    let Solved::Values(raw) = solved else {
        return Err(lost("no values"));
    };
    let mut model = capture.take().ok_or_else(|| lost("empty capture"))?;
    model.rename(&raw.names)?;
    let size = model.size();
    let header = lp_header(problem, objective, options, &grid, about, &size);
    Ok((model.to_text(format, "swarmplan_hop_milp", &header), size))
}

/// Writes [`model_text`] to `path`: free MPS when its name ends in `.mps`, CPLEX LP otherwise
/// ([`ModelFormat::of_path`]).
///
/// # Arguments
/// As [`lp_text`], and `path`, the file to write (replaced if it exists).
///
/// # Returns
/// The size of the model written.
///
/// # Errors
/// Those of [`lp_text`]; [`Error::Io`] when the file cannot be written.
///
/// # Example
/// ```
/// use swarmplan::eaas::*;
/// use swarmplan::problem::Role;
/// use swarmplan::eaas::exact::milp::{write_lp, MilpOptions};
/// use swarmplan::eaas::exact::Objective;
/// use nalgebra::Vector2;
/// let p = HopProblem {
///     legs: vec![LegRates { duration_min: 3.0, rate_mah_per_min: vec![vec![10.0, 10.0], vec![5.0, 5.0]].into() }],
///     drones: vec![
///         DroneState { role: Role::Delivery, capacity_mah: 200.0, battery_mah: 80.0 },
///         DroneState { role: Role::Support, capacity_mah: 500.0, battery_mah: 500.0 },
///     ],
///     slots_m: vec![Vector2::new(0.0, 0.0), Vector2::new(1.0, 0.0)],
///     initial_slot: vec![0, 1],
///     rho_mah_per_min: 4.0, range_m: 1.2, gamma_mah: 50.0, lambda_mah: 20.0, delta_mah: 100.0,
/// };
/// let path = std::env::temp_dir().join("swarmplan_doc_example.lp");
/// let size = write_lp(&p, &Objective::MaxMinArrival, &MilpOptions::default(), "example", &path).unwrap();
/// // One move (support 1 serves 0) in 3 periods: 3 binaries.
/// assert_eq!(size.binaries, 3);
/// assert!(std::fs::read_to_string(&path).unwrap().contains("y_k0_t2"));
/// ```
pub fn write_lp(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
    about: &str,
    path: &Path,
) -> Result<LpSize> {
    let (text, size) = model_text(
        problem,
        objective,
        options,
        about,
        ModelFormat::of_path(path),
    )?;
    write_model_file(path, &text)?;
    Ok(size)
}

/// Comment lines opening an exported LP file.
fn lp_header(
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
    grid: &Grid,
    about: &str,
    size: &LpSize,
) -> Vec<String> {
    let n = problem.drones.len();
    let supports = (0..n)
        .filter(|&d| problem.drones[d].role == Role::Support)
        .count();
    let tt: f64 = problem.legs.iter().map(|l| l.duration_min).sum();
    let goal = match *objective {
        Objective::NodeTime(EndPads {
            pads,
            pad_rate_mah_per_min,
        }) => format!(
            "node_time, pads = {pads}, pad_rate_mah_per_min = {pad_rate_mah_per_min}: \
             minimise M, the node time at the hop's end, min"
        ),
        Objective::MaxMinArrival => {
            "max_min_arrival: maximise g, the lowest delivery arrival battery, mAh".to_string()
        }
        Objective::Feasible => "feasible: minimise 0, any schedule that flies".to_string(),
    };
    let mut out = vec![
        "swarmplan: time-indexed sharing MILP of one hop (models/eaas_milp.md), CPLEX LP format"
            .to_string(),
        format!(
            "hop: {about}; {} leg(s), tt = {tt} min, {n} drones ({} delivery, {supports} support)",
            problem.legs.len(),
            n - supports
        ),
        format!("objective: {goal}"),
        "objective constant: 0 (the optimum of this file is the MILP's model objective)"
            .to_string(),
        format!("reorder: {}", options.reorder.to_string()),
        format!(
            "grid: period_min = {}, grid_step_min = {}, periods = {}",
            options.period_min,
            grid.step_min(),
            grid.periods()
        ),
        "optimal over full-period schedules on this grid (a transfer runs for whole periods), \
         not over every continuous-time schedule"
            .to_string(),
        format!(
            "size: {} variables ({} binary), {} constraints ({} without variables that always \
             hold left out)",
            size.variables, size.binaries, size.constraints, size.trivial_constraints_left_out
        ),
        "variables: y_k{k}_t{t} move k runs in period t; b_d{d}_t{t} battery of drone d at grid \
         point t >= 1, mAh (t = 0 is the departure battery, a constant)"
            .to_string(),
    ];
    if options.reorder == Reorder::Free {
        out.push(
            "variables: z_c{c}_q{q}_t{t} delivery drone c flies in slot q during period t".into(),
        );
    }
    match objective {
        Objective::NodeTime(EndPads { .. }) => out.push(
            "variables: x_d{d}_p{i} drone d charges on pad i; w_d{d}_p{i} its charge time on \
             pad i, min; M node time, min"
                .into(),
        ),
        Objective::MaxMinArrival => {
            out.push("variables: g lowest delivery arrival battery, mAh".into())
        }
        Objective::Feasible => {}
    }
    out.push("periods (t, leg l, [start, end) min):".into());
    let mut t = 0;
    while t < grid.periods() {
        let l = grid.leg[t];
        let e = (t..grid.periods())
            .find(|&e| grid.leg[e] != l)
            .unwrap_or(grid.periods());
        let span = if e - t == 1 {
            format!("t{t}")
        } else {
            format!("t{t}..t{}", e - 1)
        };
        out.push(format!(
            "  {span}: leg {l}, [{}, {}), {} period(s) of {} min",
            grid.points_min[t],
            grid.points_min[e],
            e - t,
            grid.len_min(t)
        ));
        t = e;
    }
    out.push(
        "moves (k: support s serves consumer c flying in slot q; p the swap partner holding c's \
         slot):"
            .into(),
    );
    for (k, m) in moves(problem, options.reorder).iter().enumerate() {
        let slot = if options.reorder == Reorder::Free {
            "slot from z".to_string()
        } else {
            format!("q{}", m.slot)
        };
        out.push(match m.partner {
            Some(p) => format!("  k{k}: s{} c{} {slot} p{p}", m.support, m.consumer),
            None => format!("  k{k}: s{} c{} {slot}", m.support, m.consumer),
        });
    }
    out
}

/// The outcome of a solve stopped by its limit without a schedule: the bound, and the empty
/// schedule (a grid schedule of every mode) as the incumbent when it flies, so a hop that flies
/// without sharing is never `time_limit_no_solution`.
fn no_solution_in_time(
    out: &mut ExactOutcome,
    problem: &HopProblem,
    grid: &Grid,
    objective: &Objective,
    options: &MilpOptions,
) -> Result<()> {
    out.bound = relaxation_bound(problem, grid, objective, options)?;
    let empty = evaluate(problem, &[]).into_outcome();
    if !empty.feasible {
        out.status = ExactStatus::TimeLimitNoSolution;
        return Ok(());
    }
    let value = objective_of(problem, objective, &empty.final_battery_mah)?;
    out.status = ExactStatus::Feasible;
    out.objective = Some(value.value);
    out.objective_proven = value.proven;
    out.transfers = Vec::new();
    out.slots = (options.reorder == Reorder::Free)
        .then(|| vec![problem.initial_slot.clone(); grid.periods()]);
    out.outcome = Some(empty);
    Ok(())
}

fn node_time_ms(start: Instant) -> f64 {
    start.elapsed().as_secs_f64() * 1e3
}

/// A bound on the MILP's optimum after a time limit: the better of the LP relaxation (all
/// binaries in `[0, 1]`, when its solve finishes in the time limit) and the fluid LP bound
/// (`models/eaas_fluid.md`, valid for every continuous-time schedule, hence for the MILP's).
fn relaxation_bound(
    problem: &HopProblem,
    grid: &Grid,
    objective: &Objective,
    options: &MilpOptions,
) -> Result<Option<f64>> {
    let lp = match run(problem, grid, objective, options, true)? {
        Solved::Values(r) if r.proven => Some(r.value),
        _ => None,
    };
    let fluid = super::fluid::bound(problem, objective, options.reorder, options.time_limit_s)?;
    let maximise = matches!(objective, Objective::MaxMinArrival);
    Ok(match (lp, fluid.bound) {
        (Some(a), Some(b)) if maximise => Some(a.min(b)),
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    })
}

/// Final batteries of a `free` schedule, integrating per period with the given slots.
fn replay_free(
    problem: &HopProblem,
    grid: &Grid,
    transfers: &[Transfer],
    slots: &[Vec<usize>],
) -> Vec<f64> {
    let rho = problem.rho_mah_per_min;
    let mut b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
    for (t, slot) in slots.iter().enumerate().take(grid.periods()) {
        let h = grid.len_min(t);
        let mid = 0.5 * (grid.points_min[t] + grid.points_min[t + 1]);
        let rates = &problem.legs[grid.leg[t]].rate_mah_per_min;
        for (d, bd) in b.iter_mut().enumerate() {
            *bd -= h * rates[d][slot[d]];
        }
        for x in transfers
            .iter()
            .filter(|x| x.start_min < mid && mid < x.end_min)
        {
            b[x.support] -= rho * h;
            b[x.consumer] += rho * h;
        }
    }
    b
}
