//! Plan files: the document `swarmplan solve --json` prints (a [`RequestReport`]: the request,
//! the method combination, the swarm and the plan, under a `schema_version`), read back so that
//! the plan can be re-verified by [`super::check_report`] without the planner.
//!
//! A malformed file is an [`Error::Invalid`] with a code, never a panic: `E0008`/`E0009` for a
//! file that cannot be read or is not UTF-8, `E6001` for text that is not JSON, `E6002` for a
//! missing or other `schema_version`, `E6003` for JSON that is not a plan document (an unknown,
//! missing or mistyped field), each with the line and column serde reports.

use crate::compose::RequestReport;
use crate::error::{Error, Result};
use crate::problem::SCHEMA_VERSION;
use std::path::Path;

/// Reads a plan file.
///
/// # Arguments
/// * `path` - the JSON file, as `swarmplan solve --json` writes it.
///
/// # Returns
/// The document; its plan is not checked yet (see [`super::check_report`]).
///
/// # Errors
/// [`Error::Invalid`] with `E0008` or `E0009` when the file cannot be read or is not UTF-8
/// text, else those of [`parse_plan_file`].
pub fn read_plan_file(path: &Path) -> Result<RequestReport> {
    let text = crate::problem::io::read_text(path)?;
    parse_plan_file(&text, &path.display().to_string())
}

/// Parses the text of a plan file; `origin` names its source in messages.
///
/// # Errors
/// [`Error::Invalid`] with one violation: `E6001` when the text is not JSON, `E6002` when its
/// `schema_version` is missing or not [`SCHEMA_VERSION`] (checked first: another version may
/// have other fields), `E6003` when it is JSON but not a plan document.
///
/// # Example
/// ```
/// use swarmplan::check::plan_file::parse_plan_file;
/// let e = parse_plan_file(r#"{"schema_version": 99}"#, "plan.json").unwrap_err();
/// assert!(e.to_string().contains("[E6002]"));
/// ```
pub fn parse_plan_file(text: &str, origin: &str) -> Result<RequestReport> {
    let unreadable = |e: crate::problem::io::JsonError| {
        let (code, what) = if e.error.is_syntax() || e.error.is_eof() {
            ("E6001", "not JSON")
        } else {
            ("E6003", "not a plan document")
        };
        Error::invalid(
            code,
            origin,
            format!("{what}: {e}"),
            "give the JSON that `swarmplan solve --json` prints, unchanged in its fields; see \
             docs/src/commands/solve.md, \"The plan document\"",
        )
    };
    // The version first: another version may have other fields.
    let document: serde_json::Value = crate::problem::io::from_json(text).map_err(unreadable)?;
    let Some(fields) = document.as_object() else {
        return Err(Error::invalid(
            "E6003",
            origin,
            "not a plan document: the top level is not a JSON object",
            "give the JSON object that `swarmplan solve --json` prints",
        ));
    };
    match fields.get("schema_version") {
        Some(v) if v.as_u64() == Some(u64::from(SCHEMA_VERSION)) => {}
        found => {
            let found = found.map_or("missing".to_string(), |v| v.to_string());
            return Err(Error::invalid(
                "E6002",
                format!("{origin}: schema_version"),
                format!("schema_version is {found}, this build reads {SCHEMA_VERSION}"),
                "write the plan again with this build's `swarmplan solve --json`",
            ));
        }
    }
    crate::problem::io::from_json(text).map_err(unreadable)
}
