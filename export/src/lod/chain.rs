//! The chain of levels a tree is drawn at, nearest first: the full mesh, each coarser
//! [`LodLevel`], then the impostor; and the distance at which each takes over, from the
//! screen-space error it makes.

use super::impostor::{Impostor, ImpostorOptions};
use super::simplify::LodLevel;

/// Vertical pixels per radian of a 1080-pixel-high picture with a 60-degree field of view:
/// the screen the default distances are worked out for.
pub const PIXELS_PER_RADIAN_1080P: f32 = 1080.0 / (std::f32::consts::PI / 3.0);

/// The levels of detail and when each is drawn.
///
/// A level whose geometry is off by at most `e` metres is drawn from the distance where `e`
/// spans [`LodChain::pixel_error`] pixels: `d = e * pixels_per_radian / pixel_error`.
///
/// ```
/// use sylva_export::lod::LodChain;
/// let chain = LodChain::default();
/// // For cards of 0.5 m, each level takes over farther out than the one before.
/// let d: Vec<f32> = (0..chain.levels.len()).map(|k| chain.level_distance(k, 0.5)).collect();
/// assert!(d.windows(2).all(|w| w[0] < w[1]));
/// assert!(d[0] > 20.0 && d[1] < 300.0);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct LodChain {
    /// The coarser levels, finest first.
    /// Default: two, bark within 3 cm with 60% of the cards, then within 8 cm with 35%.
    pub levels: Vec<LodLevel>,
    /// How the impostor, the last level, is drawn. Default: [`ImpostorOptions::default`].
    pub impostor: ImpostorOptions,
    /// The screen-space error allowed, in pixels. Default: 2.
    pub pixel_error: f32,
    /// The screen's vertical pixels per radian of view.
    /// Default: [`PIXELS_PER_RADIAN_1080P`], about 1031.
    pub pixels_per_radian: f32,
    /// Share of a switch distance over which a level fades into the next (dithered). Default: 0.1.
    pub fade: f32,
}

impl Default for LodChain {
    /// Two levels (bark within 3 cm with 60% of the cards; within 8 cm with 35%) and an
    /// 8 x 8 impostor of 128-pixel views, switched at two pixels of error at 1080p.
    fn default() -> Self {
        LodChain {
            levels: vec![
                LodLevel {
                    bark_error: 0.03,
                    leaf_keep: 0.6,
                    leaf_growth: None,
                },
                LodLevel {
                    bark_error: 0.08,
                    leaf_keep: 0.35,
                    leaf_growth: None,
                },
            ],
            impostor: ImpostorOptions::default(),
            pixel_error: 2.0,
            pixels_per_radian: PIXELS_PER_RADIAN_1080P,
            fade: 0.1,
        }
    }
}

impl LodChain {
    /// Sets [`LodChain::pixels_per_radian`]: a picture `height` pixels high with a vertical
    /// field of view of `fov` radians.
    #[must_use]
    pub fn with_screen(mut self, height: u32, fov: f32) -> Self {
        self.pixels_per_radian = height as f32 / fov.max(1e-3);
        self
    }

    /// Sets [`LodChain::pixel_error`].
    #[must_use]
    pub fn with_pixel_error(mut self, pixels: f32) -> Self {
        self.pixel_error = pixels;
        self
    }

    /// The distance at which `error` metres span the allowed pixels.
    pub fn distance_for(&self, error: f32) -> f32 {
        error * self.pixels_per_radian / self.pixel_error.max(1e-3)
    }

    /// The error of level `k` (0: the first coarser level) for leaf cards of side `card`:
    /// the larger of its bark error and how far its grown cards reach.
    pub fn level_error(&self, k: usize, card: f32) -> f32 {
        self.levels
            .get(k)
            .map_or(0.0, |l| l.bark_error.max(l.leaf_error(card)))
    }

    /// The distance from which level `k` is drawn, for cards of side `card`.
    pub fn level_distance(&self, k: usize, card: f32) -> f32 {
        (0..=k)
            .map(|j| self.distance_for(self.level_error(j, card)))
            .fold(0.0, f32::max)
    }

    /// The impostor's error: a texel, and half another for the blend between views.
    pub fn impostor_error(&self, impostor: &Impostor) -> f32 {
        1.5 * impostor.texel()
    }

    /// The distance from which the impostor is drawn: where its error spans the allowed
    /// pixels, and never before the last mesh level.
    pub fn impostor_distance(&self, impostor: &Impostor) -> f32 {
        self.distance_for(self.impostor_error(impostor))
    }

    /// Every switch distance for a tree with cards of side `card` and `impostor`: level 1,
    /// level 2, ..., then the impostor; each at least the one before.
    pub fn distances(&self, card: f32, impostor: &Impostor) -> Vec<f32> {
        let mut out: Vec<f32> = (0..self.levels.len())
            .map(|k| self.level_distance(k, card))
            .collect();
        let last = out.last().copied().unwrap_or(0.0);
        out.push(self.impostor_distance(impostor).max(last));
        out
    }
}
