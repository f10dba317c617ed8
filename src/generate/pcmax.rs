//! Seeded instances of the classical P||Cmax benchmark classes, as node-time instances (jobs =
//! drone charge times in whole minutes, machines = pads). See `models/generate.md`, "Node-time
//! benchmark classes".
//!
//! Every class draws `n` integer processing times `p_1..p_n` independently (apart from `nu*`, which
//! fixes how many jobs are short) from one distribution:
//!
//! | class | `p_j` | source |
//! |---|---|---|
//! | `u1`, `u2`, `u3` | `U{1..b}`, `b` = 100, 1000, 10000 | França, Gendreau, Laporte & Müller 1994 |
//! | `nu1`, `nu2`, `nu3` | 98% `U{ceil(0.9(b-a))..b}`, 2% `U{a..max(a, floor(0.02(b-a)))}`, `a = 1` | Frangioni, Necciari & Scutellà 2004 |
//! | `l1`, `l2`, `l3` | `U{1..100}`, `U{20..100}`, `U{50..100}` | Lawrinenko 2017 (ranges of Dell'Amico & Martello 1995) |
//! | `l4`, `l5` | `trunc(N(100, 20^2))`, `trunc(N(100, 50^2))`, redrawn while `< 1` | Lawrinenko 2017 |
//! | `l6`, `l7` | `U{n..4n}`, `trunc(N(4n, n^2))`, redrawn while `< 1` | Lawrinenko 2017 |
//! | `e1-*` .. `e4-*` | `U{a..b}`, the range in the name | Berndt, Deppert, Jansen & Rohwedder 2022 |
//!
//! What is uncertain in these definitions (we could read none of the original papers, only how later
//! papers and the benchmark repositories describe them) is stated on each class, on
//! [`PcmaxClass::note`] and in `models/generate.md`; the published files themselves, when at hand,
//! are read as published by [`crate::problem::pcmax_file`] (`node-time --instance FILE`). The
//! published `(n, m)` grid of each class is
//! [`PcmaxClass::published_grid`]; the generator accepts any `n >= 1`, `m >= 1`.
//!
//! Random numbers: one `ChaCha8Rng::seed_from_u64(seed)`, raw `next_u64` only (see
//! [`crate::generate`]): `U{a..b}` is `a + below(b - a + 1)`, `N(0, 1)` is Box–Muller.

use super::{below, normal, shuffle};
use crate::error::{Error, Result, Violation};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

/// Most jobs of a generated instance.
pub const MAX_JOBS: usize = 100_000;
/// Most pads of a generated instance.
pub const MAX_PADS: usize = 10_000;

