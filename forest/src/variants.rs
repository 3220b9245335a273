//! The caches a forest draws its trees from: per species a canopy and a young form, or, for
//! forests of every age, a form per generation and the damaged forms.

use sylva_base::hash::mix;
use sylva_instancing::{HeroOptions, InstanceCache, InstancingError, build_cache};
use sylva_turtle::StemBreak;

use crate::error::ForestError;
use crate::form::TreeForm;
use crate::species::{Species, skeleton_top};

/// Heroes of a damaged form: whole trees, no instancing (damaged trees are few, and a broken
/// trunk cuts across the branches instancing would share).
const DAMAGED_HEROES: u32 = 4;

/// Most living forms of one species in a forest of every age: a species of more
/// generations is drawn at this many of them, spread evenly and ending at its canopy form.
pub(crate) const MAX_LIVE_FORMS: u32 = 8;

/// One instance cache: a species in one form (a maturity, or a damage).
#[derive(Debug, Clone)]
pub struct Variant {
    /// Index into the configuration's species.
    pub species: usize,
    /// Whether this is a young form: too small to stand in the canopy (no impostor, left out
    /// of coarse tiles).
    pub seedling: bool,
    /// Generations of its trees.
    pub generations: u32,
    /// How its trees look.
    pub form: TreeForm,
    /// Its cache.
    pub cache: InstanceCache,
}

/// What the caches are built from: a forest configuration's parts.
pub(crate) struct Plan<'a> {
    pub(crate) species: &'a [Species],
    /// Bytes of all caches.
    pub(crate) budget: usize,
    pub(crate) seed: u64,
    /// A form per generation and the damaged forms, or the canopy and young forms.
    pub(crate) all_ages: bool,
    /// Whether the young form is wanted (forests of one age with seedlings).
    pub(crate) seedlings: bool,
}

/// What building the caches made.
pub(crate) struct Built {
    pub(crate) variants: Vec<Variant>,
    pub(crate) heroes: u32,
    /// Per species, its living forms' generations and drawn heights, youngest first (empty
    /// unless the forest has every age).
    pub(crate) heights: Vec<Vec<(u32, f32)>>,
}

/// Fills the caches of `config`'s species.
pub(crate) fn build(config: Plan<'_>) -> Result<Built, ForestError> {
    let total_weight: f32 = config.species.iter().map(|s| s.weight.max(0.0)).sum();
    let mut built = Built {
        variants: Vec::new(),
        heroes: 0,
        heights: Vec::new(),
    };
    for (i, s) in config.species.iter().enumerate() {
        let share = (config.budget as f64 * f64::from(s.weight.max(0.0) / total_weight)) as usize;
        let plan = if config.all_ages {
            let heights = form_heights(s)?;
            let plan = every_age(s, &heights, share);
            built.heights.push(heights);
            plan
        } else {
            let mut plan = vec![(TreeForm::Live(s.generations), false, share - share / 4)];
            if config.seedlings {
                plan.push((TreeForm::Live(s.seedling_generations), true, share / 4));
            }
            plan
        };
        for (form, seedling, part) in plan {
            if part == 0 {
                continue;
            }
            // The canopy and young forms keep the seeds they always had (0 and 1), so
            // forests without every age are the same forests.
            let salt = if config.all_ages {
                2 + form_index(form)
            } else {
                u64::from(seedling)
            };
            let cache = form_cache(s, form, part, mix(config.seed ^ ((i as u64) << 1) ^ salt))?;
            built.heroes += cache.1;
            built.variants.push(Variant {
                species: i,
                seedling,
                generations: match form {
                    TreeForm::Live(g) => g,
                    _ => s.generations,
                },
                form,
                cache: cache.0,
            });
        }
    }
    Ok(built)
}

/// A salt per form, so each form's heroes differ.
fn form_index(form: TreeForm) -> u64 {
    match form {
        TreeForm::Live(g) => u64::from(g),
        other => {
            100 + TreeForm::DAMAGED
                .iter()
                .position(|f| *f == other)
                .unwrap_or(0) as u64
        }
    }
}

/// The forms of a forest of every age and their shares of `share` bytes: the canopy form
/// two fifths, the younger generations two fifths between them, the damaged forms the rest.
/// The generations up to the species' seedling form are its young trees.
fn every_age(s: &Species, heights: &[(u32, f32)], share: usize) -> Vec<(TreeForm, bool, usize)> {
    let g = s.generations.max(1);
    let mut plan = vec![(TreeForm::Live(g), false, share * 2 / 5)];
    let younger = share * 2 / 5 / (heights.len() - 1).max(1);
    plan.extend(
        heights
            .iter()
            .filter(|(k, _)| *k < g)
            .map(|&(k, _)| (TreeForm::Live(k), k <= s.seedling_generations, younger)),
    );
    let damaged = share / 5 / TreeForm::DAMAGED.len();
    plan.extend(TreeForm::DAMAGED.iter().map(|f| (*f, false, damaged)));
    plan
}

