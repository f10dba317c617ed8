//! The instances shipped in the binary, by name: networks, profiles and the request set, so that
//! every front end (the command line, the Python package) plans on the same files without a path.

use super::{io, validate, Instance, Network, Profile, RequestSet};
use crate::error::{Error, Result};

/// A network and profile shipped in the binary, used when no file is given.
#[derive(Debug, Clone, Copy)]
pub struct Shipped {
    /// The network's JSON.
    pub network: &'static str,
    /// Its name in messages and reports.
    pub network_name: &'static str,
    /// The profile's TOML.
    pub profile: &'static str,
    /// Its name in messages and reports.
    pub profile_name: &'static str,
}

/// paper-195 with the `paper` profile: the default of every planning command but `bench`.
pub const PAPER_195: Shipped = Shipped {
    network: include_str!("../../instances/paper-195/network.json"),
    network_name: "embedded paper-195 network",
    profile: include_str!("../../instances/profiles/paper.toml"),
    profile_name: "embedded paper profile",
};

/// findings-195 with the `paper-findings` profile: the instance of the paper's findings, the
/// default of `bench`.
pub const FINDINGS_195: Shipped = Shipped {
    network: include_str!("../../instances/findings-195/network.json"),
    network_name: "embedded findings-195 network",
    profile: include_str!("../../instances/profiles/paper-findings.toml"),
    profile_name: "embedded paper-findings profile",
};

/// The shipped request set (10,000 requests over the 195 nodes shared by the three networks).
pub const REQUESTS: &str = include_str!("../../instances/paper-195/requests.json");

/// Its name in messages and reports.
pub const REQUESTS_NAME: &str = "embedded paper-195 requests";

/// Shipped networks: name, JSON, the profile each is planned with by default.
pub const NETWORKS: [(&str, &str, &str); 3] = [
    ("paper-195", PAPER_195.network, "paper"),
    ("findings-195", FINDINGS_195.network, "paper-findings"),
    (
        "sparse-195",
        include_str!("../../instances/sparse-195/network.json"),
        "paper",
    ),
];

/// Shipped profiles: name, TOML.
pub const PROFILES: [(&str, &str); 4] = [
    ("paper", PAPER_195.profile),
    ("paper-findings", FINDINGS_195.profile),
    (
        "fast-sharing",
        include_str!("../../instances/profiles/fast-sharing.toml"),
    ),
    (
        "redundancy-levels",
        include_str!("../../instances/profiles/redundancy-levels.toml"),
    ),
];

fn unknown(code: &'static str, field: &str, name: &str, known: Vec<&str>) -> Error {
    Error::invalid(
        code,
        field,
        format!("no shipped {field} is called `{name}`"),
        format!("give one of {}, or a file", known.join(", ")),
    )
}

/// Reads a shipped network by name (E0020 for an unknown name).
///
/// # Errors
/// [`Error::Invalid`] E0020.
pub fn network(name: &str) -> Result<Network> {
    let (_, text, _) = NETWORKS
        .iter()
        .find(|(n, _, _)| *n == name)
        .ok_or_else(|| unknown("E0020", "network", name, NETWORKS.map(|x| x.0).to_vec()))?;
    io::parse_json(text, &format!("embedded {name} network"))
}

/// Reads a shipped profile by name (E0021 for an unknown name), not validated.
///
/// # Errors
/// [`Error::Invalid`] E0021.
pub fn profile(name: &str) -> Result<Profile> {
    let (_, text) = PROFILES
        .iter()
        .find(|(n, _)| *n == name)
        .ok_or_else(|| unknown("E0021", "profile", name, PROFILES.map(|x| x.0).to_vec()))?;
    io::parse_toml(text, &format!("embedded {name} profile"))
}

/// The profile a shipped network is planned with by default (`paper-findings` for
/// `findings-195`, else `paper`); `None` for an unknown name.
pub fn default_profile(network: &str) -> Option<&'static str> {
    NETWORKS
        .iter()
        .find(|(n, _, _)| *n == network)
        .map(|(_, _, p)| *p)
}

/// The shipped request set, its header and ids checked (E3001, E3002, E3102).
///
/// # Errors
/// [`Error::Invalid`] (none for the shipped file).
pub fn requests() -> Result<RequestSet> {
    checked_set(io::parse_json(REQUESTS, REQUESTS_NAME)?)
}

/// A request set with its header and ids checked (E3001, E3002, E3102); the requests themselves
/// are checked against a network by [`Instance::with_request_set`].
///
/// # Errors
/// [`Error::Invalid`] with every violation.
pub fn checked_set(set: RequestSet) -> Result<RequestSet> {
    let violations = validate::validate_request_set_header(&set);
    if violations.is_empty() {
        Ok(set)
    } else {
        Err(Error::Invalid(violations))
    }
}

/// A shipped network with a shipped profile (its default when `profile` is `None`), validated
/// together, without requests.
///
/// # Errors
/// [`Error::Invalid`] E0020, E0021.
pub fn instance(network_name: &str, profile_name: Option<&str>) -> Result<Instance> {
    let network = network(network_name)?;
    let profile_name = profile_name
        .or(default_profile(network_name))
        .unwrap_or("paper");
    Instance::new(network, profile(profile_name)?)
}
