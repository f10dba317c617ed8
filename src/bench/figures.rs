//! The SVG figures of a bench run, drawn from its summary with plotters.
//!
//! Each figure kind first gathers its data from the [`Summary`] into one of four chart shapes
//! (`Bars`, `Lines`, `GroupedBars`, `StackedBars`); one function per shape then draws it. A figure whose
//! data are absent is not written. Text is laid out by plotters itself (no system font is read)
//! and the SVG holds no date, so the same summary gives the same bytes.

use super::{DistanceBucket, GapHistogram, MethodSummary, Summary};
use crate::compose::{PlanOptions, RouteMethod};
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use crate::solver::ZERO_GAP_TOL;
use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::types::RangedCoordi32;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// The folder of the figures, relative to the output directory.
pub const FIGURES_DIR: &str = "figures";

/// Width of every figure, px.
const WIDTH_PX: u32 = 960;
/// Height of a figure with a numeric y axis, px.
const HEIGHT_PX: u32 = 600;
/// Height of one bar of a horizontal bar chart, px.
const BAR_ROW_PX: u32 = 26;
const FONT: &str = "sans-serif";
const TITLE_PT: u32 = 22;
const LABEL_PT: u32 = 15;
const SMALL_PT: u32 = 13;

/// The outcome of drawing with plotters; its error becomes an [`Error::Io`].
type Drawn<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// One horizontal bar per category, the first at the top, each with its value written beside it.
struct Bars {
    title: String,
    value_axis: String,
    labels: Vec<String>,
    values: Vec<f64>,
    /// The values as written beside the bars.
    value_texts: Vec<String>,
    /// Whether the values are counts (whole ticks on the value axis).
    counts: bool,
}

/// One named series of points.
struct Series {
    label: String,
    points: Vec<(f64, f64)>,
}

/// Line series over a numeric x axis, with a legend.
struct Lines {
    title: String,
    x_axis: String,
    y_axis: String,
    series: Vec<Series>,
}

/// Counts over categorical bins, one bar per series in each bin, with a legend.
struct GroupedBars {
    title: String,
    x_axis: String,
    y_axis: String,
    bins: Vec<String>,
    /// Per series, its label and its count in each bin.
    series: Vec<(String, Vec<usize>)>,
}

/// One horizontal bar per category, the first at the top, made of stacked parts (each `>= 0`,
/// negative parts drawn as 0), with a legend naming the parts.
struct StackedBars {
    title: String,
    value_axis: String,
    labels: Vec<String>,
    parts: Vec<String>,
    /// Per category, its value of each part.
    values: Vec<Vec<f64>>,
}

/// Empirical distribution functions of a gap, in panels side by side sharing their axes, each
/// with its legend below it.
struct GapCdfs {
    title: String,
    x_axis: String,
    y_axis: String,
    panels: Vec<CdfPanel>,
}

/// One panel of [`GapCdfs`].
struct CdfPanel {
    title: String,
    series: Vec<CdfSeries>,
}

/// The gaps of one or more combinations with the same gaps.
struct CdfSeries {
    /// The combinations' names (without the panel's part).
    names: Vec<String>,
    /// The first combination's route, which picks the colour.
    route: RouteMethod,
    /// Drawn dashed (energy-aware positioning) or solid.
    dashed: bool,
    /// The gaps, ascending.
    gaps: Vec<f64>,
}

/// Delivery time or node time, the two quantities drawn against distance.
#[derive(Clone, Copy)]
enum Time {
    Delivery,
    Node,
}

impl Time {
    fn file_prefix(self) -> &'static str {
        match self {
            Time::Delivery => "dt",
            Time::Node => "nt",
        }
    }

    fn name(self) -> &'static str {
        match self {
            Time::Delivery => "delivery time",
            Time::Node => "node time",
        }
    }

    fn of(self, bucket: &DistanceBucket) -> Option<f64> {
        match self {
            Time::Delivery => bucket.mean_dt_min,
            Time::Node => bucket.mean_nt_min,
        }
    }
}

