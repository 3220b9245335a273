//! Light at a point (Greene's method, as the paper uses it): direct light is the fraction of
//! rays towards positions of the sun that leave the voxel space unblocked, ambient light the
//! same over directions spread on the sky's hemisphere; a species weighs the two.

use glam::Vec3;
use sylva_base::hash::{mix, unit_f32};

use crate::grid::VoxelGrid;
use crate::ray::march;

/// Where the sun goes across the sky.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SunPath {
    /// `positions` equidistant points on a half circle from east to west whose plane leans
    /// `tilt_degrees` from the zenith towards the south (0: straight overhead), as the paper
    /// places them.
    Arc {
        /// How many sun positions.
        positions: u32,
        /// Lean of the arc from vertical, towards -z (south), degrees.
        tilt_degrees: f32,
    },
    /// The sun's path on one day at a latitude: `positions` times evenly spread between
    /// sunrise and sunset. North is +z, east +x.
    Season {
        /// Latitude in degrees (north positive).
        latitude: f32,
        /// Day of the year, 1 to 365.
        day: u32,
        /// How many sun positions.
        positions: u32,
    },
}

/// The rays light is sampled along: sun positions and sky directions, all unit vectors with
/// a positive height.
#[derive(Debug, Clone, PartialEq)]
pub struct Sky {
    /// Directions towards the sun's positions.
    pub sun: Vec<Vec3>,
    /// Directions spread uniformly over the upper hemisphere.
    pub hemisphere: Vec<Vec3>,
}

/// Direct and ambient light at a point, each from 0 (all rays blocked) to 1 (open sky).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Light {
    /// Fraction of sun rays that escape.
    pub direct: f32,
    /// Fraction of sky rays that escape.
    pub ambient: f32,
    /// The mean of the escaping sky and sun directions, not normalised (zero when all are
    /// blocked): where the light comes from.
    pub towards: Vec3,
    /// Voxel steps the rays took.
    pub steps: u64,
}

impl Light {
    /// The species' mix: `direct_weight` of the direct light plus the rest of the ambient.
    pub fn combined(&self, direct_weight: f32) -> f32 {
        let w = direct_weight.clamp(0.0, 1.0);
        w * self.direct + (1.0 - w) * self.ambient
    }
}

impl Sky {
    /// The sun's positions along `path` and `rays` sky directions drawn from `seed`.
    ///
    /// ```
    /// use sylva_growth::{Sky, SunPath};
    /// let sky = Sky::new(SunPath::Arc { positions: 9, tilt_degrees: 30.0 }, 64, 7);
    /// assert_eq!((sky.sun.len(), sky.hemisphere.len()), (9, 64));
    /// assert!(sky.sun.iter().chain(&sky.hemisphere).all(|d| d.y > 0.0 && (d.length() - 1.0).abs() < 1e-4));
    /// ```
    pub fn new(path: SunPath, rays: u32, seed: u64) -> Sky {
        Sky {
            sun: sun_positions(path),
            hemisphere: hemisphere(rays, seed),
        }
    }

    /// Direct and ambient light at `point` in `grid`.
    pub fn light_at(&self, grid: &VoxelGrid, point: Vec3) -> Light {
        let mut light = Light::default();
        let mut open = |dirs: &[Vec3]| {
            let mut escaped = 0u32;
            for &d in dirs {
                let m = march(grid, point, d, true);
                light.steps += u64::from(m.steps);
                if m.escaped {
                    escaped += 1;
                    light.towards += d;
                }
            }
            if dirs.is_empty() {
                1.0
            } else {
                escaped as f32 / dirs.len() as f32
            }
        };
        light.direct = open(&self.sun);
        light.ambient = open(&self.hemisphere);
        let n = (self.sun.len() + self.hemisphere.len()).max(1) as f32;
        light.towards /= n;
        light
    }
}

