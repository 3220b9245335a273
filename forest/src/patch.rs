//! The Garden of Eden gap model: one canopy tree per patch, placement errors fixed, seedlings
//! thinned around canopy trees.

use std::fmt;

use glam::Vec2;

use sylva_base::hash::{hash_cell as hash, mix, unit_f32 as unit};

use crate::density::{Candidate, DensityModel, Rect};

/// Decides the species of each tree the patch density model proposes, or that no tree stands.
///
/// Implementations must be pure functions of their inputs: the same spot and draw give the
/// same answer on every thread and in every region, so forests stay seamless and
/// deterministic.
///
/// ```
/// use sylva_forest::{Composition, DensityModel, PatchDensity, PatchSpecies, Rect};
/// use sylva_terrain::glam::Vec2;
///
/// /// Trees only west of x = 50, their species drawn by weight.
/// #[derive(Debug)]
/// struct West;
///
/// impl Composition for West {
///     fn choose(&self, density: &PatchDensity, p: Vec2, draw: u64) -> Option<usize> {
///         (p.x < 50.0).then(|| density.pick_species(draw))
///     }
///     fn species(&self) -> Option<usize> {
///         None
///     }
/// }
///
/// let model = PatchDensity::new(vec![PatchSpecies { canopy_radius: 3.0, weight: 1.0 }]);
/// let mut trees = Vec::new();
/// model.composed(&West).candidates(Rect::new(Vec2::ZERO, Vec2::splat(100.0)), 7, &mut trees);
/// assert!(!trees.is_empty() && trees.iter().all(|t| t.position.x < 50.0));
/// ```
pub trait Composition: fmt::Debug + Send + Sync {
    /// The species of a tree proposed at `p` (x, z), drawn from the bits of `draw`, or `None`
    /// for no tree there.
    fn choose(&self, density: &PatchDensity, p: Vec2, draw: u64) -> Option<usize>;

    /// How many species this composition was made for, so a forest can refuse one made for
    /// another forest; `None` when it fits any.
    fn species(&self) -> Option<usize>;
}

/// Patch-based density management (thesis 5.3.3 and 7.10).
///
/// The plane is cut into square patches of side [`PatchDensity::patch`], anchored at the
/// world origin. Each patch holds one canopy tree at a random position (its species drawn by
/// weight). Canopy trees of neighbouring patches closer than `spacing` (the larger of their
/// canopy radii times [`PatchDensity::spacing_factor`]) are found through the patch grid
/// itself (each patch is one grid cell, so the search is linear time, the thesis's
/// closest-pair idea) and resolved: the tree of lower priority moves to a free spot of its own
/// patch, and if none of 16 tries is free, or a conflict remains with a tree of higher
/// priority, it is removed. Every decision reads only patches within three rings, so any region
/// gives the same trees where regions overlap.
///
/// Seedlings (thesis 7.10.1): each patch also proposes `seedlings_per_patch` young trees at
/// random spots, each eliminated with probability `min(1, (r0 / d)^2)`, `d` being the distance
/// to the nearest canopy tree and `r0 = seedling_clearance * canopy radius`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct PatchDensity {
    /// Patch side length. Default: the largest canopy diameter among the species.
    pub patch: f32,
    /// Canopy radius and weight of each species, indexed by species. One list, so that a
    /// species can never have a radius without a weight or the other way round.
    /// No default: the species given to [`PatchDensity::new`].
    pub species: Vec<PatchSpecies>,
    /// Minimum trunk spacing as a multiple of the larger canopy radius (at most 2, so that
    /// conflicts stay between neighbouring patches). Default: 1.
    pub spacing_factor: f32,
    /// Seedlings proposed per patch. Default: 3.
    pub seedlings_per_patch: u32,
    /// `r0` of the elimination probability, as a multiple of the canopy radius. Default: 0.6.
    pub seedling_clearance: f32,
}

/// What the density model knows of one species.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchSpecies {
    /// Canopy radius in metres.
    pub canopy_radius: f32,
    /// Relative frequency (any scale; species of weight 0 or less never appear).
    pub weight: f32,
}

#[derive(Debug, Clone, Copy)]
struct Canopy {
    position: Vec2,
    species: usize,
    priority: u64,
    present: bool,
}

/// How far, in patches, a patch's trees look: a seedling looks at canopy trees one ring away,
/// whose fate depends on their own neighbours' moves, which depend on theirs.
pub(crate) const RINGS: i64 = 3;
/// Side, in patches, of the blocks a large region is processed in.
const BLOCK: i64 = 128;
const TRIES: u64 = 16;

