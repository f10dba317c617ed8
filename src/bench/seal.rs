//! The seal of a bench directory: the `complete` mark a run writes last records the shard it is,
//! the inputs' fingerprint, and the SHA-256 and row count of every file the run wrote. A
//! directory whose mark is missing did not finish; one whose files differ from their seal was
//! changed after the run. `bench merge` and `check --bench` verify the seal before they read a
//! row.
//!
//! The mark is text, one record a line:
//!
//! ```text
//! seal 1
//! shard 0/4
//! inputs_sha256 9f2c...
//! file config.json sha256 4be1... rows -
//! file requests.csv sha256 07aa... rows 120
//! ```
//!
//! `rows` is the number of records of a CSV table (its lines but the header), `-` for the JSON
//! and SVG files.

use super::{BenchConfig, Shard};
use crate::error::{Error, Result};
use sha2::{Digest, Sha256};
use std::path::Path;

/// The file a run writes last, atomically (written aside, then renamed): its presence says every
/// other file of the run is complete, and its records seal them.
pub const COMPLETE_FILE: &str = "complete";

/// The version of the mark's format; a mark of another version is refused (E7008).
const SEAL_VERSION: u32 = 1;

/// One sealed file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SealedFile {
    /// Its name in the directory.
    pub name: String,
    /// SHA-256 of its bytes, lowercase hex.
    pub sha256: String,
    /// Records of a CSV table; `None` for the other files.
    pub rows: Option<usize>,
}

impl SealedFile {
    /// Reads `dir/name` and seals it.
    fn of(dir: &Path, name: &str) -> Result<SealedFile> {
        let path = dir.join(name);
        let bytes = std::fs::read(&path).map_err(|e| {
            Error::invalid(
                "E7009",
                path.display().to_string(),
                format!("a file of the run's seal cannot be read: {e}"),
                "run the bench again: its files were removed or moved after the run",
            )
        })?;
        let rows = name.ends_with(".csv").then(|| {
            let lines = bytes.iter().filter(|&&b| b == b'\n').count();
            lines.saturating_sub(1)
        });
        Ok(SealedFile {
            name: name.to_string(),
            sha256: Sha256::digest(&bytes)
                .iter()
                .map(|b| format!("{b:02x}"))
                .collect(),
            rows,
        })
    }
}

/// The records of a `complete` mark.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Seal {
    /// The shard the run planned.
    pub shard: Shard,
    /// The inputs' fingerprint (`config.json`'s `inputs_sha256`).
    pub inputs_sha256: String,
    /// Every file the run wrote, in the order written.
    pub files: Vec<SealedFile>,
}

impl Seal {
    fn text(&self) -> String {
        let mut text = format!(
            "seal {SEAL_VERSION}\nshard {}\ninputs_sha256 {}\n",
            self.shard, self.inputs_sha256
        );
        for f in &self.files {
            let rows = f.rows.map_or("-".to_string(), |n| n.to_string());
            text.push_str(&format!(
                "file {} sha256 {} rows {rows}\n",
                f.name, f.sha256
            ));
        }
        text
    }

