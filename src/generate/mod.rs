//! Seeded synthetic instances: rooftop networks ([`generate_network`]), request sets ([`generate_requests`]) and
//! the classical P||Cmax benchmark classes as node-time instances ([`pcmax`]).
//! User guide: the command `generate` (`docs/src/commands/generate.md`) and "The instance
//! generator" (`docs/src/models/generate.md`).
//!
//! Every random choice comes from one `ChaCha8Rng` seeded with the user's seed. Only the generator's
//! raw 64-bit output is used (`next_u64`); uniform reals, bounded integers, normal deviates and
//! shuffles are derived here, so a file depends only on the seed, the parameters and this code, not
//! on how a `rand` release maps bits to distributions. Same seed and parameters: byte-identical file.
//!
//! The distributions are documented on [`network::generate_network`] and
//! [`requests::generate_requests`], and in `instances/paper-195/README.md`.

pub mod import;
mod network;
pub mod pcmax;
mod requests;

pub use network::{
    check_network_params, generate_network, NetworkParams, DEFAULT_NODES, DEFAULT_SPACING_M,
    DIAGONAL_PROBABILITY, JITTER_SHARE, MAX_NODES, MEAN_WIND_RANGE_MPS, MIN_NODES,
    PAD_PROBABILITIES, REMOVE_PROBABILITY, WIND_DIRECTION_SD_DEG, WIND_SPEED_CAP_MPS,
    WIND_SPEED_LOG_SD,
};
pub use requests::{
    check_request_params, generate_requests, RequestParams, DEFAULT_MAX_PACKAGE_KG,
    DEFAULT_REQUESTS, MAX_PACKAGES, MAX_REQUESTS, MIN_PACKAGES,
};

use rand::RngCore;
use rand_chacha::ChaCha8Rng;

/// Uniform real in `[0, 1)` with 53 random bits.
pub(crate) fn unit(rng: &mut ChaCha8Rng) -> f64 {
    (rng.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Uniform integer in `0..n` (`n > 0`), unbiased by rejection.
pub(crate) fn below(rng: &mut ChaCha8Rng, n: usize) -> usize {
    let n = n as u64;
    let zone = u64::MAX - (u64::MAX % n + 1) % n;
    loop {
        let x = rng.next_u64();
        if x <= zone {
            return (x % n) as usize;
        }
    }
}

/// Standard normal deviate (Box–Muller, cosine branch).
pub(crate) fn normal(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - unit(rng); // (0, 1]
    let u2 = unit(rng);
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// Fisher–Yates shuffle driven by [`below`].
pub(crate) fn shuffle<T>(rng: &mut ChaCha8Rng, items: &mut [T]) {
    for i in (1..items.len()).rev() {
        let j = below(rng, i + 1);
        items.swap(i, j);
    }
}

/// Rounds to `decimals` decimal places (keeps the JSON files short and readable).
pub(crate) fn round_to(x: f64, decimals: i32) -> f64 {
    let f = 10f64.powi(decimals);
    (x * f).round() / f
}
