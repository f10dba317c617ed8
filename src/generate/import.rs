//! A user's road network turned into a skyway network: intersections become rooftop nodes, roads
//! become edges; the largest connected component is kept (optionally only the `N` nodes nearest a
//! centre, as the paper took 195 nodes of London); pads and winds are drawn from a seed as
//! [`super::generate_network`] draws them.
//!
//! Two input formats:
//! - **CSV**: a nodes file with columns `id,x,y` and an edges file with columns `from,to` and an
//!   optional `length_m`; coordinates in projected metres, or longitude and latitude in degrees;
//! - **GeoJSON**: a `FeatureCollection` of `LineString` (and `MultiLineString`) features in
//!   longitude and latitude (WGS 84, as the format prescribes). Line ends, and vertices shared by
//!   two lines or met twice, are intersections; each line is cut there into edges whose length is
//!   the great-circle length of the polyline between them (haversine, on the sphere of the mean
//!   Earth radius `R` = 6,371,008.8 m).
//!
//! Node positions in longitude and latitude are projected to metres by the equirectangular
//! projection about the centroid of the input's points: `x = R (lon - lon0) cos(lat0)`,
//! `y = R (lat - lat0)`. Over a city (10 km) its distances are within about 0.1% of the
//! great-circle ones; they give headings, and lengths where the input gives none.

use super::network::{draw_edge_winds, draw_network_pads};
use crate::error::{Error, Result, Violation};
use crate::problem::validate::validate_network;
use crate::problem::{Edge, Network, Node, SCHEMA_VERSION};
use petgraph::unionfind::UnionFind;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::collections::HashMap;

/// Mean Earth radius, m (IUGG).
pub const EARTH_RADIUS_M: f64 = 6_371_008.8;

/// Most nodes an imported road network may have.
pub const MAX_IMPORT_NODES: usize = 100_000;

/// How coordinates are given.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Coordinates {
    /// Projected metres (x east, y north).
    Metres,
    /// Longitude and latitude, degrees (WGS 84).
    LonLat,
}

/// A road network in metres: intersections and the roads between them.
#[derive(Debug, Clone, PartialEq)]
pub struct RoadNetwork {
    /// Node ids.
    pub ids: Vec<String>,
    /// Node positions, metres (x east, y north).
    pub positions_m: Vec<(f64, f64)>,
    /// Roads `(from, to, length)`: node indices and the length along the road, metres, when the
    /// input gives it (else the straight line is taken).
    pub roads: Vec<(usize, usize, Option<f64>)>,
    /// The projection used, for longitude and latitude input.
    pub projection: Option<Projection>,
}

/// The equirectangular projection about `(lon0, lat0)` (module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Longitude of the origin, degrees.
    pub lon0_deg: f64,
    /// Latitude of the origin, degrees.
    pub lat0_deg: f64,
}

impl Projection {
    /// `(lon, lat)` in degrees to `(x, y)` in metres.
    pub fn project(&self, lon_deg: f64, lat_deg: f64) -> (f64, f64) {
        let k = EARTH_RADIUS_M * std::f64::consts::PI / 180.0;
        (
            k * (lon_deg - self.lon0_deg) * self.lat0_deg.to_radians().cos(),
            k * (lat_deg - self.lat0_deg),
        )
    }

    /// The projection about the centroid of `points` (`(lon, lat)`, degrees).
    fn about_centroid(points: &[(f64, f64)]) -> Projection {
        let n = points.len().max(1) as f64;
        Projection {
            lon0_deg: points.iter().map(|p| p.0).sum::<f64>() / n,
            lat0_deg: points.iter().map(|p| p.1).sum::<f64>() / n,
        }
    }
}

/// What to keep and how to draw pads and winds.
#[derive(Debug, Clone, PartialEq)]
pub struct ImportParams {
    /// Seed of the pads and winds.
    pub seed: u64,
    /// Keep only the `N` nodes nearest this centre (in the input's coordinates), then the largest
    /// connected component among them.
    pub nearest: Option<(usize, (f64, f64))>,
    /// Name written in the network file.
    pub name: String,
}

fn bad(
    code: &'static str,
    field: impl Into<String>,
    problem: impl Into<String>,
    fix: &'static str,
) -> Error {
    Error::invalid(code, field, problem, fix)
}

