//! Fluid relaxation of one hop's sharing, solved with clarabel, see `models/eaas_fluid.md`.
//!
//! Per leg `l` (duration `τ_l`), the order of events inside the leg is forgotten; only amounts
//! remain (all in mAh or minutes):
//!
//! ```text
//! a[s][c][l] >= 0        energy support drone s gives consumer c during leg l
//! f[c][q][l] >= 0        time consumer c flies in non-support slot q during leg l (paper, free)
//! sum_q f[c][q][l] = τ_l,  sum_c f[c][q][l] = τ_l              slots are shared over time
//! a[s][c][l] <= rho sum_{q : |x_q - x_π(s)| <= R} f[c][q][l]    served only within range
//! sum_c a[s][c][l] <= rho τ_l,  sum_s a[s][c][l] <= rho τ_l     one at a time, at rate rho
//! sum_{c, l} a[s][c][l] <= B_s                                    support reserve
//! b[d][l+1] = b[d][l] - sum_q r[l][d][q] f[d][q][l] + sum_s a[s][d][l]   (delivery)
//! b[s][l+1] = b[s][l] - τ_l r[l][s][π(s)] - sum_c a[s][c][l]             (support)
//! 0 <= b[d][l] <= C_d at every leg end
//! ```
//!
//! With `none` re-ordering `f[c][π(c)][l] = τ_l` and only in-range pairs exist. The bounds
//! inside a leg are dropped (the relaxation). As an LP ([`bound`]) it minimises
//! `max(max_d ct_d, sum_d ct_d / k)`, `ct_d = (C_d - b_d(tt)) / pad rate`, a lower bound on the node
//! time of every continuous-time schedule; infeasibility proves no schedule flies. As a QP
//! ([`fair`]) it minimises `sum_d (C_d - b_d(tt))^2` over every drone, and its amounts are laid out
//! as a concrete schedule and replayed.

use super::EndPads;
use super::{
    objective_of, validate_inputs, BoundOutcome, ExactOutcome, ExactStatus, Objective, Reorder,
};
use crate::eaas::reorder::{busy_drones, choose_consumer_slot, slot_distance_m};
use crate::eaas::simulate::evaluate;
use crate::eaas::{sharing_budget_mah, HopProblem, Role, Transfer, TIME_TOL_MIN};
use crate::error::{BackendFailure, Error, Result};
use crate::solver::conic::{
    self, ConicSettings, ConicValues, CscMatrix, NonnegativeConeT, SupportedConeT, ZeroConeT,
};
use crate::solver::BackendStatus;
use std::time::Instant;

/// A linear row `sum coef x <= rhs` (or `= rhs`).
struct Row {
    terms: Vec<(usize, f64)>,
    rhs: f64,
}

/// The row `sum vars (<= or =) rhs`.
fn sum_row(vars: impl Iterator<Item = usize>, rhs: f64) -> Row {
    Row {
        terms: vars.map(|v| (v, 1.0)).collect(),
        rhs,
    }
}

/// The relaxation's variables and constraints, in clarabel's `A x + s = b`, `s in K` form.
struct Fluid {
    n_vars: usize,
    eq: Vec<Row>,
    le: Vec<Row>,
    /// `a[s][c][l]` variable index (or `None` for a pair that cannot share).
    a: Vec<Vec<Vec<Option<usize>>>>,
    /// `b[d][l]` for leg ends `l = 1..=L` (index `l - 1`).
    b_end: Vec<Vec<usize>>,
    /// Legs of positive duration.
    legs: Vec<usize>,
}

impl Fluid {
    fn var(&mut self) -> usize {
        self.n_vars += 1;
        self.le.push(Row {
            terms: vec![(self.n_vars - 1, -1.0)],
            rhs: 0.0,
        });
        self.n_vars - 1
    }

    /// The constant-plus-linear battery of `d` after leg index `i` (`i = 0` is the start).
    fn battery(&self, problem: &HopProblem, d: usize, i: usize) -> (f64, Vec<(usize, f64)>) {
        if i == 0 {
            (problem.drones[d].battery_mah, Vec::new())
        } else {
            (0.0, vec![(self.b_end[d][i - 1], 1.0)])
        }
    }

