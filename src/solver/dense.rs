//! A dense dual simplex for small linear programs that gain rows one at a time: the node LPs of
//! the pad search (`models/eaas_config.md`, "The pad search"), a few dozen rows and columns each.
//!
//! Written here rather than taken from microlp because of what it measured on those LPs: its
//! warm re-solve after [`microlp::Solution::add_constraint`] took about 47 µs per row added on
//! the 9-drone, 4-pad hops of `bench` (about 25 rows, 30 columns), most of it in
//! rebuilding the sparse constraint matrix and refactorising the basis, which microlp does on
//! every row added; this tableau does the same re-solve in a few microseconds
//! (`models/experiments/eaas_config.md`, "The pad search on a dense tableau").
//!
//! The model: minimise `c x` over `l <= x <= u` and rows `a x (<=, >=, =) rhs`. Each row `i`
//! gets a row variable `r_i = a_i x` bounded by its right-hand side, so the rows read
//! `[A, -I] (x, r) = 0`. The simplex keeps the full tableau `B^-1 [A, -I]` dense. It starts from
//! the basis of the row variables, which is dual feasible when every column of negative cost
//! has a finite upper bound and every other column a finite lower one (the pad search's LPs:
//! minimise `M >= 0`), and runs the dual simplex (largest bound violation leaves, Harris' ratio
//! test with the textbook two passes) until every basic value is within its bounds. A row added
//! later enters the basis with its row variable, and the dual simplex goes on from the basis it
//! had: the parent's optimum is the child's start.
//!
//! Every basis the dual simplex visits is dual feasible (within [`DUAL_TOL`]), so the value of
//! the point it stops at is the optimum, and never above it.

/// A column's bound is kept when the value is off it by at most this, relative to
/// `max(1, |bound|)`.
pub const PRIMAL_TOL: f64 = 1e-9;

/// Reduced costs of the wrong sign down to minus this count as dual feasible.
pub const DUAL_TOL: f64 = 1e-9;

/// A tableau entry smaller than this in magnitude is never a pivot.
const PIVOT_TOL: f64 = 1e-9;

/// Dual simplex iterations allowed per solve or row added, per row and column of the tableau.
const ITERATIONS_PER_SIZE: usize = 20;

/// The sense of a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sense {
    /// `a x <= rhs`.
    Le,
    /// `a x >= rhs`.
    Ge,
    /// `a x = rhs`.
    Eq,
}

/// Why a solve gave no optimum.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DenseFailure {
    /// A row has no entering column: the rows cannot all hold.
    Infeasible,
    /// The start is not dual feasible (a column of negative cost without a finite upper bound,
    /// or of nonnegative cost without a finite lower one).
    NoDualStart,
    /// The iteration limit: cycling or a numerically hard model.
    IterationLimit,
}

/// A linear program before its first solve.
#[derive(Debug, Clone, Default)]
pub struct DenseLp {
    cost: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    rows: Vec<Row>,
}

/// A row: its terms (column, coefficient), sense and right-hand side.
type Row = (Vec<(usize, f64)>, Sense, f64);

impl DenseLp {
    /// An LP over no column yet.
    pub fn new() -> DenseLp {
        DenseLp::default()
    }

    /// Adds a column of cost `cost` within `[lower, upper]` (either may be infinite); its index.
    pub fn add_column(&mut self, cost: f64, lower: f64, upper: f64) -> usize {
        self.cost.push(cost);
        self.lower.push(lower);
        self.upper.push(upper);
        self.cost.len() - 1
    }

    /// Adds the row `sum terms (sense) rhs` (a column may appear in several terms).
    pub fn add_row(&mut self, terms: Vec<(usize, f64)>, sense: Sense, rhs: f64) {
        self.rows.push((terms, sense, rhs));
    }

    /// The columns so far.
    pub fn columns(&self) -> usize {
        self.cost.len()
    }

