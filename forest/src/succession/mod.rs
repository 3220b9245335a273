//! A forest over time (Garden of Eden 7.9 to 7.11): a region simulated year by year from bare
//! ground. Seeds from parent trees (and a little from beyond) take where the ground gets light
//! and room; every tree grows by the light that reaches its top through its neighbours'
//! crowns, answering it as its species does (pioneers and shade-tolerant trees as in the
//! growth crate's `Response`); trees die of suppression, age and events: storms that break or
//! throw tall exposed trees along the wind, lightning that kills or splits the tallest tree
//! near a strike, disease that thins one species' crowns. Gaps they leave are refilled by
//! whatever the light there favours.
//!
//! ```
//! use sylva_forest::succession::{Succession, SuccessionOptions};
//! use sylva_forest::{Rect, Species};
//! use sylva_terrain::glam::Vec2;
//!
//! let mut birch = Species::from_preset("kenwood-leafy", 3)?;
//! birch.life = birch.life.with_shade_tolerance(0.1).with_growth_rate(0.07);
//! let region = Rect::new(Vec2::ZERO, Vec2::splat(60.0));
//! let mut forest = Succession::new(vec![birch], region, SuccessionOptions::default())?;
//! forest.run(40, |_| Ok(()))?;
//! let year = forest.stats().last().unwrap();
//! assert_eq!(year.year, 40);
//! assert!(year.stems_per_ha > 50.0 && year.mean_height > 5.0);
//! # Ok::<(), sylva_forest::ForestError>(())
//! ```
//!
//! Everything drawn is a hash of the world seed, the year and a place or a tree's identity
//! (itself a hash of where and when it germinated), never of the order trees are held in:
//! a run is the same at any thread count, and a tile simulated with a halo holds the trees
//! a larger run holds there wherever the halo kept their history the same.

mod establishment;
mod events;
mod light;
mod options;
mod snapshot;
mod stats;
mod stem;
mod tally;

use rayon::prelude::*;
use sylva_base::hash::{mix, unit_f32};

use crate::density::Rect;
use crate::error::ForestError;
use crate::life::Life;
use crate::species::Species;

pub use light::{CELL as LIGHT_CELL, EXTINCTION, LAYERS as LIGHT_LAYERS};
pub use options::SuccessionOptions;
pub use snapshot::{Snapshot, SnapshotTree};
pub use stats::{Event, MIN_DIAMETER, SpeciesYear, YearStats, thinning_phase, thinning_slope};
pub use stem::{Cause, State, Stem};

use light::LightGrid;

/// Side of the cells seedlings take, metres: a cell holds one tree.
pub const ESTABLISHMENT_CELL: f32 = 2.0;
/// Side of the cells seed from beyond the forest is drawn for, metres.
const RAIN_CELL: f32 = 10.0;
/// Most simulated area, square metres (the halo included): 50 km^2, a square of about
/// 7 km, whose light grid is 600 MB (192 bytes a 4 m column). Larger worlds are simulated as
/// tiles.
pub const MAX_AREA: f64 = 5e7;
/// Years a dead tree stands whole before it decays to a snag, and as a snag before it falls
/// and rots; years a fallen tree lies.
const DEAD_YEARS: u8 = 6;
const SNAG_YEARS: u8 = 10;
const FALLEN_YEARS: u8 = 25;
/// Dead trees shorter than this, metres, are gone at once: suppressed poles collapse, only
/// trees of some size stand as snags.
const STANDING_DEAD_HEIGHT: f32 = 14.0;

/// The radius a crown shades, as a share of the drawn tree's widest reach: the reach is the
/// tip of its longest limb, and the leaf area thins out towards it (with the whole reach,
/// the bundled spruce's crowns would each shade 500 m^2 at 20 m and stands would hold a third
/// of the stems they do).
pub const CROWN_SHARE: f32 = 0.6;

/// Where a crown starts, as a share of the tree's height: the lower two fifths of a
/// stem are bare.
const CROWN_BASE: f32 = 0.4;

/// How much trees' growth differs, as a share either way: each tree's own, from its
/// identity.
const VIGOUR_SPREAD: f32 = 0.2;

/// A planted seedling's height (the middle of the nursery's spread, half to one and a half
/// times it), metres, and age, years.
const PLANTED_HEIGHT: f32 = 0.4;
const PLANTED_AGE: u16 = 3;

/// Trees killed by suppression stand dead only above this height, metres: the shaded poles
/// of a thinning stand break and rot within a year or two.
const SUPPRESSED_STANDING_HEIGHT: f32 = 16.0;

/// Salts of the independent draws made per tree and year.
mod salt {
    pub(super) const AGE: u64 = 0xa6e;
    pub(super) const SEEDS: u64 = 0x5eed5;
    pub(super) const RAIN: u64 = 0x4a17;
    pub(super) const TAKE: u64 = 0x7a4e;
    pub(super) const KEY: u64 = 0x4e7;
    pub(super) const PLANT: u64 = 0x91a47;
    pub(super) const VIGOUR: u64 = 0x0016_0e55;
}

