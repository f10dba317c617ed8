//! `report.html`: one self-contained page of a run (no network access): its command and
//! inputs, the summary table, the gap split, the findings with their verdicts and evidence,
//! every figure inline, and links to the tables. Filled from a template
//! (`src/bench/report.html.j2`) with auto-escaping; only the figures' SVG, read back from the
//! files written, goes in unescaped.

use super::table;
use super::{Summary, Verdict, CONFIG_FILE, DATA_FILES, SUMMARY_FILE};
use crate::error::{Error, Result};
use crate::problem::io;
use serde::Serialize;
use std::path::Path;

/// The report's file name in the output directory.
pub const REPORT_FILE: &str = "report.html";

const TEMPLATE: &str = include_str!("report.html.j2");

#[derive(Serialize)]
struct Page {
    command: String,
    version: String,
    heading: String,
    inputs: Vec<(&'static str, String)>,
    config_json: String,
    method_columns: [&'static str; 9],
    methods: Vec<[String; 9]>,
    route_gap_note: Option<&'static str>,
    exact_subset: Vec<String>,
    joint: Option<String>,
    split_columns: [&'static str; 7],
    splits: Vec<[String; 7]>,
    split_note: Option<String>,
    findings: Vec<FindingView>,
    figures: Vec<FigureView>,
    tables: Vec<&'static str>,
    other_files: Vec<&'static str>,
}

#[derive(Serialize)]
struct FindingView {
    id: &'static str,
    claim: &'static str,
    verdict: String,
    /// The CSS class of the verdict: `holds`, `does-not-hold` or `not-measured`.
    class: &'static str,
    measured: bool,
    ours: String,
    paper: &'static str,
    figure: &'static str,
    /// The anchor of the figure in the page, when it was drawn.
    anchor: Option<String>,
}

#[derive(Serialize)]
struct FigureView {
    name: String,
    anchor: String,
    svg: String,
}

/// The anchor of a figure file in the page: `figures/delivered.svg` is `figure-delivered`.
fn anchor(name: &str) -> String {
    let stem = name.trim_start_matches("figures/").trim_end_matches(".svg");
    let clean: String = stem
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect();
    format!("figure-{clean}")
}

/// The command line as a shell would take it back: arguments with characters beyond the plain
/// ones in single quotes.
fn shell_line(command: &[String]) -> String {
    command
        .iter()
        .map(|a| {
            let plain = !a.is_empty()
                && a.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_-./,:=@%+".contains(c));
            if plain {
                a.clone()
            } else {
                format!("'{}'", a.replace('\'', r"'\''"))
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// An SVG file's text as it goes inline: without an XML declaration.
fn inline_svg(text: &str) -> String {
    let text = text.trim_start();
    let text = match text.strip_prefix("<?xml") {
        Some(rest) => rest.split_once("?>").map_or(rest, |(_, after)| after),
        None => text,
    };
    text.trim().to_string()
}

/// Renders the report of the run in `dir` summarised by `summary`, whose figures (if any) are
/// already written there.
///
/// # Errors
/// Those of reading a figure back; [`Error::Io`] should the template fail to render.
pub fn render(dir: &Path, summary: &Summary) -> Result<String> {
    let s = summary;
    let c = &s.config;
    let figures = s
        .figures
        .iter()
        .map(|name| {
            Ok(FigureView {
                name: name.clone(),
                anchor: anchor(name),
                svg: inline_svg(&io::read_text(&dir.join(name))?),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let findings = s
        .findings
        .iter()
        .map(|f| FindingView {
            id: f.id,
            claim: f.claim,
            verdict: f.verdict.to_string(),
            class: match f.verdict {
                Verdict::Holds => "holds",
                Verdict::DoesNotHold => "does-not-hold",
                Verdict::NotMeasured => "not-measured",
            },
            measured: f.verdict != Verdict::NotMeasured,
            ours: f.ours.clone(),
            paper: f.paper,
            figure: f.figure,
            anchor: s
                .figures
                .iter()
                .any(|g| g == f.figure)
                .then(|| anchor(f.figure)),
        })
        .collect();
    let config_json = serde_json::to_string_pretty(c).unwrap_or_default();
    let page = Page {
        command: shell_line(&s.command),
        version: s.version.clone(),
        heading: table::heading(s),
        inputs: vec![
            ("network", c.network.clone()),
            ("profile", c.profile.clone()),
            ("requests", c.requests.clone()),
            ("inputs' SHA-256", c.inputs_sha256.clone()),
            ("request limit", c.limit.to_string()),
            ("requests planned", s.requests_planned.to_string()),
            ("shard", c.shard.to_string()),
            ("exact subset (first requests)", c.exact_limit.to_string()),
            ("route gaps", c.gap.to_string()),
            ("joint optimum", c.joint.to_string()),
        ],
        config_json,
        method_columns: table::METHOD_COLUMNS,
        methods: s.methods.iter().map(table::method_row).collect(),
        route_gap_note: c.gap.then_some(table::ROUTE_GAP_NOTE),
        exact_subset: table::exact_subset_lines(s),
        joint: s.joint.as_ref().map(table::joint_line),
        split_columns: table::SPLIT_COLUMNS,
        splits: s.methods.iter().filter_map(table::split_row).collect(),
        split_note: s.joint.as_ref().map(|_| table::split_note(s)),
        findings,
        figures,
        tables: DATA_FILES.to_vec(),
        other_files: vec![SUMMARY_FILE, CONFIG_FILE],
    };
    let template_error = |e: minijinja::Error| Error::Io {
        path: dir.join(REPORT_FILE).display().to_string(),
        source: std::io::Error::other(format!("the report's template: {e:#}")),
    };
    let mut env = minijinja::Environment::new();
    env.add_template(REPORT_FILE, TEMPLATE)
        .map_err(template_error)?;
    env.get_template(REPORT_FILE)
        .and_then(|t| t.render(&page))
        .map_err(template_error)
}

/// Writes `report.html` to `dir` ([`render`]); returns its name.
///
/// # Errors
/// Those of [`render`]; [`Error::Io`] when the file cannot be written.
pub fn write_report(dir: &Path, summary: &Summary) -> Result<String> {
    let html = render(dir, summary)?;
    io::write_whole(&dir.join(REPORT_FILE), html.as_bytes())?;
    Ok(REPORT_FILE.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchors_and_command_lines() {
        assert_eq!(
            anchor("figures/dt-by-distance-energy-aware.svg"),
            "figure-dt-by-distance-energy-aware"
        );
        let command = ["swarmplan", "bench", "--out", "my dir", "it's"].map(String::from);
        assert_eq!(
            shell_line(&command),
            r"swarmplan bench --out 'my dir' 'it'\''s'"
        );
        assert_eq!(
            inline_svg("<?xml version=\"1.0\"?>\n<svg a>x</svg>\n"),
            "<svg a>x</svg>"
        );
    }
}
