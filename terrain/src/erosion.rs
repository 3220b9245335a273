//! Erosion: thermal weathering and droplet-based hydraulic erosion (the thesis's proposed
//! replacement for the blur, extension 7.6).

use glam::Vec2;

use crate::error::{TerrainError, check};
use crate::hash::unit;
use crate::heightmap::Heightmap;

/// Thermal erosion: material slides from a sample to lower neighbours wherever the height
/// difference exceeds the talus threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ThermalErosion {
    /// Steepest stable slope (rise over run); 0.7 is about 35 degrees, the angle of repose of
    /// loose rock. Default: 0.7.
    pub talus: f32,
    /// Fraction of the excess moved per iteration, in (0, 0.5]. Default: 0.25.
    pub rate: f32,
    /// Number of iterations; each is one pass over the map. 50 is a light touch, 500 heavy.
    /// Default: 50.
    pub iterations: u32,
}

impl Default for ThermalErosion {
    fn default() -> Self {
        ThermalErosion {
            talus: 0.7,
            rate: 0.25,
            iterations: 50,
        }
    }
}

impl ThermalErosion {
    /// Sets [`ThermalErosion::talus`].
    #[must_use]
    pub fn with_talus(mut self, talus: f32) -> Self {
        self.talus = talus;
        self
    }

    /// Sets [`ThermalErosion::rate`].
    #[must_use]
    pub fn with_rate(mut self, rate: f32) -> Self {
        self.rate = rate;
        self
    }

    /// Sets [`ThermalErosion::iterations`].
    #[must_use]
    pub fn with_iterations(mut self, iterations: u32) -> Self {
        self.iterations = iterations;
        self
    }
}

impl ThermalErosion {
    /// Thermal erosion with the given talus slope, rate and iteration count.
    pub fn new(talus: f32, rate: f32, iterations: u32) -> Self {
        ThermalErosion {
            talus,
            rate,
            iterations,
        }
    }

    /// Runs the erosion. Mass is conserved: every iteration moves height, never removes it.
    /// Each iteration reads the previous one's heights only, so the result does not depend on
    /// traversal order.
    pub fn apply(&self, map: &mut Heightmap) -> Result<(), TerrainError> {
        check(
            "talus",
            f64::from(self.talus),
            self.talus >= 0.0,
            "finite and not negative",
        )?;
        check(
            "rate",
            f64::from(self.rate),
            self.rate > 0.0 && self.rate <= 0.5,
            "in (0, 0.5]",
        )?;
        let n = map.size();
        let threshold = self.talus * map.spacing();
        let mut delta = vec![0.0f32; n * n];
        for _ in 0..self.iterations {
            delta.iter_mut().for_each(|d| *d = 0.0);
            let h = map.heights();
            for z in 0..n {
                for x in 0..n {
                    let here = h[z * n + x];
                    let mut lower = [(0usize, 0.0f32); 4];
                    let mut count = 0;
                    let (mut max_drop, mut total) = (0.0f32, 0.0f32);
                    let neighbours = [
                        (x.wrapping_sub(1), z),
                        (x + 1, z),
                        (x, z.wrapping_sub(1)),
                        (x, z + 1),
                    ];
                    for (nx, nz) in neighbours {
                        if nx >= n || nz >= n {
                            continue;
                        }
                        let d = here - h[nz * n + nx];
                        if d > threshold {
                            lower[count] = (nz * n + nx, d);
                            count += 1;
                            max_drop = max_drop.max(d);
                            total += d;
                        }
                    }
                    if count == 0 {
                        continue;
                    }
                    let moved = self.rate * (max_drop - threshold);
                    delta[z * n + x] -= moved;
                    for &(i, d) in &lower[..count] {
                        delta[i] += moved * d / total;
                    }
                }
            }
            for (h, d) in map.heights_mut().iter_mut().zip(&delta) {
                *h += d;
            }
        }
        Ok(())
    }
}

/// Hydraulic erosion by simulated rain droplets that pick up sediment running downhill and
/// drop it where they slow down. Distances are in samples.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct HydraulicErosion {
    /// Number of droplets. About one per 4 samples gives visible gullies. Default: 50,000.
    pub droplets: u32,
    /// Seed of the droplets' starting points. Default: 0.
    pub seed: u64,
    /// How much a droplet keeps its direction (0: follows the slope, 1: never turns).
    /// Default: 0.05.
    pub inertia: f32,
    /// Sediment capacity per unit of slope, speed and water. Default: 4.
    pub capacity: f32,
    /// Slope assumed on flat ground when computing capacity. Default: 0.01.
    pub min_slope: f32,
    /// Fraction of free capacity taken from the ground per step. Default: 0.3.
    pub erosion: f32,
    /// Fraction of excess sediment dropped per step. Default: 0.3.
    pub deposition: f32,
    /// Fraction of water that evaporates per step. Default: 0.02.
    pub evaporation: f32,
    /// Acceleration down slopes. Default: 4.
    pub gravity: f32,
    /// Most steps a droplet lives. Default: 30.
    pub lifetime: u32,
}

impl Default for HydraulicErosion {
    fn default() -> Self {
        HydraulicErosion {
            droplets: 50_000,
            seed: 0,
            inertia: 0.05,
            capacity: 4.0,
            min_slope: 0.01,
            erosion: 0.3,
            deposition: 0.3,
            evaporation: 0.02,
            gravity: 4.0,
            lifetime: 30,
        }
    }
}