/// A classical P||Cmax benchmark class. Sources and uncertain points on each variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PcmaxClass {
    /// França, Gendreau, Laporte & Müller, "A composite heuristic for the identical parallel
    /// machine scheduling problem with minimum makespan objective", Computers & Operations
    /// Research 21(2):205–210, 1994: `p_j ~ U{1..100}`.
    U1,
    /// França et al. 1994: `p_j ~ U{1..1000}`.
    U2,
    /// França et al. 1994: `p_j ~ U{1..10000}`.
    U3,
    /// Frangioni, Necciari & Scutellà, "A multi-exchange neighborhood for minimum makespan
    /// parallel machine scheduling problems", J. Combinatorial Optimization 8:195–220, 2004,
    /// non-uniform with `[a, b] = [1, 100]`: `round(0.02 n)` jobs `~ U{a..max(a, floor(0.02(b-a)))}`,
    /// the others `~ U{ceil(0.9(b-a))..b}`. Uncertain: see [`PcmaxClass::note`].
    Nu1,
    /// Frangioni et al. 2004, non-uniform with `[a, b] = [1, 1000]`.
    Nu2,
    /// Frangioni et al. 2004, non-uniform with `[a, b] = [1, 10000]`.
    Nu3,
    /// Lawrinenko, "Identical parallel machine scheduling problems: structural patterns, bounding
    /// techniques and solution procedures", PhD thesis, Friedrich-Schiller-Universität Jena, 2017,
    /// as used by Mrad & Souayah, "An arc-flow model for the makespan minimization problem on
    /// identical parallel machines", IEEE Access 6:5300–5307, 2018 (class C1): `U{1..100}`, the
    /// first range of Dell'Amico & Martello, "Optimal scheduling of tasks on identical parallel
    /// processors", ORSA J. Computing 7(2):191–200, 1995.
    L1,
    /// Lawrinenko 2017, class C2: `U{20..100}` (a Dell'Amico & Martello 1995 range).
    L2,
    /// Lawrinenko 2017, class C3: `U{50..100}` (a Dell'Amico & Martello 1995 range).
    L3,
    /// Lawrinenko 2017, class C4: normal, mean 100, standard deviation 20, integer.
    L4,
    /// Lawrinenko 2017, class C5: normal, mean 100, standard deviation 50, integer.
    L5,
    /// Lawrinenko 2017, class C6: `U{n..4n}`.
    L6,
    /// Lawrinenko 2017, class C7: normal, mean `4n`, standard deviation `n`, integer.
    L7,
    /// Berndt, Deppert, Jansen & Rohwedder, "Load balancing: the long road from theory to
    /// practice", ALENEX 2022, class E1: `n = k m`, `k` in {2, 3, 5}, `m` in {3, 4, 5}, `U{1..20}`.
    E1R1To20,
    /// Berndt et al. 2022, E1 with `U{20..50}`.
    E1R20To50,
    /// Berndt et al. 2022, E2: `m` in {2, 3} with `n` in {10, 30, 50, 100}, `m` in {4, 6, 8, 10}
    /// with `n` in {30, 50, 100}; `U{100..800}`.
    E2R100To800,
    /// Berndt et al. 2022, E3: `n = k m + 1` or `k m + 2`, `k` in {3, 4, 5}, `m` in {3, 5, 8, 10};
    /// `U{1..100}`.
    E3R1To100,
    /// Berndt et al. 2022, E3 with `U{100..200}`.
    E3R100To200,
    /// Berndt et al. 2022, E4: `(n, m)` = (10, 2) or (9, 3); `U{1..20}`.
    E4R1To20,
    /// Berndt et al. 2022, E4 with `U{20..50}`.
    E4R20To50,
    /// Berndt et al. 2022, E4 with `U{1..100}`.
    E4R1To100,
    /// Berndt et al. 2022, E4 with `U{50..100}`.
    E4R50To100,
    /// Berndt et al. 2022, E4 with `U{100..200}`.
    E4R100To200,
    /// Berndt et al. 2022, E4 with `U{100..800}`.
    E4R100To800,
}

/// Distribution of one processing time, for a given `n`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PcmaxDist {
    /// Integers uniform in `a..=b`.
    Uniform {
        /// Smallest value.
        a: u64,
        /// Largest value.
        b: u64,
    },
    /// Frangioni et al.'s non-uniform distribution over `[a, b]` (see [`PcmaxClass::Nu1`]).
    NonUniform {
        /// Bottom of the range.
        a: u64,
        /// Top of the range.
        b: u64,
    },
    /// `trunc(N(mu, sigma^2))`, redrawn while below 1.
    Normal {
        /// Mean.
        mu: f64,
        /// Standard deviation.
        sigma: f64,
    },
}

impl PcmaxDist {
    /// The two ranges of [`PcmaxDist::NonUniform`]: `(short, long)`, each `(lo, hi)` inclusive:
    /// short `[a, max(a, floor(0.02 (b - a)))]`, long `[ceil(0.9 (b - a)), b]`.
    pub fn non_uniform_ranges(a: u64, b: u64) -> ((u64, u64), (u64, u64)) {
        let w = b - a;
        (
            (a, a.max(w / 50)),
            (w.saturating_mul(9).div_ceil(10).max(a), b),
        )
    }
}

/// Number of short jobs of a `nu*` instance with `n` jobs: `round(0.02 n)`, halves up.
pub fn non_uniform_short_jobs(n: usize) -> usize {
    (n + 25) / 50
}

