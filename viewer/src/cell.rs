//! One streamed cell of the world: its key (column, row and level of detail), and its
//! instances generated from the forest, a pure function of the world and the key.

use sylva::forest::{ForestError, PlacementBlock, Rect, tree_tint, tree_wind};
use sylva::instancing::CompactTree;
use sylva::terrain::glam::{Vec2, Vec3};

use crate::world::{InstanceRaw, World, world_sphere};

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
    /// Where each run starts in `instances`, and one more entry for the end.
    starts: Vec<u32>,
}

impl Runs {
    /// Gathers `(run, instance)` pairs into `runs` runs, keeping their order within a run.
    pub(crate) fn gather(mut tagged: Vec<(u32, InstanceRaw)>, runs: usize) -> Runs {
        tagged.sort_by_key(|(run, _)| *run);
        let mut starts = vec![0u32; runs + 1];
        for (run, _) in &tagged {
            starts[*run as usize + 1] += 1;
        }
        for k in 0..runs {
            starts[k + 1] += starts[k];
        }
        Runs {
            instances: tagged.into_iter().map(|(_, i)| i).collect(),
            starts,
        }
    }

    /// The instances of run `k`.
    pub(crate) fn run(&self, k: usize) -> &[InstanceRaw] {
        match (self.starts.get(k), self.starts.get(k + 1)) {
            (Some(&a), Some(&b)) => &self.instances[a as usize..b as usize],
            _ => &[],
        }
    }

    pub(crate) fn len(&self) -> usize {
        self.instances.len()
    }
}

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
}

impl Cell {
    pub(crate) fn new(
        world: &World,
        placements: Runs,
        proxies: Runs,
        trees: usize,
        version: u64,
    ) -> Cell {
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        let mut bound = |runs: &Runs, spheres: &mut dyn Iterator<Item = (Vec3, f32)>| {
            for (k, sphere) in spheres.enumerate() {
                for i in runs.run(k) {
                    let (centre, radius) = world_sphere(i, sphere);
                    lo = lo.min(centre - radius);
                    hi = hi.max(centre + radius);
                }
            }
        };
        bound(&placements, &mut world.groups.iter().map(|g| g.sphere));
        bound(&proxies, &mut world.proxies.iter().map(|p| p.sphere));
        let sphere = if lo.x <= hi.x {
            ((lo + hi) * 0.5, (hi - lo).length() * 0.5)
        } else {
            (Vec3::ZERO, -1.0)
        };
        Cell {
            placements,
            proxies,
            sphere,
            trees,
            version,
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
        let variants = self.proxies.len();
        let proxies = |trees: &[CompactTree]| {
            Runs::gather(
                trees
                    .iter()
                    .filter(|t| !self.seedling[usize::from(t.variant)])
                    .map(|t| (u32::from(t.variant), tree_instance(t)))
                    .collect(),
                variants,
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
        let placements = Runs::gather(tagged, self.groups.len());
        Ok(Cell::new(
            self,
            placements,
            proxies(&trees),
            trees.len(),
            version,
        ))
    }
}
