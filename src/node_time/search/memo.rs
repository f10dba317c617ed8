//! Memo of failed states of the bin-completion search, keyed by exact bitsets.

use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};

/// Largest number of failed states remembered by one decision search.
pub(crate) const MEMO_MAX_STATES: usize = 1 << 21;

/// Multiply-rotate hash of the memo keys (bitsets of placed drones): the keys are exact, the hash
/// only spreads them, so a cheap one serves better than the default keyed hash.
#[derive(Default)]
pub(crate) struct WordHasher(u64);

impl Hasher for WordHasher {
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut word = [0u8; 8];
            word[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(word));
        }
    }

    fn write_u64(&mut self, x: u64) {
        self.0 = (self.0.rotate_left(5) ^ x).wrapping_mul(0x517c_c1b7_2722_0a95);
    }

    fn finish(&self) -> u64 {
        self.0
    }
}

/// Failed states of the bin-completion search: the bitset of placed drones, then the number of
/// full pads.
pub(crate) type Memo = HashSet<Box<[u64]>, BuildHasherDefault<WordHasher>>;
