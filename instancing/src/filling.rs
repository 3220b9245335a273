//! The parts of hero creation (Kenwood section 6): the probability schedule, hero trees
//! derived in instancing form, and the cache they are appended to while the budget lasts.

use sylva_lsys::{LSystem, Word};
use sylva_turtle::{Command, TurtleOptions, interpret};

use crate::cache::{CANDIDATE_BYTES, EXIT_BYTES, Exit, INSTANCE_BYTES, Instance, InstanceCache};
use crate::error::InstancingError;
use crate::options::{HeroOptions, ROOT};
use crate::recorder::HeroRecorder;
use crate::rewrite::{InstancingGrammar, Markers, probability_at_ages};
use crate::span::Span;
use sylva_base::hash::mix;

/// The instancing probability of the next hero: 0 for whole heroes while the first
/// `complete_share` of the budget fills, then rising from `p_min` to `p_max` with the fill of
/// the rest (`p_max` right after a hero did not fit).
#[derive(Debug)]
pub(crate) struct Schedule {
    p_min: f64,
    p_max: f64,
    budget: f64,
    whole_budget: f64,
    max_tree_exits: u32,
    /// Learnt from the first hero: branches introduced up to this age may be instanced.
    pub(crate) instanced_ages: Option<u32>,
}

impl Schedule {
    pub(crate) fn new(options: &HeroOptions) -> Self {
        Schedule {
            p_min: options.p_min,
            p_max: options.p_max,
            budget: options.budget as f64,
            whole_budget: options.budget as f64 * options.complete_share,
            max_tree_exits: options.max_tree_exits,
            instanced_ages: None,
        }
    }

    /// The probability for a hero when `used` bytes are spent and the last `rejections`
    /// heroes did not fit.
    pub(crate) fn probability(&self, used: usize, rejections: u32) -> f64 {
        let used = used as f64;
        match self.instanced_ages {
            Some(_) if used >= self.whole_budget => {
                let crowns = ((used - self.whole_budget)
                    / (self.budget - self.whole_budget).max(1.0))
                .clamp(0.0, 1.0);
                if rejections > 0 {
                    self.p_max
                } else {
                    self.p_min + (self.p_max - self.p_min) * crowns
                }
            }
            _ => 0.0,
        }
    }

    /// Learns the eligible ages from the first hero that fits (a whole one).
    pub(crate) fn learn(&mut self, hero: &Hero) {
        if self.instanced_ages.is_none() {
            self.instanced_ages = Some(eligible_ages(&hero.recorder, self.max_tree_exits));
        }
    }
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

/// A hero tree, derived in instancing form and meshed, with its instances recorded.
#[derive(Debug)]
pub(crate) struct Hero {
    recorder: HeroRecorder,
    /// Each recorded instance's word, when the options keep words.
    words: Vec<Word>,
}

/// Derives heroes, rebuilding the rewritten grammar only when the probability (in steps of
/// 1/64) or the set of known (id, age) keys changed.
#[derive(Debug)]
pub(crate) struct HeroGrammar {
    rewriting: InstancingGrammar,
    turtle: TurtleOptions,
    markers: Markers,
    current: Option<(u64, Vec<Vec<u32>>, LSystem)>,
}

impl HeroGrammar {
    pub(crate) fn new(grammar: &LSystem, options: &HeroOptions) -> Result<Self, InstancingError> {
        let mut turtle = options.turtle.clone();
        for c in [
            options.markers.start,
            options.markers.stop,
            options.markers.get,
        ] {
            turtle.symbols.set(c, Command::Marker);
        }
        Ok(HeroGrammar {
            rewriting: InstancingGrammar::new(grammar, options.markers)?,
            turtle,
            markers: options.markers,
            current: None,
        })
    }

    /// Branch ids, the whole tree (id 0) included.
    pub(crate) fn ids(&self) -> u32 {
        self.rewriting.branch_count() + 1
    }