/// Checks a coordinate pair; longitude and latitude also for their range.
fn check_point(x: f64, y: f64, coordinates: Coordinates, field: &str) -> Result<()> {
    let ok = x.is_finite()
        && y.is_finite()
        && match coordinates {
            Coordinates::Metres => true,
            Coordinates::LonLat => (-180.0..=180.0).contains(&x) && (-90.0..=90.0).contains(&y),
        };
    if ok {
        Ok(())
    } else {
        Err(bad(
            "E1952",
            field,
            format!(
                "({x}, {y}) is not a finite point{}",
                match coordinates {
                    Coordinates::Metres => "",
                    Coordinates::LonLat =>
                        " with longitude in [-180, 180] and latitude in [-90, 90]",
                }
            ),
            "give finite coordinates (for longitude/latitude input, longitude first)",
        ))
    }
}

/// Reads the CSV pair.
///
/// # Arguments
/// * `nodes_csv` - header `id,x,y` (any column order, extra columns ignored).
/// * `edges_csv` - header `from,to` and optionally `length_m`.
/// * `coordinates` - how `x` and `y` are given (longitude and latitude: `x` is the longitude).
///
/// # Errors
/// E1950 for a malformed file or a missing column, E1951 for an unknown or repeated node id,
/// E1952 for a coordinate that is not a finite point (or out of the longitude/latitude range),
/// E1953 for a length that is not finite and above 0.
pub fn read_csv(nodes_csv: &str, edges_csv: &str, coordinates: Coordinates) -> Result<RoadNetwork> {
    let nodes = table(nodes_csv, "nodes", &["id", "x", "y"])?;
    let mut ids = Vec::with_capacity(nodes.len());
    let mut points = Vec::with_capacity(nodes.len());
    let mut index = HashMap::new();
    for (row, cells) in nodes.iter().enumerate() {
        let field = format!("nodes line {}", row + 2);
        let id = cells[0].trim().to_string();
        if id.is_empty() || index.insert(id.clone(), row).is_some() {
            return Err(bad(
                "E1951",
                field,
                format!("node id `{id}` is empty or repeated"),
                "give every node a distinct id",
            ));
        }
        let x = number(&cells[1], &field, "x")?;
        let y = number(&cells[2], &field, "y")?;
        check_point(x, y, coordinates, &field)?;
        ids.push(id);
        points.push((x, y));
    }
    let edges = table(edges_csv, "edges", &["from", "to", "length_m?"])?;
    let mut roads = Vec::with_capacity(edges.len());
    for (row, cells) in edges.iter().enumerate() {
        let field = format!("edges line {}", row + 2);
        let end = |cell: &str| {
            index.get(cell.trim()).copied().ok_or_else(|| {
                bad(
                    "E1951",
                    &field,
                    format!("unknown node id `{}`", cell.trim()),
                    "use ids of the nodes file",
                )
            })
        };
        let (a, b) = (end(&cells[0])?, end(&cells[1])?);
        let length = match cells.get(2).map(|c| c.trim()).filter(|c| !c.is_empty()) {
            None => None,
            Some(c) => Some(length(number(c, &field, "length_m")?, &field)?),
        };
        roads.push((a, b, length));
    }
    Ok(project(ids, points, roads, coordinates))
}