    /// The optimum, by the dual simplex from the basis of the row variables.
    ///
    /// # Errors
    /// [`DenseFailure`]: no dual feasible start, an infeasible model, the iteration limit.
    pub fn solve(&self) -> Result<Tableau, DenseFailure> {
        let n = self.cost.len();
        let mut state = Vec::with_capacity(n);
        for j in 0..n {
            let at_upper =
                self.cost[j] < 0.0 || (self.cost[j] == 0.0 && self.lower[j] == f64::NEG_INFINITY);
            let bound = if at_upper {
                self.upper[j]
            } else {
                self.lower[j]
            };
            if !bound.is_finite() {
                return Err(DenseFailure::NoDualStart);
            }
            state.push(if at_upper { At::Upper } else { At::Lower });
        }
        let mut t = Tableau {
            structural: n,
            stride: n + self.rows.len() + SPARE_COLUMNS,
            table: Vec::new(),
            basis: Vec::new(),
            state,
            cost: self.cost.clone(),
            lower: self.lower.clone(),
            upper: self.upper.clone(),
            reduced: self.cost.clone(),
            beta: Vec::new(),
        };
        t.table.reserve(t.stride * self.rows.len());
        for (terms, sense, rhs) in &self.rows {
            t.push_row(terms, *sense, *rhs);
        }
        t.optimise()?;
        Ok(t)
    }
}

/// Room left for row variables of rows added after the first solve before the tableau is laid
/// out again.
const SPARE_COLUMNS: usize = 16;

/// Where a column is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum At {
    Basic(usize),
    Lower,
    Upper,
}

/// An optimal basis and its tableau; rows may be added and the optimum found again from it.
#[derive(Debug, Clone)]
pub struct Tableau {
    /// The LP's own columns; the row variables follow them.
    structural: usize,
    /// Columns allocated per tableau row (at least every column's).
    stride: usize,
    /// `B^-1 [A, -I]`, row-major, `stride` entries per row.
    table: Vec<f64>,
    /// The basic column of every row.
    basis: Vec<usize>,
    state: Vec<At>,
    cost: Vec<f64>,
    lower: Vec<f64>,
    upper: Vec<f64>,
    /// Reduced costs (0 on basic columns).
    reduced: Vec<f64>,
    /// Values of the basic columns, by row.
    beta: Vec<f64>,
}

impl Tableau {
    fn columns(&self) -> usize {
        self.state.len()
    }

    fn row(&self, i: usize) -> &[f64] {
        &self.table[i * self.stride..i * self.stride + self.columns()]
    }

    /// The value of column `j` (one of the LP's own) at the optimum.
    pub fn value(&self, j: usize) -> f64 {
        debug_assert!(j < self.structural);
        self.value_of(j)
    }

    fn value_of(&self, j: usize) -> f64 {
        match self.state[j] {
            At::Basic(i) => self.beta[i],
            At::Lower => self.lower[j],
            At::Upper => self.upper[j],
        }
    }

    /// The rows of the LP, those added included.
    pub fn rows(&self) -> usize {
        self.basis.len()
    }

    /// The optimal value `c x`.
    pub fn objective(&self) -> f64 {
        (0..self.structural)
            .filter(|&j| self.cost[j] != 0.0)
            .map(|j| self.cost[j] * self.value_of(j))
            .sum()
    }

    /// Adds the row `sum terms (sense) rhs` and finds the optimum again by the dual simplex
    /// from the current basis.
    ///
    /// # Errors
    /// [`DenseFailure::Infeasible`] when the rows cannot all hold; the iteration limit.
    pub fn add_row(
        &mut self,
        terms: &[(usize, f64)],
        sense: Sense,
        rhs: f64,
    ) -> Result<(), DenseFailure> {
        self.push_row(terms, sense, rhs);
        self.optimise()
    }

    /// Appends the row and its row variable, basic in it, expressed in the current basis.
    fn push_row(&mut self, terms: &[(usize, f64)], sense: Sense, rhs: f64) {
        let r = self.columns();
        if r + 1 > self.stride {
            self.relayout(r + 1 + SPARE_COLUMNS);
        }
        let (lo, hi) = match sense {
            Sense::Le => (f64::NEG_INFINITY, rhs),
            Sense::Ge => (rhs, f64::INFINITY),
            Sense::Eq => (rhs, rhs),
        };
        self.state.push(At::Basic(self.basis.len()));
        self.cost.push(0.0);
        self.lower.push(lo);
        self.upper.push(hi);
        self.reduced.push(0.0);
        // The row `r - a x = 0` with the basic columns eliminated: `r = a x` in the nonbasic ones.
        let mut w = vec![0.0; self.stride];
        for &(j, a) in terms {
            w[j] -= a;
        }
        w[r] = 1.0;
        for i in 0..self.basis.len() {
            let f = w[self.basis[i]];
            if f != 0.0 {
                let row = &self.table[i * self.stride..(i + 1) * self.stride];
                for (wj, &tj) in w.iter_mut().zip(row) {
                    *wj -= f * tj;
                }
                w[self.basis[i]] = 0.0;
            }
        }
        self.table.extend_from_slice(&w);
        self.basis.push(r);
        self.beta.push(0.0);
    }

