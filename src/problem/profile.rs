//! Parameter profile (TOML): every constant of the models, each documented with its source in the
//! shipped profile files under `instances/profiles/`.

use crate::error::Violation;
use serde::{Deserialize, Serialize};

/// A parameter profile.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Schema version, must equal [`super::SCHEMA_VERSION`].
    pub schema_version: u32,
    /// Profile name, such as `paper`.
    pub name: String,
    /// The drone model every drone of the swarm uses.
    pub drone: DroneParams,
    /// What makes a support drone.
    pub support: SupportParams,
    /// In-flight energy sharing (EaaS).
    pub sharing: SharingParams,
    /// Recharging pads at nodes.
    pub pads: PadParams,
    /// Energy model constants (models/energy.md). Defaults to the `paper` profile's values.
    #[serde(default)]
    pub energy: EnergyParams,
    /// Formation geometry and wake model (models/formation.md). Defaults to the `paper` values.
    #[serde(default)]
    pub formation: FormationParams,
    /// Redundancy table: failure probability (percent) to number of support drones (paper Table 2).
    #[serde(default)]
    pub redundancy: RedundancyParams,
    /// Failure probability of Eq. 2 (models/precompose.md). Defaults to the `paper` values.
    #[serde(default)]
    pub failure: FailureParams,
    /// Readings of the paper where it can be taken more than one way; each field defaults to the
    /// reading argued in models/ ([`Readings::literal`] gives the paper's literal one).
    #[serde(default)]
    pub readings: Readings,
}

/// Readings of the paper's Algorithms 1-3 where the text can be taken more than one way. The
/// default of each is argued in `models/eaas.md` (PB, FB) and `models/compose.md` (Algorithm 1);
/// [`Readings::literal`] is the paper taken word for word (`--literal` on `solve` and `batch`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Readings {
    /// PB: a request whose start `st` is earlier than its support drone's next free time starts
    /// when the support drone becomes free (`true`, default); `false` skips it, as Algorithm 2's
    /// literal test `er.st >= SD.st` does.
    pub pb_wait_for_support: bool,
    /// PB: how much energy a request asks for (`re`).
    pub pb_request: PbRequest,
    /// FB: a full drone's round still costs the support drone `lambda` of its sharing budget and
    /// one round of time, as Algorithm 3's literal pseudo-code does (`true`); default `false`
    /// skips it at no cost.
    pub fb_charge_skipped: bool,
    /// Algorithm 1: which nodes are candidates for the next stop (lines 12-14).
    pub candidates: Candidates,
}

/// Size `re` of a PB energy request raised at time `st` (models/eaas.md, "PB's request size").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum PbRequest {
    /// What the drone needs to end the hop at the threshold `gamma` under the schedule so far, at
    /// most `C - b(st)` (default: requests differ by need, so the paper's `re`-descending key
    /// and its worked example of simultaneous requests of different sizes apply).
    ToHopEnd,
    /// Fill the battery: `re = C - b(st)`, which is `C - gamma` for every request raised at the
    /// threshold (literal "fully charge"; every request then holds its support drone to the end).
    Fill,
}

/// Candidate next stops of Algorithm 1 (models/compose.md, "Algorithm 1's candidates").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Candidates {
    /// Every node with pads not yet stopped at, reached along the shortest path (default).
    PadNodes,
    /// The literal "nearest neighbor nodes": the nodes adjacent to the current one in the skyway
    /// network; the swarm passes a neighbour without pads without charging and flies on.
    Adjacent,
}

display_as_value_name!(PbRequest, Candidates);

impl Default for Readings {
    fn default() -> Self {
        Readings {
            pb_wait_for_support: true,
            pb_request: PbRequest::ToHopEnd,
            fb_charge_skipped: false,
            candidates: Candidates::PadNodes,
        }
    }
}

impl Readings {
    /// The paper word for word: PB skips a request that starts before its support drone is
    /// free and fills the battery, FB charges a round for a full drone, Algorithm 1 looks at the
    /// adjacent nodes only.
    pub fn literal() -> Readings {
        Readings {
            pb_wait_for_support: false,
            pb_request: PbRequest::Fill,
            fb_charge_skipped: true,
            candidates: Candidates::Adjacent,
        }
    }
}

