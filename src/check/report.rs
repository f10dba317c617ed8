//! Re-verifies a plan document ([`RequestReport`], the output of `swarmplan solve --json`) read
//! from a file: its request is the request set's (P5041, P5042), its summary fields agree with
//! its swarm (P5043), its support decision is the instance's (P5045, P5046), its search report agrees with the plan
//! and with the method run again (P5047, P5048, [`super::search`]), and its plan passes [`check_plan`] against the raw instance, the request
//! set's request and the document's swarm and sharing policy.

use super::check_plan;
use super::decision::check_support_decision;
use super::search;
use crate::compose::RequestReport;
use crate::error::Violation;
use crate::problem::fingerprint::Fingerprint;
use crate::problem::io::json_name;
use crate::problem::{Network, Profile, Request};

fn violation(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
    Violation::new(
        code,
        field,
        cause,
        "check the plan against the request file and instance it was made with, or plan the \
         request again",
    )
}

/// Checks a plan document against the raw instance and a request set.
///
/// # Arguments
/// * `network`, `profile` - the instance the plan claims to be made on (assumed valid).
/// * `requests` - the request set; the document's request must be in it, unchanged.
/// * `report` - the document read back (see [`super::plan_file::read_plan_file`]).
///
/// # Returns
/// E6004 and E6005 alone when the document records another network or profile than the ones
/// given (see [`made_on_another_instance`]); else every broken rule (codes `P5xxx`); empty when
/// the document passes. The plan is checked
/// against the request set's request when the set has the document's request id, else against
/// the document's own request.
///
/// # Complexity
/// That of [`check_plan`], plus `O(R)` to find the request among `R`.
pub fn check_report(
    network: &Network,
    profile: &Profile,
    requests: &[Request],
    report: &RequestReport,
) -> Vec<Violation> {
    let mismatch = made_on_another_instance(network, profile, report);
    if !mismatch.is_empty() {
        return mismatch;
    }
    let mut out = Vec::new();
    let found = requests.iter().find(|r| r.id == report.request.id);
    out.extend(p5041_request_is_in_the_request_set(report, found));
    out.extend(p5042_request_is_the_request_sets(report, found));
    out.extend(p5043_summary_matches_the_swarm(report));
    let request = found.unwrap_or(&report.request);
    out.extend(check_support_decision(network, profile, request, report));
    out.extend(search::check_consistency(report));
    out.extend(search::check_rerun(network, profile, request, report));
    out.extend(check_plan(
        network,
        profile,
        request,
        &report.swarm,
        report.options.sharing,
        &report.plan,
    ));
    out
}

/// E6004, E6005: the document was made on another network, another profile (its fingerprint
/// differs from theirs): a user's mix-up, not a broken model, so nothing else is checked. A
/// document without a fingerprint (an earlier version's) is checked as it is.
pub fn made_on_another_instance(
    network: &Network,
    profile: &Profile,
    report: &RequestReport,
) -> Vec<Violation> {
    match &report.made_on {
        Some(made_on) => fingerprint_mismatch(network, profile, made_on),
        None => Vec::new(),
    }
}

/// E6004, E6005: `made_on` differs from the fingerprint of `network`, of `profile`.
pub fn fingerprint_mismatch(
    network: &Network,
    profile: &Profile,
    made_on: &Fingerprint,
) -> Vec<Violation> {
    let given = Fingerprint::of(network, profile);
    let short = |h: &str| h.chars().take(12).collect::<String>();
    let mut out = Vec::new();
    if made_on.network_sha256 != given.network_sha256 {
        out.push(Violation::new(
            "E6004",
            "made_on.network_sha256",
            format!(
                "this plan was made on another network (sha256 {}..., the network given is {}...{})",
                short(&made_on.network_sha256),
                short(&given.network_sha256),
                network
                    .name
                    .as_ref()
                    .map_or(String::new(), |n| format!(", named `{n}`"))
            ),
            "check it with the network it was made on (--network FILE; without it, the shipped \
             paper-195)",
        ));
    }
    if made_on.profile_sha256 != given.profile_sha256 {
        out.push(Violation::new(
            "E6005",
            "made_on.profile_sha256",
            format!(
                "this plan was made with another profile (sha256 {}..., the profile given is \
                 {}..., named `{}`)",
                short(&made_on.profile_sha256),
                short(&given.profile_sha256),
                profile.name
            ),
            "check it with the profile it was made with (--profile FILE, and --literal if it was \
             planned with it)",
        ));
    }
    out
}

/// P5041: the document's request id is in the request set, unless the request was given inline
/// ([`Request::is_inline`]: the plan is then checked against its own request).
fn p5041_request_is_in_the_request_set(
    report: &RequestReport,
    found: Option<&Request>,
) -> Option<Violation> {
    (found.is_none() && !report.request.is_inline()).then(|| {
        violation(
            "P5041",
            "request.id",
            format!(
                "no request with id `{}` in the request file",
                report.request.id
            ),
        )
    })
}

/// P5042: the document's request is the request set's, field for field (one violation per
/// field that differs).
fn p5042_request_is_the_request_sets(
    report: &RequestReport,
    found: Option<&Request>,
) -> Vec<Violation> {
    let Some(file) = found else {
        return Vec::new();
    };
    let stated = &report.request;
    let mut out = Vec::new();
    let mut differs = |field: &str, stated: String, file: String| {
        if stated != file {
            out.push(violation(
                "P5042",
                format!("request.{field}"),
                format!("the plan's request states {stated}, the request file's {file}"),
            ));
        }
    };
    differs("source", stated.source.clone(), file.source.clone());
    differs(
        "destination",
        stated.destination.clone(),
        file.destination.clone(),
    );
    differs(
        "packages_kg",
        format!("{:?}", stated.packages_kg),
        format!("{:?}", file.packages_kg),
    );
    out
}

/// P5043: the document's formation and support-drone count are its swarm's, and a support
/// count given on the command line is the one flown (the paper's baseline `none` flies none).
fn p5043_summary_matches_the_swarm(report: &RequestReport) -> Vec<Violation> {
    let mut out = Vec::new();
    let swarm = &report.swarm;
    if report.formation != swarm.formation {
        out.push(violation(
            "P5043",
            "formation",
            format!(
                "formation {}, the swarm flies {}",
                json_name(&report.formation),
                json_name(&swarm.formation)
            ),
        ));
    }
    let flown = swarm.support_count();
    if report.support_drones != flown {
        out.push(violation(
            "P5043",
            "support_drones",
            format!(
                "support_drones {}, the swarm flies {flown}",
                report.support_drones
            ),
        ));
    }
    let given = report
        .options
        .support
        .filter(|_| report.options.sharing.flies_support());
    if given.is_some_and(|n| n != flown) {
        out.push(violation(
            "P5043",
            "options.support",
            format!(
                "options.support {} (sharing {}), the swarm flies {flown}",
                json_name(&given),
                json_name(&report.options.sharing)
            ),
        ));
    }
    if !report.options.sharing.flies_support() && flown != 0 {
        out.push(violation(
            "P5043",
            "support_drones",
            format!(
                "sharing {} flies no support drone, the swarm has {flown}",
                json_name(&report.options.sharing)
            ),
        ));
    }
    out
}
