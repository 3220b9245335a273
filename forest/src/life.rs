//! A species' life: how tall it grows with the years (Chapman-Richards), how long it lives,
//! how it answers shade, and how it seeds. The forest over time (`Succession`) runs on it, and
//! a tree of any age is drawn from it ([`Life::form_for_height`]).

use sylva_growth::Response;

/// How a species grows, ages, competes and spreads.
///
/// Height follows the Chapman-Richards curve `H(t) = max_height (1 - exp(-growth_rate t))
/// ^ growth_shape` for a tree in the open; in shade a tree's yearly step along the curve is
/// scaled by [`Life::growth_in`] of the light it gets.
///
/// ```
/// use sylva_forest::Life;
///
/// let oak = Life::default().with_max_height(30.0).with_growth_rate(0.025).with_growth_shape(1.3);
/// assert!((oak.height(80.0) - 24.9).abs() < 0.1);
/// assert!((oak.age_at(oak.height(37.0)) - 37.0).abs() < 1e-2);
/// // A shade-tolerant tree grows on in light a pioneer cannot live in.
/// let (tolerant, pioneer) = (oak.with_shade_tolerance(0.9), oak.with_shade_tolerance(0.1));
/// assert!(tolerant.growth_in(0.1) > 0.3 && pioneer.growth_in(0.1) == 0.0);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct Life {
    /// The height a tree approaches with age, metres (Chapman-Richards' asymptote). Default: 22.
    pub max_height: f32,
    /// How fast it gets there, per year (Chapman-Richards' k). Default: 0.035.
    pub growth_rate: f32,
    /// The curve's shape (Chapman-Richards' p): above 1, slow first years, then the sigmoid.
    /// Default: 1.3.
    pub growth_shape: f32,
    /// The age few trees outlive, years: the yearly chance of dying of age rises with age,
    /// [`Life::age_mortality`], so about one tree in seven reaches it and none half as old
    /// again. Default: 200.
    pub max_age: f32,
    /// The age at which a tree first bears seed, years. Default: 25.
    pub maturity_age: f32,
    /// 0 a pioneer that needs the open sky, 1 a tree that grows on under a closed canopy:
    /// sets the light response (between the growth crate's [`Response::pioneer`] and
    /// [`Response::shade_tolerant`]) and how long a suppressed tree lasts. Default: 0.5.
    pub shade_tolerance: f32,
    /// Mean distance its seeds travel, metres (an exponential kernel: wind-borne birch and
    /// pine far, jay-carried acorns and hazelnuts near). Default: 30.
    pub dispersal: f32,
    /// Seedlings a mature tree in full light sends out a year (before the ground's light
    /// and room decide which take). Default: 3.
    pub seeds_per_year: f32,
    /// Leaf area per unit of crown projection: how deep a shade the crown casts (Beer's
    /// law with extinction 0.5). Default: 4.
    pub leaf_area_index: f32,
}

impl Default for Life {
    /// A generic broadleaf of middling size, tolerance and reach.
    fn default() -> Self {
        Life {
            max_height: 22.0,
            growth_rate: 0.035,
            growth_shape: 1.3,
            max_age: 200.0,
            maturity_age: 25.0,
            shade_tolerance: 0.5,
            dispersal: 30.0,
            seeds_per_year: 3.0,
            leaf_area_index: 4.0,
        }
    }
}

/// Heights below this are seedlings just germinated: the curve starts here.
pub const SEEDLING_HEIGHT: f32 = 0.1;

impl Life {
    /// Sets [`Life::max_height`].
    #[must_use]
    pub fn with_max_height(mut self, metres: f32) -> Self {
        self.max_height = metres;
        self
    }

    /// Sets [`Life::growth_rate`].
    #[must_use]
    pub fn with_growth_rate(mut self, per_year: f32) -> Self {
        self.growth_rate = per_year;
        self
    }

    /// Sets [`Life::growth_shape`].
    #[must_use]
    pub fn with_growth_shape(mut self, shape: f32) -> Self {
        self.growth_shape = shape;
        self
    }

    /// Sets [`Life::max_age`].
    #[must_use]
    pub fn with_max_age(mut self, years: f32) -> Self {
        self.max_age = years;
        self
    }

    /// Sets [`Life::maturity_age`].
    #[must_use]
    pub fn with_maturity_age(mut self, years: f32) -> Self {
        self.maturity_age = years;
        self
    }

