//! Streaming: the world cut into square cells, and only the cells near the camera kept.
//!
//! Cells within [`LOD_DISTANCE`] of the camera are *fine*: every placement of every tree in
//! them, generated from the compact forest (`ForestBuilder::stream` over the cell), and a
//! proxy per canopy tree for those of its trees a frame finds beyond that distance. Cells
//! within [`VIEW_DISTANCE`] are *coarse*: only the proxies (`ForestBuilder::trees`), as the
//! coarse tiles of a 3D Tiles world carry. Farther cells are dropped. A cell's content
//! is a pure function of the world and the cell, so a cell dropped and streamed in again is
//! the same, and a frame is the same whatever order its cells arrived in.
//!
//! Headless frames wait for every cell they need ([`Cells::update`] with `wait`); the window
//! asks a [`Loader`] thread for them, nearest first, and draws what has arrived, a coarse cell
//! standing in for a fine one until the fine one comes.

use std::collections::BTreeMap;
use std::sync::Arc;
use std::time::Instant;

use rayon::prelude::*;
use sylva::forest::{ForestError, Rect};
use sylva::terrain::glam::Vec3;

use crate::cell::{CELL, Cell, CellKey, Level};
use crate::loader::Loader;
use crate::world::World;

/// Cells nearer than this (horizontally, from the camera to the cell's nearest point) are
/// fine; trees beyond it are drawn as proxies, as a 3D Tiles client switches to coarse tiles.
pub(crate) const LOD_DISTANCE: f32 = 250.0;
/// Cells farther than this are not kept; fog hides what lies beyond.
pub(crate) const VIEW_DISTANCE: f32 = 1500.0;
/// A resident cell is dropped only this much beyond the distance that wanted it, so walking
/// to and fro across a boundary does not generate the same cell again and again.
const KEEP_MARGIN: f32 = 60.0;

