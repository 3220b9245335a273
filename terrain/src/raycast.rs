//! Where a ray meets the terrain, exactly: the ray's shadow on the grid is walked cell by
//! cell (each cell once, in order), and in each cell the ray is met with the cell's bilinear
//! surface (the surface [`HeightField::height`] describes) by solving a quadratic, so no
//! ridge, however thin, is stepped over. The painting tool finds the point under the cursor
//! this way.

use glam::{Vec2, Vec3};

use crate::field::HeightField;
use crate::heightmap::Heightmap;

/// A ray's first meeting with the terrain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RayHit {
    /// Distance along the ray, in units of the direction's length.
    pub t: f32,
    /// The point.
    pub point: Vec3,
}

impl Heightmap {
    /// Where the ray from `origin` along `direction` first meets the terrain's surface within
    /// `max_t` (in units of `direction`'s length), or `None`. A ray starting below the
    /// surface meets it at once (`t = 0`). Only the map's square is terrain: rays meet
    /// nothing outside it.
    ///
    /// ```
    /// use sylva_terrain::{Heightmap, glam::Vec3};
    /// let map = Heightmap::from_heights(3, 1.0, vec![0.0, 0.0, 0.0, 0.0, 4.0, 0.0, 0.0, 0.0, 0.0])?;
    /// // Straight down onto the peak in the middle.
    /// let hit = map.raycast(Vec3::new(1.0, 10.0, 1.0), Vec3::NEG_Y, 100.0).unwrap();
    /// assert!((hit.point.y - 4.0).abs() < 1e-4);
    /// # Ok::<(), sylva_terrain::TerrainError>(())
    /// ```
    pub fn raycast(&self, origin: Vec3, direction: Vec3, max_t: f32) -> Option<RayHit> {
        if !(origin.is_finite() && direction.is_finite() && max_t >= 0.0) || direction == Vec3::ZERO
        {
            return None;
        }
        let (lo, hi) = self.bounds();
        let flat = Vec2::new(direction.x, direction.z);
        let start = Vec2::new(origin.x, origin.z);
        // The part of the ray over the map's square (slab test in x and z).
        let (mut t0, mut t1) = (0.0f32, max_t);
        for axis in 0..2 {
            let (s, d) = (start[axis], flat[axis]);
            if d == 0.0 {
                if s < lo[axis] || s > hi[axis] {
                    return None;
                }
                continue;
            }
            let (a, b) = ((lo[axis] - s) / d, (hi[axis] - s) / d);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        if t0 > t1 {
            return None;
        }
        let at = |t: f32| origin + direction * t;
        let spacing = self.spacing();
        let cells = (self.size() - 1) as i64;
        let cell_of = |p: Vec3| {
            let g = (Vec2::new(p.x, p.z) - lo) / spacing;
            (
                (g.x.floor() as i64).clamp(0, cells - 1),
                (g.y.floor() as i64).clamp(0, cells - 1),
            )
        };
        let (mut cx, mut cz) = cell_of(at(t0));
        let (end_x, end_z) = cell_of(at(t1));
        // 2D DDA (Amanatides and Woo): the ray parameter at which it crosses into the next
        // column and row.
        let step = |d: f32| if d > 0.0 { 1 } else { -1 };
        let (sx, sz) = (step(flat.x), step(flat.y));
        let next_boundary = |c: i64, s: i64, o: f32, d: f32, base: f32| {
            if d == 0.0 {
                f32::INFINITY
            } else {
                let edge = base + (c + i64::from(s > 0)) as f32 * spacing;
                (edge - o) / d
            }
        };
        let mut t_next_x = next_boundary(cx, sx, origin.x, flat.x, lo.x);
        let mut t_next_z = next_boundary(cz, sz, origin.z, flat.y, lo.y);
        let dt_x = if flat.x == 0.0 {
            f32::INFINITY
        } else {
            spacing / flat.x.abs()
        };
        let dt_z = if flat.y == 0.0 {
            f32::INFINITY
        } else {
            spacing / flat.y.abs()
        };
        let mut enter = t0;
        // Each cell once: at most every column plus every row.
        for _ in 0..=(2 * cells + 2) {
            let leave = t_next_x.min(t_next_z).min(t1);
            if let Some(t) = self.meet_cell((cx, cz), origin, direction, (enter, leave)) {
                return Some(RayHit { t, point: at(t) });
            }
            if (cx, cz) == (end_x, end_z) || leave >= t1 {
                return None;
            }
            if t_next_x < t_next_z {
                cx += sx;
                t_next_x += dt_x;
            } else {
                cz += sz;
                t_next_z += dt_z;
            }
            if !(0..cells).contains(&cx) || !(0..cells).contains(&cz) {
                return None;
            }
            enter = leave;
        }
        None
    }

    /// The first `t` in `[enter, leave]` where the ray meets cell `(cx, cz)`'s bilinear
    /// surface: the height above the surface along the ray is a quadratic in `t`.
    fn meet_cell(
        &self,
        (cx, cz): (i64, i64),
        origin: Vec3,
        direction: Vec3,
        (enter, leave): (f32, f32),
    ) -> Option<f32> {
        let (ix, iz) = (cx as usize, cz as usize);
        let (a, b) = (self.get(ix, iz), self.get(ix + 1, iz));
        let (c, d) = (self.get(ix, iz + 1), self.get(ix + 1, iz + 1));
        let spacing = self.spacing();
        let corner = self.origin() + Vec2::new(ix as f32, iz as f32) * spacing;
        // u(t) = u0 + du t, v(t) = v0 + dv t in the cell's unit square.
        let (u0, du) = ((origin.x - corner.x) / spacing, direction.x / spacing);
        let (v0, dv) = ((origin.z - corner.y) / spacing, direction.z / spacing);
        // h(u, v) = a + (b - a) u + (c - a) v + (a - b - c + d) u v.
        let (p, q, r) = (b - a, c - a, a - b - c + d);
        // f(t) = y(t) - h(u(t), v(t)) = k2 t^2 + k1 t + k0, in f64 for the cancellations.
        let (u0, du, v0, dv) = (f64::from(u0), f64::from(du), f64::from(v0), f64::from(dv));
        let (p, q, r, a) = (f64::from(p), f64::from(q), f64::from(r), f64::from(a));
        let k2 = -r * du * dv;
        let k1 = f64::from(direction.y) - p * du - q * dv - r * (u0 * dv + v0 * du);
        let k0 = f64::from(origin.y) - (a + p * u0 + q * v0 + r * u0 * v0);
        let f = |t: f64| (k2 * t + k1) * t + k0;
        let (t_in, t_out) = (f64::from(enter), f64::from(leave));
        if f(t_in) <= 0.0 {
            return Some(enter);
        }
        // Roots of the quadratic (or the line) inside the span, the first where f falls to 0.
        let mut roots = [f64::NAN; 2];
        if k2.abs() < 1e-12 {
            if k1 != 0.0 {
                roots[0] = -k0 / k1;
            }
        } else {
            let disc = k1 * k1 - 4.0 * k2 * k0;
            if disc >= 0.0 {
                let s = disc.sqrt();
                // The numerically stable pair.
                let qq = -0.5 * (k1 + k1.signum() * s);
                roots = [qq / k2, if qq != 0.0 { k0 / qq } else { f64::NAN }];
            }
        }
        roots
            .into_iter()
            .filter(|t| t.is_finite() && *t >= t_in && *t <= t_out)
            .fold(None, |best: Option<f64>, t| {
                Some(best.map_or(t, |b| b.min(t)))
            })
            .map(|t| t as f32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(size: usize, heights: Vec<f32>) -> Heightmap {
        Heightmap::from_heights(size, 1.0, heights).expect("map")
    }

    /// The first t where the ray is at or below the surface, by tiny steps (the slow
    /// reference a march would approximate).
    fn brute(map: &Heightmap, o: Vec3, d: Vec3, max_t: f32) -> Option<f32> {
        let (lo, hi) = map.bounds();
        let n = 200_000;
        (0..=n).map(|k| max_t * k as f32 / n as f32).find(|&t| {
            let p = o + d * t;
            p.x >= lo.x && p.z >= lo.y && p.x <= hi.x && p.z <= hi.y && p.y <= map.height(p.x, p.z)
        })
    }

    #[test]
    fn a_thin_ridge_is_not_stepped_over() {
        // One high sample in a flat 9 x 9 map: a ridge a cell wide.
        let mut h = vec![0.0; 81];
        h[4 * 9 + 4] = 3.0;
        let m = map(9, h);
        // A low, long ray across the ridge at height 2, falling slowly.
        let o = Vec3::new(0.5, 2.0, 4.0);
        let d = Vec3::new(1.0, -0.01, 0.0);
        let hit = m.raycast(o, d, 8.0).expect("the ray meets the ridge");
        let reference = brute(&m, o, d, 8.0).expect("reference");
        assert!((hit.t - reference).abs() < 1e-3, "{} vs {reference}", hit.t);
        assert!((hit.point.y - m.height(hit.point.x, hit.point.z)).abs() < 1e-4);
        // A march of one-metre steps would miss it: at no whole step is the ray below.
        assert!((0..=8).all(|k| {
            let p = o + d * k as f32;
            p.y > m.height(p.x.clamp(0.0, 8.0), p.z)
        }));
    }

    #[test]
    fn rays_that_miss_or_start_below() {
        let m = map(3, vec![1.0; 9]);
        assert_eq!(m.raycast(Vec3::new(1.0, 5.0, 1.0), Vec3::Y, 10.0), None);
        assert_eq!(
            m.raycast(Vec3::new(10.0, 5.0, 10.0), Vec3::NEG_Y, 10.0),
            None
        );
        let below = m.raycast(Vec3::new(1.0, 0.0, 1.0), Vec3::X, 10.0).unwrap();
        assert_eq!(below.t, 0.0);
        assert_eq!(m.raycast(Vec3::new(1.0, 5.0, 1.0), Vec3::ZERO, 10.0), None);
        assert_eq!(m.raycast(Vec3::new(1.0, 5.0, 1.0), Vec3::NEG_Y, 3.0), None);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

        /// On any terrain, from any point above it, the exact meeting agrees with a march of
        /// tiny steps (and where the march finds none, the ray at most grazes the surface).
        #[test]
        fn the_meeting_agrees_with_a_fine_march(
            size in proptest::sample::select(vec![3usize, 5, 9]),
            heights in proptest::collection::vec(0.0f32..5.0, 81),
            x in 0.0f32..8.0, z in 0.0f32..8.0, y in 5.5f32..9.0,
            dx in -1.0f32..1.0, dz in -1.0f32..1.0, dy in -1.0f32..-0.05,
        ) {
            let m = map(size, heights[..size * size].to_vec());
            let (o, d) = (Vec3::new(x, y, z), Vec3::new(dx, dy, dz));
            let max_t = 40.0;
            let hit = m.raycast(o, d, max_t);
            match (hit, brute(&m, o, d, max_t)) {
                (Some(h), Some(r)) => proptest::prop_assert!((h.t - r).abs() < 1e-2, "{} vs {}", h.t, r),
                (None, None) => {}
                (Some(h), None) => {
                    let p = h.point;
                    proptest::prop_assert!((p.y - m.height(p.x, p.z)).abs() < 1e-3, "{h:?}");
                }
                (None, Some(r)) => proptest::prop_assert!(false, "missed the terrain at t = {r}"),
            }
        }
    }
}
