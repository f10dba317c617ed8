//! Flying one hop: turning a network path into the hop problem of in-flight sharing, and the
//! node time at a recharging stop.

use super::factors::{EdgeFactorCache, EdgeFactors};
use super::plan::{Hop, LegFlown, Plan, Stop};
use crate::eaas::exact::EndPads;
use crate::eaas::exact::Objective;
use crate::eaas::exact_hop::HopGoal;
use crate::eaas::exact_hop::{self, ExactSettings, HopSolve, HopSolveCounts};
use crate::eaas::{self, HopOutcome, HopPolicy, HopProblem, SharingPolicy};
use crate::energy;
use crate::error::{Error, Result};
use crate::network::Route;
use crate::node_time::{self, Limits};
use crate::problem::Profile;
use crate::problem::Readings;
use crate::problem::SkywayGraph;
use crate::problem::{Role, Swarm};
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

/// Rate matrices `[drone][slot]` per directed edge ([`Planner::edge_key`]), each computed once.
type RateCache = Vec<OnceLock<Arc<Vec<Vec<f64>>>>>;

/// Exact and fair flights from full batteries, by policy, path nodes and goal.
type FlightCache = Mutex<HashMap<(SharingPolicy, Vec<usize>, HopGoal), Flight>>;

/// Data a [`Planner`] or a [`super::Context`] holds: given by reference (cloned once) or as an
/// `Arc` (shared without a copy), so that both own what they read and can be sent to and shared
/// between threads.
pub trait IntoShared<T> {
    /// The data behind an `Arc`.
    fn into_shared(self) -> Arc<T>;
}

impl<T: Clone> IntoShared<T> for &T {
    fn into_shared(self) -> Arc<T> {
        Arc::new(self.clone())
    }
}

impl<T> IntoShared<T> for Arc<T> {
    fn into_shared(self) -> Arc<T> {
        self
    }
}

impl<T> IntoShared<T> for &Arc<T> {
    fn into_shared(self) -> Arc<T> {
        Arc::clone(self)
    }
}

/// A hop flown under a policy: the replayed schedule, and for the exact and fair policies how
/// their solve ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Flight {
    /// The schedule and batteries.
    pub outcome: HopOutcome,
    /// The exact or fair solve behind the schedule (`None` for the simulated policies).
    pub solve: Option<HopSolve>,
}

/// Everything fixed while one request is planned: network, profile, swarm and sharing policy.
///
/// A planner owns what it reads (`Arc` where shared) and its caches are filled once per entry, so
/// it is `Send + Sync`: one planner may compose on several threads at once. What a composition
/// counts (its hop solves) comes back in its [`Plan`].
pub struct Planner {
    graph: Arc<SkywayGraph>,
    profile: Arc<Profile>,
    swarm: Arc<Swarm>,
    sharing: SharingPolicy,
    /// Consumption-rate matrices `[drone][slot]` per directed edge, computed once.
    rates: RateCache,
    /// The energy model's leg factors of every directed edge (shared with other planners of the
    /// same formation slots through [`Planner::with_edge_factors`]).
    factors: OnceLock<Arc<EdgeFactors>>,
    /// Every drone's `base rate x payload factor`, mAh/min.
    payload_rates: OnceLock<Vec<f64>>,
    /// The swarm's least total consumption rate per directed edge, mAh/min, computed once.
    cheapest_rates: Vec<OnceLock<f64>>,
    /// Settings of the exact and fair policies.
    exact: ExactSettings,
    /// The exact and fair flights from full batteries solved so far: a hop departing full is
    /// the same model whichever route method or stop sequence flies it.
    flights: FlightCache,
    /// Node limit of the exact node time at every stop; `None` for none.
    node_limit: Option<u64>,
    /// Which paths the hops of the optimal route may follow.
    hop_paths: super::HopPaths,
    /// Whether a hop problem of this planner passed [`eaas::validate`] (the rules that do not
    /// depend on the path: drones, slots, sharing parameters).
    validated: AtomicBool,
}

