//! A year's figures over the region: stems, basal area and heights by species, the dead,
//! recruits and deaths, the canopy's cover.

use super::Succession;
use super::stats::{MIN_DIAMETER, SpeciesYear, YearStats};
use super::stem::State;

impl Succession {
    /// The year's figures over the region.
    pub(super) fn tally(&self, stats: &mut YearStats) {
        let size = self.region.max - self.region.min;
        let hectares = f64::from(size.x) * f64::from(size.y) / 10_000.0;
        let per_ha = |n: f64| (n / hectares) as f32;
        let n = self.species.len();
        let (mut stems, mut saplings, mut basal, mut heights) =
            (vec![0f64; n], vec![0f64; n], vec![0f64; n], vec![0f64; n]);
        let (mut dead, mut fallen, mut squares) = (0f64, 0f64, 0f64);
        for s in &self.stems {
            if !self.region.contains(s.position.into()) {
                continue;
            }
            match s.state {
                State::Dead | State::Snag => dead += 1.0,
                State::Fallen => fallen += 1.0,
                _ => {
                    let k = usize::from(s.species);
                    let d = f64::from(self.kinds[k].life.diameter(s.height));
                    if d >= f64::from(MIN_DIAMETER) {
                        stems[k] += 1.0;
                        basal[k] += std::f64::consts::PI * d * d / 4.0;
                        heights[k] += f64::from(s.top());
                        squares += d * d;
                    } else {
                        saplings[k] += 1.0;
                    }
                }
            }
        }
        let all: f64 = stems.iter().sum();
        for k in 0..n {
            stats.species[k] = SpeciesYear {
                stems_per_ha: per_ha(stems[k]),
                saplings_per_ha: per_ha(saplings[k]),
                basal_area: per_ha(basal[k]),
                mean_height: if stems[k] > 0.0 {
                    (heights[k] / stems[k]) as f32
                } else {
                    0.0
                },
            };
        }
        stats.stems_per_ha = per_ha(all);
        stats.basal_area = per_ha(basal.iter().sum());
        stats.mean_height = if all > 0.0 {
            (heights.iter().sum::<f64>() / all) as f32
        } else {
            0.0
        };
        stats.mean_diameter = if all > 0.0 {
            (100.0 * (squares / all).sqrt()) as f32
        } else {
            0.0
        };
        stats.dead_standing_per_ha = per_ha(dead);
        stats.fallen_per_ha = per_ha(fallen);
        stats.recruits_per_ha = per_ha(f64::from(stats.recruits_per_ha));
        for d in &mut stats.deaths_per_ha {
            *d = per_ha(f64::from(*d));
        }
        stats.canopy_cover =
            self.grid
                .cover_within(5.0, self.region.min.into(), self.region.max.into());
    }
}
