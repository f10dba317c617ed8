//! The output directory of `swarmplan bench`: writing it, reading its rows back, and merging the
//! directories of shards into the one a single run writes.

#[cfg(feature = "cli")]
use super::{figures, report};
use super::{findings, seal, BenchConfig, BenchData, Shard, Summary};
use crate::error::{Error, Result};
use crate::problem::io;
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;

/// The configuration file of a run.
pub const CONFIG_FILE: &str = "config.json";
/// The summary of a run, with its findings.
pub const SUMMARY_FILE: &str = "summary.json";
/// The data files, one row per record, reproducible byte for byte but `timings.csv`.
pub const DATA_FILES: [&str; 5] = [
    "requests.csv",
    "hops.csv",
    "stops.csv",
    "timings.csv",
    "joint.csv",
];

/// `E7005`: `dir` holds the files of a run and `force` (`--force`) was not given.
///
/// # Errors
/// [`Error::Invalid`] E7005.
pub fn may_write(dir: &Path, force: bool) -> Result<()> {
    let taken = std::iter::once(&CONFIG_FILE)
        .chain(&DATA_FILES)
        .any(|f| dir.join(f).exists());
    if force || !taken {
        return Ok(());
    }
    Err(Error::invalid(
        "E7005",
        dir.display().to_string(),
        "the directory holds the files of an earlier run; bench does not overwrite them unasked",
        "pass --force to overwrite them, or give another --out",
    ))
}

fn csv_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::invalid(
        "E7004",
        path.display().to_string(),
        format!("not a table `swarmplan bench` writes: {e}"),
        "give the output directories of `swarmplan bench` runs, unchanged",
    )
}

/// Writes a table whole (aside, then renamed).
fn write_csv<T: Serialize>(path: &Path, rows: &[T]) -> Result<()> {
    let mut bytes = Vec::new();
    crate::experiment::write_csv(&mut bytes, rows).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })?;
    io::write_whole(path, &bytes)
}

fn read_csv<T: DeserializeOwned>(path: &Path) -> Result<Vec<T>> {
    let text = io::read_text(path)?;
    let mut r = csv::Reader::from_reader(text.as_bytes());
    r.deserialize()
        .map(|row| row.map_err(|e| csv_error(path, e)))
        .collect()
}

/// Reads a run's configuration and rows from its directory.
///
/// # Errors
/// E0008/E0009 for a file that cannot be read, E7004 for a table that does not parse, the
/// JSON errors of the configuration.
pub fn read_data(dir: &Path) -> Result<(BenchConfig, BenchData)> {
    let config: BenchConfig = io::read_json(&dir.join(CONFIG_FILE))?;
    let data = BenchData {
        requests: read_csv(&dir.join(DATA_FILES[0]))?,
        hops: read_csv(&dir.join(DATA_FILES[1]))?,
        stops: read_csv(&dir.join(DATA_FILES[2]))?,
        timings: read_csv(&dir.join(DATA_FILES[3]))?,
        joint: read_csv(&dir.join(DATA_FILES[4]))?,
    };
    Ok((config, data))
}

/// Writes a run (or a merge) to `dir`: the configuration and the tables, then the summary with
/// the findings and the figures, computed from the tables as written (so a run and the merge of
/// its shards summarise the same numbers), and `report.html`, which shows them on one page. A
/// shard's directory gets neither figures nor report: its summary covers only its own requests.
///
/// # Errors
/// [`Error::Io`] when a file cannot be written; those of [`read_data`].
pub fn write_outputs(
    dir: &Path,
    config: &BenchConfig,
    data: &BenchData,
    command: Vec<String>,
) -> Result<Summary> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Io {
        path: dir.display().to_string(),
        source,
    })?;
    io::write_json(&dir.join(CONFIG_FILE), config)?;
    write_csv(&dir.join(DATA_FILES[0]), &data.requests)?;
    write_csv(&dir.join(DATA_FILES[1]), &data.hops)?;
    write_csv(&dir.join(DATA_FILES[2]), &data.stops)?;
    write_csv(&dir.join(DATA_FILES[3]), &data.timings)?;
    write_csv(&dir.join(DATA_FILES[4]), &data.joint)?;
    let (config, data) = read_data(dir)?;
    let mut summary = Summary::of(&config, &data, command);
    summary.findings = findings(&summary.methods, &data);
    // The figures are drawn by the front ends' plotters (feature `cli`); the planning core alone
    // writes the tables and the summary.
    #[cfg(feature = "cli")]
    if config.shard == Shard::WHOLE {
        summary.figures = figures::write_figures(dir, &summary)?;
    }
    io::write_json(&dir.join(SUMMARY_FILE), &summary)?;
    let written: Vec<String> = std::iter::once(CONFIG_FILE)
        .chain(DATA_FILES)
        .chain([SUMMARY_FILE])
        .map(String::from)
        .chain(summary.figures.iter().cloned())
        .collect();
    // The report, filled from the summary and the figures as written (feature `cli`, like them).
    #[cfg(feature = "cli")]
    let written = match config.shard == Shard::WHOLE {
        true => [written, vec![report::write_report(dir, &summary)?]].concat(),
        false => written,
    };
    seal::mark_complete(dir, &config, &written)?;
    Ok(summary)
}