/// Drone model (paper Table 3: DJI Phantom 3).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DroneParams {
    /// Capacity of one battery, mAh.
    pub battery_mah: f64,
    /// Battery voltage, V.
    pub voltage_v: f64,
    /// Ground speed of the swarm, km/h.
    pub speed_kmh: f64,
    /// Mass of the drone without battery and payload, kg.
    pub empty_mass_kg: f64,
    /// Mass of one battery, kg.
    pub battery_mass_kg: f64,
    /// Heaviest package one drone may carry, kg.
    pub max_payload_kg: f64,
}

/// Support drones: same airframe, extra batteries as payload.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportParams {
    /// Extra batteries carried (3 in the paper: capacity 4x a delivery drone's).
    pub extra_batteries: u32,
}

/// In-flight energy sharing parameters (paper 5.2.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SharingParams {
    /// Transfer rate `rho` from a support drone to one consumer, mAh/min.
    pub rate_mah_per_min: f64,
    /// Largest support-to-consumer distance at which energy can be transferred, m.
    pub range_m: f64,
    /// Fairness-based round size `lambda`, mAh.
    pub lambda_mah: f64,
    /// Priority-based request threshold `gamma`: a delivery drone requests energy when its battery
    /// falls below this, mAh.
    pub gamma_mah: f64,
    /// Support reserve `delta`: a support drone stops sharing at this battery level, mAh.
    pub delta_mah: f64,
}

/// Recharging pads at nodes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PadParams {
    /// Default charge rate of one pad, mAh/min (a node may override it).
    pub charge_rate_mah_per_min: f64,
}

/// Energy model constants; see models/energy.md. Symbols: `r0` base rate, `e_m` payload exponent,
/// `c_par` parasitic share.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct EnergyParams {
    /// Flight time of an unloaded drone on one battery in still air at cruise, min. The base rate is
    /// `r0 = drone.battery_mah / endurance_min` (mAh/min).
    pub endurance_min: f64,
    /// Exponent `e_m` of the payload factor `((m0 + p) / m0)^e_m` (momentum theory: 3/2).
    pub payload_exponent: f64,
    /// Share `c_par` of still-air cruise power spent against parasitic drag; the wind factor is
    /// `(1 - c_par) + c_par * (v_air / v)^3`, so it stays at least `1 - c_par > 0`.
    pub parasitic_fraction: f64,
    /// Safe-flight wind limit, m/s: winds at or above it are refused.
    pub wind_limit_mps: f64,
}

impl Default for EnergyParams {
    fn default() -> Self {
        EnergyParams {
            endurance_min: 23.0,
            payload_exponent: 1.5,
            parasitic_fraction: 0.1,
            wind_limit_mps: 13.8,
        }
    }
}

/// Formation geometry and the wake/shielding model over slot positions; see models/formation.md.
/// Every gain is a fraction of a drone's consumption; every length is in metres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FormationParams {
    /// Distance between neighbouring drones in every formation, m (1 m in the paper).
    pub spacing_m: f64,
    /// Drag shielding `a_sh` behind an upstream drone (a benefit).
    pub shield_gain: f64,
    /// Lateral half-width `sigma_sh` of the shielded region, m.
    pub shield_width_m: f64,
    /// Downstream decay length `L_sh` of the shielding (the drafting wake recovers quickly), m.
    pub shield_decay_m: f64,
    /// Rotor downwash penalty `a_dw` directly behind an upstream drone.
    pub downwash_gain: f64,
    /// Lateral half-width `sigma_dw` of the downwash region, m.
    pub downwash_width_m: f64,
    /// Upwash benefit `a_up` beside an upstream drone's wake.
    pub upwash_gain: f64,
    /// Lateral offset `b_up` of the upwash peak from the upstream drone's track, m.
    pub upwash_offset_m: f64,
    /// Width `sigma_up` of the upwash peak, m.
    pub upwash_width_m: f64,
    /// Downstream decay length `L` of the downwash and upwash (trailing vortices persist), m.
    pub wake_decay_m: f64,
    /// Downstream distance `s0` over which a wake builds up (factor `s / (s + s0)`), m.
    pub wake_onset_m: f64,
    /// Mutual benefit `a_ab` of flying abreast (side-by-side rotors), applied to both drones.
    pub abreast_gain: f64,
    /// Lateral offset `b_ab` of the abreast benefit peak, m.
    pub abreast_offset_m: f64,
    /// Lateral width `sigma_ab` of the abreast peak, m.
    pub abreast_width_m: f64,
    /// Downstream half-width `sigma_as` of the band counted as abreast, m.
    pub abreast_band_m: f64,
    /// Smallest position factor; the wake model never brings a drone below it.
    pub min_position_factor: f64,
    /// Swarm size used to rank formations when the network's formation is chosen before any
    /// request is known.
    pub select_swarm_size: u32,
    /// Number of equal direction bins (the first centred on north) for the most frequent wind
    /// direction.
    pub direction_bins: u32,
}

