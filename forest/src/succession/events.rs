//! Growth events (Garden of Eden 7.11): storms, lightning and disease, each seeded by the
//! world seed and the year (and, for lightning, the place), each changing the trees it hits.

use sylva_base::hash::{hash_cell, mix, unit_f32};

use super::stats::{Event, YearStats};
use super::stem::{Cause, State, Stem};
use super::{Succession, draw, kill};

/// Side of the cells lightning is drawn for, metres (a hectare).
const STRIKE_CELL: f32 = 100.0;
/// How far from a strike the tallest tree draws it, metres.
const STRIKE_REACH: f32 = 15.0;
/// Trees shorter than this, metres, stand below a storm's reach.
const STORM_HEIGHT: f32 = 10.0;
/// Yearly chances of a diseased tree catching it and dying of it.
const INFECTION: f32 = 0.1;
const DISEASE_DEATH: f32 = 0.12;

mod salt {
    pub(super) const STORM: u64 = 0x0005_7023;
    pub(super) const STORM_HIT: u64 = 0x0005_7024;
    pub(super) const GUST: u64 = 0x0005_7025;
    pub(super) const STRIKE: u64 = 0x11_6471;
    pub(super) const OUTBREAK: u64 = 0x0d15_ea5e;
    pub(super) const INFECT: u64 = 0x0d15_ea5f;
    pub(super) const DISEASE_DEATH: u64 = 0x0d15_ea60;
}

/// A year-level draw: the same for every tile.
fn year_draw(seed: u64, year: u32, salt: u64, k: u64) -> f32 {
    unit_f32(mix(seed ^ mix((u64::from(year) << 24) ^ salt ^ (k << 8))))
}

/// This year's storm, lightning and disease, if any.
pub(super) fn strike(forest: &mut Succession, stats: &mut YearStats) {
    storm(forest, stats);
    lightning(forest, stats);
    disease(forest, stats);
}

/// A storm breaks or throws tall trees, the more the taller, the more exposed (the light at
/// their tops: a tree above its neighbours takes the wind) and the harder its gusts blow
/// where they stand ([`gusts`]), thrown ones falling along it.
fn storm(forest: &mut Succession, stats: &mut YearStats) {
    let (seed, year) = (forest.options.seed, forest.year);
    if year_draw(seed, year, salt::STORM, 0) >= forest.options.storm_rate {
        return;
    }
    let direction = year_draw(seed, year, salt::STORM, 1);
    let strength = 0.3 + 0.7 * year_draw(seed, year, salt::STORM, 2);
    let fall = (direction * 256.0) as u8;
    let (mut thrown, mut broken) = (0, 0);
    let (grid, region) = (&forest.grid, forest.region);
    for s in &mut forest.stems {
        if !s.state.is_alive() || s.height < STORM_HEIGHT {
            continue;
        }
        let exposure = grid.light(s.position[0], s.position[1], s.top());
        let tall = ((s.height - STORM_HEIGHT) / 15.0).clamp(0.0, 1.0);
        let gust = gusts(seed, year, s.position);
        let p = strength * tall * tall * (0.2 + 0.8 * exposure) * 1.5 * gust * gust;
        let d = draw(seed, s.key, year, salt::STORM_HIT);
        if d >= p {
            continue;
        }
        let inside = region.contains(s.position.into());
        // Half the trees hit are thrown (every broken one hit again).
        if d < 0.5 * p || s.state == State::BrokenTop {
            s.state = State::Fallen;
            s.fall = fall;
            kill(s, Cause::Storm, region, stats);
            thrown += u32::from(inside);
        } else {
            s.state = State::BrokenTop;
            broken += u32::from(inside);
        }
    }
    stats.events.push(Event::Storm {
        direction: direction * 360.0,
        strength,
        thrown,
        broken,
    });
}

/// Side of the cells of a storm's gust field, metres: storms throw trees in patches of about
/// this size, the gaps pioneers fill.
const GUST_CELL: f32 = 80.0;

