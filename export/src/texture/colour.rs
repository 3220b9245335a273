//! Colour in textures: the sRGB transfer function both ways, and textures tinted by a
//! material's colour.

use super::Texture;

/// An 8-bit sRGB channel value as linear light in [0, 1].
///
/// ```
/// use sylva_export::{linear_to_srgb, srgb_to_linear};
/// assert_eq!(srgb_to_linear(0), 0.0);
/// assert!((srgb_to_linear(255) - 1.0).abs() < 1e-6);
/// assert!((srgb_to_linear(188) - 0.5).abs() < 0.01); // mid-grey is 188, not 128
/// for v in 0..=255u8 {
///     assert_eq!(linear_to_srgb(srgb_to_linear(v)), v);
/// }
/// ```
pub fn srgb_to_linear(v: u8) -> f32 {
    let s = f32::from(v) / 255.0;
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear light (clamped to [0, 1]) as an 8-bit sRGB channel value, rounded.
pub fn linear_to_srgb(x: f32) -> u8 {
    let x = x.clamp(0.0, 1.0);
    let s = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

impl Texture {
    /// This texture with its colour multiplied by `colour` (linear RGB) as a renderer
    /// multiplies a material's colour factor: each texel decoded from sRGB, multiplied and
    /// encoded again; alpha kept. For formats whose clients read a material's texture without
    /// a factor (USD files give each species its own tinted leaf and bark images).
    ///
    /// ```
    /// use sylva_export::Texture;
    /// use sylva_forest::LeafShape;
    /// let white = Texture::leaf(LeafShape::Broadleaf);
    /// let green = white.tinted([0.1, 0.5, 0.05]);
    /// let middle = ((white.height / 2 * white.width + white.width / 2) * 4) as usize;
    /// let (w, g) = (&white.rgba[middle..middle + 4], &green.rgba[middle..middle + 4]);
    /// assert!(g[1] > g[0] && g[1] > g[2] && g[1] <= w[1]); // greener, never brighter
    /// assert_eq!(g[3], w[3]); // the same cut-out
    /// ```
    #[must_use]
    pub fn tinted(&self, colour: [f32; 3]) -> Texture {
        let mut rgba = self.rgba.clone();
        for px in rgba.chunks_exact_mut(4) {
            for (c, factor) in px[..3].iter_mut().zip(colour) {
                *c = linear_to_srgb(srgb_to_linear(*c) * factor);
            }
        }
        Texture { rgba, ..*self }
    }
}