    /// Lays the tableau out again with `stride` columns per row.
    fn relayout(&mut self, stride: usize) {
        let rows = self.basis.len();
        let mut table = vec![0.0; stride * rows];
        for i in 0..rows {
            let old = &self.table[i * self.stride..i * self.stride + self.columns()];
            table[i * stride..i * stride + old.len()].copy_from_slice(old);
        }
        self.table = table;
        self.stride = stride;
    }

    /// The basic values from the nonbasic columns at their bounds: `x_B = -sum_N T_j x_j`.
    fn compute_beta(&mut self) {
        let n = self.columns();
        let nonbasic: Vec<(usize, f64)> = (0..n)
            .filter_map(|j| match self.state[j] {
                At::Basic(_) => None,
                _ => Some((j, self.value_of(j))),
            })
            .filter(|&(_, x)| x != 0.0)
            .collect();
        for i in 0..self.basis.len() {
            let row = &self.table[i * self.stride..];
            self.beta[i] = -nonbasic.iter().map(|&(j, x)| row[j] * x).sum::<f64>();
        }
    }

    /// The row whose basic value is farthest outside its bounds, and the direction it must
    /// move (`+1` up to its lower bound, `-1` down to its upper one); `None` when all hold.
    fn leaving(&self) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64, f64)> = None;
        for (i, &b) in self.beta.iter().enumerate() {
            let j = self.basis[i];
            let (lo, hi) = (self.lower[j], self.upper[j]);
            let (violation, direction) = if b < lo - PRIMAL_TOL * lo.abs().max(1.0) {
                (lo - b, 1.0)
            } else if b > hi + PRIMAL_TOL * hi.abs().max(1.0) {
                (b - hi, -1.0)
            } else {
                continue;
            };
            if best.is_none_or(|(_, v, _)| violation > v) {
                best = Some((i, violation, direction));
            }
        }
        best.map(|(i, _, d)| (i, d))
    }

    /// Harris' two-pass ratio test on row `p` moving in `direction`: the entering column.
    fn entering(&self, p: usize, direction: f64) -> Option<usize> {
        let row = self.row(p);
        let eligible = |j: usize| -> Option<f64> {
            let alpha = direction * row[j];
            match self.state[j] {
                At::Basic(_) => None,
                _ if self.lower[j] == self.upper[j] => None,
                At::Lower if alpha < -PIVOT_TOL => Some(alpha),
                At::Upper if alpha > PIVOT_TOL => Some(alpha),
                _ => None,
            }
        };
        let mut bound = f64::INFINITY;
        for j in 0..self.columns() {
            if let Some(alpha) = eligible(j) {
                bound = bound.min((self.reduced[j].abs() + DUAL_TOL) / alpha.abs());
            }
        }
        let mut chosen: Option<(usize, f64)> = None;
        for j in 0..self.columns() {
            if let Some(alpha) = eligible(j) {
                if self.reduced[j].abs() / alpha.abs() <= bound
                    && chosen.is_none_or(|(_, a)| alpha.abs() > a)
                {
                    chosen = Some((j, alpha.abs()));
                }
            }
        }
        chosen.map(|(j, _)| j)
    }

    /// Pivots column `q` into the basis of row `p`; the leaving column goes to the bound it
    /// violated (`direction` as in [`Tableau::leaving`]), and the basic values follow: `x_q`
    /// moves by `delta` from its bound so that row `p`'s value reaches that bound.
    fn pivot(&mut self, p: usize, q: usize, direction: f64) {
        let n = self.columns();
        let stride = self.stride;
        let leaving = self.basis[p];
        let pivot = self.table[p * stride + q];
        let target = if direction > 0.0 {
            self.lower[leaving]
        } else {
            self.upper[leaving]
        };
        let delta = (self.beta[p] - target) / pivot;
        let entering_value = self.value_of(q) + delta;
        for i in 0..self.basis.len() {
            self.beta[i] -= self.table[i * stride + q] * delta;
        }
        self.beta[p] = entering_value;
        for x in &mut self.table[p * stride..p * stride + n] {
            *x /= pivot;
        }
        self.table[p * stride + q] = 1.0;
        let pivot_row: Vec<f64> = self.table[p * stride..p * stride + n].to_vec();
        for i in 0..self.basis.len() {
            if i == p {
                continue;
            }
            let f = self.table[i * stride + q];
            if f != 0.0 {
                let row = &mut self.table[i * stride..i * stride + n];
                for (x, &y) in row.iter_mut().zip(&pivot_row) {
                    *x -= f * y;
                }
                row[q] = 0.0;
            }
        }
        let f = self.reduced[q];
        if f != 0.0 {
            for (d, &y) in self.reduced.iter_mut().zip(&pivot_row) {
                *d -= f * y;
            }
        }
        self.reduced[q] = 0.0;
        self.basis[p] = q;
        self.state[q] = At::Basic(p);
        self.state[leaving] = if direction > 0.0 || self.lower[leaving] == self.upper[leaving] {
            At::Lower
        } else {
            At::Upper
        };
    }

    /// The dual simplex from the current (dual feasible) basis to the optimum. The basic values
    /// are updated at each pivot and computed afresh from the nonbasic columns at the start and
    /// before the optimum is declared, so round-off in the updates never decides it.
    fn optimise(&mut self) -> Result<(), DenseFailure> {
        let limit = ITERATIONS_PER_SIZE * (self.basis.len() + self.columns());
        self.compute_beta();
        for _ in 0..limit {
            let mut next = self.leaving();
            if next.is_none() {
                self.compute_beta();
                next = self.leaving();
            }
            let Some((p, direction)) = next else {
                return Ok(());
            };
            let Some(q) = self.entering(p, direction) else {
                return Err(DenseFailure::Infeasible);
            };
            self.pivot(p, q, direction);
        }
        Err(DenseFailure::IterationLimit)
    }
}