/// What a species brings to the simulation: its life and its crown's shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Kind {
    pub(crate) life: Life,
    /// Crown radius as a share of height, from the drawn canopy tree ([`CROWN_SHARE`] of
    /// its widest reach).
    pub(crate) crown: f32,
    /// Share of the seed from beyond the forest.
    pub(crate) rain: f32,
}

/// A region's forest, year by year.
#[derive(Debug, Clone)]
pub struct Succession {
    species: Vec<Species>,
    kinds: Vec<Kind>,
    region: Rect,
    /// The region and its halo: what is simulated.
    area: Rect,
    options: SuccessionOptions,
    year: u32,
    stems: Vec<Stem>,
    grid: LightGrid,
    /// Per establishment cell of the area, whether a tree stands there.
    occupied: Vec<bool>,
    /// Per tree (in `stems`' order), the leaf area it put in each layer of its own light
    /// column this year.
    own: Vec<u32>,
    /// The establishment cells: the global lattice's index of the first, and how many.
    first_cell: [i64; 2],
    cells: [usize; 2],
    /// The disease raging, if one is: its species and its last year.
    outbreak: Option<(usize, u32)>,
    history: Vec<YearStats>,
}

impl Succession {
    /// Bare ground over `region` (and its halo), to be grown by [`Succession::step`] with
    /// `species`. An error for no species, a life out of range, or an area beyond
    /// [`MAX_AREA`].
    pub fn new(
        species: Vec<Species>,
        region: Rect,
        options: SuccessionOptions,
    ) -> Result<Self, ForestError> {
        options.check()?;
        if species.is_empty() || species.len() > 255 || !species.iter().any(|s| s.weight > 0.0) {
            return Err(ForestError::NoSpecies);
        }
        let area = region.expanded(options.halo);
        let size = area.max - area.min;
        if region.is_empty() || f64::from(size.x) * f64::from(size.y) > MAX_AREA {
            return Err(ForestError::SuccessionArea {
                size: region.max - region.min,
                halo: options.halo,
                limit: MAX_AREA,
            });
        }
        let total: f32 = species.iter().map(|s| s.weight.max(0.0)).sum();
        let mut kinds = Vec::with_capacity(species.len());
        for s in &species {
            s.life.check()?;
            let canopy = s.canopy()?;
            let height = s.drawn_height(s.generations, 3)?;
            kinds.push(Kind {
                life: s.life,
                crown: (CROWN_SHARE * 0.5 * canopy.measured / height).clamp(0.05, 2.0),
                rain: s.weight.max(0.0) / total,
            });
        }
        // Establishment cells on the global lattice, so runs over overlapping areas (tiles)
        // contest the same cells.
        let first_cell = [
            (area.min.x / ESTABLISHMENT_CELL).floor() as i64,
            (area.min.y / ESTABLISHMENT_CELL).floor() as i64,
        ];
        let cells = [
            ((area.max.x / ESTABLISHMENT_CELL).ceil() as i64 - first_cell[0]) as usize,
            ((area.max.y / ESTABLISHMENT_CELL).ceil() as i64 - first_cell[1]) as usize,
        ];
        let history = vec![YearStats {
            species: vec![SpeciesYear::default(); species.len()],
            ..YearStats::default()
        }];
        Ok(Succession {
            grid: LightGrid::new(area.min.into(), area.max.into()),
            occupied: vec![false; cells[0] * cells[1]],
            own: Vec::new(),
            first_cell,
            cells,
            species,
            kinds,
            region,
            area,
            options,
            year: 0,
            stems: Vec::new(),
            outbreak: None,
            history,
        })
    }

    /// The year reached (0 before the first step).
    pub fn year(&self) -> u32 {
        self.year
    }

    /// The species, in their order.
    pub fn species(&self) -> &[Species] {
        &self.species
    }

    /// The region reported and drawn (the halo is simulated around it).
    pub fn region(&self) -> Rect {
        self.region
    }

    /// The settings.
    pub fn options(&self) -> &SuccessionOptions {
        &self.options
    }

    /// Every tree simulated, the halo's included.
    pub fn stems(&self) -> &[Stem] {
        &self.stems
    }

    /// The statistics of every year so far, from year 0.
    pub fn stats(&self) -> &[YearStats] {
        &self.history
    }

    /// Runs `years` more years, handing each year's statistics to `each` (an error from it
    /// stops the run).
    pub fn run(
        &mut self,
        years: u32,
        mut each: impl FnMut(&YearStats) -> Result<(), ForestError>,
    ) -> Result<(), ForestError> {
        for _ in 0..years {
            self.step()?;
            if let Some(last) = self.history.last() {
                each(last)?;
            }
        }
        Ok(())
    }

    /// One year: light, growth and mortality, events, seeds.
    pub fn step(&mut self) -> Result<(), ForestError> {
        self.year += 1;
        let year = self.year;
        self.shade();
        let mut stats = YearStats {
            year,
            species: vec![SpeciesYear::default(); self.species.len()],
            ..YearStats::default()
        };
        self.grow(&mut stats);
        events::strike(self, &mut stats);
        self.decay();
        self.seed(&mut stats)?;
        self.tally(&mut stats);
        self.history.push(stats);
        Ok(())
    }

