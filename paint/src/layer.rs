//! The paint layer: how densely each species grows, cell by cell, over the terrain.

use glam::Vec2;
use sylva_base::hash::unit_f32 as unit;
use sylva_base::range::check;
use sylva_forest::{Composition, PatchDensity, Rect};

use crate::error::PaintError;

/// Most values (cells times species) a layer may hold: 128 MB of 16-bit values.
pub const MAX_PAINT_VALUES: usize = 1 << 26;

/// Full density of one species in a cell.
pub const FULL: u16 = u16::MAX;

/// A density and species mask over a rectangle of the terrain, edited by brushes.
///
/// The rectangle is cut into `width x depth` square-ish cells (row-major: rows run along +z,
/// the cell at index 0 has the rectangle's lower corner). Each cell holds one 16-bit value
/// per species: that species' density there, `0` (none) to [`FULL`]. Where a layer is in
/// use, a tree the density model proposes in a cell is kept with probability equal to the
/// cell's total density (at most 1) and takes species `s` with probability `value_s /
/// total`; so an empty layer grows nothing, and painted trees still keep the density model's
/// spacing and seedling rules. Spots beyond the layer are as unpainted (they matter only to
/// the trees near its edge, through spacing).
///
/// ```
/// use sylva_forest::Rect;
/// use sylva_paint::PaintLayer;
/// use sylva_terrain::glam::Vec2;
///
/// let bounds = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
/// let mut layer = PaintLayer::new(bounds, 2.0, 2)?;
/// assert_eq!((layer.width(), layer.depth()), (50, 50));
/// let cell = layer.cell_at(Vec2::new(11.0, 3.0)).unwrap();
/// layer.set(cell, &[0, sylva_paint::FULL])?;
/// assert_eq!(layer.density(Vec2::new(11.0, 3.0)), 1.0);
/// assert_eq!(layer.density(Vec2::new(30.0, 30.0)), 0.0);
/// # Ok::<(), sylva_paint::PaintError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct PaintLayer {
    bounds: Rect,
    width: usize,
    depth: usize,
    species: usize,
    /// `species` values per cell, cell by cell.
    values: Vec<u16>,
}

impl PaintLayer {
    /// An empty layer (no trees anywhere) over `bounds`, in cells of about `cell` metres, for
    /// `species` species. Errors when the rectangle is empty, the cell size is not positive,
    /// or the layer would hold more than [`MAX_PAINT_VALUES`] values.
    pub fn new(bounds: Rect, cell: f32, species: usize) -> Result<Self, PaintError> {
        check(
            "paint cell size",
            cell.into(),
            cell > 0.0,
            "a positive number of metres",
        )?;
        let size = bounds.max - bounds.min;
        let width = (f64::from(size.x) / f64::from(cell)).ceil().max(1.0);
        let depth = (f64::from(size.y) / f64::from(cell)).ceil().max(1.0);
        Self::with_grid(bounds, width, depth, species)
    }

    /// An empty layer of exactly `width x depth` cells over `bounds`.
    pub fn with_cells(
        bounds: Rect,
        width: usize,
        depth: usize,
        species: usize,
    ) -> Result<Self, PaintError> {
        Self::with_grid(bounds, width as f64, depth as f64, species)
    }

    fn with_grid(bounds: Rect, width: f64, depth: f64, species: usize) -> Result<Self, PaintError> {
        if bounds.is_empty() {
            return Err(PaintError::NoArea {
                min: bounds.min,
                max: bounds.max,
            });
        }
        if species == 0 {
            return Err(PaintError::NoSpecies);
        }
        if width < 1.0 || depth < 1.0 || width * depth * species as f64 > MAX_PAINT_VALUES as f64 {
            return Err(PaintError::TooLarge {
                width,
                depth,
                species,
                limit: MAX_PAINT_VALUES,
            });
        }
        let (width, depth) = (width as usize, depth as usize);
        Ok(PaintLayer {
            bounds,
            width,
            depth,
            species,
            values: vec![0; width * depth * species],
        })
    }

    /// A layer that grows the forest the density model would grow without one: every cell
    /// at full density, species mixed by `weights` (as [`Species::weight`](sylva_forest::Species::weight)).
    pub fn filled(bounds: Rect, cell: f32, weights: &[f32]) -> Result<Self, PaintError> {
        let mut layer = Self::new(bounds, cell, weights.len())?;
        let total: f32 = weights.iter().map(|w| w.max(0.0)).sum();
        if !(total.is_finite() && total > 0.0) {
            return Err(PaintError::NoWeight);
        }
        let mix: Vec<u16> = quantize_mix(weights.iter().map(|w| w.max(0.0) / total));
        for cell in layer.values.chunks_exact_mut(weights.len()) {
            cell.copy_from_slice(&mix);
        }
        Ok(layer)
    }

    /// An error unless the layer has one channel per species of a forest of `species`.
    pub fn check_species(&self, species: usize) -> Result<(), PaintError> {
        if self.species != species {
            return Err(PaintError::SpeciesCount {
                layer: self.species,
                forest: species,
            });
        }
        Ok(())
    }

