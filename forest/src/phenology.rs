//! The seasons: when a species' leaves come and go, their colours through the year, and snow.
//!
//! Every card has an order in `[0, 1)` (drawn by the turtle from its place in the word, and
//! carried in the meshes as its wind phase); a day of the year gives each species a share of
//! its cards on the trees, and the cards below that share are drawn. In spring the share
//! rises over [`FLUSH_DAYS`] from the species' `leaf_out`, in autumn it falls over
//! [`FALL_DAYS`] about its `leaf_fall`, so the same cards that came out first fall last.
//! Each tree runs up to [`TREE_DAYS`] early or late ([`tree_day`]). A shader that knows
//! the day, the species' [`Phenology`], the card's order and the tree's offset plays a year
//! without new meshes; `sylva forest --season DAY` draws one day with the leaves that day
//! has.

/// Days over which a species' buds break, first card to last.
pub const FLUSH_DAYS: f32 = 25.0;
/// Days over which its leaves fall, centred on its `leaf_fall`.
pub const FALL_DAYS: f32 = 30.0;
/// Days the autumn colour takes to come in, ending a little before `leaf_fall`.
pub const TURN_DAYS: f32 = 35.0;
/// Days from `leaf_out` the spring colour takes to become the summer colour.
pub const GREEN_DAYS: f32 = 45.0;
/// The most a tree is early or late, in days.
pub const TREE_DAYS: f32 = 7.0;

/// When a species' leaves come and go and how their colour changes. The days are days of
/// the year, 1 to 365; colours are linear RGB from 0 to 1. Species files set it with
/// `evergreen`, `leaf_out`, `leaf_fall`, `spring_leaf` and `autumn_leaf`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Phenology {
    /// Keeps its leaves all year (spruce, pine, fir): only snow marks the seasons.
    /// Default: true, so a species file without a season draws as it always did.
    pub evergreen: bool,
    /// The day its first buds break. Default: 110.
    pub leaf_out: f32,
    /// The day half its leaves have fallen. Default: 300.
    pub leaf_fall: f32,
    /// The young leaves' colour, which becomes the summer colour (the species' `leaf`) over
    /// [`GREEN_DAYS`]. Default: a fresh yellow-green.
    pub spring: [f32; 3],
    /// The autumn colour the leaves take before they fall. Default: a yellow-brown.
    pub autumn: [f32; 3],
}

impl Default for Phenology {
    fn default() -> Self {
        Phenology {
            evergreen: true,
            leaf_out: 110.0,
            leaf_fall: 300.0,
            spring: [0.38, 0.52, 0.14],
            autumn: [0.62, 0.45, 0.12],
        }
    }
}

/// What a species' leaves look like on one day.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LeafSeason {
    /// The share of its cards on the trees, 0 (bare) to 1: cards of order below it are drawn.
    pub share: f32,
    /// The leaves' colour that day (the species' summer colour between spring and autumn).
    pub colour: [f32; 3],
    /// The cards' size against their summer size: young leaves are small.
    pub size: f32,
}

impl Phenology {
    /// The leaves on `day` (any number: taken round the year) of a species whose summer
    /// colour is `summer`.
    ///
    /// ```
    /// use sylva_forest::Phenology;
    ///
    /// let oak = Phenology { evergreen: false, leaf_out: 120.0, leaf_fall: 305.0, ..Default::default() };
    /// let summer = [0.16, 0.30, 0.07];
    /// assert_eq!(oak.leaves(200.0, summer).share, 1.0);
    /// assert_eq!(oak.leaves(200.0, summer).colour, summer);
    /// assert_eq!(oak.leaves(20.0, summer).share, 0.0); // bare in winter
    /// assert!((oak.leaves(305.0, summer).share - 0.5).abs() < 1e-6); // half fallen
    /// let evergreen = Phenology::default();
    /// assert_eq!(evergreen.leaves(20.0, summer).share, 1.0);
    /// ```
    pub fn leaves(&self, day: f32, summer: [f32; 3]) -> LeafSeason {
        if self.evergreen {
            return LeafSeason {
                share: 1.0,
                colour: summer,
                size: 1.0,
            };
        }
        let day = year_day(day);
        let since_out = day - self.leaf_out;
        let flush = ramp(since_out / FLUSH_DAYS);
        let fall = 1.0 - ramp((day - (self.leaf_fall - 0.5 * FALL_DAYS)) / FALL_DAYS);
        let share = if day < self.leaf_out {
            0.0
        } else {
            flush.min(fall)
        };
        let green = ramp(since_out / GREEN_DAYS);
        let turn = ramp((day - (self.leaf_fall - 5.0 - TURN_DAYS)) / TURN_DAYS);
        let colour = mix(mix(self.spring, summer, green), self.autumn, turn);
        LeafSeason {
            share,
            colour,
            size: 0.4 + 0.6 * ramp(since_out / (FLUSH_DAYS + 15.0)),
        }
    }
}

