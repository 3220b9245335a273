//! The paint canvas: a paint layer edited stroke by stroke, with undo and redo.

use std::collections::HashMap;
use std::sync::Arc;

use glam::Vec2;
use sylva_forest::{ForestBuilder, Rect, distance_to_segment};

use crate::brush::Brush;
use crate::error::PaintError;
use crate::layer::PaintLayer;

/// Most strokes kept for undo.
pub const MAX_UNDO: usize = 256;

/// Most cell values kept for undo, over all strokes (the oldest strokes are forgotten first).
const MAX_UNDO_VALUES: usize = 1 << 25;

/// What an edit changed: how many cells, and the rectangle they span (the trees that may
/// differ are those within the density model's reach of it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Change {
    /// Cells whose values changed.
    pub cells: usize,
    /// The union of those cells' rectangles.
    pub region: Rect,
}

impl Change {
    fn union(a: Option<Change>, b: Option<Change>) -> Option<Change> {
        match (a, b) {
            (Some(a), Some(b)) => Some(Change {
                cells: a.cells + b.cells,
                region: Rect::new(
                    a.region.min.min(b.region.min),
                    a.region.max.max(b.region.max),
                ),
            }),
            (a, b) => a.or(b),
        }
    }
}

/// One stroke's edit: the cells it changed, their values before and after.
#[derive(Debug, Clone)]
struct Edit {
    cells: Vec<usize>,
    before: Vec<u16>,
    after: Vec<u16>,
    region: Rect,
}

/// The stroke being painted.
#[derive(Debug, Clone)]
struct ActiveStroke {
    brush: Brush,
    last: Option<Vec2>,
    /// Cell index to its slot in `cells`, `cover` and `before`.
    slots: HashMap<usize, usize>,
    cells: Vec<usize>,
    cover: Vec<f32>,
    before: Vec<u16>,
}

/// A paint layer and the strokes that edit it, with undo and redo.
///
/// ```
/// use sylva_forest::Rect;
/// use sylva_paint::{Brush, BrushAction, PaintCanvas, PaintLayer};
/// use sylva_terrain::glam::Vec2;
///
/// let layer = PaintLayer::new(Rect::new(Vec2::ZERO, Vec2::splat(100.0)), 1.0, 1)?;
/// let mut canvas = PaintCanvas::new(layer);
/// let brush = Brush::new(BrushAction::Add { species: 0 }, 10.0);
/// let change = canvas.stroke(brush, &[Vec2::new(20.0, 50.0), Vec2::new(80.0, 50.0)])?.unwrap();
/// assert!(change.cells > 1000);
/// assert_eq!(canvas.layer().density(Vec2::new(50.0, 50.0)), 1.0);
/// canvas.undo();
/// assert_eq!(canvas.layer().density(Vec2::new(50.0, 50.0)), 0.0);
/// canvas.redo();
/// assert_eq!(canvas.layer().density(Vec2::new(50.0, 50.0)), 1.0);
/// # Ok::<(), sylva_paint::PaintError>(())
/// ```
#[derive(Debug, Clone)]
pub struct PaintCanvas {
    layer: Arc<PaintLayer>,
    /// Per species: its name and whether it has trees to paint.
    species: Vec<(String, bool)>,
    stroke: Option<ActiveStroke>,
    undo: Vec<Edit>,
    redo: Vec<Edit>,
}

impl PaintCanvas {
    /// A canvas over `layer`; every species may be painted.
    pub fn new(layer: PaintLayer) -> Self {
        let species = (0..layer.species())
            .map(|s| (format!("species {s}"), true))
            .collect();
        PaintCanvas {
            layer: Arc::new(layer),
            species,
            stroke: None,
            undo: Vec::new(),
            redo: Vec::new(),
        }
    }

