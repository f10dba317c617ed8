//! Profile rules (E2xxx), one function per rule code, and the stated range of every profile
//! quantity (E2013); the table of codes is in [`super`].

use crate::error::{show, Violation};
use crate::problem::profile::{
    FailureModel, FailureTerms, Profile, RedundancyLevel, RedundancyRow,
};
use crate::problem::{MAX_SUPPORT_DRONES, MAX_SWARM_DRONES, SCHEMA_VERSION};

/// Checks a profile's values; reports every violation at once (codes E2xxx, listed in
/// docs/src/errors.md).
///
/// # Arguments
/// * `p` - the profile as read.
///
/// # Returns
/// Every violation found, empty when the profile is usable.
///
/// # Complexity
/// O(rows of the redundancy table).
pub fn validate_profile(p: &Profile) -> Vec<Violation> {
    let mut out = Vec::new();
    e2001_schema_version(p, &mut out);
    e2002_positive(p, &mut out);
    e2003_non_negative(p, &mut out);
    e2004_parasitic_fraction_below_1(p, &mut out);
    e2005_min_position_factor_at_most_1(p, &mut out);
    e2006_counts_in_range(p, &mut out);
    e2007_extra_batteries_within_payload(p, &mut out);
    e2008_reserve_below_support_capacity(p, &mut out);
    e2009_threshold_below_battery(p, &mut out);
    let rows = &p.redundancy.rows;
    e2010_redundancy_table_not_empty(rows, &mut out);
    e2011_first_row_starts_at_0(rows, &mut out);
    for (i, row) in rows.iter().enumerate() {
        e2023_level_at_most_max_support(i, row, &mut out);
        e2012_rows_increasing_within_0_100(rows, i, &mut out);
    }
    e2020_normalised_weights_within_0_1(p, &mut out);
    e2022_per_unit_weights_not_negative(p, &mut out);
    e2021_weighted_sum_has_a_positive_weight(p, &mut out);
    e2013_stated_ranges(p, &mut out);
    out
}

