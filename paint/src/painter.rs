//! The forest painter: a paint canvas and the forest it grows, regenerated patch-locally as
//! strokes land.

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec2;
use rayon::prelude::*;
use sylva_forest::{Composition, Forest, ForestBuilder, Rect};
use sylva_instancing::CompactTree;
use sylva_terrain::HeightField;

use crate::brush::Brush;
use crate::canvas::{Change, PaintCanvas};
use crate::error::PaintError;
use crate::layer::PaintLayer;

/// Side of the painter's tiles of trees, in density patches: small, so a stroke regenerates
/// little beyond its own reach.
pub const PAINT_TILE_PATCHES: f32 = 8.0;

/// What one edit (a stroke, or part of one, an undo or a redo) did to the forest.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct StrokeReport {
    /// The cells changed, if any.
    pub change: Option<Change>,
    /// The rectangle whose trees were regenerated (the change and the density model's reach).
    pub regenerated: Option<Rect>,
    /// Tiles of trees regenerated.
    pub tiles: usize,
    /// Trees in those tiles before and after.
    pub trees_before: usize,
    /// See `trees_before`.
    pub trees_after: usize,
    /// Wall time of the edit and the regeneration.
    pub elapsed: Duration,
}

/// A forest painted onto a terrain: strokes edit the paint layer and regenerate only the
/// trees within the density model's reach of the cells they changed, through the same
/// density management as a generated forest (spacing, seedlings, terrain constraints).
///
/// The painted forest is exactly the forest a [`ForestBuilder`] grows from the same layer
/// ([`ForestPainter::painted_builder`]), so it streams and exports like a generated one.
///
/// ```
/// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
/// use sylva_paint::{Brush, BrushAction, ForestPainter, PaintLayer};
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let mut leafy = Species::from_preset("kenwood-leafy", 4)?;
/// leafy.turtle.step = 0.5;
/// let config = ForestConfig::new(vec![leafy]).with_budget(2 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(200.0) };
/// let bounds = Rect::new(Vec2::ZERO, Vec2::splat(200.0));
/// let mut painter = ForestPainter::new(builder, ground, PaintLayer::new(bounds, 1.0, 1)?)?;
/// assert_eq!(painter.tree_count(), 0);
/// let report = painter.stroke(Brush::new(BrushAction::Add { species: 0 }, 20.0), &[Vec2::splat(100.0)])?;
/// assert!(report.trees_after > 0 && painter.tree_count() == report.trees_after);
/// painter.undo();
/// assert_eq!(painter.tree_count(), 0);
/// # Ok::<(), sylva_paint::PaintError>(())
/// ```
#[derive(Debug)]
pub struct ForestPainter<T> {
    builder: ForestBuilder,
    terrain: T,
    canvas: PaintCanvas,
    region: Rect,
    tile: f32,
    columns: usize,
    tiles: Vec<Vec<CompactTree>>,
}

impl<T: HeightField + Sync> ForestPainter<T> {
    /// A painter of `builder`'s species on `terrain`, starting from `layer` (one channel per
    /// species, covering the terrain or part of it: beyond it trees grow as unpainted);
    /// grows the whole forest once.
    pub fn new(builder: ForestBuilder, terrain: T, layer: PaintLayer) -> Result<Self, PaintError> {
        let canvas = PaintCanvas::for_forest(&builder, layer)?;
        let (lo, hi) = terrain.bounds();
        let region = Rect::new(lo, hi);
        if region.is_empty() || region.intersect(&canvas.layer().bounds()).is_empty() {
            return Err(PaintError::NoOverlap);
        }
        let tile = builder.density().patch * PAINT_TILE_PATCHES;
        let size = region.max - region.min;
        let (columns, rows) = ((size.x / tile).ceil(), (size.y / tile).ceil());
        if !(tile > 0.0 && f64::from(columns) * f64::from(rows) <= 1e8) {
            return Err(PaintError::TooManyTiles { size, tile });
        }
        let mut painter = ForestPainter {
            builder,
            terrain,
            canvas,
            region,
            tile,
            columns: columns as usize,
            tiles: vec![Vec::new(); columns as usize * rows as usize],
        };
        let all: Vec<usize> = (0..painter.tiles.len()).collect();
        painter.regenerate(&all);
        Ok(painter)
    }

    /// The canvas: the layer, and what can be undone.
    pub fn canvas(&self) -> &PaintCanvas {
        &self.canvas
    }

    /// The paint layer as painted so far.
    pub fn layer(&self) -> &PaintLayer {
        self.canvas.layer()
    }

    /// The terrain painted on.
    pub fn terrain(&self) -> &T {
        &self.terrain
    }

    /// The trees, tile by tile (row-major), each tile's in the density model's order.
    pub fn trees(&self) -> impl Iterator<Item = &CompactTree> {
        self.tiles.iter().flatten()
    }

    /// How many trees there are.
    pub fn tree_count(&self) -> usize {
        self.tiles.iter().map(Vec::len).sum()
    }