    /// Hero `k`, each branch introduced at generations 1 to `eligible` and already in the
    /// cache instanced with probability `p`.
    pub(crate) fn hero(
        &mut self,
        k: u32,
        p: f64,
        eligible: u32,
        filling: &Filling,
        options: &HeroOptions,
    ) -> Result<Hero, InstancingError> {
        let step = (p * 64.0).round() as u64;
        let known: Vec<Vec<u32>> = (0..filling.ids)
            .map(|id| {
                (1..filling.ages.min(eligible + 1))
                    .filter(|&a| !filling.candidates(id, a).is_empty())
                    .collect()
            })
            .collect();
        let grammar = match self.current.take() {
            Some((s, kn, g)) if s == step && kn == known => (s, kn, g),
            _ => {
                let q = step as f64 / 64.0;
                let g = self
                    .rewriting
                    .compact(|id| probability_at_ages(q, &known[id as usize]))?;
                (step, known, g)
            }
        };
        let seed = mix(options.seed ^ mix(u64::from(k)));
        let word = grammar
            .2
            .derive_with(options.generations, seed, &options.limits)?;
        // What the turtle draws: the homomorphism's word (the same word without one).
        let word = grammar.2.interpretation(&word, seed)?;
        self.current = Some(grammar);
        let mut recorder = HeroRecorder::new(&self.turtle, self.markers);
        interpret(&word, &self.turtle, &mut recorder)?;
        let words = if options.keep_words {
            instance_words(&word, &self.markers)
        } else {
            Vec::new()
        };
        Ok(Hero { recorder, words })
    }
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

/// What of a hero the cache would take, and what it costs.
#[derive(Debug)]
pub(crate) struct Offer {
    /// Indices of the recorded instances that are kept.
    accepted: Vec<usize>,
    /// Bytes they add: the hero's geometry, instance metadata, exits and words.
    pub(crate) bytes: usize,
}

impl Offer {
    /// Whether nothing of the hero would be kept.
    pub(crate) fn is_empty(&self) -> bool {
        self.accepted.is_empty()
    }
}

/// The cache being filled, with its per-key candidate lists and every byte counted.
#[derive(Debug)]
pub(crate) struct Filling {
    pub(crate) cache: InstanceCache,
    lists: Vec<Vec<u32>>,
    ids: u32,
    ages: u32,
    pub(crate) words: Vec<Word>,
    word_bytes: usize,
    /// Bytes spent, the lookup table's included.
    pub(crate) used: usize,
}

impl Filling {
    pub(crate) fn new(budget: usize, ids: u32, ages: u32) -> Self {
        let keys = (ids * ages) as usize;
        Filling {
            cache: InstanceCache::new(budget),
            lists: vec![Vec::new(); keys],
            ids,
            ages,
            words: Vec::new(),
            word_bytes: 0,
            used: keys * 8,
        }
    }

    /// Bytes of the dense lookup table, spent before any hero.
    pub(crate) fn table_bytes(&self) -> usize {
        (self.ids * self.ages) as usize * 8
    }

    fn candidates(&self, id: u32, age: u32) -> &[u32] {
        &self.lists[(id * self.ages + age) as usize]
    }

    /// The instances of `hero` the cache would take (known keys below the cap; crowns with
    /// at most `max_tree_exits` exits) and their cost.
    pub(crate) fn offer(&self, hero: &Hero, options: &HeroOptions) -> Offer {
        let rec = &hero.recorder;
        let mut extra = vec![0usize; self.lists.len()];
        let accepted: Vec<usize> = (0..rec.instances.len())
            .filter(|&i| {
                let r = &rec.instances[i];
                if r.id >= self.ids || r.age >= self.ages {
                    return false;
                }
                // A crown with more exits than a tree may have placements is not kept as a
                // root; its branches still are.
                if (r.id, r.age) == ROOT && r.exits.count > options.max_tree_exits {
                    return false;
                }
                let slot = (r.id * self.ages + r.age) as usize;
                let ok = self.lists[slot].len() + extra[slot] < options.cap_per_key;
                extra[slot] += usize::from(ok);
                ok
            })
            .collect();
        let exits: usize = accepted
            .iter()
            .map(|&i| rec.instances[i].exits.count as usize)
            .sum();
        let word_bytes: usize = accepted
            .iter()
            .filter_map(|&i| hero.words.get(rec.instances[i].start_order as usize))
            .map(Word::heap_bytes)
            .sum();
        let bytes = rec.builder.mesh.byte_size()
            + accepted.len() * (INSTANCE_BYTES + CANDIDATE_BYTES)
            + exits * EXIT_BYTES
            + word_bytes;
        Offer { accepted, bytes }
    }

    /// Appends the hero's geometry and the accepted instances, their exits relative to their
    /// own frames (E = M^-1 * world), and their words.
    pub(crate) fn append(&mut self, hero: &Hero, offer: &Offer) {
        let rec = &hero.recorder;
        let mesh = &rec.builder.mesh;
        let cache = &mut self.cache;
        let (v0, b0, l0) = (
            cache.vertices.len() as u32,
            cache.bark.len() as u32,
            cache.leaves.len() as u32,
        );
        cache.vertices.extend_from_slice(&mesh.vertices);
        cache.bark.extend(mesh.bark.iter().map(|&i| i + v0));
        cache.leaves.extend(mesh.leaves.iter().map(|&i| i + v0));
        for &i in &offer.accepted {
            let r = &rec.instances[i];
            let inverse = r.frame.inverse();
            let e0 = cache.exits.len() as u32;
            for &(id, age, world) in &rec.exits[r.exits.range()] {
                cache.exits.push(Exit {
                    id,
                    age,
                    frame: inverse.mul(&world),
                });
            }
            self.lists[(r.id * self.ages + r.age) as usize].push(cache.instances.len() as u32);
            cache.instances.push(Instance {
                id: r.id,
                age: r.age,
                bark: r.bark.offset(b0),
                leaves: r.leaves.offset(l0),
                frame_inverse: inverse,
                exits: Span::between(e0, cache.exits.len() as u32),
            });
            if let Some(w) = hero.words.get(r.start_order as usize) {
                self.word_bytes += w.heap_bytes();
                self.words.push(w.clone());
            }
        }
        self.used += offer.bytes;
    }

    /// The finished cache with its lookup table, and the bytes its words take.
    pub(crate) fn finish(mut self) -> (InstanceCache, Vec<Word>, usize) {
        self.cache.index(self.ids, self.ages);
        debug_assert_eq!(self.cache.bytes() + self.word_bytes, self.used);
        (self.cache, self.words, self.word_bytes)
    }
}
