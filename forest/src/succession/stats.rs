//! What a forest over time reports each year: stems and basal area by species, heights,
//! deaths by cause, the events, canopy cover; as CSV and JSON.

use super::stem::Cause;

/// Stems thinner than this at breast height, metres, are left out of densities and
/// diameters (the inventories' threshold).
pub const MIN_DIAMETER: f32 = 0.05;

/// One species in one year.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[non_exhaustive]
pub struct SpeciesYear {
    /// Living stems of at least [`MIN_DIAMETER`] at breast height, per hectare.
    pub stems_per_ha: f32,
    /// Living trees below that (saplings and seedlings), per hectare.
    pub saplings_per_ha: f32,
    /// Basal area of the stems, square metres per hectare.
    pub basal_area: f32,
    /// Mean height of the stems, metres (0 without any).
    pub mean_height: f32,
}

/// Something that happened in a year.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Event {
    /// A storm from `direction` (degrees, the way it blew: 0 towards +X, 90 towards +Z) of
    /// `strength` (0 to 1): `thrown` trees fell along it, `broken` lost their tops.
    Storm {
        /// Direction it blew towards, degrees.
        direction: f32,
        /// Strength, 0 to 1.
        strength: f32,
        /// Trees thrown.
        thrown: u32,
        /// Trees that lost their tops.
        broken: u32,
    },
    /// Lightning struck the tallest tree near `position`; `split` when it split the trunk.
    Lightning {
        /// Where it struck (x, z).
        position: [f32; 2],
        /// Whether the trunk split (a snag) rather than the tree dying whole.
        split: bool,
    },
    /// A disease broke out in `species`, for `years` years.
    Disease {
        /// Index of the species.
        species: usize,
        /// How long it lasts.
        years: u32,
    },
}

impl Event {
    /// Its kind: `storm`, `lightning` or `disease`.
    pub fn kind(&self) -> &'static str {
        match self {
            Event::Storm { .. } => "storm",
            Event::Lightning { .. } => "lightning",
            Event::Disease { .. } => "disease",
        }
    }
}

/// The forest of one year, over the simulation's region (the halo left out).
#[derive(Debug, Clone, Default, PartialEq)]
#[non_exhaustive]
pub struct YearStats {
    /// The year (0: bare ground).
    pub year: u32,
    /// Per species, in the simulation's order.
    pub species: Vec<SpeciesYear>,
    /// Living stems of at least [`MIN_DIAMETER`], per hectare.
    pub stems_per_ha: f32,
    /// Their basal area, square metres per hectare.
    pub basal_area: f32,
    /// Their mean height, metres.
    pub mean_height: f32,
    /// Their quadratic mean diameter at breast height, centimetres (Reineke's D).
    pub mean_diameter: f32,
    /// Dead standing trees (dead and snags), per hectare.
    pub dead_standing_per_ha: f32,
    /// Fallen trees, per hectare.
    pub fallen_per_ha: f32,
    /// Seedlings that took this year, per hectare.
    pub recruits_per_ha: f32,
    /// Deaths this year by cause, in [`Cause::ALL`]'s order, per hectare.
    pub deaths_per_ha: [f32; 5],
    /// Share of the ground under at least one leaf layer above 5 m: the closed canopy.
    pub canopy_cover: f32,
    /// What happened.
    pub events: Vec<Event>,
}

impl YearStats {
    /// The CSV header matching [`YearStats::csv_row`], for species named `names`.
    pub fn csv_header(names: &[String]) -> String {
        let mut h = String::from(
            "year,stems_per_ha,basal_area_m2_per_ha,mean_height_m,mean_diameter_cm,dead_standing_per_ha,fallen_per_ha,recruits_per_ha",
        );
        for c in Cause::ALL {
            h.push_str(&format!(",deaths_{}_per_ha", c.name()));
        }
        h.push_str(",canopy_cover");
        for n in names {
            h.push_str(&format!(
                ",{n}_stems_per_ha,{n}_saplings_per_ha,{n}_basal_area_m2_per_ha,{n}_mean_height_m"
            ));
        }
        h.push_str(",events");
        h
    }