    /// Fills the light grid from the crowns as they stand.
    fn shade(&mut self) {
        self.grid.clear();
        self.own.clear();
        self.own.resize(self.stems.len(), 0);
        for (s, own) in self.stems.iter().zip(&mut self.own) {
            if !s.state.is_alive() {
                continue;
            }
            let kind = &self.kinds[usize::from(s.species)];
            let top = s.top();
            let radius = (kind.crown * s.height).max(0.1);
            let lai = kind.life.leaf_area_index
                * match s.state {
                    State::Dieback => 0.3,
                    _ => 1.0,
                };
            *own = self.grid.deposit(
                s.position[0],
                s.position[1],
                radius,
                CROWN_BASE * top,
                top,
                lai,
            );
        }
        self.grid.accumulate();
    }

    /// Every living tree grows by its light, and dies of suppression or age; each on its
    /// own, so in parallel.
    fn grow(&mut self, stats: &mut YearStats) {
        let (kinds, grid, year, seed) = (&self.kinds, &self.grid, self.year, self.options.seed);
        let own = &self.own;
        let deaths: Vec<Option<Cause>> = self
            .stems
            .par_iter_mut()
            .zip(own.par_iter())
            .map(|(s, &own)| {
                if !s.state.is_alive() {
                    return None;
                }
                let life = &kinds[usize::from(s.species)].life;
                // The light at the crown's centre, the tree's own leaves left out: the
                // neighbours' crowns above it and beside it in its own layers shade it.
                let top = s.top();
                let centre = top * (1.0 + CROWN_BASE) / 2.0;
                let light = grid.light_in_crown(s.position[0], s.position[1], centre, top, own);
                let mut share = life.growth_in(light);
                match s.state {
                    State::Dieback => share *= 0.3,
                    State::BrokenTop => share *= 0.6,
                    _ => {}
                }
                // Trees of a species differ in vigour (their genes, their spot), so stands of
                // equal trees still sort themselves into dominant and suppressed.
                let vigour =
                    1.0 + VIGOUR_SPREAD * (2.0 * unit_f32(mix(s.key ^ salt::VIGOUR)) - 1.0);
                s.height = (s.height + vigour * life.potential_growth(s.height) * share)
                    .min(1.2 * life.max_height);
                s.vigour = share;
                s.age = s.age.saturating_add(1);
                s.suppressed = if share < 0.1 {
                    s.suppressed.saturating_add(1)
                } else {
                    0
                };
                if s.suppressed > life.suppression_years() {
                    return Some(Cause::Suppression);
                }
                let old = f32::from(s.age) > 1.5 * life.max_age;
                if old || draw(seed, s.key, year, salt::AGE) < life.age_mortality(f32::from(s.age))
                {
                    return Some(Cause::Age);
                }
                events::disease_death(s, seed, year)
            })
            .collect();
        for (s, cause) in self.stems.iter_mut().zip(deaths) {
            if let Some(cause) = cause {
                kill(s, cause, self.region, stats);
            }
        }
    }

    /// Dead trees decay: dead standing to snag, snag to nothing; fallen trees rot away.
    fn decay(&mut self) {
        for s in &mut self.stems {
            if s.state.is_alive() {
                continue;
            }
            s.dead_years = s.dead_years.saturating_add(1);
            if s.state == State::Dead && s.dead_years > DEAD_YEARS {
                s.state = State::Snag;
                s.dead_years = 0;
            }
        }
        self.stems.retain(|s| match s.state {
            State::Snag => s.dead_years <= SNAG_YEARS,
            State::Fallen => s.dead_years <= FALLEN_YEARS,
            State::Dead => s.height >= STANDING_DEAD_HEIGHT,
            _ => true,
        });
    }
}

/// A uniform draw in [0, 1) for tree `key` in `year`, of the kind `salt`.
pub(crate) fn draw(seed: u64, key: u64, year: u32, salt: u64) -> f32 {
    unit_f32(mix(key ^ mix(seed ^ (u64::from(year) << 20) ^ salt)))
}

/// `s` dies of `cause`: it stands dead if it was tall enough, else it is gone at the next
/// decay; the death is counted if it stood in `region`.
pub(crate) fn kill(s: &mut Stem, cause: Cause, region: Rect, stats: &mut YearStats) {
    if s.state != State::Fallen {
        s.state = State::Dead;
    }
    if cause == Cause::Suppression && s.height < SUPPRESSED_STANDING_HEIGHT {
        // A suppressed pole snaps and rots where it stands: gone at the next decay.
        s.height = 0.0;
    }
    s.dead_years = 0;
    if region.contains(s.position.into()) {
        let k = Cause::ALL.iter().position(|c| *c == cause).unwrap_or(0);
        stats.deaths_per_ha[k] += 1.0;
    }
}
