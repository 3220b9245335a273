//! Position-keyed random numbers: each sample's randomness depends only on the seed and its
//! global grid coordinates, so tiles generated apart agree where they meet.

use sylva_base::hash::{cell_row_key, hash_cell_in_row, mix, unit_f32};

/// Position-keyed noise along one row of samples: the row's share of the key is worked out
/// once, so each sample costs only its own.
#[derive(Debug, Clone, Copy)]
pub(crate) struct NoiseRow {
    seed: u64,
    row: u64,
}

impl NoiseRow {
    /// The row at global coordinate `z`.
    #[inline]
    pub(crate) fn new(seed: u64, z: i64) -> NoiseRow {
        NoiseRow {
            seed,
            row: cell_row_key(z, 0),
        }
    }

    /// The noise at global coordinate `x` of the row: `hash_cell(seed, x, z, 0)` as a value in [-1, 1) with a triangular distribution (the sum
    /// of two uniform halves).
    #[inline]
    pub(crate) fn at(&self, x: i64) -> f32 {
        let h = hash_cell_in_row(self.seed, x, self.row);
        let a = unit_f32(h);
        let b = ((h >> 16) & 0xff_ffff) as f32 * (1.0 / (1u64 << 24) as f32);
        a + b - 1.0
    }
}

/// A value in [0, 1) keyed by seed and a counter.
#[inline]
pub(crate) fn unit(seed: u64, n: u64) -> f32 {
    unit_f32(mix(seed ^ mix(n.wrapping_add(0x632b_e59b_d9b4_e019))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva_base::hash::hash_cell;

    /// The noise is keyed by `hash_cell` with salt 0, as the terrains pinned by the known
    /// answers were made.
    #[test]
    fn a_row_of_noise_is_keyed_by_the_cell_hash() {
        for (seed, z) in [(0u64, 0i64), (7, -3), (u64::MAX, 1 << 40)] {
            let row = NoiseRow::new(seed, z);
            for x in [-5i64, 0, 1, 4096, i64::MAX] {
                let h = hash_cell(seed, x, z, 0);
                let b = ((h >> 16) & 0xff_ffff) as f32 * (1.0 / (1u64 << 24) as f32);
                assert_eq!(row.at(x).to_bits(), (unit_f32(h) + b - 1.0).to_bits());
            }
        }
    }
}