/// Writes the figures of `summary` under `dir/figures/` and returns their paths relative to
/// `dir`, in a fixed order:
///
/// - `delivered.svg`: requests delivered per combination;
/// - `dt-by-distance-{positioning}.svg`, `nt-by-distance-{positioning}.svg`: mean delivery time
///   and mean node time of the delivered (min) against the source–destination distance (km), one
///   line per combination of that positioning (the combinations without sharing in both);
/// - `exec-time.svg`: median execution time per request (ms) per combination;
/// - `route-gap-cdf.svg`: the empirical distribution of the route gap of the combinations that
///   measured it, one panel per sharing policy, one line per combination (combinations with
///   the same gaps drawn once, their names joined by ` = `);
/// - `hop-gap-histogram.svg`: each sharing heuristic's loss per hop against the hop's
///   continuous-time optimum;
/// - `stop-gap-histogram.svg`: LPT's gap against the exact node time per stop;
/// - `gap-split.svg`: unless `--no-joint`, the mean parts of each combination's gap to the joint
///   optimum.
///
/// The names are written with hyphens, as the copies shipped under `instances/`. Only the
/// figures whose data exist are written.
///
/// # Errors
/// [`crate::error::Error::Io`] when a file cannot be written or plotters fails to draw it.
///
/// # Example
/// ```no_run
/// # fn run(summary: &swarmplan::bench::Summary) -> swarmplan::error::Result<()> {
/// let written = swarmplan::bench::figures::write_figures(std::path::Path::new("out"), summary)?;
/// assert!(written.iter().all(|p| p.starts_with("figures/")));
/// # Ok(()) }
/// ```
pub fn write_figures(dir: &Path, summary: &Summary) -> Result<Vec<String>> {
    let mut figures: Vec<(String, Drawn<String>)> = Vec::new();
    if let Some(bars) = delivered(summary) {
        figures.push(("delivered.svg".to_string(), draw_bars(&bars)));
    }
    for time in [Time::Delivery, Time::Node] {
        for positioning in [Positioning::LocationAware, Positioning::EnergyAware] {
            if let Some(lines) = time_by_distance(summary, positioning, time) {
                let name = format!("{}-by-distance-{positioning}.svg", time.file_prefix());
                figures.push((name, draw_lines(&lines)));
            }
        }
    }
    if let Some(bars) = exec_time(summary) {
        figures.push(("exec-time.svg".to_string(), draw_bars(&bars)));
    }
    if let Some(cdfs) = route_gap_cdfs(summary) {
        figures.push(("route-gap-cdf.svg".to_string(), draw_cdfs(&cdfs)));
    }
    let histograms = [
        ("hop-gap-histogram.svg", hop_gaps(summary)),
        ("stop-gap-histogram.svg", stop_gaps(summary)),
    ];
    for (name, histogram) in histograms {
        if let Some(h) = histogram {
            figures.push((name.to_string(), draw_grouped_bars(&h)));
        }
    }
    if let Some(bars) = gap_split(summary) {
        figures.push(("gap-split.svg".to_string(), draw_stacked_bars(&bars)));
    }

    let mut written = Vec::new();
    if !figures.is_empty() {
        let folder = dir.join(FIGURES_DIR);
        std::fs::create_dir_all(&folder).map_err(|source| Error::Io {
            path: folder.display().to_string(),
            source,
        })?;
    }
    for (name, svg) in figures {
        let relative = format!("{FIGURES_DIR}/{name}");
        let path = dir.join(&relative);
        let io_error = |source: std::io::Error| Error::Io {
            path: path.display().to_string(),
            source,
        };
        let svg = svg.map_err(|e| io_error(std::io::Error::other(e.to_string())))?;
        crate::problem::io::write_whole(&path, svg.as_bytes())?;
        written.push(relative);
    }
    Ok(written)
}

/// `sharing/positioning/route`, with the support drones when the combination fixes them.
fn combination(o: &PlanOptions) -> String {
    match o.support {
        Some(k) => format!("{}/{}/{}/{k} support", o.sharing, o.positioning, o.route),
        None => format!("{}/{}/{}", o.sharing, o.positioning, o.route),
    }
}

// ---- The figure kinds: their data, from the summary. ----

fn delivered(summary: &Summary) -> Option<Bars> {
    per_combination(
        &summary.methods,
        format!(
            "Requests delivered (of {} requests)",
            summary.requests_planned
        ),
        format!("requests delivered (of {})", summary.requests_planned),
        true,
        |m| {
            (
                m.delivered as f64,
                format!("{} of {}", m.delivered, m.requests),
            )
        },
    )
}

/// Unless `--no-joint`: the mean parts of every combination's gap to the joint optimum, minutes.
fn gap_split(summary: &Summary) -> Option<StackedBars> {
    let split: Vec<&MethodSummary> = summary
        .methods
        .iter()
        .filter(|m| m.gap_split.as_ref().is_some_and(|g| g.split > 0))
        .collect();
    if split.is_empty() {
        return None;
    }
    Some(StackedBars {
        title: "Mean gap to the joint optimum, split".to_string(),
        value_axis: "mean dt - dt_joint over the requests split (min)".to_string(),
        labels: split.iter().map(|m| combination(&m.options)).collect(),
        parts: ["sharing schedule", "route", "swarm"]
            .map(String::from)
            .to_vec(),
        values: split
            .iter()
            .map(|m| {
                let g = m.gap_split.as_ref().expect("filtered above");
                vec![g.mean_sharing_min, g.mean_route_min, g.mean_swarm_min]
            })
            .collect(),
    })
}

