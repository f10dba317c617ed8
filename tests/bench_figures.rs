//! The SVG figures of `bench`, drawn from hand-built summaries: which files are written, that each
//! is a whole SVG with its title and axis text, and one series per combination (or heuristic).
//! Every expected number below is read off the summaries built here, not from a run.

use std::path::{Path, PathBuf};
use swarmplan::bench::figures::write_figures;
use swarmplan::bench::{BenchConfig, BenchData, DistanceBucket, GapHistogram, Shard, Summary};
use swarmplan::bench::{HopGapSummary, SUMMARY_SCHEMA_VERSION};
use swarmplan::compose::{PlanOptions, RouteMethod};
use swarmplan::eaas::exact::milp::MilpOptions;
use swarmplan::eaas::SharingPolicy;
use swarmplan::precompose::Positioning;

const NONE_LA_SEQ: &str = "none/location-aware/sequential";
const PB_LA_SEQ: &str = "pb/location-aware/sequential";
const PB_EA_SEQ: &str = "pb/energy-aware/sequential";
const FB_EA_ASTAR: &str = "fb/energy-aware/astar";

fn combo(sharing: SharingPolicy, positioning: Positioning, route: RouteMethod) -> PlanOptions {
    PlanOptions {
        sharing,
        positioning,
        route,
        support: None,
    }
}

fn config(combos: Vec<PlanOptions>) -> BenchConfig {
    BenchConfig {
        schema_version: SUMMARY_SCHEMA_VERSION,
        version: "test".to_string(),
        inputs_sha256: "test".to_string(),
        network: "embedded test".to_string(),
        profile: "embedded test".to_string(),
        requests: "embedded test".to_string(),
        combos,
        gap: true,
        joint: false,
        limit: 10,
        exact_limit: 2,
        milp: MilpOptions::default(),
        node_limit: None,
        distance_bucket_m: 1000.0,
        shard: Shard::WHOLE,
    }
}

fn bucket(
    from_km: f64,
    requests: usize,
    delivered: usize,
    dt_nt: Option<(f64, f64)>,
) -> DistanceBucket {
    DistanceBucket {
        from_m: from_km * 1000.0,
        to_m: (from_km + 1.0) * 1000.0,
        requests,
        delivered,
        mean_dt_min: dt_nt.map(|t| t.0),
        mean_nt_min: dt_nt.map(|t| t.1),
    }
}

fn histogram(gaps: &[f64]) -> GapHistogram {
    GapHistogram::of(gaps.iter().copied())
}

/// Four combinations over 10 requests:
///
/// | combination | delivered | buckets with a delivered request | route gap histogram |
/// | --- | --- | --- | --- |
/// | none/location-aware/sequential | 6 | 0-1 km, 1-2 km | yes |
/// | pb/location-aware/sequential | 9 | 0-1 km, 1-2 km | yes |
/// | pb/energy-aware/sequential | 8 | 1-2 km | no |
/// | fb/energy-aware/astar | 0 | none | no |
///
/// Hop gaps for PB and FB; 5 stops.
fn full_summary() -> Summary {
    let combos = vec![
        combo(
            SharingPolicy::None,
            Positioning::LocationAware,
            RouteMethod::Sequential,
        ),
        combo(
            SharingPolicy::Pb,
            Positioning::LocationAware,
            RouteMethod::Sequential,
        ),
        combo(
            SharingPolicy::Pb,
            Positioning::EnergyAware,
            RouteMethod::Sequential,
        ),
        combo(
            SharingPolicy::Fb,
            Positioning::EnergyAware,
            RouteMethod::Astar,
        ),
    ];
    let mut s = Summary::of(
        &config(combos),
        &BenchData::default(),
        vec!["test".to_string()],
    );
    s.requests_planned = 10;
    let filled = [
        (
            6,
            1.5,
            vec![
                bucket(0.0, 5, 4, Some((10.0, 1.0))),
                bucket(1.0, 5, 2, Some((20.0, 3.0))),
            ],
            Some(vec![0.0, 0.0, 0.02]),
        ),
        (
            9,
            2.5,
            vec![
                bucket(0.0, 5, 5, Some((9.0, 0.5))),
                bucket(1.0, 5, 4, Some((18.0, 2.0))),
            ],
            Some(vec![0.0, 0.3]),
        ),
        (
            8,
            4.0,
            vec![
                bucket(0.0, 5, 0, None),
                bucket(1.0, 5, 8, Some((17.0, 1.5))),
            ],
            None,
        ),
        (
            0,
            0.5,
            vec![bucket(0.0, 5, 0, None), bucket(1.0, 5, 0, None)],
            None,
        ),
    ];
    for (m, (delivered, exec_ms, by_distance, gaps)) in s.methods.iter_mut().zip(filled) {
        m.requests = 10;
        m.delivered = delivered;
        m.exec_ms_median = exec_ms;
        m.by_distance = by_distance;
        m.route_gap_histogram = gaps.as_deref().map(histogram);
        m.route_gaps = gaps;
    }
    s.hop_gaps = vec![
        hop_gaps(SharingPolicy::Pb, &[0.0, 0.1]),
        hop_gaps(SharingPolicy::Fb, &[0.0, 0.0, 0.6]),
    ];
    s.stop_gaps.stops = 5;
    s.stop_gaps.proven = 5;
    s.stop_gaps.histogram = histogram(&[0.0, 0.0, 0.0, 0.04, 0.2]);
    s
}

