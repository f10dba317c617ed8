//! What a browser shows: a bench run's `report.html` and the SVG `swarmplan plot` writes,
//! rendered by headless Chromium (Debian's `chromium`, which `.ci/run` installs; where no
//! Chromium is found the tests print why and pass without rendering).
//!
//! Each page is opened with a probe script added at the top of its `<head>`: it records every
//! error the page raises (a script error, a resource that fails to load, `console.error`), and
//! after `load` the box of every figure (each top-level `<svg>` and `<img>`) and whether an image
//! decoded. Chromium prints the page's DOM with the probe's record (`--dump-dom`), then a
//! screenshot of the whole page (`--screenshot`, the window as tall as the page); a figure whose
//! box in the screenshot is one colour is blank. The figures' contents are tested from the SVG
//! itself in tests/cli_plot.rs and tests/bench_report.rs.
//!
//! The checks are shown to fail where they should: a page with a figure emptied and an image
//! that does not exist is refused.

mod common;

use common::{stderr, swarmplan, tmp};
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Added at the top of a page's `<head>`: records the page's errors, then the figures' boxes.
const PROBE: &str = r#"<script>
window.__errors = [];
window.addEventListener('error', function (e) {
  var t = e.target;
  __errors.push(String(e.message || (t && (t.src || t.href)) || 'error'));
}, true);
(function () {
  var original = console.error;
  console.error = function () {
    __errors.push(Array.prototype.join.call(arguments, ' '));
    original.apply(console, arguments);
  };
})();
window.addEventListener('load', function () {
  var figures = Array.prototype.filter.call(document.querySelectorAll('svg, img'), function (e) {
    return !(e.parentElement && e.parentElement.closest('svg'));
  });
  var boxes = figures.map(function (e) {
    var r = e.getBoundingClientRect();
    return {tag: e.tagName.toLowerCase(), id: (e.closest('figure') || e).id || '',
            x: r.left + window.scrollX, y: r.top + window.scrollY, w: r.width, h: r.height,
            decoded: e.tagName.toLowerCase() !== 'img' || (e.complete && e.naturalWidth > 0)};
  });
  var pre = document.createElement('pre');
  pre.id = 'probe';
  pre.textContent = JSON.stringify({errors: __errors, boxes: boxes,
    width: document.documentElement.scrollWidth, height: document.documentElement.scrollHeight});
  document.body.appendChild(pre);
});
</script>"#;

/// The probe's record of a page.
#[derive(Debug, serde::Deserialize)]
struct Probe {
    errors: Vec<String>,
    boxes: Vec<FigureBox>,
    width: f64,
    height: f64,
}

/// A figure's box on the page, CSS px from the page's top left.
#[derive(Debug, serde::Deserialize)]
struct FigureBox {
    tag: String,
    id: String,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
    decoded: bool,
}

/// The Chromium to render with: `SWARMPLAN_CHROMIUM`, else the first of Debian's and Google's
/// names on `PATH`.
fn chromium() -> Option<PathBuf> {
    if let Some(p) = std::env::var_os("SWARMPLAN_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let path = std::env::var_os("PATH")?;
    ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .flat_map(|name| std::env::split_paths(&path).map(move |d| d.join(name)))
        .find(|p| p.is_file())
}

/// Runs Chromium headless on `page` with `extra` flags, its own profile directory, at most two
/// minutes (a guard against a hung browser, not a measure); returns its standard output.
fn render(browser: &Path, page: &Path, extra: &[String], profile: &str) -> String {
    let profile_dir = tmp(&format!("chromium-profile-{profile}"));
    let mut child = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--force-device-scale-factor=1",
            "--virtual-time-budget=10000",
        ])
        .arg(format!("--user-data-dir={}", profile_dir.display()))
        .args(extra)
        .arg(format!("file://{}", page.display()))
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("Chromium starts");
    let mut stdout = child.stdout.take().unwrap();
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut stdout, &mut s).unwrap();
        s
    });
    let deadline = Instant::now() + Duration::from_secs(120);
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(status.success(), "Chromium on {}: {status}", page.display());
            break;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            panic!("Chromium did not finish {} in two minutes", page.display());
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    reader.join().unwrap()
}

/// `html` with the probe added, written beside `dir`'s files as `name`.
fn probed(dir: &Path, name: &str, html: &str) -> PathBuf {
    let at = html.find("<head>").map_or(0, |i| i + "<head>".len());
    let page = dir.join(name);
    std::fs::write(&page, format!("{}{PROBE}{}", &html[..at], &html[at..])).unwrap();
    page
}

