//! A forest's configuration: its species, where trees may stand, and the settings of its
//! caches and placement.

use std::sync::Arc;

use crate::patch::Composition;
use crate::species::Species;

/// Where on the terrain trees may stand.
#[derive(Clone)]
#[non_exhaustive]
pub struct Constraints {
    /// Lowest terrain height with trees. Default: no bound (negative infinity).
    pub min_height: f32,
    /// Highest terrain height with trees. Default: no bound (infinity).
    pub max_height: f32,
    /// Steepest slope with trees, in degrees (no trees on cliffs). Default: 35.
    pub max_slope_degrees: f32,
    /// Optional density mask over (x, z), 0 (none) to 1 (full density). Default: none.
    pub mask: Option<Arc<dyn Fn(f32, f32) -> f32 + Send + Sync>>,
}

impl std::fmt::Debug for Constraints {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Constraints")
            .field("min_height", &self.min_height)
            .field("max_height", &self.max_height)
            .field("max_slope_degrees", &self.max_slope_degrees)
            .field("mask", &self.mask.as_ref().map(|_| "fn"))
            .finish()
    }
}

impl Default for Constraints {
    fn default() -> Self {
        Constraints {
            min_height: f32::NEG_INFINITY,
            max_height: f32::INFINITY,
            max_slope_degrees: 35.0,
            mask: None,
        }
    }
}

/// Everything that decides a forest apart from the terrain and the region.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ForestConfig {
    /// The species, at least one with positive weight.
    /// No default: the species given to [`ForestConfig::new`].
    pub species: Vec<Species>,
    /// Terrain constraints. Default: [`Constraints::default`].
    pub constraints: Constraints,
    /// World seed. Default: 1.
    pub seed: u64,
    /// Total instance-cache budget in bytes, shared among species by weight (seedlings get a
    /// quarter of each species' share). A share too small for one hero tree is raised to one
    /// hero's bytes, so every species and form is drawn. Default: 64 MiB.
    pub budget: usize,
    /// Random scale variation: scales are uniform in `1 +- scale_variation`. Default: 0.1.
    pub scale_variation: f32,
    /// Minimum canopy spacing as a multiple of the canopy radius. Default: 1.
    pub spacing_factor: f32,
    /// Seedlings proposed per patch. Default: 8.
    pub seedlings_per_patch: u32,
    /// Which species stands at each spot (a paint layer of `sylva-paint`, or your own
    /// [`Composition`]); `None` grows every species everywhere by weight. Default: none.
    pub composition: Option<Arc<dyn Composition>>,
    /// Build a form for every generation of each species and its damaged forms (broken top,
    /// dieback, dead, snag, fallen), for forests of trees of every age: what a
    /// [`Succession`](crate::Succession)'s years are drawn with. Off, each species has its
    /// canopy and its young form. Default: false.
    pub all_ages: bool,
    /// The day of the year (1 to 365) the forest is drawn on: each species'
    /// [`Species::in_season`] that day (spring flush, autumn colour, bare winter crowns,
    /// snow). Canopies are measured on the species as given, so the trees stand in the
    /// same places whatever the day. `None` draws the species as given (summer). Default:
    /// none.
    pub season: Option<f32>,
}

impl ForestConfig {
    /// Sets [`ForestConfig::constraints`].
    #[must_use]
    pub fn with_constraints(mut self, constraints: Constraints) -> Self {
        self.constraints = constraints;
        self
    }

    /// Sets [`ForestConfig::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`ForestConfig::budget`].
    #[must_use]
    pub fn with_budget(mut self, budget: usize) -> Self {
        self.budget = budget;
        self
    }

    /// Sets [`ForestConfig::scale_variation`].
    #[must_use]
    pub fn with_scale_variation(mut self, scale_variation: f32) -> Self {
        self.scale_variation = scale_variation;
        self
    }

    /// Sets [`ForestConfig::spacing_factor`].
    #[must_use]
    pub fn with_spacing_factor(mut self, spacing_factor: f32) -> Self {
        self.spacing_factor = spacing_factor;
        self
    }

    /// Sets [`ForestConfig::all_ages`].
    #[must_use]
    pub fn with_all_ages(mut self, all_ages: bool) -> Self {
        self.all_ages = all_ages;
        self
    }

    /// Sets [`ForestConfig::season`].
    #[must_use]
    pub fn with_season(mut self, day: Option<f32>) -> Self {
        self.season = day;
        self
    }

    /// Sets [`ForestConfig::seedlings_per_patch`].
    #[must_use]
    pub fn with_seedlings_per_patch(mut self, seedlings_per_patch: u32) -> Self {
        self.seedlings_per_patch = seedlings_per_patch;
        self
    }
}

impl ForestConfig {
    /// A configuration with defaults: 64 MB of cache, seed 1, 10% scale variation.
    pub fn new(species: Vec<Species>) -> Self {
        ForestConfig {
            species,
            constraints: Constraints::default(),
            seed: 1,
            budget: 64 << 20,
            scale_variation: 0.1,
            spacing_factor: 1.0,
            seedlings_per_patch: 8,
            composition: None,
            all_ages: false,
            season: None,
        }
    }
}
