//! Forests: caches per species and maturity, trees placed on a terrain, instanced placements.

use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec2;
use sylva_instancing::{Assembler, CompactTree, Placements};
use sylva_terrain::HeightField;

use sylva_base::hash::{mix, unit_f32 as unit};
use sylva_base::range::check;

use crate::config::ForestConfig;
use crate::density::{Candidate, DensityModel, Rect};
use crate::error::ForestError;
use crate::form::TreeForm;
use crate::patch::Composition;
use crate::patch::{PatchDensity, PatchSpecies};
use crate::siting_report::SitingReport;
use crate::species::{Canopy, Species};
use crate::succession::Snapshot;
use crate::variants::Variant;

/// Timings and sizes of a forest build.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[non_exhaustive]
pub struct ForestStats {
    /// Hero creation time.
    pub hero_time: Duration,
    /// Placement time (density model and terrain constraints).
    pub placement_time: Duration,
    /// Bytes of all caches.
    pub cache_bytes: usize,
    /// Hero trees built.
    pub heroes: u32,
}

/// A built forest: caches and compact trees.
#[derive(Debug, Clone)]
pub struct Forest {
    /// The species used.
    pub species: Vec<Species>,
    /// Caches, one per species and maturity, shared with the builder; `CompactTree::variant`
    /// indexes this.
    pub variants: Arc<[Variant]>,
    /// The trees.
    pub trees: Vec<CompactTree>,
    /// Canopy sizes per species.
    pub canopies: Vec<Canopy>,
    /// What it cost.
    pub stats: ForestStats,
}

/// Most seedling slots told apart by crown class: 9 cells x 28 slots fit a `u8`.
const MAX_SEEDLING_SLOTS: u32 = 28;

/// Patch side as a multiple of the species' weighted mean cover diameter
/// ([`Canopy::cover_diameter`]). Trees stand nearly at random, so the ground a canopy hides
/// grows as 1 - exp(-crown cover per ground area), and the trees are mostly smaller than
/// the full-grown ones measured: issue 12's measure (at least 70% foliage seen from above
/// the default forest) needs patches about two thirds of a crown's cover across. Measured
/// on the default forest (issue 50): 0.85 gives 60.6%, 0.75 65.8%, 0.65 73.8%, 0.6 77.0%.
const PATCH_PER_COVER_DIAMETER: f32 = 0.65;

/// The patch side for these species and canopies: the weighted mean cover diameter, grown
/// as the trees are, times [`PATCH_PER_COVER_DIAMETER`]; `None` if no species weighs anything
/// or the crowns measure nothing.
fn patch_side(canopies: &[Canopy], species: &[Species], grown: f32) -> Option<f32> {
    let total: f32 = species.iter().map(|s| s.weight.max(0.0)).sum();
    let mean = canopies
        .iter()
        .zip(species)
        .map(|(c, s)| c.cover_diameter() * grown * s.weight.max(0.0) / total)
        .sum::<f32>();
    (mean.is_finite() && mean > 0.0).then_some(mean * PATCH_PER_COVER_DIAMETER)
}

/// A candidate's crown class and the number of classes of its kind. The plane is cut into
/// cells of side `cell` (at least two canopy radii), coloured 3 x 3 so that a cell and its
/// eight neighbours have nine colours. Canopy trees (one per cell when the density patch is
/// the cell) take their cell's colour, of 9 classes; seedlings take colour and slot, of
/// 9 x `slots` classes. So two trees of one variant closer than two canopy radii always have
/// different classes, and so different crowns.
fn crown_class(candidate: &Candidate, cell: f32, slots: u32) -> (u8, u8) {
    if !(cell.is_finite() && cell > 0.0) {
        return (0, 0);
    }
    let colour = |v: f32| ((v / cell).floor() as i64).rem_euclid(3) as u32;
    let colour = colour(candidate.position.x) + 3 * colour(candidate.position.y);
    if candidate.seedling && slots > 0 {
        let slot = candidate.slot.saturating_sub(1) % slots;
        ((colour + 9 * slot) as u8, (9 * slots) as u8)
    } else {
        (colour as u8, 9)
    }
}

/// Builds the caches once; then generates the trees of any region.
#[derive(Debug, Clone)]
pub struct ForestBuilder {
    config: ForestConfig,
    density: PatchDensity,
    canopies: Vec<Canopy>,
    variants: Arc<[Variant]>,
    /// Per species, its living forms' generations and drawn heights, youngest first
    /// (forests of every age).
    heights: Vec<Vec<(u32, f32)>>,
    /// A year of a forest over time to draw instead of the density model's trees.
    snapshot: Option<Arc<Snapshot>>,
    stats: ForestStats,
}

