//! `swarmplan.SwarmplanError` and the core's errors in the package's words: every
//! command-line option of a message becomes its keyword (`--route optimal` is
//! `route="optimal"`).

use pyo3::exceptions::PyException;
use pyo3::prelude::*;
use pythonize::pythonize;
use swarmplan::compose::{HopPaths, RouteMethod};
use swarmplan::eaas::exact::Reorder;
use swarmplan::eaas::SharingPolicy;
use swarmplan::error::{Error, Violation};
use swarmplan::precompose::Positioning;

use crate::args::value_names;

pyo3::create_exception!(
    swarmplan,
    SwarmplanError,
    PyException,
    "An error of swarmplan, with the code of the error table (docs/src/errors.md).\n\n\
     Attributes\n\
     ----------\n\
     code : str or None\n    \
     The first violation's code, such as \"E4111\" or a checker code \"C3006\".\n\
     field : str or None\n    \
     The argument or field concerned, in the package's names (\"index\", \"route\").\n\
     cause : str or None\n    \
     What is wrong.\n\
     action : str or None\n    \
     What to do.\n\
     violations : list of dict\n    \
     Every broken rule, each with the keys code, field, cause and action.\n"
);

/// Result of the crate.
pub(crate) type Result<T> = swarmplan::error::Result<T>;

/// One coded violation, for a Python-side input the crate's serde could not read.
pub(crate) fn invalid(code: &'static str, field: &str, cause: String, action: &str) -> Error {
    Error::Invalid(vec![Violation::new(code, field, cause, action)])
}

/// The crate's error as a `SwarmplanError` with its code, field, cause, action and every
/// violation.
pub(crate) fn to_py_err(py: Python<'_>, e: Error) -> PyErr {
    let violations = match &e {
        Error::Invalid(list) => list.clone(),
        Error::Io { path, source } => vec![Violation::new(
            "E0010",
            path.clone(),
            source.to_string(),
            "check that the directory exists and is writable",
        )],
        Error::Output(source) => vec![Violation::new(
            "E0010",
            "output",
            source.to_string(),
            "check the output stream",
        )],
        Error::Backend {
            backend, message, ..
        } => vec![Violation::new(
            "E0027",
            backend.clone(),
            message.clone(),
            "report it with the instance and the call",
        )],
        Error::Internal { code, context } => vec![Violation::new(
            code,
            "internal",
            context.clone(),
            "a bug: report it with the instance and the call",
        )],
    };
    let violations: Vec<Violation> = violations.into_iter().map(in_python_words).collect();
    let message = match &e {
        Error::Invalid(_) => Error::Invalid(violations.clone()).to_string(),
        other => in_python_text(&other.to_string()),
    };
    let err = SwarmplanError::new_err(message);
    let value = err.value(py);
    let first = violations.first();
    let set = || -> PyResult<()> {
        value.setattr("code", first.map(|v| v.code))?;
        value.setattr("field", first.map(|v| v.field.clone()))?;
        value.setattr("cause", first.map(|v| v.cause.clone()))?;
        value.setattr("action", first.map(|v| v.action.clone()))?;
        value.setattr("violations", pythonize(py, &violations)?)?;
        Ok(())
    };
    match set() {
        Ok(()) => err,
        Err(other) => other,
    }
}

/// The Python name of a command-line option of the core's messages: the keyword of the same
/// meaning (`--hop-time-limit` is `hop_time_limit_s`, `--hop` the hop's `index`, `--count` the
/// number of `requests` of `Instance.generate`, `--request-limit` the `limit` of `bench`, `--time-budget` its `time_budget_s`), else
/// the option with underscores (`--hop-paths` is `hop_paths`).
pub(crate) fn python_name(flag: &str) -> String {
    match flag {
        "hop-time-limit" => "hop_time_limit_s".into(),
        "time-limit" => "time_limit_s".into(),
        "hop" => "index".into(),
        "count" => "requests".into(),
        "request-limit" => "limit".into(),
        "time-budget" => "time_budget_s".into(),
        other => other.replace('-', "_"),
    }
}

