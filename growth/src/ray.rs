//! Rays through the voxel space: a voxel DDA (Amanatides and Woo) that, with the hierarchy,
//! crosses an empty brick in one step instead of one step per voxel.

use glam::{IVec3, Vec3};

use crate::grid::{BRICK, VoxelGrid};

/// Whether a ray left the grid without meeting an occupied voxel, and what it cost.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct March {
    /// True when the ray reached the grid's boundary unblocked.
    pub escaped: bool,
    /// Voxel and brick steps taken.
    pub steps: u32,
}

/// Marches from `origin` along `direction` (need not be unit) until an occupied voxel or the
/// grid's boundary. The voxel holding `origin` itself is not tested (a bud sits in its own
/// branch's voxels). With `skip_empty_bricks` the march leaps across bricks that hold no
/// occupied voxel. A ray that starts outside the grid, or whose direction is zero or not
/// finite, escapes at once.
///
/// ```
/// use sylva_growth::{VoxelGrid, march};
/// use sylva_growth::glam::{UVec3, Vec3};
/// let mut grid = VoxelGrid::new(Vec3::ZERO, Vec3::splat(8.0), 0.25)?;
/// grid.occupy(UVec3::new(16, 30, 16)); // one voxel above the middle
/// let from = Vec3::new(4.1, 1.0, 4.1);
/// assert!(!march(&grid, from, Vec3::Y, true).escaped);
/// assert!(march(&grid, from, Vec3::X, true).escaped);
/// // The hierarchy takes fewer steps to the same answer.
/// assert!(march(&grid, from, Vec3::X, true).steps < march(&grid, from, Vec3::X, false).steps);
/// # Ok::<(), sylva_growth::GrowthError>(())
/// ```
pub fn march(grid: &VoxelGrid, origin: Vec3, direction: Vec3, skip_empty_bricks: bool) -> March {
    let escaped = March {
        escaped: true,
        steps: 0,
    };
    let Some(dir) = direction.try_normalize() else {
        return escaped;
    };
    if !origin.is_finite() {
        return escaped;
    }
    let v = grid.voxel_size();
    // Work in voxel units from the grid's corner.
    let p = (origin - grid.origin()) / v;
    let mut cell = p.floor().as_ivec3();
    if !grid.contains(cell) {
        return escaped;
    }
    let step = IVec3::new(sign(dir.x), sign(dir.y), sign(dir.z));
    let mut t = 0.0f32;
    let mut steps = 0u32;
    // Distances along the ray from `t` to the far planes of the cube of `size` voxels
    // holding `cell`, per axis (infinite along axes the ray does not travel).
    let to_planes = |cell: IVec3, t: f32, size: i32| -> Vec3 {
        let here = p + dir * t;
        let lo = cell.div_euclid(IVec3::splat(size)) * size;
        let plane = |axis: usize| -> f32 {
            match step[axis] {
                1 => ((lo[axis] + size) as f32 - here[axis]) / dir[axis],
                -1 => (lo[axis] as f32 - here[axis]) / dir[axis],
                _ => f32::INFINITY,
            }
        };
        Vec3::new(plane(0), plane(1), plane(2)).max(Vec3::ZERO)
    };
    let first_axis = |d: Vec3| -> usize {
        if d.x <= d.y && d.x <= d.z {
            0
        } else if d.y <= d.z {
            1
        } else {
            2
        }
    };
    let mut first = true;
    loop {
        steps += 1;
        let c = cell.as_uvec3();
        let leap = skip_empty_bricks && grid.brick_is_empty(c);
        if !leap && !first && grid.is_occupied(c) {
            return March {
                escaped: false,
                steps,
            };
        }
        first = false;
        // Leave this brick (when it is empty) or this voxel, along the axis whose plane
        // comes first; the cell is stepped explicitly, so every step makes progress.
        let size = if leap { BRICK as i32 } else { 1 };
        let d = to_planes(cell, t, size);
        let axis = first_axis(d);
        t += d[axis];
        if leap {
            let lo = cell.div_euclid(IVec3::splat(size)) * size;
            // Where the ray is now, never behind where it was on any axis (rounding at a
            // plane must not send it back), and in the next brick along `axis`.
            let at = (p + dir * t).floor().as_ivec3();
            for k in 0..3 {
                cell[k] = match step[k] {
                    1 => at[k].max(cell[k]),
                    -1 => at[k].min(cell[k]),
                    _ => cell[k],
                };
            }
            cell[axis] = if step[axis] > 0 {
                lo[axis] + size
            } else {
                lo[axis] - 1
            };
        } else {
            cell[axis] += step[axis];
        }
        if !grid.contains(cell) {
            return March {
                escaped: true,
                steps,
            };
        }
    }
}

/// The direction of travel along an axis; components this small never cross a plane.
fn sign(x: f32) -> i32 {
    if x > 1e-7 {
        1
    } else if x < -1e-7 {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::UVec3;

    /// With and without the hierarchy, every ray gets the same answer.
    #[test]
    fn the_hierarchy_never_changes_the_answer() {
        let mut g = VoxelGrid::new(Vec3::ZERO, Vec3::splat(6.0), 0.1).unwrap();
        let mut h = 12345u64;
        let mut next = || {
            h = sylva_base::hash::mix(h);
            sylva_base::hash::unit_f32(h)
        };
        for _ in 0..300 {
            let c = UVec3::new(
                (next() * 60.0) as u32,
                (next() * 60.0) as u32,
                (next() * 60.0) as u32,
            );
            g.occupy(c);
        }
        for _ in 0..2000 {
            let o = Vec3::new(next(), next(), next()) * 6.0;
            let d = Vec3::new(next() - 0.5, next() - 0.5, next() - 0.5);
            assert_eq!(
                march(&g, o, d, true).escaped,
                march(&g, o, d, false).escaped,
                "{o} {d}"
            );
        }
    }
}
