//! Numbers for people: human output rounds, CSV and JSON keep every digit.

/// `x` rounded to `decimals` places, without trailing zeros: `274.15999999999997` with 2 places
/// is `274.16`, `70.0` is `70`, and a value that rounds to zero is `0`, never `-0`.
///
/// # Example
/// ```
/// use swarmplan::cli::human::round;
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
