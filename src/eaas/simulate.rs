//! Battery evolution under piecewise-constant rates: realises a planned schedule.
//!
//! A planned transfer `(s, c, start, planned_end, consumer_slot)` starts at `start` unless, at that
//! instant, the support drone has no sharing budget left, the consumer is full and would overfill
//! (its rate in `consumer_slot` is below `rho`), or it collides with a running transfer of the same
//! support or consumer. It ends at the first of: `planned_end`, `tt`, the consumer reaching its
//! capacity while gaining energy, the support drone exhausting its sharing budget
//! ([`super::sharing_budget_mah`], i.e. reaching `delta` net of its own remaining consumption).
//! Between breakpoints every battery is linear, so checks at breakpoints are exact.

use super::reorder::slot_assignment_into;
use super::{
    sharing_budget_mah, travel_time_min, FailureReason, HopFailure, HopOutcome, HopProblem, Role,
    Transfer, ENERGY_TOL_MAH, TIME_TOL_MIN,
};

/// A realised schedule with its batteries.
pub(crate) struct Run {
    /// Realised transfers, by start then support drone.
    pub transfers: Vec<Transfer>,
    /// Time of every breakpoint, minutes.
    pub times_min: Vec<f64>,
    /// Every drone's battery at every breakpoint, mAh: breakpoint `k`, drone `d` at
    /// `k * drones + d`.
    pub batteries_mah: Vec<f64>,
    /// Number of drones.
    pub drones: usize,
    /// First battery below zero.
    pub failure: Option<HopFailure>,
    /// Lowest battery per drone.
    pub min_battery: Vec<f64>,
    /// Energy given per drone (non-zero for support drones only).
    pub shared_by_support: Vec<f64>,
}

impl Run {
    /// The public outcome.
    pub fn into_outcome(self) -> HopOutcome {
        let final_battery_mah = self
            .breakpoint(self.times_min.len().wrapping_sub(1))
            .to_vec();
        HopOutcome {
            feasible: self.failure.is_none(),
            failure: self.failure,
            // fold from +0.0: `f64::sum` of no transfers is -0.0, printed as `-0.0` in reports.
            shared_mah: self.transfers.iter().fold(0.0, |a, t| a + t.energy_mah),
            transfers: self.transfers,
            final_battery_mah,
            min_battery_mah: self.min_battery,
        }
    }

    /// Whether `self` (a trial schedule) takes some drone below zero that `before` kept above it,
    /// or deeper below zero than `before` did: its lowest battery falls, and ends below zero. A
    /// transfer whose trial harms the swarm must not be made (models/eaas.md, "No harmful
    /// transfer"); so a hop feasible without sharing stays feasible under every policy.
    pub fn harms(&self, before: &Run) -> bool {
        self.min_battery
            .iter()
            .zip(&before.min_battery)
            .any(|(&after, &was)| after < -ENERGY_TOL_MAH && after < was - ENERGY_TOL_MAH)
    }

    /// Every drone's battery at breakpoint `k`; empty when there is no such breakpoint.
    pub fn breakpoint(&self, k: usize) -> &[f64] {
        if k >= self.times_min.len() {
            return &[];
        }
        &self.batteries_mah[k * self.drones..(k + 1) * self.drones]
    }

    /// Battery of drone `d` at `tt`.
    pub fn final_battery(&self, d: usize) -> f64 {
        self.breakpoint(self.times_min.len().wrapping_sub(1))
            .get(d)
            .copied()
            .unwrap_or(0.0)
    }

    /// Battery of drone `d` at time `t` (linear between breakpoints).
    pub fn battery_at(&self, d: usize, t: f64) -> f64 {
        let tr = &self.times_min;
        let k = tr.partition_point(|ti| *ti <= t);
        if k == 0 {
            return self.breakpoint(0)[d];
        }
        if k == tr.len() {
            return self.breakpoint(k - 1)[d];
        }
        let (t0, b0) = (tr[k - 1], self.breakpoint(k - 1)[d]);
        let (t1, b1) = (tr[k], self.breakpoint(k)[d]);
        if t1 - t0 <= 0.0 {
            return b1;
        }
        b0 + (b1 - b0) * (t - t0) / (t1 - t0)
    }

    /// `(t, batteries)` at every breakpoint.
    pub fn trace(&self) -> Vec<(f64, Vec<f64>)> {
        (0..self.times_min.len())
            .map(|k| (self.times_min[k], self.breakpoint(k).to_vec()))
            .collect()
    }
}

/// Index of the leg flown just after time `t`; `None` at or after `tt`.
pub(crate) fn leg_at(problem: &HopProblem, t: f64) -> Option<usize> {
    let mut end = 0.0;
    for (l, leg) in problem.legs.iter().enumerate() {
        end += leg.duration_min;
        if end > t + TIME_TOL_MIN {
            return Some(l);
        }
    }
    None
}

