//! The settings of a forest over time.

use sylva_base::range::{OutOfRange, check};

/// How a [`Succession`](crate::Succession) runs: its seed, the halo simulated around its
/// region, how much seed arrives from outside, how often events strike, and its bound.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct SuccessionOptions {
    /// World seed: every draw of the simulation derives from it, the place and the year.
    /// Default: 1.
    pub seed: u64,
    /// Metres simulated beyond the region on every side, so trees near its edges have
    /// neighbours, parents and shade as in a larger run; tiles simulated apart with a halo
    /// agree near their borders (see the crate's README for how closely, by halo). Default: 60.
    pub halo: f32,
    /// Seedlings arriving from beyond the forest, per hectare and year, shared among the
    /// species by weight: how bare ground is first colonised. Default: 4.
    pub seed_rain: f32,
    /// Storms per year. Default: 0.04.
    pub storm_rate: f32,
    /// Lightning strikes per hectare and year. Default: 0.002.
    pub lightning_rate: f32,
    /// Disease outbreaks per year (each in one species, for several years). Default: 0.015.
    pub disease_rate: f32,
    /// Most trees (living, dead standing and fallen) the simulation holds: a year that would
    /// hold more is refused with [`ForestError::TooManyStems`](crate::ForestError::TooManyStems).
    /// Default: 8,000,000.
    pub max_stems: usize,
}

impl Default for SuccessionOptions {
    fn default() -> Self {
        SuccessionOptions {
            seed: 1,
            halo: 60.0,
            seed_rain: 4.0,
            storm_rate: 0.04,
            lightning_rate: 0.002,
            disease_rate: 0.015,
            max_stems: 8_000_000,
        }
    }
}

impl SuccessionOptions {
    /// Sets [`SuccessionOptions::seed`].
    #[must_use]
    pub fn with_seed(mut self, seed: u64) -> Self {
        self.seed = seed;
        self
    }

    /// Sets [`SuccessionOptions::halo`].
    #[must_use]
    pub fn with_halo(mut self, metres: f32) -> Self {
        self.halo = metres;
        self
    }

    /// Sets [`SuccessionOptions::seed_rain`].
    #[must_use]
    pub fn with_seed_rain(mut self, per_hectare: f32) -> Self {
        self.seed_rain = per_hectare;
        self
    }

    /// Sets [`SuccessionOptions::storm_rate`].
    #[must_use]
    pub fn with_storm_rate(mut self, per_year: f32) -> Self {
        self.storm_rate = per_year;
        self
    }

    /// Sets [`SuccessionOptions::lightning_rate`].
    #[must_use]
    pub fn with_lightning_rate(mut self, per_hectare: f32) -> Self {
        self.lightning_rate = per_hectare;
        self
    }

    /// Sets [`SuccessionOptions::disease_rate`].
    #[must_use]
    pub fn with_disease_rate(mut self, per_year: f32) -> Self {
        self.disease_rate = per_year;
        self
    }

    /// Sets [`SuccessionOptions::max_stems`].
    #[must_use]
    pub fn with_max_stems(mut self, max_stems: usize) -> Self {
        self.max_stems = max_stems;
        self
    }

    /// Every setting in its range, or the first that is not.
    pub fn check(&self) -> Result<(), OutOfRange> {
        let f = f64::from;
        check(
            "halo",
            f(self.halo),
            (0.0..=2000.0).contains(&self.halo),
            "0 to 2000 metres",
        )?;
        check(
            "seed_rain",
            f(self.seed_rain),
            (0.0..=1000.0).contains(&self.seed_rain),
            "0 to 1000 per hectare and year",
        )?;
        check(
            "storm_rate",
            f(self.storm_rate),
            (0.0..=1.0).contains(&self.storm_rate),
            "0 to 1 per year",
        )?;
        check(
            "lightning_rate",
            f(self.lightning_rate),
            (0.0..=1.0).contains(&self.lightning_rate),
            "0 to 1 per hectare and year",
        )?;
        check(
            "disease_rate",
            f(self.disease_rate),
            (0.0..=1.0).contains(&self.disease_rate),
            "0 to 1 per year",
        )?;
        check(
            "max_stems",
            self.max_stems as f64,
            self.max_stems > 0,
            "at least 1",
        )?;
        Ok(())
    }
}
