//! A grid of requests x method combinations planned on a local thread pool.

use super::{Context, PlanOptions, RequestReport};
use crate::error::{Error, Result};
use crate::problem::Request;
use rayon::prelude::*;

impl Context<'_> {
    /// Plans every request with every combination on a pool of `threads` threads, one job per
    /// request ([`Context::plan_each`], which does the work the combinations share once), and
    /// keeps of each report what `keep(request position, report)` returns. Row `i` of the result
    /// holds request `i`'s kept values in the order of `combos`, whatever the thread count;
    /// `done(n)` is called as each request's `n` combinations are planned.
    ///
    /// # Errors
    /// E0004 when the pool cannot be started; else the first error in request order, of
    /// planning or of `keep`.
    ///
    /// # Complexity
    /// That of [`Context::plan_each`] per request, over `threads` threads.
    pub fn plan_grid<T: Send>(
        &self,
        requests: &[Request],
        combos: &[PlanOptions],
        threads: usize,
        done: &(dyn Fn(u64) + Sync),
        keep: &(dyn Fn(usize, RequestReport) -> Result<T> + Sync),
    ) -> Result<Vec<Vec<T>>> {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| {
                Error::invalid(
                    "E0004",
                    "--threads",
                    format!("cannot start {threads} worker threads: {e}"),
                    "give fewer --threads",
                )
            })?;
        let rows: Vec<Result<Vec<T>>> = pool.install(|| {
            requests
                .par_iter()
                .enumerate()
                .map(|(i, r)| {
                    let reports = self.plan_each(r, combos)?;
                    done(combos.len() as u64);
                    reports.into_iter().map(|report| keep(i, report)).collect()
                })
                .collect()
        });
        rows.into_iter().collect()
    }
}
