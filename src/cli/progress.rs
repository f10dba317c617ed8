//! Progress on stderr for the runs that can take more than a second: a bar where the work is a
//! loop of known length (`batch` over its requests and method combinations, `eaas` over its
//! methods), a spinner with the elapsed time where it is not (`solve` with `--sharing
//! exact|fair`, `node-time`). Drawn only when stderr is a terminal (indicatif's stderr target
//! hides itself otherwise, and under `TERM=dumb`), so a pipe, a file or a test sees nothing of
//! it; it never touches stdout, and a bar left by an early error is cleared.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressFinish, ProgressStyle};
use std::time::Duration;

/// A bar over `len` units of work, each a `unit` (such as `requests`), on stderr.
pub fn bar(len: u64, unit: &str) -> ProgressBar {
    let template = format!(
        "{{spinner}} [{{elapsed_precise}}] {{wide_bar}} {{pos}}/{{len}} {unit} (eta {{eta}}) {{msg}}"
    );
    let style = ProgressStyle::with_template(&template)
        .expect("a fixed, valid template")
        .progress_chars("=> ");
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr())
        .with_style(style)
        .with_finish(ProgressFinish::AndClear);
    tick(&bar);
    bar
}

/// A spinner saying `message` with the elapsed time, on stderr, ticking by itself: for work of
/// unknown length.
pub fn spinner(message: impl Into<std::borrow::Cow<'static, str>>) -> ProgressBar {
    let style = ProgressStyle::with_template("{spinner} [{elapsed_precise}] {msg}")
        .expect("a fixed, valid template");
    let spinner = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr())
        .with_style(style)
        .with_message(message)
        .with_finish(ProgressFinish::AndClear);
    tick(&spinner);
    spinner
}

/// Redraws `bar` by itself (the elapsed time moves on while one unit of work runs long), unless
/// it is hidden: then no ticker thread is started.
fn tick(bar: &ProgressBar) {
    if !bar.is_hidden() {
        bar.enable_steady_tick(Duration::from_millis(200));
    }
}
