//! Numbers for people: human output rounds, CSV and JSON keep every digit.
//! User guide: "Conventions of every command" (`docs/src/commands/conventions.md`).

use crate::solver::ZERO_GAP_TOL;

/// `x` rounded to `decimals` places, without trailing zeros: `274.15999999999997` with 2 places
/// is `274.16`, `70.0` is `70`, and a value that rounds to zero is `0`, never `-0`.
///
/// # Example
/// ```
/// use swarmplan::human::round;
/// assert_eq!(round(274.15999999999997, 2), "274.16");
/// assert_eq!(round(70.0, 2), "70");
/// assert_eq!(round(0.7751692976376183, 4), "0.7752");
/// assert_eq!(round(-0.0001, 2), "0");
/// ```
pub fn round(x: f64, decimals: usize) -> String {
    let text = format!("{x:.decimals$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.')
    } else {
        &text
    };
    match text {
        "-0" => "0".to_string(),
        t => t.to_string(),
    }
}

/// A relative gap (a fraction, [`crate::solver::Gap`]) as a percentage with `decimals` places
/// and its sign: `+2.7178%` for a loss, `-0.5%` below the reference, and `0%`, without a sign,
/// for a gap within [`ZERO_GAP_TOL`] of zero or one that rounds to zero. Human output only:
/// JSON and CSV keep every digit.
///
/// # Example
/// ```
/// use swarmplan::human::gap_percent;
/// assert_eq!(gap_percent(0.027178, 4), "+2.7178%");
/// assert_eq!(gap_percent(-0.005, 1), "-0.5%");
/// assert_eq!(gap_percent(-1e-12, 4), "0%");
/// assert_eq!(gap_percent(2e-8, 4), "0%");
/// ```
pub fn gap_percent(gap: f64, decimals: usize) -> String {
    let text = format!("{:+.decimals$}", 100.0 * gap);
    let zero = gap.abs() <= ZERO_GAP_TOL || text[1..].chars().all(|c| c == '0' || c == '.');
    if zero {
        "0%".to_string()
    } else {
        format!("{text}%")
    }
}
