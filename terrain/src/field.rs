//! The `HeightField` trait: anything trees can stand on.

use glam::{Vec2, Vec3};

use crate::heightmap::Heightmap;

/// A terrain surface: height and normal at any (x, z), and the rectangle it covers.
///
/// Forest placement takes any implementor: a generated [`Heightmap`], a [`FlatPlane`], or a
/// user's own terrain.
pub trait HeightField {
    /// Height at world (x, z). Outside [`HeightField::bounds`] implementors clamp to the edge.
    fn height(&self, x: f32, z: f32) -> f32;

    /// Unit surface normal at (x, z). The default uses central differences over `0.5` units.
    fn normal(&self, x: f32, z: f32) -> Vec3 {
        central_difference_normal(self, x, z, 0.5)
    }

    /// The covered rectangle, (min x, min z) and (max x, max z).
    fn bounds(&self) -> (Vec2, Vec2);
}

/// The unit normal of `field` at (x, z) from central differences `e` either side.
fn central_difference_normal<F: HeightField + ?Sized>(field: &F, x: f32, z: f32, e: f32) -> Vec3 {
    let dx = field.height(x + e, z) - field.height(x - e, z);
    let dz = field.height(x, z + e) - field.height(x, z - e);
    Vec3::new(-dx, 2.0 * e, -dz).normalize_or(Vec3::Y)
}

/// A horizontal plane over a rectangle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlatPlane {
    /// Its height.
    pub height: f32,
    /// (min x, min z).
    pub min: Vec2,
    /// (max x, max z).
    pub max: Vec2,
}

impl HeightField for FlatPlane {
    fn height(&self, _x: f32, _z: f32) -> f32 {
        self.height
    }

    fn normal(&self, _x: f32, _z: f32) -> Vec3 {
        Vec3::Y
    }

    fn bounds(&self) -> (Vec2, Vec2) {
        (self.min, self.max)
    }
}

impl Heightmap {
    /// Grid coordinates of world (x, z), clamped to the map.
    fn grid(&self, x: f32, z: f32) -> Vec2 {
        let max = (self.size() - 1) as f32;
        let g = (Vec2::new(x, z) - self.origin()) / self.spacing();
        let g = if g.is_finite() { g } else { Vec2::ZERO };
        g.clamp(Vec2::ZERO, Vec2::splat(max))
    }
}

impl HeightField for Heightmap {
    /// Bilinear interpolation; exact at grid points.
    fn height(&self, x: f32, z: f32) -> f32 {
        let g = self.grid(x, z);
        let n = self.size();
        let (ix, iz) = ((g.x as usize).min(n - 2), (g.y as usize).min(n - 2));
        let (u, v) = (g.x - ix as f32, g.y - iz as f32);
        let (a, b) = (self.get(ix, iz), self.get(ix + 1, iz));
        let (c, d) = (self.get(ix, iz + 1), self.get(ix + 1, iz + 1));
        let top = a + (b - a) * u;
        let bottom = c + (d - c) * u;
        top + (bottom - top) * v
    }

    /// Central differences over one sample spacing.
    fn normal(&self, x: f32, z: f32) -> Vec3 {
        central_difference_normal(self, x, z, self.spacing())
    }

    fn bounds(&self) -> (Vec2, Vec2) {
        (self.origin(), self.origin() + Vec2::splat(self.extent()))
    }
}
