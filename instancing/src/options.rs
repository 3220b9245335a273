//! Hero creation's settings, and the key of a whole tree.

use sylva_lsys::Limits;
use sylva_turtle::TurtleOptions;

use crate::rewrite::Markers;

/// Settings for [`build_cache`](crate::build_cache).
///
/// **Granularity** (Kenwood: an instance carries its whole branch subtree, so a tree is a few
/// large instances). Hero creation runs in two phases:
///
/// 1. *Whole heroes* fill the first [`HeroOptions::complete_share`] of the budget with
///    instancing probability 0: every branch of every such hero is recorded whole, so each
///    branch key (id, age) gets complete candidates, instances without exits.
/// 2. *Crowns*: later heroes instance only the big branches, those introduced at generations
///    1 to A, where A is the deepest generation at which a whole hero has at most twice
///    [`HeroOptions::max_tree_exits`] branches introduced up to it. Their root instances are a
///    trunk with a few exits each (a root with more than `max_tree_exits` is not kept), and
///    assembly fills every exit with a complete candidate, so a tree is one root placement
///    plus at most `max_tree_exits` branch placements.
///
/// **Probability schedule.** In the second phase hero `k` instances each eligible branch with
/// `P = p_min + (p_max - p_min) * fill`, where `fill` is the fraction of the second phase's
/// budget already used (Kenwood: instancing grows more aggressive as memory becomes scarce).
/// A branch whose (id, age) has no instance in the cache yet is always recorded, never
/// instanced, so every exit of every cached instance has at least one candidate and every
/// assembled tree is complete without deriving anything at assembly time.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct HeroOptions {
    /// Bytes the cache may use: geometry, instance metadata, exits and the lookup table.
    /// Default: 32 MiB.
    pub budget: usize,
    /// Generations of every tree of the species. Default: 6.
    pub generations: u32,
    /// Seed of the hero trees. Default: 0.
    pub seed: u64,
    /// Instancing probability when the cache is empty. Default: 0.3.
    pub p_min: f64,
    /// Instancing probability when the cache is full. Default: 0.95.
    pub p_max: f64,
    /// Most instances registered per (id, age) (Carey's cap). At least 1. Default: 4096.
    pub cap_per_key: usize,
    /// Most hero trees derived. Default: 100,000.
    pub max_heroes: u32,
    /// Consecutive heroes that did not fit before hero creation stops. Default: 4.
    pub max_rejections: u32,
    /// Turtle settings for meshing heroes (the marker symbols are added automatically).
    /// Default: [`TurtleOptions::default`].
    pub turtle: TurtleOptions,
    /// Marker symbols. Default: [`Markers::default`].
    pub markers: Markers,
    /// Derivation limits per hero. Default: [`Limits::DEFAULT`].
    pub limits: Limits,
    /// Keep each instance's word (for validation and debugging; counted in the budget).
    /// Default: false.
    pub keep_words: bool,
    /// Share of the budget filled first with whole heroes (probability 0), in `[0, 1]`.
    /// Default: 0.5.
    pub complete_share: f64,
    /// Most branches a hero of the second phase may leave as exits: bounds the placements
    /// per assembled tree to `1 + max_tree_exits`. At least 1. Default: 12.
    pub max_tree_exits: u32,
}

impl Default for HeroOptions {
    fn default() -> Self {
        HeroOptions {
            budget: 32 << 20,
            generations: 6,
            seed: 0,
            p_min: 0.3,
            p_max: 0.95,
            cap_per_key: 4096,
            max_heroes: 100_000,
            max_rejections: 4,
            turtle: TurtleOptions::default(),
            markers: Markers::default(),
            limits: Limits::default(),
            keep_words: false,
            complete_share: 0.5,
            max_tree_exits: 12,
        }
    }
}

impl HeroOptions {
    /// Sets [`HeroOptions::max_rejections`].
    #[must_use]
    pub fn with_max_rejections(mut self, max_rejections: u32) -> Self {
        self.max_rejections = max_rejections;
        self
    }

    /// Sets [`HeroOptions::markers`].
    #[must_use]
    pub fn with_markers(mut self, markers: Markers) -> Self {
        self.markers = markers;
        self
    }

    /// Sets [`HeroOptions::limits`].
    #[must_use]
    pub fn with_limits(mut self, limits: Limits) -> Self {
        self.limits = limits;
        self
    }
}

impl HeroOptions {
    /// Sets [`HeroOptions::budget`] in bytes.
    #[must_use]
    pub fn with_budget(mut self, bytes: usize) -> Self {
        self.budget = bytes;
        self
    }

    /// Sets [`HeroOptions::generations`].
    #[must_use]
    pub fn with_generations(mut self, n: u32) -> Self {
        self.generations = n;
        self
    }

    /// Sets [`HeroOptions::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets both ends of the probability schedule.
    #[must_use]
    pub fn with_probability(mut self, p_min: f64, p_max: f64) -> Self {
        self.p_min = p_min;
        self.p_max = p_max;
        self
    }

    /// Sets [`HeroOptions::turtle`].
    #[must_use]
    pub fn with_turtle(mut self, turtle: TurtleOptions) -> Self {
        self.turtle = turtle;
        self
    }

    /// Sets [`HeroOptions::cap_per_key`].
    #[must_use]
    pub fn with_cap(mut self, cap: usize) -> Self {
        self.cap_per_key = cap;
        self
    }

    /// Sets [`HeroOptions::max_heroes`].
    #[must_use]
    pub fn with_max_heroes(mut self, n: u32) -> Self {
        self.max_heroes = n;
        self
    }

    /// Sets [`HeroOptions::complete_share`] and [`HeroOptions::max_tree_exits`].
    #[must_use]
    pub fn with_granularity(mut self, complete_share: f64, max_tree_exits: u32) -> Self {
        self.complete_share = complete_share;
        self.max_tree_exits = max_tree_exits;
        self
    }

    /// Sets [`HeroOptions::keep_words`].
    #[must_use]
    pub fn with_words(mut self, keep: bool) -> Self {
        self.keep_words = keep;
        self
    }
}

/// The key of a whole tree: branch id 0, introduced at generation 0.
pub(crate) const ROOT: (u32, u32) = (0, 0);
