//! Hero creation: derive and mesh hero trees in instancing form until the budget is used.

use std::time::{Duration, Instant};

use sylva_lsys::{LSystem, Word};

use sylva_base::range::check;

use crate::cache::InstanceCache;
use crate::error::InstancingError;
use crate::filling::{Filling, HeroGrammar, Schedule};
use crate::options::HeroOptions;

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
    check_options(options)?;
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

/// Every setting of `options` in its range.
fn check_options(options: &HeroOptions) -> Result<(), InstancingError> {
    let unit = |p: f64| (0.0..=1.0).contains(&p);
    check("p_min", options.p_min, unit(options.p_min), "in [0, 1]")?;
    check(
        "p_max",
        options.p_max,
        unit(options.p_max) && options.p_max >= options.p_min,
        "in [0, 1] and at least p_min",
    )?;
    check(
        "cap_per_key",
        options.cap_per_key as f64,
        options.cap_per_key > 0,
        "at least 1",
    )?;
    check(
        "generations",
        f64::from(options.generations),
        options.generations <= 64,
        "at most 64",
    )?;
    check(
        "complete_share",
        options.complete_share,
        unit(options.complete_share),
        "in [0, 1]",
    )?;
    check(
        "max_tree_exits",
        f64::from(options.max_tree_exits),
        options.max_tree_exits > 0,
        "at least 1",
    )?;
    Ok(())
}