impl Planner {
    /// A planner for one swarm on one network; each of the three given by reference (copied
    /// once) or as an `Arc` (shared).
    pub fn new(
        graph: impl IntoShared<SkywayGraph>,
        profile: impl IntoShared<Profile>,
        swarm: impl IntoShared<Swarm>,
        sharing: SharingPolicy,
    ) -> Planner {
        let graph = graph.into_shared();
        let directed_edges = 2 * graph.edge_count();
        Planner {
            graph,
            profile: profile.into_shared(),
            swarm: swarm.into_shared(),
            sharing,
            rates: (0..directed_edges).map(|_| OnceLock::new()).collect(),
            cheapest_rates: (0..directed_edges).map(|_| OnceLock::new()).collect(),
            factors: OnceLock::new(),
            payload_rates: OnceLock::new(),
            exact: ExactSettings::default(),
            flights: Mutex::new(HashMap::new()),
            node_limit: Some(node_time::DEFAULT_STOP_NODE_LIMIT),
            hop_paths: super::HopPaths::Rule,
            validated: AtomicBool::new(false),
        }
    }

    /// The planner with the given settings of the exact and fair policies.
    pub fn with_exact(mut self, settings: ExactSettings) -> Planner {
        self.exact = settings;
        self
    }

    /// The planner with the node limit of the exact node time at every stop (`None`: no limit;
    /// default [`node_time::DEFAULT_STOP_NODE_LIMIT`]).
    pub fn with_node_limit(mut self, node_limit: Option<u64>) -> Planner {
        self.node_limit = node_limit;
        self
    }

    /// The planner with the hop-path rule of its optimal route ([`super::RouteMethod::Optimal`]);
    /// default [`super::HopPaths::Rule`].
    pub fn with_hop_paths(mut self, hop_paths: super::HopPaths) -> Planner {
        self.hop_paths = hop_paths;
        self
    }

    /// Which paths the hops of the optimal route may follow.
    pub fn hop_paths(&self) -> super::HopPaths {
        self.hop_paths
    }

    /// The planner reading and filling the energy model's leg factors in `cache` (the table of
    /// this swarm's formation slots), so that planners of swarms flying the same slots compute
    /// them once; by default a planner keeps its own.
    pub fn with_edge_factors(self, cache: &EdgeFactorCache) -> Planner {
        let _ = self.factors.set(cache.for_slots(&self.swarm.slots_m));
        self
    }

    /// Settings of the exact and fair policies.
    pub fn exact_settings(&self) -> &ExactSettings {
        &self.exact
    }

    /// Charging rate of the pads at `node`, mAh/min.
    pub fn pad_rate_mah_per_min(&self, node: usize) -> f64 {
        self.graph
            .pad_rate_mah_per_min(node, self.profile.pads.charge_rate_mah_per_min)
    }

    /// The network.
    pub fn graph(&self) -> &SkywayGraph {
        &self.graph
    }

    /// The swarm.
    pub fn swarm(&self) -> &Swarm {
        &self.swarm
    }

    /// The plan of `source -> destination` before any hop is flown.
    pub(crate) fn empty_plan(&self, source: usize, destination: usize) -> Plan {
        Plan::new(
            self.graph.id_of(source).to_string(),
            self.graph.id_of(destination).to_string(),
        )
    }

    /// The readings of the paper the planner follows (the profile's `[readings]`).
    pub fn readings(&self) -> &Readings {
        &self.profile.readings
    }

    /// The sharing policy used on every hop.
    pub fn sharing(&self) -> SharingPolicy {
        self.sharing
    }

    /// Ground speed of the swarm, m/min.
    pub fn speed_m_per_min(&self) -> f64 {
        self.profile.drone.speed_kmh * 1000.0 / 60.0
    }

    /// Every drone's capacity, mAh, by drone id: the battery after a full charge.
    pub fn full_battery_mah(&self) -> Vec<f64> {
        self.swarm.drones.iter().map(|d| d.capacity_mah).collect()
    }

