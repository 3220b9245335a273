//! The canopy's light: leaf area deposited by every crown into columns of a grid, layer by
//! layer, and Beer's law over the leaf area above a point.
//!
//! Why a grid of leaf-area columns and not the growth crate's voxel light: that traces rays
//! from every bud through voxels a few centimetres across, seconds for a stand of 25 trees;
//! a 1 km forest of 10^5 trees over 300 years needs a tree's light in well under a
//! microsecond. A column of 4 m x 4 m holding leaf area per metre of height gives each tree
//! the leaf area above its top (and the ground its whole column) in one lookup, at the cost
//! of light coming straight down only: what gap models (JABOWA, SORTIE's simplest form) do.

/// Side of a column, metres.
pub const CELL: f32 = 4.0;
/// Height layers of a column, a metre each: trees taller than this are counted in the top
/// layer.
pub const LAYERS: usize = 48;
/// Beer's law's extinction coefficient for leaf area.
pub const EXTINCTION: f32 = 0.5;
/// Leaf area is summed in fixed point, this many units to 1, so that a column's sum is the
/// same whatever order its crowns are added in: a tile and a larger run that hold the same
/// trees see the same light, to the bit.
const UNIT: f32 = 65_536.0;

/// Leaf area per layer over a grid of columns.
#[derive(Debug, Clone)]
pub(crate) struct LightGrid {
    origin: [f32; 2],
    width: usize,
    depth: usize,
    /// Per column, leaf area index in each layer in [`UNIT`]s; after
    /// [`LightGrid::accumulate`], the leaf area at and above each layer.
    layers: Vec<u32>,
}

impl LightGrid {
    /// A grid of columns covering `min` to `max`, on the global lattice of [`CELL`] (so runs
    /// over overlapping areas share their columns).
    pub(crate) fn new(min: [f32; 2], max: [f32; 2]) -> Self {
        let origin = [
            (min[0] / CELL).floor() * CELL,
            (min[1] / CELL).floor() * CELL,
        ];
        let width = (((max[0] - origin[0]) / CELL).ceil() as usize).max(1);
        let depth = (((max[1] - origin[1]) / CELL).ceil() as usize).max(1);
        LightGrid {
            origin,
            width,
            depth,
            layers: vec![0; width * depth * LAYERS],
        }
    }

    /// Empties every column.
    pub(crate) fn clear(&mut self) {
        self.layers.fill(0);
    }

    fn column(&self, x: f32, z: f32) -> Option<usize> {
        let i = ((x - self.origin[0]) / CELL).floor();
        let j = ((z - self.origin[1]) / CELL).floor();
        if i < 0.0 || j < 0.0 || i as usize >= self.width || j as usize >= self.depth {
            return None;
        }
        Some(j as usize * self.width + i as usize)
    }

    /// Adds a crown: leaf area index `lai` over a disc of `radius` at (x, z), spread evenly
    /// over the layers from `base` to `top`. The leaf area is kept whatever the crown's size:
    /// a crown smaller than a column puts its share of the column's area in its own column.
    /// Returns what it put in each layer of its own column (in fixed-point units), so that
    /// [`LightGrid::light_in_crown`] can leave the tree's own leaves out.
    pub(crate) fn deposit(
        &mut self,
        x: f32,
        z: f32,
        radius: f32,
        base: f32,
        top: f32,
        lai: f32,
    ) -> u32 {
        let area = std::f32::consts::PI * radius * radius;
        let (lo, hi) = (layer(base), layer(top));
        let per_layer = lai / (hi - lo + 1) as f32;
        let reach = radius - 0.5 * CELL;
        let own = self.column(x, z);
        if reach <= 0.0 {
            return match own {
                Some(c) => self.add(c, lo, hi, area / (CELL * CELL) * per_layer),
                None => 0,
            };
        }
        // Columns whose centres lie in the disc, each taking an equal part of its area.
        let span = (radius / CELL).ceil() as i64;
        let (ci, cj) = (
            ((x - self.origin[0]) / CELL).floor() as i64,
            ((z - self.origin[1]) / CELL).floor() as i64,
        );
        let mut inside = 0usize;
        let mut cells = [0usize; 128];
        for dj in -span..=span {
            for di in -span..=span {
                let (i, j) = (ci + di, cj + dj);
                if i < 0 || j < 0 || i as usize >= self.width || j as usize >= self.depth {
                    continue;
                }
                let cx = self.origin[0] + (i as f32 + 0.5) * CELL - x;
                let cz = self.origin[1] + (j as f32 + 0.5) * CELL - z;
                if cx * cx + cz * cz <= radius * radius && inside < cells.len() {
                    cells[inside] = j as usize * self.width + i as usize;
                    inside += 1;
                }
            }
        }
        if inside == 0
            && let Some(c) = own
        {
            cells[0] = c;
            inside = 1;
        }
        let share = area / (inside as f32 * CELL * CELL) * per_layer;
        let mut mine = 0;
        for &c in &cells[..inside] {
            let units = self.add(c, lo, hi, share);
            if Some(c) == own {
                mine = units;
            }
        }
        mine
    }

    /// Adds `amount` of leaf area to each layer from `lo` to `hi` of `column`; returns it in
    /// units.
    fn add(&mut self, column: usize, lo: usize, hi: usize, amount: f32) -> u32 {
        let units = (amount * UNIT).round() as u32;
        let start = column * LAYERS;
        for l in &mut self.layers[start + lo..=start + hi] {
            *l = l.saturating_add(units);
        }
        units
    }