    /// The rectangle covered.
    pub fn bounds(&self) -> Rect {
        self.bounds
    }

    /// Cells along x.
    pub fn width(&self) -> usize {
        self.width
    }

    /// Cells along z.
    pub fn depth(&self) -> usize {
        self.depth
    }

    /// Species (values per cell).
    pub fn species(&self) -> usize {
        self.species
    }

    /// The size of one cell, (x, z) metres.
    pub fn cell_size(&self) -> Vec2 {
        let b = self.bounds();
        (b.max - b.min) / Vec2::new(self.width as f32, self.depth as f32)
    }

    /// The index of the cell holding `p`, or `None` outside the layer.
    pub fn cell_at(&self, p: Vec2) -> Option<usize> {
        let b = self.bounds();
        if !b.contains(p) {
            return None;
        }
        let f = (p - b.min) / (b.max - b.min);
        let x = ((f.x * self.width as f32) as usize).min(self.width - 1);
        let z = ((f.y * self.depth as f32) as usize).min(self.depth - 1);
        Some(z * self.width + x)
    }

    /// The centre of cell `index` (x, z).
    pub fn cell_centre(&self, index: usize) -> Vec2 {
        let b = self.bounds();
        let (x, z) = (index % self.width, index / self.width);
        b.min + (Vec2::new(x as f32, z as f32) + 0.5) * self.cell_size()
    }

    /// The rectangle of cell `index`.
    pub fn cell_rect(&self, index: usize) -> Rect {
        let c = self.cell_centre(index);
        let half = 0.5 * self.cell_size();
        Rect::new(c - half, c + half)
    }

    /// The species values of cell `index`.
    pub fn get(&self, index: usize) -> &[u16] {
        &self.values[index * self.species..(index + 1) * self.species]
    }

    /// Sets the species values of cell `index`; an error when the index or the number of
    /// values is wrong.
    pub fn set(&mut self, index: usize, values: &[u16]) -> Result<(), PaintError> {
        if index >= self.width * self.depth || values.len() != self.species {
            return Err(PaintError::BadCell {
                index,
                values: values.len(),
                cells: self.width * self.depth,
                species: self.species,
            });
        }
        self.values[index * self.species..(index + 1) * self.species].copy_from_slice(values);
        Ok(())
    }

    /// The total density at `p`, 0 to 1 (0 outside the layer).
    pub fn density(&self, p: Vec2) -> f32 {
        self.cell_at(p).map_or(0.0, |c| {
            (self.get(c).iter().map(|&v| f32::from(v)).sum::<f32>() / f32::from(FULL)).min(1.0)
        })
    }

    /// One species' values, row-major (for saving it as a mask image).
    pub fn channel(&self, species: usize) -> Vec<u16> {
        self.values
            .iter()
            .skip(species)
            .step_by(self.species)
            .copied()
            .collect()
    }

    /// Replaces one species' values, row-major.
    pub fn set_channel(&mut self, species: usize, values: &[u16]) -> Result<(), PaintError> {
        if species >= self.species || values.len() != self.width * self.depth {
            return Err(PaintError::BadChannel {
                channel: species,
                values: values.len(),
                species: self.species,
                cells: self.width * self.depth,
            });
        }
        for (cell, &v) in self.values.chunks_exact_mut(self.species).zip(values) {
            cell[species] = v;
        }
        Ok(())
    }

    /// The indices of the cells whose centres lie in `rect`, row by row.
    pub(crate) fn cells_in(&self, rect: Rect) -> impl Iterator<Item = usize> + '_ {
        let b = self.bounds();
        let size = self.cell_size();
        let range = |lo: f32, hi: f32, origin: f32, step: f32, n: usize| {
            let first = ((lo - origin) / step - 0.5).ceil().max(0.0) as usize;
            let last = ((hi - origin) / step - 0.5).floor();
            let end = if last < 0.0 {
                0
            } else {
                (last as usize + 1).min(n)
            };
            first..end.max(first)
        };
        let xs = range(rect.min.x, rect.max.x, b.min.x, size.x, self.width);
        let zs = range(rect.min.y, rect.max.y, b.min.y, size.y, self.depth);
        zs.flat_map(move |z| xs.clone().map(move |x| z * self.width + x))
    }
}

/// Fractions (summing to 1) as 16-bit values summing to exactly [`FULL`].
pub(crate) fn quantize_mix(fractions: impl Iterator<Item = f32>) -> Vec<u16> {
    let fractions: Vec<f32> = fractions.collect();
    let mut out: Vec<u16> = fractions
        .iter()
        .map(|f| (f.clamp(0.0, 1.0) * f32::from(FULL)).floor() as u16)
        .collect();
    // Rounding down leaves a remainder; it goes to the largest share, so the cell is full.
    let sum: u32 = out.iter().map(|&v| u32::from(v)).sum();
    if let Some(largest) = (0..out.len()).max_by(|&a, &b| fractions[a].total_cmp(&fractions[b]))
        && sum > 0
    {
        out[largest] = out[largest].saturating_add((u32::from(FULL).saturating_sub(sum)) as u16);
    }
    out
}