impl PatchDensity {
    /// A model whose patch side is the largest canopy diameter.
    ///
    /// ```
    /// use sylva_forest::{DensityModel, PatchDensity, PatchSpecies, Rect};
    /// use sylva_terrain::glam::Vec2;
    ///
    /// let oak = PatchSpecies { canopy_radius: 6.0, weight: 2.0 };
    /// let birch = PatchSpecies { canopy_radius: 3.0, weight: 1.0 };
    /// let model = PatchDensity::new(vec![oak, birch]);
    /// assert_eq!(model.patch, 12.0);
    /// let mut trees = Vec::new();
    /// model.candidates(Rect::new(Vec2::ZERO, Vec2::splat(120.0)), 7, &mut trees);
    /// assert!(trees.iter().filter(|t| !t.seedling).count() > 50);
    /// ```
    pub fn new(species: Vec<PatchSpecies>) -> Self {
        let patch = species
            .iter()
            .map(|s| s.canopy_radius)
            .fold(0.0f32, f32::max)
            * 2.0;
        PatchDensity {
            patch,
            species,
            spacing_factor: 1.0,
            seedlings_per_patch: 3,
            seedling_clearance: 0.6,
        }
    }

    /// How far (metres) a tree's fate reaches: a change to what grows at one spot (a paint
    /// stroke) can change trees up to this far from it, and no farther.
    pub fn reach(&self) -> f32 {
        (RINGS as f32 + 1.0) * self.patch
    }

    /// A species index drawn by weight from `h`, as the unpainted model draws it (always a
    /// valid index when some weight is positive; 0 otherwise).
    ///
    /// ```
    /// use sylva_forest::{PatchDensity, PatchSpecies};
    ///
    /// let oak = PatchSpecies { canopy_radius: 6.0, weight: 1.0 };
    /// let none = PatchSpecies { canopy_radius: 3.0, weight: 0.0 };
    /// let model = PatchDensity::new(vec![oak, none]);
    /// assert!((0..100u64).all(|h| model.pick_species(h.wrapping_mul(0x9e37_79b9_7f4a_7c15)) == 0));
    /// ```
    pub fn pick_species(&self, h: u64) -> usize {
        let weight = |s: &PatchSpecies| s.weight.max(0.0);
        let total: f32 = self.species.iter().map(weight).sum();
        let mut u = unit(h) * total;
        for (i, s) in self.species.iter().enumerate() {
            if u < weight(s) {
                return i;
            }
            u -= weight(s);
        }
        self.species
            .iter()
            .rposition(|s| s.weight > 0.0)
            .unwrap_or(0)
    }

    fn radius(&self, species: usize) -> f32 {
        self.species.get(species).map_or(0.0, |s| s.canopy_radius)
    }

    fn spacing(&self, a: usize, b: usize) -> f32 {
        let r = self.radius(a).max(self.radius(b));
        (self.spacing_factor.clamp(0.0, 2.0) * r).min(self.patch)
    }

    fn spot(&self, seed: u64, i: i64, j: i64, salt: u64) -> Vec2 {
        let h = hash(seed, i, j, salt);
        Vec2::new(
            (i as f32 + unit(h)) * self.patch,
            (j as f32 + unit(mix(h))) * self.patch,
        )
    }

    /// Canopy trees of the patches in `[i0, i1] x [j0, j1]`, conflicts resolved; row-major.
    fn canopies<C: Composition + ?Sized>(
        &self,
        composition: &C,
        seed: u64,
        (i0, i1, j0, j1): (i64, i64, i64, i64),
    ) -> Vec<Canopy> {
        let w = (i1 - i0 + 1) as usize;
        let at = |i: i64, j: i64| ((j - j0) as usize) * w + (i - i0) as usize;
        let original: Vec<Canopy> = (j0..=j1)
            .flat_map(|j| (i0..=i1).map(move |i| (i, j)))
            .map(|(i, j)| {
                let position = self.spot(seed, i, j, 0);
                let species = composition.choose(self, position, hash(seed, i, j, 1));
                Canopy {
                    position,
                    species: species.unwrap_or(0),
                    priority: hash(seed, i, j, 2),
                    present: species.is_some(),
                }
            })
            .collect();
        let neighbours = |i: i64, j: i64| {
            (-1..=1)
                .flat_map(move |dj| (-1..=1).map(move |di| (i + di, j + dj)))
                .filter(move |&(a, b)| (a, b) != (i, j) && a >= i0 && a <= i1 && b >= j0 && b <= j1)
        };
        let clash = |t: &Canopy, p: Vec2, n: &Canopy| {
            n.present && p.distance(n.position) < self.spacing(t.species, n.species)
        };
        // Stage 1: a tree in conflict with a higher-priority neighbour moves within its patch,
        // clear of every neighbour's original spot.
        let mut moved = original.clone();
        for j in j0 + 1..j1 {
            for i in i0 + 1..i1 {
                let t = original[at(i, j)];
                if !t.present
                    || !neighbours(i, j).any(|(a, b)| {
                        let n = &original[at(a, b)];
                        n.priority > t.priority && clash(&t, t.position, n)
                    })
                {
                    continue;
                }
                // A painted tree moves only where its species may stand.
                let draw = hash(seed, i, j, 1);
                let spot = (1..=TRIES)
                    .map(|k| self.spot(seed, i, j, 2 + k))
                    .find(|&p| {
                        neighbours(i, j).all(|(a, b)| !clash(&t, p, &original[at(a, b)]))
                            && composition.choose(self, p, draw) == Some(t.species)
                    });
                let m = &mut moved[at(i, j)];
                match spot {
                    Some(p) => m.position = p,
                    None => m.present = false,
                }
            }
        }
        // Stage 2: any conflict left is settled by removing the lower-priority tree.
        let mut done = moved.clone();
        for j in j0 + 1..j1 {
            for i in i0 + 1..i1 {
                let t = moved[at(i, j)];
                if t.present
                    && neighbours(i, j).any(|(a, b)| {
                        let n = &moved[at(a, b)];
                        n.priority > t.priority && clash(&t, t.position, n)
                    })
                {
                    done[at(i, j)].present = false;
                }
            }
        }
        done
    }
}

