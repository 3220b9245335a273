//! Trees from instances (Kenwood algorithm 2) with an explicit stack: T = D * M^-1 and
//! D_new = D * E.

use bytemuck::{Pod, Zeroable};
use glam::{Quat, Vec3};

use crate::cache::{Candidates, Instance, InstanceCache};
use crate::error::InstancingError;
use crate::options::ROOT;
use crate::similarity::Similarity;
use sylva_base::hash::mix;

/// A placed tree, compact: 28 bytes. Its branches are expanded on demand, deterministically
/// from `seed`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Default, Pod, Zeroable)]
pub struct CompactTree {
    /// Root position.
    pub position: [f32; 3],
    /// Rotation about +Y, radians.
    pub yaw: f32,
    /// Uniform scale.
    pub scale: f32,
    /// Seed of the instance choices.
    pub seed: u32,
    /// Index of the cache it is assembled from: in a forest, its variant (a species at one
    /// maturity).
    pub variant: u16,
    /// Its crown class, below `crown_classes`: trees of different classes with the same
    /// `crown_classes` never draw the same crown, so a placement that gives neighbours
    /// different classes never puts a tree beside its copy.
    pub crown_class: u8,
    /// Number of crown classes, 0 for none (any crown).
    pub crown_classes: u8,
}

impl CompactTree {
    /// The root transform D.
    pub fn root(&self) -> Similarity {
        Similarity {
            rotation: Quat::from_rotation_y(self.yaw),
            translation: Vec3::from(self.position),
            scale: self.scale,
        }
    }
}

/// Bounds and choices of one tree's assembly.
///
/// The root instance is drawn uniformly among the whole-tree candidates that have exits (all
/// of them when none has), and among those only from the tree's crown class
/// ([`CompactTree::crown_class`]) when there are at least as many crowns as classes. Each exit is filled
/// with a complete candidate of its key (a whole branch subtree, no exits of its own) when
/// the key has any, drawn uniformly and never one the tree already uses while up to
/// [`REPEAT_PROBES`] draws find an unused one; a key without complete candidates takes the
/// fewest-exit of [`AssemblyLimits::choices`] random candidates.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct AssemblyLimits {
    /// Deepest chain of exits followed. Default: 256.
    pub max_depth: u32,
    /// Most instances one tree may place. Default: 4,194,304 (2^22).
    pub max_instances: usize,
    /// Candidates drawn at random for an exit whose key has no complete candidate; the one
    /// with the fewest exits of its own is used. Default 2.
    pub choices: u32,
}

/// Draws an exit makes among its key's complete candidates looking for one its tree does not
/// use yet: the same instance appears twice in one tree only when its key has fewer complete
/// candidates than this, or than the tree has exits of that key.
pub const REPEAT_PROBES: usize = 16;

impl Default for AssemblyLimits {
    fn default() -> Self {
        AssemblyLimits {
            max_depth: 256,
            max_instances: 1 << 22,
            choices: 2,
        }
    }
}

/// Instance placements grouped per instance: for each cached instance, the transforms at which
/// it is drawn. One instanced draw (or one glTF node with EXT_mesh_gpu_instancing) per
/// non-empty group.
#[derive(Debug, Clone, Default)]
pub struct Placements {
    /// `groups[i]`: the transforms of instance `i` of the cache.
    pub groups: Vec<Vec<Similarity>>,
    /// Total placements.
    pub count: usize,
}

impl Placements {
    /// Empty placements for a cache of `instances` instances.
    pub fn for_cache(cache: &InstanceCache) -> Self {
        Placements {
            groups: vec![Vec::new(); cache.instances.len()],
            count: 0,
        }
    }

    /// Removes all placements, keeping allocations.
    pub fn clear(&mut self) {
        self.groups.iter_mut().for_each(Vec::clear);
        self.count = 0;
    }

    /// The largest number of placements of any one instance.
    pub fn max_uses(&self) -> usize {
        self.groups.iter().map(Vec::len).max().unwrap_or(0)
    }

    /// Instances with at least one placement (draw calls needed).
    pub fn used_instances(&self) -> usize {
        self.groups.iter().filter(|g| !g.is_empty()).count()
    }
}

#[inline]
fn pick(seed: u32, counter: u32, n: usize) -> usize {
    let z = mix(((u64::from(seed) << 32) | u64::from(counter)).wrapping_add(0x9e37_79b9_7f4a_7c15));
    (((z >> 32) * n as u64) >> 32) as usize
}