impl Default for FormationParams {
    fn default() -> Self {
        FormationParams {
            spacing_m: 1.0,
            shield_gain: 0.28,
            shield_width_m: 0.55,
            shield_decay_m: 1.45,
            downwash_gain: 0.23,
            downwash_width_m: 0.12,
            upwash_gain: 0.17,
            upwash_offset_m: 1.07,
            upwash_width_m: 0.18,
            wake_decay_m: 5.5,
            wake_onset_m: 0.3,
            abreast_gain: 0.04,
            abreast_offset_m: 1.47,
            abreast_width_m: 1.12,
            abreast_band_m: 0.92,
            min_position_factor: 0.5,
            select_swarm_size: 5,
            direction_bins: 8,
        }
    }
}

/// A redundancy level of the paper's Table 2: how many support drones for `N` delivery drones.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum RedundancyLevel {
    /// `N+k`: k support drones.
    NPlus(u32),
    /// `2N`: N support drones.
    TwoN,
    /// `2(N+1)`: N+2 support drones.
    TwoNPlusOne,
}

impl RedundancyLevel {
    /// Number of support drones for `n` delivery drones.
    pub fn support_drones(self, n: usize) -> usize {
        match self {
            RedundancyLevel::NPlus(k) => k as usize,
            RedundancyLevel::TwoN => n,
            RedundancyLevel::TwoNPlusOne => n + 2,
        }
    }
}

impl TryFrom<String> for RedundancyLevel {
    type Error = String;
    fn try_from(text: String) -> Result<Self, String> {
        let t: String = text
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect::<String>()
            .to_lowercase();
        if t == "2n" {
            return Ok(RedundancyLevel::TwoN);
        }
        if t == "2(n+1)" {
            return Ok(RedundancyLevel::TwoNPlusOne);
        }
        if let Some(k) = t.strip_prefix("n+") {
            if let Ok(k) = k.parse::<u32>() {
                return Ok(RedundancyLevel::NPlus(k));
            }
        }
        Err(format!(
            "unknown redundancy level `{text}`: use \"n+K\" (K a whole number), \"2n\" or \"2(n+1)\""
        ))
    }
}

impl From<RedundancyLevel> for String {
    fn from(level: RedundancyLevel) -> String {
        match level {
            RedundancyLevel::NPlus(k) => format!("n+{k}"),
            RedundancyLevel::TwoN => "2n".to_string(),
            RedundancyLevel::TwoNPlusOne => "2(n+1)".to_string(),
        }
    }
}

/// One row of the redundancy table: from this failure probability (percent, inclusive) up to the next
/// row's, use this level.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RedundancyRow {
    /// Lowest failure probability of the row, percent.
    pub from_pct: f64,
    /// Redundancy level of the row.
    pub level: RedundancyLevel,
}

/// The redundancy table (paper Table 2).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RedundancyParams {
    /// Rows in increasing `from_pct`, the first at 0.
    pub rows: Vec<RedundancyRow>,
}

impl Default for RedundancyParams {
    fn default() -> Self {
        let row = |from_pct: f64, level| RedundancyRow { from_pct, level };
        RedundancyParams {
            rows: vec![
                row(0.0, RedundancyLevel::NPlus(1)),
                row(20.0, RedundancyLevel::NPlus(2)),
                row(40.0, RedundancyLevel::NPlus(3)),
                row(60.0, RedundancyLevel::NPlus(4)),
                row(80.0, RedundancyLevel::TwoN),
            ],
        }
    }
}

