//! Culling on the CPU: each placement's bounding sphere against the planes of a view volume
//! (the camera's frustum, or the sun's box for the shadow map), so that a frame draws the
//! trees in view rather than the whole forest; and each tree's level of detail. A frame's
//! placements are gathered with these tests.

use sylva::terrain::glam::{Mat4, Vec3, Vec4};

use crate::cell::RunBounds;
use crate::geometry::MESH_LEVELS;

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

    /// Whether the whole sphere is inside.
    pub(crate) fn holds(&self, centre: Vec3, radius: f32) -> bool {
        self.planes
            .iter()
            .all(|p| p.truncate().dot(centre) + p.w >= radius)
    }
}

/// Placements smaller on screen than this many pixels across are not drawn: far twigs and
/// seedlings that fog would hide anyway.
pub(crate) const MIN_PIXELS: f32 = 2.0;

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
    pub(crate) fn levels(&self, base: Vec3, errors: &[f32; MESH_LEVELS]) -> Levels {
        self.levels_at(base.distance(self.eye), errors)
    }

    /// [`LodView::levels`] of a tree `d` from the eye.
    fn levels_at(&self, d: f32, errors: &[f32; MESH_LEVELS]) -> Levels {
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

    /// The one level, unfaded, of every tree whose base is in the box `bases`, when they
    /// all have one: the levels at the box's nearest and farthest points agree and
    /// neither fades. A tree's distance lies between the box's (floating point keeps that
    /// order: each is the same sum of squares of differences no smaller or no larger), and
    /// the level only grows with distance, passing through a fade at each switch.
    pub(crate) fn level_across(
        &self,
        bases: (Vec3, Vec3),
        errors: &[f32; MESH_LEVELS],
    ) -> Option<Levels> {
        let near = self.levels_at(nearest_distance(self.eye, bases), errors);
        let far = self.levels_at(farthest_distance(self.eye, bases), errors);
        (near == far && near[1].is_none() && near[0].is_some_and(|(_, f)| f == 0.0)).then_some(near)
    }
}

/// The levels a tree is drawn at: one, or two fading into each other, as (level, fade).
pub(crate) type Levels = [Option<(usize, f32)>; 2];

/// One view to gather placements for: its volume, and the eye and pixels per radian that
/// decide which placements are too small on screen to draw.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Sight {
    pub(crate) volume: Volume,
    pub(crate) eye: Vec3,
    pub(crate) pixels_per_radian: f32,
}

/// How much of a bounding sphere a sight's volume holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Cover {
    Out,
    Partly,
    /// Wholly inside: what it bounds needs no test against the planes.
    Inside,
}

impl Sight {
    pub(crate) fn cover(&self, (centre, radius): (Vec3, f32)) -> Cover {
        if radius < 0.0 || !self.volume.touches(centre, radius) {
            Cover::Out
        } else if self.volume.holds(centre, radius) {
            Cover::Inside
        } else {
            Cover::Partly
        }
    }

    /// The smallest ratio of radius to distance that spans [`MIN_PIXELS`]: a sphere of
    /// radius r at distance d spans about 2 r / d radians.
    pub(crate) fn min_ratio(&self) -> f32 {
        0.5 * MIN_PIXELS / self.pixels_per_radian.max(1e-6)
    }

    /// How much of a run this sight may see: none when its box is out of the volume, or
    /// when its largest instance is too small at the box's nearest point.
    fn cover_run(&self, run: &RunBounds) -> Cover {
        let nearest = nearest_distance(self.eye, run.spheres);
        if run.radius < self.min_ratio() * nearest {
            return Cover::Out;
        }
        self.cover(run.sphere())
    }

    /// Whether every instance of a run (or piece of one) is seen without testing each: the
    /// run is wholly inside, and its smallest instance spans [`MIN_PIXELS`] even at the
    /// farthest point of its box (no instance's centre is farther).
    pub(crate) fn sees_whole(&self, cover: Cover, run: &RunBounds) -> bool {
        cover == Cover::Inside
            && run.least_radius >= self.min_ratio() * farthest_distance(self.eye, run.spheres)
    }

    /// Whether a placement's world sphere is seen: in the volume (unless its run is wholly
    /// inside) and at least [`MIN_PIXELS`] across.
    pub(crate) fn sees(&self, cover: Cover, (centre, radius): (Vec3, f32)) -> bool {
        (cover == Cover::Inside || self.volume.touches(centre, radius))
            && radius >= self.min_ratio() * centre.distance(self.eye)
    }
}

/// Distance from `p` to the nearest point of the box `(lo, hi)`.
pub(crate) fn nearest_distance(p: Vec3, (lo, hi): (Vec3, Vec3)) -> f32 {
    p.distance(p.clamp(lo, hi))
}

/// Distance from `p` to the farthest point of the box `(lo, hi)`.
pub(crate) fn farthest_distance(p: Vec3, (lo, hi): (Vec3, Vec3)) -> f32 {
    (p - lo).abs().max((p - hi).abs()).length()
}

