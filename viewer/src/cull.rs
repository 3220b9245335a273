//! Culling on the CPU: each placement's bounding sphere against the planes of a view volume
//! (the camera's frustum, or the sun's box for the shadow map), so that a frame draws the
//! trees in view rather than the whole forest.

use sylva::terrain::glam::{Mat4, Vec3, Vec4};

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

/// A bounding sphere in an instance's own space, as (centre, radius).
pub(crate) fn bounding_sphere(points: impl Iterator<Item = Vec3>) -> (Vec3, f32) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    let mut all = Vec::new();
    for p in points {
        lo = lo.min(p);
        hi = hi.max(p);
        all.push(p);
    }
    if all.is_empty() {
        return (Vec3::ZERO, 0.0);
    }
    let centre = (lo + hi) * 0.5;
    let radius = all
        .iter()
        .map(|p| p.distance(centre))
        .fold(0.0f32, f32::max);
    (centre, radius)
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

    #[test]
    fn the_sphere_holds_every_point() {
        let points = [
            Vec3::ZERO,
            Vec3::new(4.0, 1.0, 0.0),
            Vec3::new(-1.0, 6.0, 2.0),
        ];
        let (c, r) = bounding_sphere(points.into_iter());
        assert!(points.iter().all(|p| p.distance(c) <= r + 1e-5));
    }
}