#[cfg(all(test, feature = "microlp"))]
mod tests {
    use super::*;
    use microlp::{ComparisonOp, OptimizationDirection, Problem};
    use rand::{Rng, SeedableRng};

    /// The same LP for both solvers, microlp's columns, and the `<=` rows added later.
    type Case = (
        DenseLp,
        Problem,
        Vec<microlp::Variable>,
        Vec<(Vec<(usize, f64)>, f64)>,
    );

    /// A random LP shaped like the pad search's: `min M` over bounded columns, equality and
    /// inequality rows, `M` in rows `sum x <= M`; then rows added one at a time.
    fn random_case(seed: u64) -> Case {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let n = rng.random_range(3..=8usize);
        let mut lp = DenseLp::new();
        let mut p = Problem::new(OptimizationDirection::Minimize);
        let mut vars = Vec::new();
        for _ in 0..n {
            let hi = rng.random_range(1.0..10.0);
            lp.add_column(0.0, 0.0, hi);
            vars.push(p.add_var(0.0, (0.0, hi)));
        }
        let m = lp.add_column(1.0, 0.0, f64::INFINITY);
        vars.push(p.add_var(1.0, (0.0, f64::INFINITY)));
        // An equality: the columns share a total.
        let total = rng.random_range(1.0..(n as f64));
        let all: Vec<(usize, f64)> = (0..n).map(|j| (j, 1.0)).collect();
        lp.add_row(all.clone(), Sense::Eq, total);
        p.add_constraint(
            all.iter().map(|&(j, a)| (vars[j], a)).collect::<Vec<_>>(),
            ComparisonOp::Eq,
            total,
        );
        // Each column's weighted load at most M; a few >= rows.
        for j in 0..n {
            let w = rng.random_range(0.5..3.0);
            lp.add_row(vec![(j, w), (m, -1.0)], Sense::Le, 0.0);
            p.add_constraint([(vars[j], w), (vars[m], -1.0)], ComparisonOp::Le, 0.0);
        }
        for _ in 0..2 {
            let a = rng.random_range(0..n);
            let b = (a + 1) % n;
            let rhs = rng.random_range(0.0..0.5);
            lp.add_row(vec![(a, 1.0), (b, 1.0)], Sense::Ge, rhs);
            p.add_constraint([(vars[a], 1.0), (vars[b], 1.0)], ComparisonOp::Ge, rhs);
        }
        // Rows added later: pairs' loads at most M.
        let later = (0..4)
            .map(|_| {
                let a = rng.random_range(0..n);
                let b = (a + rng.random_range(1..n)) % n;
                (
                    vec![(a, 1.0), (b, rng.random_range(0.5..2.0)), (m, -1.0)],
                    0.0,
                )
            })
            .collect();
        (lp, p, vars, later)
    }

