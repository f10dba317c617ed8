//! A model in CPLEX LP or free MPS format, for any solver: the good_lp model a generic
//! `solve_with<S: good_lp::Solver>` builds is handed to [`LpCapture`] through good_lp's
//! `lp-solvers` backend (`good_lp::solvers::lp_solvers::LpSolver`), which keeps it instead of
//! running a solver. [`CapturedModel::to_lp`] prints it with `lp_solvers`' LP writer;
//! [`CapturedModel::to_mps`] is our own free MPS writer (good_lp 1.15 and `lp_solvers` 1.2 write
//! no MPS). Both models that export, the hop MILP and the node-time MILP, go through here.
//!
//! The `lp-solvers` backend keeps only the letters of each variable name (`y_k3_t7` becomes
//! `ykt` with a counter), so the captured model is renamed from the names the model gave its
//! variables, in the order it added them ([`CapturedModel::rename`]).

use crate::error::{BackendFailure, Error, Result};
use good_lp::solvers::lp_solvers::{LpSolver, Solution, SolverTrait, Status, WithMaxSeconds};
use lp_solvers::lp_format::{AsVariable, Constraint, LpObjective, LpProblem, WriteToLpFileFormat};
use lp_solvers::problem::{Problem, StrExpression, Variable};
use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::{HashMap, HashSet};
use std::fmt;
use std::path::Path;
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

impl super::MilpModel for good_lp::solvers::lp_solvers::Model<LpCapture> {
    /// The capture's "solve": every variable 0, reported optimal ([`LpCapture`]); `Err` only when
    /// the model cannot be captured.
    fn solve_outcome(
        self,
    ) -> std::result::Result<
        super::MilpOutcome<good_lp::solvers::lp_solvers::LpSolution>,
        good_lp::ResolutionError,
    > {
        use good_lp::SolverModel;
        Ok(super::MilpOutcome::Solved {
            status: super::BackendStatus::Optimal,
            solution: self.solve()?,
        })
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
        let fail = |message: String| Error::backend(BackendFailure::LostModel, "lp-file", message);
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

/// The file formats of an exported model, chosen by the file's name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModelFormat {
    /// CPLEX LP ([`CapturedModel::to_lp`]).
    Lp,
    /// Free MPS ([`CapturedModel::to_mps`]).
    Mps,
}

impl ModelFormat {
    /// Free MPS for a name ending in `.mps` (any case), CPLEX LP for any other, as solvers read
    /// a model file by its extension.
    pub fn of_path(path: &Path) -> ModelFormat {
        match path.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("mps") => ModelFormat::Mps,
            _ => ModelFormat::Lp,
        }
    }

    /// The format's name in messages: `CPLEX LP` or `free MPS`.
    pub fn name(self) -> &'static str {
        match self {
            ModelFormat::Lp => "CPLEX LP",
            ModelFormat::Mps => "free MPS",
        }
    }
}

/// Writes the text of an exported model to `path` (replaced if it exists), whole, as
/// [`crate::problem::io::write_whole`] does.
///
/// # Errors
/// E0010: [`Error::Io`] when the file cannot be written, [`Error::Invalid`] when `path` is a
/// directory.
pub fn write_model_file(path: &Path, text: &str) -> Result<()> {
    crate::problem::io::write_whole(path, text.as_bytes())
}

impl CapturedModel {
    /// The model in `format`, as [`CapturedModel::to_lp`] or [`CapturedModel::to_mps`].
    pub fn to_text(&self, format: ModelFormat, name: &str, comment: &[String]) -> String {
        match format {
            ModelFormat::Lp => self.to_lp(name, comment),
            ModelFormat::Mps => self.to_mps(name, comment),
        }
    }

