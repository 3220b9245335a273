//! What became of a region's candidate tree spots: placed, or refused and why. Counted by
//! [`ForestBuilder::siting`](crate::ForestBuilder::siting) and by placement itself.

/// Why the terrain refuses a candidate spot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Refusal {
    /// Lower than [`Constraints::min_height`](crate::Constraints::min_height).
    BelowMinHeight,
    /// Higher than [`Constraints::max_height`](crate::Constraints::max_height).
    AboveMaxHeight,
    /// Steeper than [`Constraints::max_slope_degrees`](crate::Constraints::max_slope_degrees).
    TooSteep,
}

/// What became of the candidate spots of a region: how many the density model (or the
/// snapshot of a forest over time) proposed, how many got a tree, and how many each
/// constraint refused. A spot is counted under the first constraint it fails, in the order
/// height range, slope, mask. Placed and refused add up to the candidates but for spots the
/// builder has no form to draw (a forest over time's tree of a height no generation
/// reaches), which are neither.
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
    pub(crate) fn add(self, other: SitingReport) -> SitingReport {
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
