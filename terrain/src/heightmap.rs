//! The `Heightmap` grid.

use glam::Vec2;
use rayon::prelude::*;

use crate::error::{TerrainError, check};

/// Largest level count: 2^14 + 1 = 16385 samples a side (1 GiB of `f32`).
pub const MAX_LEVELS: u32 = 14;

/// A square grid of (2^n + 1)^2 heights with a horizontal spacing, covering
/// `origin .. origin + (size - 1) * spacing` in x and z. Row-major: index `z * size + x`.
#[derive(Debug, Clone, PartialEq)]
pub struct Heightmap {
    size: usize,
    spacing: f32,
    origin: Vec2,
    heights: Vec<f32>,
}

/// Summary statistics of the heights.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeightStats {
    /// Lowest height.
    pub min: f32,
    /// Highest height.
    pub max: f32,
    /// Mean height.
    pub mean: f32,
}

/// Checks a side length and returns its level count n.
pub(crate) fn levels_of(size: usize) -> Result<u32, TerrainError> {
    let cells = size.wrapping_sub(1);
    if size < 3 || !cells.is_power_of_two() || cells.trailing_zeros() > MAX_LEVELS {
        return Err(TerrainError::BadSize(size));
    }
    Ok(cells.trailing_zeros())
}

impl Heightmap {
    /// A flat heightmap of height 0.
    ///
    /// ```
    /// let h = sylva_terrain::Heightmap::flat(5, 2.0).unwrap();
    /// assert_eq!(h.extent(), 8.0);
    /// assert!(sylva_terrain::Heightmap::flat(6, 1.0).is_err());
    /// ```
    pub fn flat(size: usize, spacing: f32) -> Result<Heightmap, TerrainError> {
        Self::from_heights(size, spacing, vec![0.0; checked_len(size)?])
    }

    /// Wraps existing heights (row-major, `size * size` of them, all finite).
    pub fn from_heights(
        size: usize,
        spacing: f32,
        heights: Vec<f32>,
    ) -> Result<Heightmap, TerrainError> {
        levels_of(size)?;
        check(
            "spacing",
            f64::from(spacing),
            spacing > 0.0,
            "a positive distance",
        )?;
        if heights.len() != size * size {
            return Err(TerrainError::HeightCount {
                heights: heights.len(),
                size,
            });
        }
        if let Some(index) = first_non_finite(&heights) {
            return Err(TerrainError::NonFiniteHeight { index, size });
        }
        Ok(Heightmap {
            size,
            spacing,
            origin: Vec2::ZERO,
            heights,
        })
    }

    /// Moves the map so that sample (0, 0) sits at `origin` (x, z).
    #[must_use]
    pub fn with_origin(mut self, origin: Vec2) -> Self {
        self.origin = origin;
        self
    }

    /// Samples per side.
    pub fn size(&self) -> usize {
        self.size
    }

    /// Distance between neighbouring samples.
    pub fn spacing(&self) -> f32 {
        self.spacing
    }

    /// World (x, z) of sample (0, 0).
    pub fn origin(&self) -> Vec2 {
        self.origin
    }

    /// Side length in world units: `(size - 1) * spacing`.
    pub fn extent(&self) -> f32 {
        (self.size - 1) as f32 * self.spacing
    }

    /// All heights, row-major.
    pub fn heights(&self) -> &[f32] {
        &self.heights
    }

    /// All heights, mutable. Callers must keep them finite.
    pub fn heights_mut(&mut self) -> &mut [f32] {
        &mut self.heights
    }

    /// Height of sample (x, z). Panics outside the grid, like slice indexing.
    pub fn get(&self, x: usize, z: usize) -> f32 {
        self.heights[z * self.size + x]
    }

    /// Sets sample (x, z).
    pub fn set(&mut self, x: usize, z: usize, h: f32) {
        self.heights[z * self.size + x] = h;
    }

    /// Minimum, maximum and mean height.
    pub fn stats(&self) -> HeightStats {
        let (mut min, mut max, mut sum) = (f32::INFINITY, f32::NEG_INFINITY, 0.0f64);
        for &h in &self.heights {
            min = min.min(h);
            max = max.max(h);
            sum += f64::from(h);
        }
        HeightStats {
            min,
            max,
            mean: (sum / self.heights.len() as f64) as f32,
        }
    }
}

/// Makes the last row and column of the `n`-wide heights `h` copies of the first: the
/// samples a periodic map repeats, one period on.
pub(crate) fn repeat_first_row_and_column(h: &mut [f32], n: usize) {
    let period = n - 1;
    for z in 0..n {
        h[z * n + period] = h[(z % period) * n];
    }
    let (first, rest) = h.split_at_mut(n);
    rest[(period - 1) * n..].copy_from_slice(first);
}

pub(crate) fn checked_len(size: usize) -> Result<usize, TerrainError> {
    levels_of(size)?;
    Ok(size * size)
}

/// The index of the first height that is not finite, if any. Blocks are checked on every
/// core without stopping early, so the check vectorises (a search that stops at the first
/// found did not, and took 15% of diamond-square at 4097²); only a failing block is
/// searched.
fn first_non_finite(heights: &[f32]) -> Option<usize> {
    const BLOCK: usize = 1 << 14;
    let finite = |block: &[f32]| block.iter().fold(true, |all, h| all & h.is_finite());
    let bad = heights
        .par_chunks(BLOCK)
        .position_first(|block| !finite(block))?;
    let block = &heights[bad * BLOCK..];
    block
        .iter()
        .position(|h| !h.is_finite())
        .map(|i| bad * BLOCK + i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The blockwise check finds the first height that is not finite, as a search does,
        /// across block boundaries and with several bad heights.
        #[test]
        fn the_first_non_finite_height_is_found(
            len in 0usize..70_000,
            bad in prop::collection::vec((any::<prop::sample::Index>(), 0u8..3), 0..4),
        ) {
            let mut heights = vec![1.5f32; len];
            if len > 0 {
                for (at, kind) in bad {
                    heights[at.index(len)] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY][kind as usize];
                }
            }
            prop_assert_eq!(
                first_non_finite(&heights),
                heights.iter().position(|h| !h.is_finite())
            );
        }
    }
}
