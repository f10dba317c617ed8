//! Delivery requests: Definition 2 of the paper, `<alpha, beta, P>`.

use serde::{Deserialize, Serialize};

/// A set of requests, read from JSON.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RequestSet {
    /// Schema version, must equal [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// The seed the set was generated with, if generated.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The requests.
    pub requests: Vec<Request>,
}

/// The id of a request given on the command line (`solve --from --to --packages`).
pub const COMMAND_LINE_REQUEST_ID: &str = "cli";
/// The id of a request given as a Python dict without an id.
pub const PYTHON_REQUEST_ID: &str = "python";

impl Request {
    /// Whether the request was given inline (on the command line or as a Python dict without an
    /// id), not read from a request set: a plan of it carries its own request, which `check`
    /// takes when the request set has no request of that id.
    pub fn is_inline(&self) -> bool {
        self.id == COMMAND_LINE_REQUEST_ID || self.id == PYTHON_REQUEST_ID
    }
}

/// One request: deliver every package from `source` to `destination`, one delivery drone per package.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Unique id within its set.
    pub id: String,
    /// Source node id (alpha).
    pub source: String,
    /// Destination node id (beta).
    pub destination: String,
    /// Package masses in kg (P); one delivery drone per package.
    pub packages_kg: Vec<f64>,
}