impl Composition for PaintLayer {
    fn species(&self) -> Option<usize> {
        Some(self.species)
    }

    fn choose(&self, density: &PatchDensity, p: Vec2, draw: u64) -> Option<usize> {
        // Beyond the layer (past the terrain's edge, where no tree is kept) spots are as
        // unpainted, so trees near the edge see the neighbours a generated forest's see.
        let Some(cell) = self.cell_at(p) else {
            return Some(density.pick_species(draw));
        };
        let values = self.get(cell);
        let total: u64 = values.iter().map(|&v| u64::from(v)).sum();
        // Kept with probability total / FULL (always at FULL or more).
        if total == 0 || (total < u64::from(FULL) && draw & 0xffff >= total) {
            return None;
        }
        // The species by its share of the cell, from the draw's top bits as the unpainted
        // model draws it (so a full layer in the species' proportions grows the same forest,
        // up to the shares' rounding); presence used the low bits, independent of these.
        let mut pick = unit(draw) * total as f32;
        for (s, &v) in values.iter().enumerate() {
            if pick < f32::from(v) {
                return Some(s);
            }
            pick -= f32::from(v);
        }
        values.iter().rposition(|&v| v > 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva_base::hash::mix;

    fn layer() -> PaintLayer {
        PaintLayer::new(Rect::new(Vec2::ZERO, Vec2::new(10.0, 6.0)), 1.0, 2).unwrap()
    }

    #[test]
    fn cells_cover_the_rectangle_row_by_row() {
        let l = layer();
        assert_eq!((l.width(), l.depth()), (10, 6));
        assert_eq!(l.cell_at(Vec2::new(0.5, 0.5)), Some(0));
        assert_eq!(l.cell_at(Vec2::new(3.5, 2.5)), Some(23));
        assert_eq!(l.cell_centre(23), Vec2::new(3.5, 2.5));
        assert_eq!(l.cell_at(Vec2::new(10.0, 1.0)), None);
        assert_eq!(l.cell_at(Vec2::new(-0.1, 1.0)), None);
        let inside: Vec<usize> = l
            .cells_in(Rect::new(Vec2::new(1.0, 1.0), Vec2::new(3.0, 2.0)))
            .collect();
        assert_eq!(inside, vec![11, 12]);
        assert_eq!(
            l.cells_in(Rect::new(Vec2::splat(-5.0), Vec2::splat(-1.0)))
                .count(),
            0
        );
        assert_eq!(
            l.cells_in(Rect::new(Vec2::splat(-5.0), Vec2::splat(50.0)))
                .count(),
            60
        );
    }

    #[test]
    fn bad_layers_are_refused() {
        let r = Rect::new(Vec2::ZERO, Vec2::splat(10.0));
        assert!(PaintLayer::new(r, 0.0, 1).is_err());
        assert!(PaintLayer::new(r, f32::NAN, 1).is_err());
        assert!(PaintLayer::new(r, 1.0, 0).is_err());
        assert!(PaintLayer::new(Rect::new(Vec2::ZERO, Vec2::ZERO), 1.0, 1).is_err());
        assert!(PaintLayer::new(r, 1e-4, 4).is_err());
        let mut l = layer();
        assert!(l.set(60, &[1, 2]).is_err());
        assert!(l.set(0, &[1]).is_err());
        assert!(l.set_channel(2, &[0; 60]).is_err());
        assert!(l.set_channel(0, &[0; 59]).is_err());
    }

    #[test]
    fn a_filled_layer_is_full_everywhere_in_the_weights_mix() {
        let l =
            PaintLayer::filled(Rect::new(Vec2::ZERO, Vec2::splat(4.0)), 1.0, &[3.0, 1.0]).unwrap();
        assert_eq!(
            l.get(5).iter().map(|&v| u32::from(v)).sum::<u32>(),
            u32::from(FULL)
        );
        assert_eq!(l.get(5)[1], FULL / 4);
        assert_eq!(l.density(Vec2::new(1.0, 2.0)), 1.0);
    }

    #[test]
    fn choices_follow_the_cell_mix() {
        let mut l = layer();
        let density = PatchDensity::new(Vec::new());
        let p = Vec2::new(2.5, 2.5);
        let cell = l.cell_at(p).unwrap();
        assert_eq!(l.choose(&density, p, 12345), None);
        l.set(cell, &[FULL / 4, FULL / 4]).unwrap();
        let draws: Vec<Option<usize>> = (0..20_000u64)
            .map(|k| l.choose(&density, p, mix(k)))
            .collect();
        let kept = draws.iter().filter(|d| d.is_some()).count() as f32 / 20_000.0;
        let first = draws.iter().filter(|d| **d == Some(0)).count() as f32 / 20_000.0;
        assert!((kept - 0.5).abs() < 0.02, "{kept}");
        assert!((first - 0.25).abs() < 0.02, "{first}");
        l.set(cell, &[0, FULL]).unwrap();
        assert!((0..1000u64).all(|k| l.choose(&density, p, mix(k)) == Some(1)));
    }
}
