//! Procedural leaf textures: alpha-masked cards drawn in Rust, deterministic from their
//! parameters, so a forest's look needs no image files.
//!
//! A leaf card's texture runs from the petiole at v = 0 to the tip at v = 1, across the blade
//! in u. Colours are near white with veins and blotches darker: the species' leaf colour is
//! multiplied in by the material, so one texture serves every species of a shape.

use sylva_base::hash::{hash_cell, mix, unit_f32};
use sylva_forest::{BarkPattern, LeafShape};

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

    /// The alpha cutoff at which this texture, box-filtered down `level` times as a client
    /// builds its mipmaps, still covers as much of the card as at full size. The texture's
    /// own alpha is 0 or 255, so any cutoff draws it the same up close; a client's mipmaps
    /// average thin leaves and needles below one half at a distance, and alpha cut there
    /// opens crowns up. Between 0.1 and 0.5.
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
        alpha.get(keep).copied().unwrap_or(0.5).clamp(0.1, 0.5)
    }

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
    pub fn tinted(&self, colour: [f32; 3]) -> Texture {
        let decode = |v: u8| {
            let s = f32::from(v) / 255.0;
            if s <= 0.040_45 {
                s / 12.92
            } else {
                ((s + 0.055) / 1.055).powf(2.4)
            }
        };
        let encode = |x: f32| {
            let x = x.clamp(0.0, 1.0);
            let s = if x <= 0.003_130_8 {
                12.92 * x
            } else {
                1.055 * x.powf(1.0 / 2.4) - 0.055
            };
            (s * 255.0).round() as u8
        };
        let mut rgba = self.rgba.clone();
        for px in rgba.chunks_exact_mut(4) {
            for (c, factor) in px[..3].iter_mut().zip(colour) {
                *c = encode(decode(*c) * factor);
            }
        }
        Texture { rgba, ..*self }
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

/// The outline of a leaf blade.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Blade {
    /// Widest at 40 per cent, drawn to a point.
    Ovate,
    /// Obovate (widest at 65 per cent) with four or five rounded lobes a side and a short
    /// stalk: an oak's.
    Lobed,
    /// Ovate with a toothed edge: a birch's or a hazel's.
    Serrated,
}

impl Blade {
    /// The blade's half width at `t` along the midrib (0 base, 1 tip), as a share of the
    /// leaf's half width.
    fn profile(self, t: f32) -> f32 {
        match self {
            Blade::Ovate => (t / 0.4).min(1.0).powf(0.6) * ((1.0 - t) / 0.6).min(1.0).powf(0.9),
            Blade::Lobed => {
                let outline = (t / 0.65).min(1.0).powf(0.8) * ((1.0 - t) / 0.35).min(1.0).powf(0.5);
                // Rounded lobes between sinuses that cut in two fifths of the width.
                let lobes = 0.6 + 0.4 * (t * std::f32::consts::PI * 4.5).sin().abs().powf(0.5);
                if t < 0.06 { 0.12 } else { outline * lobes }
            }
            Blade::Serrated => {
                let outline =
                    (t / 0.35).min(1.0).powf(0.55) * ((1.0 - t) / 0.65).min(1.0).powf(1.1);
                // Small teeth pointing towards the tip.
                outline * (1.0 - 0.12 * (t * 18.0).fract())
            }
        }
    }
}

/// A cluster of three leafy sprays fanning out from the base of the card, as a real-time leaf
/// card shows a whole twig: each spray is [`spray`] shrunk to `SCALE` of the card.
fn leaf_cluster(u: f32, v: f32, x: u32, y: u32, blade: Blade) -> Option<f32> {
    const SCALE: f32 = 0.82;
    // Middle first: where sprays overlap, the middle one is in front.
    for degrees in [0.0f32, -34.0, 34.0] {
        let (s, c) = degrees.to_radians().sin_cos();
        let (dx, dy) = (u - 0.5, v - 0.03);
        let (lu, lv) = ((dx * c - dy * s) / SCALE + 0.5, (dx * s + dy * c) / SCALE);
        if (0.0..=1.0).contains(&lu)
            && (0.0..=1.0).contains(&lv)
            && let Some(shade) = spray(lu, lv, x, y, blade)
        {
            return Some(shade);
        }
    }
    None
}