/// Realises `plan` over `[0, tt]`.
pub(crate) fn evaluate(problem: &HopProblem, plan: &[Transfer]) -> Run {
    let n = problem.drones.len();
    let rho = problem.rho_mah_per_min;
    let tt = travel_time_min(problem);
    let budget: Vec<f64> = (0..n)
        .map(|d| match problem.drones[d].role {
            Role::Support => sharing_budget_mah(problem, d),
            Role::Delivery => 0.0,
        })
        .collect();
    let cap: Vec<f64> = problem.drones.iter().map(|d| d.capacity_mah).collect();
    let mut plan: Vec<Transfer> = plan.to_vec();
    if plan.len() > 1 {
        plan.sort_by(|a, b| {
            a.start_min
                .total_cmp(&b.start_min)
                .then(a.support.cmp(&b.support))
                .then(a.consumer.cmp(&b.consumer))
        });
    }
    let mut leg_end = Vec::with_capacity(problem.legs.len());
    let mut acc = 0.0;
    for l in &problem.legs {
        acc += l.duration_min;
        leg_end.push(acc);
    }

    let mut t = 0.0_f64;
    let mut leg = 0usize;
    while leg < leg_end.len() && leg_end[leg] <= t + TIME_TOL_MIN {
        leg += 1;
    }
    let mut b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
    let mut min_battery = b.clone();
    let mut times_min = Vec::with_capacity(leg_end.len() + 2 * plan.len() + 2);
    let mut batteries_mah = Vec::with_capacity(n * (leg_end.len() + 2 * plan.len() + 2));
    times_min.push(0.0);
    batteries_mah.extend_from_slice(&b);
    let mut slot = problem.initial_slot.clone();
    let mut net = vec![0.0; n];
    let mut shared = vec![0.0; n];
    let mut active: Vec<Transfer> = Vec::new();
    let mut done: Vec<Transfer> = Vec::new();
    let mut failure: Option<HopFailure> = None;
    let mut next = 0usize;
    let guard = 4 * (plan.len() + problem.legs.len() + 2) * (n + 2) + 16;

    for _ in 0..guard {
        while next < plan.len() && plan[next].start_min <= t + TIME_TOL_MIN {
            let p = plan[next];
            next += 1;
            if leg >= leg_end.len() || p.end_min <= t + TIME_TOL_MIN {
                continue;
            }
            if budget[p.support] - shared[p.support] <= ENERGY_TOL_MAH {
                continue;
            }
            if active
                .iter()
                .any(|a| a.support == p.support || a.consumer == p.consumer)
            {
                continue;
            }
            let rate_c = problem.legs[leg].rate_mah_per_min[p.consumer][p.consumer_slot];
            if b[p.consumer] >= cap[p.consumer] - ENERGY_TOL_MAH && rate_c < rho {
                continue;
            }
            active.push(Transfer { start_min: t, ..p });
        }
        if leg >= leg_end.len() {
            break;
        }
        slot_assignment_into(problem, &active, &mut slot);
        let rates = &problem.legs[leg].rate_mah_per_min;
        // net[d] = consumption of d in mAh/min over this piece (negative when gaining).
        for d in 0..n {
            net[d] = rates[d][slot[d]];
        }
        for a in &active {
            net[a.support] += rho;
            net[a.consumer] -= rho;
        }
        let mut h = leg_end[leg] - t;
        if next < plan.len() {
            h = h.min(plan[next].start_min - t);
        }
        for a in &active {
            h = h.min(a.end_min - t);
            let c = a.consumer;
            if net[c] < 0.0 {
                h = h.min((cap[c] - b[c]) / -net[c]);
            }
            h = h.min((budget[a.support] - shared[a.support]) / rho);
        }
        let h = h.max(0.0);
        if failure.is_none() {
            let mut first: Option<HopFailure> = None;
            for d in 0..n {
                let nb = b[d] - net[d] * h;
                if nb < -ENERGY_TOL_MAH && net[d] > 0.0 {
                    let tf = t + b[d].max(0.0) / net[d];
                    if first.is_none_or(|f| tf < f.time_min) {
                        first = Some(HopFailure {
                            drone: d,
                            time_min: tf,
                            reason: FailureReason::BatteryDepleted,
                        });
                    }
                }
            }
            failure = first;
        }
        for d in 0..n {
            b[d] -= net[d] * h;
        }
        for a in &active {
            shared[a.support] += rho * h;
            if b[a.consumer] > cap[a.consumer] {
                b[a.consumer] = cap[a.consumer];
            }
        }
        t += h;
        if (t - leg_end[leg]).abs() <= TIME_TOL_MIN {
            t = leg_end[leg];
        }
        while leg < leg_end.len() && leg_end[leg] <= t + TIME_TOL_MIN {
            leg += 1;
        }
        if leg >= leg_end.len() {
            t = tt;
        }
        for d in 0..n {
            min_battery[d] = min_battery[d].min(b[d]);
        }
        let at_end = leg >= leg_end.len();
        active.retain(|a| {
            let c = a.consumer;
            let stop = at_end
                || a.end_min <= t + TIME_TOL_MIN
                || (net[c] < 0.0 && b[c] >= cap[c] - ENERGY_TOL_MAH)
                || budget[a.support] - shared[a.support] <= ENERGY_TOL_MAH;
            if stop && t - a.start_min > TIME_TOL_MIN {
                done.push(Transfer {
                    end_min: t,
                    energy_mah: rho * (t - a.start_min),
                    ..*a
                });
            }
            !stop
        });
        times_min.push(t);
        batteries_mah.extend_from_slice(&b);
    }
    done.sort_by(|a, b| {
        a.start_min
            .total_cmp(&b.start_min)
            .then(a.support.cmp(&b.support))
    });
    Run {
        transfers: done,
        times_min,
        batteries_mah,
        drones: n,
        failure,
        min_battery,
        shared_by_support: shared,
    }
}