    /// Turns each column's layers into the leaf area at and above each layer.
    pub(crate) fn accumulate(&mut self) {
        for column in self.layers.chunks_exact_mut(LAYERS) {
            let mut above = 0u32;
            for l in column.iter_mut().rev() {
                above = above.saturating_add(*l);
                *l = above;
            }
        }
    }

    /// The leaf area index at and above layer `l` of column `c`.
    fn above(&self, c: usize, l: usize) -> f32 {
        self.layers[c * LAYERS + l] as f32 / UNIT
    }

    /// The share of the open sky's light reaching height `y` at (x, z): Beer's law over the
    /// leaf area above (the layers wholly above `y`; a tree's own crown is below its top).
    pub(crate) fn light(&self, x: f32, z: f32, y: f32) -> f32 {
        let Some(c) = self.column(x, z) else {
            return 1.0;
        };
        let above = layer(y) + 1;
        let lai = if above >= LAYERS {
            0.0
        } else {
            self.above(c, above)
        };
        (-EXTINCTION * lai).exp()
    }

    /// The light a crown topping out at `top` gets at its centre, height `y`, at (x, z): Beer's
    /// law over the leaf area above `y` but the tree's own (`own` units a layer, what
    /// [`LightGrid::deposit`] returned). So trees of one height whose crowns overlap shade
    /// each other, as a closed even-aged stand's do, while a tree alone is in full light.
    pub(crate) fn light_in_crown(&self, x: f32, z: f32, y: f32, top: f32, own: u32) -> f32 {
        let Some(c) = self.column(x, z) else {
            return 1.0;
        };
        let (from, to) = (layer(y) + 1, layer(top));
        if from >= LAYERS {
            return 1.0;
        }
        let mine = own.saturating_mul((to + 1).saturating_sub(from) as u32);
        let lai = self.layers[c * LAYERS + from].saturating_sub(mine) as f32 / UNIT;
        (-EXTINCTION * lai).exp()
    }

    /// The light reaching the ground at (x, z).
    pub(crate) fn ground(&self, x: f32, z: f32) -> f32 {
        let Some(c) = self.column(x, z) else {
            return 1.0;
        };
        (-EXTINCTION * self.above(c, 0)).exp()
    }

    /// The share of the columns centred in `min` to `max` whose leaf area above `height`
    /// metres is at least 1: the canopy cover at that height.
    pub(crate) fn cover_within(&self, height: f32, min: [f32; 2], max: [f32; 2]) -> f32 {
        let l = layer(height);
        let (mut covered, mut all) = (0usize, 0usize);
        for (c, column) in self.layers.chunks_exact(LAYERS).enumerate() {
            let x = self.origin[0] + ((c % self.width) as f32 + 0.5) * CELL;
            let z = self.origin[1] + ((c / self.width) as f32 + 0.5) * CELL;
            if x >= min[0] && x < max[0] && z >= min[1] && z < max[1] {
                all += 1;
                covered += usize::from(column[l] as f32 >= UNIT);
            }
        }
        if all == 0 {
            0.0
        } else {
            covered as f32 / all as f32
        }
    }
}

/// The layer holding height `y`.
fn layer(y: f32) -> usize {
    (y.max(0.0) as usize).min(LAYERS - 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crown_shades_below_it_not_above_and_keeps_its_leaf_area() {
        let mut grid = LightGrid::new([0.0, 0.0], [40.0, 40.0]);
        let own = grid.deposit(20.0, 20.0, 6.0, 8.0, 20.0, 4.0);
        let total = grid.layers.iter().map(|&l| l as f32 / UNIT).sum::<f32>();
        let expected = 4.0 * std::f32::consts::PI * 36.0 / (CELL * CELL);
        assert!(
            (total - expected).abs() < 1e-3 * expected,
            "{total} vs {expected}"
        );
        grid.accumulate();
        assert_eq!(grid.light(20.0, 20.0, 25.0), 1.0, "above the crown");
        assert!(
            grid.ground(20.0, 20.0) < 0.3,
            "under it: {}",
            grid.ground(20.0, 20.0)
        );
        assert!(grid.light(20.0, 20.0, 14.0) > grid.ground(20.0, 20.0));
        assert_eq!(grid.ground(2.0, 2.0), 1.0, "beside it");
        // The tree itself, at its crown's centre: its own leaves left out.
        assert_eq!(grid.light_in_crown(20.0, 20.0, 14.0, 20.0, own), 1.0);
        assert!(grid.cover_within(10.0, [0.0, 0.0], [40.0, 40.0]) > 0.0);
        assert_eq!(grid.cover_within(30.0, [0.0, 0.0], [40.0, 40.0]), 0.0);
    }

    #[test]
    fn a_small_crown_puts_its_share_in_its_own_column() {
        let mut grid = LightGrid::new([0.0, 0.0], [8.0, 8.0]);
        grid.deposit(1.0, 1.0, 0.5, 0.0, 1.0, 4.0);
        grid.accumulate();
        let lai = -grid.ground(1.0, 1.0).ln() / EXTINCTION;
        let expected = 4.0 * std::f32::consts::PI * 0.25 / 16.0;
        assert!((lai - expected).abs() < 1e-4);
        assert_eq!(grid.ground(5.0, 5.0), 1.0);
    }
}
