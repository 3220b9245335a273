//! Where the terrain lets trees stand, and why not where it does not: each candidate spot's
//! verdict under the [`Constraints`], and the count of every reason over a region, so that a
//! forest on real land that comes out thin says what thinned it (a slope limit on mountains,
//! a treeline, a mask).

use rayon::prelude::*;
use sylva_terrain::HeightField;

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::{Constraints, ForestBuilder};

/// Why the terrain refuses a candidate spot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Refusal {
    /// Lower than [`Constraints::min_height`].
    BelowMinHeight,
    /// Higher than [`Constraints::max_height`].
    AboveMaxHeight,
    /// Steeper than [`Constraints::max_slope_degrees`].
    TooSteep,
}

/// What became of the candidate spots of a region: how many the density model (or the
/// snapshot of a forest over time) proposed, how many got a tree, and how many each
/// constraint refused. A spot is counted under the first constraint it fails, in the order
/// height range, slope, mask.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct SitingReport {
    /// Spots proposed.
    pub candidates: u64,
    /// Spots that got a tree.
    pub placed: u64,
    /// Refused as lower than the lowest height with trees.
    pub below_min_height: u64,
    /// Refused as higher than the highest height with trees.
    pub above_max_height: u64,
    /// Refused as steeper than the slope limit.
    pub too_steep: u64,
    /// Refused by the density mask.
    pub masked: u64,
}

impl SitingReport {
    /// Spots refused by the terrain's constraints or the mask.
    pub fn refused(&self) -> u64 {
        self.below_min_height + self.above_max_height + self.too_steep + self.masked
    }

    /// The share of candidates refused, 0 to 1 (0 without candidates).
    pub fn refused_share(&self) -> f64 {
        self.refused() as f64 / self.candidates.max(1) as f64
    }

    /// Counts one spot's verdict.
    pub(crate) fn count(&mut self, verdict: Result<(), Refusal>) {
        self.candidates += 1;
        match verdict {
            Ok(()) => {}
            Err(Refusal::BelowMinHeight) => self.below_min_height += 1,
            Err(Refusal::AboveMaxHeight) => self.above_max_height += 1,
            Err(Refusal::TooSteep) => self.too_steep += 1,
        }
    }

    /// Both reports' counts.
    fn add(self, other: SitingReport) -> SitingReport {
        SitingReport {
            candidates: self.candidates + other.candidates,
            placed: self.placed + other.placed,
            below_min_height: self.below_min_height + other.below_min_height,
            above_max_height: self.above_max_height + other.above_max_height,
            too_steep: self.too_steep + other.too_steep,
            masked: self.masked + other.masked,
        }
    }

    /// The reasons with a count, largest first, each with its count: for messages.
    pub fn reasons(&self) -> Vec<(&'static str, u64)> {
        let mut reasons: Vec<(&'static str, u64)> = [
            ("too steep", self.too_steep),
            ("above the highest height with trees", self.above_max_height),
            ("below the lowest height with trees", self.below_min_height),
            ("outside the mask", self.masked),
        ]
        .into_iter()
        .filter(|&(_, n)| n > 0)
        .collect();
        reasons.sort_by_key(|&(_, n)| std::cmp::Reverse(n));
        reasons
    }
}

impl std::fmt::Display for SitingReport {
    /// "placed 61,204 of 98,112 spots; refused 36,908 (37.6%): 35,100 too steep, ..."
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "placed {} of {} spots; refused {} ({:.1}%)",
            self.placed,
            self.candidates,
            self.refused(),
            100.0 * self.refused_share()
        )?;
        for (k, (reason, n)) in self.reasons().into_iter().enumerate() {
            write!(f, "{} {n} {reason}", if k == 0 { ":" } else { "," })?;
        }
        Ok(())
    }
}

impl Constraints {
    /// Sets [`Constraints::max_slope_degrees`].
    pub fn with_max_slope_degrees(mut self, degrees: f32) -> Self {
        self.max_slope_degrees = degrees;
        self
    }

