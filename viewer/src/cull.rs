//! Culling on the CPU: each placement's bounding sphere against the planes of a view volume
//! (the camera's frustum, or the sun's box for the shadow map), so that a frame draws the
//! trees in view rather than the whole forest.

use sylva::terrain::glam::{Mat4, Vec3, Vec4};

use crate::cell::Level;
use crate::scene::Scene;
use crate::world::{InstanceRaw, MESH_LEVELS, world_sphere};

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

/// Which level of detail each tree is drawn at: seen from `eye` by a screen of
/// `pixels_per_radian`, allowing `pixel_error` pixels of error; levels cross-fade (dithered)
/// over `fade` of each switch distance.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LodView {
    pub(crate) eye: Vec3,
    pub(crate) pixels_per_radian: f32,
    pub(crate) pixel_error: f32,
    pub(crate) fade: f32,
}

impl LodView {
    /// The levels a tree at `base` of a variant with `errors` is drawn at: one, or two
    /// fading into each other, as (level, fade) with the fade in the shader's encoding (0:
    /// whole; `f > 0`: fading out, drawn where the dither is at least `f`; `-f`: fading in,
    /// drawn where it is below `f`). Level `MESH_LEVELS` is the impostor.
    fn levels(&self, base: Vec3, errors: &[f32; MESH_LEVELS]) -> [Option<(usize, f32)>; 2] {
        let d = base.distance(self.eye);
        let scale = self.pixels_per_radian / self.pixel_error.max(1e-3);
        let mut level = 0;
        for (k, &e) in errors.iter().enumerate() {
            let from = e * scale;
            if d < from {
                break;
            }
            level = k + 1;
            let band = from * self.fade;
            if d < from + band && band > 0.0 {
                let f = ((d - from) / band).clamp(1e-3, 1.0);
                return [Some((k, f)), Some((k + 1, -f))];
            }
        }
        [Some((level, 0.0)), None]
    }
}

/// The same placement with its fade.
fn faded(i: &InstanceRaw, fade: f32) -> InstanceRaw {
    let mut out = *i;
    out.tint[3] = fade;
    out
}

/// Appends to `visible` the placements of every group in the fine cells drawn, level by
/// level, then the impostors of every variant, whose bounding spheres touch `volume` and,
/// seen from `eye` with `pixels_per_radian`, span at least [`MIN_PIXELS`]. With `lod`, each
/// tree is drawn at the level its distance asks for, and at the impostor in coarse cells;
/// without it, every tree of a fine cell at full detail. Returns (first, count) in `visible`
/// for each group's levels (group `k`, level `l` at `k * MESH_LEVELS + l`), then for each
/// variant's impostors.
pub(crate) fn visible_instances(
    scene: &Scene,
    volume: &Volume,
    (eye, pixels_per_radian): (Vec3, f32),
    lod: Option<LodView>,
    visible: &mut Vec<InstanceRaw>,
) -> Vec<(u64, u32)> {
    // A sphere of radius r at distance d spans about 2 r / d radians.
    let min_ratio = 0.5 * MIN_PIXELS / pixels_per_radian.max(1e-6);
    let seen = |i: &InstanceRaw, sphere: (Vec3, f32)| {
        let (world, r) = world_sphere(i, sphere);
        volume.touches(world, r) && r >= min_ratio * world.distance(eye)
    };
    let base = |i: &InstanceRaw| Vec3::new(i.tree[0], i.tree[1], i.tree[2]);
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
    let mut ranges = Vec::with_capacity(world.groups.len() * MESH_LEVELS + world.proxies.len());
    let mut by_level: [Vec<InstanceRaw>; MESH_LEVELS] = Default::default();
    for (k, g) in world.groups.iter().enumerate() {
        let errors = &world.lods[g.variant].errors;
        for cell in &fine {
            for i in cell.placements.run(k) {
                let Some(lod) = lod else {
                    if seen(i, g.sphere) {
                        by_level[0].push(*i);
                    }
                    continue;
                };
                for (level, fade) in lod.levels(base(i), errors).into_iter().flatten() {
                    if level < MESH_LEVELS && seen(i, g.sphere) {
                        by_level[level].push(faded(i, fade));
                    }
                }
            }
        }
        for level in &mut by_level {
            let first = visible.len();
            visible.append(level);
            ranges.push((first as u64, (visible.len() - first) as u32));
        }
    }
    for (k, p) in world.proxies.iter().enumerate() {
        let first = visible.len();
        if let Some(lod) = lod {
            let errors = &world.lods[k].errors;
            for cell in &fine {
                for i in cell.proxies.run(k) {
                    for (level, fade) in lod.levels(base(i), errors).into_iter().flatten() {
                        if level == MESH_LEVELS && seen(i, p.sphere) {
                            visible.push(faded(i, fade));
                        }
                    }
                }
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
