//! The user guide (`docs/`, an mdBook) stays whole: it builds with no error or warning and no
//! broken internal link (every relative `href` and `src` of the built HTML names a file of the
//! book, and every `#anchor` an id of that file); `SUMMARY.md` lists every page, and the models
//! part includes every write-up of `models/` once; each command's page names every option of its
//! `--help`; and the README's links name files of the repository, never one outside it.
//!
//! The build needs `mdbook` on the `PATH` (`cargo install mdbook --locked`; `.ci/run` installs
//! it). Without it the build test says so on stderr and passes; the other tests need nothing.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Component, Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// `mdbook` on the `PATH`, if any.
fn mdbook() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    std::env::split_paths(&path)
        .map(|dir| dir.join("mdbook"))
        .find(|p| p.is_file())
}

/// Every `.html` file under `dir`.
fn html_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            html_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "html") {
            out.push(path);
        }
    }
}

/// The values of every `name="..."` attribute in `html` (`name` preceded by a space).
fn attributes<'a>(html: &'a str, name: &str) -> Vec<&'a str> {
    let pattern = format!(" {name}=\"");
    html.match_indices(&pattern)
        .filter_map(|(i, _)| {
            let rest = &html[i + pattern.len()..];
            rest.find('"').map(|end| &rest[..end])
        })
        .collect()
}

/// A URL's path with `&amp;` and `%XX` decoded.
fn decoded(text: &str) -> String {
    let text = text.replace("&amp;", "&");
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let hex = |b: u8| (b as char).to_digit(16);
        if bytes[i] == b'%' && i + 2 < bytes.len() {
            if let (Some(h), Some(l)) = (hex(bytes[i + 1]), hex(bytes[i + 2])) {
                out.push((h * 16 + l) as u8);
                i += 3;
                continue;
            }
        }
        out.push(bytes[i]);
        i += 1;
    }
    String::from_utf8(out).unwrap()
}

/// `base` joined with the relative `link`, `..` resolved lexically; `None` when it leaves `root`.
fn resolve(root: &Path, base: &Path, link: &str) -> Option<PathBuf> {
    let mut out = base.to_path_buf();
    for part in Path::new(link).components() {
        match part {
            Component::ParentDir if !out.pop() || !out.starts_with(root) => return None,
            Component::ParentDir => {}
            Component::Normal(p) => out.push(p),
            _ => {}
        }
    }
    out.starts_with(root).then_some(out)
}

/// Whether a link leaves the book: a scheme (`https:`, `mailto:`, `data:`), or protocol-relative.
fn external(link: &str) -> bool {
    link.starts_with("//")
        || link
            .split_once(':')
            .is_some_and(|(scheme, _)| !scheme.contains('/') && !scheme.is_empty())
}

/// Every broken internal link of the book built in `book`: a relative `href` or `src` whose file
/// does not exist, or whose `#anchor` is no `id` of that file.
fn broken_links(book: &Path) -> (usize, Vec<String>) {
    let mut files = Vec::new();
    html_files(book, &mut files);
    assert!(files.len() > 40, "{} pages built", files.len());
    let mut ids: BTreeMap<PathBuf, BTreeSet<String>> = BTreeMap::new();
    let mut texts = BTreeMap::new();
    for file in &files {
        let text = std::fs::read_to_string(file).unwrap();
        ids.insert(
            file.clone(),
            attributes(&text, "id").into_iter().map(decoded).collect(),
        );
        texts.insert(file.clone(), text);
    }
    let (mut checked, mut broken) = (0, Vec::new());
    for (file, text) in &texts {
        // 404.html is served from any depth and says so with `<base href="/">`.
        let base = if text.contains("<base href=\"/\">") {
            book.to_path_buf()
        } else {
            file.parent().unwrap().to_path_buf()
        };
        let name = file.strip_prefix(book).unwrap().display().to_string();
        for link in attributes(text, "href")
            .into_iter()
            .chain(attributes(text, "src"))
        {
            if link.is_empty() || external(link) {
                continue;
            }
            checked += 1;
            let (path, anchor) = match link.split_once('#') {
                Some((p, a)) => (p, Some(decoded(a))),
                None => (link, None),
            };
            let path = path.split('?').next().unwrap();
            let target = if path.is_empty() {
                Some(file.clone())
            } else {
                resolve(book, &base, &decoded(path)).map(|t| {
                    if t.is_dir() {
                        t.join("index.html")
                    } else {
                        t
                    }
                })
            };
            match target {
                Some(t) if t.is_file() => {
                    if let Some(anchor) = anchor.filter(|a| !a.is_empty()) {
                        let known = ids.get(&t).is_some_and(|ids| ids.contains(&anchor));
                        if !known {
                            broken.push(format!("{name}: {link} (no id `{anchor}` there)"));
                        }
                    }
                }
                _ => broken.push(format!("{name}: {link} (no such file in the book)")),
            }
        }
    }
    (checked, broken)
}

