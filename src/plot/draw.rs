//! The SVG of a [`Figure`](crate::plot::data::Figure), drawn with plotters in the style of the bench's figures
//! ([`crate::bench::figures`]: its fonts and print colours). Panels stacked: the title, the
//! route on the network, every drone's battery against time, then each stop's pad schedule;
//! with a plan compared, the battery and pad panels of the two plans side by side on the same
//! axes. Text is laid out by plotters itself (no system font is read), so the same plans give
//! the same bytes.
//!
//! Every element the tests count has a text of its own: a legend entry `drone D (role)` per
//! battery series, a label `dD` per pad bar, `runs dry` at a failure; transfers are the only
//! rectangles filled with [`TRANSFER_COLOUR`](crate::plot::draw::TRANSFER_COLOUR).

use super::data::{check_plans, figure_data, BatteryUnit, Figure, PlanData, StopSchedule};
use super::hop::HopFigure;
use crate::bench::figures::PRINT_COLOURS;
use crate::compose::RequestReport;
use crate::error::{Error, Result};
use crate::problem::{Network, Profile, Role};
use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::types::{RangedCoordf64, RangedCoordi32};
use plotters::coord::Shift;
use plotters::element::{DashedPathElement, IntoDynElement};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// The outcome of drawing with plotters.
pub type Drawn<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// Width of the figure of one plan, px.
const WIDTH_PX: u32 = 1100;
/// Width of the figure of two plans side by side, px.
const COMPARE_WIDTH_PX: u32 = 1700;
/// Height of one line of the title, px.
const TITLE_LINE_PX: u32 = 26;
/// Height of the route map, px.
const MAP_PX: u32 = 540;
/// Height of a battery panel, px.
const BATTERY_PX: u32 = 460;
/// Height of a pad schedule without its rows, px.
const GANTT_BASE_PX: u32 = 110;
/// Height of one pad's row, px.
const PAD_ROW_PX: u32 = 34;
/// Height of the line saying a plan makes no stop, px.
const NO_STOP_PX: u32 = 40;
const FONT: &str = "sans-serif";
const TITLE_PT: u32 = 20;
const LABEL_PT: u32 = 15;
const SMALL_PT: u32 = 13;

/// The fill of a transfer's band (Okabe and Ito's sky blue), drawn translucent.
pub const TRANSFER_COLOUR: RGBColor = RGBColor(0x56, 0xB4, 0xE9);
/// The fill of a stop's interval on the battery panel.
const STOP_SHADE: RGBColor = RGBColor(0xEE, 0xEE, 0xEE);
/// Edges and nodes of the network.
const NETWORK_GREY: RGBColor = RGBColor(0xC8, 0xC8, 0xC8);
/// A failure.
const FAILURE_RED: RGBColor = RGBColor(0xD0, 0x10, 0x10);

/// Width of a pad's slot on the pad axis (plotters labels key points on an integer axis only).
const SLOT: i32 = 100;

fn font(pt: u32) -> TextStyle<'static> {
    (FONT, pt).into_font().into()
}

/// The colour of drone `d`.
fn drone_colour(d: usize) -> RGBColor {
    PRINT_COLOURS[d % PRINT_COLOURS.len()]
}

/// The colour of the `k`-th plan's route: blue, then vermillion.
fn plan_colour(k: usize) -> RGBColor {
    PRINT_COLOURS[1 + k % 2]
}

/// A number as a tick label: at most two decimals, none when whole.
fn tick(x: f64) -> String {
    let r = (x * 100.0).round() / 100.0;
    format!("{}", r + 0.0)
}

/// `1 pad`, `3 pads`.
fn pads_text(pads: u32) -> String {
    if pads == 1 {
        "1 pad".to_string()
    } else {
        format!("{pads} pads")
    }
}

/// `text` cut into lines of at most `width` characters at spaces.
fn wrapped(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if line.chars().count() + 1 + word.chars().count() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// The role's name.
fn role(r: Role) -> &'static str {
    match r {
        Role::Delivery => "delivery",
        Role::Support => "support",
    }
}

/// Which plan is which in the title: the plan, and the reference it is compared with.
fn plan_name(k: usize) -> &'static str {
    if k == 0 {
        "plan"
    } else {
        "reference"
    }
}

