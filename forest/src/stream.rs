//! A streamed forest: the region cut into blocks, each block's trees placed and expanded on
//! all cores, and the blocks handed to a consumer in order, so that memory holds the caches
//! and a few blocks whatever the number of trees.

use rayon::prelude::*;
use sylva_instancing::{Assembler, CompactTree, Similarity};
use sylva_terrain::HeightField;
use sylva_terrain::glam::Vec2;

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::ForestBuilder;

/// Most blocks one stream may have: 16 million blocks of 64 x 64 patches is a region far
/// beyond any forest a machine can write; more means a patch size or region that is wrong.
pub const MAX_BLOCKS: usize = 1 << 24;

/// Side of a block, in density patches. Every density decision looks at most three patches
/// away, so a block computes (64 + 6)^2 patches for 64^2 of its own.
pub const BLOCK_PATCHES: f32 = 64.0;

/// One instance of one tree, placed: draw instance `instance` of variant `variant`'s cache at
/// `transform`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// Index into the forest's variants.
    pub variant: u32,
    /// Index into that variant's cache instances.
    pub instance: u32,
    /// Where it goes: T = D * M^-1.
    pub transform: Similarity,
    /// Index of its tree in the block's trees (for the tree's tint, seed or position).
    pub tree: u32,
}

/// Gives the trees of block `block` (of rectangle `rect`): what [`ForestBuilder::trees`]
/// places there, or what an earlier pass kept of it.
pub type TreesOf<'a, E> = dyn Fn(usize, Rect) -> Result<Vec<CompactTree>, E> + Sync + 'a;

/// Takes the trees of block `block` as a first pass placed them
/// ([`ForestBuilder::count_instances_keeping`]).
pub type KeepTrees<'a, E> = dyn Fn(usize, &[CompactTree]) -> Result<(), E> + Sync + 'a;

/// The trees of one block and their placements, in tree order.
#[derive(Debug, Clone)]
pub struct PlacementBlock {
    /// Position of the block in the stream (row-major over the region's blocks).
    pub index: usize,
    /// The part of the region it covers.
    pub region: Rect,
    /// Its trees.
    pub trees: Vec<CompactTree>,
    /// Their placements.
    pub placements: Vec<Placement>,
}

/// Takes a streamed forest block by block, in order. The exporter, the viewer and a user's
/// engine implement it; returning an error stops the stream.
pub trait PlacementSink {
    /// Receives the next block.
    fn block(&mut self, block: &PlacementBlock) -> Result<(), ForestError>;
}

impl<F: FnMut(&PlacementBlock) -> Result<(), ForestError>> PlacementSink for F {
    fn block(&mut self, block: &PlacementBlock) -> Result<(), ForestError> {
        self(block)
    }
}

/// What a stream produced.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct StreamStats {
    /// Blocks handed on.
    pub blocks: usize,
    /// Trees.
    pub trees: usize,
    /// Trees of the seedling variants.
    pub seedlings: usize,
    /// Placements.
    pub placements: usize,
}

impl ForestBuilder {
    /// The blocks `region` is cut into, row-major; their union is the region, and each point
    /// belongs to exactly one. An error when there would be more than [`MAX_BLOCKS`] (a
    /// patch far too small for the region), checked before anything is allocated.
    pub fn blocks(&self, region: Rect) -> Result<Vec<Rect>, ForestError> {
        if region.is_empty() {
            return Ok(Vec::new());
        }
        let side = self.density().patch * BLOCK_PATCHES;
        let size = region.max - region.min;
        let (fx, fz) = ((size.x / side).ceil(), (size.y / side).ceil());
        if !(side.is_finite() && side > 0.0 && f64::from(fx) * f64::from(fz) <= MAX_BLOCKS as f64) {
            return Err(ForestError::TooManyBlocks {
                size,
                patch: self.density().patch,
                limit: MAX_BLOCKS,
            });
        }
        let (nx, nz) = (fx as usize, fz as usize);
        let mut out = Vec::with_capacity(nx * nz);
        for j in 0..nz {
            for i in 0..nx {
                // A block ends exactly where the next begins (the same expression), so no
                // tree falls between blocks or into two; the last row and column end at the
                // region's edge.
                let edge = |k: usize, n: usize, lo: f32, hi: f32| {
                    if k >= n {
                        hi
                    } else {
                        (lo + k as f32 * side).min(hi)
                    }
                };
                let min = Vec2::new(
                    edge(i, nx, region.min.x, region.max.x),
                    edge(j, nz, region.min.y, region.max.y),
                );
                let max = Vec2::new(
                    edge(i + 1, nx, region.min.x, region.max.x),
                    edge(j + 1, nz, region.min.y, region.max.y),
                );
                out.push(Rect::new(min, max));
            }
        }
        Ok(out)
    }

    /// One block: its trees and the placements of those whose variant `expand` accepts.
    pub fn block(
        &self,
        terrain: &dyn HeightField,
        index: usize,
        region: Rect,
        expand: &(dyn Fn(u16) -> bool + Sync),
        assembler: &mut Assembler,
    ) -> Result<PlacementBlock, ForestError> {
        let trees = self.trees(terrain, region);
        self.block_of(index, region, trees, expand, assembler, Vec::new())
    }

