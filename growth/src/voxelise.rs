//! Putting geometry into the voxel space, conservatively: every voxel a shape touches is
//! occupied, so thin and sliver triangles leave no holes (the paper's scattered sample points
//! could step over voxels) and branches occupy voxels by their radius, not only their centre
//! line.

use glam::{UVec3, Vec3};
use sylva_terrain::HeightField;

use crate::grid::VoxelGrid;

/// Occupies every voxel that the triangles of `positions` and `indices` (three per triangle)
/// touch, by an exact triangle-box overlap test over each triangle's bounding voxels.
/// Triangles with an index out of range, a coordinate that is not finite or no area are
/// skipped; returns how many.
///
/// ```
/// use sylva_growth::{VoxelGrid, voxelise_triangles};
/// use sylva_growth::glam::Vec3;
/// let mut grid = VoxelGrid::new(Vec3::ZERO, Vec3::splat(1.0), 0.1)?;
/// // A floor over the whole grid at y = 0.55: one full layer of voxels.
/// let floor = [Vec3::new(-1.0, 0.55, -1.0), Vec3::new(3.0, 0.55, -1.0), Vec3::new(-1.0, 0.55, 3.0)];
/// assert_eq!(voxelise_triangles(&mut grid, &floor, &[0, 1, 2]), 0);
/// assert_eq!(grid.occupied(), 100);
/// # Ok::<(), sylva_growth::GrowthError>(())
/// ```
pub fn voxelise_triangles(grid: &mut VoxelGrid, positions: &[Vec3], indices: &[u32]) -> usize {
    let mut skipped = 0;
    for t in indices.chunks_exact(3) {
        let corners = [t[0], t[1], t[2]].map(|i| positions.get(i as usize).copied());
        let [Some(a), Some(b), Some(c)] = corners else {
            skipped += 1;
            continue;
        };
        if !(a.is_finite() && b.is_finite() && c.is_finite())
            || (b - a).cross(c - a).length_squared() <= f32::MIN_POSITIVE
        {
            skipped += 1;
            continue;
        }
        let Some((lo, hi)) = cell_range(grid, a.min(b).min(c), a.max(b).max(c)) else {
            continue;
        };
        let half = Vec3::splat(grid.voxel_size() * 0.5);
        for z in lo.z..=hi.z {
            for y in lo.y..=hi.y {
                for x in lo.x..=hi.x {
                    let cell = UVec3::new(x, y, z);
                    let centre = grid.centre(cell);
                    if triangle_touches_box(a - centre, b - centre, c - centre, half) {
                        grid.occupy(cell);
                    }
                }
            }
        }
    }
    skipped
}

/// Occupies every voxel within `radius` of the segment from `a` to `b` (a capsule: a
/// branch's swept volume), conservatively: a voxel counts when its centre lies within
/// `radius` plus half the voxel's diagonal of the segment. Returns how many voxels were newly
/// occupied.
pub fn voxelise_capsule(grid: &mut VoxelGrid, a: Vec3, b: Vec3, radius: f32) -> usize {
    let mut added = 0;
    let shape = Lattice::of(grid);
    capsule_cells(shape, a, b, radius, &mut |cell| {
        added += usize::from(grid.occupy(cell));
        true
    });
    added
}

/// Whether every voxel [`voxelise_capsule`] would occupy for this capsule is empty. Parts
/// outside the grid count as free.
pub fn capsule_is_free(grid: &VoxelGrid, a: Vec3, b: Vec3, radius: f32) -> bool {
    capsule_is_free_beyond(grid, a, b, radius, -1.0)
}

/// As [`capsule_is_free`], leaving out voxels whose centre lies within `clearance` of `a`
/// (where a branch leaves the wood it grows from).
pub(crate) fn capsule_is_free_beyond(
    grid: &VoxelGrid,
    a: Vec3,
    b: Vec3,
    radius: f32,
    clearance: f32,
) -> bool {
    capsule_cells(Lattice::of(grid), a, b, radius, &mut |cell| {
        !grid.is_occupied(cell) || grid.centre(cell).distance(a) <= clearance
    })
}

