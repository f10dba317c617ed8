//! A model in CPLEX LP format, for any solver: the good_lp model a generic `solve_with<S:
//! good_lp::Solver>` builds is handed to [`LpCapture`] through good_lp's `lp-solvers` backend
//! (`good_lp::solvers::lp_solvers::LpSolver`), which keeps it instead of running a solver, and
//! [`CapturedModel::to_lp`] prints it with `lp_solvers`' LP writer.
//!
//! The `lp-solvers` backend keeps only the letters of each variable name (`y_k3_t7` becomes
//! `ykt` with a counter), so the captured model is renamed from the names the model gave its
//! variables, in the order it added them ([`CapturedModel::rename`]).

use crate::error::{Error, Result};
use good_lp::solvers::lp_solvers::{LpSolver, Solution, SolverTrait, Status, WithMaxSeconds};
use lp_solvers::lp_format::{AsVariable, Constraint, LpObjective, LpProblem, WriteToLpFileFormat};
use lp_solvers::problem::{Problem, StrExpression, Variable};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::{HashMap, HashSet};
use std::fmt;
use std::rc::Rc;

/// A good_lp "solver" (through `LpSolver`) that captures the model it is asked to solve and
/// reports an empty optimal solution (every variable 0), which the caller discards.
#[derive(Debug, Clone, Default)]
pub struct LpCapture {
    captured: Rc<RefCell<Option<CapturedModel>>>,
}

impl LpCapture {
    /// A capture with nothing in it yet.
    pub fn new() -> Self {
        LpCapture::default()
    }

    /// The good_lp solver to hand to a model; every clone shares this capture.
    pub fn solver(&self) -> LpSolver<LpCapture> {
        LpSolver(self.clone())
    }

    /// The model captured by the last solve, if any.
    pub fn take(&self) -> Option<CapturedModel> {
        self.captured.borrow_mut().take()
    }
}

impl SolverTrait for LpCapture {
    fn run<'a, P: LpProblem<'a>>(&self, problem: &'a P) -> std::result::Result<Solution, String> {
        let variables: Vec<Var> = problem
            .variables()
            .map(|v| Var {
                name: v.name().to_string(),
                is_integer: v.is_integer(),
                lower: v.lower_bound(),
                upper: v.upper_bound(),
            })
            .collect();
        // good_lp hands the terms over in hash order; the file lists them by variable.
        let index: HashMap<&str, usize> = variables
            .iter()
            .enumerate()
            .map(|(i, v)| (v.name.as_str(), i))
            .collect();
        let sorted = |e: &dyn WriteToLpFileFormat| -> std::result::Result<_, String> {
            let mut t = terms(e)?;
            t.sort_by_key(|(_, name)| index.get(name.as_str()).copied());
            Ok(t)
        };
        let model = CapturedModel {
            maximise: problem.sense() == LpObjective::Maximize,
            objective: sorted(&problem.objective())?,
            constraints: problem
                .constraints()
                .map(|c| {
                    Ok(Row {
                        terms: sorted(&c.lhs)?,
                        operator: c.operator,
                        // -0 as 0
                        rhs: c.rhs + 0.0,
                    })
                })
                .collect::<std::result::Result<_, String>>()?,
            variables,
        };
        *self.captured.borrow_mut() = Some(model);
        Ok(Solution::new(Status::Optimal, HashMap::new()))
    }
}

impl WithMaxSeconds<LpCapture> for LpCapture {
    fn max_seconds(&self) -> Option<u32> {
        None
    }

    /// Nothing is solved, so a time limit changes nothing.
    fn with_max_seconds(&self, _seconds: u32) -> LpCapture {
        self.clone()
    }
}

/// Displays a `lp_solvers` expression as its LP text.
struct Text<'e, E: ?Sized>(&'e E);

impl<E: WriteToLpFileFormat + ?Sized> fmt::Display for Text<'_, E> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.0.to_lp_file_format(f)
    }
}

/// Splits the `lp-solvers` backend's expression text (`+2 x -1 y`) into (coefficient, name).
fn terms<E: WriteToLpFileFormat + ?Sized>(
    e: &E,
) -> std::result::Result<Vec<(f64, String)>, String> {
    let text = Text(e).to_string();
    let tokens: Vec<&str> = text.split_whitespace().collect();
    tokens
        .chunks(2)
        .map(|pair| match pair {
            [c, name] => c
                .parse::<f64>()
                .map(|c| (c, (*name).to_string()))
                .map_err(|_| format!("unreadable coefficient `{c}` in `{text}`")),
            _ => Err(format!("unreadable expression `{text}`")),
        })
        .collect()
}

#[derive(Debug, Clone, PartialEq)]
struct Var {
    name: String,
    is_integer: bool,
    lower: f64,
    upper: f64,
}

#[derive(Debug, Clone, PartialEq)]
struct Row {
    terms: Vec<(f64, String)>,
    operator: Ordering,
    rhs: f64,
}

/// A linear model as good_lp handed it to its `lp-solvers` backend: objective sense and terms
/// (good_lp's objective constant is not part of it), variables with bounds and integrality in
/// the order they were added, and constraints `terms (<= | =) rhs`.
#[derive(Debug, Clone, PartialEq)]
pub struct CapturedModel {
    maximise: bool,
    objective: Vec<(f64, String)>,
    variables: Vec<Var>,
    constraints: Vec<Row>,
}

