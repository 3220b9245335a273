//! The builder that turns species, settings and ground into a [`World`]: a forest ready for
//! any writer (glTF, USD, 3D Tiles, an engine's own instancing). The world layer does not
//! depend on the writers, so it builds beside them. The CLI, the viewer and the
//! server each build their worlds here, so one description makes one forest everywhere.

use std::path::PathBuf;
use std::sync::Arc;

use sylva_forest::succession::Succession;
use sylva_forest::{
    Composition, Constraints, ForestBuilder, ForestConfig, Rect, SitingReport, Species,
};
use sylva_paint::PaintLayer;

use crate::error::WorldError;
use crate::ground::Ground;
use crate::limits::{
    BUDGET_BYTES_PER_CANOPY_TREE, CANOPY_TREES_PER_HECTARE, DEFAULT_BUDGET_MB, MAX_DENSITY,
    MAX_YEARS, MIN_SIZED_BUDGET_MB,
};
use crate::progress::{Progress, Stage, timed};

/// How to build a world: its species and the settings that shape its forest. Public fields
/// with a `with_*` method each; [`WorldBuilder::build`] makes the world on a [`Ground`].
///
/// ```
/// use sylva_world::{Ground, Quiet, WorldBuilder};
///
/// let species = sylva_world::presets::species()?[..2].to_vec();
/// let world = WorldBuilder::new(species)
///     .with_seed(7)
///     .with_budget(4 << 20)
///     .build(Ground::generated(7, 120.0)?, &Quiet)?;
/// assert!(!world.forest.trees(&world.ground.map, world.region()).is_empty());
/// # Ok::<(), sylva_world::WorldError>(())
/// ```
#[derive(Debug, Clone)]
#[must_use]
pub struct WorldBuilder {
    /// The species. Required.
    pub species: Vec<Species>,
    /// World seed. Default: 1.
    pub seed: u64,
    /// Instance-cache budget in bytes, shared among the species. Default: `None`, sized to
    /// the forest ([`WorldBuilder::budget_for`]).
    pub budget: Option<usize>,
    /// Canopy trees per hectare. Default: `None`, the species' own spacing.
    pub density: Option<f32>,
    /// Where on the terrain trees may stand. Default: [`Constraints::default`].
    pub constraints: Constraints,
    /// Draw year N of a forest over time grown from bare ground (trees of every age, dead,
    /// broken and fallen ones) instead of the density model's forest. Default: `None`.
    pub year: Option<u32>,
    /// A folder of painted masks (as `sylva paint` and the viewer save them) that decide
    /// where each species grows. Default: `None`.
    pub masks: Option<PathBuf>,
    /// Whether seedlings grow under the canopy. Default: `true`.
    pub seedlings: bool,
    /// The day of the year the forest is drawn on ([`ForestConfig::season`]): leaves,
    /// autumn colour, bare crowns and snow as that day has them. Default: `None` (summer).
    pub season: Option<f32>,
}

impl WorldBuilder {
    /// A world of `species` with every other setting at its default.
    pub fn new(species: Vec<Species>) -> WorldBuilder {
        WorldBuilder {
            species,
            seed: 1,
            budget: None,
            density: None,
            constraints: Constraints::default(),
            year: None,
            masks: None,
            seedlings: true,
            season: None,
        }
    }