/// How much snow lies on the branches on `day` (0 to 1) in sylva's default climate, a
/// temperate one: none from the middle of March to the middle of November, full from the
/// start of January to the middle of February.
///
/// ```
/// use sylva_forest::snow;
/// assert_eq!(snow(15.0), 1.0);
/// assert_eq!(snow(200.0), 0.0);
/// assert!(snow(340.0) > 0.0 && snow(340.0) < 1.0);
/// ```
pub fn snow(day: f32) -> f32 {
    let day = year_day(day);
    // Days after the first snow (day 320) and before the thaw is over (day 75).
    let settling = ramp((day - 320.0) / 45.0);
    let thaw = 1.0 - ramp((day - 45.0) / 30.0);
    if day >= 320.0 { settling } else { thaw }
}

/// A tree's day: `day` moved by up to [`TREE_DAYS`] early or late by the tree's wind phase
/// (`tree_wind(tree)[3]`, in `[0, 1)`), so a stand flushes and turns tree by tree. The
/// shaders that play a year do the same.
///
/// ```
/// use sylva_forest::{tree_day, TREE_DAYS};
/// assert_eq!(tree_day(100.0, 0.5), 100.0);
/// assert_eq!(tree_day(100.0, 0.0), 100.0 - TREE_DAYS);
/// ```
pub fn tree_day(day: f32, phase: f32) -> f32 {
    day + (2.0 * phase.clamp(0.0, 1.0) - 1.0) * TREE_DAYS
}

/// The days that stand for the four seasons in pictures and on command lines: spring
/// (the middle of May, most trees flushing), summer, autumn (the middle of October, in
/// colour) and winter (January, bare and snowy).
pub const SEASON_DAYS: [(&str, f32); 4] = [
    ("spring", 135.0),
    ("summer", 200.0),
    ("autumn", 290.0),
    ("winter", 20.0),
];

/// A day of the year from a command line: a number from 1 to 365, or a season's name
/// ([`SEASON_DAYS`], `fall` for autumn). `None` for anything else.
///
/// ```
/// use sylva_forest::parse_day;
/// assert_eq!(parse_day("autumn"), Some(290.0));
/// assert_eq!(parse_day("45"), Some(45.0));
/// assert_eq!(parse_day("400"), None);
/// ```
pub fn parse_day(text: &str) -> Option<f32> {
    let name = if text == "fall" { "autumn" } else { text };
    if let Some((_, day)) = SEASON_DAYS.iter().find(|(n, _)| *n == name) {
        return Some(*day);
    }
    text.parse::<f32>()
        .ok()
        .filter(|d| (1.0..=365.0).contains(d))
}

/// What a vertex carries for the seasons, as USD writes it (`primvars:sylva:phenology`; glTF
/// leaves it to `_WIND` and `NORMAL`, which hold it already): the order of the leaf card it belongs to (its wind
/// phase, [`sylva_turtle::Wind`]; 0 on bark), below which a species' day share keeps a
/// card ([`LeafSeason::share`]); and how much snow its surface catches, how far it faces
/// up (a card, drawn from both sides, either way).
///
/// ```
/// use sylva_forest::vertex_phenology;
/// use sylva_turtle::Vertex;
/// let top = Vertex { normal: [0.0, 1.0, 0.0], ..Default::default() };
/// assert_eq!(vertex_phenology(&top, false), [0.0, 1.0]);
/// let under = Vertex { normal: [0.0, -1.0, 0.0], wind: [0.0, 0.0, 0.0, 3.25], ..Default::default() };
/// assert_eq!(vertex_phenology(&under, false), [0.0, 0.0]);
/// assert_eq!(vertex_phenology(&under, true), [0.25, 1.0]);
/// ```
pub fn vertex_phenology(vertex: &sylva_turtle::Vertex, card: bool) -> [f32; 2] {
    let up = vertex.normal[1];
    let up = if up.is_finite() { up } else { 0.0 };
    if card {
        [sylva_turtle::Wind::of(vertex).phase, up.abs().min(1.0)]
    } else {
        [0.0, up.clamp(0.0, 1.0)]
    }
}