    /// The consumption-rate matrix `[drone][slot]` of flying `leg`, computed once per directed
    /// edge and checked then: every rate finite and `>= 0`.
    ///
    /// # Errors
    /// [`Error::Invalid`] with E4007 when the energy model gives a rate that is not finite or is
    /// negative (the profile and network passed validation, so this would be a bug).
    pub(super) fn leg_rates(&self, leg: &crate::network::Leg) -> Result<Arc<Vec<Vec<f64>>>> {
        let key = self.edge_key(leg);
        if let Some(rate) = self.rates[key].get() {
            return Ok(Arc::clone(rate));
        }
        let factors = self.leg_factors(key, leg);
        let rate = energy::rate_matrix_from_factors(
            self.payload_rates(),
            factors.wind_factor,
            &factors.slot_factors,
        );
        let bad = rate.iter().enumerate().find_map(|(d, row)| {
            row.iter()
                .position(|&r| !(r.is_finite() && r >= 0.0))
                .map(|q| (d, q))
        });
        if let Some((d, q)) = bad {
            return Err(Error::invalid(
                "E4007",
                format!(
                    "rate of drone {d} in slot {q} from {} to {}",
                    self.graph.id_of(leg.from),
                    self.graph.id_of(leg.to)
                ),
                format!("{} is not a finite rate >= 0", rate[d][q]),
                "report it with the network and profile",
            ));
        }
        // Another thread may have set the same numbers first.
        Ok(Arc::clone(self.rates[key].get_or_init(|| Arc::new(rate))))
    }

    /// The least total consumption rate of the swarm on `leg`: every drone in its cheapest slot,
    /// mAh/min, computed once per directed edge.
    ///
    /// # Errors
    /// Those of [`Planner::leg_rates`].
    pub(crate) fn cheapest_swarm_rate_mah_per_min(&self, leg: &crate::network::Leg) -> Result<f64> {
        let key = self.edge_key(leg);
        if let Some(&rate) = self.cheapest_rates[key].get() {
            return Ok(rate);
        }
        let rate: f64 = self.least_rates(key, leg).sum();
        if !(rate.is_finite() && rate >= 0.0) {
            // The rate matrix names the culprit.
            self.leg_rates(leg)?;
        }
        Ok(*self.cheapest_rates[key].get_or_init(|| rate))
    }