    /// Sets [`WorldBuilder::seed`].
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`WorldBuilder::budget`] to `bytes`.
    pub fn with_budget(mut self, bytes: usize) -> Self {
        self.budget = Some(bytes);
        self
    }

    /// Canopy trees a region of `hectares` is expected to hold before its forest is placed:
    /// at [`WorldBuilder::density`], or at the bundled species' spacing
    /// ([`CANOPY_TREES_PER_HECTARE`]).
    ///
    /// ```
    /// use sylva_world::WorldBuilder;
    /// let recipe = WorldBuilder::new(Vec::new()).with_density(Some(50.0));
    /// assert_eq!(recipe.canopy_trees_on(4.0), 200.0);
    /// ```
    pub fn canopy_trees_on(&self, hectares: f64) -> f64 {
        hectares * f64::from(self.density.unwrap_or(CANOPY_TREES_PER_HECTARE))
    }

    /// Canopy trees a world is expected to hold, to size its budget before its forest is
    /// placed: on `ground` when it is known; else `trees` when the world is sized for them
    /// (its side follows, [`ForestBuilder::side_for_canopy_trees`]); else on a square of
    /// `side` metres. The `sylva` command and the viewer ask this one question.
    ///
    /// ```
    /// use sylva_world::WorldBuilder;
    /// let recipe = WorldBuilder::new(Vec::new()).with_density(Some(100.0));
    /// assert_eq!(recipe.canopy_trees_expected(None, Some(5_000), 800.0), 5_000.0);
    /// assert_eq!(recipe.canopy_trees_expected(None, None, 200.0), 400.0);
    /// ```
    pub fn canopy_trees_expected(
        &self,
        ground: Option<&Ground>,
        trees: Option<usize>,
        side: f32,
    ) -> f64 {
        match (ground, trees) {
            (Some(ground), _) => self.canopy_trees_on(ground.hectares()),
            (None, Some(n)) => n as f64,
            (None, None) => self.canopy_trees_on(f64::from(side).powi(2) / 1e4),
        }
    }

    /// The instance-cache budget of a forest of `canopy_trees`: [`WorldBuilder::budget`] when
    /// given, else [`BUDGET_BYTES_PER_CANOPY_TREE`] a tree, from [`MIN_SIZED_BUDGET_MB`] up to
    /// [`DEFAULT_BUDGET_MB`]. Heroes follow the budget, so a small forest is drawn from few
    /// hero trees and its file is small; a species' share too small for one hero is raised
    /// to one ([`sylva_forest::ForestConfig::budget`]).
    ///
    /// ```
    /// use sylva_world::WorldBuilder;
    /// let sized = WorldBuilder::new(Vec::new());
    /// assert_eq!(sized.budget_for(18_400.0), 32 << 20);
    /// assert_eq!(sized.budget_for(290.0), 6 << 20);
    /// assert_eq!(sized.budget_for(4_000.0), 4_000 << 11);
    /// assert_eq!(sized.with_budget(4 << 20).budget_for(290.0), 4 << 20);
    /// ```
    pub fn budget_for(&self, canopy_trees: f64) -> usize {
        let [floor, cap] =
            [MIN_SIZED_BUDGET_MB, DEFAULT_BUDGET_MB].map(|mb| mb as usize * (1 << 20));
        self.budget.unwrap_or_else(|| {
            let sized = canopy_trees.max(0.0) * BUDGET_BYTES_PER_CANOPY_TREE as f64;
            (sized.min(cap as f64) as usize).max(floor)
        })
    }

    /// Sets [`WorldBuilder::density`].
    pub fn with_density(mut self, trees_per_hectare: Option<f32>) -> Self {
        self.density = trees_per_hectare;
        self
    }

    /// Sets [`WorldBuilder::constraints`].
    pub fn with_constraints(mut self, constraints: Constraints) -> Self {
        self.constraints = constraints;
        self
    }

    /// Sets [`WorldBuilder::season`].
    pub fn with_season(mut self, day: Option<f32>) -> Self {
        self.season = day;
        self
    }

    /// Sets [`WorldBuilder::year`].
    pub fn with_year(mut self, year: Option<u32>) -> Self {
        self.year = year;
        self
    }

    /// Sets [`WorldBuilder::masks`].
    pub fn with_masks(mut self, folder: Option<PathBuf>) -> Self {
        self.masks = folder;
        self
    }

    /// Sets [`WorldBuilder::seedlings`].
    pub fn with_seedlings(mut self, seedlings: bool) -> Self {
        self.seedlings = seedlings;
        self
    }

    /// Every setting in its range: checked before seconds of hero trees are spent.
    pub fn check(&self) -> Result<(), WorldError> {
        let bad = |m: String| Err(WorldError::Invalid(m));
        if self.species.is_empty() {
            return bad("a world needs at least one species".into());
        }
        if self.budget == Some(0) {
            return bad("an instance-cache budget of 0 bytes: expected at least 1 MiB".into());
        }
        if let Some(d) = self.density
            && !(d > 0.0 && d <= MAX_DENSITY)
        {
            return bad(format!(
                "density {d}: expected 0 < trees per hectare <= {MAX_DENSITY}"
            ));
        }
        if let Some(year) = self.year
            && year > MAX_YEARS
        {
            return bad(format!("year {year}: expected 0 to {MAX_YEARS}"));
        }
        Ok(())
    }

    /// The recipe of a forest of about `canopy_trees` canopy trees (which size its budget,
    /// [`WorldBuilder::budget_for`]): the species' instance caches from hero trees
    /// (seconds), at the density asked for. No ground is needed yet: its side may follow
    /// from the density ([`ForestBuilder::side_for_canopy_trees`]).
    pub fn forest(
        &self,
        canopy_trees: f64,
        progress: &dyn Progress,
    ) -> Result<ForestBuilder, WorldError> {
        self.check()?;
        let mut config = ForestConfig::new(self.species.clone())
            .with_seed(self.seed)
            .with_budget(self.budget_for(canopy_trees))
            .with_all_ages(self.year.is_some())
            .with_season(self.season)
            .with_constraints(self.constraints.clone());
        if !self.seedlings {
            config.seedlings_per_patch = 0;
        }
        let (builder, _) = timed(progress, Stage::HeroTrees, || ForestBuilder::new(config));
        let mut builder = builder?;
        if let Some(d) = self.density {
            builder.density_mut().patch = density_patch(d);
        }
        Ok(builder)
    }

    /// The world of `forest` (from [`WorldBuilder::forest`]) on `ground`: painted with the
    /// masks, grown to the year.
    pub fn finish(
        &self,
        forest: ForestBuilder,
        ground: Ground,
        progress: &dyn Progress,
    ) -> Result<World, WorldError> {
        let mut forest = forest;
        let mut layer = None;
        if let Some(folder) = &self.masks {
            let (loaded, _) = timed(progress, Stage::Painting, || {
                sylva_paint::load_masks_for(&forest, folder, &ground.map)
            });
            let loaded = Arc::new(loaded?);
            let composition: Arc<dyn Composition> = loaded.clone();
            forest = forest.with_composition(Some(composition))?;
            layer = Some(loaded);
        }
        let mut succession = None;
        if let Some(year) = self.year {
            let (grown, _) = timed(progress, Stage::Years, || {
                let mut years = forest.succession(ground.region())?;
                for done in 0..year {
                    years.step()?;
                    progress.years(done + 1, year);
                }
                let drawn = forest.drawing(&years)?;
                Ok::<_, WorldError>((years, drawn))
            });
            let (years, drawn) = grown?;
            forest = drawn;
            succession = Some(years);
        }
        Ok(World {
            forest,
            ground,
            seed: self.seed,
            layer,
            succession,
        })
    }

    /// [`WorldBuilder::forest`] then [`WorldBuilder::finish`] on `ground`.
    pub fn build(&self, ground: Ground, progress: &dyn Progress) -> Result<World, WorldError> {
        let forest = self.forest(self.canopy_trees_on(ground.hectares()), progress)?;
        self.finish(forest, ground, progress)
    }
}