impl World {
    /// The cells a camera at `eye` wants, nearest first: fine within [`LOD_DISTANCE`] (or
    /// everywhere in view with `fine_everywhere`), coarse to [`VIEW_DISTANCE`].
    fn wanted(&self, eye: Vec3, fine_everywhere: bool) -> Vec<(f32, CellKey)> {
        let count = (self.side / CELL).ceil().max(1.0) as u32;
        let span = |at: f32| {
            let lo = ((at - VIEW_DISTANCE) / CELL).floor().max(0.0) as u32;
            let hi = (((at + VIEW_DISTANCE) / CELL).floor().max(0.0) as u32).min(count - 1);
            lo..=hi
        };
        let mut out = Vec::new();
        for z in span(eye.z) {
            for x in span(eye.x) {
                let fine = CellKey {
                    x,
                    z,
                    level: Level::Fine,
                };
                let d = fine.distance(eye, self.side);
                if d > VIEW_DISTANCE {
                    continue;
                }
                let level = if fine_everywhere || d <= LOD_DISTANCE {
                    Level::Fine
                } else {
                    Level::Coarse
                };
                out.push((d, CellKey { level, ..fine }));
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }
}

/// What one update did.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Streamed {
    /// Cells generated during the update (headless) or received from the loader (window).
    pub(crate) generated: usize,
    /// Milliseconds spent generating or receiving them.
    pub(crate) milliseconds: f64,
    /// Cells wanted but not here yet (always 0 after a waiting update).
    pub(crate) pending: usize,
    /// Cells kept, drawn or not.
    pub(crate) resident: usize,
    /// Trees in the cells drawn, and how many of those are in coarse cells.
    pub(crate) trees: usize,
    pub(crate) coarse: usize,
    /// Bytes of placements held.
    pub(crate) bytes: usize,
}

/// The cells kept around the camera, and which of them a frame draws.
#[derive(Default)]
pub(crate) struct Cells {
    resident: BTreeMap<CellKey, Cell>,
    /// The cells a frame draws, in key order (a frame's instance order does not depend on
    /// the order cells arrived in).
    drawn: Vec<CellKey>,
    loader: Option<Loader>,
    /// The forest's repaints: each version and the rectangle whose trees it changed; a cell
    /// of an older version over such a rectangle (one the loader was making while the
    /// painting tool painted) is stale.
    repaints: Vec<(u64, Rect)>,
}

/// Most repaints remembered (the loader holds at most a few cells in hand).
const MAX_REPAINTS: usize = 1024;

impl Cells {
    /// Streams the cells around `eye`: generates those missing (waiting for them all with
    /// `wait`; otherwise asking the loader thread and taking what it has finished), drops
    /// those left far behind, and chooses what to draw.
    pub(crate) fn update(
        &mut self,
        world: &Arc<World>,
        eye: Vec3,
        fine_everywhere: bool,
        wait: bool,
    ) -> Result<Streamed, ForestError> {
        let start = Instant::now();
        let wanted = world.wanted(eye, fine_everywhere);
        let missing: Vec<CellKey> = wanted
            .iter()
            .map(|&(_, k)| k)
            .filter(|k| !self.resident.contains_key(k))
            .collect();
        let mut generated = 0;
        if wait {
            let made: Vec<(CellKey, Result<Cell, ForestError>)> =
                missing.par_iter().map(|&k| (k, world.cell(k))).collect();
            for (k, cell) in made {
                self.resident.insert(k, cell?);
                generated += 1;
            }
        } else {
            let loader = self
                .loader
                .get_or_insert_with(|| Loader::new(world.clone()));
            for (k, cell) in loader.ask(missing) {
                let cell = cell?;
                if !self.stale(k, &cell, world.side) {
                    self.resident.insert(k, cell);
                    generated += 1;
                }
            }
        }
        // Keep what is wanted, what stands in for a wanted cell not here yet, and what is
        // within reach of its level plus a margin.
        let wanted_keys: BTreeMap<CellKey, f32> = wanted.iter().map(|&(d, k)| (k, d)).collect();
        let standing_in: std::collections::BTreeSet<CellKey> = wanted
            .iter()
            .filter(|(_, k)| !self.resident.contains_key(k))
            .map(|(_, k)| k.other_level())
            .collect();
        self.resident.retain(|k, _| {
            let reach = match k.level {
                Level::Fine if !fine_everywhere => LOD_DISTANCE,
                _ => VIEW_DISTANCE,
            };
            wanted_keys.contains_key(k)
                || standing_in.contains(k)
                || k.distance(eye, world.side) <= reach + KEEP_MARGIN
        });
        self.drawn = wanted
            .iter()
            .filter_map(|&(_, k)| {
                [k, k.other_level()]
                    .into_iter()
                    .find(|k| self.resident.contains_key(k))
            })
            .collect();
        self.drawn.sort();
        let mut streamed = Streamed {
            generated,
            milliseconds: start.elapsed().as_secs_f64() * 1e3,
            pending: wanted
                .iter()
                .filter(|(_, k)| !self.resident.contains_key(k))
                .count(),
            resident: self.resident.len(),
            ..Streamed::default()
        };
        for (k, cell) in self.drawn() {
            streamed.trees += cell.trees;
            if k.level == Level::Coarse {
                streamed.coarse += cell.trees;
            }
        }
        streamed.bytes = self.resident.values().map(Cell::bytes).sum();
        Ok(streamed)
    }

    fn stale(&self, key: CellKey, cell: &Cell, side: f32) -> bool {
        let rect = key.rect(side);
        self.repaints
            .iter()
            .any(|(v, r)| *v > cell.version && !rect.intersect(r).is_empty())
    }