fn hop_gaps(sharing: SharingPolicy, losses: &[f64]) -> HopGapSummary {
    HopGapSummary {
        sharing,
        hops: losses.len(),
        against_optimal: losses.len(),
        against_infimum: 0,
        against_bound: 0,
        different_policy: 0,
        at_zero: losses.iter().filter(|&&l| l == 0.0).count(),
        mean_loss: losses.iter().sum::<f64>() / losses.len() as f64,
        max_loss: losses.iter().copied().fold(0.0, f64::max),
        histogram: histogram(losses),
        below_optimum: 0,
        continuous_ms_total: 1.0,
        continuous_ms_median: 0.5,
        continuous_ms_max: 0.5,
    }
}

/// A fresh, empty directory under the system's temporary directory.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!(
        "swarmplan-bench-figures-{}-{name}",
        std::process::id()
    ));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The text of a written figure, checked to be a whole SVG document.
fn svg(dir: &Path, relative: &str) -> String {
    let path = dir.join(relative);
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let trimmed = text.trim();
    assert!(
        trimmed.starts_with("<svg") || trimmed.starts_with("<?xml"),
        "{relative} starts with {:?}",
        &trimmed[..trimmed.len().min(40)]
    );
    assert!(
        trimmed.ends_with("</svg>"),
        "{relative} does not end with </svg>"
    );
    text
}

/// The contents of the `<text>` elements of `svg`, trimmed and unescaped.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| {
            let inner = &t[t.find('>')? + 1..t.find("</text>")?];
            Some(
                inner
                    .trim()
                    .replace("&lt;", "<")
                    .replace("&gt;", ">")
                    .replace("&quot;", "\"")
                    .replace("&apos;", "'")
                    .replace("&amp;", "&"),
            )
        })
        .collect()
}

/// How many `<text>` elements read exactly `label`.
fn count_text(svg: &str, label: &str) -> usize {
    texts(svg).iter().filter(|t| *t == label).count()
}

fn assert_has_text(svg: &str, relative: &str, text: &str) {
    let all = texts(svg);
    assert!(
        all.iter().any(|t| t == text),
        "{relative}: no text {text:?} among {all:?}"
    );
}