/// Counts of a written LP model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LpSize {
    /// Variables (columns).
    pub variables: usize,
    /// Integer variables with bounds `[0, 1]`.
    pub binaries: usize,
    /// Other integer variables.
    pub integers: usize,
    /// Constraints written (rows).
    pub constraints: usize,
    /// Constraints with no variable that always hold (such as `0 <= 1`), left out of the file.
    pub trivial_constraints_left_out: usize,
}

impl CapturedModel {
    /// Gives variable `i` the name `names[i]` (the order good_lp added them), in the variables,
    /// the objective and the constraints.
    ///
    /// # Errors
    /// [`Error::Backend`] when the counts differ, a name is not a valid LP name (a letter, then
    /// letters, digits or `_`), or two names are equal.
    pub fn rename(&mut self, names: &[String]) -> Result<()> {
        let fail = |message: String| Error::Backend {
            backend: "lp-file".into(),
            message,
        };
        if names.len() != self.variables.len() {
            return Err(fail(format!(
                "{} names for {} variables",
                names.len(),
                self.variables.len()
            )));
        }
        let valid = |n: &str| {
            n.starts_with(|c: char| c.is_ascii_alphabetic())
                && n.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        };
        if let Some(bad) = names.iter().find(|n| !valid(n)) {
            return Err(fail(format!("`{bad}` is not a valid LP variable name")));
        }
        let distinct: HashSet<&String> = names.iter().collect();
        if distinct.len() != names.len() {
            return Err(fail("two variables have the same name".into()));
        }
        let mut map: HashMap<String, String> = HashMap::with_capacity(names.len());
        for (v, name) in self.variables.iter_mut().zip(names) {
            map.insert(std::mem::replace(&mut v.name, name.clone()), name.clone());
        }
        let rename_terms = |terms: &mut Vec<(f64, String)>| -> Result<()> {
            for (_, n) in terms.iter_mut() {
                *n = map
                    .get(n.as_str())
                    .cloned()
                    .ok_or_else(|| fail(format!("unknown variable `{n}`")))?;
            }
            Ok(())
        };
        rename_terms(&mut self.objective)?;
        for row in &mut self.constraints {
            rename_terms(&mut row.terms)?;
        }
        Ok(())
    }

    /// Sizes of the model as [`CapturedModel::to_lp`] writes it.
    pub fn size(&self) -> LpSize {
        let binary = |v: &&Var| v.is_integer && v.lower == 0.0 && v.upper == 1.0;
        let trivial = self
            .constraints
            .iter()
            .filter(|r| r.terms.is_empty() && holds(r))
            .count();
        LpSize {
            variables: self.variables.len(),
            binaries: self.variables.iter().filter(binary).count(),
            integers: self
                .variables
                .iter()
                .filter(|v| v.is_integer && !binary(v))
                .count(),
            constraints: self.constraints.len() - trivial,
            trivial_constraints_left_out: trivial,
        }
    }

    /// The model in CPLEX LP format, `comment` lines first (each behind `\ `).
    ///
    /// A constraint with no variable that always holds is left out (some readers reject an empty
    /// left-hand side); one that never holds is written on the first variable with coefficient
    /// 0, so the file stays infeasible. An empty objective is written the same way.
    pub fn to_lp(&self, name: &str, comment: &[String]) -> String {
        let zero = || {
            self.variables
                .first()
                .map_or(String::new(), |v| format!("+0 {}", v.name))
        };
        let expr = |terms: &[(f64, String)]| {
            if terms.is_empty() {
                StrExpression(zero())
            } else {
                StrExpression(
                    terms
                        .iter()
                        .map(|(c, n)| format!("{c:+} {n}"))
                        .collect::<Vec<_>>()
                        .join(" "),
                )
            }
        };
        let problem = Problem {
            name: name.to_string(),
            sense: if self.maximise {
                LpObjective::Maximize
            } else {
                LpObjective::Minimize
            },
            objective: expr(&self.objective),
            variables: self
                .variables
                .iter()
                .map(|v| Variable {
                    name: v.name.clone(),
                    is_integer: v.is_integer,
                    lower_bound: v.lower,
                    upper_bound: v.upper,
                })
                .collect(),
            constraints: self
                .constraints
                .iter()
                .filter(|r| !(r.terms.is_empty() && holds(r)))
                .map(|r| Constraint {
                    lhs: expr(&r.terms),
                    operator: r.operator,
                    rhs: r.rhs,
                })
                .collect(),
        };
        let mut out = String::new();
        for line in comment {
            out.push_str("\\ ");
            out.push_str(line);
            out.push('\n');
        }
        out.push_str(&problem.display_lp().to_string());
        out
    }
}

/// Whether a constraint without variables holds: `0 (<= | = | >=) rhs`.
fn holds(r: &Row) -> bool {
    match r.operator {
        Ordering::Less => 0.0 <= r.rhs,
        Ordering::Equal => r.rhs == 0.0,
        Ordering::Greater => 0.0 >= r.rhs,
    }
}