impl LodView {
    /// The distances between which a tree of a variant with `errors` may be drawn at
    /// some mesh level (nearer than the first) or as the impostor (beyond the second),
    /// fades included: bounds for passing over a run whole.
    pub(crate) fn reach(&self, errors: &[f32; MESH_LEVELS]) -> (f32, f32) {
        let scale = self.pixels_per_radian / self.pixel_error.max(1e-3);
        let farthest = errors.iter().fold(0.0f32, |m, &e| m.max(e * scale));
        // A thousandth to spare either way: `levels` sums a switch distance and its fade
        // band, which may round a little beyond their product.
        (
            farthest * (1.0 + self.fade.max(0.0)) * 1.001,
            farthest * 0.999,
        )
    }
}

/// Which sights may see each instance of a run, or `None` when none can.
pub(crate) fn run_covers(sights: &[Sight], run: &RunBounds) -> Option<[Cover; MAX_SIGHTS]> {
    let mut covers = [Cover::Out; MAX_SIGHTS];
    for (cover, sight) in covers.iter_mut().zip(sights) {
        *cover = sight.cover_run(run);
    }
    covers.iter().any(|&c| c != Cover::Out).then_some(covers)
}

/// The most sights a frame's placements are gathered for in one pass: the camera
/// and the sun.
pub(crate) const MAX_SIGHTS: usize = 2;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
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
    fn a_sphere_is_held_only_when_no_part_of_it_is_outside() {
        let proj = directx::perspective(60f32.to_radians(), 1.0, 0.2, 500.0);
        let v = Volume::of(&(proj * view::look_to_mat4(Vec3::ZERO, Vec3::X, Vec3::Y)));
        assert!(v.holds(Vec3::new(50.0, 0.0, 0.0), 10.0));
        // Touching the edge of the view is not being held by it.
        assert!(v.touches(Vec3::new(50.0, 0.0, 28.0), 5.0));
        assert!(!v.holds(Vec3::new(50.0, 0.0, 28.0), 5.0));
        assert!(!v.holds(Vec3::new(0.5, 0.0, 0.0), 1.0));
    }

    #[test]
    fn box_distances_are_to_the_nearest_and_farthest_corner() {
        let b = (Vec3::ZERO, Vec3::new(2.0, 2.0, 2.0));
        assert_eq!(nearest_distance(Vec3::new(1.0, 1.0, 1.0), b), 0.0);
        assert_eq!(nearest_distance(Vec3::new(5.0, 1.0, 1.0), b), 3.0);
        assert_eq!(
            farthest_distance(Vec3::new(5.0, 0.0, 0.0), b),
            Vec3::new(5.0, 2.0, 2.0).length()
        );
    }

    /// A box from two corners and a point inside it at fractions `t` of each side.
    fn box_and_point(a: [f32; 3], b: [f32; 3], t: [f32; 3]) -> ((Vec3, Vec3), Vec3) {
        let (a, b) = (Vec3::from(a), Vec3::from(b));
        let (lo, hi) = (a.min(b), a.max(b));
        ((lo, hi), (lo + (hi - lo) * Vec3::from(t)).clamp(lo, hi))
    }

    proptest! {
        /// When a box of bases has one level across it, every base in it has that level:
        /// the pieces taken whole draw what testing each tree would.
        #[test]
        fn one_level_across_a_box_is_every_tree_s_level(
            a in prop::array::uniform3(-400.0f32..400.0),
            b in prop::array::uniform3(-400.0f32..400.0),
            t in prop::array::uniform3(0.0f32..=1.0),
            eye in prop::array::uniform3(-400.0f32..400.0),
            errors in prop::array::uniform3(0.0f32..0.4),
            fade in 0.0f32..0.5,
        ) {
            let mut errors = errors;
            errors.sort_by(f32::total_cmp);
            let lod = LodView { eye: Vec3::from(eye), pixels_per_radian: 750.0, pixel_error: 1.5, fade };
            let (bases, base) = box_and_point(a, b, t);
            if let Some(levels) = lod.level_across(bases, &errors) {
                prop_assert_eq!(lod.levels(base, &errors), levels);
                prop_assert!(levels[1].is_none());
            }
        }

        /// A run a sight sees whole has each of its spheres seen.
        #[test]
        fn a_run_seen_whole_has_every_sphere_seen(
            a in prop::array::uniform3(-50.0f32..50.0),
            b in prop::array::uniform3(-50.0f32..50.0),
            t in prop::array::uniform3(0.0f32..=1.0),
            radius in 0.01f32..5.0,
            least in 0.0f32..=1.0,
            yaw in 0.0f32..std::f32::consts::TAU,
        ) {
            let eye = Vec3::new(0.0, 2.0, 0.0) - Vec3::new(yaw.cos(), 0.0, yaw.sin()) * 80.0;
            let proj = directx::perspective(60f32.to_radians(), 1.5, 0.2, 500.0);
            let sight = Sight {
                volume: Volume::of(&(proj * view::look_to_mat4(eye, -eye.with_y(0.0), Vec3::Y))),
                eye,
                pixels_per_radian: 720.0 / 60f32.to_radians(),
            };
            let (centres, centre) = box_and_point(a, b, t);
            let run = RunBounds {
                spheres: (centres.0 - radius, centres.1 + radius),
                bases: centres,
                radius,
                least_radius: radius * least,
            };
            let cover = sight.cover(run.sphere());
            if sight.sees_whole(cover, &run) {
                // Any instance of the run: its centre in the box, its radius at least the least.
                prop_assert!(sight.sees(Cover::Partly, (centre, run.least_radius)));
            }
        }
    }
}