/// The names a choice takes (`"pb"`, `"optimal"`), for the options whose value a message
/// quotes.
pub(crate) fn choice_names(flag: &str) -> Vec<String> {
    match flag {
        "route" => value_names::<RouteMethod>(),
        "sharing" => value_names::<SharingPolicy>(),
        "positioning" => value_names::<Positioning>(),
        "hop-paths" => value_names::<HopPaths>(),
        "reorder" => value_names::<Reorder>(),
        "backend" => swarmplan::solver::known_backend_names()
            .map(String::from)
            .collect(),
        _ => Vec::new(),
    }
}

/// A message of the core in the package's words: every command-line option outside backticks
/// becomes its keyword, with its value when one follows (`--route optimal` is
/// `route="optimal"`, `--support 32` is `support=32`); commands in backticks stay as written.
pub(crate) fn in_python_text(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut quoted = false;
    let mut rest = text;
    while let Some(c) = rest.chars().next() {
        if c == '`' {
            quoted = !quoted;
        }
        let after = &rest[c.len_utf8()..];
        let flag_len = after
            .strip_prefix('-')
            .map(|f| {
                f.bytes()
                    .take_while(|b| b.is_ascii_lowercase() || *b == b'-')
                    .count()
            })
            .unwrap_or(0);
        let starts_word = !out.ends_with(|p: char| p.is_alphanumeric() || p == '-');
        if quoted || c != '-' || flag_len == 0 || !starts_word {
            out.push(c);
            rest = after;
            continue;
        }
        let flag = after[1..1 + flag_len].trim_end_matches('-');
        rest = &after[1 + flag.len()..];
        let name = python_name(flag);
        let word_len = rest
            .strip_prefix(' ')
            .map(|w| {
                w.bytes()
                    .take_while(|b| b.is_ascii_alphanumeric() || *b == b'-' || *b == b'.')
                    .count()
            })
            .unwrap_or(0);
        let word = if word_len > 0 {
            &rest[1..1 + word_len]
        } else {
            ""
        };
        let word = word.trim_end_matches('.');
        if !word.is_empty() && choice_names(flag).iter().any(|n| n == word) {
            out.push_str(&format!("{name}=\"{word}\""));
            rest = &rest[1 + word.len()..];
        } else if !word.is_empty() && word.parse::<f64>().is_ok() {
            out.push_str(&format!("{name}={word}"));
            rest = &rest[1 + word.len()..];
        } else {
            out.push_str(&name);
        }
    }
    out
}

/// A violation of the core in the package's words: its field the keyword concerned
/// (`--route optimal` is `route`), its cause and action without command-line options
/// ([`in_python_text`]), and the actions that only a command line can follow replaced.
pub(crate) fn in_python_words(v: Violation) -> Violation {
    let field = match (v.code, v.field.as_str()) {
        ("E4110", "hop") => "index".to_string(),
        (_, f) if f.starts_with("--") => {
            let flag = f[2..].split(' ').next().unwrap_or("");
            python_name(flag)
        }
        (_, f) => in_python_text(f),
    };
    let action = match v.code {
        "E4113" => "give reorder=\"paper\" or \"none\": a free schedule is not always a set of \
                    transfers a plan can carry (Hop.solve(reorder=\"free\") studies one hop)"
            .to_string(),
        "E4117" => "give reorder=\"paper\" or \"none\" (fewer moves); the largest number of \
                    configurations is the command line's (swarmplan eaas --max-configurations)"
            .to_string(),
        "E0011" => "install the package built with its default features (a MILP backend), or \
                    use a method without a MILP (sharing=\"pb\" or \"fb\"; Hop.solve with \
                    \"pb\", \"fb\", \"fluid\" or \"fair\")"
            .to_string(),
        "E8001" => "compare two plans of the same request, such as instance.plan(r) and \
                    instance.plan(r, route=\"optimal\", sharing=\"exact\")"
            .to_string(),
        "E6004" => "draw it on the instance it was made on: swarmplan.plot(plan) takes a Plan's \
                    own; Instance.plot needs an instance of the same network"
            .to_string(),
        "E6005" => "draw it on the instance it was made on: swarmplan.plot(plan) takes a Plan's \
                    own; Instance.plot needs an instance with the same profile (and literal=True \
                    if it was planned so)"
            .to_string(),
        _ => in_python_text(&v.action),
    };
    Violation {
        code: v.code,
        field,
        cause: in_python_text(&v.cause),
        action,
    }
}