    /// The year's figures in [`YearStats::csv_header`]'s order, every column but the last
    /// (`events`), unrounded: what [`YearStats::csv_row`] prints.
    ///
    /// ```
    /// use sylva_forest::succession::YearStats;
    /// let names = ["oak".to_string()];
    /// let mut year = YearStats::default();
    /// (year.year, year.stems_per_ha) = (3, 120.5);
    /// let values = year.values();
    /// // 8 figures, 5 causes of death and the canopy cover; a species has 4 (none here).
    /// assert_eq!(values.len(), 14);
    /// assert_eq!(values[..2], [3.0, 120.5]);
    /// assert_eq!(YearStats::csv_header(&names).split(',').count(), values.len() + 4 + 1);
    /// ```
    pub fn values(&self) -> Vec<f64> {
        let mut v = vec![
            f64::from(self.year),
            f64::from(self.stems_per_ha),
            f64::from(self.basal_area),
            f64::from(self.mean_height),
            f64::from(self.mean_diameter),
            f64::from(self.dead_standing_per_ha),
            f64::from(self.fallen_per_ha),
            f64::from(self.recruits_per_ha),
        ];
        v.extend(self.deaths_per_ha.map(f64::from));
        v.push(f64::from(self.canopy_cover));
        for s in &self.species {
            v.extend(
                [
                    s.stems_per_ha,
                    s.saplings_per_ha,
                    s.basal_area,
                    s.mean_height,
                ]
                .map(f64::from),
            );
        }
        v
    }

    /// One CSV row: the figures in the header's order, then the events as
    /// `kind;kind;...`.
    pub fn csv_row(&self) -> String {
        let mut r = format!(
            "{},{:.2},{:.3},{:.2},{:.2},{:.2},{:.2},{:.2}",
            self.year,
            self.stems_per_ha,
            self.basal_area,
            self.mean_height,
            self.mean_diameter,
            self.dead_standing_per_ha,
            self.fallen_per_ha,
            self.recruits_per_ha
        );
        for d in self.deaths_per_ha {
            r.push_str(&format!(",{d:.2}"));
        }
        r.push_str(&format!(",{:.4}", self.canopy_cover));
        for s in &self.species {
            r.push_str(&format!(
                ",{:.2},{:.2},{:.3},{:.2}",
                s.stems_per_ha, s.saplings_per_ha, s.basal_area, s.mean_height
            ));
        }
        let kinds: Vec<&str> = self.events.iter().map(Event::kind).collect();
        r.push(',');
        r.push_str(&kinds.join(";"));
        r
    }