    fn build(problem: &HopProblem, mode: Reorder) -> Fluid {
        let n = problem.drones.len();
        let rho = problem.rho_mah_per_min;
        let is_support = |d: usize| problem.drones[d].role == Role::Support;
        let delivery: Vec<usize> = (0..n).filter(|&d| !is_support(d)).collect();
        let supports: Vec<usize> = (0..n).filter(|&d| is_support(d)).collect();
        let open: Vec<usize> = delivery.iter().map(|&d| problem.initial_slot[d]).collect();
        let legs: Vec<usize> = (0..problem.legs.len())
            .filter(|&l| problem.legs[l].duration_min > TIME_TOL_MIN)
            .collect();
        let mut m = Fluid {
            n_vars: 0,
            eq: Vec::new(),
            le: Vec::new(),
            a: vec![vec![vec![None; legs.len()]; n]; n],
            b_end: vec![Vec::new(); n],
            legs: legs.clone(),
        };
        let in_range = |s: usize, q: usize| {
            slot_distance_m(problem, problem.initial_slot[s], q) <= problem.range_m
        };
        for (i, &l) in legs.iter().enumerate() {
            let tau = problem.legs[l].duration_min;
            let rates = &problem.legs[l].rate_mah_per_min;
            // f[c][q] for c in delivery, q in open (paper, free).
            let f: Vec<Vec<usize>> = if mode == Reorder::None {
                Vec::new()
            } else {
                delivery
                    .iter()
                    .map(|_| open.iter().map(|_| m.var()).collect())
                    .collect()
            };
            for &s in &supports {
                for &c in &delivery {
                    if mode == Reorder::None && !in_range(s, problem.initial_slot[c]) {
                        continue;
                    }
                    m.a[s][c][i] = Some(m.var());
                }
            }
            if mode != Reorder::None {
                for fc in &f {
                    m.eq.push(sum_row(fc.iter().copied(), tau));
                }
                for j in 0..open.len() {
                    m.eq.push(sum_row(f.iter().map(|fc| fc[j]), tau));
                }
                for &s in &supports {
                    for (ci, &c) in delivery.iter().enumerate() {
                        let Some(a) = m.a[s][c][i] else { continue };
                        let mut terms = vec![(a, 1.0)];
                        for (j, &q) in open.iter().enumerate() {
                            if in_range(s, q) {
                                terms.push((f[ci][j], -rho));
                            }
                        }
                        m.le.push(Row { terms, rhs: 0.0 });
                    }
                }
            }
            for &s in &supports {
                let row = sum_row(delivery.iter().filter_map(|&c| m.a[s][c][i]), rho * tau);
                m.le.push(row);
            }
            for &c in &delivery {
                let row = sum_row(supports.iter().filter_map(|&s| m.a[s][c][i]), rho * tau);
                m.le.push(row);
            }
            // Battery balance: b_next - b_prev + use - received = 0.
            for d in 0..n {
                let next = m.var();
                let (c0, prev) = m.battery(problem, d, i);
                let mut terms = vec![(next, 1.0)];
                terms.extend(prev.iter().map(|&(v, k)| (v, -k)));
                let mut rhs = c0;
                if is_support(d) {
                    rhs -= tau * rates[d][problem.initial_slot[d]];
                    terms.extend(
                        delivery
                            .iter()
                            .filter_map(|&c| m.a[d][c][i])
                            .map(|v| (v, 1.0)),
                    );
                } else {
                    match delivery.iter().position(|&x| x == d) {
                        Some(ci) if mode != Reorder::None => {
                            for (j, &q) in open.iter().enumerate() {
                                terms.push((f[ci][j], rates[d][q]));
                            }
                        }
                        _ => rhs -= tau * rates[d][problem.initial_slot[d]],
                    }
                    terms.extend(
                        supports
                            .iter()
                            .filter_map(|&s| m.a[s][d][i])
                            .map(|v| (v, -1.0)),
                    );
                }
                m.eq.push(Row { terms, rhs });
                m.le.push(Row {
                    terms: vec![(next, 1.0)],
                    rhs: problem.drones[d].capacity_mah,
                });
                m.b_end[d].push(next);
            }
        }
        for &s in &supports {
            let row = sum_row(
                m.a[s].iter().flatten().flatten().copied(),
                sharing_budget_mah(problem, s),
            );
            m.le.push(row);
        }
        m
    }

