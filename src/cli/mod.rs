//! Command-line interface: clap derive, one file per subcommand. Data goes to stdout (`--json` for
//! machine-readable output), messages to stderr. Exit code 0 ok, 1 failed run, 2 bad input.
//! User guide: one page per command under `docs/src/commands/`, from "Conventions of every command"
//! (`docs/src/commands/conventions.md`).

use clap::{Parser, Subcommand};
use serde::Serialize;

/// `println!` to stdout that returns [`crate::error::Error::Output`] from the calling function instead
/// of panicking when stdout cannot be written (a closed pipe, a full disk).
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        $crate::cli::stdout_written(writeln!(std::io::stdout().lock(), $($arg)*))?
    }};
}

pub mod batch;
pub mod bench;
pub mod check;
pub mod eaas;
pub mod generate;
pub mod import;
pub mod inputs;
pub mod inspect;
pub mod node_time;
pub mod plot;
pub mod progress;
pub mod solve;

/// swarmplan: plan swarm-based drone deliveries with in-flight energy sharing.
#[derive(Debug, Parser)]
#[command(name = "swarmplan", version, about, long_about = None)]
pub struct Cli {
    /// The subcommand.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Write a seeded synthetic network or request set.
    #[command(subcommand)]
    Generate(generate::GenerateCommand),
    /// Turn a road network (nodes/edges CSV or GeoJSON lines) into a skyway network.
    Import(import::ImportArgs),
    /// Describe a network, and the swarm a request would fly.
    Inspect(inspect::InspectArgs),
    /// Node time at a recharging node: pad-to-drone assignment (P||Cmax).
    NodeTime(node_time::NodeTimeArgs),
    /// Plan one request: route, sharing schedules, node times, delivery time.
    Solve(solve::SolveArgs),
    /// Plan every request of a request set with one or more method combinations.
    Batch(batch::BatchArgs),
    /// The paper's experiments and the optimality-gap report, as files and figures.
    Bench(bench::BenchArgs),
    /// One hop of a request: sharing heuristics against the exact MILP, fluid bound and fair QP.
    Eaas(eaas::EaasArgs),
    /// Re-verify a plan written by `solve --json` with the independent checker.
    Check(check::CheckArgs),
    /// Draw a plan written by `solve --json` (and another of the same request) as an SVG.
    Plot(plot::PlotArgs),
}

/// Parses the process arguments, runs the subcommand, prints errors, returns the exit code.
pub fn main() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => match coded_usage_error(&e) {
            Some(message) => {
                eprint!("{message}");
                return 2;
            }
            // `--help`, `--version`: clap prints them to stdout.
            None => {
                let _ = e.print();
                return 0;
            }
        },
    };
    let result = match cli.command {
        Command::Generate(cmd) => generate::run(cmd),
        Command::Import(args) => import::run(args),
        Command::Inspect(args) => inspect::run(args),
        Command::NodeTime(args) => node_time::run(args),
        Command::Solve(args) => solve::run(args),
        Command::Batch(args) => batch::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Eaas(args) => eaas::run(args),
        Command::Check(args) => check::run(args),
        Command::Plot(args) => plot::run(args),
    };
    match result {
        Ok(code) => code,
        // The reader of stdout went away (`| head`): nothing is left to say to anyone.
        Err(e) if e.is_broken_pipe() => 0,
        Err(e) => {
            eprintln!("error: {e}");
            e.exit_code()
        }
    }
}

/// The message of a command-line error, with a code: its own when a value parser gave one (the
/// `E19xx`, `E39xx` checks of `generate`), else `E0007` (an unknown or missing argument, a value
/// that does not parse). `None` for `--help` and `--version`, which are not errors; the help
/// without a code for `swarmplan` alone.
///
/// # Example
/// ```
/// use clap::Parser;
/// let e = swarmplan::cli::Cli::try_parse_from(["swarmplan", "node-time", "--pads", "x"]).unwrap_err();
/// assert!(swarmplan::cli::coded_usage_error(&e).unwrap().contains("[E0007]"));
/// let help = swarmplan::cli::Cli::try_parse_from(["swarmplan", "--help"]).unwrap_err();
/// assert!(swarmplan::cli::coded_usage_error(&help).is_none());
/// let bare = swarmplan::cli::Cli::try_parse_from(["swarmplan"]).unwrap_err();
/// assert!(!swarmplan::cli::coded_usage_error(&bare).unwrap().contains("[E0007]"));
/// ```
pub fn coded_usage_error(e: &clap::Error) -> Option<String> {
    if !e.use_stderr() {
        return None;
    }
    let text = e.render().to_string();
    // `swarmplan` alone: the help, as asked for, without an error prefix (still exit 2).
    if e.kind() == clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        return Some(text);
    }
    if has_code(&text) {
        return Some(text);
    }
    let rest = text.strip_prefix("error: ").unwrap_or(&text);
    Some(format!("error: [E0007] command line: {rest}"))
}

