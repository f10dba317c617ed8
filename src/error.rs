//! The library's one error type. Outcomes of a solve (optimal, feasible, infeasible) are data, not
//! errors: `Err` is for bad input and for a backend that broke.
//! User guide: "Error codes" (`docs/src/errors.md`), one table of every code.

use serde::Serialize;
use std::fmt;

/// One broken input rule: a stable code, the field it concerns, what is wrong and what to do.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Violation {
    /// Stable rule code, such as `E1101`; listed in the guide's error table, docs/src/errors.md.
    pub code: &'static str,
    /// Where the problem is, such as `edges[3].wind_speed_mps` or `--pads`.
    pub field: String,
    /// What is wrong, with the offending value.
    pub cause: String,
    /// What to do about it.
    pub action: String,
}

impl Violation {
    /// Builds a violation from its four parts.
    pub fn new(
        code: &'static str,
        field: impl Into<String>,
        cause: impl Into<String>,
        action: impl Into<String>,
    ) -> Self {
        Violation {
            code,
            field: field.into(),
            cause: cause.into(),
            action: action.into(),
        }
    }
}

impl fmt::Display for Violation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "[{}] {}: {}; {}",
            self.code, self.field, self.cause, self.action
        )
    }
}

/// A violation alone is an error too: the command-line parsers return it to clap.
impl std::error::Error for Violation {}

/// Errors of the library.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// The input breaks one or more rules; every violation found is listed, not only the first.
    #[error("invalid input, {} problem(s):\n{}", .0.len(), list(.0))]
    Invalid(Vec<Violation>),
    /// A file could not be written (`E0010`). A file that cannot be read is an [`Error::Invalid`]
    /// with `E0008` or `E0009`.
    #[error(
        "[E0010] {path}: cannot write the file: {source}; check that its directory exists and \
         is writable and that its disk has space"
    )]
    Io {
        /// The path concerned.
        path: String,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The results could not be written to standard output (`E0010`, as a file that cannot be
    /// written); a closed pipe is told apart by [`Error::is_broken_pipe`].
    #[error(
        "[E0010] standard output: cannot write the results: {0}; check where \
         standard output goes: the disk it writes to may be full"
    )]
    Output(#[source] std::io::Error),
    /// A broken invariant of the tool's own code, a bug (never bad input, never a solve
    /// outcome): `code` names the invariant (the error table, docs/src/errors.md), `context`
    /// where it broke.
    /// Retries of a failed solve never match it.
    #[error(
        "[{code}] internal error: {context}; this is a bug: report it with the instance and the \
         command"
    )]
    Internal {
        /// The invariant's code.
        code: &'static str,
        /// Where and how it broke.
        context: String,
    },
    /// An optimization backend failed in a way that is not a solve outcome.
    #[error("solver backend {backend} failed: {message}")]
    Backend {
        /// What kind of failure: what a retry matches on.
        kind: BackendFailure,
        /// The backend's name.
        backend: String,
        /// What it reported.
        message: String,
    },
}

/// The kinds of [`Error::Backend`]. Infeasibility and a limit with an incumbent are solve
/// outcomes, never errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BackendFailure {
    /// The solver failed while solving: an error of its own, a status that cannot occur for the
    /// model (unbounded where every variable is bounded), or a solution that breaks the model.
    /// A retry on a rescaled or reordered model may succeed.
    Numerical,
    /// A limit stopped the solve before it had the answer the caller needs.
    Limit,
    /// The backend refused the problem as built (inconsistent dimensions).
    Refused,
    /// A model could not be captured or written as a file.
    LostModel,
}

fn list(violations: &[Violation]) -> String {
    violations
        .iter()
        .map(|v| format!("  {v}"))
        .collect::<Vec<_>>()
        .join("\n")
}

impl Error {
    /// An [`Error::Internal`]: the invariant `code` broke, `context` says where.
    pub fn internal(code: &'static str, context: impl Into<String>) -> Self {
        Error::Internal {
            code,
            context: context.into(),
        }
    }

    /// An [`Error::Backend`] of kind `kind` from `backend`, in its words `message`.
    pub fn backend(
        kind: BackendFailure,
        backend: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Error::Backend {
            kind,
            backend: backend.into(),
            message: message.into(),
        }
    }

    /// A single-violation [`Error::Invalid`].
    pub fn invalid(
        code: &'static str,
        field: impl Into<String>,
        cause: impl Into<String>,
        action: impl Into<String>,
    ) -> Self {
        Error::Invalid(vec![Violation::new(code, field, cause, action)])
    }

    /// Process exit code: 2 for bad input (including files that cannot be read or written, and
    /// a standard output that cannot be written), 1 for a failed run.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Invalid(_) | Error::Io { .. } | Error::Output(_) => 2,
            Error::Backend { .. } | Error::Internal { .. } => 1,
        }
    }

    /// An [`Error::Output`] from a failed write to stdout.
    pub fn from_output(e: std::io::Error) -> Self {
        Error::Output(e)
    }

    /// Whether this is a write to a closed pipe (the reader stopped early, as `| head` does).
    pub fn is_broken_pipe(&self) -> bool {
        matches!(self, Error::Output(e) if e.kind() == std::io::ErrorKind::BrokenPipe)
    }
}

/// Result alias of the library.
pub type Result<T> = std::result::Result<T, Error>;

/// Both results, or every violation of both ([`Error::Invalid`] lists joined, first `a`'s);
/// another error of either is returned alone, `a`'s first.
///
/// # Errors
/// The errors of `a` and `b`, as above.
pub fn both<A, B>(a: Result<A>, b: Result<B>) -> Result<(A, B)> {
    match (a, b) {
        (Ok(a), Ok(b)) => Ok((a, b)),
        (Err(Error::Invalid(mut first)), Err(Error::Invalid(second))) => {
            first.extend(second);
            Err(Error::Invalid(first))
        }
        (Err(e), _) | (_, Err(e)) => Err(e),
    }
}

/// A number as a message shows it: plain between `1e-4` and `1e9` in magnitude (and 0), in
/// scientific notation beyond, so that `1e308` does not print as 309 digits.
pub fn show(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e9).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}