    /// The forest was repainted to `version` over `region`: the resident cells over it are
    /// generated again now (so a stroke shows at once, with no hole while they come).
    pub(crate) fn repaint(
        &mut self,
        world: &World,
        region: Rect,
        version: u64,
    ) -> Result<usize, ForestError> {
        self.repaints.push((version, region));
        if self.repaints.len() > MAX_REPAINTS {
            self.repaints.remove(0);
        }
        let touched: Vec<CellKey> = self
            .resident
            .keys()
            .filter(|k| !k.rect(world.side).intersect(&region).is_empty())
            .copied()
            .collect();
        let made: Vec<(CellKey, Result<Cell, ForestError>)> =
            touched.par_iter().map(|&k| (k, world.cell(k))).collect();
        for (k, cell) in made {
            self.resident.insert(k, cell?);
        }
        Ok(touched.len())
    }

    /// The cells a frame draws, in key order.
    pub(crate) fn drawn(&self) -> impl Iterator<Item = (CellKey, &Cell)> {
        self.drawn
            .iter()
            .filter_map(|k| self.resident.get(k).map(|c| (*k, c)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::SceneOptions;
    use sylva::forest::PlacementBlock;
    use sylva::terrain::glam::Vec2;

    fn world(side: f32) -> Arc<World> {
        Arc::new(World::build(SceneOptions::small(5, side)).expect("world builds"))
    }

    /// Every tree of the world is in exactly one cell: the fine cells together hold the
    /// trees of the whole world streamed at once, placement for placement.
    #[test]
    fn fine_cells_tile_the_forest() {
        let world = world(250.0);
        let mut whole = 0usize;
        let mut placements = 0usize;
        world
            .forest()
            .0
            .stream(
                &world.heightmap,
                Rect::new(Vec2::ZERO, Vec2::splat(250.0)),
                &mut |b: &PlacementBlock| {
                    whole += b.trees.len();
                    placements += b
                        .placements
                        .iter()
                        .filter(|p| {
                            world.group_of[p.variant as usize][p.instance as usize].is_some()
                        })
                        .count();
                    Ok(())
                },
            )
            .expect("whole world streams");
        let (mut trees, mut instances) = (0, 0);
        for z in 0..3 {
            for x in 0..3 {
                let cell = world
                    .cell(CellKey {
                        x,
                        z,
                        level: Level::Fine,
                    })
                    .expect("cell");
                trees += cell.trees;
                // The trees' groups come first; the floor's items follow.
                let tree_groups = world
                    .first_floor_group
                    .map_or(world.groups.len(), |g| g as usize);
                instances += (0..tree_groups)
                    .map(|k| cell.placements.run(k).len())
                    .sum::<usize>();
            }
        }
        assert!(whole > 100, "{whole}");
        assert_eq!((trees, instances), (whole, placements));
    }

    /// Every drawn cell with where its instances stand.
    fn placed(cells: &Cells) -> Vec<(CellKey, Vec<[f32; 4]>)> {
        cells
            .drawn()
            .map(|(k, c)| {
                let all = c.placements.instances.iter().chain(&c.proxies.instances);
                (k, all.map(|i| i.translation_scale).collect())
            })
            .collect()
    }

    /// After a stroke the cells under it are generated again from the painted forest, and a
    /// cell the loader made from the layer before is dropped: the cells are then exactly those
    /// of a world painted with the final layer from the start.
    #[test]
    fn repainted_cells_are_the_painted_worlds_cells() {
        use sylva::paint::{Brush, BrushAction, PaintCanvas, PaintLayer};
        use sylva::terrain::HeightField;
        let painted = world(700.0);
        let world = world(700.0);
        let eye = Vec3::new(350.0, 20.0, 350.0);
        let mut cells = Cells::default();
        cells.update(&world, eye, false, true).expect("update");
        let before = placed(&cells);
        let (forest, _) = world.forest();
        let (lo, hi) = world.heightmap.bounds();
        let bounds = Rect::new(lo, hi);
        let weights: Vec<f32> = forest.config().species.iter().map(|s| s.weight).collect();
        let layer = PaintLayer::filled(bounds, 2.0, &weights).expect("layer");
        let mut canvas = PaintCanvas::for_forest(&forest, layer).expect("canvas");
        let version = world.repaint(canvas.shared_layer()).expect("repaint");
        cells.repaint(&world, bounds, version).expect("cells");
        // A full layer in the species' shares grows the generated forest.
        assert_eq!(placed(&cells), before);
        let stale = world
            .cell(CellKey {
                x: 3,
                z: 3,
                level: Level::Fine,
            })
            .expect("cell");
        let change = canvas
            .stroke(
                Brush::new(BrushAction::Erase, 30.0),
                &[Vec2::new(330.0, 340.0), Vec2::new(380.0, 360.0)],
            )
            .expect("stroke")
            .expect("a change");
        let version = world.repaint(canvas.shared_layer()).expect("repaint");
        let region = change.region.expanded(forest.density().reach());
        let regenerated = cells.repaint(&world, region, version).expect("cells");
        assert!(regenerated >= 2, "{regenerated}");
        assert!(cells.stale(
            CellKey {
                x: 3,
                z: 3,
                level: Level::Fine
            },
            &stale,
            world.side
        ));
        painted.repaint(canvas.shared_layer()).expect("repaint");
        let mut fresh = Cells::default();
        fresh.update(&painted, eye, false, true).expect("update");
        assert_eq!(placed(&cells), placed(&fresh));
        assert_ne!(placed(&cells), before);
    }

    /// The camera keeps fine cells near it, coarse ones farther out, none beyond the view
    /// distance; walking away drops what is left behind, and coming back streams the same
    /// cells again.
    #[test]
    fn cells_follow_the_camera() {
        let world = world(2000.0);
        let mut cells = Cells::default();
        let at = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        let first = cells
            .update(&world, at(100.0, 100.0), false, true)
            .expect("update");
        assert_eq!(first.pending, 0);
        assert!(first.generated > 0 && first.coarse > 0 && first.trees > first.coarse);
        for (k, _) in cells.drawn() {
            let d = k.distance(at(100.0, 100.0), world.side);
            assert!(d <= VIEW_DISTANCE);
            assert_eq!(k.level == Level::Fine, d <= LOD_DISTANCE, "{k:?} at {d}");
        }
        let snapshot = placed(&cells);
        let far = cells
            .update(&world, at(1900.0, 1900.0), false, true)
            .expect("update");
        assert!(far.generated > 0);
        assert!(
            cells
                .resident
                .keys()
                .all(|k| k.distance(at(1900.0, 1900.0), world.side) <= VIEW_DISTANCE + KEEP_MARGIN),
            "cells far behind are dropped"
        );
        cells
            .update(&world, at(100.0, 100.0), false, true)
            .expect("update");
        let again = placed(&cells);
        assert!(again == snapshot, "a cell streamed again is the same cell");
    }

    /// The window's way: cells asked of the loader thread arrive over a few updates, a
    /// coarse cell standing in for a fine one meanwhile, and end as the waiting way's cells.
    #[test]
    fn the_loader_delivers_what_waiting_would() {
        let world = world(1200.0);
        let eye = Vec3::new(600.0, 0.0, 600.0);
        let mut waited = Cells::default();
        waited.update(&world, eye, false, true).expect("update");
        let mut asked = Cells::default();
        let first = asked.update(&world, eye, false, false).expect("update");
        assert!(first.pending > 0, "{first:?}");
        let mut updates = 1;
        while asked
            .update(&world, eye, false, false)
            .expect("update")
            .pending
            > 0
        {
            updates += 1;
            assert!(updates < 6000, "the loader stalled");
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        let content = |cells: &Cells| -> Vec<(CellKey, usize, usize)> {
            cells
                .drawn()
                .map(|(k, c)| (k, c.placements.len(), c.proxies.len()))
                .collect()
        };
        assert_eq!(content(&asked), content(&waited));
    }
}