/// What is wrong with the page as a browser shows it: its errors, figures without a box or an
/// image that did not decode, and figures blank in the screenshot. Empty when nothing is.
fn faults(browser: &Path, page: &Path) -> Vec<String> {
    let tag = page.file_stem().unwrap().to_string_lossy().to_string();
    let dom = render(browser, page, &["--dump-dom".to_string()], &tag);
    let record = dom
        .split("<pre id=\"probe\">")
        .nth(1)
        .and_then(|s| s.split("</pre>").next())
        .unwrap_or_else(|| panic!("no probe record in the DOM of {}", page.display()));
    let record = record
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let probe: Probe = serde_json::from_str(&record).unwrap();
    let mut found: Vec<String> = probe
        .errors
        .iter()
        .map(|e| format!("the page logs an error: {e}"))
        .collect();
    assert!(!probe.boxes.is_empty(), "no figure on {}", page.display());
    let shot = page.with_extension("png");
    let _ = std::fs::remove_file(&shot);
    render(
        browser,
        page,
        &[
            format!("--screenshot={}", shot.display()),
            format!(
                "--window-size={},{}",
                probe.width.ceil() as u32,
                probe.height.ceil() as u32
            ),
        ],
        &tag,
    );
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&shot).expect("a screenshot"),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut pixels).unwrap();
    let channels = info.color_type.samples();
    let (width, height) = (info.width as usize, info.height as usize);
    for b in &probe.boxes {
        let name = format!("{} {}", b.tag, b.id);
        if !b.decoded {
            found.push(format!("{name}: the image does not decode"));
            continue;
        }
        if b.w < 50.0 || b.h < 50.0 {
            found.push(format!("{name}: a box of {} x {} px", b.w, b.h));
            continue;
        }
        let (x0, y0) = (b.x.max(0.0) as usize, b.y.max(0.0) as usize);
        let (x1, y1) = (
            ((b.x + b.w) as usize).min(width),
            ((b.y + b.h) as usize).min(height),
        );
        let first = &pixels[(y0 * width + x0) * channels..][..channels];
        let mut differing = 0usize;
        for y in y0..y1 {
            for x in x0..x1 {
                let p = &pixels[(y * width + x) * channels..][..channels];
                differing += usize::from(p != first);
            }
        }
        let area = (x1.saturating_sub(x0) * y1.saturating_sub(y0)).max(1);
        // A drawn figure's axes, lines and text cover far more than 0.5% of its box.
        if differing * 200 < area {
            found.push(format!(
                "{name}: blank ({differing} of {area} pixels differ from its corner)"
            ));
        }
    }
    found
}

fn browser_or_skip(test: &str) -> Option<PathBuf> {
    let found = chromium();
    if found.is_none() {
        eprintln!(
            "{test}: skipped, no headless Chromium found (Debian's `chromium`: .ci/run installs \
             it; or set SWARMPLAN_CHROMIUM)"
        );
    }
    found
}

#[test]
fn the_bench_report_shows_every_figure_without_an_error() {
    let Some(browser) = browser_or_skip("report.html") else {
        return;
    };
    let dir = tmp("browser-bench");
    let _ = std::fs::remove_dir_all(&dir);
    let out = swarmplan(&[
        "bench",
        "--request-limit",
        "12",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    let figures = html.matches("<figure id=").count();
    assert!(figures >= 5, "{figures} figures");
    let page = probed(&dir, "probed-report.html", &html);
    let found = faults(&browser, &page);
    assert!(found.is_empty(), "{found:#?}");

    // The same page with its first figure emptied and an image that does not exist: both found.
    let start = html.find("<figure id=").unwrap();
    let svg_open = start + html[start..].find("<svg").unwrap();
    let svg_body = svg_open + html[svg_open..].find('>').unwrap() + 1;
    let svg_close = svg_body + html[svg_body..].find("</svg>").unwrap();
    let broken = format!(
        "{}{}<img src=\"no-such-figure.svg\" width=\"300\" height=\"200\">",
        &html[..svg_body],
        &html[svg_close..]
    );
    let page = probed(&dir, "probed-broken.html", &broken);
    let found = faults(&browser, &page);
    assert!(
        found.iter().any(|f| f.contains("blank")),
        "the emptied figure is not found blank: {found:#?}"
    );
    assert!(
        found.iter().any(|f| f.contains("no-such-figure.svg")),
        "the missing image is not logged: {found:#?}"
    );
    assert!(
        found.iter().any(|f| f.contains("does not decode")),
        "{found:#?}"
    );
}

#[test]
fn a_plot_renders_as_an_image_with_its_panels_drawn() {
    let Some(browser) = browser_or_skip("plot") else {
        return;
    };
    let dir = tmp("browser-plot");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let plan = dir.join("pb.json");
    let optimal = dir.join("optimal.json");
    for (path, extra) in [
        (&plan, &["--sharing", "pb"][..]),
        (&optimal, &["--route", "optimal", "--sharing", "exact"][..]),
    ] {
        let mut args = vec!["solve", "--request-id", "r00003", "--json"];
        args.extend_from_slice(extra);
        let out = swarmplan(&args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        std::fs::write(path, &out.stdout).unwrap();
    }
    let svg = dir.join("plan.svg");
    let out = swarmplan(&[
        "plot",
        "--plan",
        plan.to_str().unwrap(),
        "--compare",
        optimal.to_str().unwrap(),
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let page = probed(
        &dir,
        "probed-plot.html",
        "<!DOCTYPE html><html><head><title>plot</title></head>\
         <body style=\"margin:0\"><img src=\"plan.svg\"></body></html>",
    );
    let found = faults(&browser, &page);
    assert!(found.is_empty(), "{found:#?}");
}
