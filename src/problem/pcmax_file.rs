//! P||Cmax instances in the plain text format of the published benchmark files (`swarmplan
//! node-time --instance FILE`).
//!
//! The format, as the instance collection of the França, Gendreau, Laporte & Müller (1994) and
//! Frangioni, Necciari & Scutellà (2004) classes describes it (`scheduling/instances/Readme.md` of
//! the public repository `jbuckow/flaschenpost`, which names both papers as the source): a text
//! file of `n + 2` lines,
//!
//! ```text
//! m        number of machines (here: pads)
//! n        number of jobs (here: drones)
//! p_1      processing time of job 1 (here: charge time, min)
//! ...
//! p_n
//! ```
//!
//! The reader splits the file on any white space, so the same numbers on fewer lines (`m n` on the
//! first line, several times a line) read the same; the order is always `m`, then `n`. We could not
//! read the published files themselves (nor the original papers) here: this is the layout as that
//! collection documents it, checked on the example shipped in
//! `instances/node_time/pcmax-u1-n10-m3-seed1.txt`. The published times are whole numbers; any
//! number is read, and the node-time rules (`E5001`-`E5005`) apply to the instance read.

use super::io::read_text;
use crate::error::{Error, Result, Violation};
use std::path::Path;

/// A P||Cmax instance read from the published text format.
#[derive(Debug, Clone, PartialEq)]
pub struct PcmaxInstance {
    /// Machines `m`: the pads.
    pub pads: usize,
    /// Processing times `p_1..p_n`: the drones' charge times, min.
    pub charge_times_min: Vec<f64>,
}

/// Reads a P||Cmax instance file in the published text format (see the module).
///
/// # Errors
/// `E0008`/`E0009` when the file cannot be read or is not UTF-8 text; those of [`parse_pcmax`].
pub fn read_pcmax(path: &Path) -> Result<PcmaxInstance> {
    parse_pcmax(&read_text(path)?, &path.display().to_string())
}

/// Parses the published P||Cmax text format; `origin` names the source in messages.
///
/// # Errors
/// [`Error::Invalid`] with every violation at once: `E5009` when `m` or `n` is missing or not a
/// whole number `>= 1`; `E5010` for a processing time that is not a number (with its line) or
/// when the file holds another count of times than `n`.
///
/// # Example
/// ```
/// use swarmplan::problem::pcmax_file::parse_pcmax;
/// let i = parse_pcmax("3\n5\n60\n50\n40\n30\n20\n", "example").unwrap();
/// assert_eq!(i.pads, 3);
/// assert_eq!(i.charge_times_min, [60.0, 50.0, 40.0, 30.0, 20.0]);
/// ```
pub fn parse_pcmax(text: &str, origin: &str) -> Result<PcmaxInstance> {
    // Every token with its line (1-based).
    let mut tokens = text
        .lines()
        .enumerate()
        .flat_map(|(i, l)| l.split_whitespace().map(move |t| (i + 1, t)));
    let mut violations = Vec::new();
    let mut count = |name: &str, what: &str| -> Option<usize> {
        let token = tokens.next();
        let read = token.and_then(|(_, t)| t.parse::<usize>().ok().filter(|&v| v >= 1));
        if read.is_none() {
            let found = match token {
                Some((line, t)) => format!("`{t}` on line {line}"),
                None => "the end of the file".to_string(),
            };
            violations.push(Violation::new(
                "E5009",
                format!("{origin}: {name}"),
                format!("expected {what}, a whole number >= 1, found {found}"),
                "write the published P||Cmax format: m (machines) on the first line, n (jobs) \
                 on the second, then the n processing times",
            ));
        }
        read
    };
    let pads = count("m", "the number of machines (pads)");
    let jobs = count("n", "the number of jobs (drones)");
    let mut times = Vec::new();
    for (line, t) in tokens {
        match t.parse::<f64>() {
            Ok(p) => times.push(p),
            Err(_) => violations.push(Violation::new(
                "E5010",
                format!("{origin}: p[{}] (line {line})", times.len() + 1),
                format!("`{t}` is not a number"),
                "write each processing time as a number of minutes, such as 42",
            )),
        }
    }
    if let Some(n) = jobs.filter(|&n| n != times.len() && violations.is_empty()) {
        violations.push(Violation::new(
            "E5010",
            format!("{origin}: p"),
            format!(
                "n = {n} jobs, but the file holds {} processing times",
                times.len()
            ),
            "give exactly n processing times after m and n, or correct n",
        ));
    }
    match (pads, violations.is_empty()) {
        (Some(pads), true) => Ok(PcmaxInstance {
            pads,
            charge_times_min: times,
        }),
        _ => Err(Error::Invalid(violations)),
    }
}
