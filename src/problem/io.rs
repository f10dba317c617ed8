//! Reading and writing input files. A malformed file is a [`crate::Error::Invalid`] naming the file,
//! the line and column, never a panic.

use crate::error::{Error, Result};
use serde::de::DeserializeOwned;
use serde::Serialize;
use std::path::Path;

fn read_text(path: &Path) -> Result<String> {
    std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Parses JSON text; `origin` names the source in messages.
pub fn parse_json<T: DeserializeOwned>(text: &str, origin: &str) -> Result<T> {
    serde_json::from_str(text).map_err(|e| {
        Error::invalid(
            "E0001",
            origin,
            format!(
                "malformed JSON at line {} column {}: {e}",
                e.line(),
                e.column()
            ),
            "fix the JSON syntax or the field named; see README.md for the schema",
        )
    })
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

/// Writes a value as pretty JSON with a trailing newline.
pub fn write_json<T: Serialize>(path: &Path, value: &T) -> Result<()> {
    let mut text = serde_json::to_string_pretty(value).expect("serialising plain data cannot fail");
    text.push('\n');
    std::fs::write(path, text).map_err(|source| Error::Io {
        path: path.display().to_string(),
        source,
    })
}
