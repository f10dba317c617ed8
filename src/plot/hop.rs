//! The figure of one hop's sharing schedules (`swarmplan plot --hop-file`): every drone's
//! battery against time over the hop, with the in-flight transfers, for each method's schedule,
//! one panel under the other on the same axes. The hop is a hop file's problem
//! ([`crate::eaas::hop_file`]); the schedules are what the methods of `swarmplan eaas` return
//! on it.
//!
//! As in a plan's figure ([`super::data`]), the batteries are the independent checker's
//! re-integration of the transfers as written ([`crate::check::battery_trajectory`]), so a
//! schedule that does not fly shows its drone running dry where the re-integration says.

use super::data::{
    battery_span, BatteryUnit, DroneSeries, FailureMark, Figure, MapData, PlanData, TransferBand,
};
use crate::check::battery_trajectory;
use crate::check::INTEGRATION_TOLERANCE;
use crate::eaas::hop_file::HopFile;
use crate::eaas::Transfer;
use crate::error::{Error, Result};

/// One method's schedule on the hop.
#[derive(Debug, Clone, PartialEq)]
pub struct HopSchedule {
    /// The method's name (`pb`, `continuous`, ...).
    pub method: String,
    /// What the method reports of the schedule, one line (objective, status, gap).
    pub summary: String,
    /// The schedule.
    pub transfers: Vec<Transfer>,
}

/// A hop's figure: the title's lines and one battery panel per schedule.
#[derive(Debug, Clone, PartialEq)]
pub struct HopFigure {
    /// The title: the hop, then one line per schedule.
    pub title: Vec<String>,
    /// The panels (one [`PlanData`] per schedule: no route, no stop) and their shared axes.
    pub figure: Figure,
}

/// The figure of the schedules on the hop of `file`.
///
/// # Errors
/// E8003 when a schedule names a drone or slot the hop lacks.
pub fn hop_figure_data(
    file: &HopFile,
    schedules: &[HopSchedule],
    unit: BatteryUnit,
) -> Result<HopFigure> {
    let problem = &file.hop;
    let tt_min: f64 = problem.legs.iter().map(|l| l.duration_min).sum();
    let plans = schedules
        .iter()
        .map(|s| schedule_panel(file, s, unit, tt_min))
        .collect::<Result<Vec<_>>>()?;
    let battery_range = battery_range(&plans);
    Ok(HopFigure {
        title: title(file, schedules, tt_min),
        figure: Figure {
            map: MapData {
                nodes: Vec::new(),
                edges: Vec::new(),
            },
            plans,
            unit,
            time_range_min: (0.0, tt_min.max(1e-9)),
            battery_range,
            stop_range_min: (0.0, 0.0),
        },
    })
}

/// The panel of one schedule: every drone's battery re-integrated over the hop (`tt_min`
/// long), the transfers, and the first drone to run dry.
fn schedule_panel(
    file: &HopFile,
    s: &HopSchedule,
    unit: BatteryUnit,
    tt_min: f64,
) -> Result<PlanData> {
    let trajectory = battery_trajectory(&file.hop, &s.transfers).ok_or_else(|| {
        Error::invalid(
            "E8003",
            "--hop-file",
            format!(
                "the {} schedule names a drone or slot the hop lacks",
                s.method
            ),
            "give the hop file the schedule was made on",
        )
    })?;
    let (drones, transfers) = schedule_series(file, s, unit, &trajectory);
    let failure = first_dry(&trajectory).map(|(drone, time_min)| FailureMark {
        drone,
        time_min,
        flight: format!("flying {} -> {}", file.from, file.to),
    });
    Ok(PlanData {
        combination: s.method.clone(),
        request_id: file.request_id.clone(),
        source: file.from.clone(),
        destination: file.to.clone(),
        dt_min: tt_min,
        delivered: failure.is_none(),
        outcome_kind: if failure.is_none() {
            "flies"
        } else {
            "runs dry"
        }
        .to_string(),
        outcome: s.summary.clone(),
        route: Vec::new(),
        stop_marks: Vec::new(),
        drones,
        transfers,
        stops: Vec::new(),
        failure,
        failed_at: None,
    })
}