/// The four weights of Eq. 2 with their fields.
fn failure_weights(p: &Profile) -> [(&'static str, f64); 4] {
    let w = &p.failure.weights;
    [
        ("failure.weights.payload", w.payload),
        ("failure.weights.distance", w.distance),
        ("failure.weights.capacity", w.capacity),
        ("failure.weights.wind", w.wind),
    ]
}

/// E2001: the file's schema version is the one this build reads.
fn e2001_schema_version(p: &Profile, out: &mut Vec<Violation>) {
    if p.schema_version != SCHEMA_VERSION {
        out.push(Violation::new(
            "E2001",
            "schema_version",
            format!(
                "profile schema version {} but this build reads {}",
                p.schema_version, SCHEMA_VERSION
            ),
            format!(
                "set schema_version = {} and compare with instances/profiles/paper.toml",
                SCHEMA_VERSION
            ),
        ));
    }
}

/// E2002: strictly positive quantities are finite and above 0: zero or negative makes the models
/// meaningless.
fn e2002_positive(p: &Profile, out: &mut Vec<Violation>) {
    let positive: [(&str, f64); 24] = [
        ("drone.battery_mah", p.drone.battery_mah),
        ("drone.voltage_v", p.drone.voltage_v),
        ("drone.speed_kmh", p.drone.speed_kmh),
        ("drone.empty_mass_kg", p.drone.empty_mass_kg),
        ("drone.battery_mass_kg", p.drone.battery_mass_kg),
        ("drone.max_payload_kg", p.drone.max_payload_kg),
        ("sharing.rate_mah_per_min", p.sharing.rate_mah_per_min),
        ("sharing.range_m", p.sharing.range_m),
        ("sharing.lambda_mah", p.sharing.lambda_mah),
        (
            "pads.charge_rate_mah_per_min",
            p.pads.charge_rate_mah_per_min,
        ),
        ("energy.endurance_min", p.energy.endurance_min),
        ("energy.wind_limit_mps", p.energy.wind_limit_mps),
        ("formation.spacing_m", p.formation.spacing_m),
        ("failure.payload_norm_kg", p.failure.payload_norm_kg),
        ("energy.payload_exponent", p.energy.payload_exponent),
        ("formation.shield_width_m", p.formation.shield_width_m),
        ("formation.shield_decay_m", p.formation.shield_decay_m),
        ("formation.downwash_width_m", p.formation.downwash_width_m),
        ("formation.upwash_width_m", p.formation.upwash_width_m),
        ("formation.wake_decay_m", p.formation.wake_decay_m),
        ("formation.abreast_width_m", p.formation.abreast_width_m),
        ("formation.abreast_band_m", p.formation.abreast_band_m),
        (
            "formation.min_position_factor",
            p.formation.min_position_factor,
        ),
        ("failure.distance_norm_m", p.failure.distance_norm_m),
    ];
    for (field, v) in positive {
        if !(v.is_finite() && v > 0.0) {
            out.push(Violation::new(
                "E2002",
                field,
                format!("must be a finite number above 0, got {}", show(v)),
                "set a positive value; see instances/profiles/paper.toml for its source",
            ));
        }
    }
}

/// E2003: non-negative quantities are finite and at least 0.
fn e2003_non_negative(p: &Profile, out: &mut Vec<Violation>) {
    let non_negative: [(&str, f64); 9] = [
        ("sharing.gamma_mah", p.sharing.gamma_mah),
        ("sharing.delta_mah", p.sharing.delta_mah),
        ("formation.shield_gain", p.formation.shield_gain),
        ("formation.downwash_gain", p.formation.downwash_gain),
        ("formation.upwash_gain", p.formation.upwash_gain),
        ("formation.upwash_offset_m", p.formation.upwash_offset_m),
        ("formation.wake_onset_m", p.formation.wake_onset_m),
        ("formation.abreast_gain", p.formation.abreast_gain),
        ("formation.abreast_offset_m", p.formation.abreast_offset_m),
    ];
    for (field, v) in non_negative {
        if !(v.is_finite() && v >= 0.0) {
            out.push(Violation::new(
                "E2003",
                field,
                format!("must be a finite number at least 0, got {}", show(v)),
                "set a value of 0 or more",
            ));
        }
    }
}

/// E2004: the parasitic share `c_par` is in [0, 1).
fn e2004_parasitic_fraction_below_1(p: &Profile, out: &mut Vec<Violation>) {
    let c_par = p.energy.parasitic_fraction;
    if !(c_par.is_finite() && (0.0..1.0).contains(&c_par)) {
        out.push(Violation::new(
            "E2004",
            "energy.parasitic_fraction",
            format!("must be in [0, 1), got {}", show(c_par)),
            "set the share of cruise power spent against drag, e.g. 0.1",
        ));
    }
}

/// E2005: the smallest position factor is at most 1 (its sign is E2002's).
fn e2005_min_position_factor_at_most_1(p: &Profile, out: &mut Vec<Violation>) {
    let mf = p.formation.min_position_factor;
    if mf.is_finite() && mf > 1.0 {
        out.push(Violation::new(
            "E2005",
            "formation.min_position_factor",
            format!("must be at most 1, got {}", show(mf)),
            "set a floor in (0, 1], e.g. 0.5",
        ));
    }
}

/// E2006: the swarm size that ranks formations is in 1..=[`MAX_SWARM_DRONES`], and the number of
/// wind direction bins in 1..=360.
fn e2006_counts_in_range(p: &Profile, out: &mut Vec<Violation>) {
    let swarm_size = p.formation.select_swarm_size as usize;
    if !(1..=MAX_SWARM_DRONES).contains(&swarm_size) {
        out.push(Violation::new(
            "E2006",
            "formation.select_swarm_size",
            format!("must be in 1..={}, got {swarm_size}", MAX_SWARM_DRONES),
            "set the swarm size used to rank formations, e.g. 5",
        ));
    }
    if !(1..=360).contains(&p.formation.direction_bins) {
        out.push(Violation::new(
            "E2006",
            "formation.direction_bins",
            format!("must be in 1..=360, got {}", p.formation.direction_bins),
            "set the number of wind direction bins, e.g. 8",
        ));
    }
}

/// E2007: a support drone's extra batteries weigh at most the drone's max payload.
fn e2007_extra_batteries_within_payload(p: &Profile, out: &mut Vec<Violation>) {
    if p.support.extra_batteries > 0 && p.support_payload_kg() > p.drone.max_payload_kg {
        out.push(Violation::new(
            "E2007",
            "support.extra_batteries",
            format!(
                "{} extra batteries weigh {:.3} kg, over drone.max_payload_kg = {} kg",
                p.support.extra_batteries,
                p.support_payload_kg(),
                show(p.drone.max_payload_kg)
            ),
            "carry fewer extra batteries or raise the max payload",
        ));
    }
}

/// E2008: the support reserve `delta` is below a support drone's capacity.
fn e2008_reserve_below_support_capacity(p: &Profile, out: &mut Vec<Violation>) {
    if p.sharing.delta_mah.is_finite()
        && p.drone.battery_mah.is_finite()
        && p.sharing.delta_mah >= p.support_capacity_mah()
    {
        out.push(Violation::new(
            "E2008",
            "sharing.delta_mah",
            format!(
                "support reserve {} mAh is not below the support capacity {} mAh",
                show(p.sharing.delta_mah),
                show(p.support_capacity_mah())
            ),
            "lower the reserve or add extra batteries",
        ));
    }
}

/// E2009: the request threshold `gamma` is below the battery capacity.
fn e2009_threshold_below_battery(p: &Profile, out: &mut Vec<Violation>) {
    if p.sharing.gamma_mah.is_finite()
        && p.drone.battery_mah.is_finite()
        && p.sharing.gamma_mah >= p.drone.battery_mah
    {
        out.push(Violation::new(
            "E2009",
            "sharing.gamma_mah",
            format!(
                "request threshold {} mAh is not below the battery capacity {} mAh",
                show(p.sharing.gamma_mah),
                show(p.drone.battery_mah)
            ),
            "set gamma below drone.battery_mah (the paper profile uses 20% of it)",
        ));
    }
}

/// E2010: the redundancy table has at least one row.
fn e2010_redundancy_table_not_empty(rows: &[RedundancyRow], out: &mut Vec<Violation>) {
    if rows.is_empty() {
        out.push(Violation::new(
            "E2010",
            "redundancy.rows",
            "the redundancy table is empty",
            "list rows from from_pct = 0 upwards, as in instances/profiles/paper.toml",
        ));
    }
}

/// E2011: the redundancy table's first row starts at 0 %.
fn e2011_first_row_starts_at_0(rows: &[RedundancyRow], out: &mut Vec<Violation>) {
    match rows.first() {
        Some(first) if first.from_pct != 0.0 => out.push(Violation::new(
            "E2011",
            "redundancy.rows[0].from_pct",
            format!(
                "the first row must start at 0, got {}",
                show(first.from_pct)
            ),
            "start the table at from_pct = 0",
        )),
        _ => {}
    }
}

/// E2023: a level `n+k` asks for at most [`MAX_SUPPORT_DRONES`] support drones.
fn e2023_level_at_most_max_support(i: usize, row: &RedundancyRow, out: &mut Vec<Violation>) {
    match row.level {
        RedundancyLevel::NPlus(k) if k as usize > MAX_SUPPORT_DRONES => out.push(Violation::new(
            "E2023",
            format!("redundancy.rows[{i}].level"),
            format!(
                "n+{k} asks for more than {} support drones",
                MAX_SUPPORT_DRONES
            ),
            "use a level of at most n+32, or 2n / 2(n+1)",
        )),
        _ => {}
    }
}

/// E2012: row `i` starts within [0, 100] %, above the previous row.
fn e2012_rows_increasing_within_0_100(rows: &[RedundancyRow], i: usize, out: &mut Vec<Violation>) {
    let from_pct = rows[i].from_pct;
    let ok_range = from_pct.is_finite() && (0.0..=100.0).contains(&from_pct);
    let ok_order = i == 0 || from_pct > rows[i - 1].from_pct;
    if !ok_range || !ok_order {
        out.push(Violation::new(
            "E2012",
            format!("redundancy.rows[{i}].from_pct"),
            format!(
                "must be in [0, 100] and above the previous row's, got {}",
                show(from_pct)
            ),
            "list rows in strictly increasing from_pct within 0..100",
        ));
    }
}

/// E2020: under `terms = "normalised"`, each weight of Eq. 2 is in [0, 1].
fn e2020_normalised_weights_within_0_1(p: &Profile, out: &mut Vec<Violation>) {
    if p.failure.terms != FailureTerms::Normalised {
        return;
    }
    for (field, v) in failure_weights(p) {
        if !(v.is_finite() && (0.0..=1.0).contains(&v)) {
            out.push(Violation::new(
                "E2020",
                field,
                format!(
                    "a weight of normalised terms must be in [0, 1], got {}",
                    show(v)
                ),
                "set the weight between 0 and 1, or set failure.terms = \"per-unit\"",
            ));
        }
    }
}

/// E2022: under `terms = "per-unit"`, each weight of Eq. 2 is finite and at least 0.
fn e2022_per_unit_weights_not_negative(p: &Profile, out: &mut Vec<Violation>) {
    if p.failure.terms != FailureTerms::PerUnit {
        return;
    }
    for (field, v) in failure_weights(p) {
        if !(v.is_finite() && v >= 0.0) {
            out.push(Violation::new(
                "E2022",
                field,
                format!(
                    "a per-unit weight must be a finite number at least 0, got {}",
                    show(v)
                ),
                "set the share of a battery the factor consumes per unit of it, e.g. \
                 distance = 0.03 (3% per minute of flight, the paper's example)",
            ));
        }
    }
}

/// E2021: the weighted sum has at least one weight above 0. A negative weight is reported by
/// E2020 or E2022 and does not cancel a positive one.
fn e2021_weighted_sum_has_a_positive_weight(p: &Profile, out: &mut Vec<Violation>) {
    let weights = failure_weights(p);
    let all_finite = weights.iter().all(|(_, v)| v.is_finite());
    let any_positive = weights.iter().any(|(_, v)| *v > 0.0);
    if p.failure.model == FailureModel::WeightedSum && all_finite && !any_positive {
        out.push(Violation::new(
            "E2021",
            "failure.weights",
            "the weighted sum needs at least one weight above 0",
            "give at least one term a positive weight",
        ));
    }
}

/// E2013: each quantity that passed the sign rules above also lies in its stated range
/// ([`profile_ranges`]), so that every number derived from it stays finite. A field already
/// reported as not finite or of the wrong sign (E2002, E2003, E2020, E2022) is not reported twice.
fn e2013_stated_ranges(p: &Profile, out: &mut Vec<Violation>) {
    let reported: Vec<String> = out
        .iter()
        .filter(|v| ["E2002", "E2003", "E2020", "E2022"].contains(&v.code))
        .map(|v| v.field.clone())
        .collect();
    for r in profile_ranges(p) {
        let v = r.value;
        if reported.iter().any(|f| f == r.field) || !v.is_finite() || (r.min..=r.max).contains(&v) {
            continue;
        }
        let unit = if r.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", r.unit)
        };
        let (min, max) = (show(r.min), show(r.max));
        out.push(Violation::new(
            "E2013",
            r.field,
            format!(
                "{}{unit} is outside the stated range [{min}, {max}]{unit}",
                show(v)
            ),
            format!(
                "set a value within [{min}, {max}]{unit} ({}); see \"Ranges\" in \
                 docs/src/inputs.md",
                r.why
            ),
        ));
    }
}