#[test]
fn every_figure_with_data_is_written_in_order() {
    let dir = temp_dir("full");
    let written = write_figures(&dir, &full_summary()).unwrap();
    assert_eq!(
        written,
        [
            "figures/delivered.svg",
            "figures/dt-by-distance-location-aware.svg",
            "figures/dt-by-distance-energy-aware.svg",
            "figures/nt-by-distance-location-aware.svg",
            "figures/nt-by-distance-energy-aware.svg",
            "figures/exec-time.svg",
            "figures/route-gap-cdf.svg",
            "figures/hop-gap-histogram.svg",
            "figures/stop-gap-histogram.svg",
        ]
    );
    for relative in &written {
        svg(&dir, relative);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bar_charts_have_one_labelled_bar_per_combination() {
    let dir = temp_dir("bars");
    write_figures(&dir, &full_summary()).unwrap();
    let delivered = svg(&dir, "figures/delivered.svg");
    assert_has_text(
        &delivered,
        "delivered",
        "Requests delivered (of 10 requests)",
    );
    assert_has_text(&delivered, "delivered", "requests delivered (of 10)");
    for label in [NONE_LA_SEQ, PB_LA_SEQ, PB_EA_SEQ, FB_EA_ASTAR] {
        assert_eq!(count_text(&delivered, label), 1, "delivered: label {label}");
    }
    for count in ["6 of 10", "9 of 10", "8 of 10", "0 of 10"] {
        assert_eq!(count_text(&delivered, count), 1, "delivered: value {count}");
    }
    let exec = svg(&dir, "figures/exec-time.svg");
    assert_has_text(&exec, "exec_time", "Median execution time per request");
    assert_has_text(&exec, "exec_time", "median execution time per request (ms)");
    for (label, ms) in [
        (NONE_LA_SEQ, "1.5 ms"),
        (PB_LA_SEQ, "2.5 ms"),
        (PB_EA_SEQ, "4.0 ms"),
        (FB_EA_ASTAR, "0.5 ms"),
    ] {
        assert_eq!(count_text(&exec, label), 1, "exec_time: label {label}");
        assert_eq!(count_text(&exec, ms), 1, "exec_time: value {ms}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn distance_figures_have_one_line_per_combination_of_their_positioning_with_data() {
    let dir = temp_dir("lines");
    write_figures(&dir, &full_summary()).unwrap();
    // `none` appears under both positionings; fb/energy-aware/astar delivers nothing, so has no
    // line.
    // (file prefix, positioning, quantity, series, points: delivered buckets over the series)
    let cases = [
        (
            "dt",
            "location-aware",
            "delivery time",
            [NONE_LA_SEQ, PB_LA_SEQ],
            4,
        ),
        (
            "dt",
            "energy-aware",
            "delivery time",
            [NONE_LA_SEQ, PB_EA_SEQ],
            3,
        ),
        (
            "nt",
            "location-aware",
            "node time",
            [NONE_LA_SEQ, PB_LA_SEQ],
            4,
        ),
        (
            "nt",
            "energy-aware",
            "node time",
            [NONE_LA_SEQ, PB_EA_SEQ],
            3,
        ),
    ];
    for (prefix, positioning, time, series, points) in cases {
        let relative = format!("figures/{prefix}-by-distance-{positioning}.svg");
        let text = svg(&dir, &relative);
        assert_has_text(
            &text,
            &relative,
            &format!("Mean {time} of the delivered by distance, {positioning}"),
        );
        assert_has_text(&text, &relative, &format!("mean {time} (min)"));
        assert_has_text(
            &text,
            &relative,
            "source–destination distance, bucket midpoint (km)",
        );
        for label in series {
            assert_eq!(count_text(&text, label), 1, "{relative}: legend {label}");
        }
        for absent in [
            FB_EA_ASTAR,
            if positioning == "location-aware" {
                PB_EA_SEQ
            } else {
                PB_LA_SEQ
            },
        ] {
            assert_eq!(count_text(&text, absent), 0, "{relative}: legend {absent}");
        }
        // The series are drawn 2 px wide (the axes 1 px): one polyline per series and one per
        // legend entry; a dot at every point.
        let wide = text
            .lines()
            .filter(|l| l.starts_with("<polyline") && l.contains(r#"stroke-width="2""#))
            .count();
        assert_eq!(wide, 2 * series.len(), "{relative}: series polylines");
        assert_eq!(text.matches("<circle").count(), points, "{relative}: dots");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn gap_histograms_have_one_series_per_heuristic() {
    let dir = temp_dir("histograms");
    write_figures(&dir, &full_summary()).unwrap();
    let bins = histogram(&[]).bins;
    let cases: [(&str, &str, &[&str]); 2] = [
        (
            "hop-gap-histogram",
            "Sharing heuristics' loss against the hop's continuous-time optimum, per hop",
            &["pb", "fb"],
        ),
        (
            "stop-gap-histogram",
            "LPT's gap against the exact node time, per stop",
            &["LPT"],
        ),
    ];
    for (name, title, series) in cases {
        let relative = format!("figures/{name}.svg");
        let text = svg(&dir, &relative);
        assert_has_text(&text, &relative, title);
        for bin in &bins {
            // The bin `0` shares its text with the count axis' tick 0.
            let ticks = usize::from(bin == "0");
            assert_eq!(count_text(&text, bin), 1 + ticks, "{relative}: bin {bin}");
        }
        for label in series {
            assert_eq!(count_text(&text, label), 1, "{relative}: legend {label}");
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

const ROUTE_GAP_CDF: &str = "figures/route-gap-cdf.svg";

/// Five combinations with route gaps: Dijkstra's and Floyd–Warshall's under PB are the same.
///
/// | combination | gaps | panel | legend entry |
/// | --- | --- | --- | --- |
/// | none/location-aware/sequential | 0, 0, 2% | sharing none | location-aware/sequential (3 requests) |
/// | pb/location-aware/sequential | 0, 30% | sharing pb | location-aware/sequential (2 requests) |
/// | pb/location-aware/dijkstra | -10%, 0, 50% | sharing pb | location-aware/dijkstra = floyd-warshall (3 requests) |
/// | pb/location-aware/floyd-warshall | -10%, 0, 50% | (merged) | |
/// | pb/energy-aware/sequential | 0, 0, 10%, 900% | sharing pb | energy-aware/sequential (4 requests) |
fn cdf_summary() -> Summary {
    use Positioning::{EnergyAware, LocationAware};
    use RouteMethod::{Dijkstra, FloydWarshall, Sequential};
    use SharingPolicy::{None, Pb};
    let combos = [
        (None, LocationAware, Sequential),
        (Pb, LocationAware, Sequential),
        (Pb, LocationAware, Dijkstra),
        (Pb, LocationAware, FloydWarshall),
        (Pb, EnergyAware, Sequential),
    ]
    .map(|(s, p, r)| combo(s, p, r))
    .to_vec();
    let mut s = Summary::of(
        &config(combos),
        &BenchData::default(),
        vec!["test".to_string()],
    );
    let gaps: [&[f64]; 5] = [
        &[0.0, 0.0, 0.02],
        &[0.0, 0.3],
        &[-0.1, 0.0, 0.5],
        &[-0.1, 0.0, 0.5],
        &[0.0, 0.0, 0.1, 9.0],
    ];
    for (m, g) in s.methods.iter_mut().zip(gaps) {
        m.route_gaps = Some(g.to_vec());
    }
    s
}

/// The `y` attribute of every `<text>` element reading exactly `label`.
fn text_ys(svg: &str, label: &str) -> Vec<f64> {
    svg.split("<text")
        .skip(1)
        .filter(|t| {
            t.find('>')
                .zip(t.find("</text>"))
                .is_some_and(|(a, b)| t[a + 1..b].trim() == label)
        })
        .filter_map(|t| attribute(t, "y"))
        .collect()
}

/// The number in the attribute `name="..."` of the element text `element`.
fn attribute(element: &str, name: &str) -> Option<f64> {
    let key = format!(" {name}=\"");
    let at = element.find(&key)? + key.len();
    element[at..at + element[at..].find('"')?].parse().ok()
}

/// WCAG's relative luminance of `#RRGGBB`.
fn luminance(hex: &str) -> f64 {
    let channel = |i: usize| {
        let c = f64::from(u8::from_str_radix(&hex[i..i + 2], 16).unwrap()) / 255.0;
        if c <= 0.03928 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    0.2126 * channel(1) + 0.7152 * channel(3) + 0.0722 * channel(5)
}

#[test]
fn route_gap_cdf_has_a_panel_per_sharing_policy_and_one_line_per_distinct_series() {
    let dir = temp_dir("cdf");
    let written = write_figures(&dir, &cdf_summary()).unwrap();
    assert!(written.iter().any(|w| w == ROUTE_GAP_CDF), "{written:?}");
    let text = svg(&dir, ROUTE_GAP_CDF);
    assert_has_text(
        &text,
        ROUTE_GAP_CDF,
        "Route gap against the optimal route: share of the requests at or below each gap",
    );
    for panel in ["sharing none", "sharing pb"] {
        assert_eq!(count_text(&text, panel), 1, "panel {panel}");
    }
    for entry in [
        "location-aware/sequential (3 requests)",
        "location-aware/sequential (2 requests)",
        "location-aware/dijkstra = floyd-warshall (3 requests)",
        "energy-aware/sequential (4 requests)",
    ] {
        assert_eq!(count_text(&text, entry), 1, "legend {entry}");
    }
    for absent in [
        "location-aware/dijkstra (3 requests)",
        "location-aware/floyd-warshall (3 requests)",
    ] {
        assert_eq!(count_text(&text, absent), 0, "legend {absent}");
    }
    // The gaps span -10% to 900%: on log10(1 + gap), -0.0458 to 1, padded by 4% of that span
    // (0.0418) to -0.0876 .. 1.0418. Ticks keep 0.1129 (a tenth) apart from 0 outwards: -25%
    // (-0.125) is outside; 10% (0.041) and 25% (0.097) too close to 0; then 50% (0.176), 100%
    // (0.301), 200% (0.477), 500% (0.778), 1000% (1.041); each in both panels.
    for tick in ["0%", "50%", "100%", "200%", "500%", "1000%"] {
        assert_eq!(count_text(&text, tick), 2, "tick {tick}");
    }
    for absent in ["-25%", "10%", "25%", "2000%"] {
        assert_eq!(count_text(&text, absent), 0, "tick {absent}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn route_gap_cdf_is_in_dark_colours_with_its_legends_below_the_data() {
    let dir = temp_dir("cdf-style");
    write_figures(&dir, &cdf_summary()).unwrap();
    let text = svg(&dir, ROUTE_GAP_CDF);
    // The series and the legend samples are the 2 px strokes; a contrast ratio of at least 2.6
    // against white is a relative luminance below 0.35.
    let strokes: Vec<&str> = text
        .lines()
        .filter(|l| l.starts_with("<polyline") && l.contains(r#"stroke-width="2""#))
        .collect();
    assert!(!strokes.is_empty());
    for line in &strokes {
        let at = line.find("stroke=\"#").unwrap() + "stroke=\"".len();
        let hex = &line[at..at + 7];
        assert!(luminance(hex) < 0.35, "pale colour {hex} in {line}");
    }
    // Solid series are one polyline of more than 2 points; the lowest point of the data is
    // above (smaller y than) every legend entry.
    let lowest_point = strokes
        .iter()
        .filter_map(|l| {
            let at = l.find(r#"points=""#)? + r#"points=""#.len();
            let points: Vec<f64> = l[at..at + l[at..].find('"')?]
                .split_whitespace()
                .filter_map(|p| p.split(',').nth(1)?.parse().ok())
                .collect();
            (points.len() > 2).then(|| points.into_iter().fold(f64::MIN, f64::max))
        })
        .fold(f64::MIN, f64::max);
    assert!(lowest_point > 0.0, "no series polyline found");
    for entry in [
        "location-aware/sequential (3 requests)",
        "energy-aware/sequential (4 requests)",
    ] {
        for y in text_ys(&text, entry) {
            assert!(
                y > lowest_point,
                "legend {entry} at y {y}, data down to {lowest_point}"
            );
        }
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn figures_without_data_are_not_written() {
    let dir = temp_dir("sparse");
    let mut s = full_summary();
    for m in &mut s.methods {
        m.route_gap_histogram = None;
        m.route_gaps = None;
        if m.options.positioning == Positioning::EnergyAware {
            m.by_distance.clear();
        }
    }
    // Only `none` is left for energy-aware; without its data no energy-aware figure has a line.
    s.methods[0].by_distance.clear();
    s.hop_gaps.clear();
    s.stop_gaps.stops = 0;
    let written = write_figures(&dir, &s).unwrap();
    assert_eq!(
        written,
        [
            "figures/delivered.svg",
            "figures/dt-by-distance-location-aware.svg",
            "figures/nt-by-distance-location-aware.svg",
            "figures/exec-time.svg",
        ]
    );
    for name in [
        "dt-by-distance-energy-aware",
        "nt-by-distance-energy-aware",
        "route-gap-cdf",
        "hop-gap-histogram",
        "stop-gap-histogram",
    ] {
        assert!(
            !dir.join(format!("figures/{name}.svg")).exists(),
            "{name} written"
        );
    }
    let dt = svg(&dir, "figures/dt-by-distance-location-aware.svg");
    assert_eq!(count_text(&dt, PB_LA_SEQ), 1);
    assert_eq!(count_text(&dt, NONE_LA_SEQ), 0);

    let empty = temp_dir("empty");
    let none = Summary::of(&config(Vec::new()), &BenchData::default(), Vec::new());
    assert!(write_figures(&empty, &none).unwrap().is_empty());
    assert!(!empty.join("figures").exists());
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_dir_all(&empty).unwrap();
}

#[test]
fn the_same_summary_gives_the_same_bytes() {
    let (a, b) = (temp_dir("same-a"), temp_dir("same-b"));
    let written = write_figures(&a, &full_summary()).unwrap();
    assert_eq!(write_figures(&b, &full_summary()).unwrap(), written);
    for relative in &written {
        let (x, y) = (
            std::fs::read(a.join(relative)).unwrap(),
            std::fs::read(b.join(relative)).unwrap(),
        );
        assert!(x == y, "{relative} differs");
    }
    std::fs::remove_dir_all(&a).unwrap();
    std::fs::remove_dir_all(&b).unwrap();
}