    /// The year as one JSON object (hand-written: the forest crate has no JSON dependency),
    /// species by `names`.
    pub fn to_json(&self, names: &[String]) -> String {
        let num = |x: f32| {
            if x.is_finite() {
                format!("{}", (x * 1000.0).round() / 1000.0)
            } else {
                "null".into()
            }
        };
        let species: Vec<String> = self
            .species
            .iter()
            .zip(names)
            .map(|(s, n)| {
                format!(
                    "\"{}\":{{\"stems_per_ha\":{},\"saplings_per_ha\":{},\"basal_area_m2_per_ha\":{},\"mean_height_m\":{}}}",
                    escape(n),
                    num(s.stems_per_ha),
                    num(s.saplings_per_ha),
                    num(s.basal_area),
                    num(s.mean_height)
                )
            })
            .collect();
        let deaths: Vec<String> = Cause::ALL
            .iter()
            .zip(self.deaths_per_ha)
            .map(|(c, d)| format!("\"{}\":{}", c.name(), num(d)))
            .collect();
        let events: Vec<String> = self
            .events
            .iter()
            .map(|e| match e {
                Event::Storm { direction, strength, thrown, broken } => format!(
                    "{{\"kind\":\"storm\",\"direction_deg\":{},\"strength\":{},\"thrown\":{thrown},\"broken\":{broken}}}",
                    num(*direction),
                    num(*strength)
                ),
                Event::Lightning { position, split } => format!(
                    "{{\"kind\":\"lightning\",\"x\":{},\"z\":{},\"split\":{split}}}",
                    num(position[0]),
                    num(position[1])
                ),
                Event::Disease { species, years } => format!(
                    "{{\"kind\":\"disease\",\"species\":\"{}\",\"years\":{years}}}",
                    escape(names.get(*species).map_or("?", String::as_str))
                ),
            })
            .collect();
        format!(
            "{{\"year\":{},\"stems_per_ha\":{},\"basal_area_m2_per_ha\":{},\"mean_height_m\":{},\"mean_diameter_cm\":{},\"dead_standing_per_ha\":{},\"fallen_per_ha\":{},\"recruits_per_ha\":{},\"canopy_cover\":{},\"deaths_per_ha\":{{{}}},\"species\":{{{}}},\"events\":[{}]}}",
            self.year,
            num(self.stems_per_ha),
            num(self.basal_area),
            num(self.mean_height),
            num(self.mean_diameter),
            num(self.dead_standing_per_ha),
            num(self.fallen_per_ha),
            num(self.recruits_per_ha),
            num(self.canopy_cover),
            deaths.join(","),
            species.join(","),
            events.join(",")
        )
    }
}

/// A JSON string's text with quotes, backslashes and control characters escaped.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => out.push_str(&format!("\\u{:04x}", c as u32)),
            c => out.push(c),
        }
    }
    out
}

/// The slope of log density against log mean diameter over `years` (a least-squares
/// line), for comparison with Reineke's self-thinning rule (-1.605): `None` with fewer than
/// three years of stems.
///
/// ```
/// use sylva_forest::succession::{YearStats, thinning_slope};
/// // A stand on Reineke's line: N = 1e5 * D^-1.605.
/// let years: Vec<YearStats> = [10.0f32, 15.0, 20.0, 30.0]
///     .iter()
///     .map(|&d| {
///         let mut y = YearStats::default();
///         y.mean_diameter = d;
///         y.stems_per_ha = 1e5 * d.powf(-1.605);
///         y
///     })
///     .collect();
/// assert!((thinning_slope(&years).unwrap() + 1.605).abs() < 1e-3);
/// ```
pub fn thinning_slope(years: &[YearStats]) -> Option<f32> {
    let points: Vec<(f64, f64)> = years
        .iter()
        .filter(|y| y.stems_per_ha > 0.0 && y.mean_diameter > 0.0)
        .map(|y| {
            (
                f64::from(y.mean_diameter).ln(),
                f64::from(y.stems_per_ha).ln(),
            )
        })
        .collect();
    if points.len() < 3 {
        return None;
    }
    let n = points.len() as f64;
    let (mx, my) = points
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / n, b + y / n));
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + (x - mx) * (y - my), b + (x - mx) * (x - mx))
    });
    (sxx > 0.0).then(|| (sxy / sxx) as f32)
}

/// The years a stand thins itself: from its densest year (the most stems of at least
/// [`MIN_DIAMETER`]) while its mean diameter grows, until that diameter first falls 5% below
/// the largest it reached (gaps and recruits, not thinning, then set the figures). Where
/// Reineke's rule applies; [`thinning_slope`] over it is the self-thinning slope.
pub fn thinning_phase(years: &[YearStats]) -> &[YearStats] {
    let Some(densest) = (0..years.len()).max_by(|&a, &b| {
        years[a]
            .stems_per_ha
            .total_cmp(&years[b].stems_per_ha)
            .then(b.cmp(&a))
    }) else {
        return years;
    };
    let mut widest = 0.0f32;
    let end = years[densest..]
        .iter()
        .position(|y| {
            widest = widest.max(y.mean_diameter);
            y.mean_diameter < 0.95 * widest
        })
        .map_or(years.len(), |k| densest + k);
    &years[densest..end]
}