fn exec_time(summary: &Summary) -> Option<Bars> {
    per_combination(
        &summary.methods,
        "Median execution time per request".to_string(),
        "median execution time per request (ms)".to_string(),
        false,
        |m| (m.exec_ms_median, format!("{:.1} ms", m.exec_ms_median)),
    )
}

/// One bar per combination, with its value and the value's text from `value`.
fn per_combination(
    methods: &[MethodSummary],
    title: String,
    value_axis: String,
    counts: bool,
    value: impl Fn(&MethodSummary) -> (f64, String),
) -> Option<Bars> {
    if methods.is_empty() {
        return None;
    }
    let (values, value_texts) = methods.iter().map(value).unzip();
    Some(Bars {
        title,
        value_axis,
        labels: methods.iter().map(|m| combination(&m.options)).collect(),
        values,
        value_texts,
        counts,
    })
}

/// The mean `time` of the delivered by distance bucket (at its midpoint, km), one series per
/// combination of `positioning` or without sharing; `None` when no bucket has a delivered request.
fn time_by_distance(summary: &Summary, positioning: Positioning, time: Time) -> Option<Lines> {
    let series: Vec<Series> = summary
        .methods
        .iter()
        .filter(|m| {
            m.options.positioning == positioning || m.options.sharing == SharingPolicy::None
        })
        .map(|m| Series {
            label: combination(&m.options),
            points: m
                .by_distance
                .iter()
                .filter_map(|b| Some(((b.from_m + b.to_m) / 2.0 / 1000.0, time.of(b)?)))
                .collect(),
        })
        .filter(|s| !s.points.is_empty())
        .collect();
    (!series.is_empty()).then(|| Lines {
        title: format!(
            "Mean {} of the delivered by distance, {positioning}",
            time.name()
        ),
        x_axis: "source–destination distance, bucket midpoint (km)".to_string(),
        y_axis: format!("mean {} (min)", time.name()),
        series,
    })
}

/// The route gaps' empirical distribution functions, one panel per sharing policy in the order
/// of the combinations; `None` when no combination measured a gap.
fn route_gap_cdfs(summary: &Summary) -> Option<GapCdfs> {
    let mut panels: Vec<(SharingPolicy, Vec<CdfSeries>)> = Vec::new();
    for m in &summary.methods {
        let Some(gaps) = m.route_gaps.as_ref().filter(|g| !g.is_empty()) else {
            continue;
        };
        let o = &m.options;
        let at = match panels.iter().position(|p| p.0 == o.sharing) {
            Some(at) => at,
            None => {
                panels.push((o.sharing, Vec::new()));
                panels.len() - 1
            }
        };
        let series = &mut panels[at].1;
        let name = without_sharing(o);
        match series.iter_mut().find(|s| same_gaps(&s.gaps, gaps)) {
            Some(same) => same.names.push(name),
            None => series.push(CdfSeries {
                names: vec![name],
                route: o.route,
                dashed: o.positioning == Positioning::EnergyAware,
                gaps: gaps.clone(),
            }),
        }
    }
    (!panels.is_empty()).then(|| GapCdfs {
        title: "Route gap against the optimal route: share of the requests at or below each gap"
            .to_string(),
        x_axis: "route gap (%), log scale of 1 + gap = dt / dt_opt".to_string(),
        y_axis: "share of the requests both deliver".to_string(),
        panels: panels
            .into_iter()
            .map(|(sharing, series)| CdfPanel {
                title: format!("sharing {sharing}"),
                series,
            })
            .collect(),
    })
}

/// `positioning/route`, with the support drones when the combination fixes them.
fn without_sharing(o: &PlanOptions) -> String {
    match o.support {
        Some(k) => format!("{}/{}/{k} support", o.positioning, o.route),
        None => format!("{}/{}", o.positioning, o.route),
    }
}

/// Whether two ascending gap lists are the same, each gap within [`ZERO_GAP_TOL`] (relative).
fn same_gaps(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(x, y)| (x - y).abs() <= ZERO_GAP_TOL * (1.0 + x.abs()))
}

