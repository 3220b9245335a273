//! Midpoint displacement by the diamond-square algorithm.

use glam::Vec2;
use rayon::prelude::*;

use crate::error::{TerrainError, check};
use crate::hash::NoiseRow;
use crate::heightmap::{Heightmap, checked_len, levels_of, repeat_first_row_and_column};

/// Fewest rows a task of a pass takes (a row of a late pass is thousands of samples).
const ROWS_PER_TASK: usize = 8;

/// Settings for [`DiamondSquare::generate`].
///
/// Every sample's random displacement is keyed by the seed and the sample's global grid
/// coordinates (`tile * (size - 1) + local`), and samples on a tile's border are interpolated
/// from the border alone. So neighbouring tiles generated separately share their border
/// samples exactly: a world can be generated tile by tile with no seams. Structure larger than
/// one tile comes only from the corner heights.
///
/// ```
/// use sylva_terrain::DiamondSquare;
/// let map = DiamondSquare::new(129).with_seed(7).with_roughness(0.8).generate().unwrap();
/// assert_eq!(map.size(), 129);
/// assert_eq!(map, DiamondSquare::new(129).with_seed(7).with_roughness(0.8).generate().unwrap());
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct DiamondSquare {
    /// Samples per side, 2^n + 1. No default: the `size` given to [`DiamondSquare::new`].
    pub size: usize,
    /// Horizontal distance between samples. Default: 1.
    pub spacing: f32,
    /// Roughness H in [0, 1]: displacements shrink by 2^-H per level, so the mean squared
    /// height difference at lag d grows as d^(2H). Low H is rough, high H smooth. Default: 0.8.
    pub roughness: f32,
    /// Displacement scale of the first level (and of random corners). Default: `size / 4`.
    pub amplitude: f32,
    /// Seed of the displacements. Default: 0.
    pub seed: u64,
    /// Fixed corner heights (x0z0, x1z0, x0z1, x1z1), or `None` for random corners.
    /// Default: none (random corners).
    pub corners: Option<[f32; 4]>,
    /// Periodic mode: opposite edges are equal, so the map tiles with copies of itself.
    /// Default: false.
    pub wrap: bool,
    /// Which tile of the world this map is (in units of `size - 1` samples). Default: [0, 0].
    pub tile: [i64; 2],
}

impl DiamondSquare {
    /// Defaults: spacing 1, roughness 0.8, amplitude `size / 4` spacings, seed 0, random
    /// corners, no wrap, tile (0, 0).
    pub fn new(size: usize) -> Self {
        DiamondSquare {
            size,
            spacing: 1.0,
            roughness: 0.8,
            amplitude: size as f32 * 0.25,
            seed: 0,
            corners: None,
            wrap: false,
            tile: [0, 0],
        }
    }

    /// Sets [`DiamondSquare::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`DiamondSquare::roughness`].
    #[must_use]
    pub fn with_roughness(mut self, h: f32) -> Self {
        self.roughness = h;
        self
    }

    /// Sets [`DiamondSquare::amplitude`].
    #[must_use]
    pub fn with_amplitude(mut self, a: f32) -> Self {
        self.amplitude = a;
        self
    }

    /// Sets [`DiamondSquare::spacing`].
    #[must_use]
    pub fn with_spacing(mut self, s: f32) -> Self {
        self.spacing = s;
        self
    }

    /// Sets [`DiamondSquare::corners`].
    #[must_use]
    pub fn with_corners(mut self, corners: [f32; 4]) -> Self {
        self.corners = Some(corners);
        self
    }

    /// Sets [`DiamondSquare::wrap`].
    #[must_use]
    pub fn with_wrap(mut self, wrap: bool) -> Self {
        self.wrap = wrap;
        self
    }

    /// Sets [`DiamondSquare::tile`].
    #[must_use]
    pub fn with_tile(mut self, x: i64, z: i64) -> Self {
        self.tile = [x, z];
        self
    }

    fn validate(&self) -> Result<(), TerrainError> {
        levels_of(self.size)?;
        check(
            "spacing",
            f64::from(self.spacing),
            self.spacing > 0.0,
            "a positive distance",
        )?;
        check(
            "roughness",
            f64::from(self.roughness),
            (0.0..=1.0).contains(&self.roughness),
            "in [0, 1]",
        )?;
        check(
            "amplitude",
            f64::from(self.amplitude),
            self.amplitude >= 0.0,
            "finite and not negative",
        )?;
        if let Some(c) = self.corners {
            for v in c {
                check("corner height", f64::from(v), true, "finite")?;
            }
        }
        Ok(())
    }

