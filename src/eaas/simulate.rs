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

/// Realises `plan` over `[0, tt]` (models/eaas.md, "Evaluation"): at each breakpoint the planned
/// transfers due start, the slot assignment gives every drone's net rate, and the batteries
/// advance to the next event.
pub(crate) fn evaluate(problem: &HopProblem, plan: &[Transfer]) -> Run {
    let mut run = Evaluation::new(problem, plan);
    let guard = 4 * (run.plan.len() + problem.legs.len() + 2) * (run.n + 2) + 16;
    for _ in 0..guard {
        run.start_due();
        if run.leg >= run.leg_end.len() {
            break;
        }
        run.net_rates();
        let h = run.next_event();
        if run.failure.is_none() {
            run.failure = run.first_failure(h);
        }
        run.advance(h);
        run.end_transfers();
        run.times_min.push(run.t);
        run.batteries_mah.extend_from_slice(&run.b);
    }
    run.into_run()
}

/// The state of one evaluation: the hop, the planned transfers by start, and at the current
/// breakpoint the time, leg, batteries, energy shared, running transfers and the record so far.
struct Evaluation<'a> {
    problem: &'a HopProblem,
    n: usize,
    rho: f64,
    tt: f64,
    /// Sharing budget of every drone (0 for delivery drones).
    budget: Vec<f64>,
    cap: Vec<f64>,
    /// The planned transfers, by start, support, then consumer.
    plan: Vec<Transfer>,
    /// End of every leg, min.
    leg_end: Vec<f64>,
    t: f64,
    leg: usize,
    b: Vec<f64>,
    min_battery: Vec<f64>,
    times_min: Vec<f64>,
    batteries_mah: Vec<f64>,
    slot: Vec<usize>,
    /// Consumption of every drone over the current piece, mAh/min (negative when gaining).
    net: Vec<f64>,
    shared: Vec<f64>,
    active: Vec<Transfer>,
    done: Vec<Transfer>,
    failure: Option<HopFailure>,
    /// The next planned transfer not yet due.
    next: usize,
}

impl<'a> Evaluation<'a> {
    /// The evaluation at time 0: `plan` sorted, the first breakpoint recorded.
    fn new(problem: &'a HopProblem, plan: &[Transfer]) -> Self {
        let n = problem.drones.len();
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
        let t = 0.0_f64;
        let mut leg = 0usize;
        while leg < leg_end.len() && leg_end[leg] <= t + TIME_TOL_MIN {
            leg += 1;
        }
        let b: Vec<f64> = problem.drones.iter().map(|d| d.battery_mah).collect();
        let mut times_min = Vec::with_capacity(leg_end.len() + 2 * plan.len() + 2);
        let mut batteries_mah = Vec::with_capacity(n * (leg_end.len() + 2 * plan.len() + 2));
        times_min.push(0.0);
        batteries_mah.extend_from_slice(&b);
        Evaluation {
            problem,
            n,
            rho: problem.rho_mah_per_min,
            tt: travel_time_min(problem),
            budget,
            cap,
            plan,
            leg_end,
            t,
            leg,
            min_battery: b.clone(),
            b,
            times_min,
            batteries_mah,
            slot: problem.initial_slot.clone(),
            net: vec![0.0; n],
            shared: vec![0.0; n],
            active: Vec::new(),
            done: Vec::new(),
            failure: None,
            next: 0,
        }
    }

    /// Starts the planned transfers due now, unless the hop is over or the transfer's end has
    /// passed, its support drone has no budget left, it collides with a running transfer of the
    /// same support or consumer, or its consumer is full and would overfill.
    fn start_due(&mut self) {
        let t = self.t;
        while self.next < self.plan.len() && self.plan[self.next].start_min <= t + TIME_TOL_MIN {
            let p = self.plan[self.next];
            self.next += 1;
            if self.leg >= self.leg_end.len() || p.end_min <= t + TIME_TOL_MIN {
                continue;
            }
            if self.budget[p.support] - self.shared[p.support] <= ENERGY_TOL_MAH {
                continue;
            }
            if self
                .active
                .iter()
                .any(|a| a.support == p.support || a.consumer == p.consumer)
            {
                continue;
            }
            let rate_c = self.problem.legs[self.leg].rate_mah_per_min[p.consumer][p.consumer_slot];
            if self.b[p.consumer] >= self.cap[p.consumer] - ENERGY_TOL_MAH && rate_c < self.rho {
                continue;
            }
            self.active.push(Transfer { start_min: t, ..p });
        }
    }