    /// Every drone's least rate over the slots on `leg` (directed edge index `key`), mAh/min:
    /// the row minima of [`Planner::leg_rates`] without building the matrix (`(p w) f` grows with
    /// `f` in floating point too, so the least slot factor gives the least product).
    pub(super) fn least_rates<'s>(
        &'s self,
        key: usize,
        leg: &crate::network::Leg,
    ) -> impl Iterator<Item = f64> + 's {
        let factors = self.leg_factors(key, leg);
        self.payload_rates().iter().map(move |&p| {
            energy::rate_from_factors(p, factors.wind_factor, factors.min_slot_factor)
        })
    }

    /// Every drone's battery after flying the single edge `leg` from full batteries without
    /// sharing, mAh: `C_d - r_{d, q_d} τ` with `q_d` the drone's own slot and `τ` the leg's
    /// duration. This is the hop evaluation ([`Planner::fly`] with [`SharingPolicy::None`])
    /// for one leg and no transfer, with the same arithmetic and so the same numbers, without
    /// building the hop problem.
    ///
    /// # Errors
    /// Those of [`Planner::hop_problem`] when a rate is not finite.
    pub(crate) fn arrival_without_sharing_mah(
        &self,
        leg: &crate::network::Leg,
    ) -> Result<Vec<f64>> {
        let duration_min = leg.distance_m / self.speed_m_per_min();
        let key = self.edge_key(leg);
        let factors = self.leg_factors(key, leg);
        let mut arrival = self.full_battery_mah();
        // The evaluation skips a leg shorter than its time tolerance.
        if duration_min <= eaas::TIME_TOL_MIN {
            return Ok(arrival);
        }
        for ((b, &p), &q) in arrival
            .iter_mut()
            .zip(self.payload_rates())
            .zip(&self.swarm.initial_slot)
        {
            let rate = energy::rate_from_factors(p, factors.wind_factor, factors.slot_factors[q]);
            if !(rate.is_finite() && rate >= 0.0) {
                // The rate matrix names the culprit.
                self.leg_rates(leg)?;
            }
            *b -= rate * duration_min;
        }
        Ok(arrival)
    }

    /// Every drone's consumption flying the single edge `leg` without sharing, mAh: `r_{d, q_d} τ`
    /// with `q_d` the drone's own slot and `τ` the leg's duration (0 for a leg shorter than the
    /// evaluation's time tolerance), the terms [`Planner::arrival_without_sharing_mah`]
    /// subtracts.
    ///
    /// # Errors
    /// Those of [`Planner::hop_problem`] when a rate is not finite.
    pub(crate) fn leg_use_without_sharing_mah(
        &self,
        leg: &crate::network::Leg,
    ) -> Result<Vec<f64>> {
        let full = self.full_battery_mah();
        let arrival = self.arrival_without_sharing_mah(leg)?;
        Ok(full.iter().zip(&arrival).map(|(c, b)| c - b).collect())
    }

    /// The energy model's factors of `leg` (directed edge index `key`).
    fn leg_factors(&self, key: usize, leg: &crate::network::Leg) -> &super::factors::LegFactors {
        self.factors
            .get_or_init(|| EdgeFactorCache::new(&self.graph).for_slots(&self.swarm.slots_m))
            .leg(&self.profile, key, leg)
    }

    /// Every drone's `base rate x payload factor`, mAh/min.
    fn payload_rates(&self) -> &[f64] {
        self.payload_rates
            .get_or_init(|| energy::payload_rates_mah_per_min(&self.profile, &self.swarm))
    }

    /// Index of the directed edge `leg` flies in the per-edge caches: edge `e` flown from its
    /// file `from` node at `2 e`, the other way at `2 e + 1`.
    pub(super) fn edge_key(&self, leg: &crate::network::Leg) -> usize {
        2 * leg.edge + usize::from(leg.from != self.graph.edge(leg.edge).a)
    }

    /// A hop of a plan this planner's swarm flew, as a sharing problem with its objective: the
    /// node time on the pads at its end when the plan stops there, else (the destination, where
    /// no node time counts whatever its pads) the lowest delivery arrival battery.
    ///
    /// # Errors
    /// [`Error::Backend`] when the hop's path is not a path of the network; those of
    /// [`Planner::hop_problem`].
    pub fn studied_hop(&self, hop: &Hop) -> Result<(HopProblem, Objective)> {
        let nodes: Vec<usize> = hop
            .path
            .iter()
            .filter_map(|id| self.graph.index_of(id))
            .collect();
        let path = self
            .graph
            .path_from_nodes(&nodes)
            .filter(|_| nodes.len() == hop.path.len())
            .ok_or_else(|| {
                Error::internal(
                    "E0019",
                    format!("the plan's hop path {:?} is not a network path", hop.path),
                )
            })?;
        let problem = self.hop_problem(&path, &hop.departure_battery_mah)?;
        let end = nodes.last().copied().unwrap_or(0);
        let objective = match (&hop.stop, self.graph.pads(end)) {
            (Some(_), pads) if pads > 0 => Objective::NodeTime(EndPads {
                pads: pads as usize,
                pad_rate_mah_per_min: self.pad_rate_mah_per_min(end),
            }),
            _ => Objective::MaxMinArrival,
        };
        Ok((problem, objective))
    }

    /// The in-flight sharing problem of flying `path` with batteries `battery_mah` at departure.
    /// The first problem a planner builds is validated in full ([`eaas::validate`]), every rate
    /// matrix when first computed; the planner's own hops are then simulated without
    /// re-validation.
    ///
    /// # Errors
    /// [`Error::Invalid`] when a rate is not finite (E4007) or the first problem breaks a rule of
    /// [`eaas::validate`].
    pub fn hop_problem(&self, path: &Route, battery_mah: &[f64]) -> Result<HopProblem> {
        let speed = self.speed_m_per_min();
        let legs = path
            .legs
            .iter()
            .map(|leg| {
                Ok(eaas::LegRates {
                    duration_min: leg.distance_m / speed,
                    rate_mah_per_min: self.leg_rates(leg)?,
                })
            })
            .collect::<Result<Vec<_>>>()?;
        let drones = self
            .swarm
            .drones
            .iter()
            .zip(battery_mah)
            .map(|(d, &b)| eaas::DroneState {
                role: d.role,
                capacity_mah: d.capacity_mah,
                battery_mah: b,
            })
            .collect();
        let s = &self.profile.sharing;
        let problem = HopProblem {
            legs,
            drones,
            slots_m: self.swarm.slots_m.clone(),
            initial_slot: self.swarm.initial_slot.clone(),
            rho_mah_per_min: s.rate_mah_per_min,
            range_m: s.range_m,
            gamma_mah: s.gamma_mah,
            lambda_mah: s.lambda_mah,
            delta_mah: s.delta_mah,
        };
        if !self.validated.load(Ordering::Acquire) {
            eaas::validate(&problem)?;
            self.validated.store(true, Ordering::Release);
        }
        Ok(problem)
    }

    /// Flies `path` without stopping under `policy`: PB, FB and the baselines are simulated; the
    /// exact and fair policies solve their model, for the least node time at the stop ending the
    /// hop when `goal` is [`HopGoal::NodeTimeMin`] and the node has pads, else for any schedule
    /// that flies.
    /// An exact or fair hop departing with full batteries is solved once per planner: a second
    /// call returns the first flight, with its solve (so a composition that counts the solves of
    /// its flights, `Planner::fly_counted`, counts the same whatever the planner flew before).
    ///
    /// # Errors
    /// Those of [`eaas::simulate_with`] and [`exact_hop::fly_exact`].
    pub fn fly(
        &self,
        path: &Route,
        battery_mah: &[f64],
        policy: SharingPolicy,
        goal: HopGoal,
    ) -> Result<Flight> {
        let full = self
            .swarm
            .drones
            .iter()
            .zip(battery_mah)
            .all(|(d, &b)| b == d.capacity_mah);
        let key = (policy, path.nodes.clone(), goal);
        if policy.is_exact() && full {
            let flights = self.flights.lock().unwrap_or_else(|e| e.into_inner());
            if let Some(flight) = flights.get(&key) {
                return Ok(flight.clone());
            }
        }
        let problem = self.hop_problem(path, battery_mah)?;
        let exact_policy = match policy.on_hop() {
            HopPolicy::Simulated(heuristic) => {
                let options = eaas::PolicyOptions::from(&self.profile.readings);
                return Ok(Flight {
                    outcome: eaas::simulate_valid(&problem, heuristic, &options)?,
                    solve: None,
                });
            }
            HopPolicy::Solved(exact_policy) => exact_policy,
        };
        let last = *path.nodes.last().expect("a path has at least one node");
        let pads = self.graph.pads(last);
        let objective = if goal == HopGoal::NodeTimeMin && pads > 0 {
            Objective::NodeTime(EndPads {
                pads: pads as usize,
                pad_rate_mah_per_min: self.pad_rate_mah_per_min(last),
            })
        } else {
            Objective::Feasible
        };
        let readings = eaas::PolicyOptions::from(&self.profile.readings);
        let (outcome, solve) =
            exact_hop::fly_exact(&problem, exact_policy, &objective, &self.exact, &readings)?;
        let flight = Flight {
            outcome,
            solve: Some(solve),
        };
        if full {
            // A poisoned lock only means another thread panicked while holding it; every entry
            // is inserted whole.
            self.flights
                .lock()
                .unwrap_or_else(|e| e.into_inner())
                .insert(key, flight.clone());
        }
        Ok(flight)
    }

    /// [`Planner::fly`], adding the flight's exact or fair solve (if any) to `solves`: how a
    /// composition counts its hop solves.
    ///
    /// # Errors
    /// Those of [`Planner::fly`].
    pub(crate) fn fly_counted(
        &self,
        path: &Route,
        battery_mah: &[f64],
        policy: SharingPolicy,
        goal: HopGoal,
        solves: &mut HopSolveCounts,
    ) -> Result<Flight> {
        let flight = self.fly(path, battery_mah, policy, goal)?;
        if let Some(solve) = &flight.solve {
            solves.add(solve);
        }
        Ok(flight)
    }

    /// The recharging stop at `node` for a swarm arriving with `arrival_mah`: every drone charges to
    /// full, `ct = (capacity - battery) / pad rate`, and `nt` is the exact optimal makespan on the
    /// node's pads, or, when the planner's node limit stops the search, the incumbent with status
    /// `Feasible`. `None` when the node has no pads.
    pub fn stop_at(&self, node: usize, arrival_mah: &[f64]) -> Result<Option<Stop>> {
        let pads = self.graph.pads(node);
        if pads == 0 {
            return Ok(None);
        }
        let rate = self.pad_rate_mah_per_min(node);
        let charge_times_min: Vec<f64> = self
            .swarm
            .drones
            .iter()
            .zip(arrival_mah)
            .map(|(d, &b)| (d.capacity_mah - b).max(0.0) / rate)
            .collect();
        let limits = Limits {
            time_limit_s: None,
            node_limit: self.node_limit,
        };
        let solution = node_time::exact(pads as usize, &charge_times_min, &limits)?;
        Ok(Some(Stop {
            node: self.graph.id_of(node).to_string(),
            pads,
            charge_times_min,
            nt_min: solution.makespan_min,
            assignment: solution.assignment,
            status: solution.status,
        }))
    }

    /// Assembles a hop from a flown path.
    pub(crate) fn hop(
        &self,
        path: &Route,
        departure_mah: &[f64],
        flight: Flight,
        stop: Option<Stop>,
    ) -> Hop {
        let Flight { outcome, solve } = flight;
        let ids = |i: &usize| self.graph.id_of(*i).to_string();
        Hop {
            from: ids(&path.nodes[0]),
            to: ids(path.nodes.last().expect("a path has at least one node")),
            path: path.nodes.iter().map(ids).collect(),
            distance_m: path.distance_m,
            tt_min: path.distance_m / self.speed_m_per_min(),
            legs: path
                .legs
                .iter()
                .map(|leg| LegFlown {
                    from: ids(&leg.from),
                    to: ids(&leg.to),
                    distance_m: leg.distance_m,
                    tt_min: leg.distance_m / self.speed_m_per_min(),
                    heading_deg: leg.heading_deg,
                    wind_speed_mps: leg.wind_speed_mps,
                    wind_from_deg: leg.wind_from_deg,
                })
                .collect(),
            shared_mah: outcome.shared_mah,
            transfers: outcome.transfers,
            departure_battery_mah: departure_mah.to_vec(),
            arrival_battery_mah: outcome.final_battery_mah,
            sharing_solve: solve,
            stop,
        }
    }

    /// Longest time, min, the swarm could possibly fly without stopping from batteries
    /// `battery_mah`: drone `d` with smallest possible rate `r_d` over the whole network and slots
    /// can stay aloft at most `b_d / (r_d - rho)` (a delivery drone can receive at most `rho` while
    /// some support drone exists). A necessary condition used to skip hopeless candidates.
    pub(crate) fn endurance_bound_min(&self, battery_mah: &[f64], min_rate: &[f64]) -> f64 {
        let has_support = self.swarm.drones.iter().any(|d| d.role == Role::Support);
        let rho = if has_support && self.sharing.shares() {
            self.profile.sharing.rate_mah_per_min
        } else {
            0.0
        };
        let mut bound = f64::INFINITY;
        for (d, (&b, &r)) in self
            .swarm
            .drones
            .iter()
            .zip(battery_mah.iter().zip(min_rate))
        {
            let inflow = if d.role == Role::Delivery { rho } else { 0.0 };
            let net = r - inflow;
            if net > 0.0 {
                bound = bound.min(b / net);
            }
        }
        bound
    }

    /// The most a delivery drone can receive per minute under the planner's policy, mAh/min:
    /// the sharing rate `rho` when the policy shares and the swarm has a support drone, else 0.
    pub(super) fn inflow_rate_mah_per_min(&self) -> f64 {
        let has_support = self.swarm.drones.iter().any(|d| d.role == Role::Support);
        if has_support && self.sharing.shares() {
            self.profile.sharing.rate_mah_per_min
        } else {
            0.0
        }
    }

    /// A lower bound on the cost `tt + nt` of flying `path` from full batteries under any
    /// continuous-time sharing schedule and stopping at `stop` (`None`: into the destination,
    /// cost `tt`), min; `None` when no schedule can fly it.
    ///
    /// Each drone `d` consumes at least `w_d = Σ_l τ_l r_min[l][d]` (its least rate over the
    /// slots on every leg). A support drone receives nothing, so its deficit at the end is at
    /// least `w_s`; a delivery drone receives at most `rho` per minute, so its deficit is at
    /// least `w_d - rho tt`; sharing creates no energy, so the deficits sum to at least `Σ w`.
    /// The hop cannot fly when a deficit bound exceeds the drone's capacity, or the sum the
    /// swarm's (beyond the hop evaluation's `1e-6` mAh and a relative `1e-9`). With `k` pads at
    /// rate `q`, the node time is at least the P||Cmax bound `max(Σ w / (k q), max_d l_d / q,
    /// (l_(k) + l_(k+1)) / q)` on the deficit bounds `l` sorted in decreasing order (two of the
    /// `k + 1` largest share a pad). Lowered by a relative `1e-9` against rounding.
    ///
    /// # Errors
    /// Those of [`Planner::leg_rates`] for a rate that is not finite.
    pub(super) fn hop_bound_min(&self, path: &Route, stop: Option<usize>) -> Result<Option<f64>> {
        const MARGIN: f64 = 1e-9;
        let speed = self.speed_m_per_min();
        let tt_min = path.distance_m / speed;
        let n = self.swarm.drones.len();
        let mut consumed_mah = vec![0.0; n];
        for leg in &path.legs {
            let key = self.edge_key(leg);
            let tau_min = leg.distance_m / speed;
            for (w, r) in consumed_mah.iter_mut().zip(self.least_rates(key, leg)) {
                if !(r.is_finite() && r >= 0.0) {
                    self.leg_rates(leg)?;
                }
                *w += tau_min * r;
            }
        }
        let inflow_mah = self.inflow_rate_mah_per_min() * tt_min;
        let beyond = |deficit: f64, capacity: f64| deficit > capacity * (1.0 + MARGIN) + 1e-6;
        let mut deficits = Vec::with_capacity(n);
        for (d, &w) in self.swarm.drones.iter().zip(&consumed_mah) {
            let deficit = match d.role {
                Role::Support => w,
                Role::Delivery => (w - inflow_mah).max(0.0),
            };
            if beyond(deficit, d.capacity_mah) {
                return Ok(None);
            }
            deficits.push(deficit);
        }
        let total_mah: f64 = consumed_mah.iter().sum();
        let capacity_mah: f64 = self.swarm.drones.iter().map(|d| d.capacity_mah).sum();
        if beyond(total_mah, capacity_mah) {
            return Ok(None);
        }
        let Some(v) = stop else {
            return Ok(Some(tt_min));
        };
        let pads = self.graph.pads(v) as usize;
        let q = self.pad_rate_mah_per_min(v);
        deficits.sort_by(|a, b| b.total_cmp(a));
        let mut nt_min = (total_mah / pads as f64).max(deficits[0]) / q;
        if n > pads {
            nt_min = nt_min.max((deficits[pads - 1] + deficits[pads]) / q);
        }
        Ok(Some((tt_min + nt_min) * (1.0 - MARGIN)))
    }

    /// Smallest consumption rate of every drone over every directed edge and every slot, mAh/min.
    ///
    /// # Errors
    /// Those of [`Planner::hop_problem`].
    pub(crate) fn min_rates_mah_per_min(&self) -> Result<Vec<f64>> {
        let n = self.swarm.drones.len();
        let mut min_rate = vec![f64::INFINITY; n];
        for u in 0..self.graph.node_count() {
            for &(v, _) in self.graph.neighbors(u) {
                let Some(leg) = self.graph.leg(u, v) else {
                    continue;
                };
                let key = self.edge_key(&leg);
                for (d, r) in self.least_rates(key, &leg).enumerate() {
                    if !(r.is_finite() && r >= 0.0) {
                        // The rate matrix names the culprit.
                        self.leg_rates(&leg)?;
                    }
                    min_rate[d] = min_rate[d].min(r);
                }
            }
        }
        Ok(min_rate)
    }
}
