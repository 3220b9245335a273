//! Counting a forest without placing it: how often it places each cached instance (the
//! figure a file's layout needs before its placements are written), and how large a world
//! holds a number of canopy trees.

use std::collections::BTreeMap;

use rayon::prelude::*;
use sylva_instancing::{Assembler, CompactTree};
use sylva_terrain::glam::Vec2;
use sylva_terrain::{FlatPlane, HeightField};

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::ForestBuilder;
use crate::stream::{KeepTrees, StreamStats};

/// Patches along each side of the sample [`ForestBuilder::side_for_canopy_trees`] counts.
const SAMPLE_PATCHES: f32 = 40.0;

/// Per variant and cached instance, how many placements a region's forest has of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InstanceCounts {
    /// `counts[variant][instance]`: placements of that instance (saturating at `u32::MAX`).
    pub counts: Vec<Vec<u32>>,
    /// What a stream of the same region would hold: blocks, trees, seedlings, placements.
    pub stats: StreamStats,
}

impl ForestBuilder {
    /// The side of a square world that holds about `n` canopy trees (seedlings not
    /// counted): not every density patch holds one (some are gaps, some hold only
    /// seedlings), so the share that does is counted on flat ground over a sample of 40 x 40
    /// patches. Painted or masked forests hold fewer where their masks leave ground bare.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let side = builder.side_for_canopy_trees(2000);
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(side) };
    /// let trees = builder.trees(&ground, Rect::new(Vec2::ZERO, Vec2::splat(side)));
    /// let canopy = trees.iter().filter(|t| !builder.variants()[t.variant as usize].seedling).count();
    /// assert!((1800..2200).contains(&canopy), "{canopy}");
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn side_for_canopy_trees(&self, n: usize) -> f32 {
        let patch = self.density().patch;
        let side = SAMPLE_PATCHES * patch;
        let ground = FlatPlane {
            height: 0.0,
            min: Vec2::ZERO,
            max: Vec2::splat(side),
        };
        let variants = self.variants();
        let canopy = self
            .trees(&ground, Rect::new(Vec2::ZERO, Vec2::splat(side)))
            .iter()
            .filter(|t| {
                variants
                    .get(usize::from(t.variant))
                    .is_some_and(|v| !v.seedling)
            })
            .count();
        let per_patch = (canopy as f32 / (SAMPLE_PATCHES * SAMPLE_PATCHES)).max(0.01);
        (n as f32 / per_patch).sqrt() * patch
    }

    /// Counts the placements of every instance in the forest of `region` on `terrain`: the
    /// same trees as [`ForestBuilder::stream`], each assembled for which instances it draws
    /// but without their transforms, on every core. The counts equal what streaming the
    /// region and counting its placements gives, at any thread count.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, PlacementBlock, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(100.0) };
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
    /// let counted = builder.count_instances(&ground, region)?;
    /// let mut streamed: Vec<Vec<u32>> = counted.counts.iter().map(|c| vec![0; c.len()]).collect();
    /// let stats = builder.stream(&ground, region, &mut |b: &PlacementBlock| {
    ///     for p in &b.placements {
    ///         streamed[p.variant as usize][p.instance as usize] += 1;
    ///     }
    ///     Ok(())
    /// })?;
    /// assert_eq!(counted.counts, streamed);
    /// assert_eq!(counted.stats, stats);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn count_instances(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
    ) -> Result<InstanceCounts, ForestError> {
        self.count_instances_keeping(terrain, region, &|_, _| Ok(()))
    }

    /// As [`ForestBuilder::count_instances`], handing each block's trees to `keep(block,
    /// trees)` (on the thread that placed them, blocks in any order) so that a second pass
    /// can expand them without placing them again ([`ForestBuilder::stream_map_from`]).
    /// Errors of `keep` stop the count and come back as they were.
    pub fn count_instances_keeping<E: From<ForestError> + Send>(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        keep: &KeepTrees<'_, E>,
    ) -> Result<InstanceCounts, E> {
        let blocks = self.blocks(region)?;
        let variants = self.variants();
        let empty = || InstanceCounts {
            counts: variants
                .iter()
                .map(|v| vec![0; v.cache.instances.len()])
                .collect(),
            stats: StreamStats::default(),
        };
        blocks
            .par_iter()
            .enumerate()
            .try_fold(
                || (empty(), Assembler::new()),
                |(mut tally, mut assembler), (index, &rect)| {
                    let trees = self.trees(terrain, rect);
                    for tree in &trees {
                        let v = usize::from(tree.variant);
                        let (variant, counts) = variants
                            .get(v)
                            .zip(tally.counts.get_mut(v))
                            .ok_or(ForestError::UnknownVariant {
                                variant: tree.variant,
                                variants: variants.len(),
                            })?;
                        let placed = assembler
                            .instances_with(&variant.cache, tree, |i| {
                                if let Some(c) = counts.get_mut(i as usize) {
                                    *c = c.saturating_add(1);
                                }
                            })
                            .map_err(ForestError::from)?;
                        tally.stats.placements += placed;
                        tally.stats.seedlings += usize::from(variant.seedling);
                    }
                    tally.stats.trees += trees.len();
                    tally.stats.blocks += 1;
                    keep(index, &trees)?;
                    Ok::<_, E>((tally, assembler))
                },
            )
            .map(|folded| folded.map(|(tally, _)| tally))
            .try_reduce(empty, |mut a, b| {
                for (x, y) in a.counts.iter_mut().zip(&b.counts) {
                    for (p, q) in x.iter_mut().zip(y) {
                        *p = p.saturating_add(*q);
                    }
                }
                a.stats.blocks += b.stats.blocks;
                a.stats.trees += b.stats.trees;
                a.stats.seedlings += b.stats.seedlings;
                a.stats.placements += b.stats.placements;
                Ok(a)
            })
    }

    /// As [`ForestBuilder::count_instances_keeping`], with every tree's placements counted in
    /// the bin `bin_of(tree)` gives it (a file's cells, say), and each bin's trees counted
    /// per variant. Bins no tree falls in are left out; the bins come in ascending order.
    /// The counts are what streaming the region and counting each placement in its tree's
    /// bin gives, at any thread count.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20);
    /// let builder = ForestBuilder::new(config)?;
    /// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(100.0) };
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
    /// // Two bins: the west half and the east half.
    /// let halves = |t: &sylva_instancing::CompactTree| u32::from(t.position[0] >= 50.0);
    /// let binned = builder.count_instances_binned(&ground, region, &halves, &|_, _| Ok::<_, sylva_forest::ForestError>(()))?;
    /// let whole = builder.count_instances(&ground, region)?;
    /// let sum: u32 = binned.bins.iter().map(|b| b.counts[0].iter().sum::<u32>()).sum();
    /// assert_eq!(sum, whole.counts[0].iter().sum::<u32>());
    /// assert_eq!(binned.stats, whole.stats);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn count_instances_binned<E: From<ForestError> + Send>(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
        bin_of: &(dyn Fn(&CompactTree) -> u32 + Sync),
        keep: &KeepTrees<'_, E>,
    ) -> Result<BinnedCounts, E> {
        let blocks = self.blocks(region)?;
        let variants = self.variants();
        let new_bin = |bin: u32| BinCounts {
            bin,
            counts: variants
                .iter()
                .map(|v| vec![0; v.cache.instances.len()])
                .collect(),
            trees: vec![0; variants.len()],
        };
        let empty = || (BTreeMap::<u32, BinCounts>::new(), StreamStats::default());
        let (bins, stats) = blocks
            .par_iter()
            .enumerate()
            .try_fold(
                || (empty(), Assembler::new()),
                |((mut bins, mut stats), mut assembler), (index, &rect)| {
                    let trees = self.trees(terrain, rect);
                    for tree in &trees {
                        let v = usize::from(tree.variant);
                        let Some(variant) = variants.get(v) else {
                            return Err(ForestError::UnknownVariant {
                                variant: tree.variant,
                                variants: variants.len(),
                            }
                            .into());
                        };
                        let bin = bin_of(tree);
                        let tally = bins.entry(bin).or_insert_with(|| new_bin(bin));
                        let counts = &mut tally.counts[v];
                        let placed = assembler
                            .instances_with(&variant.cache, tree, |i| {
                                if let Some(c) = counts.get_mut(i as usize) {
                                    *c = c.saturating_add(1);
                                }
                            })
                            .map_err(ForestError::from)?;
                        tally.trees[v] = tally.trees[v].saturating_add(1);
                        stats.placements += placed;
                        stats.seedlings += usize::from(variant.seedling);
                    }
                    stats.trees += trees.len();
                    stats.blocks += 1;
                    keep(index, &trees)?;
                    Ok::<_, E>(((bins, stats), assembler))
                },
            )
            .map(|folded| folded.map(|(tally, _)| tally))
            .try_reduce(empty, |(mut a, mut sa), (b, sb)| {
                for (bin, theirs) in b {
                    match a.get_mut(&bin) {
                        None => {
                            a.insert(bin, theirs);
                        }
                        Some(ours) => {
                            for (x, y) in ours.counts.iter_mut().zip(&theirs.counts) {
                                for (p, q) in x.iter_mut().zip(y) {
                                    *p = p.saturating_add(*q);
                                }
                            }
                            for (p, q) in ours.trees.iter_mut().zip(&theirs.trees) {
                                *p = p.saturating_add(*q);
                            }
                        }
                    }
                }
                sa.blocks += sb.blocks;
                sa.trees += sb.trees;
                sa.seedlings += sb.seedlings;
                sa.placements += sb.placements;
                Ok((a, sa))
            })?;
        Ok(BinnedCounts {
            bins: bins.into_values().collect(),
            stats,
        })
    }
}

/// One bin's counts ([`ForestBuilder::count_instances_binned`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BinCounts {
    /// The bin.
    pub bin: u32,
    /// `counts[variant][instance]`: placements of that instance by the bin's trees
    /// (saturating at `u32::MAX`).
    pub counts: Vec<Vec<u32>>,
    /// `trees[variant]`: the bin's trees of that variant.
    pub trees: Vec<u32>,
}

/// Per bin, how many placements of each instance and how many trees of each variant a
/// region's forest has ([`ForestBuilder::count_instances_binned`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct BinnedCounts {
    /// The bins that hold a tree, in ascending order.
    pub bins: Vec<BinCounts>,
    /// What a stream of the same region would hold: blocks, trees, seedlings, placements.
    pub stats: StreamStats,
}