/// The state of one kind of walk, kept between trees so that its lists are reused.
#[derive(Debug)]
struct Walk<F> {
    /// Exits still to fill: the key wanted (id, age), the frame D, the depth.
    stack: Vec<(u32, u32, F, u32)>,
    /// Whole branches chosen but not yet placed, with their frames.
    pending: Vec<(u32, F)>,
}

impl<F> Default for Walk<F> {
    fn default() -> Self {
        Walk {
            stack: Vec::new(),
            pending: Vec::new(),
        }
    }
}

/// Most whole branches chosen before their records are read and placed together: enough
/// for their cache misses to overlap, few enough to stay in registers' and L1's reach.
const PENDING: usize = 8;

/// Places the whole branches `pending` holds, in the order they were chosen, and empties it.
#[inline]
fn place_pending<F: Frame>(
    pending: &mut Vec<(u32, F)>,
    cache: &InstanceCache,
    place: &mut impl FnMut(u32, &Instance, F),
) {
    for &(k, frame) in pending.iter() {
        place(k, &cache.instances[k as usize], frame);
    }
    pending.clear();
}

/// What the assembly carries down a tree to each exit: a placement's frame D, or nothing
/// when only which instances a tree places matters (counting them needs no transforms).
trait Frame: Copy {
    /// The frame one step on: D * E.
    fn then(&self, step: &Similarity) -> Self;
}

impl Frame for Similarity {
    #[inline]
    fn then(&self, step: &Similarity) -> Self {
        self.mul(step)
    }
}

impl Frame for () {
    #[inline]
    fn then(&self, _: &Similarity) -> Self {}
}

/// Reusable state for expanding trees.
#[derive(Debug)]
pub struct Assembler {
    /// The walk of [`Assembler::expand_with`].
    framed: Walk<Similarity>,
    /// The walk of [`Assembler::instances_with`], which carries no frames.
    bare: Walk<()>,
    /// Instances the current tree uses, to avoid repeats within one crown.
    used: Vec<u32>,
    /// Most whole branches pending at once ([`PENDING`]; 1 places each as it is chosen).
    batch: usize,
    /// Limits applied to every tree. Default: [`AssemblyLimits::default`].
    pub limits: AssemblyLimits,
}

impl Default for Assembler {
    fn default() -> Self {
        Assembler {
            framed: Walk::default(),
            bare: Walk::default(),
            used: Vec::new(),
            batch: PENDING,
            limits: AssemblyLimits::default(),
        }
    }
}

impl Assembler {
    /// An assembler with default limits.
    pub fn new() -> Self {
        Self::default()
    }

    /// Expands one tree into `out`, calling `place(instance, transform)` for each placement.
    /// Returns the number of instances placed.
    #[inline]
    pub fn expand_with(
        &mut self,
        cache: &InstanceCache,
        tree: &CompactTree,
        mut place: impl FnMut(u32, Similarity),
    ) -> Result<usize, InstancingError> {
        let mut walk = std::mem::take(&mut self.framed);
        let placed = self.walk(
            &mut walk,
            cache,
            tree,
            tree.root(),
            |k, instance, desired| {
                place(k, desired.mul(&instance.frame_inverse));
            },
        );
        self.framed = walk;
        placed
    }

