//! The voxel space: occupancy as one bit per voxel, with a coarse level of 8 x 8 x 8 bricks
//! that counts the occupied voxels of each, so that rays skip empty space a brick at a time
//! (the paper's octree idea, one level deep, which is where almost all the saving is).

use glam::{IVec3, UVec3, Vec3};

use crate::error::GrowthError;

/// Voxels along each side of a brick.
pub const BRICK: u32 = 8;

/// The most voxels a grid may have: 2^32 bits, 512 MiB. Larger grids are refused before
/// anything is allocated.
pub const MAX_VOXELS: u64 = 1 << 32;

/// An axis-aligned grid of cubic voxels over a region, each empty or occupied.
///
/// ```
/// use sylva_growth::VoxelGrid;
/// use sylva_growth::glam::Vec3;
/// let mut grid = VoxelGrid::new(Vec3::ZERO, Vec3::splat(4.0), 0.5)?;
/// assert_eq!(grid.dims().to_array(), [8, 8, 8]);
/// let cell = grid.cell_of(Vec3::new(1.2, 0.1, 3.9)).unwrap();
/// assert!(grid.occupy(cell));
/// assert!(grid.is_occupied(cell) && grid.occupied() == 1);
/// # Ok::<(), sylva_growth::GrowthError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct VoxelGrid {
    origin: Vec3,
    voxel: f32,
    dims: UVec3,
    bits: Vec<u64>,
    bricks: Vec<u32>,
    brick_dims: UVec3,
    occupied: u64,
}

impl VoxelGrid {
    /// A grid of empty voxels of side `voxel` covering the box from `min` to `max` (rounded
    /// up to whole voxels). Refuses grids that are empty, not finite or over [`MAX_VOXELS`].
    pub fn new(min: Vec3, max: Vec3, voxel: f32) -> Result<VoxelGrid, GrowthError> {
        sylva_base::range::check(
            "voxel size",
            f64::from(voxel),
            voxel > 0.0,
            "a positive length in metres",
        )?;
        if !(min.is_finite() && max.is_finite()) || max.cmple(min).any() {
            return Err(GrowthError::EmptyRegion { min, max });
        }
        let extent = ((max - min) / voxel).ceil();
        let voxels = f64::from(extent.x) * f64::from(extent.y) * f64::from(extent.z);
        if voxels.is_nan()
            || voxels > MAX_VOXELS as f64
            || extent.max_element() > u32::MAX as f32 / 2.0
        {
            return Err(GrowthError::TooManyVoxels {
                voxels,
                voxel,
                limit: MAX_VOXELS,
            });
        }
        let dims = extent.as_uvec3().max(UVec3::ONE);
        let brick_dims = (dims + UVec3::splat(BRICK - 1)) / BRICK;
        let count = dims.as_u64vec3().element_product();
        let bricks = brick_dims.as_u64vec3().element_product();
        Ok(VoxelGrid {
            origin: min,
            voxel,
            dims,
            bits: vec![0; count.div_ceil(64) as usize],
            bricks: vec![0; bricks as usize],
            brick_dims,
            occupied: 0,
        })
    }

    /// The grid's lowest corner.
    pub fn origin(&self) -> Vec3 {
        self.origin
    }

    /// Side of a voxel.
    pub fn voxel_size(&self) -> f32 {
        self.voxel
    }

    /// Voxels along each axis.
    pub fn dims(&self) -> UVec3 {
        self.dims
    }

    /// Bricks along each axis.
    pub fn brick_dims(&self) -> UVec3 {
        self.brick_dims
    }

    /// The grid's highest corner.
    pub fn max(&self) -> Vec3 {
        self.origin + self.dims.as_vec3() * self.voxel
    }

    /// How many voxels are occupied.
    pub fn occupied(&self) -> u64 {
        self.occupied
    }

    /// The voxel holding `p`, if it is inside the grid.
    pub fn cell_of(&self, p: Vec3) -> Option<UVec3> {
        let c = ((p - self.origin) / self.voxel).floor();
        let inside = c.cmpge(Vec3::ZERO).all() && c.cmplt(self.dims.as_vec3()).all();
        inside.then(|| c.as_uvec3())
    }

    /// The voxel coordinates of `p`, unclamped (may lie outside the grid).
    pub fn cell_coords(&self, p: Vec3) -> IVec3 {
        ((p - self.origin) / self.voxel).floor().as_ivec3()
    }

    /// Whether `cell` (signed, possibly outside) is inside the grid.
    pub fn contains(&self, cell: IVec3) -> bool {
        cell.cmpge(IVec3::ZERO).all() && cell.as_uvec3().cmplt(self.dims).all()
    }