/// The names of series drawn as one, joined by ` = `, the `/`-separated fields they share at the
/// front written once: `location-aware/dijkstra = floyd-warshall`.
fn merged_name(names: &[String]) -> String {
    let fields: Vec<Vec<&str>> = names.iter().map(|n| n.split('/').collect()).collect();
    let shortest = fields.iter().map(Vec::len).min().unwrap_or(0);
    // Keep at least one field of each name of its own.
    let shared = (0..shortest.saturating_sub(1))
        .take_while(|&i| fields.iter().all(|f| f[i] == fields[0][i]))
        .count();
    let rests: Vec<String> = fields.iter().map(|f| f[shared..].join("/")).collect();
    let prefix = fields
        .first()
        .map(|f| {
            f[..shared]
                .iter()
                .map(|x| format!("{x}/"))
                .collect::<String>()
        })
        .unwrap_or_default();
    format!("{prefix}{}", rests.join(" = "))
}

fn hop_gaps(summary: &Summary) -> Option<GroupedBars> {
    let series = summary
        .hop_gaps
        .iter()
        .map(|h| (h.sharing.to_string(), &h.histogram))
        .collect();
    gap_histogram(
        "Sharing heuristics' loss against the hop's continuous-time optimum, per hop",
        "loss (% of the optimum)",
        "hops",
        series,
    )
}

fn stop_gaps(summary: &Summary) -> Option<GroupedBars> {
    let series = if summary.stop_gaps.stops > 0 {
        vec![("LPT".to_string(), &summary.stop_gaps.histogram)]
    } else {
        Vec::new()
    };
    gap_histogram(
        "LPT's gap against the exact node time, per stop",
        "LPT's gap (% of the exact node time)",
        "stops",
        series,
    )
}

/// Gap histograms sharing the bins of the first; `None` without any.
fn gap_histogram(
    title: &str,
    x_axis: &str,
    y_axis: &str,
    series: Vec<(String, &GapHistogram)>,
) -> Option<GroupedBars> {
    let bins = series.first()?.1.bins.clone();
    Some(GroupedBars {
        title: title.to_string(),
        x_axis: x_axis.to_string(),
        y_axis: y_axis.to_string(),
        bins,
        series: series
            .into_iter()
            .map(|(label, h)| (label, h.counts.clone()))
            .collect(),
    })
}

// ---- The chart shapes: drawing. ----

/// Draws an SVG of `size` px with `paint` on a white background.
fn draw(
    size: (u32, u32),
    paint: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Drawn<()>,
) -> Drawn<String> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE)?;
        paint(&root)?;
        root.present()?;
    }
    Ok(svg)
}

fn font(pt: u32) -> TextStyle<'static> {
    (FONT, pt).into_font().into()
}

fn colour(series: usize) -> PaletteColor<Palette99> {
    Palette99::pick(series)
}

/// The chart area common to every figure: title, margins and label areas.
fn chart_builder<'a, 's>(
    root: &'a DrawingArea<SVGBackend<'s>, Shift>,
    title: &str,
    y_label_px: u32,
) -> ChartBuilder<'a, 'static, SVGBackend<'s>> {
    let mut builder = ChartBuilder::on(root);
    builder
        .caption(title, font(TITLE_PT))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(y_label_px);
    builder
}

/// Width of a category's slot on a categorical axis (plotters' key points need an integer axis
/// to be labelled by a formatter).
const SLOT: i32 = 100;

/// A categorical axis of `n` slots, with a key point at the centre of each.
fn categories(n: usize) -> WithKeyPoints<RangedCoordi32> {
    let n = n as i32;
    (0..n * SLOT).with_key_points((0..n).map(|i| i * SLOT + SLOT / 2).collect())
}

/// The label of the category whose slot holds `at`.
fn category_at(labels: &[String], at: i32) -> String {
    usize::try_from(at.div_euclid(SLOT))
        .ok()
        .and_then(|i| labels.get(i).cloned())
        .unwrap_or_default()
}

/// The top of an axis from 0 holding `max`, with `headroom` above it (1 when `max` is 0).
fn axis_top(max: f64, headroom: f64) -> f64 {
    if max > 0.0 {
        max * headroom
    } else {
        1.0
    }
}

/// How many ticks an axis of counts from 0 to `top` gets so that plotters' steps are whole.
fn whole_ticks(top: f64) -> usize {
    (top.floor() as usize + 1).clamp(2, 10)
}

/// A tick of an axis of counts.
fn whole(tick: &f64) -> String {
    format!("{tick:.0}")
}

