//! `swarmplan plot`: one plan written by `solve --json` drawn as one SVG (the route on the
//! network, every drone's battery against time, every stop's pad schedule), and optionally a
//! second plan of the same request beside it.

use super::check::read_plan;
use super::inputs::InstanceArgs;
use crate::compose::RequestReport;
use crate::error::{Error, Result};
use crate::plot::data::BatteryUnit;
use crate::plot::draw::plans_svg;
use std::path::{Path, PathBuf};

/// Draw a plan written by `solve --json` as an SVG: the route on the network, every drone's
/// battery against time with the in-flight transfers, every stop's pad schedule.
#[derive(Debug, clap::Args)]
pub struct PlotArgs {
    /// Network and profile the plan was made with.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// The plan: the JSON `solve --json` prints (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub plan: PathBuf,
    /// A second plan of the same request, drawn beside the first on the same axes as the
    /// reference of the gap in the title (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub compare: Option<PathBuf>,
    /// The SVG file to write (`-` for standard output).
    #[arg(short = 'o', long = "output", value_name = "FILE")]
    pub output: PathBuf,
    /// Batteries in percent of each drone's capacity instead of mAh.
    #[arg(long)]
    pub percent: bool,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub force: bool,
}

/// Runs the subcommand: writes the SVG, exit code 0.
///
/// # Errors
/// E0013 when the output exists without `--force`, E0031 when it is one of the inputs, those of
/// reading the plans (E0008, E0009, E6001-E6003), E6004/E6005 for a plan made on another
/// instance, E8001 for a compared plan of another request, E8002 for both plans on standard
/// input, E8003 for a plan that does not fit the instance, E8004 (a bug) when plotters cannot
/// draw it (see [`plans_svg`]).
pub fn run(args: PlotArgs) -> Result<i32> {
    let mut inputs: Vec<&Path> = vec![&args.plan];
    inputs.extend(args.compare.as_deref());
    inputs.extend(args.instance.network.as_deref());
    inputs.extend(args.instance.profile.as_deref());
    super::distinct_from_inputs(&[&args.output], &inputs)?;
    super::may_write(&args.output, args.force)?;
    let stdin = |p: &Path| p.as_os_str() == "-";
    if stdin(&args.plan) && args.compare.as_deref().is_some_and(stdin) {
        return Err(Error::invalid(
            "E8002",
            "--plan, --compare",
            "both plans on standard input: it holds one document",
            "write one of the plans to a file and give its path",
        ));
    }
    let instance = args.instance.load()?;
    let mut reports = vec![read_plan(&args.plan)?];
    if let Some(other) = &args.compare {
        reports.push(read_plan(other)?);
    }
    let unit = if args.percent {
        BatteryUnit::Percent
    } else {
        BatteryUnit::Mah
    };
    let refs: Vec<&RequestReport> = reports.iter().collect();
    let svg = plans_svg(&instance.network, &instance.profile, &refs, unit)?;
    if args.output.as_os_str() == "-" {
        use std::io::Write as _;
        super::stdout_written(std::io::stdout().lock().write_all(svg.as_bytes()))?;
    } else {
        crate::problem::io::write_whole(&args.output, svg.as_bytes())?;
    }
    eprintln!("wrote {}", super::output_name(&args.output));
    Ok(0)
}