/// Fills every column of voxels from the grid's floor up to the ground of `terrain` (the
/// highest of the ground at the column's corners and centre, so slopes leave no gaps).
pub fn voxelise_ground(grid: &mut VoxelGrid, terrain: &dyn HeightField) {
    let dims = grid.dims();
    let v = grid.voxel_size();
    for z in 0..dims.z {
        for x in 0..dims.x {
            let c = grid.centre(UVec3::new(x, 0, z));
            let h = [
                (-0.5f32, -0.5f32),
                (0.5, -0.5),
                (-0.5, 0.5),
                (0.5, 0.5),
                (0.0, 0.0),
            ]
            .iter()
            .map(|(dx, dz)| terrain.height(c.x + dx * v, c.z + dz * v))
            .fold(f32::NEG_INFINITY, f32::max);
            if !h.is_finite() {
                continue;
            }
            let top = ((h - grid.origin().y) / v).floor();
            if top < 0.0 {
                continue;
            }
            let top = (top as u32).min(dims.y - 1);
            for y in 0..=top {
                grid.occupy(UVec3::new(x, y, z));
            }
        }
    }
}

/// The voxels a box from `lo` to `hi` overlaps, clamped to the grid; `None` if it misses.
fn cell_range(grid: &VoxelGrid, lo: Vec3, hi: Vec3) -> Option<(UVec3, UVec3)> {
    let dims = grid.dims().as_ivec3();
    let l = grid.cell_coords(lo).max(glam::IVec3::ZERO);
    let h = grid.cell_coords(hi).min(dims - 1);
    (l.cmple(h).all()).then(|| (l.as_uvec3(), h.as_uvec3()))
}

/// A grid's shape without its contents, so that visiting its voxels leaves the grid free to
/// change.
#[derive(Debug, Clone, Copy)]
struct Lattice {
    origin: Vec3,
    voxel: f32,
    dims: UVec3,
}

impl Lattice {
    fn of(grid: &VoxelGrid) -> Lattice {
        Lattice {
            origin: grid.origin(),
            voxel: grid.voxel_size(),
            dims: grid.dims(),
        }
    }

    fn centre(&self, cell: UVec3) -> Vec3 {
        self.origin + (cell.as_vec3() + 0.5) * self.voxel
    }

    /// The voxels a box from `lo` to `hi` overlaps, clamped to the grid; `None` if it misses.
    fn range(&self, lo: Vec3, hi: Vec3) -> Option<(UVec3, UVec3)> {
        let coords = |p: Vec3| ((p - self.origin) / self.voxel).floor().as_ivec3();
        let l = coords(lo).max(glam::IVec3::ZERO);
        let h = coords(hi).min(self.dims.as_ivec3() - 1);
        (l.cmple(h).all()).then(|| (l.as_uvec3(), h.as_uvec3()))
    }
}

/// Visits the voxels a capsule touches (see [`voxelise_capsule`]) until `visit` returns
/// false; returns whether every one was visited. Nothing is gathered, so any radius runs in
/// bounded memory.
fn capsule_cells(
    lattice: Lattice,
    a: Vec3,
    b: Vec3,
    radius: f32,
    visit: &mut dyn FnMut(UVec3) -> bool,
) -> bool {
    let r = radius.max(0.0);
    if !(a.is_finite() && b.is_finite() && r.is_finite()) {
        return true;
    }
    let Some((lo, hi)) = lattice.range(a.min(b) - r, a.max(b) + r) else {
        return true;
    };
    let reach = r + lattice.voxel * 0.5 * 3f32.sqrt();
    for z in lo.z..=hi.z {
        for y in lo.y..=hi.y {
            for x in lo.x..=hi.x {
                let cell = UVec3::new(x, y, z);
                if distance_to_segment(lattice.centre(cell), a, b) <= reach && !visit(cell) {
                    return false;
                }
            }
        }
    }
    true
}