impl DensityModel for PatchDensity {
    fn candidates(&self, region: Rect, seed: u64, out: &mut Vec<Candidate>) {
        self.candidates_by(&ByWeight, region, seed, out);
    }
}

/// Every spot takes a tree, its species drawn by the species' weights.
#[derive(Debug)]
struct ByWeight;

impl Composition for ByWeight {
    fn choose(&self, density: &PatchDensity, _: Vec2, draw: u64) -> Option<usize> {
        Some(density.pick_species(draw))
    }

    fn species(&self) -> Option<usize> {
        None
    }
}

impl PatchDensity {
    /// The candidates of `region` with species (and presence) decided by `composition`.
    pub(crate) fn candidates_by<C: Composition + ?Sized>(
        &self,
        composition: &C,
        region: Rect,
        seed: u64,
        out: &mut Vec<Candidate>,
    ) {
        let usable_patch = self.patch.is_finite() && self.patch > 0.0;
        if region.is_empty() || !usable_patch || !self.species.iter().any(|s| s.weight > 0.0) {
            return;
        }
        let cell = |v: f32| (v / self.patch).floor() as i64;
        let (ri0, ri1, rj0, rj1) = (
            cell(region.min.x),
            cell(region.max.x),
            cell(region.min.y),
            cell(region.max.y),
        );
        // Large regions go in blocks of patches, so memory stays bounded whatever the area;
        // every decision is local, so blocks give the same trees as one pass.
        if ri1 - ri0 >= BLOCK || rj1 - rj0 >= BLOCK {
            let mut j = rj0;
            while j <= rj1 {
                let mut i = ri0;
                while i <= ri1 {
                    // Each block emits the trees of its own patches, so none is lost or
                    // doubled at block borders.
                    self.candidates_in(
                        composition,
                        region,
                        seed,
                        out,
                        (i, (i + BLOCK - 1).min(ri1), j, (j + BLOCK - 1).min(rj1)),
                    );
                    i += BLOCK;
                }
                j += BLOCK;
            }
            return;
        }
        self.candidates_in(composition, region, seed, out, (ri0, ri1, rj0, rj1));
    }

    /// Candidates of `region`, whose patches are `cells` = (i0, i1, j0, j1) inclusive.
    fn candidates_in<C: Composition + ?Sized>(
        &self,
        composition: &C,
        region: Rect,
        seed: u64,
        out: &mut Vec<Candidate>,
        cells: (i64, i64, i64, i64),
    ) {
        let (ri0, ri1, rj0, rj1) = cells;
        let (i0, i1, j0, j1) = (ri0 - RINGS, ri1 + RINGS, rj0 - RINGS, rj1 + RINGS);
        let canopies = self.canopies(composition, seed, (i0, i1, j0, j1));
        let w = (i1 - i0 + 1) as usize;
        let at = |i: i64, j: i64| ((j - j0) as usize) * w + (i - i0) as usize;
        for j in rj0..=rj1 {
            for i in ri0..=ri1 {
                let c = canopies[at(i, j)];
                if c.present && region.contains(c.position) {
                    out.push(Candidate {
                        position: c.position,
                        species: c.species,
                        seedling: false,
                        key: hash(seed, i, j, 100),
                        slot: 0,
                    });
                }
                for k in 0..u64::from(self.seedlings_per_patch) {
                    let p = self.spot(seed, i, j, 1000 + k);
                    if !region.contains(p) {
                        continue;
                    }
                    let Some(species) = composition.choose(self, p, hash(seed, i, j, 2000 + k))
                    else {
                        continue;
                    };
                    let nearest = nearest_canopy(
                        p,
                        (0..3).map(|b| {
                            let row = at(i - 1, j - 1 + b);
                            &canopies[row..row + 3]
                        }),
                    );
                    let eliminate = match nearest {
                        Some((d, s)) => {
                            let r0 = self.seedling_clearance * self.radius(s);
                            if d <= 0.0 {
                                1.0
                            } else {
                                ((r0 / d) * (r0 / d)).min(1.0)
                            }
                        }
                        None => 0.0,
                    };
                    if unit(hash(seed, i, j, 3000 + k)) >= eliminate {
                        out.push(Candidate {
                            position: p,
                            species,
                            seedling: true,
                            key: hash(seed, i, j, 4000 + k),
                            slot: 1 + k as u32,
                        });
                    }
                }
            }
        }
    }
}