/// The side of the density model's patch for `trees_per_hectare` canopy trees: one
/// canopy tree stands in each patch.
///
/// ```
/// assert_eq!(sylva_world::density_patch(100.0), 10.0);
/// ```
pub fn density_patch(trees_per_hectare: f32) -> f32 {
    (10_000.0 / trees_per_hectare).sqrt()
}

/// A world ready for any writer: its forest's recipe, its ground, and what made them.
#[derive(Debug, Clone)]
pub struct World {
    /// The forest's recipe: instance caches, placement, composition.
    pub forest: ForestBuilder,
    /// The ground.
    pub ground: Ground,
    /// The world seed.
    pub seed: u64,
    /// The painted layer the forest is composed by, if masks were given.
    pub layer: Option<Arc<PaintLayer>>,
    /// The forest over time the trees come from, at its year, if a year was asked for.
    pub succession: Option<Succession>,
}

impl World {
    /// The world's region on its ground.
    pub fn region(&self) -> Rect {
        self.ground.region()
    }

    /// The world's longer side, metres.
    pub fn side(&self) -> f32 {
        self.ground.side()
    }

    /// What the terrain makes of the candidate tree spots (slopes, heights, masks).
    pub fn siting(&self) -> Result<SitingReport, WorldError> {
        Ok(self.forest.siting(&self.ground.map, self.region())?)
    }
}
