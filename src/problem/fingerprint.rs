//! Fingerprints of the inputs a result was made on: the SHA-256 of their JSON as read, so that a
//! plan, a hop file or a bench run records which network and profile it belongs to, and `check`
//! can tell a plan made on another instance from a plan that breaks the model.

use super::{Network, Profile};
use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};

/// SHA-256, in lowercase hex, of the JSON serialisation of `value`.
pub fn sha256_json<T: Serialize + ?Sized>(value: &T) -> String {
    let json = serde_json::to_vec(value).expect("input types serialise to JSON");
    Sha256::digest(&json)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// The network and the profile a result was made on.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Fingerprint {
    /// SHA-256 of the network's JSON (its serialisation as read).
    pub network_sha256: String,
    /// SHA-256 of the profile's JSON (with `--literal` applied).
    pub profile_sha256: String,
}

impl Fingerprint {
    /// The fingerprint of a network and a profile.
    pub fn of(network: &Network, profile: &Profile) -> Fingerprint {
        Fingerprint {
            network_sha256: sha256_json(network),
            profile_sha256: sha256_json(profile),
        }
    }
}