/// Horizontal bars: the categories on the y axis, the first at the top.
fn draw_bars(bars: &Bars) -> Drawn<String> {
    let n = bars.labels.len();
    // The first category sits in the top slot.
    let labels: Vec<String> = bars.labels.iter().rev().cloned().collect();
    let longest = labels.iter().map(String::len).max().unwrap_or(0) as u32;
    let height = 160 + BAR_ROW_PX * n as u32;
    let top = axis_top(bars.values.iter().copied().fold(0.0, f64::max), 1.2);
    draw((WIDTH_PX, height), |root| {
        let mut chart = chart_builder(root, &bars.title, 24 + 8 * longest)
            .build_cartesian_2d(0.0..top, categories(n))?;
        let category = |y: &i32| category_at(&labels, *y);
        let mut mesh = chart.configure_mesh();
        mesh.disable_y_mesh()
            .x_desc(bars.value_axis.as_str())
            .label_style(font(SMALL_PT))
            .axis_desc_style(font(LABEL_PT))
            .y_label_formatter(&category);
        if bars.counts {
            mesh.x_labels(whole_ticks(top)).x_label_formatter(&whole);
        }
        mesh.draw()?;
        let slot = |i: usize| (n - 1 - i) as i32 * SLOT;
        chart.draw_series(bars.values.iter().enumerate().map(|(i, &v)| {
            Rectangle::new(
                [(0.0, slot(i) + SLOT / 8), (v, slot(i) + SLOT - SLOT / 8)],
                colour(i).filled(),
            )
        }))?;
        let beside = font(SMALL_PT).pos(Pos::new(HPos::Left, VPos::Center));
        chart.draw_series(bars.values.iter().enumerate().map(|(i, &v)| {
            EmptyElement::at((v, slot(i) + SLOT / 2))
                + Text::new(bars.value_texts[i].clone(), (6, 0), beside.clone())
        }))?;
        Ok(())
    })
}

/// Horizontal stacked bars: the categories on the y axis, the first at the top; a legend in the
/// lower right corner.
fn draw_stacked_bars(bars: &StackedBars) -> Drawn<String> {
    let n = bars.labels.len();
    let labels: Vec<String> = bars.labels.iter().rev().cloned().collect();
    let longest = labels.iter().map(String::len).max().unwrap_or(0) as u32;
    let height = 200 + BAR_ROW_PX * n as u32;
    let totals = bars
        .values
        .iter()
        .map(|v| v.iter().map(|x| x.max(0.0)).sum::<f64>());
    let top = axis_top(totals.fold(0.0, f64::max), 1.1);
    draw((WIDTH_PX, height), |root| {
        let mut chart = chart_builder(root, &bars.title, 24 + 8 * longest)
            .build_cartesian_2d(0.0..top, categories(n))?;
        let category = |y: &i32| category_at(&labels, *y);
        chart
            .configure_mesh()
            .disable_y_mesh()
            .x_desc(bars.value_axis.as_str())
            .label_style(font(SMALL_PT))
            .axis_desc_style(font(LABEL_PT))
            .y_label_formatter(&category)
            .draw()?;
        let slot = |i: usize| (n - 1 - i) as i32 * SLOT;
        for (j, part) in bars.parts.iter().enumerate() {
            let start = |i: usize| bars.values[i][..j].iter().map(|x| x.max(0.0)).sum::<f64>();
            chart
                .draw_series((0..n).map(|i| {
                    let from = start(i);
                    let to = from + bars.values[i][j].max(0.0);
                    Rectangle::new(
                        [(from, slot(i) + SLOT / 8), (to, slot(i) + SLOT - SLOT / 8)],
                        colour(j).filled(),
                    )
                }))?
                .label(part.as_str())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 12, y + 6)], colour(j).filled())
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::LowerRight)
    })
}

/// Lines with a dot at every point, and a legend in the upper left corner.
fn draw_lines(lines: &Lines) -> Drawn<String> {
    let points = || lines.series.iter().flat_map(|s| s.points.iter());
    let x_top = axis_top(points().map(|p| p.0).fold(0.0, f64::max), 1.05);
    let y_top = axis_top(points().map(|p| p.1).fold(0.0, f64::max), 1.1);
    draw((WIDTH_PX, HEIGHT_PX), |root| {
        let mut chart =
            chart_builder(root, &lines.title, 70).build_cartesian_2d(0.0..x_top, 0.0..y_top)?;
        chart
            .configure_mesh()
            .x_desc(lines.x_axis.as_str())
            .y_desc(lines.y_axis.as_str())
            .label_style(font(SMALL_PT))
            .axis_desc_style(font(LABEL_PT))
            .draw()?;
        for (i, s) in lines.series.iter().enumerate() {
            let style = colour(i).stroke_width(2);
            chart
                .draw_series(LineSeries::new(s.points.iter().copied(), style))?
                .label(s.label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 24, y)], style));
            chart.draw_series(
                s.points
                    .iter()
                    .map(|&p| Circle::new(p, 3, colour(i).filled())),
            )?;
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperLeft)
    })
}

