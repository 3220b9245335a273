//! Hero creation: derive and mesh hero trees in instancing form until the budget is used.

use std::time::{Duration, Instant};

use sylva_lsys::{LSystem, Limits, Word};
use sylva_turtle::TurtleOptions;

use crate::cache::InstanceCache;
use crate::error::InstancingError;
use crate::filling::{Filling, HeroGrammar, Schedule};
use crate::rewrite::Markers;

/// Settings for [`build_cache`].
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
    pub budget: usize,
    /// Generations of every tree of the species.
    pub generations: u32,
    /// Seed of the hero trees.
    pub seed: u64,
    /// Instancing probability when the cache is empty.
    pub p_min: f64,
    /// Instancing probability when the cache is full.
    pub p_max: f64,
    /// Most instances registered per (id, age) (Carey's cap). At least 1.
    pub cap_per_key: usize,
    /// Most hero trees derived.
    pub max_heroes: u32,
    /// Consecutive heroes that did not fit before hero creation stops.
    pub max_rejections: u32,
    /// Turtle settings for meshing heroes (the marker symbols are added automatically).
    pub turtle: TurtleOptions,
    /// Marker symbols.
    pub markers: Markers,
    /// Derivation limits per hero.
    pub limits: Limits,
    /// Keep each instance's word (for validation and debugging; counted in the budget).
    pub keep_words: bool,
    /// Share of the budget filled first with whole heroes (probability 0), in `[0, 1]`.
    pub complete_share: f64,
    /// Most branches a hero of the second phase may leave as exits: bounds the placements
    /// per assembled tree to `1 + max_tree_exits`. At least 1.
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
    /// Sets [`HeroOptions::budget`] in bytes.
    pub fn with_budget(mut self, bytes: usize) -> Self {
        self.budget = bytes;
        self
    }

    /// Sets [`HeroOptions::generations`].
    pub fn with_generations(mut self, n: u32) -> Self {
        self.generations = n;
        self
    }

    /// Sets [`HeroOptions::seed`].
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets both ends of the probability schedule.
    pub fn with_probability(mut self, p_min: f64, p_max: f64) -> Self {
        self.p_min = p_min;
        self.p_max = p_max;
        self
    }

    /// Sets [`HeroOptions::turtle`].
    pub fn with_turtle(mut self, turtle: TurtleOptions) -> Self {
        self.turtle = turtle;
        self
    }

    /// Sets [`HeroOptions::cap_per_key`].
    pub fn with_cap(mut self, cap: usize) -> Self {
        self.cap_per_key = cap;
        self
    }

    /// Sets [`HeroOptions::max_heroes`].
    pub fn with_max_heroes(mut self, n: u32) -> Self {
        self.max_heroes = n;
        self
    }

    /// Sets [`HeroOptions::complete_share`] and [`HeroOptions::max_tree_exits`].
    pub fn with_granularity(mut self, complete_share: f64, max_tree_exits: u32) -> Self {
        self.complete_share = complete_share;
        self.max_tree_exits = max_tree_exits;
        self
    }

    /// Sets [`HeroOptions::keep_words`].
    pub fn with_words(mut self, keep: bool) -> Self {
        self.keep_words = keep;
        self
    }
}

/// What hero creation did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[non_exhaustive]
pub struct HeroStats {
    /// Heroes committed to the cache.
    pub heroes: u32,
    /// Heroes derived but too big for what was left of the budget.
    pub rejected: u32,
    /// Wall time of hero creation.
    pub time: Duration,
    /// Bytes used by the cache.
    pub bytes: usize,
    /// Instances registered.
    pub instances: usize,
    /// Exit points stored.
    pub exits: usize,
    /// Instancing probability of the last hero.
    pub final_probability: f64,
    /// Branches introduced at generations 1 to this age may be instanced (A above).
    pub instanced_ages: u32,
}

/// A cache plus, when asked for, each instance's word.
#[derive(Debug, Clone)]
pub struct HeroCache {
    /// The cache.
    pub cache: InstanceCache,
    /// Per instance (same order as `cache.instances`), its word from the start marker to the
    /// stop marker, when [`HeroOptions::keep_words`] was set.
    pub words: Vec<Word>,
    /// What happened.
    pub stats: HeroStats,
}

/// Derives hero trees of `grammar` in instancing form and fills a cache with their instances
/// until the budget is used (Kenwood section 6, Carey 4.4).
///
/// ```
/// use sylva_instancing::{build_cache, HeroOptions};
/// let g = sylva_lsys::preset("kenwood-leafy").unwrap().lsystem().unwrap();
/// let built = build_cache(&g, &HeroOptions::default().with_budget(2 << 20).with_generations(5)).unwrap();
/// assert!(built.cache.bytes() <= 2 << 20);
/// assert!(!built.cache.lookup(0, 0).is_empty()); // there is a whole tree to start from
/// ```
pub fn build_cache(grammar: &LSystem, options: &HeroOptions) -> Result<HeroCache, InstancingError> {
    let start = Instant::now();
    if !(0.0..=1.0).contains(&options.p_min)
        || !(0.0..=1.0).contains(&options.p_max)
        || options.p_min > options.p_max
    {
        return Err(InstancingError::BadParameter(format!(
            "probability schedule {}..{} must lie in [0, 1] and rise",
            options.p_min, options.p_max
        )));
    }
    if options.cap_per_key == 0 || options.generations > 64 {
        return Err(InstancingError::BadParameter(
            "cap_per_key must be at least 1 and generations at most 64".into(),
        ));
    }
    if !(0.0..=1.0).contains(&options.complete_share) || options.max_tree_exits == 0 {
        return Err(InstancingError::BadParameter(format!(
            "complete_share {} must lie in [0, 1] and max_tree_exits {} be at least 1",
            options.complete_share, options.max_tree_exits
        )));
    }
    let mut grammar = HeroGrammar::new(grammar, options)?;
    let mut filling = Filling::new(options.budget, grammar.ids(), options.generations + 1);
    let mut schedule = Schedule::new(options);
    let mut stats = HeroStats::default();
    let mut rejections = 0;
    let mut smallest_rejected = usize::MAX;
    for k in 0..options.max_heroes {
        if filling.used as f64 >= 0.999 * options.budget as f64 {
            break;
        }
        let p = schedule.probability(filling.used, rejections);
        let eligible = schedule.instanced_ages.unwrap_or(0);
        let hero = grammar.hero(k, p, eligible, &filling, options)?;
        let offer = filling.offer(&hero, options);
        if filling.used + offer.bytes > options.budget || offer.is_empty() {
            stats.rejected += 1;
            rejections += 1;
            smallest_rejected = smallest_rejected.min(offer.bytes);
            if rejections >= options.max_rejections {
                break;
            }
            continue;
        }
        rejections = 0;
        schedule.learn(&hero);
        filling.append(&hero, &offer);
        stats.heroes += 1;
        stats.final_probability = p;
    }
    if stats.heroes == 0 {
        return Err(InstancingError::BudgetTooSmall {
            budget: options.budget,
            needed: smallest_rejected.saturating_add(filling.table_bytes()),
        });
    }
    let (cache, words, word_bytes) = filling.finish();
    stats.instanced_ages = schedule.instanced_ages.unwrap_or(0);
    stats.time = start.elapsed();
    stats.bytes = cache.bytes() + word_bytes;
    stats.instances = cache.instances.len();
    stats.exits = cache.exits.len();
    Ok(HeroCache {
        cache,
        words,
        stats,
    })
}

/// The key of a whole tree: branch id 0, introduced at generation 0.
pub(crate) const ROOT: (u32, u32) = (0, 0);