    /// The model in free MPS format (fields separated by spaces, names of any length without
    /// spaces), `comment` lines first (each behind `* `): the same rows as [`CapturedModel::to_lp`]
    /// under the same names `c0, c1, ...` (constraints without a variable that always hold are
    /// left out; one that never holds is a row without entries and its right-hand side), the
    /// objective row `obj`, `OBJSENSE MAX` when maximising. Integer variables are framed by
    /// `INTORG`/`INTEND` markers and always get both bounds (`LO`/`MI` and `UP`/`PL`), since
    /// some readers bound an integer column without an `UP` by 1; a continuous one gets the
    /// bounds that differ from `[0, +inf)`. A variable in no row is listed with objective
    /// coefficient 0, so every bound names a known column.
    pub fn to_mps(&self, name: &str, comment: &[String]) -> String {
        use std::fmt::Write;
        let rows: Vec<&Row> = self
            .constraints
            .iter()
            .filter(|r| !(r.terms.is_empty() && holds(r)))
            .collect();
        let index: HashMap<&str, usize> = self
            .variables
            .iter()
            .enumerate()
            .map(|(i, v)| (v.name.as_str(), i))
            .collect();
        // Per variable, its (row, coefficient) in the order of the rows, the objective first.
        let mut columns: Vec<Vec<(String, f64)>> = vec![Vec::new(); self.variables.len()];
        for (c, n) in &self.objective {
            columns[index[n.as_str()]].push(("obj".to_string(), *c));
        }
        for (r, row) in rows.iter().enumerate() {
            for (c, n) in &row.terms {
                columns[index[n.as_str()]].push((format!("c{r}"), *c));
            }
        }
        let mut out = String::new();
        for line in comment {
            let _ = writeln!(out, "* {line}");
        }
        let _ = writeln!(out, "NAME {name}");
        if self.maximise {
            let _ = writeln!(out, "OBJSENSE\n    MAX");
        }
        let _ = writeln!(out, "ROWS\n N  obj");
        for (r, row) in rows.iter().enumerate() {
            let kind = match row.operator {
                Ordering::Less => 'L',
                Ordering::Equal => 'E',
                Ordering::Greater => 'G',
            };
            let _ = writeln!(out, " {kind}  c{r}");
        }
        let _ = writeln!(out, "COLUMNS");
        let mut integer = false;
        for (v, entries) in self.variables.iter().zip(&columns) {
            if v.is_integer != integer {
                let marker = if v.is_integer { "INTORG" } else { "INTEND" };
                let _ = writeln!(out, "    MARKER 'MARKER' '{marker}'");
                integer = v.is_integer;
            }
            if entries.is_empty() {
                let _ = writeln!(out, "    {} obj 0", v.name);
            }
            for (row, c) in entries {
                let _ = writeln!(out, "    {} {row} {c}", v.name);
            }
        }
        if integer {
            let _ = writeln!(out, "    MARKER 'MARKER' 'INTEND'");
        }
        let _ = writeln!(out, "RHS");
        for (r, row) in rows.iter().enumerate() {
            if row.rhs != 0.0 {
                let _ = writeln!(out, "    RHS c{r} {}", row.rhs);
            }
        }
        let _ = writeln!(out, "BOUNDS");
        for v in &self.variables {
            for (kind, value) in mps_bounds(v) {
                let _ = match value {
                    Some(x) => writeln!(out, " {kind} BND {} {x}", v.name),
                    None => writeln!(out, " {kind} BND {}", v.name),
                };
            }
        }
        out.push_str("ENDATA\n");
        out
    }
}

/// The MPS bound lines of `v`: kind and value (none for `MI`, `PL`, `FR`).
fn mps_bounds(v: &Var) -> Vec<(&'static str, Option<f64>)> {
    let (lo, up) = (v.lower, v.upper);
    if lo == up {
        return vec![("FX", Some(lo))];
    }
    if lo == f64::NEG_INFINITY && up == f64::INFINITY && !v.is_integer {
        return vec![("FR", None)];
    }
    let mut bounds = Vec::new();
    if lo == f64::NEG_INFINITY {
        bounds.push(("MI", None));
    } else if lo != 0.0 || v.is_integer {
        bounds.push(("LO", Some(lo)));
    }
    if up != f64::INFINITY {
        bounds.push(("UP", Some(up)));
    } else if v.is_integer {
        bounds.push(("PL", None));
    }
    bounds
}
