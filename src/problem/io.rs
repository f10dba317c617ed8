//! Reading and writing input files. A malformed file is a [`crate::error::Error::Invalid`] naming the file,
//! the line and column, never a panic.

use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;

/// Reads a text file whole. A leading UTF-8 byte-order mark (U+FEFF, written by some editors)
/// is dropped, so every reader of JSON, TOML and P||Cmax files accepts it.
///
/// # Errors
/// [`Error::Invalid`] with `E0008` when the file cannot be read (missing, a directory, no
/// permission) and `E0009` when it is not UTF-8 text (the line and column of the first bad byte).
pub fn read_text(path: &Path) -> Result<String> {
    let origin = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| {
        Error::invalid(
            "E0008",
            origin.as_str(),
            format!("cannot read the file: {e}"),
            "check the path, that it names a file and not a directory, and its read permission",
        )
    })?;
    let text = String::from_utf8(bytes).map_err(|e| {
        let good = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
        let column = 1 + good.iter().rev().take_while(|&&b| b != b'\n').count();
        Error::invalid(
            "E0009",
            origin.as_str(),
            format!(
                "not UTF-8 text: invalid byte at line {line} column {column} (byte {})",
                good.len()
            ),
            "save the file as UTF-8 (JSON and TOML files are UTF-8 text)",
        )
    })?;
    Ok(match text.strip_prefix('\u{feff}') {
        Some(rest) => rest.to_string(),
        None => text,
    })
}

/// Parses JSON text; `origin` names the source in messages.
pub fn parse_json<T: DeserializeOwned>(text: &str, origin: &str) -> Result<T> {
    from_json(text).map_err(|e| {
        Error::invalid(
            "E0001",
            e.field(origin),
            format!(
                "malformed JSON at line {} column {}: {}",
                e.error.line(),
                e.error.column(),
                e.error
            ),
            "fix the JSON syntax or the field named; see docs/src/inputs.md for the schema",
        )
    })
}

/// A JSON error with the path of the field it happened in.
#[derive(Debug)]
pub struct JsonError {
    /// serde_json's error (line, column, what).
    pub error: serde_json::Error,
    /// The field's path, `requests[3].packages_kg[0]`; empty at the top level, for a syntax
    /// error and for an early end.
    pub path: String,
}

impl JsonError {
    /// `origin` followed by the field's path, when there is one: `requests.json:
    /// requests[3].packages_kg[0]`.
    pub fn field(&self, origin: &str) -> String {
        if self.path.is_empty() {
            origin.to_string()
        } else {
            format!("{origin}: {}", self.path)
        }
    }
}

impl std::fmt::Display for JsonError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.path.is_empty() {
            write!(f, "{}", self.error)
        } else {
            write!(f, "{}: {}", self.path, self.error)
        }
    }
}

/// Deserialises JSON text as `serde_json::from_str` does (the whole text, nothing after the
/// value), the error carrying the path of the field it happened in.
///
/// # Errors
/// The [`JsonError`].
pub fn from_json<T: DeserializeOwned>(text: &str) -> std::result::Result<T, JsonError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let value = serde_path_to_error::deserialize(&mut de).map_err(|e| {
        let path = e.path().to_string();
        let error = e.into_inner();
        // A syntax error or an early end has no field to name (the path ends in `?`).
        let named = error.is_data() && path != ".";
        JsonError {
            error,
            path: if named { path } else { String::new() },
        }
    })?;
    de.end().map_err(|error| JsonError {
        error,
        path: String::new(),
    })?;
    Ok(value)
}

/// Parses TOML text; `origin` names the source in messages.
pub fn parse_toml<T: DeserializeOwned>(text: &str, origin: &str) -> Result<T> {
    toml::from_str(text).map_err(|e| {
        Error::invalid(
            "E0002",
            origin,
            format!("malformed TOML: {}", e.to_string().trim_end()),
            "fix the TOML syntax or the field named; compare with instances/profiles/paper.toml",
        )
    })
}

/// Reads and parses a JSON file.
pub fn read_json<T: DeserializeOwned>(path: &Path) -> Result<T> {
    parse_json(&read_text(path)?, &path.display().to_string())
}

/// Reads and parses a TOML file.
pub fn read_toml<T: DeserializeOwned>(path: &Path) -> Result<T> {
    parse_toml(&read_text(path)?, &path.display().to_string())
}

/// Writes a value as pretty JSON with a trailing newline: to standard output when `path` is
/// `-`, else through [`write_whole`] (never a half-written file).
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value).expect("serialising plain data cannot fail");
    text.push('\n');
    if path == Path::new("-") {
        use std::io::Write;
        let mut out = std::io::stdout().lock();
        return out
            .write_all(text.as_bytes())
            .and_then(|()| out.flush())
            .map_err(Error::from_output);
    }
    write_whole(path, text.as_bytes())
}

/// Writes `bytes` to `path` whole: into a temporary file beside it, then renamed over it, so a
/// reader (or a run stopped midway) never sees a half-written file. A path that exists and is
/// not a regular file (a device such as `/dev/null`, a pipe) is written directly.
///
/// # Errors
/// E0010: [`Error::Invalid`] when `path` is a directory ([`refuse_directory`]), [`Error::Io`]
/// when the file cannot be written.
pub fn write_whole(path: &Path, bytes: &[u8]) -> Result<()> {
    refuse_directory(path)?;
    let io = |source| Error::Io {
        path: path.display().to_string(),
        source,
    };
    let regular_or_new = std::fs::metadata(path).map_or(true, |m| m.is_file());
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let (true, Some(name)) = (regular_or_new, name) else {
        return std::fs::write(path, bytes).map_err(io);
    };
    let temporary = path.with_file_name(format!(".{name}.{}.partial", std::process::id()));
    std::fs::write(&temporary, bytes).map_err(io)?;
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        io(e)
    })
}

/// `E0010` when `path` is a directory: an output is written to a file, never into a folder by
/// a name of the tool's choosing. Checked by [`write_whole`], and by the command line before
/// any work (`-o`, `--write-lp` and the other options that name an output file).
///
/// # Errors
/// [`Error::Invalid`] with `E0010`, naming the path.
pub fn refuse_directory(path: &Path) -> Result<()> {
    if !path.is_dir() {
        return Ok(());
    }
    Err(Error::invalid(
        "E0010",
        path.display().to_string(),
        "the output path is a directory; an output is written to a file",
        format!(
            "give the path of a file, such as {} inside it",
            path.join("FILE").display()
        ),
    ))
}

/// The name a value goes by in JSON (`diamond`, `optimal`, `time_limit_no_solution`), so that
/// human output, the checker's messages and `--json` speak of the same things with the same
/// words. A number is its JSON text, `None` is `null`, a list or a struct its compact JSON.
///
/// # Example
/// ```
/// use swarmplan::problem::io::json_name;
/// use swarmplan::problem::FormationKind;
/// assert_eq!(json_name(&FormationKind::Diamond), "diamond");
/// assert_eq!(json_name(&Some(0.5)), "0.5");
/// assert_eq!(json_name(&None::<f64>), "null");
/// ```
pub fn json_name<T: serde::Serialize>(value: &T) -> String {
    match serde_json::to_value(value) {
        Ok(serde_json::Value::String(s)) => s,
        Ok(other) => other.to_string(),
        Err(_) => String::new(),
    }
}
