//! One streamed cell of the world: its key (column, row and level of detail), and its
//! instances generated from the forest, a pure function of the world and the key.

use std::sync::atomic::{AtomicU64, Ordering};

use sylva::forest::{ForestError, PlacementBlock, Rect, tree_tint, tree_wind};
use sylva::instancing::CompactTree;
use sylva::terrain::glam::{Vec2, Vec3};

use crate::geometry::{InstanceRaw, world_sphere};
use crate::world::World;

/// Side of a cell in metres.
pub(crate) const CELL: f32 = 100.0;
/// A cell's level of detail.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) enum Level {
    /// Every placement of every tree.
    Fine,
    /// One proxy per canopy tree.
    Coarse,
}

/// A cell of the world at one level: column `x`, row `z` of the grid of [`CELL`]-metre squares
/// from the world's origin.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub(crate) struct CellKey {
    pub(crate) x: u32,
    pub(crate) z: u32,
    pub(crate) level: Level,
}

impl CellKey {
    /// The ground the cell covers, clipped to the world.
    pub(crate) fn rect(&self, side: f32) -> Rect {
        let min = Vec2::new(self.x as f32 * CELL, self.z as f32 * CELL);
        Rect::new(min, (min + Vec2::splat(CELL)).min(Vec2::splat(side)))
    }

    /// Horizontal distance from `eye` to the cell's nearest point.
    pub(crate) fn distance(&self, eye: Vec3, side: f32) -> f32 {
        let r = self.rect(side);
        let p = Vec2::new(eye.x, eye.z);
        p.distance(p.clamp(r.min, r.max))
    }

    pub(crate) fn other_level(self) -> CellKey {
        CellKey {
            level: match self.level {
                Level::Fine => Level::Coarse,
                Level::Coarse => Level::Fine,
            },
            ..self
        }
    }
}

/// Instances gathered by what draws them: run `k` is group `k`'s placements, or variant
/// `k`'s proxies.
#[derive(Default)]
pub(crate) struct Runs {
    pub(crate) instances: Vec<InstanceRaw>,
    /// The occupied runs cut into pieces of at most [`PIECE`] instances, in order: a cell
    /// holds a few of the world's tens of thousands of groups, and culling visits only
    /// these, passing over (or taking whole) a piece at a time.
    pieces: Vec<Piece>,
}

/// The most instances in one [`Piece`]: few enough that a piece's bounds are tight (most
/// pieces are then wholly in or out of a view, and at one level of detail), enough that
/// testing its bounds costs little beside testing its instances.
const PIECE: usize = 64;

/// Consecutive instances of one run, with their bounds.
#[derive(Debug, Clone, Copy)]
struct Piece {
    run: u32,
    /// Where it starts and ends in [`Runs::instances`].
    first: u32,
    end: u32,
    bounds: RunBounds,
}

/// The Z-order (Morton) key of a point on a grid: the bits of `x` and `z` interleaved, so
/// that points near in the key are near on the ground.
fn z_order(x: u16, z: u16) -> u32 {
    let spread = |v: u16| {
        let mut v = u32::from(v);
        v = (v | (v << 8)) & 0x00ff_00ff;
        v = (v | (v << 4)) & 0x0f0f_0f0f;
        v = (v | (v << 2)) & 0x3333_3333;
        (v | (v << 1)) & 0x5555_5555
    };
    spread(x) | (spread(z) << 1)
}

/// Bounds of one run's instances, so culling can pass over a run whole: out of view, too
/// small to see, or past (or short of) the distance its levels of detail are drawn at.
#[derive(Debug, Clone, Copy)]
pub(crate) struct RunBounds {
    /// The box around every instance's bounding sphere in the world.
    pub(crate) spheres: (Vec3, Vec3),
    /// The box around its trees' bases, where the level of detail is measured from.
    pub(crate) bases: (Vec3, Vec3),
    /// The largest instance's bounding radius in the world.
    pub(crate) radius: f32,
    /// The smallest instance's bounding radius in the world.
    pub(crate) least_radius: f32,
}

impl RunBounds {
    const EMPTY: RunBounds = RunBounds {
        spheres: (Vec3::INFINITY, Vec3::NEG_INFINITY),
        bases: (Vec3::INFINITY, Vec3::NEG_INFINITY),
        radius: 0.0,
        least_radius: f32::INFINITY,
    };

    /// The sphere around the box of instance spheres, as (centre, radius).
    pub(crate) fn sphere(&self) -> (Vec3, f32) {
        sphere_around(self.spheres)
    }
}

/// The sphere around the box `(lo, hi)`, as (centre, radius).
fn sphere_around((lo, hi): (Vec3, Vec3)) -> (Vec3, f32) {
    ((lo + hi) * 0.5, (hi - lo).length() * 0.5)
}

