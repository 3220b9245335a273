//! Hero creation: derive and mesh hero trees in instancing form until the budget is used.

use std::time::{Duration, Instant};

use sylva_lsys::{LSystem, Limits, Word};
use sylva_turtle::{Command, TurtleOptions, interpret};

use crate::cache::{CANDIDATE_BYTES, EXIT_BYTES, INSTANCE_BYTES, Instance, InstanceCache};
use crate::error::InstancingError;
use crate::recorder::HeroRecorder;
use crate::rewrite::{InstancingGrammar, Markers, probability_at_ages};
use crate::span::Span;
use sylva_base::hash::mix;

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
    let ig = InstancingGrammar::new(grammar, options.markers)?;
    let mut turtle = options.turtle.clone();
    for c in [
        options.markers.start,
        options.markers.stop,
        options.markers.get,
    ] {
        turtle.symbols.set(c, Command::Marker);
    }
    let ids = ig.branch_count() + 1;
    let ages = options.generations + 1;
    let mut cache = InstanceCache::new(options.budget);
    let table_bytes = (ids * ages) as usize * 8;
    let mut lists: Vec<Vec<u32>> = vec![Vec::new(); (ids * ages) as usize];
    let mut words = Vec::new();
    let mut word_bytes = 0usize;
    let mut used = table_bytes;
    let mut stats = HeroStats::default();
    let mut rejections = 0;
    let mut smallest_rejected = usize::MAX;
    let mut grammar_cache: Option<(u64, Vec<Vec<u32>>, LSystem)> = None;
    // Known after the first (whole) hero: the branches introduced up to this age are eligible.
    let mut instanced_ages: Option<u32> = None;
    let whole_budget = options.budget as f64 * options.complete_share;
    for k in 0..options.max_heroes {
        let fill = used as f64 / options.budget.max(1) as f64;
        if fill >= 0.999 {
            break;
        }
        let p = match instanced_ages {
            Some(_) if (used as f64) >= whole_budget => {
                let crowns = ((used as f64 - whole_budget)
                    / (options.budget as f64 - whole_budget).max(1.0))
                .clamp(0.0, 1.0);
                if rejections > 0 {
                    options.p_max
                } else {
                    options.p_min + (options.p_max - options.p_min) * crowns
                }
            }
            _ => 0.0,
        };
        let eligible = instanced_ages.unwrap_or(0);
        // Rebuild the rewritten grammar only when the probability (in steps of 1/64) or the
        // set of known (id, age) keys changed.
        let p_step = (p * 64.0).round() as u64;
        let known: Vec<Vec<u32>> = (0..ids)
            .map(|id| {
                (1..ages.min(eligible + 1))
                    .filter(|&a| !lists[(id * ages + a) as usize].is_empty())
                    .collect()
            })
            .collect();
        let reuse = matches!(&grammar_cache, Some((s, kn, _)) if *s == p_step && *kn == known);
        if !reuse {
            let q = p_step as f64 / 64.0;
            let g = ig.compact(|id| probability_at_ages(q, &known[id as usize]))?;
            grammar_cache = Some((p_step, known, g));
        }
        let Some((_, _, g)) = &grammar_cache else {
            unreachable!("just set")
        };
        let word = g.derive_with(
            options.generations,
            mix(options.seed ^ mix(u64::from(k))),
            &options.limits,
        )?;
        let mut rec = HeroRecorder::new(&turtle, options.markers);
        interpret(&word, &turtle, &mut rec)?;
        let mesh = &rec.builder.mesh;
        let accepted: Vec<usize> = {
            let mut extra = vec![0usize; lists.len()];
            (0..rec.instances.len())
                .filter(|&i| {
                    let r = &rec.instances[i];
                    if r.id >= ids || r.age >= ages {
                        return false;
                    }
                    // A crown with more exits than a tree may have placements is not kept
                    // as a root; its branches still are.
                    if (r.id, r.age) == ROOT && r.exits.count > options.max_tree_exits {
                        return false;
                    }
                    let slot = (r.id * ages + r.age) as usize;
                    let ok = lists[slot].len() + extra[slot] < options.cap_per_key;
                    extra[slot] += usize::from(ok);
                    ok
                })
                .collect()
        };
        let exit_count: usize = accepted
            .iter()
            .map(|&i| rec.instances[i].exits.count as usize)
            .sum();
        let hero_words: Vec<Word> = if options.keep_words {
            instance_words(&word, &options.markers)
        } else {
            Vec::new()
        };
        let new_word_bytes: usize = accepted
            .iter()
            .filter_map(|&i| hero_words.get(rec.instances[i].start_order as usize))
            .map(Word::heap_bytes)
            .sum();
        let needed = mesh.byte_size()
            + accepted.len() * (INSTANCE_BYTES + CANDIDATE_BYTES)
            + exit_count * EXIT_BYTES
            + new_word_bytes;
        if used + needed > options.budget || accepted.is_empty() {
            stats.rejected += 1;
            rejections += 1;
            smallest_rejected = smallest_rejected.min(needed);
            if rejections >= options.max_rejections {
                break;
            }
            continue;
        }
        rejections = 0;
        if instanced_ages.is_none() {
            instanced_ages = Some(eligible_ages(&rec, options.max_tree_exits));
        }
        let (v0, b0, f0) = (
            cache.vertices.len() as u32,
            cache.bark.len() as u32,
            cache.leaves.len() as u32,
        );
        cache.vertices.extend_from_slice(&mesh.vertices);
        cache.bark.extend(mesh.bark.iter().map(|&i| i + v0));
        cache.leaves.extend(mesh.leaves.iter().map(|&i| i + v0));
        for &i in &accepted {
            let r = &rec.instances[i];
            let inverse = r.frame.inverse();
            let e0 = cache.exits.len() as u32;
            for &(id, age, world) in &rec.exits[r.exits.range()] {
                cache.exits.push(crate::cache::Exit {
                    id,
                    age,
                    frame: inverse.mul(&world),
                });
            }
            lists[(r.id * ages + r.age) as usize].push(cache.instances.len() as u32);
            cache.instances.push(Instance {
                id: r.id,
                age: r.age,
                bark: r.bark.offset(b0),
                leaves: r.leaves.offset(f0),
                frame_inverse: inverse,
                exits: Span::between(e0, cache.exits.len() as u32),
            });
            if let Some(w) = hero_words.get(r.start_order as usize) {
                word_bytes += w.heap_bytes();
                words.push(w.clone());
            }
        }
        used += needed;
        stats.heroes += 1;
        stats.final_probability = p;
    }
    if stats.heroes == 0 {
        return Err(InstancingError::BudgetTooSmall {
            budget: options.budget,
            needed: smallest_rejected.saturating_add(table_bytes),
        });
    }
    cache.index(ids, ages);
    debug_assert_eq!(cache.bytes() + word_bytes, used);
    stats.instanced_ages = instanced_ages.unwrap_or(0);
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