/// The title's lines.
fn title_lines(fig: &Figure) -> Vec<String> {
    let mut lines = Vec::new();
    if let Some(p) = fig.plans.first() {
        lines.push(format!(
            "request {}: {} -> {}",
            p.request_id, p.source, p.destination
        ));
    }
    for (k, p) in fig.plans.iter().enumerate() {
        let what = if fig.plans.len() > 1 {
            format!("{} ({}): ", plan_name(k), route_style(k))
        } else {
            String::new()
        };
        let dt = if p.delivered {
            format!("dt {:.2} min", p.dt_min)
        } else {
            format!("dt {:.2} min flown", p.dt_min)
        };
        lines.push(format!(
            "{what}{} | {dt} | {}",
            p.combination, p.outcome_kind
        ));
        if !p.delivered {
            let width = if fig.plans.len() > 1 { 190 } else { 120 };
            lines.extend(
                wrapped(&p.outcome, width)
                    .into_iter()
                    .map(|l| format!("    {l}")),
            );
        }
    }
    if fig.plans.len() > 1 {
        lines.push(match fig.gap() {
            Some(g) => format!(
                "gap of the plan against the reference (dt_plan - dt_ref) / dt_ref = {:+.2}%",
                100.0 * g
            ),
            None => "gap: none, a plan is not delivered".to_string(),
        });
    }
    lines
}

/// How the `k`-th plan's route is drawn.
fn route_style(k: usize) -> &'static str {
    if k == 0 {
        "solid route"
    } else {
        "dashed route"
    }
}

/// Height of a plan's pad schedules, px.
fn stops_px(p: &PlanData) -> u32 {
    if p.stops.is_empty() {
        return NO_STOP_PX;
    }
    p.stops
        .iter()
        .map(|s| GANTT_BASE_PX + PAD_ROW_PX * s.pads.max(1))
        .sum()
}

/// The SVG of one plan, or of two plans of the same request side by side, as `swarmplan plot`
/// writes it and the Python package's `swarmplan.plot` returns it: the plans checked
/// ([`check_plans`]), their figure computed ([`figure_data`]) and drawn ([`svg`]).
///
/// # Arguments
/// * `network`, `profile` - the instance the plans were made on.
/// * `reports` - the plan, then the plan compared with it, if any.
/// * `unit` - the battery axis' unit.
///
/// # Errors
/// Those of [`check_plans`] (E6004, E6005, E8001) and of [`figure_data`] (E8003);
/// [`Error::Internal`] E8005 when plotters cannot draw the figure (a bug).
///
/// # Example
/// ```no_run
/// # fn main() -> swarmplan::error::Result<()> {
/// use swarmplan::plot::data::BatteryUnit;
/// use swarmplan::problem::shipped;
/// let (network, profile) = (shipped::network("paper-195")?, shipped::profile("paper")?);
/// let plan = swarmplan::check::plan_file::read_plan_file(std::path::Path::new("plan.json"))?;
/// let svg = swarmplan::plot::draw::plans_svg(&network, &profile, &[&plan], BatteryUnit::Mah)?;
/// assert!(svg.starts_with("<svg"));
/// # Ok(())
/// # }
/// ```
pub fn plans_svg(
    network: &Network,
    profile: &Profile,
    reports: &[&RequestReport],
    unit: BatteryUnit,
) -> Result<String> {
    check_plans(network, profile, reports)?;
    let figure = figure_data(network, profile, reports, unit)?;
    svg(&figure).map_err(|e| Error::internal("E8005", format!("drawing the figure: {e}")))
}

