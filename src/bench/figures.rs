//! The SVG figures of a bench run, drawn from its summary with plotters.
//!
//! Each figure kind first gathers its data from the [`Summary`] into one of four chart shapes
//! (`Bars`, `Lines`, `GroupedBars`, `StackedBars`); one function per shape then draws it. A figure whose
//! data are absent is not written. Text is laid out by plotters itself (no system font is read)
//! and the SVG holds no date, so the same summary gives the same bytes.

use super::{DistanceBucket, GapHistogram, MethodSummary, Summary};
use crate::compose::PlanOptions;
use crate::eaas::SharingPolicy;
use crate::error::{Error, Result};
use crate::precompose::Positioning;
use plotters::coord::combinators::WithKeyPoints;
use plotters::coord::types::RangedCoordi32;
use plotters::coord::Shift;
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
/// - `dt_by_distance_{positioning}.svg`, `nt_by_distance_{positioning}.svg`: mean delivery time
///   and mean node time of the delivered (min) against the source–destination distance (km), one
///   line per combination of that positioning (the combinations without sharing in both);
/// - `exec_time.svg`: median execution time per request (ms) per combination;
/// - `route_gap_histogram.svg`: the route gaps of the combinations that measured them;
/// - `hop_gap_histogram.svg`: each sharing heuristic's loss per hop against the hop's
///   continuous-time optimum;
/// - `stop_gap_histogram.svg`: LPT's gap against the exact node time per stop.
///
/// Only the figures whose data exist are written.
///
/// # Errors
/// [`crate::Error::Io`] when a file cannot be written or plotters fails to draw it.
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
                let name = format!("{}_by_distance_{positioning}.svg", time.file_prefix());
                figures.push((name, draw_lines(&lines)));
            }
        }
    }
    if let Some(bars) = exec_time(summary) {
        figures.push(("exec_time.svg".to_string(), draw_bars(&bars)));
    }
    let histograms = [
        ("route_gap_histogram.svg", route_gaps(summary)),
        ("hop_gap_histogram.svg", hop_gaps(summary)),
        ("stop_gap_histogram.svg", stop_gaps(summary)),
    ];
    for (name, histogram) in histograms {
        if let Some(h) = histogram {
            figures.push((name.to_string(), draw_grouped_bars(&h)));
        }
    }
    if let Some(bars) = gap_split(summary) {
        figures.push(("gap_split.svg".to_string(), draw_stacked_bars(&bars)));
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
        std::fs::write(&path, svg).map_err(io_error)?;
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

/// `--joint`: the mean parts of every combination's gap to the joint optimum, minutes.
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

fn route_gaps(summary: &Summary) -> Option<GroupedBars> {
    let series: Vec<(String, &GapHistogram)> = summary
        .methods
        .iter()
        .filter_map(|m| Some((combination(&m.options), m.route_gap_histogram.as_ref()?)))
        .collect();
    gap_histogram(
        "Route gap against the optimal route, per request",
        "route gap (% of the optimal route's delivery time)",
        "requests",
        series,
    )
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
