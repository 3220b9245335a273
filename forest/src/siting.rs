//! Where the terrain lets trees stand, and why not where it does not: each candidate spot's
//! verdict under the [`Constraints`], and the count of every reason over a region, so that a
//! forest on real land that comes out thin says what thinned it (a slope limit on mountains,
//! a treeline, a mask).

use rayon::prelude::*;
use sylva_terrain::HeightField;

use crate::config::Constraints;
use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::ForestBuilder;
use crate::siting_report::{Refusal, SitingReport};

impl Constraints {
    /// Sets [`Constraints::max_slope_degrees`].
    #[must_use]
    pub fn with_max_slope_degrees(mut self, degrees: f32) -> Self {
        self.max_slope_degrees = degrees;
        self
    }

    /// Sets [`Constraints::min_height`] and [`Constraints::max_height`].
    #[must_use]
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
    /// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
    ///     .with_budget(1 << 20)
    ///     .with_constraints(Constraints::default().with_height_range(0.0, 500.0));
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