/// Reads a GeoJSON `FeatureCollection` of `LineString` and `MultiLineString` features in
/// longitude and latitude; other geometries are skipped.
///
/// # Errors
/// E1950 for text that is not such a collection, E1952 for a position that is not a finite
/// longitude and latitude.
pub fn read_geojson(text: &str) -> Result<RoadNetwork> {
    let value: serde_json::Value = serde_json::from_str(text).map_err(|e| {
        bad(
            "E1950",
            "geojson",
            format!("not JSON: {e}"),
            "give a GeoJSON FeatureCollection",
        )
    })?;
    let features = value
        .get("features")
        .and_then(|f| f.as_array())
        .ok_or_else(|| {
            bad(
                "E1950",
                "geojson.features",
                "no `features` array",
                "give a GeoJSON FeatureCollection",
            )
        })?;
    let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
    for (i, feature) in features.iter().enumerate() {
        let geometry = &feature["geometry"];
        let field = format!("features[{i}].geometry.coordinates");
        let parts: Vec<&serde_json::Value> = match geometry["type"].as_str() {
            Some("LineString") => vec![&geometry["coordinates"]],
            Some("MultiLineString") => geometry["coordinates"]
                .as_array()
                .map(|a| a.iter().collect())
                .unwrap_or_default(),
            _ => continue,
        };
        for part in parts {
            let positions = part.as_array().ok_or_else(|| {
                bad(
                    "E1950",
                    &field,
                    "not an array of positions",
                    "give [lon, lat] positions",
                )
            })?;
            let mut line = Vec::with_capacity(positions.len());
            for p in positions {
                let (lon, lat) = match (
                    p.get(0).and_then(|v| v.as_f64()),
                    p.get(1).and_then(|v| v.as_f64()),
                ) {
                    (Some(lon), Some(lat)) => (lon, lat),
                    _ => {
                        return Err(bad(
                            "E1950",
                            &field,
                            format!("{p} is not a [lon, lat] position"),
                            "give [lon, lat] positions",
                        ))
                    }
                };
                check_point(lon, lat, Coordinates::LonLat, &field)?;
                line.push((lon, lat));
            }
            if line.len() >= 2 {
                lines.push(line);
            }
        }
    }
    // Intersections: line ends, and vertices met more than once.
    let key = |p: (f64, f64)| (p.0.to_bits(), p.1.to_bits());
    let mut seen: HashMap<(u64, u64), usize> = HashMap::new();
    for line in &lines {
        for &p in line {
            *seen.entry(key(p)).or_insert(0) += 1;
        }
    }
    let projection =
        Projection::about_centroid(&lines.iter().flatten().copied().collect::<Vec<_>>());
    let mut index: HashMap<(u64, u64), usize> = HashMap::new();
    let mut ids = Vec::new();
    let mut points = Vec::new();
    let mut node_of = |p: (f64, f64), ids: &mut Vec<String>, points: &mut Vec<(f64, f64)>| {
        *index.entry(key(p)).or_insert_with(|| {
            ids.push(format!("n{}", ids.len()));
            points.push(p);
            points.len() - 1
        })
    };
    let mut roads = Vec::new();
    for line in &lines {
        let mut start = node_of(line[0], &mut ids, &mut points);
        let mut length_m = 0.0;
        for (k, w) in line.windows(2).enumerate() {
            length_m += great_circle_m(w[0], w[1]);
            let last = k + 2 == line.len();
            if last || seen[&key(w[1])] > 1 {
                let end = node_of(w[1], &mut ids, &mut points);
                roads.push((start, end, Some(length_m)));
                start = end;
                length_m = 0.0;
            }
        }
    }
    let positions_m = points
        .iter()
        .map(|&(lon, lat)| projection.project(lon, lat))
        .collect();
    Ok(RoadNetwork {
        ids,
        positions_m,
        roads,
        projection: Some(projection),
    })
}

/// Great-circle distance between two `(lon, lat)` points in degrees on the sphere of radius
/// [`EARTH_RADIUS_M`] (haversine formula), m.
pub fn great_circle_m(a: (f64, f64), b: (f64, f64)) -> f64 {
    let (lat1, lat2) = (a.1.to_radians(), b.1.to_radians());
    let dlat = lat2 - lat1;
    let dlon = (b.0 - a.0).to_radians();
    let h = (dlat / 2.0).sin().powi(2) + lat1.cos() * lat2.cos() * (dlon / 2.0).sin().powi(2);
    2.0 * EARTH_RADIUS_M * h.sqrt().min(1.0).asin()
}

