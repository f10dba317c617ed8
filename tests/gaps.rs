//! LPT node-time gaps against recorded optima, with hand-computed expected values.

use swarmplan::compose::{lpt_node_time_gaps, Stop};
use swarmplan::solver::{ReferenceKind, SolveStatus};

fn stop(pads: u32, charge_times_min: &[f64], nt_min: f64, status: SolveStatus) -> Stop {
    Stop {
        node: "x".to_string(),
        pads,
        charge_times_min: charge_times_min.to_vec(),
        nt_min,
        assignment: Vec::new(),
        status,
    }
}

#[test]
fn lpt_gap_is_measured_against_proven_optima_only() {
    let stops = [
        // 3, 3, 2, 2, 2 on 2 pads: LPT puts 3 | 3, then 2 on each (5 | 5), then the last 2 -> 7.
        // Optimum 6 = {3, 3} | {2, 2, 2}. Gap (7 - 6) / 6 = 1/6.
        stop(2, &[3.0, 3.0, 2.0, 2.0, 2.0], 6.0, SolveStatus::Optimal),
        // The paper's example on 3 pads: LPT 60 | 50 | 40, 30 -> 40 (70), 20 -> 50 (70): 70 = optimum.
        stop(
            3,
            &[60.0, 50.0, 40.0, 30.0, 20.0],
            70.0,
            SolveStatus::Optimal,
        ),
        // An incumbent is not an optimum: it must be counted apart and left out of the gaps.
        stop(2, &[3.0, 3.0, 2.0, 2.0, 2.0], 7.0, SolveStatus::Feasible),
    ];
    let s = lpt_node_time_gaps(stops.iter()).unwrap();
    assert_eq!(s.stops, 2);
    assert_eq!(s.stops_with_incumbent_only, 1);
    assert_eq!(s.lpt_optimal, 1);
    assert!((s.max_gap - 1.0 / 6.0).abs() < 1e-12, "{}", s.max_gap);
    assert!((s.mean_gap - 1.0 / 12.0).abs() < 1e-12, "{}", s.mean_gap);
    assert_eq!(s.reference, ReferenceKind::Optimal);
}
