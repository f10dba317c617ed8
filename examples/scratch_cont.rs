//! scratch
use swarmplan::eaas::exact::continuous::{solve_continuous, ContinuousOptions};
use swarmplan::eaas::exact::Objective;
use swarmplan::eaas::HopProblem;
fn main() {
    for path in std::env::args().skip(1) {
        let (p, objective): (HopProblem, Objective) =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        let o = solve_continuous(&p, &objective, &ContinuousOptions::default()).unwrap();
        eprintln!(
            "{path}: {:?} {:?} {:?} eps {:?} {:.1} ms transfers {}",
            objective,
            o.status,
            o.objective,
            o.epsilon,
            o.solve_ms,
            o.transfers.len()
        );
    }
}
