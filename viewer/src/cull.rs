//! Culling on the CPU: each placement's bounding sphere against the planes of a view volume
//! (the camera's frustum, or the sun's box for the shadow map), so that a frame draws the
//! trees in view rather than the whole forest.

use sylva::terrain::glam::{Mat4, Vec3, Vec4};

use crate::cell::Level;
use crate::scene::Scene;
use crate::world::{InstanceRaw, world_sphere};

/// A convex view volume as inward-facing planes `n . p + d >= 0`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Volume {
    planes: [Vec4; 6],
}

impl Volume {
    /// The volume a view-projection matrix sees, with wgpu's clip space (depth 0 to 1):
    /// the Gribb-Hartmann planes, normalised so distances are in world units.
    pub(crate) fn of(view_proj: &Mat4) -> Volume {
        let m = view_proj.transpose();
        let (r0, r1, r2, r3) = (m.x_axis, m.y_axis, m.z_axis, m.w_axis);
        let planes = [r3 + r0, r3 - r0, r3 + r1, r3 - r1, r2, r3 - r2].map(|p| {
            let length = p.truncate().length();
            if length > 0.0 { p / length } else { p }
        });
        Volume { planes }
    }

    /// Whether any part of the sphere may be inside.
    pub(crate) fn touches(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|p| p.truncate().dot(centre) + p.w >= -radius)
    }
}

/// Placements smaller on screen than this many pixels across are not drawn: far twigs and
/// seedlings that fog would hide anyway.
const MIN_PIXELS: f32 = 2.0;

/// Appends to `visible` the placements of every group in the fine cells drawn, then the
/// proxies of every variant, whose bounding spheres touch `volume` and, seen from `eye` with
/// `pixels_per_radian`, span at least [`MIN_PIXELS`]. With `lod` (a point and a distance), a
/// fine cell's trees farther than that from the point are drawn as proxies too. Returns (first, count) in
/// `visible` for each group, then for each variant's proxies.
pub(crate) fn visible_instances(
    scene: &Scene,
    volume: &Volume,
    (eye, pixels_per_radian): (Vec3, f32),
    lod: Option<(Vec3, f32)>,
    visible: &mut Vec<InstanceRaw>,
) -> Vec<(u64, u32)> {
    // A sphere of radius r at distance d spans about 2 r / d radians.
    let min_ratio = 0.5 * MIN_PIXELS / pixels_per_radian.max(1e-6);
    let seen = |i: &InstanceRaw, sphere: (Vec3, f32)| {
        let (world, r) = world_sphere(i, sphere);
        volume.touches(world, r) && r >= min_ratio * world.distance(eye)
    };
    let near = |i: &InstanceRaw| {
        lod.is_none_or(|(from, far)| {
            Vec3::new(i.tree[0], i.tree[1], i.tree[2]).distance(from) <= far
        })
    };
    // Whole cells out of view are skipped before their placements are looked at.
    let (mut fine, mut coarse) = (Vec::new(), Vec::new());
    for (key, cell) in scene.cells.drawn() {
        let (centre, radius) = cell.sphere;
        if radius >= 0.0 && volume.touches(centre, radius) {
            match key.level {
                Level::Fine => fine.push(cell),
                Level::Coarse => coarse.push(cell),
            }
        }
    }
    let world = &scene.world;
    let mut ranges = Vec::with_capacity(world.groups.len() + world.proxies.len());
    for (k, g) in world.groups.iter().enumerate() {
        let first = visible.len();
        for cell in &fine {
            let run = cell.placements.run(k).iter();
            visible.extend(run.filter(|i| near(i) && seen(i, g.sphere)));
        }
        ranges.push((first as u64, (visible.len() - first) as u32));
    }
    for (k, p) in world.proxies.iter().enumerate() {
        let first = visible.len();
        if lod.is_some() {
            for cell in &fine {
                let run = cell.proxies.run(k).iter();
                visible.extend(run.filter(|i| !near(i) && seen(i, p.sphere)));
            }
        }
        for cell in &coarse {
            visible.extend(cell.proxies.run(k).iter().filter(|i| seen(i, p.sphere)));
        }
        ranges.push((first as u64, (visible.len() - first) as u32));
    }
    ranges
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::terrain::glam::camera::rh::{proj::directx, view};

    #[test]
    fn spheres_in_front_are_kept_and_spheres_behind_or_aside_are_culled() {
        let proj = directx::perspective(60f32.to_radians(), 1.0, 0.2, 500.0);
        let look = view::look_to_mat4(Vec3::ZERO, Vec3::X, Vec3::Y);
        let v = Volume::of(&(proj * look));
        assert!(v.touches(Vec3::new(50.0, 0.0, 0.0), 1.0));
        assert!(!v.touches(Vec3::new(-50.0, 0.0, 0.0), 1.0));
        assert!(!v.touches(Vec3::new(50.0, 0.0, 60.0), 1.0));
        // Half a field of view is 30 degrees: a sphere just outside the edge, larger than
        // its distance to the plane, is kept.
        assert!(v.touches(Vec3::new(50.0, 0.0, 31.0), 5.0));
        assert!(!v.touches(Vec3::new(600.0, 0.0, 0.0), 1.0));
    }
}