/// The figure as SVG text.
///
/// # Errors
/// What plotters reports when it cannot draw.
pub fn svg(fig: &Figure) -> Drawn<String> {
    let columns = fig.plans.len().max(1);
    let width = if columns > 1 {
        COMPARE_WIDTH_PX
    } else {
        WIDTH_PX
    };
    let lines = title_lines(fig);
    let title_px = 20 + TITLE_LINE_PX * lines.len() as u32;
    let stops = fig.plans.iter().map(stops_px).max().unwrap_or(NO_STOP_PX);
    let height = title_px + MAP_PX + BATTERY_PX + stops;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let (title, rest) = root.split_vertically(title_px);
        draw_title(&title, &lines)?;
        let (map, rest) = rest.split_vertically(MAP_PX);
        draw_map(&map, fig)?;
        let (battery, schedules) = rest.split_vertically(BATTERY_PX);
        let battery = battery.split_evenly((1, columns));
        let schedules = schedules.split_evenly((1, columns));
        for (k, p) in fig.plans.iter().enumerate() {
            let name = if columns > 1 {
                format!("{}: {}", plan_name(k), p.combination)
            } else {
                p.combination.clone()
            };
            draw_battery(&battery[k], fig, p, &name)?;
            draw_stops(&schedules[k], fig, p)?;
        }
        root.present()?;
    }
    Ok(text)
}

/// The SVG of a hop's figure: its title, then one battery panel per schedule, one under the
/// other on the same axes.
///
/// # Errors
/// What plotters reports when it cannot draw.
pub fn hop_svg(h: &HopFigure) -> Drawn<String> {
    let title_px = 20 + TITLE_LINE_PX * h.title.len() as u32;
    let panels = h.figure.plans.len().max(1) as u32;
    let height = title_px + BATTERY_PX * panels;
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, (WIDTH_PX, height)).into_drawing_area();
        root.fill(&WHITE)?;
        let (title, rest) = root.split_vertically(title_px);
        draw_title(&title, &h.title)?;
        let rows = rest.split_evenly((panels as usize, 1));
        for (p, area) in h.figure.plans.iter().zip(&rows) {
            draw_battery(area, &h.figure, p, &p.combination)?;
        }
        root.present()?;
    }
    Ok(text)
}

fn draw_title(area: &DrawingArea<SVGBackend<'_>, Shift>, lines: &[String]) -> Drawn<()> {
    for (i, line) in lines.iter().enumerate() {
        let pt = if i == 0 { TITLE_PT } else { LABEL_PT };
        area.draw(&Text::new(
            line.as_str(),
            (16, 12 + (TITLE_LINE_PX * i as u32) as i32),
            font(pt),
        ))?;
    }
    Ok(())
}

/// The map's chart: metres on both axes.
type MapChart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Margin around the map, px.
const MAP_MARGIN: u32 = 14;
/// Width of the map's y labels, px.
const MAP_Y_LABEL: u32 = 60;

/// The network to scale (the same metres per pixel on both axes), every route over it.
fn draw_map(area: &DrawingArea<SVGBackend<'_>, Shift>, fig: &Figure) -> Drawn<()> {
    const X_LABEL: u32 = 40;
    const CAPTION: u32 = 30;
    let (w, h) = area.dim_in_pixel();
    let plot_w = f64::from(w.saturating_sub(2 * MAP_MARGIN + MAP_Y_LABEL).max(1));
    let plot_h = f64::from(h.saturating_sub(2 * MAP_MARGIN + X_LABEL + CAPTION).max(1));
    let (x0, x1, y0, y1) = map_extent(fig);
    // Metres per pixel: the larger of the two axes' needs, with a margin of a twentieth.
    let scale = ((x1 - x0) / plot_w).max((y1 - y0) / plot_h).max(1e-9) * 1.1;
    let (cx, cy) = ((x0 + x1) / 2.0, (y0 + y1) / 2.0);
    let (hx, hy) = (scale * plot_w / 2.0, scale * plot_h / 2.0);
    let mut chart = ChartBuilder::on(area)
        .caption(
            "route on the network (to scale; grey: edges and nodes)",
            font(LABEL_PT),
        )
        .margin(MAP_MARGIN)
        .x_label_area_size(X_LABEL)
        .y_label_area_size(MAP_Y_LABEL)
        .build_cartesian_2d(cx - hx..cx + hx, cy - hy..cy + hy)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("easting (km)")
        .y_desc("northing (km)")
        .label_style(font(SMALL_PT))
        .axis_desc_style(font(SMALL_PT))
        .x_label_formatter(&|x| tick(x / 1000.0))
        .y_label_formatter(&|y| tick(y / 1000.0))
        .draw()?;
    chart.draw_series(
        fig.map
            .edges
            .iter()
            .map(|&(a, b)| PathElement::new(vec![a, b], NETWORK_GREY.stroke_width(1))),
    )?;
    chart.draw_series(
        fig.map
            .nodes
            .iter()
            .map(|n| Circle::new((n.1, n.2), 2, NETWORK_GREY.filled())),
    )?;
    for (k, p) in fig.plans.iter().enumerate() {
        draw_route(&mut chart, k, p, scale)?;
    }
    if let Some(p) = fig.plans.first() {
        draw_ends(&mut chart, fig, p, scale)?;
    }
    if fig.plans.len() > 1 {
        draw_route_legend(area, fig)?;
    }
    Ok(())
}