    /// The centre of a voxel.
    pub fn centre(&self, cell: UVec3) -> Vec3 {
        self.origin + (cell.as_vec3() + 0.5) * self.voxel
    }

    fn index(&self, c: UVec3) -> usize {
        (c.x as usize) + self.dims.x as usize * (c.y as usize + self.dims.y as usize * c.z as usize)
    }

    fn brick_index(&self, c: UVec3) -> usize {
        let b = c / BRICK;
        (b.x as usize)
            + self.brick_dims.x as usize
                * (b.y as usize + self.brick_dims.y as usize * b.z as usize)
    }

    /// Whether a voxel inside the grid is occupied; outside the grid, false.
    pub fn is_occupied(&self, cell: UVec3) -> bool {
        if !cell.cmplt(self.dims).all() {
            return false;
        }
        let i = self.index(cell);
        self.bits[i / 64] >> (i % 64) & 1 == 1
    }

    /// Whether the brick holding `cell` has no occupied voxel.
    pub fn brick_is_empty(&self, cell: UVec3) -> bool {
        !cell.cmplt(self.dims).all() || self.bricks[self.brick_index(cell)] == 0
    }

    /// Occupies a voxel inside the grid; returns whether it was empty before. Cells outside
    /// the grid are ignored.
    pub fn occupy(&mut self, cell: UVec3) -> bool {
        if !cell.cmplt(self.dims).all() {
            return false;
        }
        let i = self.index(cell);
        let bit = 1u64 << (i % 64);
        if self.bits[i / 64] & bit != 0 {
            return false;
        }
        self.bits[i / 64] |= bit;
        let b = self.brick_index(cell);
        self.bricks[b] += 1;
        self.occupied += 1;
        true
    }

    /// Empties every voxel.
    pub fn clear(&mut self) {
        self.bits.fill(0);
        self.bricks.fill(0);
        self.occupied = 0;
    }

    /// Occupies every voxel occupied in `other`, a grid of the same shape.
    pub fn union_with(&mut self, other: &VoxelGrid) -> Result<(), GrowthError> {
        if other.dims != self.dims || other.origin != self.origin || other.voxel != self.voxel {
            return Err(GrowthError::GridShapes);
        }
        let (nx, ny) = (self.dims.x as usize, self.dims.y as usize);
        for w in 0..self.bits.len() {
            let mut new = other.bits[w] & !self.bits[w];
            self.bits[w] |= other.bits[w];
            while new != 0 {
                let i = w * 64 + new.trailing_zeros() as usize;
                new &= new - 1;
                let cell = UVec3::new(
                    (i % nx) as u32,
                    ((i / nx) % ny) as u32,
                    (i / (nx * ny)) as u32,
                );
                let brick = self.brick_index(cell);
                self.bricks[brick] += 1;
                self.occupied += 1;
            }
        }
        Ok(())
    }

    /// Bytes of occupancy and brick counts held.
    pub fn heap_bytes(&self) -> usize {
        self.bits.len() * 8 + self.bricks.len() * 4
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_grids_beyond_the_limit_before_allocating() {
        let e = VoxelGrid::new(Vec3::ZERO, Vec3::splat(10_000.0), 0.01).unwrap_err();
        assert!(e.to_string().contains("more than the limit"), "{e}");
        assert!(VoxelGrid::new(Vec3::ZERO, Vec3::ONE, 0.0).is_err());
        assert!(VoxelGrid::new(Vec3::ZERO, Vec3::ONE, f32::NAN).is_err());
        assert!(VoxelGrid::new(Vec3::ONE, Vec3::ZERO, 0.1).is_err());
        assert!(VoxelGrid::new(Vec3::ZERO, Vec3::new(1.0, f32::INFINITY, 1.0), 0.1).is_err());
    }

    #[test]
    fn bricks_count_their_occupied_voxels() {
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(2.0), 0.1).unwrap();
        assert_eq!(g.dims(), UVec3::splat(20));
        assert_eq!(g.brick_dims(), UVec3::splat(3));
        let c = UVec3::new(17, 3, 9);
        assert!(g.brick_is_empty(c));
        assert!(g.occupy(c));
        assert!(!g.occupy(c));
        assert!(!g.brick_is_empty(UVec3::new(16, 0, 8)));
        assert!(g.brick_is_empty(UVec3::new(15, 0, 8)));
        let mut h = VoxelGrid::new(Vec3::ZERO, Vec3::splat(2.0), 0.1).unwrap();
        h.occupy(UVec3::new(1, 1, 1));
        h.occupy(c);
        g.union_with(&h).unwrap();
        assert_eq!(g.occupied(), 2);
        assert!(!g.brick_is_empty(UVec3::ZERO));
        g.clear();
        assert_eq!(g.occupied(), 0);
        assert!(g.brick_is_empty(c));
    }
}
