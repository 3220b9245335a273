//! Procedural textures, leaf cards (alpha-masked) and bark (colour and normal maps), drawn in
//! Rust and deterministic from their parameters, so a forest's look needs no image files.
//!
//! A leaf card's texture runs from the petiole at v = 0 to the tip at v = 1, across the blade
//! in u. Colours are near white with veins and blotches darker: the species' leaf colour is
//! multiplied in by the material, so one texture serves every species of a shape.

mod bark;
mod colour;
mod cutoff;
mod leaf;

use sylva_base::hash::{hash_cell, unit_f32};
use sylva_forest::{BarkPattern, LeafShape};

use bark::{bark_relief, periodic_noise};
pub use colour::{linear_to_srgb, srgb_to_linear};
pub use cutoff::CUTOFF_MIP_LEVEL;
pub(crate) use cutoff::card_alpha_cutoff;
use leaf::{Blade, leaf_cluster, needle_tuft, needles, pine_shoot};

/// An RGBA8 image, rows from the top (v = 0 is the first row).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Texture {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// Row-major RGBA, straight alpha.
    pub rgba: Vec<u8>,
}

/// Side of the leaf and bark textures (colour and normal maps), in pixels.
pub const TEXTURE_SIZE: u32 = 256;

impl Texture {
    /// The leaf texture of `shape`: transparent outside the leaves (alpha 0), opaque inside.
    ///
    /// ```
    /// use sylva_export::Texture;
    /// use sylva_forest::LeafShape;
    /// let t = Texture::leaf(LeafShape::Broadleaf);
    /// let alpha = |x: u32, y: u32| t.rgba[((y * t.width + x) * 4 + 3) as usize];
    /// assert_eq!(alpha(0, 0), 0); // a corner is outside the blade
    /// assert_eq!(alpha(t.width / 2, t.height / 2), 255); // the middle is leaf
    /// ```
    pub fn leaf(shape: LeafShape) -> Texture {
        let n = TEXTURE_SIZE;
        let mut rgba = vec![0u8; (n * n * 4) as usize];
        for y in 0..n {
            for x in 0..n {
                let (u, v) = ((x as f32 + 0.5) / n as f32, (y as f32 + 0.5) / n as f32);
                let texel = match shape {
                    LeafShape::Broadleaf => leaf_cluster(u, v, x, y, Blade::Ovate),
                    LeafShape::Lobed => leaf_cluster(u, v, x, y, Blade::Lobed),
                    LeafShape::Serrated => leaf_cluster(u, v, x, y, Blade::Serrated),
                    LeafShape::Needles => needles(u, v, x, y),
                    LeafShape::NeedleTuft => needle_tuft(u, v, x, y),
                    LeafShape::Rounded => leaf_cluster(u, v, x, y, Blade::Rounded),
                    LeafShape::Deltoid => leaf_cluster(u, v, x, y, Blade::Deltoid),
                    LeafShape::Palmate => leaf_cluster(u, v, x, y, Blade::Palmate),
                    LeafShape::PineShoot => pine_shoot(u, v, x, y),
                };
                if let Some(shade) = texel {
                    let i = ((y * n + x) * 4) as usize;
                    let s = (shade.clamp(0.0, 1.0) * 255.0).round() as u8;
                    // A faint yellow-green cast in the veins and blotches, white elsewhere.
                    rgba[i..i + 4].copy_from_slice(&[s, s, (f32::from(s) * 0.92) as u8, 255]);
                }
            }
        }
        Texture {
            width: n,
            height: n,
            rgba,
        }
    }

