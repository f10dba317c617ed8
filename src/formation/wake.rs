//! Wake/shielding model: the position factor of every slot of a formation, from the slot geometry in
//! the frame of the air-relative flow. See models/formation.md for the derivation and sources.
//!
//! For slots `i != j`, with `d = p_j - p_i` (body frame, m) and `u` the unit vector along which the
//! air moves past the swarm, the downstream distance of `j` behind `i` is `s = d . u` and its lateral
//! offset `t = d . u_perp` (`u_perp` is `u` turned 90 degrees). Drone `j` gains
//!
//! ```text
//! g(s, t) = [s > 0] * s / (s + s0) * ( a_sh * G(t; sigma_sh) * exp(-s / L_sh)        drag shielding
//!                                    - a_dw * G(t; sigma_dw) * exp(-s / L)           downwash
//!                                    + a_up * G(|t| - b_up; sigma_up) * exp(-s / L) ) upwash
//!         + a_ab * G(s; sigma_as) * G(|t| - b_ab; sigma_ab)                          abreast
//! ```
//!
//! with `G(x; sigma) = exp(-x^2 / (2 sigma^2))`, and its position factor is
//! `f_j = max(f_min, 1 - sum_{i != j} g(s_ij, t_ij))`. A drone with no drone upstream pays the full
//! still-formation rate (`f = 1`), which is why a leader in a head wind pays most.

use crate::problem::FormationParams;
use nalgebra::Vector2;

fn gauss(x: f64, sigma: f64) -> f64 {
    (-x * x / (2.0 * sigma * sigma)).exp()
}

/// Gain `g(s, t)` of a drone at downstream distance `s_m` and lateral offset `t_m` from another
/// drone (see the module documentation).
pub fn pair_gain(s_m: f64, t_m: f64, p: &FormationParams) -> f64 {
    let mut g = 0.0;
    if s_m > 0.0 {
        let onset = s_m / (s_m + p.wake_onset_m);
        let shield = p.shield_gain * gauss(t_m, p.shield_width_m) * (-s_m / p.shield_decay_m).exp();
        let decay = (-s_m / p.wake_decay_m).exp();
        let downwash = p.downwash_gain * gauss(t_m, p.downwash_width_m);
        let upwash = p.upwash_gain * gauss(t_m.abs() - p.upwash_offset_m, p.upwash_width_m);
        g += onset * (shield + decay * (upwash - downwash));
    }
    g += p.abreast_gain
        * gauss(s_m, p.abreast_band_m)
        * gauss(t_m.abs() - p.abreast_offset_m, p.abreast_width_m);
    g
}

/// Position factor of every slot for air moving past the swarm along `flow_body`.
///
/// # Arguments
/// * `slots_m` - slot positions, body frame, m.
/// * `flow_body` - the air's velocity relative to the swarm in the body frame (m/s; only its
///   direction is used). A zero vector (the air moves with the swarm) means no wake is convected
///   between drones: every factor is 1.
/// * `p` - the wake parameters.
///
/// # Returns
/// One factor per slot, in `[f_min, 1 + sum of penalties]`.
///
/// # Complexity
/// O(n^2) for n slots.
pub fn position_factors(
    slots_m: &[Vector2<f64>],
    flow_body: Vector2<f64>,
    p: &FormationParams,
) -> Vec<f64> {
    let norm = flow_body.norm();
    if norm.is_nan() || norm <= 1e-9 {
        return vec![1.0; slots_m.len()];
    }
    let u = flow_body / norm;
    let u_perp = Vector2::new(-u.y, u.x);
    slots_m
        .iter()
        .enumerate()
        .map(|(j, pj)| {
            let gain: f64 = slots_m
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != j)
                .map(|(_, pi)| {
                    let d = pj - pi;
                    pair_gain(d.dot(&u), d.dot(&u_perp), p)
                })
                .sum();
            (1.0 - gain).max(p.min_position_factor)
        })
        .collect()
}