    /// The slot assignment of the running transfers, and every drone's net rate over the piece.
    fn net_rates(&mut self) {
        slot_assignment_into(self.problem, &self.active, &mut self.slot);
        let rates = &self.problem.legs[self.leg].rate_mah_per_min;
        for d in 0..self.n {
            self.net[d] = rates[d][self.slot[d]];
        }
        for a in &self.active {
            self.net[a.support] += self.rho;
            self.net[a.consumer] -= self.rho;
        }
    }

    /// The length of the piece to the next event: the leg's end, the next planned start, a
    /// planned end, a consumer reaching its capacity, a support drone exhausting its budget.
    fn next_event(&self) -> f64 {
        let (t, b, cap) = (self.t, &self.b, &self.cap);
        let mut h = self.leg_end[self.leg] - t;
        if self.next < self.plan.len() {
            h = h.min(self.plan[self.next].start_min - t);
        }
        for a in &self.active {
            h = h.min(a.end_min - t);
            let c = a.consumer;
            if self.net[c] < 0.0 {
                h = h.min((cap[c] - b[c]) / -self.net[c]);
            }
            h = h.min((self.budget[a.support] - self.shared[a.support]) / self.rho);
        }
        h.max(0.0)
    }

    /// The first drone whose battery falls below zero over the next `h` minutes, and when.
    fn first_failure(&self, h: f64) -> Option<HopFailure> {
        let mut first: Option<HopFailure> = None;
        for d in 0..self.n {
            let nb = self.b[d] - self.net[d] * h;
            if nb < -ENERGY_TOL_MAH && self.net[d] > 0.0 {
                let tf = self.t + self.b[d].max(0.0) / self.net[d];
                if first.is_none_or(|f| tf < f.time_min) {
                    first = Some(HopFailure {
                        drone: d,
                        time_min: tf,
                        reason: FailureReason::BatteryDepleted,
                    });
                }
            }
        }
        first
    }

    /// Advances every battery and the energy shared by `h` minutes (a consumer never above its
    /// capacity), to the next breakpoint and its leg (`tt` past the last one).
    fn advance(&mut self, h: f64) {
        for d in 0..self.n {
            self.b[d] -= self.net[d] * h;
        }
        for a in &self.active {
            self.shared[a.support] += self.rho * h;
            if self.b[a.consumer] > self.cap[a.consumer] {
                self.b[a.consumer] = self.cap[a.consumer];
            }
        }
        self.t += h;
        if (self.t - self.leg_end[self.leg]).abs() <= TIME_TOL_MIN {
            self.t = self.leg_end[self.leg];
        }
        while self.leg < self.leg_end.len() && self.leg_end[self.leg] <= self.t + TIME_TOL_MIN {
            self.leg += 1;
        }
        if self.leg >= self.leg_end.len() {
            self.t = self.tt;
        }
        for d in 0..self.n {
            self.min_battery[d] = self.min_battery[d].min(self.b[d]);
        }
    }

    /// Ends the running transfers whose hop, planned end, consumer's room or support's budget
    /// is over; one that ran is recorded.
    fn end_transfers(&mut self) {
        let at_end = self.leg >= self.leg_end.len();
        let (t, rho) = (self.t, self.rho);
        let (net, b, cap) = (&self.net, &self.b, &self.cap);
        let (budget, shared, done) = (&self.budget, &self.shared, &mut self.done);
        self.active.retain(|a| {
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
    }

    /// The realised schedule, its transfers by start then support drone.
    fn into_run(mut self) -> Run {
        self.done.sort_by(|a, b| {
            a.start_min
                .total_cmp(&b.start_min)
                .then(a.support.cmp(&b.support))
        });
        Run {
            transfers: self.done,
            times_min: self.times_min,
            batteries_mah: self.batteries_mah,
            drones: self.n,
            failure: self.failure,
            min_battery: self.min_battery,
            shared_by_support: self.shared,
        }
    }
}