impl ForestBuilder {
    /// Measures canopies and fills one cache per species and maturity.
    pub fn new(mut config: ForestConfig) -> Result<Self, ForestError> {
        if config.species.is_empty() || !config.species.iter().any(|s| s.weight > 0.0) {
            return Err(ForestError::NoSpecies);
        }
        check(
            "budget",
            config.budget as f64,
            config.budget > 0,
            "a positive number of bytes",
        )?;
        check(
            "scale_variation",
            f64::from(config.scale_variation),
            (0.0..1.0).contains(&config.scale_variation),
            "0 <= scale_variation < 1",
        )?;
        if let Some(composition) = &config.composition {
            check_composition(composition.as_ref(), config.species.len())?;
        }
        let canopies = config
            .species
            .iter()
            .map(Species::canopy)
            .collect::<Result<Vec<_>, _>>()?;
        if let Some((s, _)) = config
            .species
            .iter()
            .zip(&canopies)
            .find(|(s, c)| s.weight > 0.0 && !(c.radius() > 0.0 && c.radius().is_finite()))
        {
            return Err(ForestError::EmptySpecies {
                species: s.name.clone(),
            });
        }
        if let Some(day) = config.season {
            check(
                "season",
                f64::from(day),
                (1.0..=365.0).contains(&day),
                "a day of the year from 1 to 365",
            )?;
            // After the canopies are measured: leaves come and go, the trees stay put.
            for s in &mut config.species {
                *s = s.in_season(day);
            }
        }
        let start = Instant::now();
        let built = crate::variants::build(crate::variants::Plan {
            species: &config.species,
            budget: config.budget,
            seed: config.seed,
            all_ages: config.all_ages,
            seedlings: config.seedlings_per_patch > 0,
        })?;
        let (variants, heroes) = (built.variants, built.heroes);
        // Trees grow up to 1 + variation times their measured size.
        let grown = 1.0 + config.scale_variation;
        let mut density = PatchDensity::new(
            canopies
                .iter()
                .zip(&config.species)
                .map(|(canopy, species)| PatchSpecies {
                    canopy_radius: canopy.radius() * grown,
                    weight: species.weight.max(0.0),
                })
                .collect(),
        );
        // The thesis sizes patches by the widest canopy, which leaves a gap wherever a
        // narrower species stands. Patches are sized instead by the ground a crown's leaves
        // hide seen from above (its cover, as a disc's diameter), weighted by how often each
        // species stands, so that a forest of narrow spires or open pines closes its canopy
        // as a forest of broad oaks does; wide crowns in neighbouring patches are still kept
        // apart by the spacing rule, which goes by their reach.
        if let Some(patch) = patch_side(&canopies, &config.species, grown) {
            density.patch = patch;
        }
        density.spacing_factor = config.spacing_factor;
        density.seedlings_per_patch = config.seedlings_per_patch;
        let stats = ForestStats {
            hero_time: start.elapsed(),
            cache_bytes: variants.iter().map(|v| v.cache.bytes()).sum(),
            heroes,
            ..ForestStats::default()
        };
        Ok(ForestBuilder {
            config,
            density,
            canopies,
            variants: variants.into(),
            heights: built.heights,
            snapshot: None,
            stats,
        })
    }

    /// This builder drawing `snapshot` (a year of a [`Succession`](crate::Succession) of
    /// the same species), or the density model's trees again with `None`, sharing its
    /// caches: every output then draws that year. An error unless the builder has every age
    /// ([`ForestConfig::all_ages`]) and the snapshot's forest had its number of species.
    pub fn with_snapshot(
        &self,
        snapshot: Option<Arc<Snapshot>>,
    ) -> Result<ForestBuilder, ForestError> {
        if let Some(s) = &snapshot {
            if !self.config.all_ages {
                return Err(ForestError::NotAllAges);
            }
            if s.species != self.config.species.len() {
                return Err(ForestError::SnapshotSpecies {
                    snapshot: s.species,
                    forest: self.config.species.len(),
                });
            }
        }
        let mut builder = self.clone();
        builder.snapshot = snapshot;
        Ok(builder)
    }

    /// The snapshot drawn, if one is.
    pub fn snapshot(&self) -> Option<&Snapshot> {
        self.snapshot.as_deref()
    }