    /// The painted forest, ready for placements and export.
    pub fn forest(&self) -> Forest {
        self.builder.forest_of(self.trees().copied().collect())
    }

    /// A builder that grows this painted forest anywhere asked (streaming, tiles, export).
    pub fn painted_builder(&self) -> Result<ForestBuilder, PaintError> {
        let layer: Arc<dyn Composition> = self.canvas.shared_layer();
        Ok(self.builder.with_composition(Some(layer))?)
    }

    /// A whole stroke along `path` (see [`PaintCanvas::stroke`]), then the trees it touches
    /// regenerated. An error leaves layer and forest unchanged.
    pub fn stroke(&mut self, brush: Brush, path: &[Vec2]) -> Result<StrokeReport, PaintError> {
        let start = Instant::now();
        let change = self.canvas.stroke(brush, path)?;
        Ok(self.update(change, start))
    }

    /// Starts a stroke (for painting as the mouse moves); see [`PaintCanvas::begin_stroke`].
    pub fn begin_stroke(&mut self, brush: Brush) -> Result<(), PaintError> {
        self.canvas.begin_stroke(brush)
    }

    /// Paints the stroke on to `p` and regenerates the trees it touches.
    pub fn stroke_to(&mut self, p: Vec2) -> Result<StrokeReport, PaintError> {
        let start = Instant::now();
        let change = self.canvas.stroke_to(p)?;
        Ok(self.update(change, start))
    }

    /// Ends the stroke under way; it can then be undone.
    pub fn end_stroke(&mut self) -> bool {
        self.canvas.end_stroke()
    }

    /// Undoes the last stroke, trees and all; `None` when there is nothing to undo.
    pub fn undo(&mut self) -> Option<StrokeReport> {
        let start = Instant::now();
        let change = self.canvas.undo()?;
        Some(self.update(Some(change), start))
    }

    /// Redoes the last undone stroke; `None` when there is nothing to redo.
    pub fn redo(&mut self) -> Option<StrokeReport> {
        let start = Instant::now();
        let change = self.canvas.redo()?;
        Some(self.update(Some(change), start))
    }

    /// The rectangle whose trees a change of `cells` may alter: a tree's fate reads the
    /// layer at spots up to `RINGS` patches away, and spots lie inside their own patches.
    pub fn reach(&self, cells: Rect) -> Rect {
        cells.expanded(self.builder.density().reach())
    }

    fn update(&mut self, change: Option<Change>, start: Instant) -> StrokeReport {
        let Some(c) = change else {
            return StrokeReport {
                change: None,
                regenerated: None,
                tiles: 0,
                trees_before: 0,
                trees_after: 0,
                elapsed: start.elapsed(),
            };
        };
        let reach = self.reach(c.region);
        let tiles = self.tiles_in(reach);
        let trees_before = tiles.iter().map(|&t| self.tiles[t].len()).sum();
        self.regenerate(&tiles);
        StrokeReport {
            change,
            regenerated: Some(reach),
            tiles: tiles.len(),
            trees_before,
            trees_after: tiles.iter().map(|&t| self.tiles[t].len()).sum(),
            elapsed: start.elapsed(),
        }
    }

    fn tile_rect(&self, index: usize) -> Rect {
        let (i, j) = (index % self.columns, index / self.columns);
        let edge = |k: usize, lo: f32, hi: f32| (lo + k as f32 * self.tile).min(hi);
        let (lo, hi) = (self.region.min, self.region.max);
        Rect::new(
            Vec2::new(edge(i, lo.x, hi.x), edge(j, lo.y, hi.y)),
            Vec2::new(edge(i + 1, lo.x, hi.x), edge(j + 1, lo.y, hi.y)),
        )
    }

    fn tiles_in(&self, rect: Rect) -> Vec<usize> {
        let rows = self.tiles.len() / self.columns;
        let span = |lo: f32, hi: f32, origin: f32, n: usize| {
            let a = ((lo - origin) / self.tile).floor().max(0.0) as usize;
            let b = (((hi - origin) / self.tile).floor().max(-1.0) + 1.0) as usize;
            a.min(n)..b.min(n)
        };
        let xs = span(rect.min.x, rect.max.x, self.region.min.x, self.columns);
        let zs = span(rect.min.y, rect.max.y, self.region.min.y, rows);
        zs.flat_map(|j| xs.clone().map(move |i| j * self.columns + i))
            .collect()
    }

    fn regenerate(&mut self, tiles: &[usize]) {
        let density = self.builder.density().composed(self.canvas.layer());
        let fresh: Vec<Vec<CompactTree>> = tiles
            .par_iter()
            .map(|&t| {
                self.builder
                    .trees_with(&density, &self.terrain, self.tile_rect(t))
            })
            .collect();
        for (&t, trees) in tiles.iter().zip(fresh) {
            self.tiles[t] = trees;
        }
    }
}