impl Runs {
    /// Gathers `(run, instance)` pairs into their runs, each in Z order of its trees'
    /// bases over the ground (ties in the order given), so that each piece of a run covers
    /// a small patch of the cell rather than a scatter across it.
    pub(crate) fn gather(mut tagged: Vec<(u32, InstanceRaw)>) -> Runs {
        let ground = |i: &InstanceRaw| Vec2::new(i.tree[0], i.tree[2]);
        let (lo, hi) = (tagged.iter())
            .fold((Vec2::INFINITY, Vec2::NEG_INFINITY), |(lo, hi), (_, i)| {
                (lo.min(ground(i)), hi.max(ground(i)))
            });
        let scale = f32::from(u16::MAX) / (hi - lo).max_element().max(1e-3);
        tagged.sort_by_cached_key(|(run, i)| {
            let [x, z] = ((ground(i) - lo) * scale).to_array().map(|q| q as u16);
            (*run, z_order(x, z))
        });
        // Each run is a stretch of equal keys, cut every PIECE instances.
        let mut pieces = Vec::new();
        let mut first = 0;
        for run in tagged.chunk_by(|a, b| a.0 == b.0) {
            for part in run.chunks(PIECE) {
                pieces.push(Piece {
                    run: part[0].0,
                    first: first as u32,
                    end: (first + part.len()) as u32,
                    bounds: RunBounds::EMPTY,
                });
                first += part.len();
            }
        }
        Runs {
            instances: tagged.into_iter().map(|(_, i)| i).collect(),
            pieces,
        }
    }

    /// Makes each piece's bounds, with `sphere(k)` the bounding sphere of run `k`'s
    /// instances in their own space; returns the box around them all.
    fn bound(&mut self, sphere: impl Fn(usize) -> (Vec3, f32)) -> (Vec3, Vec3) {
        let mut all = RunBounds::EMPTY.spheres;
        for piece in &mut self.pieces {
            let b = &mut piece.bounds;
            let own = sphere(piece.run as usize);
            for i in &self.instances[piece.first as usize..piece.end as usize] {
                let (centre, radius) = world_sphere(i, own);
                b.spheres = (
                    b.spheres.0.min(centre - radius),
                    b.spheres.1.max(centre + radius),
                );
                b.bases = (b.bases.0.min(i.base()), b.bases.1.max(i.base()));
                b.radius = b.radius.max(radius);
                b.least_radius = b.least_radius.min(radius);
            }
            all = (all.0.min(b.spheres.0), all.1.max(b.spheres.1));
        }
        all
    }

    /// Each piece of the occupied runs, as (its run, its bounds, where it starts in
    /// `instances`, its instances), in order of run and place in the run.
    pub(crate) fn occupied(
        &self,
    ) -> impl Iterator<Item = (usize, &RunBounds, usize, &[InstanceRaw])> {
        self.pieces.iter().map(|p| {
            let (first, end) = (p.first as usize, p.end as usize);
            (
                p.run as usize,
                &p.bounds,
                first,
                &self.instances[first..end],
            )
        })
    }

    /// The instances of run `k`.
    #[cfg(test)]
    pub(crate) fn run(&self, k: usize) -> &[InstanceRaw] {
        let of_k = |p: &&Piece| p.run as usize == k;
        match (
            self.pieces.iter().find(of_k),
            self.pieces.iter().rfind(of_k),
        ) {
            (Some(a), Some(b)) => &self.instances[a.first as usize..b.end as usize],
            _ => &[],
        }
    }

    pub(crate) fn len(&self) -> usize {
        self.instances.len()
    }
}

/// The next [`Cell::id`].
static NEXT_ID: AtomicU64 = AtomicU64::new(0);

/// One streamed cell.
pub(crate) struct Cell {
    /// Fine cells: the placements of every tree, by group (empty in coarse cells).
    pub(crate) placements: Runs,
    /// A proxy per canopy tree, by variant: a coarse cell draws them all, a fine one those of
    /// its trees beyond the level-of-detail distance.
    pub(crate) proxies: Runs,
    /// A sphere around everything in the cell, for culling it whole (radius below zero:
    /// nothing in it).
    pub(crate) sphere: (Vec3, f32),
    /// Trees in the cell.
    pub(crate) trees: usize,
    /// The version of the forest (see `World::repaint`) it was generated from.
    pub(crate) version: u64,
    /// This cell's own number, unlike any other cell's made in this run: what the GPU's
    /// copy of its instances is kept under (a cell made again after a repaint is another).
    pub(crate) id: u64,
}