    /// Generates the heightmap.
    pub fn generate(&self) -> Result<Heightmap, TerrainError> {
        self.validate()?;
        let n = self.size;
        let mut h = vec![0.0f32; checked_len(n)?];
        let cells = n - 1;
        let (gx0, gz0) = (
            self.tile[0].wrapping_mul(cells as i64),
            self.tile[1].wrapping_mul(cells as i64),
        );
        let wrap = self.wrap;
        // The noise along row `z`, by column. Wrapped maps key their noise by the periodic
        // coordinate.
        let noise_row = |z: usize| {
            let z = if wrap { z % cells } else { z };
            let row = NoiseRow::new(self.seed, gz0.wrapping_add(z as i64));
            move |x: usize| {
                let x = if wrap { x % cells } else { x };
                row.at(gx0.wrapping_add(x as i64))
            }
        };
        let noise = |x: usize, z: usize| noise_row(z)(x);
        let corner = |i: usize, x: usize, z: usize| match self.corners {
            Some(c) => c[i],
            None => self.amplitude * noise(x, z),
        };
        if self.wrap {
            let c = corner(0, 0, 0);
            h.iter_mut().for_each(|v| *v = c);
        } else {
            h[0] = corner(0, 0, 0);
            h[cells] = corner(1, cells, 0);
            h[cells * n] = corner(2, 0, cells);
            h[cells * n + cells] = corner(3, cells, cells);
        }
        let decay = 2f32.powf(-self.roughness);
        let half_decay = 2f32.powf(-0.5 * self.roughness);
        let mut scale = self.amplitude * decay;
        let mut step = cells;
        // A periodic map's last row and column are copies of its first, made at the end:
        // no pass reads them, so they are not worked out.
        let last = if wrap { cells - 1 } else { cells };
        while step > 1 {
            let half = step / 2;
            // Diamond step: centres of squares (rows at odd multiples of `half`), from the
            // corners around them in the rows `half` above and below.
            let odd = |z: usize| z % step == half;
            for_rows(&mut h, n, odd, |z, row, rows| {
                // A periodic map's row and column `cells` (not worked out) are its first.
                let wrapped = |i: usize| if wrap { i % cells } else { i };
                let (up, down) = (rows.get(z - half), rows.get(wrapped(z + half)));
                let right = |x: usize| wrapped(x + half);
                let noise = noise_row(z);
                for x in (half..cells).step_by(step) {
                    let avg =
                        0.25 * (up[x - half] + up[right(x)] + down[x - half] + down[right(x)]);
                    row[x] = avg + scale * noise(x);
                }
            });
            // Square step: edge midpoints. Their parents are closer by a factor of sqrt 2 than
            // the diamond step's, so their displacement is smaller by 2^(-H/2). The rows at
            // even multiples of `half` take their midpoints first, from the odd rows; then the
            // odd rows take theirs, from the even rows' samples the first part never writes:
            // every sample is the sum it always was.
            let square_scale = scale * half_decay;
            for parity in [0, half] {
                let picked = |z: usize| z % step == parity && z <= last;
                for_rows(&mut h, n, picked, |z, row, rows| {
                    let start = if parity == 0 { half } else { 0 };
                    let noise = noise_row(z);
                    if wrap {
                        let up = rows.get((z + cells - half) % cells);
                        let down = rows.get((z + half) % cells);
                        for x in (start..cells).step_by(step) {
                            let avg = 0.25
                                * (row[(x + cells - half) % cells]
                                    + row[(x + half) % cells]
                                    + up[x]
                                    + down[x]);
                            row[x] = avg + square_scale * noise(x);
                        }
                        return;
                    }
                    if z == 0 || z == cells {
                        // On a tile border only border samples count, so neighbours agree.
                        for x in (start..=cells).step_by(step) {
                            let avg = 0.5 * (row[x - half] + row[x + half]);
                            row[x] = avg + square_scale * noise(x);
                        }
                        return;
                    }
                    let (up, down) = (rows.get(z - half), rows.get(z + half));
                    // The map's left and right edges take the mean of the two samples above
                    // and below; every other sample the mean of its four neighbours. Each
                    // sample reads only samples this pass does not write, so the edges may
                    // go first.
                    let edge = |x: usize| 0.5 * (up[x] + down[x]) + square_scale * noise(x);
                    let mut first = start;
                    if first == 0 {
                        row[0] = edge(0);
                        first = step;
                    }
                    if cells % step == start % step {
                        row[cells] = edge(cells);
                    }
                    for x in (first..cells).step_by(step) {
                        let avg = 0.25 * (row[x - half] + row[x + half] + up[x] + down[x]);
                        row[x] = avg + square_scale * noise(x);
                    }
                });
            }
            scale *= decay;
            step = half;
        }
        if self.wrap {
            // Opposite edges are the same periodic samples.
            repeat_first_row_and_column(&mut h, n);
        }
        let origin = Vec2::new(gx0 as f32, gz0 as f32) * self.spacing;
        Ok(Heightmap::from_heights(n, self.spacing, h)?.with_origin(origin))
    }
}

/// The rows of a map not being written in a pass, by row number.
struct ReadRows<'a>(Vec<Option<&'a [f32]>>);

impl ReadRows<'_> {
    /// Row `z`, which the pass only reads.
    fn get(&self, z: usize) -> &[f32] {
        self.0[z].expect("a pass reads only rows it does not write")
    }
}

/// Runs `body` on every core for each row of the `n`-wide map `h` that `written` picks,
/// with its number and the rows the pass only reads.
fn for_rows(
    h: &mut [f32],
    n: usize,
    written: impl Fn(usize) -> bool,
    body: impl Fn(usize, &mut [f32], &ReadRows) + Sync,
) {
    let mut mine = Vec::new();
    let mut read = Vec::with_capacity(n);
    for (z, row) in h.chunks_mut(n).enumerate() {
        if written(z) {
            mine.push((z, row));
            read.push(None);
        } else {
            read.push(Some(&*row));
        }
    }
    let read = ReadRows(read);
    mine.into_par_iter()
        .with_min_len(ROWS_PER_TASK)
        .for_each(|(z, row)| body(z, row, &read));
}