/// One quantity of a profile with its stated range (rule E2013, the table in docs/src/inputs.md,
/// "Ranges").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StatedRange {
    /// The profile field, such as `drone.speed_kmh`.
    pub field: &'static str,
    /// The field's value in the profile checked.
    pub value: f64,
    /// Smallest value allowed (inclusive).
    pub min: f64,
    /// Largest value allowed (inclusive).
    pub max: f64,
    /// Unit of the quantity.
    pub unit: &'static str,
    /// Why the range is what it is, in a few words.
    pub why: &'static str,
}

/// Largest number of extra batteries a support drone may carry (E2013).
pub const MAX_EXTRA_BATTERIES: u32 = 64;

/// Reads a quantity from a profile.
type Reading = fn(&Profile) -> f64;

/// A quantity of a profile with its own stated range: a row of [`PROFILE_RANGES`].
struct RangeRow {
    /// The profile field.
    field: &'static str,
    /// Reads the field's value from a profile.
    value: Reading,
    /// Smallest value allowed (inclusive).
    min: f64,
    /// Largest value allowed (inclusive).
    max: f64,
    /// Unit of the quantity.
    unit: &'static str,
    /// Why the range is what it is.
    why: &'static str,
}

/// Every quantity of a profile with a range of its own, in the order E2013 reports them.
const PROFILE_RANGES: [RangeRow; 21] = [
    RangeRow {
        field: "drone.battery_mah",
        value: |p| p.drone.battery_mah,
        min: 1.0,
        max: 1e6,
        unit: "mAh",
        why: "1 mAh to 1,000 Ah: beyond any drone battery",
    },
    RangeRow {
        field: "drone.voltage_v",
        value: |p| p.drone.voltage_v,
        min: 1.0,
        max: 1e3,
        unit: "V",
        why: "one cell to a 1 kV pack",
    },
    RangeRow {
        field: "drone.speed_kmh",
        value: |p| p.drone.speed_kmh,
        min: 1.0,
        max: 500.0,
        unit: "km/h",
        why: "walking pace to beyond the fastest multirotor",
    },
    RangeRow {
        field: "drone.empty_mass_kg",
        value: |p| p.drone.empty_mass_kg,
        min: 0.01,
        max: 1e3,
        unit: "kg",
        why: "a 10 g micro drone to a 1 t cargo drone",
    },
    RangeRow {
        field: "drone.battery_mass_kg",
        value: |p| p.drone.battery_mass_kg,
        min: 0.001,
        max: 1e3,
        unit: "kg",
        why: "1 g to 1 t",
    },
    RangeRow {
        field: "drone.max_payload_kg",
        value: |p| p.drone.max_payload_kg,
        min: 0.001,
        max: 1e3,
        unit: "kg",
        why: "1 g to 1 t",
    },
    RangeRow {
        field: "support.extra_batteries",
        value: |p| f64::from(p.support.extra_batteries),
        min: 0.0,
        max: MAX_EXTRA_BATTERIES as f64,
        unit: "batteries",
        why: "the paper carries 3; 64 bounds a support drone's capacity",
    },
    RangeRow {
        field: "sharing.rate_mah_per_min",
        value: |p| p.sharing.rate_mah_per_min,
        min: 0.01,
        max: 1e6,
        unit: "mAh/min",
        why: "a trickle to a full battery in well under a second",
    },
    RangeRow {
        field: "sharing.range_m",
        value: |p| p.sharing.range_m,
        min: 0.01,
        max: 1e3,
        unit: "m",
        why: "1 cm to 1 km of wireless transfer",
    },
    RangeRow {
        field: "sharing.lambda_mah",
        value: |p| p.sharing.lambda_mah,
        min: 1.0,
        max: 1e6,
        unit: "mAh",
        why: "at least 1 mAh per FB round, at most a whole battery of the largest size",
    },
    RangeRow {
        field: "pads.charge_rate_mah_per_min",
        value: |p| p.pads.charge_rate_mah_per_min,
        min: 0.1,
        max: 1e6,
        unit: "mAh/min",
        why: "a full 4480 mAh charge in 31 days to well under a second",
    },
    RangeRow {
        field: "energy.endurance_min",
        value: |p| p.energy.endurance_min,
        min: 1.0,
        max: 1e4,
        unit: "min",
        why: "1 min to a week aloft",
    },
    RangeRow {
        field: "energy.payload_exponent",
        value: |p| p.energy.payload_exponent,
        min: 0.1,
        max: 5.0,
        unit: "",
        why: "momentum theory gives 1.5",
    },
    RangeRow {
        field: "energy.wind_limit_mps",
        value: |p| p.energy.wind_limit_mps,
        min: 0.1,
        max: 100.0,
        unit: "m/s",
        why: "100 m/s is beyond any storm a drone flies in",
    },
    RangeRow {
        field: "formation.spacing_m",
        value: |p| p.formation.spacing_m,
        min: 0.01,
        max: 100.0,
        unit: "m",
        why: "1 cm to 100 m between neighbours",
    },
    RangeRow {
        field: "formation.shield_gain",
        value: |p| p.formation.shield_gain,
        min: 0.0,
        max: 1.0,
        unit: "",
        why: "a fraction of a drone's consumption",
    },
    RangeRow {
        field: "formation.downwash_gain",
        value: |p| p.formation.downwash_gain,
        min: 0.0,
        max: 1.0,
        unit: "",
        why: "a fraction of a drone's consumption",
    },
    RangeRow {
        field: "formation.upwash_gain",
        value: |p| p.formation.upwash_gain,
        min: 0.0,
        max: 1.0,
        unit: "",
        why: "a fraction of a drone's consumption",
    },
    RangeRow {
        field: "formation.abreast_gain",
        value: |p| p.formation.abreast_gain,
        min: 0.0,
        max: 1.0,
        unit: "",
        why: "a fraction of a drone's consumption",
    },
    RangeRow {
        field: "failure.payload_norm_kg",
        value: |p| p.failure.payload_norm_kg,
        min: 0.001,
        max: 1e3,
        unit: "kg",
        why: "1 g to 1 t",
    },
    RangeRow {
        field: "failure.distance_norm_m",
        value: |p| p.failure.distance_norm_m,
        min: 1.0,
        max: 1e7,
        unit: "m",
        why: "1 m to a quarter of the Earth's circumference",
    },
];