impl Cell {
    pub(crate) fn new(
        world: &World,
        mut placements: Runs,
        mut proxies: Runs,
        trees: usize,
        version: u64,
    ) -> Cell {
        let (a, b) = (
            placements.bound(|k| world.groups[k].sphere),
            proxies.bound(|k| world.proxies[k].sphere),
        );
        let (lo, hi) = (a.0.min(b.0), a.1.max(b.1));
        let sphere = if lo.x <= hi.x {
            sphere_around((lo, hi))
        } else {
            (Vec3::ZERO, -1.0)
        };
        Cell {
            placements,
            proxies,
            sphere,
            trees,
            version,
            id: NEXT_ID.fetch_add(1, Ordering::Relaxed),
        }
    }

    /// Bytes of instances held.
    pub(crate) fn bytes(&self) -> usize {
        (self.placements.len() + self.proxies.len()) * size_of::<InstanceRaw>()
    }
}

fn tree_instance(tree: &CompactTree) -> InstanceRaw {
    let root = tree.root();
    let tint = tree_tint(tree);
    InstanceRaw {
        rotation: root.rotation.normalize().to_array(),
        translation_scale: [
            root.translation.x,
            root.translation.y,
            root.translation.z,
            root.scale,
        ],
        tint: [tint[0], tint[1], tint[2], 0.0],
        tree: tree_wind(tree),
    }
}

impl World {
    /// Generates one cell: a pure function of the world and the key.
    pub(crate) fn cell(&self, key: CellKey) -> Result<Cell, ForestError> {
        let rect = key.rect(self.side);
        let proxies = |trees: &[CompactTree]| {
            Runs::gather(
                trees
                    .iter()
                    .filter(|t| !self.seedling[usize::from(t.variant)])
                    .map(|t| (u32::from(t.variant), tree_instance(t)))
                    .collect(),
            )
        };
        let (forest, version) = self.forest();
        if key.level == Level::Coarse {
            let trees = forest.trees(&self.heightmap, rect);
            return Ok(Cell::new(
                self,
                Runs::default(),
                proxies(&trees),
                trees.len(),
                version,
            ));
        }
        let (mut tagged, mut trees) = (Vec::new(), Vec::new());
        forest.stream(&self.heightmap, rect, &mut |block: &PlacementBlock| {
            for p in &block.placements {
                let Some(group) = self
                    .group_of
                    .get(p.variant as usize)
                    .and_then(|g| g.get(p.instance as usize))
                    .copied()
                    .flatten()
                else {
                    continue;
                };
                let tree = block.trees.get(p.tree as usize);
                let tint = tree.map_or([1.0; 3], tree_tint);
                let t = &p.transform;
                tagged.push((
                    group,
                    InstanceRaw {
                        rotation: t.rotation.to_array(),
                        translation_scale: [
                            t.translation.x,
                            t.translation.y,
                            t.translation.z,
                            t.scale,
                        ],
                        tint: [tint[0], tint[1], tint[2], 0.0],
                        tree: tree.map_or([0.0; 4], tree_wind),
                    },
                ));
            }
            trees.extend_from_slice(&block.trees);
            Ok(())
        })?;
        if let Some(floor) = &self.floor {
            tagged.extend(self.floor_instances(floor, rect)?);
        }
        let placements = Runs::gather(tagged);
        Ok(Cell::new(
            self,
            placements,
            proxies(&trees),
            trees.len(),
            version,
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn z_order_interleaves_the_bits_of_x_and_z() {
        assert_eq!(z_order(0, 0), 0);
        assert_eq!(z_order(1, 0), 1);
        assert_eq!(z_order(0, 1), 2);
        assert_eq!(z_order(3, 3), 15);
        assert_eq!(z_order(u16::MAX, 0), 0x5555_5555);
        assert_eq!(z_order(0, u16::MAX), 0xaaaa_aaaa);
    }

    #[test]
    fn runs_are_cut_into_pieces_in_z_order_of_their_bases() {
        let at = |x: f32, z: f32| InstanceRaw {
            rotation: [0.0, 0.0, 0.0, 1.0],
            translation_scale: [x, 0.0, z, 1.0],
            tint: [1.0; 4],
            tree: [x, 0.0, z, 0.0],
        };
        // Run 1: a row of trees along x, given back to front; run 0: one tree.
        let mut tagged: Vec<(u32, InstanceRaw)> =
            (0..100).rev().map(|k| (1, at(k as f32, 0.0))).collect();
        tagged.push((0, at(5.0, 5.0)));
        let runs = Runs::gather(tagged);
        assert_eq!(runs.run(0).len(), 1);
        let row: Vec<f32> = runs.run(1).iter().map(|i| i.tree[0]).collect();
        assert_eq!(row, (0..100).map(|k| k as f32).collect::<Vec<_>>());
        assert!(runs.run(2).is_empty());
        // 1 + 100 instances: one piece, then pieces of at most PIECE.
        let pieces: Vec<(usize, usize)> =
            runs.occupied().map(|(k, _, _, i)| (k, i.len())).collect();
        assert_eq!(pieces, vec![(0, 1), (1, PIECE), (1, 100 - PIECE)]);
    }
}
