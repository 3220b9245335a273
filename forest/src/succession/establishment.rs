//! Establishment: seedlings planted, or seeds from parent trees and from beyond the forest
//! taking where the ground has light and room.

use rayon::prelude::*;
use sylva_base::hash::{hash_cell, mix, unit_f32};

use super::stats::YearStats;
use super::stem::{State, Stem};
use super::{ESTABLISHMENT_CELL, PLANTED_AGE, PLANTED_HEIGHT, RAIN_CELL, Succession, salt};
use crate::error::ForestError;
use crate::life::SEEDLING_HEIGHT;

impl Succession {
    /// Plants `species` at `per_hectare` trees (at most 2,500: one per 2 m cell) on a square
    /// lattice over the whole area, each seedling a little off its lattice point, as a
    /// forester plants a stand: a dense even-aged start, where self-thinning shows best.
    /// Returns how many were planted; before the first year only (the lattice and the
    /// seedlings' identities are of the world, so tiles plant the same trees).
    ///
    /// ```
    /// use sylva_forest::succession::{Succession, SuccessionOptions};
    /// use sylva_forest::{Rect, Species};
    /// use sylva_terrain::glam::Vec2;
    ///
    /// let species = vec![Species::from_preset("kenwood-leafy", 3)?];
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
    /// let mut stand = Succession::new(species, region, SuccessionOptions::default().with_halo(0.0))?;
    /// assert_eq!(stand.plant(0, 2500.0)?, 2500);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn plant(&mut self, species: usize, per_hectare: f32) -> Result<usize, ForestError> {
        sylva_base::range::check(
            "per_hectare",
            f64::from(per_hectare),
            per_hectare > 0.0 && per_hectare <= 2500.0,
            "0 < trees per hectare <= 2500",
        )?;
        if species >= self.species.len() || self.year > 0 {
            return Err(ForestError::PlantingTooLate {
                species,
                year: self.year,
            });
        }
        let spacing = (10_000.0 / per_hectare).sqrt();
        // Lattice points at the centres of a global grid of `spacing`, so a square of whole
        // cells holds exactly its share.
        let (i0, j0) = (
            (self.area.min.x / spacing).floor() as i64,
            (self.area.min.y / spacing).floor() as i64,
        );
        let (i1, j1) = (
            (self.area.max.x / spacing).ceil() as i64,
            (self.area.max.y / spacing).ceil() as i64,
        );
        let count = ((i1 - i0).max(0) as usize) * ((j1 - j0).max(0) as usize);
        if self.stems.len() + count > self.options.max_stems {
            return Err(ForestError::TooManyStems {
                stems: self.stems.len() + count,
                limit: self.options.max_stems,
            });
        }
        let seed = self.options.seed;
        let before = self.stems.len();
        for j in j0..j1 {
            for i in i0..i1 {
                let h = hash_cell(seed, i, j, salt::PLANT);
                // Off the lattice point by up to a fifth of the spacing, staying in its cell.
                let jitter = 0.2 * spacing.min(ESTABLISHMENT_CELL);
                let p = [
                    (i as f32 + 0.5) * spacing + jitter * (unit_f32(h) - 0.5),
                    (j as f32 + 0.5) * spacing + jitter * (unit_f32(mix(h)) - 0.5),
                ];
                if !self.area.contains(p.into()) {
                    continue;
                }
                let cell = [
                    (p[0] / ESTABLISHMENT_CELL).floor() as i64,
                    (p[1] / ESTABLISHMENT_CELL).floor() as i64,
                ];
                self.stems.push(Stem {
                    position: p,
                    height: PLANTED_HEIGHT * (0.5 + unit_f32(mix(h ^ 2))),
                    vigour: 1.0,
                    key: hash_cell(seed, cell[0], cell[1], salt::KEY),
                    age: PLANTED_AGE,
                    species: species as u8,
                    state: State::Live,
                    suppressed: 0,
                    dead_years: 0,
                    fall: 0,
                });
            }
        }
        Ok(self.stems.len() - before)
    }

    /// Seeds from mature trees and from beyond land, and take where the ground has light and
    /// room; where several land in one free cell, the one with the lowest draw takes it.
    pub(super) fn seed(&mut self, stats: &mut YearStats) -> Result<(), ForestError> {
        let (year, seed) = (self.year, self.options.seed);
        self.occupied.fill(false);
        for s in &self.stems {
            if s.state != State::Fallen
                && let Some(c) = self.cell(s.position)
            {
                self.occupied[c] = true;
            }
        }
        let this = &*self;
        // Seeds of the forest's own trees, each tree's from its own draws.
        let mut landed: Vec<(usize, u64, u8, [f32; 2])> = this
            .stems
            .par_iter()
            .flat_map_iter(|s| {
                let kind = &this.kinds[usize::from(s.species)];
                let fertile = s.state.is_alive() && f32::from(s.age) >= kind.life.maturity_age;
                let light = if fertile {
                    this.grid.light(s.position[0], s.position[1], s.top())
                } else {
                    0.0
                };
                let expected = kind.life.seeds_per_year * light;
                let h = mix(s.key ^ mix(seed ^ u64::from(year) ^ salt::SEEDS));
                let n = expected.floor() as u32 + u32::from(unit_f32(h) < expected.fract());
                (0..n).filter_map(move |k| {
                    let d = mix(h ^ u64::from(k + 1));
                    let distance = -(1.0 - unit_f32(d)).max(1e-6).ln() * kind.life.dispersal;
                    let angle = unit_f32(mix(d)) * std::f32::consts::TAU;
                    let p = [
                        s.position[0] + distance * angle.cos(),
                        s.position[1] + distance * angle.sin(),
                    ];
                    this.landing(p, s.species, mix(d ^ salt::TAKE))
                })
            })
            .collect();
        // Seed from beyond: per cell of a global grid, so tiles draw the same.
        let rain = self.options.seed_rain * RAIN_CELL * RAIN_CELL / 10_000.0;
        let (columns, rows) = self.area.cells(RAIN_CELL);
        let rained: Vec<(usize, u64, u8, [f32; 2])> = rows
            .into_par_iter()
            .flat_map_iter(|j| {
                columns.clone().flat_map(move |i| {
                    this.kinds.iter().enumerate().filter_map(move |(k, kind)| {
                        let h =
                            hash_cell(seed, i, j, salt::RAIN ^ (u64::from(year) << 8) ^ k as u64);
                        if unit_f32(h) >= rain * kind.rain {
                            return None;
                        }
                        let p = [
                            (i as f32 + unit_f32(mix(h))) * RAIN_CELL,
                            (j as f32 + unit_f32(mix(h ^ 1))) * RAIN_CELL,
                        ];
                        this.landing(p, k as u8, mix(h ^ salt::TAKE))
                    })
                })
            })
            .collect();
        landed.extend(rained);
        landed.par_sort_unstable_by_key(|&(cell, priority, ..)| (cell, priority));
        landed.dedup_by_key(|l| l.0);
        if self.stems.len() + landed.len() > self.options.max_stems {
            return Err(ForestError::TooManyStems {
                stems: self.stems.len() + landed.len(),
                limit: self.options.max_stems,
            });
        }
        for (_, _, species, position) in landed {
            let cell = [
                (position[0] / ESTABLISHMENT_CELL).floor() as i64,
                (position[1] / ESTABLISHMENT_CELL).floor() as i64,
            ];
            if self.region.contains(position.into()) {
                stats.recruits_per_ha += 1.0;
            }
            self.stems.push(Stem {
                position,
                height: SEEDLING_HEIGHT,
                vigour: 1.0,
                key: hash_cell(seed, cell[0], cell[1], salt::KEY ^ (u64::from(year) << 16)),
                age: 0,
                species,
                state: State::Live,
                suppressed: 0,
                dead_years: 0,
                fall: 0,
            });
        }
        Ok(())
    }

    /// Where a seed of `species` landing at `p` takes: its cell and priority, if the cell is
    /// in the area and free and the ground's light lets it germinate.
    fn landing(&self, p: [f32; 2], species: u8, h: u64) -> Option<(usize, u64, u8, [f32; 2])> {
        let cell = self.cell(p)?;
        if self.occupied[cell] {
            return None;
        }
        let life = &self.kinds[usize::from(species)].life;
        let light = self.grid.ground(p[0], p[1]);
        (unit_f32(h) < life.growth_in(light)).then_some((cell, h, species, p))
    }

    /// The establishment cell of `p`, if `p` lies in the area.
    fn cell(&self, p: [f32; 2]) -> Option<usize> {
        if !self.area.contains(p.into()) {
            return None;
        }
        let i = (p[0] / ESTABLISHMENT_CELL).floor() as i64 - self.first_cell[0];
        let j = (p[1] / ESTABLISHMENT_CELL).floor() as i64 - self.first_cell[1];
        if !(i >= 0 && j >= 0 && (i as usize) < self.cells[0] && (j as usize) < self.cells[1]) {
            return None;
        }
        Some(j as usize * self.cells[0] + i as usize)
    }
}