    /// Final battery of `d` as (constant, terms).
    fn final_battery(&self, problem: &HopProblem, d: usize) -> (f64, Vec<(usize, f64)>) {
        self.battery(problem, d, self.legs.len())
    }

    /// Solves `min 1/2 x'Px + q'x` over the rows; `p_diag` gives P's diagonal entries. The
    /// status, and the answer when optimal.
    fn solve(
        &self,
        q: &[f64],
        p_diag: &[(usize, f64)],
        time_limit_s: f64,
    ) -> Result<(ExactStatus, Option<ConicValues>)> {
        let (mut ri, mut ci, mut vals, mut rhs) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (r, row) in self.eq.iter().chain(&self.le).enumerate() {
            for &(c, v) in &row.terms {
                ri.push(r);
                ci.push(c);
                vals.push(v);
            }
            rhs.push(row.rhs);
        }
        let rows = self.eq.len() + self.le.len();
        let a = CscMatrix::new_from_triplets(rows, self.n_vars, ri, ci, vals);
        let (pi, pj): (Vec<usize>, Vec<usize>) = p_diag.iter().map(|&(i, _)| (i, i)).unzip();
        let pv: Vec<f64> = p_diag.iter().map(|&(_, v)| v).collect();
        let p = CscMatrix::new_from_triplets(self.n_vars, self.n_vars, pi, pj, pv);
        let cones: Vec<SupportedConeT<f64>> =
            vec![ZeroConeT(self.eq.len()), NonnegativeConeT(self.le.len())];
        let settings = ConicSettings {
            tolerance: 1e-10,
            time_limit_s: Some(time_limit_s),
        };
        let out = conic::solve(&p, q, &a, &rhs, &cones, settings)?;
        Ok((status_of(out.status)?, out.values))
    }
}

/// The outcome of the relaxation from clarabel's; errors for an unbounded relaxation (every
/// variable of the relaxation is bounded, so never).
fn status_of(status: BackendStatus) -> Result<ExactStatus> {
    match status {
        BackendStatus::Optimal => Ok(ExactStatus::Optimal),
        BackendStatus::Infeasible => Ok(ExactStatus::Infeasible),
        BackendStatus::LimitNoSolution => Ok(ExactStatus::TimeLimitNoSolution),
        BackendStatus::Unbounded | BackendStatus::OptimalWithinGap | BackendStatus::Feasible => {
            Err(Error::backend(
                BackendFailure::Numerical,
                "clarabel",
                format!("stopped with status {status:?}; report it with the instance"),
            ))
        }
    }
}

