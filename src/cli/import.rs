//! `swarmplan import`: a user's road network (nodes and edges CSV, or GeoJSON lines) as a skyway
//! network file, with pads and winds drawn from a seed (`generate::import`).

use crate::error::both;
use crate::error::{Error, Result, Violation};
use crate::generate::import::{read_csv, read_geojson, to_skyway, Coordinates, ImportParams};
use crate::problem::io::{read_text, write_json};
use std::path::PathBuf;

/// Arguments of `import`.
#[derive(Debug, clap::Args)]
pub struct ImportArgs {
    /// Nodes CSV (header `id,x,y`); with --edges.
    #[arg(
        long,
        value_name = "FILE",
        requires = "edges",
        conflicts_with = "geojson"
    )]
    pub nodes: Option<PathBuf>,
    /// Edges CSV (header `from,to`, optional `length_m`); with --nodes.
    #[arg(long, value_name = "FILE", requires = "nodes")]
    pub edges: Option<PathBuf>,
    /// GeoJSON FeatureCollection of LineString / MultiLineString roads, longitude and latitude.
    #[arg(long, value_name = "FILE")]
    pub geojson: Option<PathBuf>,
    /// How the CSV coordinates are given: projected metres, or longitude and latitude (x is the
    /// longitude); GeoJSON is always longitude and latitude.
    #[arg(long, value_enum, default_value_t = Coordinates::Metres)]
    pub coordinates: Coordinates,
    /// Keep only the N nodes nearest --centre (then the largest connected component among them).
    #[arg(long, value_name = "N", requires = "centre")]
    pub nearest: Option<usize>,
    /// Centre of --nearest, `X,Y` in the input's coordinates (longitude,latitude for GeoJSON).
    #[arg(long, value_name = "X,Y", value_parser = parse_centre, allow_hyphen_values = true, requires = "nearest")]
    pub centre: Option<(f64, f64)>,
    /// Seed of the pads and winds; the same seed and input write the same file.
    #[arg(long)]
    pub seed: u64,
    /// Name written in the network file [default: imported-seed-S].
    #[arg(long)]
    pub name: Option<String>,
    /// Output network JSON file.
    #[arg(short = 'o', long = "output")]
    pub output: PathBuf,
    /// Overwrite the output file if it exists.
    #[arg(long)]
    pub force: bool,
}

fn parse_centre(s: &str) -> std::result::Result<(f64, f64), Violation> {
    let parts: Vec<&str> = s.split(',').map(str::trim).collect();
    let numbers = match parts.as_slice() {
        [x, y] => x.parse::<f64>().ok().zip(y.parse::<f64>().ok()),
        _ => None,
    };
    match numbers {
        Some((x, y)) if x.is_finite() && y.is_finite() => Ok((x, y)),
        _ => Err(Violation::new(
            "E1956",
            "--centre",
            format!("'{s}' is not two numbers X,Y"),
            "give them",
        )),
    }
}

/// Runs the subcommand: writes the network and reports what it kept on stderr.
///
/// # Errors
/// E1950–E1956 for unreadable or unusable input (exit code 2), every network rule (E1xxx), E0008
/// and E0009 when a file cannot be read, E0013 when the output exists and `--force` is not given.
pub fn run(args: ImportArgs) -> Result<i32> {
    let inputs: Vec<&std::path::Path> = [&args.nodes, &args.edges, &args.geojson]
        .into_iter()
        .flatten()
        .map(std::path::PathBuf::as_path)
        .collect();
    super::distinct_from_inputs(&[&args.output], &inputs)?;
    super::may_write(&args.output, args.force)?;
    let road = match (&args.nodes, &args.edges, &args.geojson) {
        (Some(nodes), Some(edges), None) => {
            let (nodes, edges) = both(read_text(nodes), read_text(edges))?;
            read_csv(&nodes, &edges, args.coordinates)?
        }
        (None, None, Some(geojson)) => read_geojson(&read_text(geojson)?)?,
        _ => {
            return Err(Error::invalid(
                "E1957",
                "--nodes/--edges/--geojson",
                "no road network given, or both formats at once",
                "give --nodes F --edges F, or --geojson F",
            ))
        }
    };
    let params = ImportParams {
        seed: args.seed,
        nearest: args.nearest.zip(args.centre),
        name: args
            .name
            .unwrap_or_else(|| format!("imported-seed-{}", args.seed)),
    };
    let network = to_skyway(&road, &params)?;
    write_json(&args.output, &network)?;
    eprintln!(
        "read {} intersections and {} roads; wrote {} nodes, {} edges (seed {}) to {}",
        road.positions_m.len(),
        road.roads.len(),
        network.nodes.len(),
        network.edges.len(),
        args.seed,
        super::output_name(&args.output)
    );
    Ok(0)
}