    /// The block of `trees` (those of `region`, as [`ForestBuilder::trees`] gives them, kept
    /// from an earlier pass perhaps) with the placements of those whose variant `expand`
    /// accepts, written into `placements` (emptied first: an earlier block's, whose memory
    /// is in use and so costs no page faults).
    fn block_of(
        &self,
        index: usize,
        region: Rect,
        trees: Vec<CompactTree>,
        expand: &(dyn Fn(u16) -> bool + Sync),
        assembler: &mut Assembler,
        mut placements: Vec<Placement>,
    ) -> Result<PlacementBlock, ForestError> {
        placements.clear();
        placements.reserve(trees.len() * 8);
        let variants = self.variants();
        for (position, tree) in trees.iter().enumerate().filter(|(_, t)| expand(t.variant)) {
            let variant = u32::from(tree.variant);
            let cache = &variants
                .get(usize::from(tree.variant))
                .ok_or(ForestError::UnknownVariant {
                    variant: tree.variant,
                    variants: variants.len(),
                })?
                .cache;
            assembler.expand_with(cache, tree, |instance, transform| {
                placements.push(Placement {
                    variant,
                    instance,
                    transform,
                    tree: position as u32,
                });
            })?;
        }
        Ok(PlacementBlock {
            index,
            region,
            trees,
            placements,
        })
    }