/// The smallest and largest easting and northing of the network's nodes, m: `(x0, x1, y0, y1)`;
/// `(0, 1, 0, 1)` for a network without nodes.
fn map_extent(fig: &Figure) -> (f64, f64, f64, f64) {
    let xs = || fig.map.nodes.iter().map(|n| n.1);
    let ys = || fig.map.nodes.iter().map(|n| n.2);
    let (x0, x1) = (
        xs().fold(f64::INFINITY, f64::min),
        xs().fold(f64::NEG_INFINITY, f64::max),
    );
    let (y0, y1) = (
        ys().fold(f64::INFINITY, f64::min),
        ys().fold(f64::NEG_INFINITY, f64::max),
    );
    if x0.is_finite() && y0.is_finite() {
        (x0, x1, y0, y1)
    } else {
        (0.0, 1.0, 0.0, 1.0)
    }
}

/// Plan `k`'s route on the map (solid for the plan, dashed for the one compared), its stops
/// with their pads, and where it fails; `scale` in metres per pixel.
fn draw_route(chart: &mut MapChart<'_, '_>, k: usize, p: &PlanData, scale: f64) -> Drawn<()> {
    let style = plan_colour(k).stroke_width(3);
    for path in &p.route {
        if k == 0 {
            chart.draw_series(std::iter::once(PathElement::new(path.clone(), style)))?;
        } else {
            chart.draw_series(std::iter::once(DashedPathElement::new(
                path.clone(),
                10,
                6,
                style,
            )))?;
        }
    }
    for (node, x, y, pads) in &p.stop_marks {
        chart.draw_series(std::iter::once(Circle::new(
            (*x, *y),
            6,
            plan_colour(k).filled(),
        )))?;
        let beside = font(SMALL_PT).pos(Pos::new(HPos::Left, VPos::Bottom));
        let dy = if k == 0 { 0.0 } else { -16.0 * scale };
        chart.draw_series(std::iter::once(Text::new(
            format!("{node}: {}", pads_text(*pads)),
            (*x + 8.0 * scale, *y + 6.0 * scale + dy),
            beside,
        )))?;
    }
    if let Some((node, x, y)) = &p.failed_at {
        chart.draw_series(std::iter::once(Cross::new(
            (*x, *y),
            9,
            FAILURE_RED.stroke_width(3),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("{} fails at {node}", plan_name(k)),
            (*x + 10.0 * scale, *y - 10.0 * scale),
            font(SMALL_PT)
                .color(&FAILURE_RED)
                .pos(Pos::new(HPos::Left, VPos::Top)),
        )))?;
    }
    Ok(())
}

/// The request's source and destination, marked and named; `scale` in metres per pixel.
fn draw_ends(chart: &mut MapChart<'_, '_>, fig: &Figure, p: &PlanData, scale: f64) -> Drawn<()> {
    let at = |id: &str| fig.map.nodes.iter().find(|n| n.0 == id);
    for (label, id, below) in [
        ("source", &p.source, true),
        ("destination", &p.destination, false),
    ] {
        if let Some(n) = at(id) {
            chart.draw_series(std::iter::once(Circle::new((n.1, n.2), 5, BLACK.filled())))?;
            let (dy, v) = if below {
                (-8.0 * scale, VPos::Top)
            } else {
                (8.0 * scale, VPos::Bottom)
            };
            chart.draw_series(std::iter::once(Text::new(
                format!("{label} {id}"),
                (n.1 - 8.0 * scale, n.2 + dy),
                font(LABEL_PT).pos(Pos::new(HPos::Right, v)),
            )))?;
        }
    }
    Ok(())
}