    /// The instances one tree places, in the order [`Assembler::expand_with`] places them,
    /// without their transforms: `visit(instance)` for each. For counting a forest's
    /// instances before writing them.
    ///
    /// ```
    /// use sylva_instancing::{build_cache, Assembler, CompactTree, HeroOptions};
    ///
    /// let grammar = sylva_lsys::preset("kenwood-leafy").unwrap().lsystem()?;
    /// let options = HeroOptions::default().with_budget(1 << 20).with_generations(4);
    /// let cache = build_cache(&grammar, &options)?.cache;
    /// let tree = CompactTree { scale: 1.0, seed: 9, ..Default::default() };
    /// let mut assembler = Assembler::new();
    /// let (mut placed, mut visited) = (Vec::new(), Vec::new());
    /// assembler.expand_with(&cache, &tree, |i, _| placed.push(i))?;
    /// assembler.instances_with(&cache, &tree, |i| visited.push(i))?;
    /// assert_eq!(placed, visited);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn instances_with(
        &mut self,
        cache: &InstanceCache,
        tree: &CompactTree,
        mut visit: impl FnMut(u32),
    ) -> Result<usize, InstancingError> {
        let mut walk = std::mem::take(&mut self.bare);
        let placed = self.walk(&mut walk, cache, tree, (), |k, _, ()| visit(k));
        self.bare = walk;
        placed
    }

    /// Kenwood's algorithm 2 with `walk`'s stack, from `root`: chooses each instance of the
    /// tree and calls `place(index, instance, frame)` with the frame D it is placed at (the
    /// instance looked up once, here).
    ///
    /// A whole branch has no exits, so nothing that follows depends on its record: its
    /// placement waits in `walk`'s pending list while the next choices are made, and a run of
    /// up to [`PENDING`] of them is placed together. Their records lie anywhere in a cache of
    /// many megabytes, and read one after another each would wait for memory in turn; read
    /// together, their misses overlap. The placements come out in the same order.
    #[inline]
    fn walk<F: Frame>(
        &mut self,
        walk: &mut Walk<F>,
        cache: &InstanceCache,
        tree: &CompactTree,
        root: F,
        mut place: impl FnMut(u32, &Instance, F),
    ) -> Result<usize, InstancingError> {
        let Walk { stack, pending } = walk;
        stack.clear();
        pending.clear();
        self.used.clear();
        stack.push((ROOT.0, ROOT.1, root, 0));
        let mut placed = 0usize;
        let mut counter = 0u32;
        let walked = loop {
            let Some((id, age, desired, depth)) = stack.pop() else {
                break Ok(placed);
            };
            if depth > self.limits.max_depth {
                break Err(InstancingError::AssemblyLimit("depth"));
            }
            let Candidates {
                indices: candidates,
                whole: complete,
                exits,
            } = cache.candidates_of(id, age);
            if candidates.is_empty() {
                // Heroes guarantee a candidate for every exit; only a foreign cache gets here.
                break Err(InstancingError::AssemblyLimit("missing instance"));
            }
            let chosen = if depth == 0 {
                // The root: a crown with exits when there are any (a whole hero would make
                // every tree that draws it the same tree), so crowns differ from tree to tree.
                let crowns = &candidates[complete.min(candidates.len() - 1)..];
                let crowns = if complete < candidates.len() {
                    crowns
                } else {
                    candidates
                };
                let classes = usize::from(tree.crown_classes);
                let k = if classes > 0 && crowns.len() >= classes {
                    // Only the crowns of this tree's class: indices c, c + K, c + 2K, ...
                    let c = usize::from(tree.crown_class) % classes;
                    let count = (crowns.len() - c).div_ceil(classes);
                    c + pick(tree.seed, counter, count) * classes
                } else {
                    pick(tree.seed, counter, crowns.len())
                };
                counter = counter.wrapping_add(1);
                crowns[k]
            } else if complete > 0 {
                // A whole branch, preferably one this tree does not show yet.
                let start = pick(tree.seed, counter, complete);
                counter = counter.wrapping_add(1);
                let probes = complete.min(REPEAT_PROBES);
                (0..probes)
                    .map(|k| candidates[(start + k * (complete / probes)) % complete])
                    // Past a few dozen placements the check would cost more than a repeat.
                    .find(|c| self.used.len() > 64 || !self.used.contains(c))
                    .unwrap_or(candidates[start])
            } else {
                // No whole branch of this key: the fewest-exit of a few random candidates.
                let mut best = pick(tree.seed, counter, candidates.len());
                for k in 1..self.limits.choices.max(1) {
                    let other = pick(tree.seed, counter.wrapping_add(k), candidates.len());
                    if exits[other] < exits[best] {
                        best = other;
                    }
                }
                counter = counter.wrapping_add(self.limits.choices.max(1));
                candidates[best]
            };
            self.used.push(chosen);
            // Below the root, a key with complete candidates gave one: a whole branch.
            let whole = depth > 0 && complete > 0;
            let instance = if whole {
                pending.push((chosen, desired));
                if pending.len() >= self.batch {
                    place_pending(pending, cache, &mut place);
                }
                None
            } else {
                place_pending(pending, cache, &mut place);
                let instance = &cache.instances[chosen as usize];
                place(chosen, instance, desired);
                Some(instance)
            };
            placed += 1;
            if placed > self.limits.max_instances {
                break Err(InstancingError::AssemblyLimit("instances per tree"));
            }
            for exit in instance.map_or(&[][..], |i| cache.exits_of(i)) {
                stack.push((exit.id, exit.age, desired.then(&exit.frame), depth + 1));
            }
        };
        // What was chosen before the walk ended (or stopped at a limit) is placed, as it
        // was when each placement followed its choice.
        place_pending(pending, cache, &mut place);
        walked
    }

    /// A fingerprint of a tree's composition: the instances it places, in order. Instances
    /// fix their relative transforms, so two trees of one cache with equal fingerprints are
    /// copies of each other up to their root transform.
    pub fn composition(
        &mut self,
        cache: &InstanceCache,
        tree: &CompactTree,
    ) -> Result<u64, InstancingError> {
        let mut h = 0x243f_6a88_85a3_08d3u64;
        self.expand_with(cache, tree, |i, _| h = mix(h ^ u64::from(i)))?;
        Ok(h)
    }

    /// Expands `trees` (all of the species whose cache is `cache`) into grouped placements.
    pub fn expand(
        &mut self,
        cache: &InstanceCache,
        trees: &[CompactTree],
        out: &mut Placements,
    ) -> Result<usize, InstancingError> {
        if out.groups.len() < cache.instances.len() {
            out.groups.resize(cache.instances.len(), Vec::new());
        }
        let mut total = 0;
        for tree in trees {
            let groups = &mut out.groups;
            total += self.expand_with(cache, tree, |i, t| groups[i as usize].push(t))?;
        }
        out.count += total;
        Ok(total)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{HeroOptions, build_cache};
    use proptest::prelude::*;
    use std::sync::OnceLock;

    /// A birch's cache of a budget so small that some keys have no whole branch: their
    /// branches, with exits of their own, follow whole ones in a tree's walk, so that
    /// placing pending branches late would show (in 78 of 200 trees when this was written).
    fn small_cache() -> &'static InstanceCache {
        static CACHE: OnceLock<InstanceCache> = OnceLock::new();
        CACHE.get_or_init(|| {
            let grammar = sylva_lsys::preset("sylva-birch")
                .expect("preset")
                .lsystem()
                .expect("parses");
            let options = HeroOptions::default()
                .with_budget(256 << 10)
                .with_generations(5);
            build_cache(&grammar, &options).expect("fits").cache
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Placing whole branches in runs changes nothing: every tree's placements, and the
        /// instances counted without transforms, are the same bits in the same order as
        /// when each is placed as soon as it is chosen.
        #[test]
        fn pending_branches_place_what_each_choice_placed_at_once(
            seed in any::<u32>(),
            yaw in 0.0f32..6.3,
            scale in 0.5f32..2.0,
            (crown_classes, crown_class) in (0u8..4).prop_flat_map(|n| (Just(n), 0..n.max(1))),
            max_instances in 1usize..16,
        ) {
            let cache = small_cache();
            let tree = CompactTree {
                position: [3.0, 1.0, -2.0],
                yaw,
                scale,
                seed,
                variant: 0,
                crown_class,
                crown_classes,
            };
            // Without a limit, then with one that may stop the walk: what was placed before
            // it stopped is the same too.
            let placements = |batch: usize, max_instances: usize| {
                let mut assembler = Assembler { batch, ..Assembler::new() };
                assembler.limits.max_instances = max_instances;
                let mut out = Vec::new();
                let placed = assembler.expand_with(cache, &tree, |i, t| out.push((i, t)));
                let mut visited = Vec::new();
                let counted = assembler.instances_with(cache, &tree, |i| visited.push(i));
                (format!("{placed:?} {out:?}"), format!("{counted:?} {visited:?}"), out.len())
            };
            for batch in [2, PENDING] {
                prop_assert_eq!(placements(1, max_instances), placements(batch, max_instances));
            }
            let (at_once, visited_at_once, placed) = placements(1, usize::MAX);
            // Trees here place about six instances: runs of two meet the cap, of
            // PENDING end with the walk or at a branch with exits.
            prop_assert!(placed > 2, "a tree of {} placements tests little", placed);
            for batch in [2, PENDING] {
                let (pending, visited, _) = placements(batch, usize::MAX);
                prop_assert_eq!(&at_once, &pending);
                prop_assert_eq!(&visited_at_once, &visited);
            }
        }
    }
}