    fn parse(text: &str) -> Option<Seal> {
        let mut lines = text.lines();
        if lines.next()? != format!("seal {SEAL_VERSION}") {
            return None;
        }
        let shard = Shard::parse(lines.next()?.strip_prefix("shard ")?).ok()?;
        let inputs_sha256 = lines.next()?.strip_prefix("inputs_sha256 ")?.to_string();
        let files = lines
            .map(|line| {
                let w: Vec<&str> = line.split(' ').collect();
                let ["file", name, "sha256", sha256, "rows", rows] = w[..] else {
                    return None;
                };
                let rows = match rows {
                    "-" => None,
                    n => Some(n.parse().ok()?),
                };
                Some(SealedFile {
                    name: name.to_string(),
                    sha256: sha256.to_string(),
                    rows,
                })
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Seal {
            shard,
            inputs_sha256,
            files,
        })
    }
}

/// Removes the completion mark of an earlier run in `dir` before a new run writes there, so a
/// run stopped half way never looks complete.
///
/// # Errors
/// [`Error::Io`] when the mark exists and cannot be removed.
pub fn unmark_complete(dir: &Path) -> Result<()> {
    match std::fs::remove_file(dir.join(COMPLETE_FILE)) {
        Err(e) if e.kind() != std::io::ErrorKind::NotFound => Err(Error::Io {
            path: dir.join(COMPLETE_FILE).display().to_string(),
            source: e,
        }),
        _ => Ok(()),
    }
}

/// Writes the mark of a finished run: `files` (written before, in that order) sealed.
///
/// # Errors
/// [`Error::Io`] when the mark cannot be written; E7009 when a file cannot be read back.
pub fn mark_complete(dir: &Path, config: &BenchConfig, files: &[String]) -> Result<()> {
    let seal = Seal {
        shard: config.shard,
        inputs_sha256: config.inputs_sha256.clone(),
        files: files
            .iter()
            .map(|name| SealedFile::of(dir, name))
            .collect::<Result<_>>()?,
    };
    crate::problem::io::write_whole(&dir.join(COMPLETE_FILE), seal.text().as_bytes())
}

/// Verifies `dir`'s seal: the mark is there and of this format (E7007, E7008), and every file
/// it seals has the bytes and the row count it had when the run finished (E7009).
///
/// # Errors
/// E7007 without a mark (the run did not finish), E7008 for a mark this version does not read,
/// E7009 naming the first file that differs.
pub fn verify_seal(dir: &Path) -> Result<Seal> {
    let path = dir.join(COMPLETE_FILE);
    if !dir.exists() {
        return Err(Error::invalid(
            "E7007",
            dir.display().to_string(),
            "no such directory: the run never started (a shard killed before it ran), or the \
             path is mistyped",
            "check the path; run that shard (the Slurm script reruns only the shards without \
             the mark)",
        ));
    }
    if !dir.is_dir() {
        return Err(Error::invalid(
            "E0008",
            dir.display().to_string(),
            "not a directory",
            "give the output directory of a `swarmplan bench` run (`--out DIR`)",
        ));
    }
    let text =
        match std::fs::read(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(Error::invalid(
                "E7007",
                dir.display().to_string(),
                "the run did not finish (no `complete` mark: it was stopped, or is still running)",
                "run it again (the Slurm script reruns only the shards without the mark)",
            )),
            Err(e) => {
                return Err(Error::invalid(
                    "E0008",
                    path.display().to_string(),
                    format!("cannot read the file: {e}"),
                    "check its read permission",
                ))
            }
            Ok(bytes) => String::from_utf8(bytes).unwrap_or_default(),
        };
    let Some(seal) = Seal::parse(&text) else {
        return Err(Error::invalid(
            "E7008",
            path.display().to_string(),
            format!(
                "not a `complete` mark this version writes (seal {SEAL_VERSION}: the shard, the \
                 inputs' fingerprint and the SHA-256 of every file)"
            ),
            "run the bench again with this version: the mark was edited, or an older version \
             wrote it",
        ));
    };
    for sealed in &seal.files {
        let found = SealedFile::of(dir, &sealed.name)?;
        if found != *sealed {
            let what = match (found.rows, sealed.rows) {
                (Some(n), Some(m)) if n != m => {
                    format!("has {n} rows where the run wrote {m}")
                }
                _ => "differs from the bytes the run wrote (SHA-256)".to_string(),
            };
            return Err(Error::invalid(
                "E7009",
                dir.join(&sealed.name).display().to_string(),
                format!("{what}: it was changed after the run"),
                "run the bench again (or that shard): results edited by hand are not merged or \
                 checked",
            ));
        }
    }
    Ok(seal)
}

/// E7009 when the run's `config.json` (already verified against the seal) is not the shard and
/// the inputs the seal names.
///
/// # Errors
/// E7009.
pub fn seal_agrees(dir: &Path, seal: &Seal, config: &BenchConfig) -> Result<()> {
    if seal.shard == config.shard && seal.inputs_sha256 == config.inputs_sha256 {
        return Ok(());
    }
    Err(Error::invalid(
        "E7009",
        dir.join(COMPLETE_FILE).display().to_string(),
        format!(
            "the mark names shard {} and inputs {}..., config.json shard {} and inputs {}...",
            seal.shard,
            seal.inputs_sha256.chars().take(12).collect::<String>(),
            config.shard,
            config.inputs_sha256.chars().take(12).collect::<String>()
        ),
        "run the bench again (or that shard): the mark belongs to another run",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_seal_reads_back_as_written() {
        let seal = Seal {
            shard: Shard { index: 2, count: 4 },
            inputs_sha256: "ab".repeat(32),
            files: vec![
                SealedFile {
                    name: "config.json".into(),
                    sha256: "01".repeat(32),
                    rows: None,
                },
                SealedFile {
                    name: "requests.csv".into(),
                    sha256: "ff".repeat(32),
                    rows: Some(120),
                },
            ],
        };
        assert_eq!(Seal::parse(&seal.text()), Some(seal.clone()));
        let old = "shard 2/4\ninputs_sha256 abab\n";
        assert_eq!(Seal::parse(old), None, "the mark of an older version");
        let torn = seal.text().replace(" rows 120", " rows");
        assert_eq!(Seal::parse(&torn), None);
    }

    #[test]
    fn the_row_count_is_the_records_of_a_table() {
        let dir = std::env::temp_dir().join(format!("swarmplan-seal-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("t.csv"), "a,b\n1,2\n3,4\n").unwrap();
        std::fs::write(dir.join("t.json"), "{}\n").unwrap();
        let t = SealedFile::of(&dir, "t.csv").unwrap();
        assert_eq!(t.rows, Some(2));
        // sha256("a,b\n1,2\n3,4\n"), computed with `sha256sum`.
        assert_eq!(
            t.sha256,
            "b9485148546419a0f6a85e8d708c923557c15d7f3c7d078ef1fa7f7c0f57d5a5"
        );
        assert_eq!(SealedFile::of(&dir, "t.json").unwrap().rows, None);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