/// A leafy spray: a twig up the card with eight leaves of `blade` in alternate pairs angled
/// towards its tip and a terminal leaf, each leaf a slightly different shade.
fn spray(u: f32, v: f32, x: u32, y: u32, blade: Blade) -> Option<f32> {
    // The twig: a thin stroke up the middle, to the terminal leaf.
    if (u - 0.5).abs() < 0.010 && v < 0.62 {
        return Some(0.5);
    }
    // Each leaf: base height on the twig, side (-1 left, 0 terminal, 1 right), length and
    // half width, in card units.
    const LEAVES: [(f32, f32, f32, f32); 9] = [
        (0.60, 0.0, 0.38, 0.115),
        (0.52, 1.0, 0.33, 0.10),
        (0.46, -1.0, 0.34, 0.10),
        (0.38, 1.0, 0.35, 0.105),
        (0.31, -1.0, 0.36, 0.105),
        (0.23, 1.0, 0.36, 0.11),
        (0.16, -1.0, 0.35, 0.105),
        (0.09, 1.0, 0.32, 0.10),
        (0.04, -1.0, 0.28, 0.09),
    ];
    for (k, (base, side, length, half)) in LEAVES.into_iter().enumerate() {
        // Side leaves leave the twig at 62 degrees, the terminal one follows it.
        let angle = side * 62f32.to_radians();
        let (s, c) = angle.sin_cos();
        let (dx, dy) = (u - 0.5, v - base);
        // Leaf coordinates: t along the midrib (0 base, 1 tip), w across it.
        let t = (dx * s + dy * c) / length;
        let w = (dx * c - dy * s) / half;
        if !(0.0..=1.0).contains(&t) {
            continue;
        }
        let profile = blade.profile(t);
        if w.abs() > profile {
            continue;
        }
        let midrib = (w.abs() < 0.07) as u8 as f32;
        let vein = ((t * 7.0 - w.abs() * 2.0).fract() < 0.12) as u8 as f32;
        let edge = (w.abs() / profile.max(1e-3)).powi(4);
        let tone = 0.84 + 0.16 * unit_f32(hash_cell(0x1eaf, k as i64, 0, 1));
        return Some(
            tone * (0.95 - 0.12 * edge + 0.06 * midrib - 0.06 * vein) + 0.06 * grain(x, y),
        );
    }
    None
}

/// A spruce's spray: a shoot with eight side shoots in two ranks, alternating, angled towards
/// the tip, of uneven lengths and shorter towards it; every shoot a bottle brush of short needles (a thirtieth of the card) slanting forward, so the
/// card reads as a branchlet, not a frond.
fn needles(u: f32, v: f32, x: u32, y: u32) -> Option<f32> {
    const SIDE_SHOOTS: usize = 8;
    const NEEDLE: f32 = 0.035;
    let p = glam::Vec2::new(u, v);
    // Every shoot: origin, direction, length. The leading shoot first.
    let mut shoots = vec![(glam::Vec2::new(0.5, 0.02), glam::Vec2::Y, 0.93)];
    for k in 0..SIDE_SHOOTS {
        let at = 0.08 + 0.11 * k as f32;
        let side = if k % 2 == 0 { -1.0 } else { 1.0 };
        let angle = (52.0f32 + 4.0 * (k % 3) as f32).to_radians();
        let dir = glam::Vec2::new(side * angle.sin(), angle.cos());
        // Lengths differ shoot to shoot, so the spray's outline is ragged, not a smooth
        // triangle (mipmapped alpha fills the gaps between needles, not between shoots).
        let vigour = 0.4 + 0.9 * unit_f32(hash_cell(0x5b7a, k as i64, 0, 0));
        let length = 0.45 * (1.0 - 0.7 * at) * vigour + 0.04;
        let origin = glam::Vec2::new(0.5, at);
        shoots.push((origin, dir, length));
    }
    for (origin, dir, length) in shoots {
        let d = p - origin;
        let along = d.dot(dir);
        if !(0.0..=length).contains(&along) {
            continue;
        }
        let across = (d - dir * along).length();
        if across < 0.006 {
            return Some(0.5);
        }
        // Needles shorten towards the shoot's tip; each is a stroke slanting forward.
        let reach = NEEDLE * (1.0 - 0.45 * along / length);
        if across < reach && ((along - across * 0.7) / 0.011).fract() < 0.62 {
            return Some(0.78 + 0.12 * grain(x, y));
        }
    }
    None
}

/// A tuft of needles: 40 thin, slightly curved needles of different lengths fanning out
/// from a shoot's tip at the bottom middle of the card, up to 75 degrees either side.
fn needle_tuft(u: f32, v: f32, x: u32, y: u32) -> Option<f32> {
    const COUNT: usize = 40;
    const SPREAD: f32 = 75.0;
    let (dx, dy) = (u - 0.5, v - 0.04);
    let r = (dx * dx + dy * dy).sqrt();
    if r < 0.02 {
        return Some(0.45);
    }
    // Angle from the card's axis, bent a little so the needles curve outwards.
    let angle = dx.atan2(dy).to_degrees() - 12.0 * r * dx.signum();
    let step = 2.0 * SPREAD / (COUNT - 1) as f32;
    let nearest = ((angle + SPREAD) / step).round();
    for k in [nearest - 1.0, nearest, nearest + 1.0] {
        if !(0.0..COUNT as f32).contains(&k) {
            continue;
        }
        let h = hash_cell(0x7af7, k as i64, 0, 0);
        let centre = -SPREAD + k * step + (unit_f32(h) - 0.5) * step * 0.8;
        let length = 0.55 + 0.4 * unit_f32(mix(h));
        // Needles taper: 2.5 texels wide at the base, a point at the tip.
        let half = 0.006 * (1.0 - r / length).max(0.0) + 0.002;
        if r <= length && (angle - centre).to_radians().abs() * r < half {
            return Some(0.75 + 0.2 * unit_f32(mix(mix(h))) + 0.05 * grain(x, y));
        }
    }
    None
}