/// The deepest age A such that the hero (whole, as the first one is) has at most twice
/// `max_exits` branches introduced at generations 1 to A; at least 1.
fn eligible_ages(hero: &HeroRecorder, max_exits: u32) -> u32 {
    let mut per_age: Vec<u32> = Vec::new();
    for r in hero.instances.iter().filter(|r| (r.id, r.age) != ROOT) {
        let a = r.age as usize;
        if per_age.len() <= a {
            per_age.resize(a + 1, 0);
        }
        per_age[a] += 1;
    }
    // Twice the bound: not every eligible branch is instanced, and crowns over the bound are
    // not kept as roots.
    let mut total = 0u32;
    let mut deepest = 1;
    for (age, &n) in per_age.iter().enumerate().skip(1) {
        total = total.saturating_add(n);
        if total > max_exits.saturating_mul(2) {
            break;
        }
        deepest = age as u32;
    }
    deepest
}

/// The sub-word of every start..stop marker pair, in order of the start markers.
fn instance_words(word: &Word, markers: &Markers) -> Vec<Word> {
    let mut out: Vec<Option<Word>> = Vec::new();
    let mut open: Vec<(usize, usize)> = Vec::new();
    for (i, m) in word.iter().enumerate() {
        if m.symbol == markers.start {
            open.push((i, out.len()));
            out.push(None);
        } else if m.symbol == markers.stop
            && let Some((s, slot)) = open.pop()
        {
            let mut w = Word::empty(word.alphabet().clone());
            for j in s..=i {
                w.push(word.symbols()[j], word.params(j));
            }
            out[slot] = Some(w);
        }
    }
    out.into_iter()
        .map(|w| w.unwrap_or_else(|| Word::empty(word.alphabet().clone())))
        .collect()
}

/// The key of a whole tree: branch id 0, introduced at generation 0.
pub(crate) const ROOT: (u32, u32) = (0, 0);
