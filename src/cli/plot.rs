//! `swarmplan plot`: one plan written by `solve --json` drawn as one SVG (the route on the
//! network, every drone's battery against time, every stop's pad schedule), and optionally a
//! second plan of the same request beside it; or the sharing schedules of methods on one hop
//! of a hop file (`eaas --write-hop`), one battery panel each.

use super::check::read_plan;
use super::inputs::InstanceArgs;
use crate::compose::RequestReport;
use crate::eaas::compare::{label_gaps, run_method, HopMethod, MethodRow};
use crate::eaas::exact::milp::MilpOptions;
use crate::eaas::exact::Objective;
use crate::eaas::hop_file::read_hop_file;
use crate::eaas::PolicyOptions;
use crate::error::{Error, Result};
use crate::plot::data::BatteryUnit;
use crate::plot::draw::plans_svg;
use crate::plot::hop::{hop_figure_data, HopSchedule};
use crate::problem::io::json_name;
use std::path::{Path, PathBuf};

/// Draw a plan written by `solve --json` as an SVG: the route on the network, every drone's
/// battery against time with the in-flight transfers, every stop's pad schedule. Or, with
/// `--hop-file`, the schedules of methods on one hop.
#[derive(Debug, clap::Args)]
#[command(group(clap::ArgGroup::new("drawn").required(true).args(["plan", "hop_file"])))]
pub struct PlotArgs {
    /// Network and profile the plan was made with.
    #[command(flatten)]
    pub instance: InstanceArgs,
    /// The plan: the JSON `solve --json` prints (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub plan: Option<PathBuf>,
    /// A second plan of the same request, drawn beside the first on the same axes as the
    /// reference of the gap in the title (`-` reads standard input).
    #[arg(long, value_name = "FILE")]
    pub compare: Option<PathBuf>,
    /// A hop file (`eaas --write-hop`): draw the schedules `--methods` make on its hop, one
    /// battery panel each on the same axes (the exact methods with `eaas`'s defaults).
    #[arg(long, value_name = "FILE", conflicts_with_all = ["plan", "compare"])]
    pub hop_file: Option<PathBuf>,
    /// With --hop-file: the methods whose schedules are drawn, comma-separated (those of
    /// `eaas` that make a schedule: none, pb, fb, continuous, milp, fair).
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "pb,continuous",
        conflicts_with = "plan"
    )]
    pub methods: Vec<HopMethod>,
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
/// input, E8003 for a plan that does not fit the instance, E8004 for a hop method without a
/// schedule, E8005 (a bug) when plotters cannot draw the figure (see [`plans_svg`]).
pub fn run(args: PlotArgs) -> Result<i32> {
    let mut inputs: Vec<&Path> = Vec::new();
    inputs.extend(args.plan.as_deref());
    inputs.extend(args.compare.as_deref());
    inputs.extend(args.hop_file.as_deref());
    inputs.extend(args.instance.network.as_deref());
    inputs.extend(args.instance.profile.as_deref());
    super::distinct_from_inputs(&[&args.output], &inputs)?;
    super::may_write(&args.output, args.force)?;
    let unit = if args.percent {
        BatteryUnit::Percent
    } else {
        BatteryUnit::Mah
    };
    let svg = match (&args.plan, &args.hop_file) {
        (_, Some(hop_file)) => hop_svg(&args, hop_file, unit)?,
        (Some(plan), None) => plan_svg(&args, plan, unit)?,
        (None, None) => unreachable!("clap requires --plan or --hop-file"),
    };
    if args.output.as_os_str() == "-" {
        use std::io::Write as _;
        super::stdout_written(std::io::stdout().lock().write_all(svg.as_bytes()))?;
    } else {
        crate::problem::io::write_whole(&args.output, svg.as_bytes())?;
    }
    eprintln!("wrote {}", super::output_name(&args.output));
    Ok(0)
}

/// The SVG of a plan, and of the plan compared with it.
fn plan_svg(args: &PlotArgs, plan: &Path, unit: BatteryUnit) -> Result<String> {
    let stdin = |p: &Path| p.as_os_str() == "-";
    if stdin(plan) && args.compare.as_deref().is_some_and(stdin) {
        return Err(Error::invalid(
            "E8002",
            "--plan, --compare",
            "both plans on standard input: it holds one document",
            "write one of the plans to a file and give its path",
        ));
    }
    let instance = args.instance.load()?;
    let mut reports = vec![read_plan(plan)?];
    if let Some(other) = &args.compare {
        reports.push(read_plan(other)?);
    }
    let refs: Vec<&RequestReport> = reports.iter().collect();
    plans_svg(&instance.network, &instance.profile, &refs, unit)
}

/// The SVG of the schedules `--methods` make on the hop of a hop file.
fn hop_svg(args: &PlotArgs, path: &Path, unit: BatteryUnit) -> Result<String> {
    if let Some(m) = args.methods.iter().find(|m| **m == HopMethod::Fluid) {
        return Err(Error::invalid(
            "E8004",
            "--methods",
            format!("`{m}` gives a bound, not a schedule to draw"),
            "draw the schedules of none, pb, fb, continuous, milp or fair",
        ));
    }
    let (profile, file) = crate::error::both(args.instance.load_profile(), read_hop_file(path))?;
    let readings = PolicyOptions::from(&profile.readings);
    let objective = file.objective();
    let milp = MilpOptions::default();
    let mut rows = args
        .methods
        .iter()
        .map(|&m| run_method(&file.hop, &objective, m, &milp, &readings))
        .collect::<Result<Vec<_>>>()?;
    label_gaps(&mut rows, &file.hop, &objective, milp.reorder);
    let schedules: Vec<HopSchedule> = rows
        .into_iter()
        .map(|row| HopSchedule {
            method: row.method.to_string(),
            summary: summary(&row, &objective),
            transfers: row.transfers,
        })
        .collect();
    let figure = hop_figure_data(&file, &schedules, unit)?;
    crate::plot::draw::hop_svg(&figure)
        .map_err(|e| Error::internal("E8005", format!("drawing the figure: {e}")))
}

/// One method's line in a hop figure's title: its objective, status and gap.
fn summary(row: &MethodRow, objective: &Objective) -> String {
    let mut parts = Vec::new();
    if let Some(v) = row.objective {
        let proven = if row.objective_proven { "" } else { "<=" };
        parts.push(match objective {
            Objective::NodeTime(_) => format!("node time at the end {proven}{v:.4} min"),
            Objective::MaxMinArrival => format!("lowest delivery arrival {v:.2} mAh"),
            Objective::Feasible => "flies".to_string(),
        });
    } else if row.feasible == Some(false) {
        parts.push("does not fly".to_string());
    }
    if let Some(status) = row.status {
        parts.push(format!("status {}", json_name(&status)));
    }
    if let Some(g) = row.gap.and_then(|g| g.relative.map(|x| (x, g.reference))) {
        parts.push(format!(
            "gap {} vs {}",
            crate::human::gap_percent(g.0, 2),
            json_name(&g.1)
        ));
    }
    parts.push(format!("{} transfer(s)", row.transfers.len()));
    parts.join(" | ")
}