/// The rows of a CSV text with the named columns (a name ending in `?` is optional: an empty cell
/// when absent).
fn table(text: &str, file: &str, columns: &[&str]) -> Result<Vec<Vec<String>>> {
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes());
    let malformed = |e: csv::Error| {
        bad(
            "E1950",
            format!("{file} file"),
            format!("not CSV: {e}"),
            "give a CSV file with a header line",
        )
    };
    let header = reader.headers().map_err(malformed)?.clone();
    let mut at = Vec::with_capacity(columns.len());
    for c in columns {
        let (name, optional) = match c.strip_suffix('?') {
            Some(name) => (name, true),
            None => (*c, false),
        };
        match header.iter().position(|h| h == name) {
            Some(i) => at.push(Some(i)),
            None if optional => at.push(None),
            None => {
                return Err(bad(
                    "E1950",
                    format!("{file} file"),
                    format!("no column `{name}` in the header"),
                    "name the columns in the first line",
                ))
            }
        }
    }
    let mut rows = Vec::new();
    for record in reader.records() {
        let record = record.map_err(malformed)?;
        rows.push(
            at.iter()
                .map(|i| i.and_then(|i| record.get(i)).unwrap_or("").to_string())
                .collect(),
        );
    }
    Ok(rows)
}

fn number(cell: &str, field: &str, column: &str) -> Result<f64> {
    cell.trim().parse::<f64>().map_err(|_| {
        bad(
            "E1950",
            format!("{field}, {column}"),
            format!("`{cell}` is not a number"),
            "give a number",
        )
    })
}

fn length(v: f64, field: &str) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(bad(
            "E1953",
            format!("{field}, length_m"),
            format!("{v} is not a length above 0"),
            "give the road's length in metres, or leave the cell empty for the straight line",
        ))
    }
}

/// The network in metres, projecting longitude and latitude about the centroid.
fn project(
    ids: Vec<String>,
    points: Vec<(f64, f64)>,
    roads: Vec<(usize, usize, Option<f64>)>,
    coordinates: Coordinates,
) -> RoadNetwork {
    let projection =
        (coordinates == Coordinates::LonLat).then(|| Projection::about_centroid(&points));
    let positions_m = match projection {
        Some(p) => points
            .iter()
            .map(|&(lon, lat)| p.project(lon, lat))
            .collect(),
        None => points,
    };
    RoadNetwork {
        ids,
        positions_m,
        roads,
        projection,
    }
}

/// The skyway network of a road network (module documentation).
///
/// Steps: roads joining a node to itself are dropped, and of several roads between two nodes the
/// shortest is kept; with `nearest = (N, centre)` the `N` nodes nearest the centre (ties: file
/// order) are kept; then the largest connected component (ties: the one with the first node in
/// file order). Nodes keep their file order and ids; pads and winds are drawn from the seed, pads
/// by node then winds by edge (sorted by node indices), with the distributions of
/// [`super::generate_network`]. An edge's `distance_m` is the road's length when the input gives
/// one.
///
/// # Errors
/// E1954 when fewer than 2 nodes are left or `N` is 0, E1955 for more than
/// [`MAX_IMPORT_NODES`] nodes; then every rule of the network validation.
///
/// # Complexity
/// O((V + E) log V).
pub fn to_skyway(road: &RoadNetwork, params: &ImportParams) -> Result<Network> {
    let n = road.positions_m.len();
    if n > MAX_IMPORT_NODES {
        return Err(bad(
            "E1955",
            "nodes",
            format!("{n} nodes, more than {MAX_IMPORT_NODES}"),
            "cut the road network to a smaller area, or keep the nodes nearest a centre (--nearest)",
        ));
    }
    let keep = match params.nearest {
        Some((count, centre)) => nearest_nodes(road, count, centre)?,
        None => vec![true; n],
    };
    let best = shortest_roads(road, &keep);
    let kept = largest_component(n, &keep, &best)?;
    let network = drawn_network(road, params, &kept, &best);
    let violations: Vec<Violation> = validate_network(&network);
    if !violations.is_empty() {
        return Err(Error::Invalid(violations));
    }
    Ok(network)
}

/// Which nodes are kept: the `count` nearest `centre` (in the input's coordinates; ties: file
/// order).
fn nearest_nodes(road: &RoadNetwork, count: usize, centre: (f64, f64)) -> Result<Vec<bool>> {
    if count == 0 {
        return Err(bad(
            "E1954",
            "--nearest",
            "0 nodes",
            "give --nearest 2 or more",
        ));
    }
    let n = road.positions_m.len();
    let centre_m = match road.projection {
        Some(p) => p.project(centre.0, centre.1),
        None => centre,
    };
    let d2 = |i: usize| {
        let (x, y) = road.positions_m[i];
        (x - centre_m.0).powi(2) + (y - centre_m.1).powi(2)
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| d2(a).total_cmp(&d2(b)).then(a.cmp(&b)));
    let mut keep = vec![false; n];
    for &i in order.iter().take(count) {
        keep[i] = true;
    }
    Ok(keep)
}