/// Fluid LP bound of a hop.
///
/// # Arguments
/// * `problem` - the hop.
/// * `objective` - `NodeTime`: minimise `max(max_d ct_d, sum_d ct_d / k)` (a lower bound on the
///   node time of every continuous-time schedule); `MaxMinArrival`: maximise the lowest delivery
///   arrival battery (an upper bound); `Feasible`: feasibility of the relaxation.
/// * `mode` - re-ordering mode; `paper` and `free` share one relaxation (slot time shares).
/// * `time_limit_s` - clarabel's time limit.
///
/// # Returns
/// Status `optimal` with `bound` (the safer of the primal and dual objective values) and
/// `model_objective`, or `infeasible`: then no continuous-time schedule of the mode flies, and
/// neither does any MILP schedule. No schedule.
///
/// # Errors
/// [`Error::Invalid`] for a malformed problem, objective or time limit; [`Error::Backend`] when
/// clarabel fails numerically.
///
/// # Complexity
/// `O(L (S D + D^2))` variables; interior point, polynomial.
pub fn bound(
    problem: &HopProblem,
    objective: &Objective,
    mode: Reorder,
    time_limit_s: f64,
) -> Result<BoundOutcome> {
    validate_inputs(problem, objective, time_limit_s)?;
    let start = Instant::now();
    let mut m = Fluid::build(problem, mode);
    let n = problem.drones.len();
    // The goal variable g: min g (node time) or min -g (max-min).
    let g = m.var();
    let mut q = vec![0.0; m.n_vars];
    let mut sign = 1.0;
    match *objective {
        Objective::NodeTime(EndPads {
            pads,
            pad_rate_mah_per_min: pr,
        }) => {
            q[g] = 1.0;
            // ct_d = (C_d - b_d) / pr <= g, i.e. -b_d / pr - g <= -C_d / pr (+ constant part).
            let mut sum_terms = vec![(g, -1.0)];
            let mut sum_rhs = 0.0;
            for d in 0..n {
                let cap = problem.drones[d].capacity_mah;
                let (c0, terms) = m.final_battery(problem, d);
                let mut row: Vec<(usize, f64)> = terms.iter().map(|&(v, k)| (v, -k / pr)).collect();
                row.push((g, -1.0));
                m.le.push(Row {
                    terms: row,
                    rhs: (c0 - cap) / pr,
                });
                sum_terms.extend(terms.iter().map(|&(v, k)| (v, -k / (pr * pads as f64))));
                sum_rhs += (c0 - cap) / (pr * pads as f64);
            }
            m.le.push(Row {
                terms: sum_terms,
                rhs: sum_rhs,
            });
        }
        Objective::MaxMinArrival => {
            q[g] = -1.0;
            sign = -1.0;
            for d in (0..n).filter(|&d| problem.drones[d].role == Role::Delivery) {
                let (c0, terms) = m.final_battery(problem, d);
                let mut row: Vec<(usize, f64)> = terms.iter().map(|&(v, k)| (v, -k)).collect();
                row.push((g, 1.0));
                m.le.push(Row {
                    terms: row,
                    rhs: c0,
                });
            }
            // g is free: drop its default g >= 0 row by bounding it below by -sum of capacities.
            let lo = -problem.drones.iter().map(|d| d.capacity_mah).sum::<f64>();
            if let Some(r) = m.le.iter_mut().find(|r| r.terms == [(g, -1.0)]) {
                r.rhs = -lo;
            }
        }
        Objective::Feasible => {}
    }
    let (status, values) = m.solve(&q, &[], time_limit_s)?;
    Ok(BoundOutcome {
        status,
        // Minimisation of sign * goal: the smaller of primal and dual is the safer lower bound.
        bound: values.as_ref().map(|v| sign * v.primal.min(v.dual)),
        model_objective: values.as_ref().map(|v| sign * v.primal),
        legs: m.legs.len(),
        solve_ms: start.elapsed().as_secs_f64() * 1e3,
    })
}