impl PcmaxClass {
    /// Every class, in the order of the table in the module doc.
    pub const ALL: [PcmaxClass; 24] = [
        Self::U1,
        Self::U2,
        Self::U3,
        Self::Nu1,
        Self::Nu2,
        Self::Nu3,
        Self::L1,
        Self::L2,
        Self::L3,
        Self::L4,
        Self::L5,
        Self::L6,
        Self::L7,
        Self::E1R1To20,
        Self::E1R20To50,
        Self::E2R100To800,
        Self::E3R1To100,
        Self::E3R100To200,
        Self::E4R1To20,
        Self::E4R20To50,
        Self::E4R1To100,
        Self::E4R50To100,
        Self::E4R100To200,
        Self::E4R100To800,
    ];

    /// The name on the command line, e.g. `u1`, `nu2`, `l7`, `e3-100-200`.
    pub fn name(self) -> &'static str {
        match self {
            Self::U1 => "u1",
            Self::U2 => "u2",
            Self::U3 => "u3",
            Self::Nu1 => "nu1",
            Self::Nu2 => "nu2",
            Self::Nu3 => "nu3",
            Self::L1 => "l1",
            Self::L2 => "l2",
            Self::L3 => "l3",
            Self::L4 => "l4",
            Self::L5 => "l5",
            Self::L6 => "l6",
            Self::L7 => "l7",
            Self::E1R1To20 => "e1-1-20",
            Self::E1R20To50 => "e1-20-50",
            Self::E2R100To800 => "e2-100-800",
            Self::E3R1To100 => "e3-1-100",
            Self::E3R100To200 => "e3-100-200",
            Self::E4R1To20 => "e4-1-20",
            Self::E4R20To50 => "e4-20-50",
            Self::E4R1To100 => "e4-1-100",
            Self::E4R50To100 => "e4-50-100",
            Self::E4R100To200 => "e4-100-200",
            Self::E4R100To800 => "e4-100-800",
        }
    }

    /// The class called `name` (as [`PcmaxClass::name`], case-insensitive), if any.
    pub fn from_name(name: &str) -> Option<Self> {
        let name = name.trim().to_ascii_lowercase();
        Self::ALL.into_iter().find(|c| c.name() == name)
    }

    /// The distribution of each processing time for `n` jobs.
    pub fn dist(self, n: usize) -> PcmaxDist {
        use PcmaxDist::{NonUniform, Normal, Uniform};
        let n64 = n as u64;
        match self {
            Self::U1 => Uniform { a: 1, b: 100 },
            Self::U2 => Uniform { a: 1, b: 1000 },
            Self::U3 => Uniform { a: 1, b: 10_000 },
            Self::Nu1 => NonUniform { a: 1, b: 100 },
            Self::Nu2 => NonUniform { a: 1, b: 1000 },
            Self::Nu3 => NonUniform { a: 1, b: 10_000 },
            Self::L1 => Uniform { a: 1, b: 100 },
            Self::L2 => Uniform { a: 20, b: 100 },
            Self::L3 => Uniform { a: 50, b: 100 },
            Self::L4 => Normal {
                mu: 100.0,
                sigma: 20.0,
            },
            Self::L5 => Normal {
                mu: 100.0,
                sigma: 50.0,
            },
            Self::L6 => Uniform { a: n64, b: 4 * n64 },
            Self::L7 => Normal {
                mu: 4.0 * n as f64,
                sigma: n as f64,
            },
            Self::E1R1To20 | Self::E4R1To20 => Uniform { a: 1, b: 20 },
            Self::E1R20To50 | Self::E4R20To50 => Uniform { a: 20, b: 50 },
            Self::E2R100To800 | Self::E4R100To800 => Uniform { a: 100, b: 800 },
            Self::E3R1To100 | Self::E4R1To100 => Uniform { a: 1, b: 100 },
            Self::E3R100To200 | Self::E4R100To200 => Uniform { a: 100, b: 200 },
            Self::E4R50To100 => Uniform { a: 50, b: 100 },
        }
    }

    /// Short source of the class, as cited in `models/generate.md`.
    pub fn source(self) -> &'static str {
        match self {
            Self::U1 | Self::U2 | Self::U3 => "França, Gendreau, Laporte & Müller 1994",
            Self::Nu1 | Self::Nu2 | Self::Nu3 => "Frangioni, Necciari & Scutellà 2004",
            Self::L1 | Self::L2 | Self::L3 => {
                "Lawrinenko 2017 / Mrad & Souayah 2018 (ranges of Dell'Amico & Martello 1995)"
            }
            Self::L4 | Self::L5 | Self::L6 | Self::L7 => "Lawrinenko 2017 / Mrad & Souayah 2018",
            _ => "Berndt, Deppert, Jansen & Rohwedder 2022",
        }
    }

    /// What is uncertain in this class's definition (empty when nothing is known to be).
    pub fn note(self) -> &'static str {
        match self {
            Self::U1 | Self::U2 | Self::U3 => "",
            Self::Nu1 | Self::Nu2 | Self::Nu3 => {
                "uncertain: the short range is read as [a, 0.02(b-a)] (one other reading: \
                 0.2(b-a)); 98%/2% is read as exactly round(0.02 n) short jobs; interval ends \
                 rounded inwards; the distributed files may be bimodal instead"
            }
            Self::L1 | Self::L2 | Self::L3 => {
                "uncertain: Dell'Amico & Martello 1995's own n, m grid is not reproduced"
            }
            Self::L4 | Self::L5 | Self::L7 => {
                "uncertain: rounding of the normal deviate (truncated here, values < 1 redrawn)"
            }
            Self::L6 => "",
            _ => "uncertain: taken from the authors' generator script as redistributed, not the paper",
        }
    }

    /// Whether `(n, m)` belongs to the class's published grid (the instances the papers list).
    pub fn published_grid(self, n: usize, m: usize) -> bool {
        match self {
            Self::U1 | Self::U2 | Self::U3 | Self::Nu1 | Self::Nu2 | Self::Nu3 => {
                [10, 50, 100, 500, 1000].contains(&n) && [5, 10, 25].contains(&m) && n > m
            }
            Self::L1 | Self::L2 | Self::L3 | Self::L4 | Self::L5 | Self::L6 | Self::L7 => {
                // n/m in {2, 2.25, 2.5, 2.75, 3}, each ratio with its ten n.
                let ratio = |num: usize, den: usize| n * den == m * num;
                // n in {s k : k in ks}: 20..=200 step 20, 36..=198 step 18, 22..=220 step 22.
                let step = |s: usize, ks: std::ops::RangeInclusive<usize>| {
                    n.is_multiple_of(s) && ks.contains(&(n / s))
                };
                (step(20, 1..=10) && (ratio(2, 1) || ratio(5, 2)))
                    || (step(18, 2..=11) && (ratio(9, 4) || ratio(3, 1)))
                    || (step(22, 1..=10) && ratio(11, 4))
            }
            Self::E1R1To20 | Self::E1R20To50 => {
                [3, 4, 5].contains(&m) && n.is_multiple_of(m) && [2, 3, 5].contains(&(n / m))
            }
            Self::E2R100To800 => {
                ([2, 3].contains(&m) && [10, 30, 50, 100].contains(&n))
                    || ([4, 6, 8, 10].contains(&m) && [30, 50, 100].contains(&n))
            }
            Self::E3R1To100 | Self::E3R100To200 => {
                [3, 5, 8, 10].contains(&m)
                    && n > m
                    && [1, 2].contains(&(n % m))
                    && [3, 4, 5].contains(&(n / m))
            }
            _ => (n, m) == (10, 2) || (n, m) == (9, 3),
        }
    }
}