/// How Eq. 2 combines its four weighted normalised terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureModel {
    /// As written: `P = 100 * prod_i (w_i * p_i)`.
    Product,
    /// `P = 100 * sum_i (w_i * p_i) / sum_i w_i` of normalised terms; `P = 100 * sum_i (w_i * p_i)`
    /// of per-unit terms (each `w_i * p_i` is already a share of a battery).
    WeightedSum,
}

/// How the four factors enter Eq. 2 (models/precompose.md, "Two readings of the terms").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureTerms {
    /// Each factor normalised to [0, 1] (the paper's "we normalize them between 0 and 1"):
    /// `p1 = D_pr`, `p2 = d / distance_norm_m`, `p3 = C / E_c`, `p4 = W / wind_limit_mps`, each
    /// clamped to [0, 1]; the weights are fractions in [0, 1].
    #[default]
    Normalised,
    /// Each factor in its own unit (the paper's worked example `w2 = 0.03` per minute, 5 km at
    /// 30 km/h, `P_2 = 0.3`): `p1 = D_pr` (ratio), `p2 = d / v` (minutes of flight),
    /// `p3 = C / E_c` (ratio), `p4 = W` (m/s). A weight is the share of a battery the factor
    /// consumes per unit of it, so `w_i * p_i` is a share of a battery; the weighted sum adds
    /// the shares without dividing by the weights.
    PerUnit,
}

/// Weights `w_1..w_4` of Eq. 2. Under [`FailureTerms::Normalised`] fractions in [0, 1]; under
/// [`FailureTerms::PerUnit`] shares of a battery per unit of the factor (per unit of `D_pr`, per
/// minute of flight, per unit of `C / E_c`, per m/s of wind), at least 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FailureWeights {
    /// `w_1`, payload ratio term.
    pub payload: f64,
    /// `w_2`, route distance term.
    pub distance: f64,
    /// `w_3`, support capacity term.
    pub capacity: f64,
    /// `w_4`, averaged wind term.
    pub wind: f64,
}

/// Failure probability of Eq. 2; see models/precompose.md.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FailureParams {
    /// Product (as written) or weighted sum.
    pub model: FailureModel,
    /// Normalised terms (the default) or terms in their own units.
    #[serde(default)]
    pub terms: FailureTerms,
    /// Eq. 1's normaliser of the payload ratio, kg (5 kg in the paper; not the max payload).
    pub payload_norm_kg: f64,
    /// Route distance mapped to the distance term 1, m.
    pub distance_norm_m: f64,
    /// Weights of the four terms.
    pub weights: FailureWeights,
}

impl Default for FailureParams {
    fn default() -> Self {
        FailureParams {
            model: FailureModel::Product,
            terms: FailureTerms::Normalised,
            payload_norm_kg: 5.0,
            distance_norm_m: 11_500.0,
            weights: FailureWeights {
                payload: 1.0,
                distance: 1.0,
                capacity: 1.0,
                wind: 1.0,
            },
        }
    }
}

impl Profile {
    /// Base rate `r0` of an unloaded drone at cruise in still air, mAh/min.
    pub fn base_rate_mah_per_min(&self) -> f64 {
        self.drone.battery_mah / self.energy.endurance_min
    }

    /// Takeoff mass `m0` of a drone with its own battery and no payload, kg.
    pub fn base_mass_kg(&self) -> f64 {
        self.drone.empty_mass_kg + self.drone.battery_mass_kg
    }

    /// Payload of a support drone (its extra batteries), kg.
    pub fn support_payload_kg(&self) -> f64 {
        self.support.extra_batteries as f64 * self.drone.battery_mass_kg
    }

    /// Capacity of a support drone (own battery plus extra batteries), mAh.
    pub fn support_capacity_mah(&self) -> f64 {
        (1 + self.support.extra_batteries) as f64 * self.drone.battery_mah
    }

    /// Cruise ground speed, m/s.
    pub fn speed_mps(&self) -> f64 {
        self.drone.speed_kmh / 3.6
    }
}

/// One quantity of a profile with its stated range (rule E2013, the table in README.md, "Ranges").
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