/// The lengths of the formation's wake model (m) with their smallest values: an offset or an
/// onset may be 0, a width or a decay is at least 1 mm. Each at most 1 km.
const WAKE_LENGTHS: [(&str, Reading, f64); 10] = [
    (
        "formation.shield_width_m",
        |p| p.formation.shield_width_m,
        0.001,
    ),
    (
        "formation.shield_decay_m",
        |p| p.formation.shield_decay_m,
        0.001,
    ),
    (
        "formation.downwash_width_m",
        |p| p.formation.downwash_width_m,
        0.001,
    ),
    (
        "formation.upwash_offset_m",
        |p| p.formation.upwash_offset_m,
        0.0,
    ),
    (
        "formation.upwash_width_m",
        |p| p.formation.upwash_width_m,
        0.001,
    ),
    (
        "formation.wake_decay_m",
        |p| p.formation.wake_decay_m,
        0.001,
    ),
    ("formation.wake_onset_m", |p| p.formation.wake_onset_m, 0.0),
    (
        "formation.abreast_offset_m",
        |p| p.formation.abreast_offset_m,
        0.0,
    ),
    (
        "formation.abreast_width_m",
        |p| p.formation.abreast_width_m,
        0.001,
    ),
    (
        "formation.abreast_band_m",
        |p| p.formation.abreast_band_m,
        0.001,
    ),
];

