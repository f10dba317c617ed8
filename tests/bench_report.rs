//! `swarmplan bench` writes `report.html` (issue 47): one self-contained page with the run's
//! command and inputs, the summary table, the findings with their verdicts and evidence, every
//! figure inline, and links to the tables; sealed with the run's other files, and written by
//! `bench merge` too. The page is checked against `summary.json`, read on its own.

mod common;

use common::{bench_shards, stderr, swarmplan, tmp};
use serde_json::Value;
use std::path::Path;

fn arg(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// The text of HTML with the entities the report's escaping writes turned back into characters.
fn unescape(html: &str) -> String {
    html.replace("&#x2f;", "/")
        .replace("&#x27;", "'")
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

fn read_json(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// Every `attribute="..."` value in `html`.
fn attribute_values<'a>(html: &'a str, attribute: &str) -> Vec<&'a str> {
    let key = format!("{attribute}=\"");
    html.match_indices(&key)
        .map(|(i, _)| {
            let rest = &html[i + key.len()..];
            &rest[..rest.find('"').unwrap()]
        })
        .collect()
}

/// The checks of one directory's report against its own `summary.json`.
fn assert_report_matches_summary(dir: &Path) {
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    let text = unescape(&html);
    let summary = read_json(&dir.join("summary.json"));

    assert!(html.starts_with("<!DOCTYPE html>"), "{}", &html[..80]);
    assert!(html.contains("<html") && html.trim_end().ends_with("</html>"));
    assert!(html.contains("<style>"));

    // Every figure inline, and nothing fetched from elsewhere.
    let figures = summary["figures"].as_array().unwrap();
    assert!(!figures.is_empty());
    assert_eq!(
        html.matches("<svg").count(),
        figures.len(),
        "one <svg> per figure"
    );
    assert_eq!(html.matches("</svg>").count(), figures.len());
    for f in figures {
        let name = f.as_str().unwrap();
        let svg = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(html.contains(svg.trim()), "{name} is not inline whole");
    }
    assert!(!html.contains("<img") && !html.contains("<script") && !html.contains("<link"));
    assert!(!html.contains("@import") && !html.contains("url("));
    for attribute in ["src", "href"] {
        for value in attribute_values(&html, attribute) {
            let value = unescape(value);
            assert!(
                !value.contains("://") && !value.starts_with("//"),
                "{attribute}=\"{value}\" leaves the directory"
            );
        }
    }

    // The command and the inputs.
    let command: Vec<&str> = summary["command"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a.as_str().unwrap())
        .collect();
    assert!(
        text.contains(&command[1..].join(" ")),
        "command {command:?} missing"
    );
    for input in ["network", "profile", "requests", "inputs_sha256"] {
        let value = summary["config"][input].as_str().unwrap();
        assert!(text.contains(value), "input {input} = {value} missing");
    }

    // Each combination, each finding with its verdict and evidence.
    for m in summary["methods"].as_array().unwrap() {
        let o = &m["options"];
        let name = format!(
            "{}/{}/{}",
            o["sharing"].as_str().unwrap(),
            o["positioning"].as_str().unwrap(),
            o["route"].as_str().unwrap()
        );
        let delivered = format!("{}/{}", m["delivered"], m["requests"]);
        assert!(
            text.contains(&format!(
                "<tr><td>{name}</td><td class=\"num\">{delivered}</td>"
            )),
            "the row of {name} ({delivered}) missing"
        );
    }
    let findings = summary["findings"].as_array().unwrap();
    assert!(!findings.is_empty());
    for f in findings {
        let verdict = f["verdict"].as_str().unwrap().replace('-', " ");
        for field in ["claim", "paper", "ours"] {
            let value = f[field].as_str().unwrap();
            assert!(text.contains(value), "finding {}: {field} missing", f["id"]);
        }
        let row = format!(
            "<td>{}</td>\n<td>{}</td>\n<td class=\"{}\">{verdict}</td>",
            f["id"].as_str().unwrap(),
            f["claim"].as_str().unwrap(),
            f["verdict"].as_str().unwrap()
        );
        assert!(text.contains(&row), "finding {}'s verdict missing", f["id"]);
    }

    // A link to each table, relative.
    for csv in [
        "requests.csv",
        "hops.csv",
        "stops.csv",
        "timings.csv",
        "joint.csv",
    ] {
        assert!(
            html.contains(&format!("<a href=\"{csv}\">")),
            "no link to {csv}"
        );
    }
}

/// The files a seal lists.
fn sealed_files(dir: &Path) -> Vec<String> {
    std::fs::read_to_string(dir.join("complete"))
        .unwrap()
        .lines()
        .filter_map(|l| l.strip_prefix("file "))
        .map(|l| l.split(' ').next().unwrap().to_string())
        .collect()
}

#[test]
fn bench_writes_a_self_contained_report_the_seal_covers() {
    let dir = tmp("bench-report/run");
    let _ = std::fs::remove_dir_all(&dir);
    let out = swarmplan(&[
        "bench",
        "--request-limit",
        "3",
        "--sharing",
        "none,pb",
        "--route",
        "sequential,dijkstra",
        "--out",
        arg(&dir),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("report.html in"), "{}", stderr(&out));
    assert_report_matches_summary(&dir);

    // The tables printed on stdout (the combinations', then the gap split's) and the page show
    // the same cells.
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    let text = unescape(&std::fs::read_to_string(dir.join("report.html")).unwrap());
    let rows: Vec<&str> = stdout
        .lines()
        .filter(|l| l.starts_with("none/") || l.starts_with("pb/"))
        .collect();
    assert_eq!(rows.len(), 12, "{stdout}");
    let html_row = |cells: &[&str]| {
        format!(
            "<tr><td>{}</td>{}</tr>",
            cells[0],
            cells[1..]
                .iter()
                .map(|c| format!("<td class=\"num\">{c}</td>"))
                .collect::<String>()
        )
    };
    for row in &rows[..6] {
        // ms/request (the last column) is machine-dependent but printed from the same summary.
        let html = html_row(&row.split_whitespace().collect::<Vec<_>>());
        assert!(text.contains(&html), "{html} missing");
    }
    for row in &rows[6..] {
        // Cells with spaces (`166.4 (129.1%)`): the columns' widths, 36, 7, 7 and 17.
        let mut at = 0;
        let cells: Vec<&str> = [36, 7, 7, 17, 17, 17, 17]
            .iter()
            .map(|&w| {
                let cell = row[at..at + w].trim();
                at += w + 1;
                cell
            })
            .collect();
        let html = html_row(&cells);
        assert!(text.contains(&html), "{html} missing");
    }

    assert!(sealed_files(&dir).contains(&"report.html".to_string()));
    let out = swarmplan(&["check", "--bench", arg(&dir)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let verdict = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(verdict.contains("rows of 3 requests: valid"), "{verdict}");

    // A report edited after the run breaks the seal.
    let path = dir.join("report.html");
    let saved = std::fs::read(&path).unwrap();
    std::fs::write(&path, b"<html></html>").unwrap();
    let out = swarmplan(&["check", "--bench", arg(&dir)]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("[E7009]"), "{}", stderr(&out));
    std::fs::write(&path, saved).unwrap();
}

#[test]
fn shards_get_no_report_and_their_merge_writes_one() {
    let (s0, s1) = bench_shards("bench-report/shards");
    for s in [&s0, &s1] {
        assert!(!s.join("report.html").exists(), "a shard's report");
        assert!(!sealed_files(s).contains(&"report.html".to_string()));
    }
    let merged = s0.parent().unwrap().join("merged");
    let out = swarmplan(&["bench", "merge", arg(&s0), arg(&s1), "--out", arg(&merged)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(stderr(&out).contains("report.html in"), "{}", stderr(&out));
    assert_report_matches_summary(&merged);
    assert!(sealed_files(&merged).contains(&"report.html".to_string()));
    let out = swarmplan(&["check", "--bench", arg(&merged)]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}