/// Merges the directories of the shards `0/N`, ..., `N-1/N` of one run (in any order) into the
/// rows one run of the whole would have written, in its order.
///
/// # Errors
/// Those of [`seal::verify_seal`] for a directory without the completion mark of a finished run
/// or whose files were changed after it (E7007-E7009), E7002 when the
/// configurations (inputs' fingerprint and tool version included) differ but for the shard,
/// E7003 when the shards are not exactly `0/N`, ..., `N-1/N`; those of [`read_data`].
pub fn merge(dirs: &[&Path]) -> Result<(BenchConfig, BenchData)> {
    let mut parts = Vec::new();
    for dir in dirs {
        let sealed = seal::verify_seal(dir)?;
        let (config, data) = read_data(dir)?;
        seal::seal_agrees(dir, &sealed, &config)?;
        parts.push((dir, (config, data)));
    }
    let Some((first_dir, (first, _))) = parts.first() else {
        return Err(Error::invalid(
            "E7003",
            "bench merge",
            "no shard directory given",
            "give the output directories of every shard of the run",
        ));
    };
    let mut config = first.clone();
    config.shard = Shard::WHOLE;
    let count = first.shard.count;
    let mut seen = vec![false; count];
    for (dir, (c, _)) in &parts {
        let mut same = c.clone();
        same.shard = Shard::WHOLE;
        if same != config {
            return Err(Error::invalid(
                "E7002",
                dir.display().to_string(),
                format!(
                    "its run's configuration differs from that of {} beyond the shard",
                    first_dir.display()
                ),
                "merge only the shards of one run: same instance, request set, --request-limit, methods \
                 and exact settings",
            ));
        }
        if c.shard.count != count || std::mem::replace(&mut seen[c.shard.index], true) {
            return Err(Error::invalid(
                "E7003",
                dir.display().to_string(),
                format!(
                    "shard {} repeats a shard or is not of {count} shards",
                    c.shard
                ),
                "give each shard 0/N ... N-1/N of one run once",
            ));
        }
    }
    if let Some(missing) = seen.iter().position(|s| !s) {
        return Err(Error::invalid(
            "E7003",
            "bench merge",
            format!("shard {missing}/{count} is missing"),
            "give the output directories of every shard of the run",
        ));
    }
    let combos = config.planned_combos();
    let position = |s, p, r| {
        combos
            .iter()
            .position(|c| super::summary::is_of((s, p, r), c))
            .unwrap_or(usize::MAX)
    };
    let mut data = BenchData::default();
    for (_, (_, d)) in parts {
        data.requests.extend(d.requests);
        data.hops.extend(d.hops);
        data.stops.extend(d.stops);
        data.timings.extend(d.timings);
        data.joint.extend(d.joint);
    }
    // Stable sorts: within one request and combination the rows keep their shard's order.
    data.requests
        .sort_by_key(|r| (r.request_index, position(r.sharing, r.positioning, r.route)));
    data.hops
        .sort_by_key(|r| (r.request_index, position(r.sharing, r.positioning, r.route)));
    data.stops
        .sort_by_key(|r| (r.request_index, position(r.sharing, r.positioning, r.route)));
    data.timings
        .sort_by_key(|r| (r.request_index, position(r.sharing, r.positioning, r.route)));
    data.joint.sort_by_key(|r| r.request_index);
    Ok((config, data))
}
