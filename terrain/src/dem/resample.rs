//! An elevation model onto the square (2^n + 1) grid that generation, erosion, meshes and
//! forests take: the smallest such grid at least as fine as the model, covering its longer
//! side; the shorter side is continued by its edge heights (the model's own extent is
//! returned, so forests can be kept inside it).

use super::ElevationModel;
use crate::error::TerrainError;
use crate::heightmap::Heightmap;

/// Most levels of a resampled model: 2^13 + 1 = 8193 samples a side.
const MAX_RESAMPLED_LEVELS: u32 = 13;

impl ElevationModel {
    /// Bilinear height at (x, z) metres from the north-west sample, clamped to the model.
    pub fn height_at(&self, x: f32, z: f32) -> f32 {
        let fx = (x / self.spacing[0]).clamp(0.0, (self.width - 1) as f32);
        let fz = (z / self.spacing[1]).clamp(0.0, (self.height - 1) as f32);
        let (x0, z0) = (fx.floor() as usize, fz.floor() as usize);
        let (x1, z1) = ((x0 + 1).min(self.width - 1), (z0 + 1).min(self.height - 1));
        let (tx, tz) = (fx - x0 as f32, fz - z0 as f32);
        let at = |x: usize, z: usize| self.heights[z * self.width + x];
        let top = at(x0, z0) + (at(x1, z0) - at(x0, z0)) * tx;
        let bottom = at(x0, z1) + (at(x1, z1) - at(x0, z1)) * tx;
        top + (bottom - top) * tz
    }

    /// The largest square of the model's own land, about its middle, on a (2^n + 1) grid no
    /// coarser than the model: nothing padded, for comparing statistics and pictures.
    pub fn square_heightmap(&self) -> Result<Heightmap, TerrainError> {
        let [ex, ez] = self.extent();
        let side = ex.min(ez);
        let finest = self.spacing[0].min(self.spacing[1]);
        let cells =
            ((side / finest).ceil() as u64).clamp(2, 2 * self.width.min(self.height) as u64);
        let size =
            (1usize << (64 - (cells - 1).leading_zeros()).clamp(1, MAX_RESAMPLED_LEVELS)) + 1;
        let step = side / (size - 1) as f32;
        let (x0, z0) = ((ex - side) / 2.0, (ez - side) / 2.0);
        let mut heights = Vec::with_capacity(size * size);
        for z in 0..size {
            for x in 0..size {
                heights.push(self.height_at(x0 + x as f32 * step, z0 + z as f32 * step));
            }
        }
        Heightmap::from_heights(size, step, heights)
    }

    /// The model on a square (2^n + 1) heightmap: the smallest size whose spacing is no
    /// coarser than the model's finer axis over its longer extent, at most 2^13 + 1 a side;
    /// and the model's own extent `[x, z]` in metres (the map covers the larger of the two
    /// on both axes). A model already square and 2^n + 1 keeps its samples exactly.
    pub fn to_heightmap(&self) -> Result<(Heightmap, [f32; 2]), TerrainError> {
        let extent = self.extent();
        let side = extent[0].max(extent[1]);
        let finest = self.spacing[0].min(self.spacing[1]);
        // As fine as the model's finer axis, but never more samples than twice its longer
        // side nor more than 8193 a side (256 MiB), whatever its spacing claims.
        let longest = self.width.max(self.height) as u64;
        let cells_needed = ((side / finest).ceil() as u64).clamp(2, 2 * longest);
        let levels = (64 - (cells_needed - 1).leading_zeros()).clamp(1, MAX_RESAMPLED_LEVELS);
        let size = (1usize << levels) + 1;
        let exact = self.width == size && self.height == size && self.spacing[0] == self.spacing[1];
        let heights = if exact {
            self.heights.clone()
        } else {
            let step = side / (size - 1) as f32;
            let mut out = Vec::with_capacity(size * size);
            for z in 0..size {
                for x in 0..size {
                    out.push(self.height_at(x as f32 * step, z as f32 * step));
                }
            }
            out
        };
        let spacing = if exact {
            self.spacing[0]
        } else {
            side / (size - 1) as f32
        };
        Ok((Heightmap::from_heights(size, spacing, heights)?, extent))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(width: usize, height: usize, spacing: f32) -> ElevationModel {
        ElevationModel {
            width,
            height,
            heights: (0..width * height)
                .map(|i| (i % width) as f32 + 10.0 * (i / width) as f32)
                .collect(),
            spacing: [spacing; 2],
            nodata: 0,
            georeference: None,
            spacing_from_file: true,
        }
    }

    #[test]
    fn any_size_becomes_a_square_grid_keeping_its_heights() {
        // An SRTM-like 3601 grid needs 4097 samples to be no coarser.
        let (map, extent) = model(3601, 100, 30.0).to_heightmap().unwrap();
        assert_eq!(map.size(), 4097);
        assert_eq!(extent, [108_000.0, 2970.0]);
        // The heights along row 0 are the model's, wherever the grids' samples meet.
        let m = model(1009, 600, 2.0);
        let (map, _) = m.to_heightmap().unwrap();
        assert_eq!(map.size(), 1025);
        for x in [0.0f32, 100.0, 2016.0] {
            let (i, got) = ((x / map.spacing()).round() as usize, m.height_at(x, 0.0));
            assert!(
                (map.get(i, 0) - got).abs() < 0.6,
                "{x}: {} vs {got}",
                map.get(i, 0)
            );
        }
    }

    #[test]
    fn a_square_power_of_two_model_is_kept_exactly() {
        let m = model(257, 257, 3.0);
        let (map, _) = m.to_heightmap().unwrap();
        assert_eq!((map.size(), map.spacing()), (257, 3.0));
        assert_eq!(map.heights(), m.heights.as_slice());
    }
}

#[cfg(test)]
mod bounds {
    use super::*;

    #[test]
    fn a_strange_spacing_cannot_make_a_vast_grid() {
        let m = ElevationModel {
            width: 2,
            height: 2,
            heights: vec![0.0; 4],
            spacing: [0.001, 1000.0],
            nodata: 0,
            georeference: None,
            spacing_from_file: true,
        };
        assert_eq!(m.to_heightmap().unwrap().0.size(), 5);
    }
}