/// Every drone's battery along `trajectory`, the re-integration of schedule `s`, and the
/// schedule's transfers with their battery bands, in `unit`.
fn schedule_series(
    file: &HopFile,
    s: &HopSchedule,
    unit: BatteryUnit,
    trajectory: &[(f64, Vec<f64>)],
) -> (Vec<DroneSeries>, Vec<TransferBand>) {
    let problem = &file.hop;
    let scale = |d: usize, b: f64| {
        let capacity = problem.drones[d].capacity_mah;
        match unit {
            BatteryUnit::Mah => b,
            BatteryUnit::Percent if capacity > 0.0 => 100.0 * b / capacity,
            BatteryUnit::Percent => 0.0,
        }
    };
    let drones = problem
        .drones
        .iter()
        .enumerate()
        .map(|(d, drone)| DroneSeries {
            drone: d,
            role: drone.role,
            capacity: scale(d, drone.capacity_mah),
            points: trajectory
                .iter()
                .map(|(t, b)| (*t, scale(d, b[d])))
                .collect(),
        })
        .collect();
    let transfers = s
        .transfers
        .iter()
        .map(|x| TransferBand {
            hop: file.hop_index,
            support: x.support,
            consumer: x.consumer,
            start_min: x.start_min,
            end_min: x.end_min,
            energy_mah: x.energy_mah,
            battery_span: battery_span(trajectory, x, scale),
        })
        .collect();
    (drones, transfers)
}

/// The battery axis shared by the panels: every point and capacity, 0, and a margin of 4% of
/// the span above (and below, when a battery falls under 0).
fn battery_range(plans: &[PlanData]) -> (f64, f64) {
    let values = || plans.iter().flat_map(|p| p.drones.iter());
    let lowest = values()
        .flat_map(|d| d.points.iter().map(|q| q.1))
        .fold(0.0, f64::min);
    let highest = values()
        .flat_map(|d| d.points.iter().map(|q| q.1).chain([d.capacity]))
        .fold(0.0, f64::max);
    let pad = 0.04 * (highest - lowest).max(1e-9);
    (lowest - if lowest < 0.0 { pad } else { 0.0 }, highest + pad)
}

/// The title: the hop (`tt_min` long), then each schedule's method and summary.
fn title(file: &HopFile, schedules: &[HopSchedule], tt_min: f64) -> Vec<String> {
    let problem = &file.hop;
    let mut title = vec![format!(
        "request {} hop {}: {} -> {} over {} ({} leg(s), {:.2} min, {} drones)",
        file.request_id,
        file.hop_index,
        file.from,
        file.to,
        file.path.join(" "),
        problem.legs.len(),
        tt_min,
        problem.drones.len()
    )];
    title.extend(
        schedules
            .iter()
            .map(|s| format!("{}: {}", s.method, s.summary)),
    );
    title
}

/// The first drone to run dry and when, min from the hop start: where its battery first falls
/// below zero by more than the checker's tolerance (linear between the trajectory's points).
fn first_dry(trajectory: &[(f64, Vec<f64>)]) -> Option<(usize, f64)> {
    let dry = |b: f64| b < -INTEGRATION_TOLERANCE * (1.0 + b.abs());
    for pair in trajectory.windows(2) {
        let ((t0, b0), (t1, b1)) = ((pair[0].0, &pair[0].1), (pair[1].0, &pair[1].1));
        let crossing = b1
            .iter()
            .enumerate()
            .filter(|&(_, &v)| dry(v))
            .map(|(d, &v)| {
                let u = b0[d];
                let at = if u > v {
                    t0 + (t1 - t0) * u.max(0.0) / (u - v)
                } else {
                    t0
                };
                (d, at)
            })
            .min_by(|a, b| a.1.total_cmp(&b.1));
        if crossing.is_some() {
            return crossing;
        }
    }
    None
}