    #[test]
    fn the_dense_simplex_agrees_with_microlp_row_after_row() {
        let mut compared = 0;
        for seed in 0..200u64 {
            let (lp, mut p, vars, later) = random_case(seed);
            let ours = lp.solve();
            let theirs = p.solve().map(|o| o.into_solution().unwrap().objective());
            let mut t = match (ours, theirs) {
                (Ok(t), Ok(v)) => {
                    assert!(
                        (t.objective() - v).abs() <= 1e-7 * (1.0 + v.abs()),
                        "seed {seed}: {} against {v}",
                        t.objective()
                    );
                    t
                }
                (Err(DenseFailure::Infeasible), Err(microlp::Error::Infeasible)) => continue,
                (a, b) => panic!("seed {seed}: {a:?} against {b:?}"),
            };
            for (terms, rhs) in later {
                let ours = t.add_row(&terms, Sense::Le, rhs);
                p.add_constraint(
                    terms.iter().map(|&(j, a)| (vars[j], a)).collect::<Vec<_>>(),
                    ComparisonOp::Le,
                    rhs,
                );
                let theirs = p.solve().map(|o| o.into_solution().unwrap().objective());
                match (ours, theirs) {
                    (Ok(()), Ok(v)) => {
                        assert!(
                            (t.objective() - v).abs() <= 1e-7 * (1.0 + v.abs()),
                            "seed {seed}: {} against {v}",
                            t.objective()
                        );
                        // The point keeps every row and bound.
                        for j in 0..lp.columns() {
                            assert!(
                                t.value(j) >= lp.lower[j] - 1e-8
                                    && t.value(j) <= lp.upper[j] + 1e-8
                            );
                        }
                        compared += 1;
                    }
                    (a, b) => panic!("seed {seed}: {a:?} against {b:?}"),
                }
            }
        }
        assert!(compared >= 500, "only {compared} re-solves compared");
    }

    #[test]
    fn an_infeasible_model_says_so() {
        let mut lp = DenseLp::new();
        let x = lp.add_column(1.0, 0.0, 1.0);
        lp.add_row(vec![(x, 1.0)], Sense::Ge, 2.0);
        assert_eq!(lp.solve().unwrap_err(), DenseFailure::Infeasible);
        // A free column of zero cost has no dual feasible bound to start at.
        let mut lp = DenseLp::new();
        lp.add_column(0.0, f64::NEG_INFINITY, f64::INFINITY);
        assert_eq!(lp.solve().unwrap_err(), DenseFailure::NoDualStart);
    }

    #[test]
    fn a_hand_solved_lp() {
        // min M: x + y = 3, x <= M, 2 y <= M, 0 <= x, y <= 3. Optimum x = 2, y = 1, M = 2.
        let mut lp = DenseLp::new();
        let x = lp.add_column(0.0, 0.0, 3.0);
        let y = lp.add_column(0.0, 0.0, 3.0);
        let m = lp.add_column(1.0, 0.0, f64::INFINITY);
        lp.add_row(vec![(x, 1.0), (y, 1.0)], Sense::Eq, 3.0);
        lp.add_row(vec![(x, 1.0), (m, -1.0)], Sense::Le, 0.0);
        lp.add_row(vec![(y, 2.0), (m, -1.0)], Sense::Le, 0.0);
        let mut t = lp.solve().unwrap();
        assert!((t.objective() - 2.0).abs() < 1e-12);
        assert!((t.value(x) - 2.0).abs() < 1e-12 && (t.value(y) - 1.0).abs() < 1e-12);
        // Then x <= 1.5: y = 1.5, M = 3.
        t.add_row(&[(x, 1.0)], Sense::Le, 1.5).unwrap();
        assert!((t.objective() - 3.0).abs() < 1e-12);
    }
}
