//! Position-keyed random numbers: each sample's randomness depends only on the seed and its
//! global grid coordinates, so tiles generated apart agree where they meet.

use sylva_base::hash::{hash_cell, mix, unit_f32};

/// A value in [-1, 1) with a triangular distribution (the sum of two uniform halves), keyed
/// by seed and global sample coordinates.
#[inline]
pub(crate) fn signed_noise(seed: u64, x: i64, z: i64) -> f32 {
    let h = hash_cell(seed, x, z, 0);
    let a = unit_f32(h);
    let b = ((h >> 16) & 0xff_ffff) as f32 * (1.0 / (1u64 << 24) as f32);
    a + b - 1.0
}

/// A value in [0, 1) keyed by seed and a counter.
#[inline]
pub(crate) fn unit(seed: u64, n: u64) -> f32 {
    unit_f32(mix(seed ^ mix(n.wrapping_add(0x632b_e59b_d9b4_e019))))
}