/// Every quantity of a profile with its stated range. With every value in range, an edge of at
/// most 1e6 m flown at 1 km/h lasts at most 6e4 min, a drone consumes at most about 1e39 mAh/min
/// (base rate 1e6, payload factor (1 + 1000 / 0.011)^5, wind factor (100.3 / 0.278)^3), and a
/// charge of at most 65 x 1e6 mAh at 0.1 mAh/min lasts at most 6.5e8 min: every derived number
/// stays finite.
///
/// In order: the quantities with a range of their own, the wake lengths, then, with per-unit
/// failure terms, the four weights of Eq. 2.
pub fn profile_ranges(p: &Profile) -> Vec<StatedRange> {
    let own = PROFILE_RANGES.iter().map(|r| StatedRange {
        field: r.field,
        value: (r.value)(p),
        min: r.min,
        max: r.max,
        unit: r.unit,
        why: r.why,
    });
    let wakes = WAKE_LENGTHS.iter().map(|&(field, value, min)| StatedRange {
        field,
        value: value(p),
        min,
        max: 1e3,
        unit: "m",
        why: "1 mm to 1 km: wakes of a drone",
    });
    let mut out: Vec<StatedRange> = own.chain(wakes).collect();
    if p.failure.terms == FailureTerms::PerUnit {
        out.extend(failure_weights(p).map(|(field, value)| StatedRange {
            field,
            value,
            min: 0.0,
            max: 100.0,
            unit: "",
            why: "100 batteries per unit of the factor",
        }));
    }
    out
}