/// In each categorical bin, one bar per series side by side; a legend in the upper right corner.
fn draw_grouped_bars(h: &GroupedBars) -> Drawn<String> {
    let n = h.bins.len();
    let max = h
        .series
        .iter()
        .flat_map(|s| s.1.iter())
        .copied()
        .max()
        .unwrap_or(0);
    let y_top = axis_top(max as f64, 1.15);
    // The bars of a bin fill 80% of its slot.
    let width = (SLOT * 4 / 5 / h.series.len() as i32).max(1);
    // Room for the bins' labels.
    let width_px = WIDTH_PX.max(110 * n as u32 + 100);
    draw((width_px, HEIGHT_PX), |root| {
        let mut chart =
            chart_builder(root, &h.title, 70).build_cartesian_2d(categories(n), 0.0..y_top)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_desc(h.x_axis.as_str())
            .y_desc(h.y_axis.as_str())
            .label_style(font(SMALL_PT))
            .axis_desc_style(font(LABEL_PT))
            .x_label_formatter(&|x| category_at(&h.bins, *x))
            .y_labels(whole_ticks(y_top))
            .y_label_formatter(&whole)
            .draw()?;
        for (j, (label, counts)) in h.series.iter().enumerate() {
            let left = |bin: usize| bin as i32 * SLOT + SLOT / 10 + j as i32 * width;
            chart
                .draw_series(
                    counts
                        .iter()
                        .enumerate()
                        .filter(|c| *c.1 > 0)
                        .map(|(bin, &c)| {
                            Rectangle::new(
                                [(left(bin), 0.0), (left(bin) + width, c as f64)],
                                colour(j).filled(),
                            )
                        }),
                )?
                .label(label.as_str())
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 6), (x + 12, y + 6)], colour(j).filled())
                });
        }
        draw_legend(&mut chart, SeriesLabelPosition::UpperRight)
    })
}

/// Colours that stay dark and distinct in print: Okabe and Ito's colour-blind-safe set without
/// its yellow and sky blue, then three dark spares. Each has a relative luminance below 0.3.
pub(crate) const PRINT_COLOURS: [RGBColor; 8] = [
    RGBColor(0x00, 0x00, 0x00), // black
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0xA6, 0x61, 0x1A), // ochre
    RGBColor(0x6A, 0x3D, 0x9A), // violet
    RGBColor(0x59, 0x59, 0x59), // grey
];

/// Width of one panel of the route gap's distribution, px (at least).
const PANEL_PX: u32 = 440;
/// Height of a panel's chart above its legend, px.
const CDF_CHART_PX: u32 = 460;
/// Height of one legend entry, px.
const LEGEND_ROW_PX: u32 = 20;

/// Units of the route gap's x axis per unit of `log10(1 + gap)` (plotters labels key points
/// with a formatter on an integer axis only).
const X_UNITS: f64 = 10_000.0;

/// `x` on the integer x axis.
fn x_at(x: f64) -> i32 {
    (x * X_UNITS).round() as i32
}

/// The x coordinate of `gap` on the log scale of `1 + gap` (= dt / dt_opt); a gap of -100% (a
/// delivery time of 0) is drawn at -99.9%.
fn log_ratio(gap: f64) -> f64 {
    (1.0 + gap).max(1e-3).log10()
}

/// A gap in %, as labelled on the axis.
fn percent_label(percent: f64) -> String {
    format!("{}%", percent + 0.0)
}

/// The gaps (%) labelled on the x axis from `from` to `to` (log scale of `1 + gap`): 0, then
/// outwards the round values at least a tenth of the axis apart.
fn gap_ticks(from: f64, to: f64) -> Vec<f64> {
    const ABOVE: [f64; 17] = [
        10.0, 25.0, 50.0, 100.0, 200.0, 500.0, 1e3, 2e3, 5e3, 1e4, 2e4, 5e4, 1e5, 2e5, 5e5, 1e6,
        1e7,
    ];
    const BELOW: [f64; 5] = [-25.0, -50.0, -75.0, -90.0, -99.0];
    let step = (to - from) / 10.0;
    let x = |percent: f64| log_ratio(percent / 100.0);
    let outwards = |candidates: &[f64], inside: &dyn Fn(f64) -> bool| {
        let mut kept = vec![0.0];
        for &c in candidates {
            if inside(x(c)) && (x(c) - x(kept[kept.len() - 1])).abs() >= step {
                kept.push(c);
            }
        }
        kept.remove(0);
        kept
    };
    let mut ticks: Vec<f64> = outwards(&BELOW, &|v| v >= from);
    ticks.reverse();
    ticks.push(0.0);
    ticks.extend(outwards(&ABOVE, &|v| v <= to));
    ticks
}

