//! The one place that runs an exact hop formulation by name ([`Formulation`]): each arm calls
//! the formulation's own solve function in its file.

use super::continuous::{solve_continuous, ContinuousOptions};
use super::milp::{solve_milp, MilpOptions};
use super::{fluid, BoundOutcome, ExactOutcome, Formulation, Objective};
use crate::eaas::{HopProblem, PolicyOptions};
use crate::error::Result;

/// What a formulation answers: a schedule (with its bound, when the model has one) or a bound
/// alone.
#[derive(Debug, Clone, PartialEq)]
pub enum Solved {
    /// The continuous model, the grid MILP, the fair QP's layout.
    Schedule(Box<ExactOutcome>),
    /// The fluid LP.
    Bound(BoundOutcome),
}

/// Runs `formulation` on the hop for `objective`. Every formulation takes `options`' re-ordering
/// mode and time limit; the MILP also its grid, backend and node limit, the continuous model its
/// backend and node limit; `readings` are those of PB and FB, whose schedules are the continuous
/// model's first incumbents.
///
/// # Errors
/// Those of the formulation's solve function.
pub fn solve(
    formulation: Formulation,
    problem: &HopProblem,
    objective: &Objective,
    options: &MilpOptions,
    readings: &PolicyOptions,
) -> Result<Solved> {
    Ok(match formulation {
        Formulation::Continuous => Solved::Schedule(Box::new(solve_continuous(
            problem,
            objective,
            &ContinuousOptions::like(options, *readings),
        )?)),
        Formulation::Milp => Solved::Schedule(Box::new(solve_milp(problem, objective, options)?)),
        Formulation::Fluid => Solved::Bound(fluid::bound(
            problem,
            objective,
            options.reorder,
            options.time_limit_s,
        )?),
        Formulation::Fair => Solved::Schedule(Box::new(fluid::fair(
            problem,
            objective,
            options.reorder,
            options.time_limit_s,
        )?)),
    })
}