#[test]
fn the_guide_builds_with_no_broken_link() {
    let Some(mdbook) = mdbook() else {
        eprintln!(
            "SKIPPED: mdbook is not on the PATH, so the guide is not built here \
             (cargo install mdbook --locked; .ci/run installs it)"
        );
        return;
    };
    let out_dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("guide-book");
    let _ = std::fs::remove_dir_all(&out_dir);
    let out = Command::new(&mdbook)
        .arg("build")
        .arg(repo().join("docs"))
        .arg("--dest-dir")
        .arg(&out_dir)
        .output()
        .unwrap();
    let log = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "mdbook build failed:\n{log}");
    let complaints: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("ERROR") || l.contains("WARN"))
        .collect();
    assert!(
        complaints.is_empty(),
        "mdbook build complains (a missing include, a broken SUMMARY entry):\n{}",
        complaints.join("\n")
    );
    let (checked, broken) = broken_links(&out_dir);
    assert!(checked > 1000, "{checked} links checked");
    assert!(
        broken.is_empty(),
        "broken links in the built guide:\n{}",
        broken.join("\n")
    );
}

#[test]
fn the_link_check_finds_broken_links_and_anchors() {
    let book = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("guide-link-check");
    let _ = std::fs::remove_dir_all(&book);
    std::fs::create_dir_all(book.join("sub")).unwrap();
    let page = |name: &str, body: &str| {
        std::fs::write(book.join(name), body).unwrap();
    };
    page(
        "a.html",
        r##"<h1 id="top">A</h1> <a href="sub/b.html#here">ok</a> <a href="sub/b.html#gone">bad anchor</a>
           <a href="missing.html">bad file</a> <a href="https://example.org/x">external</a>
           <img src="../outside.svg"> <a href="#top">self</a> <a href="sub/b.html#a%20b">encoded</a>"##,
    );
    page(
        "sub/b.html",
        r##"<h2 id="here">B</h2><h2 id="a b">C</h2><a href="../a.html#top">back</a>"##,
    );
    for i in 0..40 {
        page(&format!("filler{i}.html"), "<p>x</p>");
    }
    let (checked, broken) = broken_links(&book);
    assert_eq!(checked, 7);
    assert_eq!(
        broken,
        [
            "a.html: sub/b.html#gone (no id `gone` there)",
            "a.html: missing.html (no such file in the book)",
            "a.html: ../outside.svg (no such file in the book)",
        ]
    );
}

/// The chapters `SUMMARY.md` lists, in order, relative to `docs/src`.
fn summary_pages() -> Vec<String> {
    let summary = std::fs::read_to_string(repo().join("docs/src/SUMMARY.md")).unwrap();
    summary
        .match_indices("](")
        .map(|(i, _)| {
            let rest = &summary[i + 2..];
            rest[..rest.find(')').unwrap()].to_string()
        })
        .collect()
}

/// Every `.md` file under `dir`, relative to `root`.
fn markdown_files(root: &Path, dir: &Path, out: &mut BTreeSet<String>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            markdown_files(root, &path, out);
        } else if path.extension().is_some_and(|e| e == "md") {
            let rel = path.strip_prefix(root).unwrap();
            out.insert(rel.to_string_lossy().replace('\\', "/"));
        }
    }
}

