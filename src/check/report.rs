//! Re-verifies a plan document ([`RequestReport`], the output of `swarmplan solve --json`) read
//! from a file: its request is the request set's (P5041, P5042), its summary fields agree with
//! its swarm (P5043), and its plan passes [`check_plan`] against the raw instance, the request
//! set's request and the document's swarm and sharing policy.

use super::check_plan;
use crate::compose::RequestReport;
use crate::error::Violation;
use crate::problem::{Network, Profile, Request};

fn v(code: &'static str, field: impl Into<String>, cause: impl Into<String>) -> Violation {
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
/// Every broken rule (codes `P5xxx`); empty when the document passes. The plan is checked
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
    let mut out = Vec::new();
    let found = requests.iter().find(|r| r.id == report.request.id);
    out.extend(p5041_request_is_in_the_request_set(report, found));
    out.extend(p5042_request_is_the_request_sets(report, found));
    out.extend(p5043_summary_matches_the_swarm(report));
    let request = found.unwrap_or(&report.request);
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

/// P5041: the document's request id is in the request set.
fn p5041_request_is_in_the_request_set(
    report: &RequestReport,
    found: Option<&Request>,
) -> Option<Violation> {
    found.is_none().then(|| {
        v(
            "P5041",
            "request.id",
            format!(
                "no request with id `{}` in the request file",
                report.request.id
            ),
        )
    })
}

/// P5042: the document's request is the request set's, field for field.
fn p5042_request_is_the_request_sets(
    report: &RequestReport,
    found: Option<&Request>,
) -> Option<Violation> {
    let file = found?;
    (*file != report.request).then(|| {
        v(
            "P5042",
            "request",
            format!(
                "the plan's request {:?} differs from the request file's {:?}",
                report.request, file
            ),
        )
    })
}

/// P5043: the document's formation and support-drone count are its swarm's, and a support
/// count given on the command line is the one flown (the paper's baseline `none` flies none).
fn p5043_summary_matches_the_swarm(report: &RequestReport) -> Vec<Violation> {
    let mut out = Vec::new();
    let swarm = &report.swarm;
    if report.formation != swarm.formation {
        out.push(v(
            "P5043",
            "formation",
            format!(
                "formation {:?}, the swarm flies {:?}",
                report.formation, swarm.formation
            ),
        ));
    }
    let flown = swarm.support_count();
    let expected = if report.options.sharing.flies_support() {
        report.options.support.unwrap_or(report.support_drones)
    } else {
        0
    };
    if report.support_drones != flown || expected != flown {
        out.push(v(
            "P5043",
            "support_drones",
            format!(
                "support_drones {} (options.support {:?}, sharing {:?}), the swarm flies {flown}",
                report.support_drones, report.options.support, report.options.sharing
            ),
        ));
    }
    out
}