/// The cache of one form of `s` under `budget` bytes (at least one hero's), and its hero
/// count.
fn form_cache(
    s: &Species,
    form: TreeForm,
    budget: usize,
    seed: u64,
) -> Result<(InstanceCache, u32), ForestError> {
    let mut options = HeroOptions::default()
        .with_budget(budget)
        .with_seed(seed)
        .with_turtle(s.turtle.clone());
    match form {
        TreeForm::Live(g) => options = options.with_generations(g),
        damaged => {
            options = options.with_generations(s.generations);
            options.turtle.stem_break = match damaged.break_share() {
                Some(share) => Some(stem_break(s, share)?),
                None => None,
            };
            options.turtle.leaf_keep = damaged.leaf_keep();
            options.p_min = 0.0;
            options.p_max = 0.0;
            options.complete_share = 1.0;
            options.max_heroes = DAMAGED_HEROES;
        }
    }
    let built = match build_cache(&s.grammar, &options) {
        // Every form is drawn from at least one hero, whatever its share of the budget: a
        // forest of every age has many forms, and a small forest's budget (sized to its
        // trees) is smaller than the species' heroes.
        Err(InstancingError::BudgetTooSmall { needed, .. }) => {
            build_cache(&s.grammar, &options.with_budget(needed))?
        }
        other => other?,
    };
    let mut cache = built.cache;
    if form == TreeForm::Fallen {
        lay_down(&mut cache);
    }
    Ok((cache, built.stats.heroes))
}

/// Turns a cache of whole upright trees to lie along +X on the ground, still: its trunk's
/// base stays at the origin, its wind data no longer sways it.
fn lay_down(cache: &mut InstanceCache) {
    // A quarter turn about Z takes +Y (up) to +X: (x, y) -> (y, -x).
    let turn = |[x, y, z]: [f32; 3]| [y, -x, z];
    for v in &mut cache.vertices {
        v.position = turn(v.position);
        v.normal = turn(v.normal);
        // Depth 0, phase 0: the trunk, which no wind moves.
        v.wind = [v.position[0], v.position[1], v.position[2], 0.0];
    }
}

/// The generations `s` is drawn at in a forest of every age ([`live_generations`]) and the
/// drawn height of each: the mean top of three sample trees' skeletons.
fn form_heights(s: &Species) -> Result<Vec<(u32, f32)>, ForestError> {
    live_generations(s.generations)
        .into_iter()
        .map(|g| Ok((g, s.drawn_height(g, 3)?)))
        .collect()
}

/// Of living forms and their drawn heights (youngest first), the one a tree `height` metres
/// tall is drawn as: the tallest not above 1.1 times `height` (the youngest when every one is
/// taller), with the scale that makes it `height` tall. `None` for no forms.
pub(crate) fn pick_live_form(heights: &[(u32, f32)], height: f32) -> Option<(u32, f32)> {
    let k = heights
        .iter()
        .rposition(|&(_, h)| h <= 1.1 * height)
        .unwrap_or(0);
    let &(generations, drawn) = heights.get(k)?;
    Some((generations, height / drawn))
}

/// How a single living tree of `species` at `age` years is drawn, as a forest of every age
/// draws it (without building any cache): the generation its grammar is derived to, and the
/// scale that brings that tree to its height on the species' height curve
/// ([`Life::height`](crate::Life::height)).
///
/// ```
/// use sylva_forest::{Species, tree_at_age};
///
/// let tree = Species::from_preset("kenwood-leafy", 4)?;
/// let (young, young_scale) = tree_at_age(&tree, 1.0)?;
/// let (old, old_scale) = tree_at_age(&tree, 300.0)?;
/// // Older trees are drawn from the same or a later generation.
/// assert!(young <= old && old <= 4);
/// assert!(young_scale > 0.0 && old_scale > 0.0);
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
pub fn tree_at_age(species: &Species, age: f32) -> Result<(u32, f32), ForestError> {
    let heights = form_heights(species)?;
    let height = species.life.height(age.max(0.0));
    pick_live_form(&heights, height).ok_or_else(|| ForestError::EmptySpecies {
        species: species.name.clone(),
    })
}

/// 1 to `generations`, or [`MAX_LIVE_FORMS`] of them spread evenly from 1 and ending there.
pub(crate) fn live_generations(generations: u32) -> Vec<u32> {
    let g = generations.max(1);
    if g <= MAX_LIVE_FORMS {
        return (1..=g).collect();
    }
    let mut out: Vec<u32> = (0..MAX_LIVE_FORMS)
        .map(|k| 1 + ((g - 1) * k + (MAX_LIVE_FORMS - 1) / 2) / (MAX_LIVE_FORMS - 1))
        .collect();
    out.dedup();
    out
}

/// Where a canopy tree of `s` snaps at `share` of its height: every stem there at least half
/// as thick as the thickest (the trunk, and limbs as stout), measured on a sample tree.
fn stem_break(s: &Species, share: f32) -> Result<StemBreak, ForestError> {
    let skeleton = s.skeleton(s.generations, 0)?;
    let height = share * skeleton_top(&skeleton);
    let thickest = skeleton
        .bones
        .iter()
        .filter(|b| b.start.y < height && b.end.y >= height)
        .map(|b| b.start_radius)
        .fold(0.0f32, f32::max);
    Ok(StemBreak {
        height,
        min_radius: 0.5 * thickest,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn live_generations_spread_from_the_first_to_the_canopy() {
        assert_eq!(live_generations(5), [1, 2, 3, 4, 5]);
        let spread = live_generations(14);
        assert_eq!(spread.len(), MAX_LIVE_FORMS as usize);
        assert_eq!((spread[0], spread[spread.len() - 1]), (1, 14));
        assert!(spread.windows(2).all(|w| w[0] < w[1]));
    }
}