    /// Sets [`Life::shade_tolerance`].
    #[must_use]
    pub fn with_shade_tolerance(mut self, tolerance: f32) -> Self {
        self.shade_tolerance = tolerance;
        self
    }

    /// Sets [`Life::dispersal`].
    #[must_use]
    pub fn with_dispersal(mut self, metres: f32) -> Self {
        self.dispersal = metres;
        self
    }

    /// Sets [`Life::seeds_per_year`].
    #[must_use]
    pub fn with_seeds_per_year(mut self, seeds: f32) -> Self {
        self.seeds_per_year = seeds;
        self
    }

    /// Sets [`Life::leaf_area_index`].
    #[must_use]
    pub fn with_leaf_area_index(mut self, lai: f32) -> Self {
        self.leaf_area_index = lai;
        self
    }

    /// Height of an open-grown tree of `age` years (Chapman-Richards), never below
    /// [`SEEDLING_HEIGHT`].
    pub fn height(&self, age: f32) -> f32 {
        let share = (1.0 - (-self.growth_rate * age.max(0.0)).exp()).powf(self.growth_shape);
        (self.max_height * share).max(SEEDLING_HEIGHT)
    }

    /// The age at which an open-grown tree reaches `height`: the inverse of
    /// [`Life::height`] (its "effective age"; a suppressed tree is older than this).
    pub fn age_at(&self, height: f32) -> f32 {
        let share = (height / self.max_height).clamp(0.0, 0.999_999);
        -(1.0 - share.powf(1.0 / self.growth_shape)).ln() / self.growth_rate
    }

    /// The height a tree of `height` adds in a year of full light: one year along the curve
    /// from its effective age.
    pub fn potential_growth(&self, height: f32) -> f32 {
        let age = self.age_at(height.max(SEEDLING_HEIGHT));
        (self.height(age + 1.0) - height).max(0.0)
    }

    /// The growth crate's response for this tolerance: the pioneer's and the shade-tolerant
    /// species' settings mixed by [`Life::shade_tolerance`].
    pub fn response(&self) -> Response {
        let (p, t) = (Response::pioneer(), Response::shade_tolerant());
        let s = self.shade_tolerance.clamp(0.0, 1.0);
        let lerp = |a: f32, b: f32| a + (b - a) * s;
        Response {
            direct_weight: lerp(p.direct_weight, t.direct_weight),
            threshold: lerp(p.threshold, t.threshold),
            ..p
        }
    }

    /// Share of its potential growth a tree makes in `light` (0 to 1, the open sky's share
    /// reaching its top). Zero below the response's threshold (the compensation point), then
    /// saturating: quickly for a tree content with the sky's light (low direct weight),
    /// slowly for a pioneer that wants the sun, as gap models' light curves do.
    pub fn growth_in(&self, light: f32) -> f32 {
        let r = self.response();
        // NaN light, like light at or below the threshold, grows nothing.
        if light.is_nan() || light <= r.threshold {
            return 0.0;
        }
        let rate = 2.0 + 8.0 * (1.0 - r.direct_weight);
        let full = 1.0 - (-rate * (1.0 - r.threshold)).exp();
        ((1.0 - (-rate * (light - r.threshold)).exp()) / full).clamp(0.0, 1.0)
    }

    /// The yearly chance that a tree of `age` dies of age: `4 age / max_age^2`, a hazard
    /// rising with age whose sum to `max_age` is 2 (so e^-2, 14%, of trees reach it). Young
    /// trees die of shade, not age: JABOWA's constant `4 / max_age` thinned young stands at
    /// random before their crowns met.
    pub fn age_mortality(&self, age: f32) -> f32 {
        4.0 * age.max(0.0) / (self.max_age * self.max_age)
    }

    /// Years a tree survives growing at under a tenth of its potential before it dies of
    /// suppression: 3 for the least tolerant, 20 for the most.
    pub fn suppression_years(&self) -> u8 {
        (3.0 + 17.0 * self.shade_tolerance.clamp(0.0, 1.0)).round() as u8
    }

    /// Stem diameter at breast height, metres, of a tree `height` tall: zero below 1.3 m,
    /// then the power-law allometry `d = 0.0077 (H - 1.3)^1.25`: 11 cm at 10 m, 30 cm at
    /// 20 m, 56 cm at 32 m, as temperate trees of the open run. The exponent also sets a
    /// closed stand's self-thinning: crowns of a radius proportional to height fill the
    /// ground when stems number about `D^(-2 / 1.25) = D^-1.6`, Reineke's rule.
    pub fn diameter(&self, height: f32) -> f32 {
        if height <= BREAST_HEIGHT {
            return 0.0;
        }
        0.0077 * (height - BREAST_HEIGHT).powf(1.25)
    }

