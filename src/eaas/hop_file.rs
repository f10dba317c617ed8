//! Hop files: one hop's sharing problem as JSON, so that it can be solved again, changed or
//! handed to others without the network, the request and the planner that produced it.
//!
//! ```json
//! {"schema_version": 1, "request_id": "r00001", "hop_index": 0, "from": "n000", "to": "n012",
//!  "path": ["n000", "n007", "n012"], "profile": "paper",
//!  "end": {"pads": 3, "pad_rate_mah_per_min": 100.0},
//!  "hop": { ...a HopProblem... }}
//! ```
//!
//! `end` holds the pads at the hop's end node, or is `null` (or absent) when that node has none,
//! as at a request's destination; it decides the objective of the exact models
//! ([`HopFile::objective`]). The other fields besides `hop` record where the hop comes from
//! (`made_on`, optional: the fingerprint of the network and profile it was taken from).
//! Unknown fields are rejected; codes `E4111` (unreadable file), `E4112` (schema version),
//! `E4115` (path and ends disagree), and the hop's and the end's own rules (`E4001`-`E4013`,
//! `E4103`, `E4104`) under `hop.` and `end.`.

use super::exact::{validate_objective, Objective};
use super::{validate, HopProblem};
use crate::error::{Error, Result, Violation};
use serde::{Deserialize, Serialize};
use std::path::Path;

/// The only schema version of hop files.
pub const HOP_FILE_SCHEMA_VERSION: u32 = 1;

use super::exact::EndPads;

/// One hop of a request's plan, with where it comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopFile {
    /// Must equal [`HOP_FILE_SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Id of the request whose plan holds the hop.
    pub request_id: String,
    /// Index of the hop in that plan (0 = the first hop).
    pub hop_index: usize,
    /// Node the hop leaves from.
    pub from: String,
    /// Node the hop ends at.
    pub to: String,
    /// Node ids flown over, `from` first and `to` last.
    pub path: Vec<String>,
    /// Name of the parameter profile the hop was built with, when known.
    #[serde(default)]
    pub profile: Option<String>,
    /// Pads at `to`, or `None` when it has none (a request's destination).
    pub end: Option<EndPads>,
    /// The network and profile the hop was taken from, when known.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub made_on: Option<crate::problem::fingerprint::Fingerprint>,
    /// The plan the hop was taken from: `hop_index` is the hop's index in the plan of the
    /// request made with this combination (`check --hop-file` plans it again and compares the
    /// path). Absent for a hop of a route the file does not record (`evaluate`'s stops, a hop
    /// built by hand): `hop_index` is then the hop's place in that route, and is not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub plan: Option<HopPlan>,
    /// The hop's sharing problem.
    pub hop: HopProblem,
}

/// The method combination of the plan a hop file's hop was taken from, by the names the
/// command line and plan files use (`route`: a `RouteMethod`'s name, such as `sequential`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HopPlan {
    /// The sharing policy of the plan.
    pub sharing: super::SharingPolicy,
    /// The support drones' initial positioning.
    pub positioning: crate::precompose::Positioning,
    /// The route method.
    pub route: String,
    /// Support drones fixed by the user, if any.
    #[serde(default)]
    pub support: Option<usize>,
}

impl HopFile {
    /// The objective of the exact models on this hop: the node time on `end`'s pads, or the
    /// lowest delivery arrival battery when the hop ends without pads.
    pub fn objective(&self) -> Objective {
        match self.end {
            Some(e) => Objective::NodeTime(EndPads {
                pads: e.pads,
                pad_rate_mah_per_min: e.pad_rate_mah_per_min,
            }),
            None => Objective::MaxMinArrival,
        }
    }