fn sun_positions(path: SunPath) -> Vec<Vec3> {
    match path {
        SunPath::Arc {
            positions,
            tilt_degrees,
        } => {
            let n = positions.clamp(1, 4096);
            let tilt = tilt_degrees.clamp(-80.0, 80.0).to_radians();
            (0..n)
                .map(|k| {
                    // Angles strictly inside (0, 180) degrees: the ends lie on the horizon.
                    let a = std::f32::consts::PI * (k as f32 + 0.5) / n as f32;
                    let (s, c) = a.sin_cos();
                    // East (+x) at a = 0, overhead at 90 degrees, leaning south by the tilt.
                    Vec3::new(c, s * tilt.cos(), -s * tilt.sin()).normalize()
                })
                .collect()
        }
        SunPath::Season {
            latitude,
            day,
            positions,
        } => {
            let n = positions.clamp(1, 4096);
            let lat = latitude.clamp(-89.0, 89.0).to_radians();
            let day = day.clamp(1, 366) as f32;
            // Declination by Cooper's formula.
            let dec =
                (23.44f32.to_radians()) * (std::f32::consts::TAU * (284.0 + day) / 365.0).sin();
            // Hour angle of sunset; the sun is up between -h0 and h0 (none in polar night).
            let cos_h0 = (-lat.tan() * dec.tan()).clamp(-1.0, 1.0);
            let h0 = cos_h0.acos();
            (0..n)
                .filter_map(|k| {
                    let h = -h0 + 2.0 * h0 * (k as f32 + 0.5) / n as f32;
                    let alt = (lat.sin() * dec.sin() + lat.cos() * dec.cos() * h.cos()).asin();
                    // Azimuth from north, clockwise (east positive).
                    let az = (-h.sin() * dec.cos())
                        .atan2(dec.sin() * lat.cos() - dec.cos() * lat.sin() * h.cos());
                    let d = Vec3::new(alt.cos() * az.sin(), alt.sin(), alt.cos() * az.cos());
                    (d.y > 1e-3).then(|| d.normalize())
                })
                .collect()
        }
    }
}

/// Uniform directions on the upper hemisphere by Marsaglia's method, the paper's choice,
/// with the height folded upwards; a pure function of `seed`.
fn hemisphere(rays: u32, seed: u64) -> Vec<Vec3> {
    let mut out = Vec::with_capacity(rays as usize);
    let mut h = mix(seed ^ 0x5eed_5c1e);
    let mut next = || {
        h = mix(h.wrapping_add(0x9e37_79b9_7f4a_7c15));
        2.0 * unit_f32(h) - 1.0
    };
    while out.len() < rays as usize {
        let (v1, v2) = (next(), next());
        let s = v1 * v1 + v2 * v2;
        if s >= 1.0 || s == 0.0 {
            continue;
        }
        let r = 2.0 * (1.0 - s).sqrt();
        let d = Vec3::new(v1 * r, (1.0 - 2.0 * s).abs(), v2 * r);
        if d.y > 1e-4 {
            out.push(d.normalize());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_hemisphere_is_uniform() {
        // Uniform on the hemisphere: the height is uniform on (0, 1), mean 1/2, and the
        // horizontal mean is zero.
        let d = hemisphere(20_000, 3);
        let mean = d.iter().copied().sum::<Vec3>() / d.len() as f32;
        assert!(
            (mean.y - 0.5).abs() < 0.01 && mean.x.abs() < 0.01 && mean.z.abs() < 0.01,
            "{mean}"
        );
    }

    #[test]
    fn the_summer_sun_at_fifty_degrees_north_peaks_in_the_south() {
        let sun = sun_positions(SunPath::Season {
            latitude: 50.0,
            day: 172,
            positions: 101,
        });
        let noon = sun
            .iter()
            .copied()
            .max_by(|a, b| a.y.total_cmp(&b.y))
            .unwrap();
        // Noon altitude: 90 - 50 + 23.44 degrees.
        let alt = noon.y.asin().to_degrees();
        assert!((alt - 63.4).abs() < 0.5, "{alt}");
        assert!(noon.z < 0.0, "the noon sun is south: {noon}");
        let winter = sun_positions(SunPath::Season {
            latitude: 80.0,
            day: 355,
            positions: 11,
        });
        assert!(winter.is_empty(), "polar night");
    }
}
