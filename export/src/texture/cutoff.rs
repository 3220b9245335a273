//! Alpha cutoffs that survive a client's mipmaps: leaf cards keep their coverage at a
//! distance.

use sylva_forest::LeafShape;

use super::Texture;

/// The mip level whose coverage a leaf card's alpha cutoff keeps
/// ([`Texture::alpha_cutoff`]): 4 x 4 texels of the 256 x 256
/// card, about what a client samples for a card 150 m away at 1280 x 720. Nearer, the card
/// draws as it is (its alpha is 0 or 1); farther, it keeps its coverage instead of fading
/// out. Measured in three.js from above: 72% foliage from 70 m and 74% from 260 m (the cutoff
/// at one half: 60% and 6%).
pub const CUTOFF_MIP_LEVEL: u32 = 6;

/// The alpha cutoff glTF materials give `shape`'s leaf cards: its texture's
/// [`Texture::alpha_cutoff`] at [`CUTOFF_MIP_LEVEL`], worked out once per shape.
pub(crate) fn card_alpha_cutoff(shape: LeafShape) -> f32 {
    static CUTOFFS: std::sync::OnceLock<Vec<(LeafShape, f32)>> = std::sync::OnceLock::new();
    let cutoffs = CUTOFFS.get_or_init(|| {
        LeafShape::ALL
            .into_iter()
            .map(|s| (s, Texture::leaf(s).alpha_cutoff(CUTOFF_MIP_LEVEL)))
            .collect()
    });
    cutoffs
        .iter()
        .find(|(s, _)| *s == shape)
        .map_or(0.5, |(_, c)| *c)
}

impl Texture {
    /// The alpha cutoff at which this texture, box-filtered down `level` times as a client
    /// builds its mipmaps, still covers as much of the card as at full size. The texture's
    /// own alpha is 0 or 255, so any cutoff draws it the same up close; a client's mipmaps
    /// average thin leaves and needles below one half at a distance, and alpha cut there
    /// opens crowns up. At most nine tenths of the texture's mean alpha, so even its
    /// one-texel mip draws; between 0.1 and 0.5.
    ///
    /// ```
    /// use sylva_export::Texture;
    /// use sylva_forest::LeafShape;
    /// let needles = Texture::leaf(LeafShape::NeedleTuft).alpha_cutoff(4);
    /// let broad = Texture::leaf(LeafShape::Broadleaf).alpha_cutoff(4);
    /// assert!(needles < broad && broad <= 0.5);
    /// ```
    pub fn alpha_cutoff(&self, level: u32) -> f32 {
        let mut alpha: Vec<f32> = self
            .rgba
            .chunks_exact(4)
            .map(|p| f32::from(p[3]) / 255.0)
            .collect();
        let covered = alpha.iter().filter(|&&a| a > 0.5).count() as f32 / alpha.len() as f32;
        // The last mip is one texel of the mean alpha: a cutoff below it keeps a card a pixel
        // or two across (a small needle card 250 m away) drawn instead of dropped.
        let mean = alpha.iter().sum::<f32>() / alpha.len() as f32;
        let (mut w, mut h) = (self.width as usize, self.height as usize);
        for _ in 0..level {
            if w < 2 || h < 2 {
                break;
            }
            let (nw, nh) = (w / 2, h / 2);
            let at = |x: usize, y: usize| alpha[y * w + x];
            alpha = (0..nh)
                .flat_map(|y| (0..nw).map(move |x| (x, y)))
                .map(|(x, y)| {
                    (at(2 * x, 2 * y)
                        + at(2 * x + 1, 2 * y)
                        + at(2 * x, 2 * y + 1)
                        + at(2 * x + 1, 2 * y + 1))
                        / 4.0
                })
                .collect();
            (w, h) = (nw, nh);
        }
        // The cutoff that keeps the same share of the small image's texels.
        alpha.sort_by(|a, b| b.total_cmp(a));
        let keep = ((covered * alpha.len() as f32).round() as usize).min(alpha.len() - 1);
        alpha
            .get(keep)
            .copied()
            .unwrap_or(0.5)
            .min(0.9 * mean)
            .clamp(0.1, 0.5)
    }
}