    /// A canvas for `builder`'s forest: the layer must have one channel per species, and
    /// only species with trees (a positive weight, so instance caches) may be painted.
    pub fn for_forest(builder: &ForestBuilder, layer: PaintLayer) -> Result<Self, PaintError> {
        let species = &builder.config().species;
        layer.check_species(species.len())?;
        let mut canvas = PaintCanvas::new(layer);
        canvas.species = species
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let loaded = builder
                    .variants()
                    .iter()
                    .any(|v| v.species == i && !v.seedling);
                (s.name.clone(), loaded)
            })
            .collect();
        Ok(canvas)
    }

    /// The layer as painted so far.
    pub fn layer(&self) -> &PaintLayer {
        &self.layer
    }

    /// The layer, shared (cheap to clone; later strokes copy it rather than change it).
    pub fn shared_layer(&self) -> Arc<PaintLayer> {
        Arc::clone(&self.layer)
    }

    /// Whether a stroke is under way (begun and not ended).
    pub fn stroking(&self) -> bool {
        self.stroke.is_some()
    }

    /// Strokes that can be undone and redone.
    pub fn history(&self) -> (usize, usize) {
        (self.undo.len(), self.redo.len())
    }

    /// Starts a stroke with `brush` (ending any stroke under way). An error, and nothing
    /// started, when the brush is out of range or paints a species that is not loaded.
    pub fn begin_stroke(&mut self, brush: Brush) -> Result<(), PaintError> {
        brush.validate()?;
        if let Some(s) = brush.species() {
            let names = || {
                self.species
                    .iter()
                    .filter(|s| s.1)
                    .map(|s| s.0.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            match self.species.get(s) {
                None => {
                    return Err(PaintError::UnknownSpecies {
                        species: s,
                        count: self.species.len(),
                        names: names(),
                    });
                }
                Some((name, false)) => {
                    return Err(PaintError::NotLoaded {
                        species: name.clone(),
                        loaded: names(),
                    });
                }
                Some(_) => {}
            }
        }
        self.end_stroke();
        self.stroke = Some(ActiveStroke {
            brush,
            last: None,
            slots: HashMap::new(),
            cells: Vec::new(),
            cover: Vec::new(),
            before: Vec::new(),
        });
        Ok(())
    }

    /// Paints from the stroke's last point to `p` (or a dab at `p`, first). Returns what
    /// changed, if anything; an error, and nothing changed, when no stroke is under way, `p`
    /// is not finite, or the brush there misses the layer.
    pub fn stroke_to(&mut self, p: Vec2) -> Result<Option<Change>, PaintError> {
        let Some(stroke) = &self.stroke else {
            return Err(PaintError::NoStroke);
        };
        let from = stroke.last.unwrap_or(p);
        self.check_reach(&stroke.brush, from, p)?;
        let Some(stroke) = &mut self.stroke else {
            return Ok(None);
        };
        stroke.last = Some(p);
        let r = stroke.brush.radius;
        let reach = Rect::new(from.min(p) - r, from.max(p) + r);
        let layer = Arc::make_mut(&mut self.layer);
        let mut change: Option<Change> = None;
        let cells: Vec<usize> = layer.cells_in(reach).collect();
        for cell in cells {
            let cover = stroke
                .brush
                .cover(distance_to_segment(layer.cell_centre(cell), from, p));
            if cover <= 0.0 {
                continue;
            }
            let slot = *stroke.slots.entry(cell).or_insert_with(|| {
                stroke.cells.push(cell);
                stroke.cover.push(0.0);
                stroke.before.extend_from_slice(layer.get(cell));
                stroke.cells.len() - 1
            });
            if cover <= stroke.cover[slot] {
                continue;
            }
            stroke.cover[slot] = cover;
            let n = layer.species();
            let after = stroke
                .brush
                .apply(&stroke.before[slot * n..(slot + 1) * n], cover);
            if after.as_slice() != layer.get(cell) {
                layer.set(cell, &after)?;
                change = Change::union(
                    change,
                    Some(Change {
                        cells: 1,
                        region: layer.cell_rect(cell),
                    }),
                );
            }
        }
        Ok(change)
    }

    /// Ends the stroke under way, keeping it for undo if it changed anything (and dropping
    /// what could be redone). Returns whether it was kept.
    pub fn end_stroke(&mut self) -> bool {
        let Some(stroke) = self.stroke.take() else {
            return false;
        };
        let n = self.layer.species();
        let mut edit = Edit {
            cells: Vec::new(),
            before: Vec::new(),
            after: Vec::new(),
            region: Rect::new(Vec2::splat(f32::INFINITY), Vec2::splat(f32::NEG_INFINITY)),
        };
        for (slot, &cell) in stroke.cells.iter().enumerate() {
            let before = &stroke.before[slot * n..(slot + 1) * n];
            let after = self.layer.get(cell);
            if before != after {
                edit.cells.push(cell);
                edit.before.extend_from_slice(before);
                edit.after.extend_from_slice(after);
                edit.region = edit.region.union(&self.layer.cell_rect(cell));
            }
        }
        if edit.cells.is_empty() {
            return false;
        }
        self.redo.clear();
        self.undo.push(edit);
        // Bounded history: the oldest strokes go first.
        let mut kept: usize = self.undo.iter().map(|e| e.before.len() * 2).sum();
        while self.undo.len() > MAX_UNDO || (kept > MAX_UNDO_VALUES && self.undo.len() > 1) {
            kept -= self.undo[0].before.len() * 2;
            self.undo.remove(0);
        }
        true
    }

    /// A whole stroke along `path`: checked first (brush, species, points, reach), so an
    /// error changes nothing; then painted and kept for undo.
    pub fn stroke(&mut self, brush: Brush, path: &[Vec2]) -> Result<Option<Change>, PaintError> {
        if path.is_empty() {
            return Err(PaintError::EmptyStroke);
        }
        brush.validate()?;
        if let Some(p) = path.iter().find(|p| !p.is_finite()) {
            return self.check_reach(&brush, *p, *p).map(|()| None);
        }
        let touches = (0..path.len()).any(|k| {
            self.check_reach(&brush, path[k.saturating_sub(1)], path[k])
                .is_ok()
        });
        if !touches {
            return self.check_reach(&brush, path[0], path[0]).map(|()| None);
        }
        self.begin_stroke(brush)?;
        let mut change = None;
        for &p in path {
            // Parts of the path off the layer paint nothing; the whole path was checked.
            if let Ok(c) = self.stroke_to(p) {
                change = Change::union(change, c);
            } else if let Some(s) = &mut self.stroke {
                s.last = Some(p);
            }
        }
        self.end_stroke();
        Ok(change)
    }

    /// Undoes the last stroke; returns what changed, or `None` when there is nothing to undo.
    pub fn undo(&mut self) -> Option<Change> {
        self.end_stroke();
        let edit = self.undo.pop()?;
        let change = self.write(&edit, false);
        self.redo.push(edit);
        Some(change)
    }

    /// Redoes the last undone stroke; `None` when there is nothing to redo.
    pub fn redo(&mut self) -> Option<Change> {
        self.end_stroke();
        let edit = self.redo.pop()?;
        let change = self.write(&edit, true);
        self.undo.push(edit);
        Some(change)
    }

    fn write(&mut self, edit: &Edit, after: bool) -> Change {
        let n = self.layer.species();
        let layer = Arc::make_mut(&mut self.layer);
        let values = if after { &edit.after } else { &edit.before };
        for (k, &cell) in edit.cells.iter().enumerate() {
            // The edit was taken from this layer, so its cells and lengths fit.
            let _ = layer.set(cell, &values[k * n..(k + 1) * n]);
        }
        Change {
            cells: edit.cells.len(),
            region: edit.region,
        }
    }

    /// An error when `p` is not finite or the brush's path from `from` to `p` misses the
    /// layer.
    fn check_reach(&self, brush: &Brush, from: Vec2, p: Vec2) -> Result<(), PaintError> {
        let b = self.layer.bounds();
        if !(p.is_finite() && from.is_finite()) {
            return Err(PaintError::NotAPoint {
                at: if p.is_finite() { from } else { p },
            });
        }
        let r = brush.radius;
        let reach = Rect::new(from.min(p) - r, from.max(p) + r);
        let touches = self
            .layer
            .cells_in(reach)
            .any(|c| brush.cover(distance_to_segment(self.layer.cell_centre(c), from, p)) > 0.0);
        if !touches {
            return Err(PaintError::MissesTerrain {
                at: p,
                radius: r,
                bounds: b,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::brush::BrushAction;

    fn canvas() -> PaintCanvas {
        PaintCanvas::new(PaintLayer::new(Rect::new(Vec2::ZERO, Vec2::splat(50.0)), 1.0, 2).unwrap())
    }

    #[test]
    fn going_over_a_spot_twice_in_one_stroke_paints_it_once() {
        let mut c = canvas();
        let mut brush = Brush::new(BrushAction::Add { species: 0 }, 5.0);
        brush.strength = 0.5;
        let p = Vec2::splat(25.0);
        c.stroke(brush, &[p, Vec2::new(35.0, 25.0), p]).unwrap();
        let once = c.layer().density(p);
        assert!((once - 0.5).abs() < 1e-3, "{once}");
        c.stroke(brush, &[p]).unwrap();
        assert!((c.layer().density(p) - 0.75).abs() < 1e-3);
        assert_eq!(c.history(), (2, 0));
    }

    #[test]
    fn strokes_off_the_layer_and_bad_species_change_nothing() {
        let mut c = canvas();
        let before = c.layer().clone();
        let add = Brush::new(BrushAction::Add { species: 0 }, 5.0);
        assert!(c.stroke(add, &[Vec2::new(-20.0, 10.0)]).is_err());
        assert!(c.stroke(add, &[Vec2::new(f32::NAN, 10.0)]).is_err());
        assert!(
            c.stroke(add, &[Vec2::new(10.0, 10.0), Vec2::new(f32::INFINITY, 0.0)])
                .is_err()
        );
        assert!(c.stroke(add, &[]).is_err());
        let missing = Brush::new(BrushAction::Species { species: 2 }, 5.0);
        let e = c.stroke(missing, &[Vec2::splat(10.0)]).unwrap_err();
        assert!(e.to_string().contains("no species 2"), "{e}");
        assert!(c.stroke_to(Vec2::splat(10.0)).is_err());
        assert_eq!(c.layer(), &before);
        assert_eq!(c.history(), (0, 0));
        // A stroke that starts off the layer and comes onto it paints the part on it.
        let change = c
            .stroke(add, &[Vec2::new(-20.0, 10.0), Vec2::new(10.0, 10.0)])
            .unwrap();
        assert!(change.is_some());
    }

    #[test]
    fn undo_and_redo_restore_exact_layers() {
        let mut c = canvas();
        let empty = c.layer().clone();
        c.stroke(
            Brush::new(BrushAction::Add { species: 1 }, 8.0),
            &[Vec2::splat(20.0)],
        )
        .unwrap();
        let added = c.layer().clone();
        let mut erase = Brush::new(BrushAction::Erase, 4.0);
        erase.strength = 0.7;
        c.stroke(erase, &[Vec2::splat(18.0), Vec2::splat(22.0)])
            .unwrap();
        let erased = c.layer().clone();
        assert_ne!(added, erased);
        c.undo().unwrap();
        assert_eq!(c.layer(), &added);
        c.undo().unwrap();
        assert_eq!(c.layer(), &empty);
        assert!(c.undo().is_none());
        c.redo().unwrap();
        c.redo().unwrap();
        assert_eq!(c.layer(), &erased);
        assert!(c.redo().is_none());
        // A new stroke drops what could be redone.
        c.undo().unwrap();
        c.stroke(Brush::new(BrushAction::Erase, 2.0), &[Vec2::splat(20.0)])
            .unwrap();
        assert_eq!(c.history(), (2, 0));
    }
}
