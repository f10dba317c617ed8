//! A planning instance: a network with its graph, a profile and a request set, validated together
//! once. Code that receives an [`Instance`] does not validate it again.

use super::validate::validate_profile;
use super::validate::{validate_network, validate_request, validate_request_set};
use super::{Network, Profile, Request, RequestSet, SkywayGraph};
use crate::error::{Error, Result};

/// A validated network, its graph, a validated profile and requests valid on both.
#[derive(Debug, Clone)]
pub struct Instance {
    /// The network as read.
    pub network: Network,
    /// Its graph.
    pub graph: SkywayGraph,
    /// The profile.
    pub profile: Profile,
    /// The requests, each valid on the network and profile; empty when none were given.
    pub requests: Vec<Request>,
}

impl Instance {
    /// Validates a network and a profile together, with no requests yet.
    ///
    /// # Errors
    /// [`Error::Invalid`] with every violation of both (codes E1xxx and E2xxx).
    pub fn new(network: Network, profile: Profile) -> Result<Instance> {
        let mut violations = validate_network(&network);
        violations.extend(validate_profile(&profile));
        if !violations.is_empty() {
            return Err(Error::Invalid(violations));
        }
        let graph = SkywayGraph::new(&network)?;
        Ok(Instance {
            network,
            graph,
            profile,
            requests: Vec::new(),
        })
    }

    /// Adds a whole request set, checking its header and ids (E3001, E3002, E3102) and every
    /// request against the network and the profile, reporting every violation at once.
    ///
    /// # Errors
    /// [`Error::Invalid`] with every E3xxx violation, fields named after the set's indices.
    pub fn with_request_set(mut self, set: RequestSet) -> Result<Instance> {
        let violations = validate_request_set(&set, &self.graph, self.profile.drone.max_payload_kg);
        if violations.is_empty() {
            self.requests = set.requests;
            Ok(self)
        } else {
            Err(Error::Invalid(violations))
        }
    }

    /// Adds requests, checking each against the network and the profile; the field of a
    /// violation names the request's position in `requests`.
    ///
    /// # Errors
    /// [`Error::Invalid`] with every E3xxx violation.
    pub fn with_requests(mut self, requests: Vec<Request>) -> Result<Instance> {
        let mut violations = Vec::new();
        for (i, r) in requests.iter().enumerate() {
            violations.extend(validate_request(
                r,
                i,
                &self.graph,
                self.profile.drone.max_payload_kg,
            ));
        }
        if violations.is_empty() {
            self.requests = requests;
            Ok(self)
        } else {
            Err(Error::Invalid(violations))
        }
    }

    /// Adds the one request of `set` with id `id`, checked against the network and the profile
    /// with its fields named after its index in the set.
    ///
    /// # Errors
    /// [`Error::Invalid`] with E3401 when no request has that id, else with every E3xxx
    /// violation of that request.
    pub fn with_request_from(mut self, set: &RequestSet, id: &str) -> Result<Instance> {
        let Some(index) = set.requests.iter().position(|r| r.id == id) else {
            return Err(Error::invalid(
                "E3401",
                "--request-id",
                format!(
                    "no request with id `{id}` in the request file{}",
                    similar_id(set, id)
                        .map_or(String::new(), |s| format!(" (did you mean `{s}`?)"))
                ),
                "give an id present in the file's `requests[].id`",
            ));
        };
        let request = set.requests[index].clone();
        let violations = validate_request(
            &request,
            index,
            &self.graph,
            self.profile.drone.max_payload_kg,
        );
        if violations.is_empty() {
            self.requests = vec![request];
            Ok(self)
        } else {
            Err(Error::Invalid(violations))
        }
    }
}

/// An id of the set with the same letters and number as `id` written otherwise (`r42` for
/// `r00042`): what a user who dropped the zeros meant.
fn similar_id<'a>(set: &'a RequestSet, id: &str) -> Option<&'a str> {
    let split = |s: &str| -> Option<(String, u64)> {
        let digits = s.len() - s.trim_start_matches(|c: char| !c.is_ascii_digit()).len();
        let (prefix, number) = s.split_at(digits);
        Some((prefix.to_string(), number.parse().ok()?))
    };
    let wanted = split(id)?;
    set.requests
        .iter()
        .map(|r| r.id.as_str())
        .find(|r| split(r).as_ref() == Some(&wanted))
}