impl HydraulicErosion {
    /// Sets [`HydraulicErosion::droplets`].
    #[must_use]
    pub fn with_droplets(mut self, droplets: u32) -> Self {
        self.droplets = droplets;
        self
    }

    /// Sets [`HydraulicErosion::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`HydraulicErosion::inertia`].
    #[must_use]
    pub fn with_inertia(mut self, inertia: f32) -> Self {
        self.inertia = inertia;
        self
    }

    /// Sets [`HydraulicErosion::capacity`].
    #[must_use]
    pub fn with_capacity(mut self, capacity: f32) -> Self {
        self.capacity = capacity;
        self
    }

    /// Sets [`HydraulicErosion::min_slope`].
    #[must_use]
    pub fn with_min_slope(mut self, min_slope: f32) -> Self {
        self.min_slope = min_slope;
        self
    }

    /// Sets [`HydraulicErosion::erosion`].
    #[must_use]
    pub fn with_erosion(mut self, erosion: f32) -> Self {
        self.erosion = erosion;
        self
    }

    /// Sets [`HydraulicErosion::deposition`].
    #[must_use]
    pub fn with_deposition(mut self, deposition: f32) -> Self {
        self.deposition = deposition;
        self
    }

    /// Sets [`HydraulicErosion::evaporation`].
    #[must_use]
    pub fn with_evaporation(mut self, evaporation: f32) -> Self {
        self.evaporation = evaporation;
        self
    }

    /// Sets [`HydraulicErosion::gravity`].
    #[must_use]
    pub fn with_gravity(mut self, gravity: f32) -> Self {
        self.gravity = gravity;
        self
    }

    /// Sets [`HydraulicErosion::lifetime`].
    #[must_use]
    pub fn with_lifetime(mut self, lifetime: u32) -> Self {
        self.lifetime = lifetime;
        self
    }
}

impl HydraulicErosion {
    /// The defaults with `droplets` droplets from `seed`.
    pub fn new(droplets: u32, seed: u64) -> Self {
        HydraulicErosion {
            droplets,
            seed,
            ..HydraulicErosion::default()
        }
    }

    /// Runs the droplets one after the other (deterministic for a seed).
    pub fn apply(&self, map: &mut Heightmap) -> Result<(), TerrainError> {
        for (name, v) in [
            ("inertia", self.inertia),
            ("erosion", self.erosion),
            ("deposition", self.deposition),
            ("evaporation", self.evaporation),
        ] {
            check(name, f64::from(v), (0.0..=1.0).contains(&v), "in [0, 1]")?;
        }
        for (name, v) in [
            ("capacity", self.capacity),
            ("min_slope", self.min_slope),
            ("gravity", self.gravity),
        ] {
            check(name, f64::from(v), v >= 0.0, "finite and not negative")?;
        }
        let n = map.size();
        let limit = (n - 1) as f32;
        let heights = map.heights_mut();
        for d in 0..self.droplets {
            let mut pos = Vec2::new(
                unit(self.seed, 2 * u64::from(d)),
                unit(self.seed, 2 * u64::from(d) + 1),
            ) * limit;
            let (mut dir, mut speed, mut water, mut sediment) =
                (Vec2::ZERO, 1.0f32, 1.0f32, 0.0f32);
            for _ in 0..self.lifetime {
                let (h, grad) = height_and_gradient(heights, n, pos);
                dir = dir * self.inertia - grad * (1.0 - self.inertia);
                let Some(step) = dir.try_normalize() else {
                    break;
                };
                dir = step;
                let next = pos + dir;
                if next.x < 0.0 || next.y < 0.0 || next.x >= limit || next.y >= limit {
                    break;
                }
                let dh = height_and_gradient(heights, n, next).0 - h;
                let capacity = (-dh).max(self.min_slope) * speed * water * self.capacity;
                if sediment > capacity || dh > 0.0 {
                    let drop = if dh > 0.0 {
                        dh.min(sediment)
                    } else {
                        (sediment - capacity) * self.deposition
                    };
                    sediment -= drop;
                    spread(heights, n, pos, drop);
                } else {
                    let take = ((capacity - sediment) * self.erosion).min(-dh);
                    spread(heights, n, pos, -take);
                    sediment += take;
                }
                speed = (speed * speed - dh * self.gravity).max(0.0).sqrt();
                water *= 1.0 - self.evaporation;
                pos = next;
            }
        }
        Ok(())
    }
}

fn height_and_gradient(h: &[f32], n: usize, p: Vec2) -> (f32, Vec2) {
    let (x, z) = (p.x as usize, p.y as usize);
    let (u, v) = (p.x - x as f32, p.y - z as f32);
    let i = z * n + x;
    let (a, b, c, d) = (h[i], h[i + 1], h[i + n], h[i + n + 1]);
    let grad = Vec2::new(
        (b - a) * (1.0 - v) + (d - c) * v,
        (c - a) * (1.0 - u) + (d - b) * u,
    );
    let height = a * (1.0 - u) * (1.0 - v) + b * u * (1.0 - v) + c * (1.0 - u) * v + d * u * v;
    (height, grad)
}

/// Adds `amount` to the four samples around `p`, bilinearly weighted.
fn spread(h: &mut [f32], n: usize, p: Vec2, amount: f32) {
    let (x, z) = (p.x as usize, p.y as usize);
    let (u, v) = (p.x - x as f32, p.y - z as f32);
    let i = z * n + x;
    h[i] += amount * (1.0 - u) * (1.0 - v);
    h[i + 1] += amount * u * (1.0 - v);
    h[i + n] += amount * (1.0 - u) * v;
    h[i + n + 1] += amount * u * v;
}