    /// Every broken rule of the file, each field named from the file's top level.
    pub fn violations(&self) -> Vec<Violation> {
        let mut v = Vec::new();
        if self.schema_version != HOP_FILE_SCHEMA_VERSION {
            v.push(version_violation(self.schema_version));
        }
        if self.path.first() != Some(&self.from) || self.path.last() != Some(&self.to) {
            v.push(Violation::new(
                "E4115",
                "path",
                format!(
                    "path {:?} does not lead from `{}` to `{}`",
                    self.path, self.from, self.to
                ),
                "give the node ids flown over, `from` first and `to` last",
            ));
        }
        // One leg per edge of the path: `path.len() = legs + 1`, and a hop flies at least one.
        let legs = self.hop.legs.len();
        if legs == 0 || self.path.len() != legs + 1 {
            v.push(Violation::new(
                "E4115",
                "path",
                format!(
                    "path {:?} has {} node(s) for {legs} leg(s): a hop flies one leg per edge of \
                     its path, at least one",
                    self.path,
                    self.path.len()
                ),
                "give the path the hop's legs fly (one more node than legs), or write the hop \
                 again with `swarmplan eaas --write-hop`",
            ));
        }
        let prefixed = |e: Error, prefix: &str| match e {
            Error::Invalid(list) => list
                .into_iter()
                .map(|mut x| {
                    x.field = format!("{prefix}.{}", x.field);
                    x
                })
                .collect(),
            other => vec![Violation::new(
                "E4111",
                prefix,
                other.to_string(),
                "check the file",
            )],
        };
        if let Err(e) = validate(&self.hop) {
            v.extend(prefixed(e, "hop"));
        }
        if let Err(e) = validate_objective(&self.objective()) {
            v.extend(prefixed(e, "end"));
        }
        v
    }
}

fn version_violation(version: u32) -> Violation {
    Violation::new(
        "E4112",
        "schema_version",
        format!("schema_version is {version}, this build reads {HOP_FILE_SCHEMA_VERSION}"),
        format!(
            "write the hop again with this build's `swarmplan eaas --write-hop`, or set \
             schema_version to {HOP_FILE_SCHEMA_VERSION} after checking the file against \
             docs/src/commands/eaas.md, \"Files\""
        ),
    )
}

/// Reads and checks a hop file.
///
/// # Arguments
/// * `path` - the JSON file, as [`write_hop_file`] writes it.
///
/// # Returns
/// The hop file, its hop valid for every sharing policy and exact model.
///
/// # Errors
/// [`Error::Invalid`] with `E0008` or `E0009` when the file cannot be read or is not UTF-8
/// text, else those of [`parse_hop_file`].
pub fn read_hop_file(path: &Path) -> Result<HopFile> {
    let text = crate::problem::io::read_text(path)?;
    parse_hop_file(&text, &path.display().to_string())
}

/// Parses and checks the text of a hop file; `origin` names its source in messages.
///
/// # Errors
/// [`Error::Invalid`] with `E4111` for malformed JSON, an unknown, missing or mistyped field
/// (line and column), `E4112` alone for another schema version, else every violation of
/// [`HopFile::violations`] at once.
pub fn parse_hop_file(text: &str, origin: &str) -> Result<HopFile> {
    let unreadable = |e: crate::problem::io::JsonError| {
        Error::invalid(
            "E4111",
            origin,
            format!("not a hop file: {e}"),
            "write hop files with `swarmplan eaas --write-hop`; see docs/src/commands/eaas.md, \
             \"Files\", for the fields",
        )
    };
    // The version first: another version may have other fields.
    #[derive(Deserialize)]
    struct Version {
        schema_version: Option<u32>,
    }
    let version: Version = crate::problem::io::from_json(text).map_err(unreadable)?;
    if let Some(v) = version
        .schema_version
        .filter(|&v| v != HOP_FILE_SCHEMA_VERSION)
    {
        return Err(Error::Invalid(vec![version_violation(v)]));
    }
    let file: HopFile = crate::problem::io::from_json(text).map_err(unreadable)?;
    let violations = file.violations();
    if violations.is_empty() {
        Ok(file)
    } else {
        Err(Error::Invalid(violations))
    }
}

/// Writes a hop file as pretty JSON.
///
/// # Errors
/// [`Error::Io`] when the file cannot be written.
pub fn write_hop_file(path: &Path, file: &HopFile) -> Result<()> {
    crate::problem::io::write_json(path, file)
}
