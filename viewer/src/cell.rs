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
    /// The runs with any instance, in order: a cell holds a few of the world's tens of
    /// thousands of groups, and culling visits only these.
    occupied: Vec<u32>,
    /// Bounds of each occupied run, once [`Runs::bound`] has made them.
    bounds: Vec<RunBounds>,
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
}

impl RunBounds {
    const EMPTY: RunBounds = RunBounds {
        spheres: (Vec3::INFINITY, Vec3::NEG_INFINITY),
        bases: (Vec3::INFINITY, Vec3::NEG_INFINITY),
        radius: 0.0,
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
    /// Gathers `(run, instance)` pairs into `runs` runs, keeping their order within a run.
    pub(crate) fn gather(mut tagged: Vec<(u32, InstanceRaw)>, runs: usize) -> Runs {
        tagged.sort_by_key(|(run, _)| *run);
        let mut starts = vec![0u32; runs + 1];
        for (run, _) in &tagged {
            starts[*run as usize + 1] += 1;
        }
        let occupied = (0..runs as u32)
            .filter(|&k| starts[k as usize + 1] > 0)
            .collect();
        for k in 0..runs {
            starts[k + 1] += starts[k];
        }
        Runs {
            instances: tagged.into_iter().map(|(_, i)| i).collect(),
            starts,
            occupied,
            bounds: Vec::new(),
        }
    }

    /// Makes each occupied run's bounds, with `sphere(k)` the bounding sphere of run `k`'s
    /// instances in their own space; returns the box around them all.
    fn bound(&mut self, sphere: impl Fn(usize) -> (Vec3, f32)) -> (Vec3, Vec3) {
        let mut all = RunBounds::EMPTY.spheres;
        self.bounds = (self.occupied.iter())
            .map(|&k| {
                let mut b = RunBounds::EMPTY;
                for i in self.run(k as usize) {
                    let (centre, radius) = world_sphere(i, sphere(k as usize));
                    b.spheres = (
                        b.spheres.0.min(centre - radius),
                        b.spheres.1.max(centre + radius),
                    );
                    b.bases = (b.bases.0.min(i.base()), b.bases.1.max(i.base()));
                    b.radius = b.radius.max(radius);
                }
                all = (all.0.min(b.spheres.0), all.1.max(b.spheres.1));
                b
            })
            .collect();
        all
    }

    /// Each run with any instance, as (run, its bounds, where it starts in `instances`, its
    /// instances), in order of run.
    pub(crate) fn occupied(
        &self,
    ) -> impl Iterator<Item = (usize, &RunBounds, usize, &[InstanceRaw])> {
        (self.occupied.iter().zip(&self.bounds)).map(|(&k, b)| {
            let first = self.starts[k as usize] as usize;
            (k as usize, b, first, self.run(k as usize))
        })
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