    /// The variant drawing `species` in `form`, if the builder has it (every form when
    /// [`ForestConfig::all_ages`] is set; the canopy and young forms otherwise).
    pub fn variant_of(&self, species: usize, form: TreeForm) -> Option<u16> {
        self.variants
            .iter()
            .position(|v| v.species == species && v.form == form)
            .map(|i| i as u16)
    }

    /// How a living tree of `species` that stands `height` metres tall is drawn: the living
    /// form whose drawn tree is the tallest not above 1.1 times `height` (the youngest when
    /// every one is taller), and the scale that makes it `height` tall. `None` unless the
    /// builder has every age.
    ///
    /// ```
    /// use sylva_forest::{ForestBuilder, ForestConfig, Species, TreeForm};
    ///
    /// let config = ForestConfig::new(vec![Species::from_preset("kenwood-leafy", 4)?])
    ///     .with_budget(4 << 20);
    /// let builder = ForestBuilder::new(config.with_all_ages(true))?;
    /// let (young, _) = builder.live_form(0, 0.5).unwrap();
    /// let (old, scale) = builder.live_form(0, 500.0).unwrap();
    /// assert_eq!((young, old), (TreeForm::Live(1), TreeForm::Live(4)));
    /// assert!(scale > 1.0);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn live_form(&self, species: usize, height: f32) -> Option<(TreeForm, f32)> {
        let heights = self.heights.get(species)?;
        let (generations, scale) = crate::variants::pick_live_form(heights, height)?;
        Some((TreeForm::Live(generations), scale))
    }

    /// The living forms of `species` and the drawn height of each, youngest first (forests
    /// of every age; empty otherwise).
    pub fn form_heights(&self, species: usize) -> &[(u32, f32)] {
        self.heights.get(species).map_or(&[], Vec::as_slice)
    }

    /// The caches, one per species and maturity; [`CompactTree::variant`] indexes this.
    pub fn variants(&self) -> &[Variant] {
        &self.variants
    }

    /// The configuration the caches were built from.
    pub fn config(&self) -> &ForestConfig {
        &self.config
    }

    /// The measured canopy of each species.
    pub fn canopies(&self) -> &[Canopy] {
        &self.canopies
    }

    /// What building the caches cost.
    pub fn stats(&self) -> ForestStats {
        self.stats
    }

    /// The density model in use (patch side, radii, weights).
    pub fn density(&self) -> &PatchDensity {
        &self.density
    }

    /// Mutable access to the density model, to tune it before generating.
    pub fn density_mut(&mut self) -> &mut PatchDensity {
        &mut self.density
    }

    /// The trees of `region` on `terrain`: a pure function of (seed, paint layer, region),
    /// seamless between adjacent regions, or the snapshot's there when the builder draws one
    /// ([`ForestBuilder::with_snapshot`]). Trees outside the terrain's bounds are dropped.
    pub fn trees(&self, terrain: &dyn HeightField, region: Rect) -> Vec<CompactTree> {
        self.trees_sited(terrain, region, &mut SitingReport::default())
    }

    /// As [`ForestBuilder::trees`], counting every candidate spot's verdict into `report`.
    pub(crate) fn trees_sited(
        &self,
        terrain: &dyn HeightField,
        region: Rect,
        report: &mut SitingReport,
    ) -> Vec<CompactTree> {
        if let Some(snapshot) = &self.snapshot {
            return self.snapshot_trees_sited(snapshot, terrain, region, report);
        }
        match &self.config.composition {
            Some(composition) => self.trees_with_sited(
                &self.density.composed(composition.as_ref()),
                terrain,
                region,
                report,
            ),
            None => self.trees_with_sited(&self.density, terrain, region, report),
        }
    }

    /// This builder with another composition (or none), sharing its caches: cheap, so a
    /// painting tool can hand each edit's layer to streaming and export. An error when the
    /// composition was made for another number of species.
    pub fn with_composition(
        &self,
        composition: Option<Arc<dyn Composition>>,
    ) -> Result<ForestBuilder, ForestError> {
        if let Some(c) = &composition {
            check_composition(c.as_ref(), self.config.species.len())?;
        }
        let mut builder = self.clone();
        builder.config.composition = composition;
        Ok(builder)
    }

    /// As [`ForestBuilder::trees`] with another density model.
    pub fn trees_with(
        &self,
        density: &dyn DensityModel,
        terrain: &dyn HeightField,
        region: Rect,
    ) -> Vec<CompactTree> {
        self.trees_with_sited(density, terrain, region, &mut SitingReport::default())
    }

    /// As [`ForestBuilder::trees_with`], counting every candidate spot's verdict into
    /// `report`.
    fn trees_with_sited(
        &self,
        density: &dyn DensityModel,
        terrain: &dyn HeightField,
        region: Rect,
        report: &mut SitingReport,
    ) -> Vec<CompactTree> {
        let (lo, hi) = terrain.bounds();
        let region = region.intersect(&Rect::new(lo, hi));
        let mut candidates = Vec::new();
        density.candidates(region, self.config.seed, &mut candidates);
        let c = &self.config.constraints;
        // Crown classes: trees closer than two canopy radii lie in the same or neighbouring
        // cells of this grid, whose classes differ (see `crown_class`).
        let widest = self
            .density
            .species
            .iter()
            .map(|s| s.canopy_radius)
            .fold(0.0f32, f32::max);
        let cell = (2.0 * widest).max(self.density.patch);
        let slots = self.config.seedlings_per_patch.min(MAX_SEEDLING_SLOTS);
        let site = c.site(terrain);
        let trees: Vec<CompactTree> = candidates
            .iter()
            .filter_map(|cand: &Candidate| {
                let Vec2 { x, y: z } = cand.position;
                let sited = site(x, z);
                report.count(sited.map(|_| ()));
                let height = sited.ok()?;
                // A NaN from the mask counts as no trees.
                if let Some(mask) = &c.mask
                    && unit(mix(cand.key ^ 0x5eed)) >= mask(x, z).clamp(0.0, 1.0).max(0.0)
                {
                    report.masked += 1;
                    return None;
                }
                let variant = self
                    .variants
                    .iter()
                    .position(|v| v.species == cand.species && v.seedling == cand.seedling)?;
                let h = mix(cand.key);
                let (crown_class, crown_classes) = crown_class(cand, cell, slots);
                Some(CompactTree {
                    position: [x, height, z],
                    yaw: unit(h) * std::f32::consts::TAU,
                    scale: 1.0 + self.config.scale_variation * (2.0 * unit(mix(h)) - 1.0),
                    seed: (h >> 32) as u32,
                    variant: variant as u16,
                    crown_class,
                    crown_classes,
                })
            })
            .collect();
        report.placed += trees.len() as u64;
        trees
    }

    /// Builds the forest of `region` on `terrain`.
    pub fn build(&self, terrain: &dyn HeightField, region: Rect) -> Forest {
        let start = Instant::now();
        let mut forest = self.forest_of(self.trees(terrain, region));
        forest.stats.placement_time = start.elapsed();
        forest
    }

    /// The forest of `trees` placed by this builder (or by a painter sharing its caches).
    pub fn forest_of(&self, trees: Vec<CompactTree>) -> Forest {
        Forest {
            species: self.config.species.clone(),
            variants: Arc::clone(&self.variants),
            trees,
            canopies: self.canopies.clone(),
            stats: self.stats,
        }
    }
}

