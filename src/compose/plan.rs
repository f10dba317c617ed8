//! The output of route composition.

use crate::eaas::exact_hop::{HopSolve, HopSolveCounts};
use crate::eaas::Transfer;
use crate::solver::SolveStatus;
use serde::Serialize;

/// A composed delivery plan for one request.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// Source node id.
    pub source: String,
    /// Destination node id.
    pub destination: String,
    /// Whether the swarm reaches the destination.
    pub success: bool,
    /// Why it does not, when it does not.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
    /// Hops flown, each from one stop (or the source) to the next stop (or the destination).
    pub hops: Vec<Hop>,
    /// Total travel time, min: sum of the hops' `tt`.
    pub tt_min: f64,
    /// Total node time, min: sum of the stops' `nt`.
    pub nt_min: f64,
    /// Delivery time `dt = tt + nt`, min (of the part flown, for a failed plan).
    pub dt_min: f64,
    /// Energy shared in flight over the whole plan, mAh.
    pub shared_mah: f64,
    /// Exact and fair policies: how every hop solve made while composing ended, candidate hops
    /// included. `all_proven` in these counts is what makes the route's schedules optimal over
    /// grid schedules.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub hop_solves: Option<HopSolveCounts>,
}

/// One hop: a flight without stopping between two stops, possibly over several edges.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Hop {
    /// Node id the hop starts at.
    pub from: String,
    /// Node id the hop ends at.
    pub to: String,
    /// Node ids flown over, `from` and `to` included.
    pub path: Vec<String>,
    /// Length, m.
    pub distance_m: f64,
    /// Travel time `tt`, min.
    pub tt_min: f64,
    /// The legs flown (one per network edge), in order, each with its own travel time and wind.
    pub legs: Vec<LegFlown>,
    /// In-flight energy transfers during the hop.
    pub transfers: Vec<Transfer>,
    /// Energy shared during the hop, mAh.
    pub shared_mah: f64,
    /// Battery of every drone (by drone id) at the start of the hop, mAh.
    pub departure_battery_mah: Vec<f64>,
    /// Battery of every drone at the end of the hop, mAh.
    pub arrival_battery_mah: Vec<f64>,
    /// Exact and fair policies: how the solve of this hop's schedule ended.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sharing_solve: Option<HopSolve>,
    /// The recharging stop at `to`; `None` at the destination.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stop: Option<Stop>,
}

/// One leg of a hop: a network edge flown in one direction.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LegFlown {
    /// Node id flown from.
    pub from: String,
    /// Node id flown to.
    pub to: String,
    /// Length, m.
    pub distance_m: f64,
    /// Travel time, min.
    pub tt_min: f64,
    /// Direction flown, degrees clockwise from north.
    pub heading_deg: f64,
    /// Wind speed on the edge, m/s.
    pub wind_speed_mps: f64,
    /// Direction the wind blows from, degrees clockwise from north.
    pub wind_from_deg: f64,
}

/// A recharging stop: every drone charges to full on one of the node's pads.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stop {
    /// Node id.
    pub node: String,
    /// Pads at the node.
    pub pads: u32,
    /// Charge time `ct` of every drone (by drone id), min.
    pub charge_times_min: Vec<f64>,
    /// Node time `nt` = makespan of the pad assignment, min.
    pub nt_min: f64,
    /// Drone ids charged on each pad, in order.
    pub assignment: Vec<Vec<usize>>,
    /// Status of the node-time solve.
    pub status: SolveStatus,
}

impl Plan {
    pub(crate) fn new(source: String, destination: String) -> Plan {
        Plan {
            source,
            destination,
            success: false,
            failure: None,
            hops: Vec::new(),
            tt_min: 0.0,
            nt_min: 0.0,
            dt_min: 0.0,
            shared_mah: 0.0,
            hop_solves: None,
        }
    }

    pub(crate) fn push(&mut self, hop: Hop) {
        self.tt_min += hop.tt_min;
        self.shared_mah += hop.shared_mah;
        if let Some(stop) = &hop.stop {
            self.nt_min += stop.nt_min;
        }
        self.dt_min = self.tt_min + self.nt_min;
        self.hops.push(hop);
    }

    pub(crate) fn finish(mut self) -> Plan {
        self.success = true;
        self
    }

    pub(crate) fn fail(mut self, reason: String) -> Plan {
        self.success = false;
        self.failure = Some(reason);
        self
    }

    /// Node ids where the swarm stopped to recharge, in order.
    pub fn stops(&self) -> Vec<&str> {
        self.hops
            .iter()
            .filter_map(|h| h.stop.as_ref().map(|s| s.node.as_str()))
            .collect()
    }
}