/// The empirical distribution function of `gaps` (ascending) as a step polyline on the axis
/// from `from` to `to`: `(x, share of the gaps <= the gap at x)`. Gaps less than `resolution`
/// apart on the axis make one step.
fn cdf_steps(gaps: &[f64], from: f64, to: f64, resolution: f64) -> Vec<(f64, f64)> {
    let n = gaps.len() as f64;
    let mut points = vec![(from, 0.0)];
    let (mut i, mut share) = (0, 0.0);
    while i < gaps.len() {
        let x = log_ratio(gaps[i]);
        let j = i + gaps[i..]
            .iter()
            .take_while(|&&g| log_ratio(g) - x <= resolution)
            .count();
        points.push((x, share));
        share = j as f64 / n;
        points.push((x, share));
        i = j;
    }
    points.push((to, share));
    points
}

/// Each series' colour (index into [`PRINT_COLOURS`]) and whether it is dashed: the colour of
/// its route, or the next one free when an earlier series of the panel has that style.
fn cdf_styles(series: &[CdfSeries]) -> Vec<(usize, bool)> {
    let mut styles: Vec<(usize, bool)> = Vec::new();
    for s in series {
        let first = RouteMethod::ALL
            .iter()
            .position(|&r| r == s.route)
            .unwrap_or(RouteMethod::ALL.len());
        let colour = (0..PRINT_COLOURS.len())
            .map(|k| (first + k) % PRINT_COLOURS.len())
            .find(|&c| !styles.contains(&(c, s.dashed)))
            .unwrap_or(first);
        styles.push((colour, s.dashed));
    }
    styles
}

/// Empirical distribution functions in panels side by side, sharing their axes, each with its
/// legend below its chart.
fn draw_cdfs(c: &GapCdfs) -> Drawn<String> {
    let xs = || {
        c.panels
            .iter()
            .flat_map(|p| p.series.iter().flat_map(|s| s.gaps.iter()))
            .map(|&g| log_ratio(g))
    };
    let (lo, hi) = (xs().fold(0.0, f64::min), xs().fold(2f64.log10(), f64::max));
    let pad = (hi - lo) * 0.04;
    let (from, to) = (lo - pad, hi + pad);
    let ticks: Vec<(i32, String)> = gap_ticks(from, to)
        .into_iter()
        .map(|p| (x_at(log_ratio(p / 100.0)), percent_label(p)))
        .collect();
    let tick_label = |x: &i32| {
        ticks
            .iter()
            .find(|t| t.0 == *x)
            .map(|t| t.1.clone())
            .unwrap_or_default()
    };
    let labels: Vec<Vec<String>> = c
        .panels
        .iter()
        .map(|p| {
            p.series
                .iter()
                .map(|s| format!("{} ({} requests)", merged_name(&s.names), s.gaps.len()))
                .collect()
        })
        .collect();
    let longest = labels.iter().flatten().map(|l| l.chars().count()).max();
    let panel_px = PANEL_PX.max(90 + 7 * longest.unwrap_or(0) as u32);
    let rows = labels.iter().map(Vec::len).max().unwrap_or(0) as u32;
    let size = (
        WIDTH_PX.max(panel_px * c.panels.len() as u32),
        50 + CDF_CHART_PX + 16 + LEGEND_ROW_PX * rows,
    );
    draw(size, |root| {
        let body = root.titled(&c.title, font(TITLE_PT))?;
        let areas = body.split_evenly((1, c.panels.len()));
        for (k, (area, panel)) in areas.iter().zip(&c.panels).enumerate() {
            let (top, legend) = area.split_vertically(CDF_CHART_PX);
            let mut chart = ChartBuilder::on(&top)
                .caption(&panel.title, font(LABEL_PT))
                .margin(12)
                .x_label_area_size(50)
                .y_label_area_size(if k == 0 { 70 } else { 40 })
                .build_cartesian_2d(
                    (x_at(from)..x_at(to)).with_key_points(ticks.iter().map(|t| t.0).collect()),
                    0.0..1.02,
                )?;
            let mut mesh = chart.configure_mesh();
            mesh.x_desc(c.x_axis.as_str())
                .y_max_light_lines(1)
                .label_style(font(SMALL_PT))
                .axis_desc_style(font(LABEL_PT))
                .x_label_formatter(&tick_label)
                .y_label_formatter(&|y| format!("{y:.1}"));
            if k == 0 {
                mesh.y_desc(c.y_axis.as_str());
            }
            mesh.draw()?;
            let resolution = (to - from) / 2000.0;
            let styles = cdf_styles(&panel.series);
            for (s, &(colour, dashed)) in panel.series.iter().zip(&styles) {
                let points = cdf_steps(&s.gaps, from, to, resolution)
                    .into_iter()
                    .map(|(x, y)| (x_at(x), y));
                let stroke = PRINT_COLOURS[colour].stroke_width(2);
                if dashed {
                    chart.draw_series(DashedLineSeries::new(points, 9, 5, stroke))?;
                } else {
                    chart.draw_series(LineSeries::new(points, stroke))?;
                }
            }
            let beside = font(SMALL_PT).pos(Pos::new(HPos::Left, VPos::Center));
            for (i, (label, &(colour, dashed))) in labels[k].iter().zip(&styles).enumerate() {
                let y = 12 + (LEGEND_ROW_PX * i as u32) as i32;
                let sample = vec![(24, y), (60, y)];
                let stroke = PRINT_COLOURS[colour].stroke_width(2);
                if dashed {
                    legend.draw(&DashedPathElement::new(sample, 9, 5, stroke))?;
                } else {
                    legend.draw(&PathElement::new(sample, stroke))?;
                }
                legend.draw(&Text::new(label.as_str(), (68, y), beside.clone()))?;
            }
        }
        Ok(())
    })
}