impl std::fmt::Display for PcmaxClass {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Parameters of [`generate_pcmax`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PcmaxParams {
    /// Benchmark class.
    pub class: PcmaxClass,
    /// Number of jobs (drones) `n`, 1..=[`MAX_JOBS`].
    pub jobs: usize,
    /// Number of machines (pads) `m`, 1..=[`MAX_PADS`].
    pub pads: usize,
    /// Seed of the random generator.
    pub seed: u64,
}

/// A generated instance, in the file format `swarmplan node-time --file` reads.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct PcmaxFile {
    /// Always 1.
    pub schema_version: u32,
    /// Number of pads `m`.
    pub pads: usize,
    /// Processing (charge) time of each job, whole minutes.
    pub charge_times_min: Vec<u64>,
}

/// Checks the parameters and reports every violation at once.
///
/// # Errors
/// [`Error::Invalid`] with `E3906` (jobs out of 1..=[`MAX_JOBS`]) and `E3907` (pads out of
/// 1..=[`MAX_PADS`]).
pub fn validate_pcmax(p: &PcmaxParams) -> Result<()> {
    let mut v = Vec::new();
    if !(1..=MAX_JOBS).contains(&p.jobs) {
        v.push(Violation::new(
            "E3906",
            "jobs",
            format!("{} jobs is not from 1 to {MAX_JOBS}", p.jobs),
            "give the number of jobs (drones) of the instance",
        ));
    }
    if !(1..=MAX_PADS).contains(&p.pads) {
        v.push(Violation::new(
            "E3907",
            "pads",
            format!("{} pads is not from 1 to {MAX_PADS}", p.pads),
            "give the number of machines (pads) of the instance",
        ));
    }
    if v.is_empty() {
        Ok(())
    } else {
        Err(Error::Invalid(v))
    }
}

/// Draws the processing times of one instance of `p.class`.
///
/// # Arguments
/// * `p` - class, `n` jobs, `m` pads (only written to the file) and seed.
///
/// # Returns
/// The node-time file: `m` pads and `n` whole-minute times. Same parameters, same file.
///
/// # Errors
/// Those of [`validate_pcmax`].
///
/// # Complexity
/// `O(n)` expected (normal classes redraw values below 1, rare for every class here).
///
/// # Example
/// ```
/// use swarmplan::generate::pcmax::{generate_pcmax, PcmaxClass, PcmaxParams};
/// let p = PcmaxParams { class: PcmaxClass::U1, jobs: 50, pads: 5, seed: 7 };
/// let f = generate_pcmax(&p).unwrap();
/// assert_eq!(f.charge_times_min.len(), 50);
/// assert!(f.charge_times_min.iter().all(|&t| (1..=100).contains(&t)));
/// assert_eq!(f, generate_pcmax(&p).unwrap());
/// ```
pub fn generate_pcmax(p: &PcmaxParams) -> Result<PcmaxFile> {
    validate_pcmax(p)?;
    let mut rng = ChaCha8Rng::seed_from_u64(p.seed);
    let n = p.jobs;
    let uniform =
        |rng: &mut ChaCha8Rng, lo: u64, hi: u64| lo + below(rng, (hi - lo + 1) as usize) as u64;
    let times = match p.class.dist(n) {
        PcmaxDist::Uniform { a, b } => (0..n).map(|_| uniform(&mut rng, a, b)).collect(),
        PcmaxDist::NonUniform { a, b } => {
            let ((s_lo, s_hi), (l_lo, l_hi)) = PcmaxDist::non_uniform_ranges(a, b);
            let short = non_uniform_short_jobs(n);
            let mut t: Vec<u64> = (0..n)
                .map(|j| {
                    if j < short {
                        uniform(&mut rng, s_lo, s_hi)
                    } else {
                        uniform(&mut rng, l_lo, l_hi)
                    }
                })
                .collect();
            shuffle(&mut rng, &mut t);
            t
        }
        PcmaxDist::Normal { mu, sigma } => (0..n)
            .map(|_| loop {
                let x = (mu + sigma * normal(&mut rng)).trunc();
                if x >= 1.0 {
                    break x as u64;
                }
            })
            .collect(),
    };
    Ok(PcmaxFile {
        schema_version: 1,
        pads: p.pads,
        charge_times_min: times,
    })
}