    /// Every setting in its range, or the first that is not.
    pub fn check(&self) -> Result<(), sylva_base::range::OutOfRange> {
        use sylva_base::range::check;
        let f = f64::from;
        check(
            "max_height",
            f(self.max_height),
            self.max_height > 0.2 && self.max_height <= 150.0,
            "0.2 < max_height <= 150 metres",
        )?;
        check(
            "growth_rate",
            f(self.growth_rate),
            self.growth_rate > 0.0 && self.growth_rate <= 2.0,
            "0 < growth_rate <= 2 per year",
        )?;
        check(
            "growth_shape",
            f(self.growth_shape),
            (0.2..=5.0).contains(&self.growth_shape),
            "0.2 <= growth_shape <= 5",
        )?;
        check(
            "max_age",
            f(self.max_age),
            (2.0..=5000.0).contains(&self.max_age),
            "2 <= max_age <= 5000 years",
        )?;
        check(
            "maturity_age",
            f(self.maturity_age),
            (0.0..=self.max_age).contains(&self.maturity_age),
            "0 <= maturity_age <= max_age",
        )?;
        check(
            "shade_tolerance",
            f(self.shade_tolerance),
            (0.0..=1.0).contains(&self.shade_tolerance),
            "0 to 1",
        )?;
        check(
            "dispersal",
            f(self.dispersal),
            self.dispersal > 0.0 && self.dispersal <= 2000.0,
            "0 < dispersal <= 2000 metres",
        )?;
        check(
            "seeds_per_year",
            f(self.seeds_per_year),
            (0.0..=100.0).contains(&self.seeds_per_year),
            "0 to 100",
        )?;
        check(
            "leaf_area_index",
            f(self.leaf_area_index),
            (0.0..=20.0).contains(&self.leaf_area_index),
            "0 to 20",
        )?;
        Ok(())
    }
}

/// Breast height, metres: stems are measured (and counted in stand statistics) from here.
pub const BREAST_HEIGHT: f32 = 1.3;

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// Height rises with age towards the asymptote, and the effective age inverts it.
        #[test]
        fn height_rises_and_inverts(age in 0.5f32..600.0, rate in 0.01f32..0.2, shape in 0.8f32..2.0) {
            let life = Life::default().with_growth_rate(rate).with_growth_shape(shape);
            let (h, later) = (life.height(age), life.height(age + 1.0));
            prop_assert!(later >= h && later <= life.max_height);
            if h > SEEDLING_HEIGHT && h < 0.99 * life.max_height {
                prop_assert!((life.age_at(h) - age).abs() < 0.05 * age + 0.05);
            }
        }

        /// More light never means less growth, and growth stays within 0 and 1.
        #[test]
        fn growth_rises_with_light(tolerance in 0.0f32..=1.0, a in 0.0f32..=1.0, b in 0.0f32..=1.0) {
            let life = Life::default().with_shade_tolerance(tolerance);
            let (lo, hi) = (a.min(b), a.max(b));
            prop_assert!(life.growth_in(lo) <= life.growth_in(hi));
            prop_assert!((0.0..=1.0).contains(&life.growth_in(hi)));
        }
    }

    #[test]
    fn full_light_is_full_growth_and_pioneers_want_more_light() {
        for tolerance in [0.0, 0.5, 1.0] {
            let life = Life::default().with_shade_tolerance(tolerance);
            assert!((life.growth_in(1.0) - 1.0).abs() < 1e-5);
        }
        let pioneer = Life::default().with_shade_tolerance(0.1);
        let tolerant = Life::default().with_shade_tolerance(0.9);
        for light in [0.1, 0.2, 0.3, 0.5] {
            assert!(
                tolerant.growth_in(light) > pioneer.growth_in(light),
                "at {light}"
            );
        }
    }

    #[test]
    fn diameters_follow_the_allometry() {
        let life = Life::default();
        assert_eq!(life.diameter(1.0), 0.0);
        assert!(
            (life.diameter(20.0) - 0.296).abs() < 0.01,
            "{}",
            life.diameter(20.0)
        );
        assert!(life.diameter(32.0) > 0.55 && life.diameter(32.0) < 0.65);
    }
}
