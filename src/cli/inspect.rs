//! `swarmplan inspect`: describe a network and, for a request, the swarm it would fly.

use super::inputs::InstanceArgs;
use crate::compose::Context;
use crate::energy;
use crate::error::Result;
use crate::precompose::{Positioning, SupportDecision};
use crate::problem::io::json_name;
use crate::problem::FormationKind;
use crate::problem::Swarm;
use crate::problem::Wind;
use serde::Serialize;
use std::path::PathBuf;

/// Describe a network, and the swarm a request would fly.
#[derive(Debug, clap::Args)]
pub struct InspectArgs {
    /// Network and profile.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// Request set (JSON) [default: the shipped paper-195 requests].
    #[arg(long, alias = "request-file", value_name = "FILE")]
    pub requests: Option<PathBuf>,
    /// Id of a request to describe the swarm of.
    #[arg(long, value_name = "ID")]
    pub request_id: Option<String>,
    /// Initial positioning of the support drones.
    #[arg(long, value_enum, default_value = "location-aware")]
    pub positioning: Positioning,
    /// Number of support drones, overriding the redundancy table.
    #[arg(long, value_name = "N")]
    pub support: Option<usize>,
    /// Print as JSON.
    #[arg(long)]
    pub json: bool,
}

/// Network facts.
#[derive(Debug, Serialize)]
pub struct NetworkReport {
    /// Nodes.
    pub nodes: usize,
    /// Edges.
    pub edges: usize,
    /// Nodes with at least one pad.
    pub pad_nodes: usize,
    /// Pads in all.
    pub pads: u64,
    /// Total edge length, m.
    pub total_length_m: f64,
    /// Mean wind speed over edges, m/s.
    pub mean_wind_speed_mps: f64,
    /// Highest wind speed, m/s.
    pub max_wind_speed_mps: f64,
    /// The averaged wind the formation is selected on.
    pub average_wind: Wind,
    /// The fixed formation.
    pub formation: FormationKind,
}

/// A request's swarm.
#[derive(Debug, Serialize)]
pub struct SwarmReport {
    /// Request id: `id`, as in request files and in `solve`'s `request` object.
    pub id: String,
    /// Shortest-path distance source to destination, m.
    pub route_distance_m: f64,
    /// Support decision of the redundancy table.
    pub support_decision: SupportDecision,
    /// Support drones used.
    pub support_drones: usize,
    /// The swarm with its positions.
    pub swarm: Swarm,
    /// Each drone's consumption rate in its initial slot, in still air, mAh/min.
    pub still_air_rates_mah_per_min: Vec<f64>,
    /// Each drone's rate flying into the averaged wind (head wind), mAh/min.
    pub head_wind_rates_mah_per_min: Vec<f64>,
}

/// The whole report.
#[derive(Debug, Serialize)]
pub struct InspectReport {
    /// Network facts.
    pub network: NetworkReport,
    /// The request's swarm, if a request was named.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub request: Option<SwarmReport>,
}

/// Runs the subcommand.
pub fn run(args: InspectArgs) -> Result<i32> {
    let inst = match &args.request_id {
        None => args.instance.load()?,
        Some(id) => {
            let (instance, set) = args.instance.load_with_requests(args.requests.as_deref())?;
            instance.with_request_from(&set, id)?
        }
    };
    let net = &inst.network;
    let context = Context::new(net, &inst.graph, &inst.profile);
    let (formation, average_wind) = (context.formation, context.average_wind);
    let speeds: Vec<f64> = net.edges.iter().map(|s| s.wind_speed_mps).collect();
    let network = NetworkReport {
        nodes: net.nodes.len(),
        edges: net.edges.len(),
        pad_nodes: net.nodes.iter().filter(|n| n.pads > 0).count(),
        pads: net.nodes.iter().map(|n| n.pads as u64).sum(),
        total_length_m: inst.graph.edges().iter().map(|s| s.distance_m).sum(),
        mean_wind_speed_mps: speeds.iter().sum::<f64>() / speeds.len().max(1) as f64,
        max_wind_speed_mps: speeds.iter().cloned().fold(0.0, f64::max),
        average_wind,
        formation,
    };
    let request = match &args.request_id {
        None => None,
        Some(_) => {
            let r = inst.requests[0].clone();
            let choice = context.swarm_for(&r, args.positioning, args.support)?;
            let (route_distance_m, support_decision, support_drones, swarm) = (
                choice.route_distance_m,
                choice.support_decision,
                choice.support_drones,
                choice.swarm,
            );
            let still = Wind {
                speed_mps: 0.0,
                from_deg: 0.0,
            };
            let heading = average_wind.from_deg;
            Some(SwarmReport {
                id: r.id.clone(),
                route_distance_m,
                support_decision,
                support_drones,
                still_air_rates_mah_per_min: energy::consumption_rates_mah_per_min(
                    &inst.profile,
                    &swarm,
                    heading,
                    &still,
                ),
                head_wind_rates_mah_per_min: energy::consumption_rates_mah_per_min(
                    &inst.profile,
                    &swarm,
                    heading,
                    &average_wind,
                ),
                swarm,
            })
        }
    };
    let report = InspectReport { network, request };
    if args.json {
        super::print_json(&report)?;
    } else {
        print_human(&report)?;
    }
    Ok(0)
}

fn print_human(report: &InspectReport) -> Result<()> {
    let n = &report.network;
    outln!(
        "network: {} nodes, {} edges ({:.1} km), {} pads on {} nodes",
        n.nodes,
        n.edges,
        n.total_length_m / 1000.0,
        n.pads,
        n.pad_nodes
    );
    outln!(
        "wind: mean {:.2} m/s, max {:.2} m/s; averaged wind {:.2} m/s from {:.0} deg; formation {}",
        n.mean_wind_speed_mps,
        n.max_wind_speed_mps,
        n.average_wind.speed_mps,
        n.average_wind.from_deg,
        json_name(&n.formation)
    );
    if let Some(r) = &report.request {
        outln!(
            "request {}: route {:.0} m, {} support drone(s) (table: {})",
            r.id,
            r.route_distance_m,
            r.support_drones,
            r.support_decision.count
        );
        outln!("  drone role      payload_kg capacity_mah slot  x_m    y_m   still mAh/min  head-wind mAh/min");
        for d in &r.swarm.drones {
            let slot = r.swarm.initial_slot[d.id];
            let p = r.swarm.slots_m[slot];
            outln!(
                "  {:>5} {:<9} {:>10.3} {:>12.0} {:>4} {:>6.2} {:>6.2} {:>13.2} {:>18.2}",
                d.id,
                json_name(&d.role),
                d.payload_kg,
                d.capacity_mah,
                slot,
                p.x,
                p.y,
                r.still_air_rates_mah_per_min[d.id],
                r.head_wind_rates_mah_per_min[d.id]
            );
        }
    }
    Ok(())
}