/// Distance from `p` to the segment from `a` to `b`.
pub fn distance_to_segment(p: Vec3, a: Vec3, b: Vec3) -> f32 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// Akenine-Möller's separating-axis test of a triangle (relative to the box's centre)
/// against a box of half extents `h`: the box's three axes, the triangle's normal and the
/// nine cross products of edges and axes.
fn triangle_touches_box(v0: Vec3, v1: Vec3, v2: Vec3, h: Vec3) -> bool {
    let edges = [v1 - v0, v2 - v1, v0 - v2];
    let axes = [Vec3::X, Vec3::Y, Vec3::Z];
    let separated = |axis: Vec3| {
        if axis.length_squared() < 1e-20 {
            return false;
        }
        let p = [v0.dot(axis), v1.dot(axis), v2.dot(axis)];
        // A hair over the box's reach: a triangle lying exactly on a face between two voxels
        // touches both, whatever the rounding.
        let r = (h.x * axis.x.abs() + h.y * axis.y.abs() + h.z * axis.z.abs()) * (1.0 + 1e-4);
        p.iter().copied().fold(f32::INFINITY, f32::min) > r
            || p.iter().copied().fold(f32::NEG_INFINITY, f32::max) < -r
    };
    for e in edges {
        for a in axes {
            if separated(e.cross(a)) {
                return false;
            }
        }
    }
    for a in axes {
        if separated(a) {
            return false;
        }
    }
    !separated(edges[0].cross(edges[1]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sliver_triangle_leaves_no_gap() {
        // A needle-thin triangle along a diagonal: every voxel its centre line crosses is hit.
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(2.0), 0.1).unwrap();
        let (a, b) = (Vec3::new(0.05, 0.05, 0.05), Vec3::new(1.95, 1.33, 0.77));
        let c = b + Vec3::new(0.0, 1e-4, 0.0);
        voxelise_triangles(&mut g, &[a, b, c], &[0, 1, 2]);
        for k in 0..=1000 {
            let p = a + (b - a) * (k as f32 / 1000.0);
            assert!(g.is_occupied(g.cell_of(p).unwrap()), "gap at {p}");
        }
    }

    #[test]
    fn a_triangle_on_the_plane_between_voxels_fills_a_whole_layer() {
        // Exactly on the boundary between two layers, rounding must not let it slip through
        // both (it once did).
        for y in [0.4, 0.5, 0.7] {
            let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(1.0), 0.1).unwrap();
            let t = [
                Vec3::new(-1.0, y, -1.0),
                Vec3::new(3.0, y, -1.0),
                Vec3::new(-1.0, y, 3.0),
            ];
            voxelise_triangles(&mut g, &t, &[0, 1, 2]);
            assert!(
                g.occupied() == 100 || g.occupied() == 200,
                "{y}: {}",
                g.occupied()
            );
        }
    }

    #[test]
    fn degenerate_triangles_are_skipped() {
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(1.0), 0.1).unwrap();
        let p = [Vec3::ZERO, Vec3::X, Vec3::X * 2.0, Vec3::NAN];
        assert_eq!(
            voxelise_triangles(&mut g, &p, &[0, 1, 2, 0, 1, 3, 0, 1, 9]),
            3
        );
        assert_eq!(g.occupied(), 0);
    }

    #[test]
    fn a_huge_radius_fills_the_grid_without_gathering_it() {
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(2.0), 0.1).unwrap();
        assert_eq!(voxelise_capsule(&mut g, Vec3::ONE, Vec3::ONE, 1e6), 8000);
        assert!(!capsule_is_free(&g, Vec3::ZERO, Vec3::ONE, 1e9));
        assert!(capsule_is_free(
            &g,
            Vec3::splat(50.0),
            Vec3::splat(60.0),
            1.0
        ));
    }

    #[test]
    fn a_capsule_occupies_its_radius_and_blocks_its_own_path() {
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(2.0), 0.05).unwrap();
        let (a, b) = (Vec3::new(1.0, 0.2, 1.0), Vec3::new(1.0, 1.8, 1.0));
        assert!(capsule_is_free(&g, a, b, 0.2));
        voxelise_capsule(&mut g, a, b, 0.2);
        // A point 0.19 m off the axis is inside a voxel the capsule occupies.
        assert!(g.is_occupied(g.cell_of(Vec3::new(1.19, 1.0, 1.0)).unwrap()));
        assert!(!g.is_occupied(g.cell_of(Vec3::new(1.4, 1.0, 1.0)).unwrap()));
        assert!(!capsule_is_free(
            &g,
            Vec3::new(0.5, 1.0, 1.0),
            Vec3::new(1.5, 1.0, 1.0),
            0.01
        ));
    }
}