/// The routes' legend, upper left of the plotting area: a line sample and the combination of
/// each plan.
fn draw_route_legend(area: &DrawingArea<SVGBackend<'_>, Shift>, fig: &Figure) -> Drawn<()> {
    for (k, p) in fig.plans.iter().enumerate() {
        let y = (24 + 20 * k) as i32;
        let x = (MAP_MARGIN + MAP_Y_LABEL + 10) as i32;
        let sample = vec![(x, y + 38), (x + 36, y + 38)];
        let style = plan_colour(k).stroke_width(3);
        if k == 0 {
            area.draw(&PathElement::new(sample, style))?;
        } else {
            area.draw(&DashedPathElement::new(sample, 10, 6, style))?;
        }
        area.draw(&Text::new(
            format!("{}: {}", plan_name(k), p.combination),
            (x + 44, y + 38),
            font(SMALL_PT).pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    Ok(())
}

/// Every drone's battery against time; stops shaded grey, transfers blue.
fn draw_battery(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    fig: &Figure,
    p: &PlanData,
    name: &str,
) -> Drawn<()> {
    let (t0, t1) = fig.time_range_min;
    let (lo, hi) = fig.battery_range;
    let unit = match fig.unit {
        BatteryUnit::Mah => "mAh",
        BatteryUnit::Percent => "% of capacity",
    };
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!("battery against time, {name} (grey: stops, blue: transfers)"),
            font(LABEL_PT),
        )
        .margin(14)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(t0..t1, lo..hi)?;
    chart
        .configure_mesh()
        .x_desc("minutes since departure")
        .y_desc(format!("battery ({unit})"))
        .label_style(font(SMALL_PT))
        .axis_desc_style(font(LABEL_PT))
        .x_label_formatter(&|x| tick(*x))
        .y_label_formatter(&|y| tick(*y))
        .light_line_style(WHITE.mix(0.0))
        .draw()?;
    for s in &p.stops {
        chart.draw_series(std::iter::once(Rectangle::new(
            [(s.arrival_min, lo), (s.arrival_min + s.nt_min, hi)],
            STOP_SHADE.filled(),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("stop {}", s.node),
            (s.arrival_min, hi),
            font(SMALL_PT).pos(Pos::new(HPos::Left, VPos::Top)),
        )))?;
    }
    chart.draw_series(p.transfers.iter().map(|x| {
        Rectangle::new(
            [
                (x.start_min, x.battery_span.0),
                (x.end_min, x.battery_span.1),
            ],
            TRANSFER_COLOUR.mix(0.35).filled(),
        )
    }))?;
    chart.draw_series(std::iter::once(PathElement::new(
        vec![(t0, 0.0), (t1, 0.0)],
        BLACK.stroke_width(1),
    )))?;
    let mut capacities: Vec<f64> = p.drones.iter().map(|d| d.capacity).collect();
    capacities.sort_by(f64::total_cmp);
    capacities.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * (1.0 + a.abs()));
    for c in capacities {
        chart.draw_series(std::iter::once(DashedPathElement::new(
            vec![(t0, c), (t1, c)],
            6,
            4,
            PRINT_COLOURS[7].stroke_width(1),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("capacity {}", tick(c)),
            (t1, c),
            font(SMALL_PT).pos(Pos::new(HPos::Right, VPos::Bottom)),
        )))?;
    }
    for d in &p.drones {
        let style = drone_colour(d.drone).stroke_width(2);
        let points = d.points.iter().copied();
        let series = if d.role == Role::Support {
            chart.draw_series(DashedLineSeries::new(points, 8, 5, style))?
        } else {
            chart.draw_series(LineSeries::new(points, style))?
        };
        let dashed = d.role == Role::Support;
        series
            .label(format!("drone {} ({})", d.drone, role(d.role)))
            .legend(move |(x, y)| {
                let sample = vec![(x, y), (x + 24, y)];
                if dashed {
                    DashedPathElement::new(sample, 6, 3, style).into_dyn()
                } else {
                    PathElement::new(sample, style).into_dyn()
                }
            });
    }
    if let Some(f) = &p.failure {
        chart.draw_series(std::iter::once(Cross::new(
            (f.time_min, 0.0),
            10,
            FAILURE_RED.stroke_width(3),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!(
                "drone {} runs dry at {} min, {}",
                f.drone,
                tick(f.time_min),
                f.flight
            ),
            (f.time_min - 0.015 * (t1 - t0), 0.0),
            font(SMALL_PT)
                .color(&FAILURE_RED)
                .pos(Pos::new(HPos::Right, VPos::Bottom)),
        )))?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font(font(SMALL_PT))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

/// Each stop's pad schedule, one under the other.
fn draw_stops(area: &DrawingArea<SVGBackend<'_>, Shift>, fig: &Figure, p: &PlanData) -> Drawn<()> {
    if p.stops.is_empty() {
        area.draw(&Text::new("no recharging stop", (20, 12), font(LABEL_PT)))?;
        return Ok(());
    }
    let mut rest = area.clone();
    for (k, s) in p.stops.iter().enumerate() {
        let (this, below) = rest.split_vertically(GANTT_BASE_PX + PAD_ROW_PX * s.pads.max(1));
        draw_stop(&this, fig, k, s)?;
        rest = below;
    }
    Ok(())
}

/// The optimum's note beside the node time.
fn optimum_note(s: &StopSchedule) -> String {
    use crate::solver::SolveStatus;
    match (s.status, s.optimum_min) {
        (SolveStatus::Optimal, _) => "optimal".to_string(),
        (status, Some(best)) => format!(
            "{}, optimum {} min",
            crate::problem::io::json_name(&status),
            tick(best)
        ),
        (status, None) => format!(
            "{}, optimum not known",
            crate::problem::io::json_name(&status)
        ),
    }
}

/// One stop: a row per pad, a bar per drone from the start to the end of its charge.
fn draw_stop(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    fig: &Figure,
    k: usize,
    s: &StopSchedule,
) -> Drawn<()> {
    let pads = s.pads.max(1) as i32;
    let axis: WithKeyPoints<RangedCoordi32> =
        (0..pads * SLOT).with_key_points((0..pads).map(|i| i * SLOT + SLOT / 2).collect());
    let (t0, t1) = fig.stop_range_min;
    let mut chart = ChartBuilder::on(area)
        .caption(
            format!(
                "stop {} at {} ({}), arrives at {} min: nt {} min ({})",
                k + 1,
                s.node,
                pads_text(s.pads),
                tick(s.arrival_min),
                tick(s.nt_min),
                optimum_note(s)
            ),
            font(LABEL_PT),
        )
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(t0..t1, axis)?;
    // Pad 1 on top.
    let row = |pad: usize| (pads - 1 - pad as i32) * SLOT;
    chart
        .configure_mesh()
        .disable_y_mesh()
        .light_line_style(WHITE.mix(0.0))
        .x_desc("minutes since arrival at the stop")
        .label_style(font(SMALL_PT))
        .axis_desc_style(font(SMALL_PT))
        .x_label_formatter(&|x| tick(*x))
        .y_label_formatter(&|y| format!("pad {}", pads - y.div_euclid(SLOT)))
        .draw()?;
    for b in &s.bars {
        let (top, bottom) = (row(b.pad) + SLOT / 8, row(b.pad) + SLOT - SLOT / 8);
        chart.draw_series(std::iter::once(Rectangle::new(
            [(b.start_min, top), (b.end_min, bottom)],
            drone_colour(b.drone).mix(0.35).filled(),
        )))?;
        chart.draw_series(std::iter::once(Rectangle::new(
            [(b.start_min, top), (b.end_min, bottom)],
            drone_colour(b.drone).stroke_width(1),
        )))?;
        chart.draw_series(std::iter::once(Text::new(
            format!("d{}", b.drone),
            ((b.start_min + b.end_min) / 2.0, row(b.pad) + SLOT / 2),
            font(SMALL_PT).pos(Pos::new(HPos::Center, VPos::Center)),
        )))?;
    }
    chart.draw_series(std::iter::once(DashedPathElement::new(
        vec![(s.nt_min, 0), (s.nt_min, pads * SLOT)],
        6,
        4,
        BLACK.stroke_width(2),
    )))?;
    Ok(())
}
