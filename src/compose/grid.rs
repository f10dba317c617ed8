//! A grid of requests x method combinations planned on a local thread pool.

use super::{Context, PlanOptions, RequestReport};
use crate::error::{Error, Result};
use crate::problem::Request;
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Mutex;

/// What [`Context::plan_grid_rows`] keeps of a request: from its position, the request and its
/// reports in the order of the combinations.
pub type KeepRow<'a, T> = dyn Fn(usize, &Request, Vec<RequestReport>) -> Result<T> + Sync + 'a;

impl Context {
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
        let keep_row = |i: usize, _: &Request, reports: Vec<RequestReport>| -> Result<Vec<T>> {
            reports.into_iter().map(|report| keep(i, report)).collect()
        };
        self.plan_grid_rows(requests, combos, threads, done, &keep_row)
    }

    /// [`Context::plan_grid`] keeping of each request what `keep_row(request position,
    /// request, reports in the order of combos)` returns: for work on a request's reports
    /// together (the joint optimum and the gap splits).
    ///
    /// With a [`Context::deadline`], a request not started by then is not planned, and the rows
    /// returned are those of the requests before the first one left out: the rows of the same
    /// call on that prefix alone (work on later requests already made is dropped).
    ///
    /// # Errors
    /// As [`Context::plan_grid`].
    ///
    /// # Complexity
    /// As [`Context::plan_grid`], plus `keep_row` per request on the pool.
    pub fn plan_grid_rows<T: Send>(
        &self,
        requests: &[Request],
        combos: &[PlanOptions],
        threads: usize,
        done: &(dyn Fn(u64) + Sync),
        keep_row: &KeepRow<'_, T>,
    ) -> Result<Vec<T>> {
        let pool = thread_pool(threads)?;
        // Requests are handed out in order from one counter, so that a deadline leaves a prefix
        // planned; each result goes to its request's slot, whatever thread made it.
        let next = AtomicUsize::new(0);
        let slots: Vec<Mutex<Option<Result<T>>>> =
            requests.iter().map(|_| Mutex::new(None)).collect();
        pool.install(|| {
            (0..threads.max(1)).into_par_iter().for_each(|_| loop {
                let i = next.fetch_add(1, Ordering::Relaxed);
                let Some(r) = requests.get(i) else { break };
                if self
                    .deadline
                    .is_some_and(|d| std::time::Instant::now() >= d)
                {
                    break;
                }
                let row = self.plan_each(r, combos).and_then(|reports| {
                    done(combos.len() as u64);
                    keep_row(i, r, reports)
                });
                *slots[i].lock().unwrap_or_else(|e| e.into_inner()) = Some(row);
            })
        });
        // The requests before the first one the deadline left unplanned.
        let mut out = Vec::with_capacity(requests.len());
        for slot in slots {
            match slot.into_inner().unwrap_or_else(|e| e.into_inner()) {
                Some(row) => out.push(row?),
                None => break,
            }
        }
        Ok(out)
    }
}

/// A pool of `threads` worker threads.
///
/// # Errors
/// E0004 when the pool cannot be started.
fn thread_pool(threads: usize) -> Result<rayon::ThreadPool> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| {
            Error::invalid(
                "E0004",
                "--threads",
                format!("cannot start {threads} worker threads: {e}"),
                "give fewer --threads",
            )
        })
}