/// Periodic value noise on a lattice of `cells` (across, along) over a tile of side `n`
/// pixels: it wraps at the tile's edges, so the texture tiles.
fn periodic_noise(x: u32, y: u32, n: u32, cells: (u32, u32), salt: u64) -> f32 {
    let (fx, fy) = (
        x as f32 * cells.0 as f32 / n as f32,
        y as f32 * cells.1 as f32 / n as f32,
    );
    let (x0, y0) = (fx.floor() as u32, fy.floor() as u32);
    let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
    let corner = |i: u32, j: u32| {
        unit_f32(hash_cell(
            salt,
            i64::from(i % cells.0),
            i64::from(j % cells.1),
            0,
        ))
    };
    let smooth = |t: f32| t * t * (3.0 - 2.0 * t);
    let (sx, sy) = (smooth(tx), smooth(ty));
    let top = corner(x0, y0) * (1.0 - sx) + corner(x0 + 1, y0) * sx;
    let bottom = corner(x0, y0 + 1) * (1.0 - sx) + corner(x0 + 1, y0 + 1) * sx;
    top * (1.0 - sy) + bottom * sy
}

/// The bark's height at a texel, from 0 (deepest) to 1, tiling over the side `n`.
fn bark_relief(pattern: BarkPattern, x: u32, y: u32, n: u32) -> f32 {
    match pattern {
        BarkPattern::Smooth => lenticels(x, y, n),
        BarkPattern::Furrowed => ridges(x, y, n),
        BarkPattern::Scaly => plates(x, y, n),
    }
}

/// Furrowed bark: ridges running along the branch (few lattice cells along, many around),
/// furrows between them.
fn ridges(x: u32, y: u32, n: u32) -> f32 {
    let ridges = periodic_noise(x, y, n, (8, 2), 0xba4c) * 0.6
        + periodic_noise(x, y, n, (16, 8), 0xba4d) * 0.3
        + periodic_noise(x, y, n, (32, 32), 0xba4e) * 0.1;
    let furrow = (1.0 - (ridges - 0.5).abs() * 4.0).clamp(0.0, 1.0);
    1.0 - furrow
}

/// Scaly bark: irregular plates, longer along the branch than around it, parted by cracks
/// (the distance to the nearest plate border, from a jittered lattice of plate centres that
/// wraps, so the pattern tiles).
fn plates(x: u32, y: u32, n: u32) -> f32 {
    let (cols, rows) = (9i64, 5i64);
    let (fx, fy) = (
        x as f32 / n as f32 * cols as f32,
        y as f32 / n as f32 * rows as f32,
    );
    let (cx, cy) = (fx.floor() as i64, fy.floor() as i64);
    let (mut first, mut second) = (f32::INFINITY, f32::INFINITY);
    for dy in -1..=1 {
        for dx in -1..=1 {
            let (i, j) = (cx + dx, cy + dy);
            let h = hash_cell(0x5ca1e, i.rem_euclid(cols), j.rem_euclid(rows), 0);
            let (px, py) = (
                i as f32 + 0.15 + 0.7 * unit_f32(h),
                j as f32 + 0.15 + 0.7 * unit_f32(mix(h)),
            );
            // Plates are taller than wide: distances along the branch count for less.
            let d = ((fx - px).powi(2) + (0.6 * (fy - py)).powi(2)).sqrt();
            if d < first {
                second = first;
                first = d;
            } else if d < second {
                second = d;
            }
        }
    }
    ((second - first) * 2.5).clamp(0.0, 1.0).powf(0.7)
}

/// Smooth bark with lenticels: short horizontal dashes, slightly sunk, scattered on a level
/// surface.
fn lenticels(x: u32, y: u32, n: u32) -> f32 {
    // Dashes sit on a periodic lattice of 6 x 24 cells (wide around, short along), each
    // with a random length and offset, so the pattern tiles.
    let (cols, rows) = (6u32, 24u32);
    let (cw, ch) = (n / cols, n / rows);
    let (cx, cy) = ((x / cw).min(cols - 1), (y / ch).min(rows - 1));
    let h = hash_cell(0xb1c4, i64::from(cx), i64::from(cy), 0);
    let length = 0.3 + 0.6 * unit_f32(h);
    let offset = unit_f32(mix(h)) * (1.0 - length);
    let (fx, fy) = (
        (x - cx * cw) as f32 / cw as f32,
        (y - cy * ch) as f32 / ch as f32,
    );
    let dash = fx >= offset && fx <= offset + length && (0.35..0.65).contains(&fy);
    if dash { 0.0 } else { 1.0 }
}