/// The series' labels, framed, at `position`.
fn draw_legend<'a, 's: 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, SVGBackend<'s>, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Drawn<()> {
    chart
        .configure_series_labels()
        .position(position)
        .label_font(font(SMALL_PT))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cdf_steps_rise_by_each_gaps_share_at_its_gap() {
        // Gaps 0, 0, 2%: 2 of 3 at or below 0, all 3 at or below 2%.
        let x2 = 1.02f64.log10();
        let steps = cdf_steps(&[0.0, 0.0, 0.02], -0.1, 0.5, 0.0);
        let expected = [
            (-0.1, 0.0),
            (0.0, 0.0),
            (0.0, 2.0 / 3.0),
            (x2, 2.0 / 3.0),
            (x2, 1.0),
            (0.5, 1.0),
        ];
        assert_eq!(steps.len(), expected.len(), "{steps:?}");
        for (got, want) in steps.iter().zip(expected) {
            assert!(
                (got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12,
                "{steps:?}"
            );
        }
        // 0.1% is log10(1.001) = 0.000434 from 0 on the axis: one step at resolution 0.01.
        let merged = cdf_steps(&[0.0, 0.001], -0.1, 0.5, 0.01);
        assert_eq!(merged, [(-0.1, 0.0), (0.0, 0.0), (0.0, 1.0), (0.5, 1.0)]);
    }

    #[test]
    fn merged_names_write_their_shared_fields_once() {
        let names = |n: &[&str]| n.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert_eq!(
            merged_name(&names(&[
                "location-aware/dijkstra",
                "location-aware/floyd-warshall"
            ])),
            "location-aware/dijkstra = floyd-warshall"
        );
        assert_eq!(
            merged_name(&names(&["location-aware/astar", "energy-aware/astar"])),
            "location-aware/astar = energy-aware/astar"
        );
        assert_eq!(
            merged_name(&names(&["energy-aware/sequential"])),
            "energy-aware/sequential"
        );
    }

    #[test]
    fn gap_ticks_start_at_zero_and_keep_a_tenth_of_the_axis_apart() {
        // Axis from log10(0.5) (-50%) to log10(11) (1000%): span 1.342, ticks 0.134 apart.
        let ticks: Vec<String> = gap_ticks(0.5f64.log10(), 11f64.log10())
            .into_iter()
            .map(percent_label)
            .collect();
        // From 0 up: 10% (0.041), 25% (0.097) too close; 50% (0.176) kept; 100% (0.301) only
        // 0.125 above it; 200% (0.477), 500% (0.778), 1000% (1.041) kept. Down: -25% (-0.125)
        // too close, -50% (-0.301) kept.
        assert_eq!(ticks, ["-50%", "0%", "50%", "200%", "500%", "1000%"]);
    }
}