/// A storm's local strength at `p`, 0 to 1: value noise over a global grid of
/// [`GUST_CELL`], smoothly interpolated, so the same for every tile.
fn gusts(seed: u64, year: u32, p: [f32; 2]) -> f32 {
    let (x, z) = (p[0] / GUST_CELL, p[1] / GUST_CELL);
    let (i, j) = (x.floor(), z.floor());
    let (fx, fz) = (x - i, z - j);
    let smooth = |t: f32| t * t * (3.0 - 2.0 * t);
    let corner = |di: i64, dj: i64| {
        unit_f32(hash_cell(
            seed,
            i as i64 + di,
            j as i64 + dj,
            salt::GUST ^ (u64::from(year) << 8),
        ))
    };
    let (sx, sz) = (smooth(fx), smooth(fz));
    let top = corner(0, 0) + (corner(1, 0) - corner(0, 0)) * sx;
    let bottom = corner(0, 1) + (corner(1, 1) - corner(0, 1)) * sx;
    top + (bottom - top) * sz
}

/// Lightning, per hectare of a global grid: the tallest living tree near each strike dies,
/// its trunk split (a snag) or whole.
fn lightning(forest: &mut Succession, stats: &mut YearStats) {
    let (seed, year) = (forest.options.seed, forest.year);
    let (columns, rows) = forest.area.cells(STRIKE_CELL);
    let rate = forest.options.lightning_rate * STRIKE_CELL * STRIKE_CELL / 10_000.0;
    for j in rows {
        for i in columns.clone() {
            let h = hash_cell(seed, i, j, salt::STRIKE ^ (u64::from(year) << 8));
            if unit_f32(h) >= rate {
                continue;
            }
            let at = [
                (i as f32 + unit_f32(mix(h))) * STRIKE_CELL,
                (j as f32 + unit_f32(mix(h ^ 1))) * STRIKE_CELL,
            ];
            // The tallest living tree within reach; ties to the lowest key, so the choice
            // does not depend on the order trees are held in.
            let hit = forest
                .stems
                .iter()
                .enumerate()
                .filter(|(_, s)| {
                    s.state.is_alive()
                        && (s.position[0] - at[0]).hypot(s.position[1] - at[1]) <= STRIKE_REACH
                })
                .max_by(|(_, a), (_, b)| a.top().total_cmp(&b.top()).then(b.key.cmp(&a.key)))
                .map(|(k, _)| k);
            let Some(k) = hit else {
                continue;
            };
            let split = unit_f32(mix(h ^ 2)) < 0.6;
            let region = forest.region;
            let s = &mut forest.stems[k];
            kill(s, Cause::Lightning, region, stats);
            if split {
                s.state = State::Snag;
            }
            if region.contains(at.into()) {
                stats.events.push(Event::Lightning {
                    position: at,
                    split,
                });
            }
        }
    }
}

/// A disease breaks out in one species now and then and, while it lasts, thins the crowns of
/// the trees it catches (dieback); [`disease_death`] kills them.
fn disease(forest: &mut Succession, stats: &mut YearStats) {
    let (seed, year) = (forest.options.seed, forest.year);
    if forest.outbreak.is_some_and(|(_, until)| year > until) {
        forest.outbreak = None;
    }
    if forest.outbreak.is_none()
        && year_draw(seed, year, salt::OUTBREAK, 0) < forest.options.disease_rate
    {
        let n = forest.species.len() as u64;
        let species = (mix(seed ^ u64::from(year) ^ salt::OUTBREAK) % n) as usize;
        let years = 6 + (year_draw(seed, year, salt::OUTBREAK, 1) * 5.0) as u32;
        forest.outbreak = Some((species, year + years - 1));
        stats.events.push(Event::Disease { species, years });
    }
    let Some((species, _)) = forest.outbreak else {
        return;
    };
    for s in &mut forest.stems {
        if s.state == State::Live
            && usize::from(s.species) == species
            && s.height > 2.0
            && draw(seed, s.key, year, salt::INFECT) < INFECTION
        {
            s.state = State::Dieback;
        }
    }
}

/// Whether a tree dying back dies of it this year.
pub(super) fn disease_death(s: &Stem, seed: u64, year: u32) -> Option<Cause> {
    (s.state == State::Dieback && draw(seed, s.key, year, salt::DISEASE_DEATH) < DISEASE_DEATH)
        .then_some(Cause::Disease)
}
