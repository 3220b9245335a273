//! Position-keyed random numbers: each sample's randomness depends only on the seed and its
//! global grid coordinates, so tiles generated apart agree where they meet.

/// SplitMix64 finaliser.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A value in [-1, 1) with a triangular distribution (the sum of two uniform halves), keyed
/// by seed and global sample coordinates.
#[inline]
pub(crate) fn signed_noise(seed: u64, x: i64, z: i64) -> f32 {
    let h = mix(seed
        ^ mix((x as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
            ^ (z as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)));
    let a = (h >> 40) as f32 * (1.0 / (1u64 << 24) as f32);
    let b = ((h >> 16) & 0xff_ffff) as f32 * (1.0 / (1u64 << 24) as f32);
    a + b - 1.0
}

/// A value in [0, 1) keyed by seed and a counter.
#[inline]
pub(crate) fn unit(seed: u64, n: u64) -> f32 {
    (mix(seed ^ mix(n.wrapping_add(0x632b_e59b_d9b4_e019))) >> 40) as f32
        * (1.0 / (1u64 << 24) as f32)
}