/// Every quantity of a profile with its stated range. With every value in range, an edge of at
/// most 1e6 m flown at 1 km/h lasts at most 6e4 min, a drone consumes at most about 1e39 mAh/min
/// (base rate 1e6, payload factor (1 + 1000 / 0.011)^5, wind factor (100.3 / 0.278)^3), and a
/// charge of at most 65 x 1e6 mAh at 0.1 mAh/min lasts at most 6.5e8 min: every derived number
/// stays finite.
pub fn profile_ranges(p: &Profile) -> Vec<StatedRange> {
    let r = |field, value, min, max, unit, why| StatedRange {
        field,
        value,
        min,
        max,
        unit,
        why,
    };
    let f = &p.formation;
    let mut out = vec![
        r(
            "drone.battery_mah",
            p.drone.battery_mah,
            1.0,
            1e6,
            "mAh",
            "1 mAh to 1,000 Ah: beyond any drone battery",
        ),
        r(
            "drone.voltage_v",
            p.drone.voltage_v,
            1.0,
            1e3,
            "V",
            "one cell to a 1 kV pack",
        ),
        r(
            "drone.speed_kmh",
            p.drone.speed_kmh,
            1.0,
            500.0,
            "km/h",
            "walking pace to beyond the fastest multirotor",
        ),
        r(
            "drone.empty_mass_kg",
            p.drone.empty_mass_kg,
            0.01,
            1e3,
            "kg",
            "a 10 g micro drone to a 1 t cargo drone",
        ),
        r(
            "drone.battery_mass_kg",
            p.drone.battery_mass_kg,
            0.001,
            1e3,
            "kg",
            "1 g to 1 t",
        ),
        r(
            "drone.max_payload_kg",
            p.drone.max_payload_kg,
            0.001,
            1e3,
            "kg",
            "1 g to 1 t",
        ),
        r(
            "support.extra_batteries",
            f64::from(p.support.extra_batteries),
            0.0,
            f64::from(MAX_EXTRA_BATTERIES),
            "batteries",
            "the paper carries 3; 64 bounds a support drone's capacity",
        ),
        r(
            "sharing.rate_mah_per_min",
            p.sharing.rate_mah_per_min,
            0.01,
            1e6,
            "mAh/min",
            "a trickle to a full battery in well under a second",
        ),
        r(
            "sharing.range_m",
            p.sharing.range_m,
            0.01,
            1e3,
            "m",
            "1 cm to 1 km of wireless transfer",
        ),
        r(
            "sharing.lambda_mah",
            p.sharing.lambda_mah,
            1.0,
            1e6,
            "mAh",
            "at least 1 mAh per FB round, at most a whole battery of the largest size",
        ),
        r(
            "pads.charge_rate_mah_per_min",
            p.pads.charge_rate_mah_per_min,
            0.1,
            1e6,
            "mAh/min",
            "a full 4480 mAh charge in 31 days to well under a second",
        ),
        r(
            "energy.endurance_min",
            p.energy.endurance_min,
            1.0,
            1e4,
            "min",
            "1 min to a week aloft",
        ),
        r(
            "energy.payload_exponent",
            p.energy.payload_exponent,
            0.1,
            5.0,
            "",
            "momentum theory gives 1.5",
        ),
        r(
            "energy.wind_limit_mps",
            p.energy.wind_limit_mps,
            0.1,
            100.0,
            "m/s",
            "100 m/s is beyond any storm a drone flies in",
        ),
        r(
            "formation.spacing_m",
            f.spacing_m,
            0.01,
            100.0,
            "m",
            "1 cm to 100 m between neighbours",
        ),
        r(
            "formation.shield_gain",
            f.shield_gain,
            0.0,
            1.0,
            "",
            "a fraction of a drone's consumption",
        ),
        r(
            "formation.downwash_gain",
            f.downwash_gain,
            0.0,
            1.0,
            "",
            "a fraction of a drone's consumption",
        ),
        r(
            "formation.upwash_gain",
            f.upwash_gain,
            0.0,
            1.0,
            "",
            "a fraction of a drone's consumption",
        ),
        r(
            "formation.abreast_gain",
            f.abreast_gain,
            0.0,
            1.0,
            "",
            "a fraction of a drone's consumption",
        ),
        r(
            "failure.payload_norm_kg",
            p.failure.payload_norm_kg,
            0.001,
            1e3,
            "kg",
            "1 g to 1 t",
        ),
        r(
            "failure.distance_norm_m",
            p.failure.distance_norm_m,
            1.0,
            1e7,
            "m",
            "1 m to a quarter of the Earth's circumference",
        ),
    ];
    for (field, value) in [
        ("formation.shield_width_m", f.shield_width_m),
        ("formation.shield_decay_m", f.shield_decay_m),
        ("formation.downwash_width_m", f.downwash_width_m),
        ("formation.upwash_offset_m", f.upwash_offset_m),
        ("formation.upwash_width_m", f.upwash_width_m),
        ("formation.wake_decay_m", f.wake_decay_m),
        ("formation.wake_onset_m", f.wake_onset_m),
        ("formation.abreast_offset_m", f.abreast_offset_m),
        ("formation.abreast_width_m", f.abreast_width_m),
        ("formation.abreast_band_m", f.abreast_band_m),
    ] {
        let min = if field == "formation.upwash_offset_m"
            || field == "formation.wake_onset_m"
            || field == "formation.abreast_offset_m"
        {
            0.0
        } else {
            0.001
        };
        out.push(r(
            field,
            value,
            min,
            1e3,
            "m",
            "1 mm to 1 km: wakes of a drone",
        ));
    }
    if p.failure.terms == FailureTerms::PerUnit {
        let w = &p.failure.weights;
        for (field, value) in [
            ("failure.weights.payload", w.payload),
            ("failure.weights.distance", w.distance),
            ("failure.weights.capacity", w.capacity),
            ("failure.weights.wind", w.wind),
        ] {
            out.push(r(
                field,
                value,
                0.0,
                100.0,
                "",
                "100 batteries per unit of the factor",
            ));
        }
    }
    out
}