#[test]
fn the_summary_lists_every_page_and_every_model_is_a_chapter() {
    let src = repo().join("docs/src");
    let listed = summary_pages();
    let mut pages = BTreeSet::new();
    markdown_files(&src, &src, &mut pages);
    pages.remove("SUMMARY.md");
    let listed_set: BTreeSet<String> = listed.iter().cloned().collect();
    assert_eq!(listed.len(), listed_set.len(), "a page listed twice");
    assert_eq!(
        pages, listed_set,
        "pages of docs/src and the pages SUMMARY.md lists differ"
    );
    // Every write-up and experiment record is included by exactly one chapter.
    let mut includes: BTreeMap<PathBuf, usize> = BTreeMap::new();
    for page in &pages {
        let file = src.join(page);
        let text = std::fs::read_to_string(&file).unwrap();
        for (i, _) in text.match_indices("{{#include ") {
            let rest = &text[i + 11..];
            let target = rest[..rest.find("}}").unwrap()].trim();
            let path = file.parent().unwrap().join(target);
            let path = std::fs::canonicalize(&path)
                .unwrap_or_else(|_| panic!("{page} includes {target}, which does not exist"));
            *includes.entry(path).or_default() += 1;
        }
    }
    let models = repo().join("models");
    let mut write_ups = BTreeSet::new();
    markdown_files(&models, &models, &mut write_ups);
    for w in &write_ups {
        let path = std::fs::canonicalize(models.join(w)).unwrap();
        assert_eq!(
            includes.get(&path).copied().unwrap_or(0),
            1,
            "models/{w} is not included by exactly one chapter of the guide"
        );
    }
}

/// Every long option (`--name`) of `swarmplan <args> --help`.
fn options_of(args: &[&str]) -> BTreeSet<String> {
    let out = Command::new(env!("CARGO_BIN_EXE_swarmplan"))
        .args(args)
        .arg("--help")
        .output()
        .unwrap();
    assert!(out.status.success(), "{args:?} --help");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .filter_map(|l| {
            let l = l.trim_start();
            let l = l.strip_prefix("-o, ").unwrap_or(l);
            let l = l.strip_prefix("-h, ").unwrap_or(l);
            l.strip_prefix("--").map(|rest| {
                let name: String = rest
                    .chars()
                    .take_while(|c| c.is_ascii_alphanumeric() || *c == '-')
                    .collect();
                format!("--{name}")
            })
        })
        .filter(|o| o != "--help")
        .collect()
}

#[test]
fn every_option_of_every_command_is_on_its_page() {
    let commands: [(&[&str], &str); 13] = [
        (&["solve"], "solve"),
        (&["batch"], "batch"),
        (&["check"], "check"),
        (&["plot"], "plot"),
        (&["inspect"], "inspect"),
        (&["node-time"], "node-time"),
        (&["eaas"], "eaas"),
        (&["generate", "network"], "generate"),
        (&["generate", "requests"], "generate"),
        (&["generate", "node-time"], "generate"),
        (&["import"], "import"),
        (&["bench"], "bench"),
        (&["bench", "merge"], "bench"),
    ];
    let mut missing = Vec::new();
    for (args, page) in commands {
        let file = repo().join(format!("docs/src/commands/{page}.md"));
        let text = std::fs::read_to_string(&file).unwrap();
        let options = options_of(args);
        assert!(!options.is_empty(), "{args:?}: no option read");
        for option in options {
            let named = text.match_indices(&option).any(|(i, _)| {
                !text[i + option.len()..]
                    .starts_with(|c: char| c.is_ascii_alphanumeric() || c == '-')
            });
            if !named {
                missing.push(format!(
                    "{} {option}: not on commands/{page}.md",
                    args.join(" ")
                ));
            }
        }
    }
    assert!(missing.is_empty(), "{}", missing.join("\n"));
}

/// The targets of the Markdown links and images of `text`: `](target)`.
fn markdown_links(text: &str) -> Vec<String> {
    text.match_indices("](")
        .filter_map(|(i, _)| {
            let rest = &text[i + 2..];
            rest.find(')').map(|end| rest[..end].to_string())
        })
        .collect()
}

#[test]
fn the_readme_links_name_files_of_the_repository() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let links = markdown_links(&readme);
    assert!(links.len() >= 3, "{links:?}");
    let root = std::fs::canonicalize(repo()).unwrap();
    for link in links {
        if link.starts_with("https://") || link.starts_with("http://") {
            continue;
        }
        assert!(
            !external(&link) && !link.starts_with('/'),
            "the README points at a file outside the repository: {link}"
        );
        let path = link.split('#').next().unwrap();
        let target = resolve(&root, &root, path)
            .unwrap_or_else(|| panic!("the README points outside the repository: {link}"));
        assert!(target.exists(), "README link to a missing file: {link}");
    }
}