    /// Streams the forest of `region` on `terrain` to `sink`, block by block in row-major
    /// order. Blocks are placed and expanded in parallel (rayon), a few per thread at a
    /// time; what the sink receives is the same, byte for byte, at any thread count.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, PlacementBlock, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let mut leafy = Species::from_preset("kenwood-leafy", 4)?;
    /// leafy.turtle.step = 0.5;
    /// let config = ForestConfig::new(vec![leafy]).with_budget(4 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(500.0) };
    /// let mut trees = 0;
    /// let stats = builder.stream(&ground, Rect::new(Vec2::ZERO, Vec2::splat(500.0)), &mut |b: &PlacementBlock| {
    ///     trees += b.trees.len();
    ///     Ok(())
    /// })?;
    /// assert_eq!(stats.trees, trees);
    /// assert!(stats.placements >= trees);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn stream(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        sink: &mut dyn PlacementSink,
    ) -> Result<StreamStats, ForestError> {
        self.stream_variants(terrain, region, &|_| true, sink)
    }

    /// As [`ForestBuilder::stream`], expanding only the trees whose variant `expand` accepts
    /// (every tree is still placed and handed on): a consumer that needs the placements of a
    /// few variants at a time skips the work for the others.
    pub fn stream_variants(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        expand: &(dyn Fn(u16) -> bool + Sync),
        sink: &mut dyn PlacementSink,
    ) -> Result<StreamStats, ForestError> {
        self.stream_with(terrain, region, expand, &mut |block| sink.block(block))
    }

    /// As [`ForestBuilder::stream_variants`], into a sink whose errors are its own: a
    /// consumer that fails for reasons of its own (a file it writes, a placement it refuses)
    /// stops the stream with its error, which comes back as it was.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, ForestError, PlacementBlock, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// #[derive(Debug)]
    /// enum MyError { Forest(ForestError), Full }
    /// impl From<ForestError> for MyError {
    ///     fn from(e: ForestError) -> Self { MyError::Forest(e) }
    /// }
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(400.0) };
    /// let mut kept = 0;
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(400.0));
    /// let stopped = builder.stream_with(&ground, region, &|_| true, &mut |b: &PlacementBlock| {
    ///     kept += b.placements.len();
    ///     if kept > 1000 { Err(MyError::Full) } else { Ok(()) }
    /// });
    /// assert!(matches!(stopped, Err(MyError::Full)));
    /// # Ok::<(), ForestError>(())
    /// ```
    pub fn stream_with<E: From<ForestError>>(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        expand: &(dyn Fn(u16) -> bool + Sync),
        sink: &mut dyn FnMut(&PlacementBlock) -> Result<(), E>,
    ) -> Result<StreamStats, E> {
        let blocks = self.blocks(region)?;
        let wave = wave_size();
        let mut stats = StreamStats::default();
        let placed = |_: usize, rect: Rect| Ok::<_, ForestError>(self.trees(terrain, rect));
        // The sink only borrows each block, so its placements' buffer is handed to a block of
        // the next wave: a wave's worth of buffers, megabytes each, stays in use rather than
        // being freed and faulted in again, block after block.
        let mut spare: Vec<Vec<Placement>> = Vec::new();
        for (w, rects) in blocks.chunks(wave).enumerate() {
            let buffers = (0..rects.len()).map(|_| spare.pop().unwrap_or_default());
            let done = self.place_wave(rects, w * wave, buffers.collect(), &placed, expand, &|b| b);
            let mut keep = |block: PlacementBlock| -> Result<(), E> {
                sink(&block)?;
                spare.push(block.placements);
                Ok(())
            };
            drain(done, &mut stats, &mut keep)?;
        }
        Ok(stats)
    }

    /// As [`ForestBuilder::stream_with`], turning each block into a `T` with `map` on the
    /// thread that placed it, so that a consumer's own per-block work (converting placements
    /// for a file, say) runs on every core; `sink` gets the `T`s in block order, one wave of
    /// blocks while the next is placed.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, ForestError, PlacementBlock, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(200.0) };
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(200.0));
    /// let mut counts = Vec::new();
    /// let count = |b: PlacementBlock| b.placements.len();
    /// let stats = builder.stream_map::<_, ForestError>(&ground, region, &|_| true, &count, &mut |n| {
    ///     counts.push(n);
    ///     Ok(())
    /// })?;
    /// assert_eq!(counts.iter().sum::<usize>(), stats.placements);
    /// # Ok::<(), ForestError>(())
    /// ```
    pub fn stream_map<T: Send, E: From<ForestError> + Send>(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        expand: &(dyn Fn(u16) -> bool + Sync),
        map: &(dyn Fn(PlacementBlock) -> T + Sync),
        sink: &mut (dyn FnMut(T) -> Result<(), E> + Send),
    ) -> Result<StreamStats, E> {
        let placed = |_: usize, rect: Rect| Ok(self.trees(terrain, rect));
        self.stream_map_from(region, &placed, expand, map, sink)
    }

    /// As [`ForestBuilder::stream_map`], with each block's trees from `trees_of(block, rect)`
    /// instead of placed anew: the trees an earlier pass kept
    /// ([`ForestBuilder::count_instances_keeping`]), which must be what
    /// [`ForestBuilder::trees`] gives for that block's rectangle. Placing trees is most of a
    /// stream's work; a writer that streams a forest twice places them once.
    pub fn stream_map_from<T: Send, E: From<ForestError> + Send>(
        &self,
        region: Rect,
        trees_of: &TreesOf<'_, E>,
        expand: &(dyn Fn(u16) -> bool + Sync),
        map: &(dyn Fn(PlacementBlock) -> T + Sync),
        sink: &mut (dyn FnMut(T) -> Result<(), E> + Send),
    ) -> Result<StreamStats, E> {
        let blocks = self.blocks(region)?;
        let wave = wave_size();
        let mut stats = StreamStats::default();
        let mut pending: Vec<Result<(StreamStats, T), E>> = Vec::new();
        for (w, rects) in blocks.chunks(wave).enumerate() {
            let (done, sunk) = rayon::join(
                || self.place_wave(rects, w * wave, Vec::new(), trees_of, expand, map),
                || drain(std::mem::take(&mut pending), &mut stats, sink),
            );
            sunk?;
            pending = done;
        }
        drain(pending, &mut stats, sink)?;
        Ok(stats)
    }

    /// The blocks `rects` (numbered from `first`, their trees from `trees_of`) expanded on
    /// every core, each turned into a `T` by `map` where it was placed, with what it held.
    /// Block `k`'s placements go into `buffers[k]` when there is one.
    fn place_wave<T: Send, E: From<ForestError> + Send>(
        &self,
        rects: &[Rect],
        first: usize,
        mut buffers: Vec<Vec<Placement>>,
        trees_of: &TreesOf<'_, E>,
        expand: &(dyn Fn(u16) -> bool + Sync),
        map: &(dyn Fn(PlacementBlock) -> T + Sync),
    ) -> Vec<Result<(StreamStats, T), E>> {
        let variants = self.variants();
        buffers.resize_with(rects.len(), Vec::new);
        (rects.par_iter().zip(buffers).enumerate())
            .map_init(Assembler::new, |assembler, (k, (&rect, buffer))| {
                let trees = trees_of(first + k, rect)?;
                let block = self.block_of(first + k, rect, trees, expand, assembler, buffer)?;
                let seedlings = block
                    .trees
                    .iter()
                    .filter(|t| {
                        variants
                            .get(usize::from(t.variant))
                            .is_some_and(|v| v.seedling)
                    })
                    .count();
                let held = StreamStats {
                    blocks: 1,
                    trees: block.trees.len(),
                    seedlings,
                    placements: block.placements.len(),
                };
                Ok((held, map(block)))
            })
            .collect()
    }
}

/// Blocks placed at once: six per thread, so that a slow block does not idle the others (a
/// wave waits for its slowest block; at two per thread a million-tree export ran 20% slower),
/// while two waves' placements stay within about 150 MB (at eight per thread the export's
/// peak memory neared 350 MB).
fn wave_size() -> usize {
    rayon::current_num_threads().max(1) * 6
}

/// Hands a wave's blocks to `sink` in order, adding what they held to `stats`; the first
/// error stops it.
fn drain<T, D, E: From<D>>(
    done: Vec<Result<(StreamStats, T), D>>,
    stats: &mut StreamStats,
    sink: &mut dyn FnMut(T) -> Result<(), E>,
) -> Result<(), E> {
    for block in done {
        let (held, mapped) = block?;
        stats.blocks += held.blocks;
        stats.trees += held.trees;
        stats.seedlings += held.seedlings;
        stats.placements += held.placements;
        sink(mapped)?;
    }
    Ok(())
}
