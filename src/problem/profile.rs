//! Parameter profile (TOML): every constant of the models, each documented with its source in the
//! shipped profile files under `instances/profiles/`. Its rules (E2xxx) and the stated range of
//! every quantity are in [`super::validate`].

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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
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
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
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