    /// A bark texture that tiles in both directions (u around a branch, v along it), near
    /// white so that each species' bark colour tints it: long ridges broken by furrows
    /// ([`BarkPattern::Furrowed`]) or smooth bark with dark lenticels
    /// ([`BarkPattern::Smooth`]), with a little grain.
    ///
    /// ```
    /// use sylva_export::Texture;
    /// use sylva_forest::BarkPattern;
    /// let t = Texture::bark(BarkPattern::Furrowed);
    /// let n = t.width as usize;
    /// // Opaque everywhere, and the first column continues the last (it tiles).
    /// assert!(t.rgba.chunks_exact(4).all(|p| p[3] == 255));
    /// let gap = |a: usize, b: usize| (t.rgba[a * 4] as i32 - t.rgba[b * 4] as i32).abs();
    /// assert!((0..n).all(|y| gap(y * n, y * n + n - 1) < 48));
    /// ```
    pub fn bark(pattern: BarkPattern) -> Texture {
        Texture::tile(|x, y, n| {
            let relief = bark_relief(pattern, x, y, n);
            let shade = match pattern {
                BarkPattern::Smooth => {
                    let blotch = periodic_noise(x, y, n, (8, 8), 0xb1c5);
                    // Lenticels are dark; the rest pale with faint blotches.
                    0.35 + 0.62 * relief - 0.12 * blotch + 0.04 * grain(x, y)
                }
                BarkPattern::Scaly => {
                    // Plates differ a little in tone; the cracks between them are dark.
                    let tone = periodic_noise(x, y, n, (6, 10), 0x5ca1);
                    0.45 + 0.45 * relief + 0.1 * tone + 0.06 * grain(x, y)
                }
                BarkPattern::Furrowed => 0.6 + 0.35 * relief + 0.08 * grain(x, y),
            };
            let s = (shade.clamp(0.0, 1.0) * 255.0).round() as u8;
            [s, s, s, 255]
        })
    }

    /// The tangent-space normal map of a bark pattern's relief, tiling like
    /// [`Texture::bark`]: red along +u (around the branch), green along -v (up the image, as
    /// glTF's normal textures read), blue out of the surface.
    ///
    /// ```
    /// use sylva_export::Texture;
    /// use sylva_forest::BarkPattern;
    /// let t = Texture::bark_normal(BarkPattern::Furrowed);
    /// // Every texel is a unit normal pointing out of the surface.
    /// for p in t.rgba.chunks_exact(4) {
    ///     let n = [p[0], p[1], p[2]].map(|c| c as f32 / 127.5 - 1.0);
    ///     let length = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    ///     assert!((length - 1.0).abs() < 0.02 && n[2] > 0.3);
    /// }
    /// ```
    pub fn bark_normal(pattern: BarkPattern) -> Texture {
        // Relief depth in texels per unit of height: furrows are deep, lenticels shallow.
        let depth = match pattern {
            BarkPattern::Smooth => 1.5,
            BarkPattern::Scaly => 4.0,
            BarkPattern::Furrowed => 6.0,
        };
        Texture::tile(|x, y, n| {
            let h = |dx: u32, dy: u32| bark_relief(pattern, (x + dx) % n, (y + dy) % n, n);
            // Central differences that wrap, so the map tiles like the relief.
            let du = (h(1, 0) - h(n - 1, 0)) * 0.5 * depth;
            let dv = (h(0, 1) - h(0, n - 1)) * 0.5 * depth;
            let (nx, ny, nz) = (-du, dv, 1.0f32);
            let length = (nx * nx + ny * ny + nz * nz).sqrt();
            let [r, g, b] = [nx, ny, nz].map(|c| ((c / length * 0.5 + 0.5) * 255.0).round() as u8);
            [r, g, b, 255]
        })
    }

    /// A square image of side [`TEXTURE_SIZE`] from a function of (x, y, side).
    fn tile(texel: impl Fn(u32, u32, u32) -> [u8; 4]) -> Texture {
        let n = TEXTURE_SIZE;
        let mut rgba = Vec::with_capacity((n * n * 4) as usize);
        for y in 0..n {
            for x in 0..n {
                rgba.extend_from_slice(&texel(x, y, n));
            }
        }
        Texture {
            width: n,
            height: n,
            rgba,
        }
    }

    /// The image as PNG bytes.
    pub fn png(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let mut encoder = png::Encoder::new(&mut out, self.width, self.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        // Writing to a Vec cannot fail and the data has the size the header says.
        if let Ok(mut writer) = encoder.write_header() {
            let _ = writer.write_image_data(&self.rgba);
        }
        out
    }
}

/// A little per-pixel noise, the same on every machine.
fn grain(x: u32, y: u32) -> f32 {
    unit_f32(hash_cell(0x1eaf, i64::from(x), i64::from(y), 0)) - 0.5
}