    /// Sets [`Constraints::min_height`] and [`Constraints::max_height`].
    pub fn with_height_range(mut self, min: f32, max: f32) -> Self {
        self.min_height = min;
        self.max_height = max;
        self
    }

    /// The verdict at (x, z) of `terrain`: the ground's height where trees may stand there,
    /// else the first constraint the spot fails (height range, then slope). The mask is the
    /// caller's. The slope's cosine is worked out once, here, not per spot.
    ///
    /// ```
    /// use sylva_forest::{Constraints, Refusal};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let ground = FlatPlane { height: 2400.0, min: Vec2::ZERO, max: Vec2::splat(100.0) };
    /// let treeline = Constraints::default().with_height_range(0.0, 2000.0);
    /// let site = treeline.site(&ground);
    /// assert_eq!(site(50.0, 50.0), Err(Refusal::AboveMaxHeight));
    /// assert_eq!(Constraints::default().site(&ground)(50.0, 50.0), Ok(2400.0));
    /// ```
    pub fn site<'a>(
        &'a self,
        terrain: &'a dyn HeightField,
    ) -> impl Fn(f32, f32) -> Result<f32, Refusal> + 'a {
        let min_up = self.max_slope_degrees.clamp(0.0, 90.0).to_radians().cos();
        move |x, z| {
            let height = terrain.height(x, z);
            if height < self.min_height {
                Err(Refusal::BelowMinHeight)
            } else if height > self.max_height {
                Err(Refusal::AboveMaxHeight)
            } else if terrain.normal(x, z).y < min_up - 1e-6 {
                Err(Refusal::TooSteep)
            } else {
                Ok(height)
            }
        }
    }
}

impl ForestBuilder {
    /// What the terrain made of `region`'s candidate spots: the same spots and verdicts as
    /// [`ForestBuilder::trees`], counted block by block on every core; `placed` is the
    /// number of trees `trees` gives. An error only when the region would be cut into more
    /// than [`MAX_BLOCKS`](crate::limits::MAX_BLOCKS) blocks.
    ///
    /// ```
    /// use sylva_forest::{Constraints, ForestBuilder, ForestConfig, Rect, Species};
    /// use sylva_terrain::{FlatPlane, glam::Vec2};
    ///
    /// let mut config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?]);
    /// config.budget = 1 << 20;
    /// config.constraints = Constraints::default().with_height_range(0.0, 500.0);
    /// let builder = ForestBuilder::new(config)?;
    /// let region = Rect::new(Vec2::ZERO, Vec2::splat(100.0));
    /// let high = FlatPlane { height: 900.0, min: Vec2::ZERO, max: Vec2::splat(100.0) };
    /// let report = builder.siting(&high, region)?;
    /// assert_eq!(report.placed, 0);
    /// assert_eq!(report.above_max_height, report.candidates);
    /// # Ok::<(), sylva_forest::ForestError>(())
    /// ```
    pub fn siting(
        &self,
        terrain: &(dyn HeightField + Sync),
        region: Rect,
    ) -> Result<SitingReport, ForestError> {
        let blocks = self.blocks(region)?;
        Ok(blocks
            .par_iter()
            .map(|&rect| {
                let mut report = SitingReport::default();
                self.trees_sited(terrain, rect, &mut report);
                report
            })
            .reduce(SitingReport::default, SitingReport::add))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_report_says_its_reasons_largest_first() {
        let report = SitingReport {
            candidates: 100,
            placed: 40,
            below_min_height: 0,
            above_max_height: 10,
            too_steep: 45,
            masked: 5,
        };
        assert_eq!(report.refused(), 60);
        assert!((report.refused_share() - 0.6).abs() < 1e-12);
        assert_eq!(
            report.to_string(),
            "placed 40 of 100 spots; refused 60 (60.0%): 45 too steep, \
             10 above the highest height with trees, 5 outside the mask"
        );
    }

    #[test]
    fn no_candidates_is_no_share() {
        assert_eq!(SitingReport::default().refused_share(), 0.0);
        assert_eq!(
            SitingReport::default().to_string(),
            "placed 0 of 0 spots; refused 0 (0.0%)"
        );
    }
}