/// `E0010` when `output` is a directory; `E0013` when it is a file that exists and `--force`
/// was not given: no command overwrites a file unasked (a device such as `/dev/null` is written
/// to, not overwritten). Called before any input is read or any work done, so a refusal costs
/// nothing.
pub(crate) fn may_write(output: &std::path::Path, force: bool) -> crate::error::Result<()> {
    if output == std::path::Path::new("-") {
        return Ok(());
    }
    crate::problem::io::refuse_directory(output)?;
    if force || !output.is_file() {
        return Ok(());
    }
    Err(crate::error::Error::invalid(
        "E0013",
        output.display().to_string(),
        "the output file exists; the tool does not overwrite a file unasked",
        "pass --force to overwrite it, or give another file",
    ))
}

/// E0031 when an output path names one of the command's inputs (the same file, however it is
/// spelled): the tool never writes over what it reads, `--force` or not.
pub(crate) fn distinct_from_inputs(
    outputs: &[&std::path::Path],
    inputs: &[&std::path::Path],
) -> crate::error::Result<()> {
    for output in outputs {
        let Ok(o) = std::fs::canonicalize(output) else {
            continue;
        };
        if let Some(input) = inputs
            .iter()
            .find(|i| std::fs::canonicalize(i).is_ok_and(|i| i == o))
        {
            return Err(crate::error::Error::invalid(
                "E0031",
                output.display().to_string(),
                format!("the output is the input {}", input.display()),
                "give another output file: the tool does not write over what it reads",
            ));
        }
    }
    Ok(())
}

/// How an output is named on stderr: `standard output` for `-`, else the path.
pub(crate) fn output_name(output: &std::path::Path) -> String {
    if output == std::path::Path::new("-") {
        "standard output".to_string()
    } else {
        output.display().to_string()
    }
}

/// Whether `text` holds a rule code such as `[E1901]`.
fn has_code(text: &str) -> bool {
    text.as_bytes().windows(7).any(|w| {
        w[0] == b'[' && w[1] == b'E' && w[2..6].iter().all(u8::is_ascii_digit) && w[6] == b']'
    })
}

/// Prints `value` as pretty JSON to stdout.
///
/// # Errors
/// [`crate::error::Error::Output`] when stdout cannot be written.
pub fn print_json<T: Serialize>(value: &T) -> crate::error::Result<()> {
    outln!(
        "{}",
        serde_json::to_string_pretty(value).expect("serialising plain data cannot fail")
    );
    Ok(())
}

/// Set once a write to stdout found its reader gone (`| head`).
static STDOUT_GONE: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// The result of a write to stdout: a closed pipe (the reader stopped early, as `| head` does)
/// is not an error, so the command still ends with its own exit code (1 for an undeliverable
/// request, a broken rule); later writes are skipped. Any other failure is an output error.
///
/// # Errors
/// [`crate::error::Error::Output`] for a failure other than a closed pipe.
pub fn stdout_written(result: std::io::Result<()>) -> crate::error::Result<()> {
    use std::sync::atomic::Ordering;
    match result {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {
            STDOUT_GONE.store(true, Ordering::Relaxed);
            Ok(())
        }
        Err(e) if !STDOUT_GONE.load(Ordering::Relaxed) => Err(crate::error::Error::from_output(e)),
        _ => Ok(()),
    }
}

/// `n` and `word`, with an `s` unless `n` is 1: "1 combination", "20 combinations".
pub(crate) fn count(n: usize, word: &str) -> String {
    if n == 1 {
        format!("{n} {word}")
    } else {
        format!("{n} {word}s")
    }
}