/// The nearest canopy tree to `p` of the 3 x 3 patches around it (given as three rows of
/// three), as its distance and species: the first of equal distances in row order, as a
/// search comparing `p.distance(c)` tree by tree finds it (distances are never NaN).
///
/// It compares squared distances and takes one square root, not nine: a square root's
/// latency chained through the comparisons was most of the seedlings' thinning. Squares
/// that differ can round to one distance, so the trees whose squares are within a few
/// ulps of the least are checked by their distance, in order, which keeps the same tree
/// and the same bits.
#[inline]
fn nearest_canopy<'a>(p: Vec2, rows: impl Iterator<Item = &'a [Canopy]>) -> Option<(f32, usize)> {
    let mut squares = [(f32::INFINITY, 0usize); 9];
    let mut least = f32::INFINITY;
    for (r, row) in rows.enumerate() {
        for (k, c) in row.iter().enumerate() {
            let square = if c.present {
                (p - c.position).length_squared()
            } else {
                f32::INFINITY
            };
            squares[r * 3 + k] = (square, c.species);
            least = least.min(square);
        }
    }
    if least == f32::INFINITY {
        return None;
    }
    let d = least.sqrt();
    // A square whose root rounds to `d` is at most about `least * (1 + 2 eps)`.
    let near = least * (1.0 + 4.0 * f32::EPSILON);
    squares
        .iter()
        .find(|&&(square, _)| square <= near && square.sqrt() == d)
        .map(|&(_, species)| (d, species))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The search `nearest_canopy` replaces: tree by tree, by distance, the first of equals.
    fn by_distance(p: Vec2, trees: &[Canopy]) -> Option<(f32, usize)> {
        let mut nearest: Option<(f32, usize)> = None;
        for c in trees.iter().filter(|c| c.present) {
            let d = p.distance(c.position);
            if nearest.is_none_or(|(best, _)| d < best) {
                nearest = Some((d, c.species));
            }
        }
        nearest
    }

    /// An offset of a few kinds: any, one of a handful shared between trees (equal
    /// distances), or one a few ulps from a shared one (squares that differ by little and
    /// may round to one distance).
    fn offset() -> impl Strategy<Value = Vec2> {
        let shared = prop::sample::select(vec![
            Vec2::new(1.5, 2.25),
            Vec2::new(-2.25, 1.5),
            Vec2::new(0.3, -0.7),
        ]);
        prop_oneof![
            (-6.0f32..6.0, -6.0f32..6.0).prop_map(|(x, y)| Vec2::new(x, y)),
            shared.clone(),
            (shared, -3i32..=3, -3i32..=3).prop_map(|(v, a, b)| {
                let nudge = |x: f32, n: i32| f32::from_bits((x.to_bits() as i32 + n) as u32);
                Vec2::new(nudge(v.x, a), nudge(v.y, b))
            }),
        ]
    }

    proptest! {
        /// Squared distances and one square root find the tree a search by distance finds,
        /// with the same distance's bits, ties and near ties included.
        #[test]
        fn nearest_canopy_is_the_first_nearest_by_distance(
            p in (0.0f32..100.0, 0.0f32..100.0),
            trees in prop::collection::vec((offset(), any::<bool>(), 0usize..5), 9),
        ) {
            let p = Vec2::new(p.0, p.1);
            let trees: Vec<Canopy> = trees
                .into_iter()
                .map(|(offset, present, species)| Canopy {
                    position: p + offset,
                    species,
                    priority: 0,
                    present,
                })
                .collect();
            let found = nearest_canopy(p, trees.chunks(3));
            let expected = by_distance(p, &trees);
            prop_assert_eq!(found.map(|(d, s)| (d.to_bits(), s)), expected.map(|(d, s)| (d.to_bits(), s)));
        }
    }
}