/// `day` taken into `[1, 366)`, for days before or after the year.
fn year_day(day: f32) -> f32 {
    if day.is_finite() {
        (day - 1.0).rem_euclid(365.0) + 1.0
    } else {
        1.0
    }
}

/// `x` clamped to `[0, 1]` and eased at both ends.
fn ramp(x: f32) -> f32 {
    let t = if x.is_finite() {
        x.clamp(0.0, 1.0)
    } else {
        0.0
    };
    t * t * (3.0 - 2.0 * t)
}

fn mix(a: [f32; 3], b: [f32; 3], t: f32) -> [f32; 3] {
    [0, 1, 2].map(|i| a[i] + (b[i] - a[i]) * t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn oak() -> Phenology {
        Phenology {
            evergreen: false,
            leaf_out: 120.0,
            leaf_fall: 305.0,
            spring: [0.35, 0.45, 0.12],
            autumn: [0.45, 0.28, 0.08],
        }
    }

    const SUMMER: [f32; 3] = [0.16, 0.30, 0.07];

    #[test]
    fn a_deciduous_year_flushes_greens_turns_and_falls() {
        let o = oak();
        let at = |d: f32| o.leaves(d, SUMMER);
        assert_eq!(at(100.0).share, 0.0);
        assert!(at(125.0).share > 0.0 && at(125.0).share < 0.5);
        assert!(at(125.0).size < 0.6);
        assert_eq!(at(150.0).share, 1.0);
        assert_eq!(at(200.0).colour, SUMMER);
        assert_eq!(at(200.0).size, 1.0);
        // Autumn colour before the leaves go.
        let turned = at(298.0);
        assert!(turned.share > 0.5 && turned.colour[0] > SUMMER[0] + 0.15);
        assert_eq!(at(330.0).share, 0.0);
        // Spring colour at budburst.
        assert!((at(121.0).colour[1] - o.spring[1]).abs() < 0.01);
    }

    #[test]
    fn snow_lies_in_winter_only() {
        assert_eq!(snow(1.0), 1.0);
        assert_eq!(snow(366.0), 1.0);
        assert_eq!(snow(100.0), 0.0);
        assert_eq!(snow(300.0), 0.0);
        assert!(snow(60.0) > 0.0 && snow(60.0) < 1.0);
    }

    proptest! {
        /// Whatever the day, the share is a share, the colour a colour and the size between
        /// a young leaf's and a grown one's; the year repeats.
        #[test]
        fn every_day_gives_a_valid_season(day in -1000.0f32..1000.0, out in 60.0f32..160.0, fall in 250.0f32..330.0) {
            let p = Phenology { evergreen: false, leaf_out: out, leaf_fall: fall, ..Default::default() };
            let s = p.leaves(day, SUMMER);
            prop_assert!((0.0..=1.0).contains(&s.share));
            prop_assert!(s.colour.iter().all(|c| (0.0..=1.0).contains(c)));
            prop_assert!((0.4..=1.0).contains(&s.size));
            let next = p.leaves(day + 365.0, SUMMER);
            prop_assert!((next.share - s.share).abs() < 1e-3);
            prop_assert!((0.0..=1.0).contains(&snow(day)));
        }

        /// Leaves come out in spring and go in autumn: the share never falls before
        /// midsummer nor rises after it.
        #[test]
        fn the_share_rises_then_falls(a in 1.0f32..365.0, b in 1.0f32..365.0) {
            let p = oak();
            let (early, late) = if a < b { (a, b) } else { (b, a) };
            let mid = 0.5 * (p.leaf_out + p.leaf_fall);
            let (sa, sb) = (p.leaves(early, SUMMER).share, p.leaves(late, SUMMER).share);
            if late <= mid {
                prop_assert!(sb >= sa);
            } else if early >= mid {
                prop_assert!(sb <= sa);
            }
        }
    }
}