/// Checks a profile's values; reports every violation at once (codes E2xxx, listed in README.md).
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
    if p.schema_version != super::SCHEMA_VERSION {
        out.push(Violation::new(
            "E2001",
            "schema_version",
            format!(
                "profile schema version {} but this build reads {}",
                p.schema_version,
                super::SCHEMA_VERSION
            ),
            format!(
                "set schema_version = {} and compare with instances/profiles/paper.toml",
                super::SCHEMA_VERSION
            ),
        ));
    }
    // Strictly positive quantities: zero or negative makes the models meaningless.
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
                format!("must be a finite number above 0, got {v}"),
                "set a positive value; see instances/profiles/paper.toml for its source",
            ));
        }
    }
    // Non-negative quantities.
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
                format!("must be a finite number at least 0, got {v}"),
                "set a value of 0 or more",
            ));
        }
    }
    let c_par = p.energy.parasitic_fraction;
    if !(c_par.is_finite() && (0.0..1.0).contains(&c_par)) {
        out.push(Violation::new(
            "E2004",
            "energy.parasitic_fraction",
            format!("must be in [0, 1), got {c_par}"),
            "set the share of cruise power spent against drag, e.g. 0.1",
        ));
    }
    let mf = p.formation.min_position_factor;
    if mf.is_finite() && mf > 1.0 {
        out.push(Violation::new(
            "E2005",
            "formation.min_position_factor",
            format!("must be at most 1, got {mf}"),
            "set a floor in (0, 1], e.g. 0.5",
        ));
    }
    let swarm_size = p.formation.select_swarm_size as usize;
    if !(1..=super::MAX_SWARM_DRONES).contains(&swarm_size) {
        out.push(Violation::new(
            "E2006",
            "formation.select_swarm_size",
            format!(
                "must be in 1..={}, got {swarm_size}",
                super::MAX_SWARM_DRONES
            ),
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
    if p.support.extra_batteries > 0 && p.support_payload_kg() > p.drone.max_payload_kg {
        out.push(Violation::new(
            "E2007",
            "support.extra_batteries",
            format!(
                "{} extra batteries weigh {:.3} kg, over drone.max_payload_kg = {} kg",
                p.support.extra_batteries,
                p.support_payload_kg(),
                p.drone.max_payload_kg
            ),
            "carry fewer extra batteries or raise the max payload",
        ));
    }
    if p.sharing.delta_mah.is_finite()
        && p.drone.battery_mah.is_finite()
        && p.sharing.delta_mah >= p.support_capacity_mah()
    {
        out.push(Violation::new(
            "E2008",
            "sharing.delta_mah",
            format!(
                "support reserve {} mAh is not below the support capacity {} mAh",
                p.sharing.delta_mah,
                p.support_capacity_mah()
            ),
            "lower the reserve or add extra batteries",
        ));
    }
    if p.sharing.gamma_mah.is_finite()
        && p.drone.battery_mah.is_finite()
        && p.sharing.gamma_mah >= p.drone.battery_mah
    {
        out.push(Violation::new(
            "E2009",
            "sharing.gamma_mah",
            format!(
                "request threshold {} mAh is not below the battery capacity {} mAh",
                p.sharing.gamma_mah, p.drone.battery_mah
            ),
            "set gamma below drone.battery_mah (the paper profile uses 20% of it)",
        ));
    }
    // Redundancy table.
    let rows = &p.redundancy.rows;
    if rows.is_empty() {
        out.push(Violation::new(
            "E2010",
            "redundancy.rows",
            "the redundancy table is empty",
            "list rows from from_pct = 0 upwards, as in instances/profiles/paper.toml",
        ));
    } else {
        if rows[0].from_pct != 0.0 {
            out.push(Violation::new(
                "E2011",
                "redundancy.rows[0].from_pct",
                format!("the first row must start at 0, got {}", rows[0].from_pct),
                "start the table at from_pct = 0",
            ));
        }
        for (i, r) in rows.iter().enumerate() {
            if let RedundancyLevel::NPlus(k) = r.level {
                if k as usize > super::MAX_SUPPORT_DRONES {
                    out.push(Violation::new(
                        "E2023",
                        format!("redundancy.rows[{i}].level"),
                        format!(
                            "n+{k} asks for more than {} support drones",
                            super::MAX_SUPPORT_DRONES
                        ),
                        "use a level of at most n+32, or 2n / 2(n+1)",
                    ));
                }
            }
            let ok_range = r.from_pct.is_finite() && (0.0..=100.0).contains(&r.from_pct);
            let ok_order = i == 0 || r.from_pct > rows[i - 1].from_pct;
            if !ok_range || !ok_order {
                out.push(Violation::new(
                    "E2012",
                    format!("redundancy.rows[{i}].from_pct"),
                    format!(
                        "must be in [0, 100] and above the previous row's, got {}",
                        r.from_pct
                    ),
                    "list rows in strictly increasing from_pct within 0..100",
                ));
            }
        }
    }
    // Failure weights.
    let w = &p.failure.weights;
    let weights = [
        ("failure.weights.payload", w.payload),
        ("failure.weights.distance", w.distance),
        ("failure.weights.capacity", w.capacity),
        ("failure.weights.wind", w.wind),
    ];
    for (field, v) in weights {
        match p.failure.terms {
            FailureTerms::Normalised if !(v.is_finite() && (0.0..=1.0).contains(&v)) => {
                out.push(Violation::new(
                    "E2020",
                    field,
                    format!("a weight of normalised terms must be in [0, 1], got {v}"),
                    "set the weight between 0 and 1, or set failure.terms = \"per-unit\"",
                ));
            }
            FailureTerms::PerUnit if !(v.is_finite() && v >= 0.0) => {
                out.push(Violation::new(
                    "E2022",
                    field,
                    format!("a per-unit weight must be a finite number at least 0, got {v}"),
                    "set the share of a battery the factor consumes per unit of it, e.g. \
                     distance = 0.03 (3% per minute of flight, the paper's example)",
                ));
            }
            _ => {}
        }
    }
    // One positive weight is needed; a negative one is reported above and does not cancel it.
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
    // Stated ranges (E2013): each quantity that passed the sign rules above must also lie in a
    // physically meaningful range, so that every number derived from it stays finite.
    // A field already reported as not finite or of the wrong sign is not reported twice.
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
        let (min, max) = (crate::error::show(r.min), crate::error::show(r.max));
        out.push(Violation::new(
            "E2013",
            r.field,
            format!(
                "{}{unit} is outside the stated range [{min}, {max}]{unit}",
                crate::error::show(v)
            ),
            format!(
                "set a value within [{min}, {max}]{unit} ({}); see \"Ranges\" in README.md",
                r.why
            ),
        ));
    }
    out
}