/// The shortest road per pair of kept nodes `(a, b)`, `a < b`: its length when the input gives
/// one (a road without one counts as the straight line). Roads from a node to itself are dropped.
fn shortest_roads(road: &RoadNetwork, keep: &[bool]) -> HashMap<(usize, usize), Option<f64>> {
    let euclid = |a: usize, b: usize| {
        let (p, q) = (road.positions_m[a], road.positions_m[b]);
        ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt()
    };
    let mut best: HashMap<(usize, usize), Option<f64>> = HashMap::new();
    for &(a, b, length) in &road.roads {
        if a == b || !keep[a] || !keep[b] {
            continue;
        }
        let pair = (a.min(b), a.max(b));
        let len = |l: Option<f64>| l.unwrap_or_else(|| euclid(pair.0, pair.1));
        best.entry(pair)
            .and_modify(|old| {
                if len(length) < len(*old) {
                    *old = length;
                }
            })
            .or_insert(length);
    }
    best
}

/// The kept nodes of the largest connected component of the roads `best` (ties: the one with
/// the first node in file order), in file order.
///
/// # Errors
/// E1954 when fewer than 2 nodes are left.
fn largest_component(
    n: usize,
    keep: &[bool],
    best: &HashMap<(usize, usize), Option<f64>>,
) -> Result<Vec<usize>> {
    let mut components = UnionFind::new(n);
    for &(a, b) in best.keys() {
        components.union(a, b);
    }
    let label = components.into_labeling();
    let mut size: HashMap<usize, usize> = HashMap::new();
    for i in (0..n).filter(|&i| keep[i]) {
        *size.entry(label[i]).or_insert(0) += 1;
    }
    let largest = (0..n)
        .filter(|&i| keep[i])
        .max_by(|&a, &b| size[&label[a]].cmp(&size[&label[b]]).then(b.cmp(&a)))
        .map(|i| label[i]);
    let kept: Vec<usize> = (0..n)
        .filter(|&i| keep[i] && Some(label[i]) == largest)
        .collect();
    if kept.len() < 2 {
        return Err(bad(
            "E1954",
            "nodes",
            format!(
                "{} node(s) left in the largest connected component",
                kept.len()
            ),
            "give a road network (or a --nearest selection) with at least two joined intersections",
        ));
    }
    Ok(kept)
}

/// The skyway network of the `kept` nodes and the roads `best` between them (edges sorted by
/// node indices), pads then winds drawn from the seed.
fn drawn_network(
    road: &RoadNetwork,
    params: &ImportParams,
    kept: &[usize],
    best: &HashMap<(usize, usize), Option<f64>>,
) -> Network {
    let new_index: HashMap<usize, usize> = kept.iter().enumerate().map(|(k, &i)| (i, k)).collect();
    let mut pairs: Vec<(usize, usize, Option<f64>)> = best
        .iter()
        .filter_map(|(&(a, b), &length)| {
            let (x, y) = (*new_index.get(&a)?, *new_index.get(&b)?);
            Some((x.min(y), x.max(y), length))
        })
        .collect();
    pairs.sort_by_key(|p| (p.0, p.1));
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let pads = draw_network_pads(&mut rng, kept.len());
    let winds = draw_edge_winds(&mut rng, pairs.len());
    let nodes = kept
        .iter()
        .zip(pads)
        .map(|(&i, pads)| Node {
            id: road.ids[i].clone(),
            x_m: road.positions_m[i].0,
            y_m: road.positions_m[i].1,
            pads,
            pad_charge_rate_mah_per_min: None,
        })
        .collect();
    let edges = pairs
        .iter()
        .zip(winds)
        .map(|(&(a, b, length), wind)| Edge {
            from: road.ids[kept[a]].clone(),
            to: road.ids[kept[b]].clone(),
            distance_m: length,
            wind_speed_mps: wind.speed_mps,
            wind_from_deg: wind.from_deg,
        })
        .collect();
    Network {
        schema_version: SCHEMA_VERSION,
        name: Some(params.name.clone()),
        nodes,
        edges,
    }
}