/// The placements of one variant's instances, ready for instanced draws.
#[derive(Debug, Clone)]
pub struct VariantPlacements {
    /// Index into [`Forest::variants`].
    pub variant: usize,
    /// Grouped placements of its instances.
    pub placements: Placements,
}

impl Forest {
    /// Expands every tree into placements grouped per variant and instance.
    pub fn placements(&self) -> Result<Vec<VariantPlacements>, ForestError> {
        let mut out: Vec<VariantPlacements> = self
            .variants
            .iter()
            .enumerate()
            .map(|(i, v)| VariantPlacements {
                variant: i,
                placements: Placements::for_cache(&v.cache),
            })
            .collect();
        let mut assembler = Assembler::new();
        for tree in &self.trees {
            let b =
                out.get_mut(tree.variant as usize)
                    .ok_or_else(|| ForestError::UnknownVariant {
                        variant: tree.variant,
                        variants: self.variants.len(),
                    })?;
            let cache = &self.variants[tree.variant as usize].cache;
            let groups = &mut b.placements.groups;
            b.placements.count +=
                assembler.expand_with(cache, tree, |i, t| groups[i as usize].push(t))?;
        }
        Ok(out)
    }
}

/// An error unless `composition` fits a forest of `forest` species.
fn check_composition(composition: &dyn Composition, forest: usize) -> Result<(), ForestError> {
    match composition.species() {
        Some(n) if n != forest => Err(ForestError::CompositionSpecies {
            composition: n,
            forest,
        }),
        _ => Ok(()),
    }
}