/// The "fair" optimum of a hop: the fluid QP minimising `sum_d (C_d - b_d(tt))^2` over every
/// drone (delivery and support), FB's exact counterpart, laid out as a schedule.
///
/// # Arguments
/// * `problem` - the hop.
/// * `objective` - how the replayed schedule is scored in [`ExactOutcome::objective`].
/// * `mode` - re-ordering mode of the relaxation; the schedule itself uses the paper's fixed
///   re-ordering for out-of-range consumers.
/// * `time_limit_s` - clarabel's time limit.
///
/// # Returns
/// `model_objective` = the QP's optimum (mAh^2, a lower bound on the squared-deficit sum of every
/// continuous-time schedule; `bound` is `None`, the hop's objective has none here); `transfers` = per leg and support drone, its
/// consumers' amounts `a / rho` back to back from the leg start (delayed past transfers that
/// would move the same drone, clipped at the leg end), replayed by the hop evaluation in
/// `outcome` (which may be infeasible: the layout is a heuristic); `objective` = the replay's
/// score under `objective`.
///
/// # Errors
/// As [`bound`].
///
/// # Complexity
/// As [`bound`], plus `O(L S D T)` for the layout of `T` transfers.
pub fn fair(
    problem: &HopProblem,
    objective: &Objective,
    mode: Reorder,
    time_limit_s: f64,
) -> Result<ExactOutcome> {
    validate_inputs(problem, objective, time_limit_s)?;
    let start = Instant::now();
    let m = Fluid::build(problem, mode);
    let n = problem.drones.len();
    let mut q = vec![0.0; m.n_vars];
    let mut p_diag = Vec::new();
    let mut constant = 0.0;
    let mut linear_const = 0.0;
    for d in 0..n {
        let cap = problem.drones[d].capacity_mah;
        let (c0, terms) = m.final_battery(problem, d);
        match terms.first() {
            Some(&(v, _)) => {
                p_diag.push((v, 2.0));
                q[v] += -2.0 * cap;
                constant += cap * cap;
            }
            None => linear_const += (cap - c0).powi(2),
        }
    }
    let (status, values) = m.solve(&q, &p_diag, time_limit_s)?;
    let mut out = ExactOutcome::infeasible(0.0, m.legs.len());
    out.status = status;
    let Some(ConicValues { x, primal, .. }) = values else {
        out.solve_ms = start.elapsed().as_secs_f64() * 1e3;
        return Ok(out);
    };
    // The QP's optimum bounds the squared deficits, not the hop's objective: no `bound`.
    out.model_objective = Some(primal + constant + linear_const);
    let transfers = layout(problem, &m, &x);
    let replay = evaluate(problem, &transfers).into_outcome();
    let value = objective_of(problem, objective, &replay.final_battery_mah)?;
    out.objective = Some(value.value);
    out.objective_proven = value.proven;
    out.transfers = replay.transfers.clone();
    out.outcome = Some(replay);
    out.solve_ms = start.elapsed().as_secs_f64() * 1e3;
    Ok(out)
}

/// Sum of squared end deficits `sum_d (C_d - b_d)^2`, mAh^2.
pub fn squared_deficits(problem: &HopProblem, final_battery_mah: &[f64]) -> f64 {
    problem
        .drones
        .iter()
        .zip(final_battery_mah)
        .map(|(d, b)| (d.capacity_mah - b).powi(2))
        .sum()
}

/// Lays the relaxation's amounts out as transfers (see [`fair`]).
fn layout(problem: &HopProblem, m: &Fluid, x: &[f64]) -> Vec<Transfer> {
    let rho = problem.rho_mah_per_min;
    let n = problem.drones.len();
    let mut leg_start = vec![0.0; problem.legs.len() + 1];
    for l in 0..problem.legs.len() {
        leg_start[l + 1] = leg_start[l] + problem.legs[l].duration_min;
    }
    let mut plan: Vec<Transfer> = Vec::new();
    for (i, &l) in m.legs.iter().enumerate() {
        let (from, to) = (leg_start[l], leg_start[l + 1]);
        for s in 0..n {
            let mut at = from;
            for c in 0..n {
                let Some(v) = m.a[s][c][i] else { continue };
                let dur = x[v].max(0.0) / rho;
                if dur <= 1e-7 {
                    continue;
                }
                // Delay past conflicting transfers, at most once per placed transfer.
                for _ in 0..=plan.len() {
                    if at >= to - TIME_TOL_MIN {
                        break;
                    }
                    let end = (at + dur).min(to);
                    let busy = busy_drones(problem, &plan, at, end);
                    if let Some(slot) = choose_consumer_slot(problem, s, c, &busy) {
                        plan.push(Transfer {
                            support: s,
                            consumer: c,
                            start_min: at,
                            end_min: end,
                            energy_mah: rho * (end - at),
                            consumer_slot: slot,
                        });
                        at = end;
                        break;
                    }
                    at = plan
                        .iter()
                        .filter(|t| t.start_min < end && at < t.end_min)
                        .map(|t| t.end_min)
                        .fold(to, f64::min);
                }
            }
        }
    }
    plan
}
