//! The leaf cards' shapes: clusters of blades, sprays, needles and needle tufts, each a
//! texel's shade inside the card or `None` outside it.

use sylva_base::hash::{hash_cell, mix, unit_f32};

use super::grain;

/// The outline of a leaf blade.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Blade {
    /// Widest at 40 per cent, drawn to a point.
    Ovate,
    /// Obovate (widest at 65 per cent) with four or five rounded lobes a side and a short
    /// stalk: an oak's.
    Lobed,
    /// Ovate with a toothed edge.
    Serrated,
    /// Round-ovate with a short tip and a doubly toothed edge (large teeth carrying small
    /// ones): a hazel's, an aspen's, an alder's.
    Rounded,
    /// Triangular-ovate, widest near a broad straight base and drawn to a long point, finely
    /// doubly toothed: a birch's.
    Deltoid,
    /// Five-lobed like a hand, as broad as long, the lobes coarsely toothed: a sycamore's.
    Palmate,
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
            Blade::Rounded => {
                // Near a circle widest at 45 per cent, with a short drawn-out tip.
                let round = (1.0 - ((t - 0.45) / 0.55).powi(2)).max(0.0).sqrt();
                let tip = ((1.0 - t) / 0.12).min(1.0).powf(0.7);
                let base = (t / 0.04).min(1.0);
                round * tip * base * double_teeth(t, 8.0, 0.09)
            }
            Blade::Deltoid => {
                let outline = (t / 0.22).min(1.0).powf(0.35) * ((1.0 - t) / 0.78).min(1.0);
                outline * double_teeth(t, 11.0, 0.07)
            }
            Blade::Palmate => {
                // Three bulges a side: the basal lobes pointing sideways, the side lobes
                // forwards and out, the terminal lobe; deep sinuses between them.
                let lobe = |centre: f32, reach: f32, height: f32| {
                    height * (1.0 - ((t - centre) / reach).powi(2)).max(0.0).sqrt()
                };
                let core = if (0.04..0.9).contains(&t) { 0.2 } else { 0.0 };
                let outline = lobe(0.2, 0.17, 0.8)
                    .max(lobe(0.52, 0.2, 1.0))
                    .max(lobe(0.8, 0.2, 0.42))
                    .max(core);
                outline * (1.0 - 0.1 * (t * 14.0).fract())
            }
        }
    }

    /// How much wider than an ovate blade of the same length this blade is drawn: round and
    /// palmate leaves are nearly as broad as long.
    fn breadth(self) -> f32 {
        match self {
            Blade::Ovate | Blade::Lobed | Blade::Serrated => 1.0,
            Blade::Rounded => 1.45,
            Blade::Deltoid => 1.25,
            Blade::Palmate => 1.9,
        }
    }
}

/// A doubly toothed margin: `teeth` large teeth along the blade, each with two small ones,
/// cutting in `depth` of the half width; the teeth point towards the tip.
fn double_teeth(t: f32, teeth: f32, depth: f32) -> f32 {
    1.0 - depth * (t * teeth).fract() - 0.5 * depth * (t * teeth * 3.0).fract()
}

/// A cluster of three leafy sprays fanning out from the base of the card, as a real-time leaf
/// card shows a whole twig: each spray is [`spray`] shrunk to `SCALE` of the card.
pub(super) fn leaf_cluster(u: f32, v: f32, x: u32, y: u32, blade: Blade) -> Option<f32> {
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
        let w = (dx * c - dy * s) / (half * blade.breadth());
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

/// A spruce's spray: a shoot with twelve side shoots in two ranks, alternating, angled towards
/// the tip, of uneven lengths and shorter towards it; every shoot a bottle brush of needles
/// (a twentieth of the card) slanting forward, close enough that the spray is a dense mat
/// with a ragged needled edge (about a third of the card opaque): the card reads as a
/// branchlet, not a frond, and a crown of them is dark and closed as a spruce's is, even in
/// clients that draw cards without mipmaps.
pub(super) fn needles(u: f32, v: f32, x: u32, y: u32) -> Option<f32> {
    const SIDE_SHOOTS: usize = 12;
    const NEEDLE: f32 = 0.05;
    let p = glam::Vec2::new(u, v);
    // Every shoot: origin, direction, length. The leading shoot first.
    let mut shoots = vec![(glam::Vec2::new(0.5, 0.02), glam::Vec2::Y, 0.93)];
    for k in 0..SIDE_SHOOTS {
        let at = 0.06 + 0.072 * k as f32;
        let side = if k % 2 == 0 { -1.0 } else { 1.0 };
        let angle = (50.0f32 + 5.0 * (k % 3) as f32).to_radians();
        let dir = glam::Vec2::new(side * angle.sin(), angle.cos());
        // Lengths differ shoot to shoot, so the spray's outline is ragged, not a smooth
        // triangle.
        let vigour = 0.6 + 0.6 * unit_f32(hash_cell(0x5b7a, k as i64, 0, 0));
        let length = 0.5 * (1.0 - 0.7 * at) * vigour + 0.05;
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
        if across < 0.007 {
            return Some(0.5);
        }
        // Needles shorten towards the shoot's tip; each is a stroke slanting forward.
        let reach = NEEDLE * (1.0 - 0.4 * along / length);
        if across < reach && ((along - across * 0.7) / 0.01).fract() < 0.7 {
            return Some(0.78 + 0.12 * grain(x, y));
        }
    }
    None
}

/// A pine's shoot end: a short shoot up the middle of the card, clothed along its last two
/// thirds in paired needles (150 of them, long and stiff, about a third of the card opaque)
/// slanting forward at 20 to 55 degrees and a brush of longer ones from its tip, so the card
/// reads as a tufted branch end, not a fan, and a crown of them closes as a pine's does.
pub(super) fn pine_shoot(u: f32, v: f32, x: u32, y: u32) -> Option<f32> {
    const COUNT: usize = 150;
    const SHOOT: f32 = 0.62;
    let p = glam::Vec2::new(u, v);
    // The shoot: a stroke up the middle from the card's base.
    if (u - 0.5).abs() < 0.012 && v < SHOOT {
        return Some(0.42);
    }
    for k in 0..COUNT {
        let h = hash_cell(0x7af7, k as i64, 0, 0);
        // Where the needle leaves the shoot: spread along its upper part, the last eighth of
        // them from its tip.
        let along = if k < COUNT * 7 / 8 {
            0.2 + (SHOOT - 0.2) * (k as f32 + unit_f32(h)) / (COUNT * 7 / 8) as f32
        } else {
            SHOOT
        };
        let side = if k % 2 == 0 { -1.0 } else { 1.0 };
        // Needles near the tip slant forward more; those from the tip itself fan a little.
        let slant = if along >= SHOOT {
            (unit_f32(mix(h)) - 0.5) * 60.0
        } else {
            side * (55.0 - 30.0 * (along - 0.2) / (SHOOT - 0.2) + 8.0 * unit_f32(mix(h)))
        };
        let (s, c) = slant.to_radians().sin_cos();
        let dir = glam::Vec2::new(s, c);
        let length = 0.26 + 0.16 * unit_f32(mix(mix(h)));
        let d = p - glam::Vec2::new(0.5, along);
        let t = d.dot(dir);
        if !(0.0..=length).contains(&t) {
            continue;
        }
        // Needles taper: three texels wide at the base, a point at the tip.
        let half = 0.007 * (1.0 - t / length) + 0.002;
        if (d - dir * t).length() < half {
            return Some(0.72 + 0.22 * unit_f32(mix(mix(mix(h)))) + 0.05 * grain(x, y));
        }
    }
    None
}

/// A tuft of needles: 40 thin, slightly curved needles of different lengths fanning out
/// from a shoot's tip at the bottom middle of the card, up to 75 degrees either side.
pub(super) fn needle_tuft(u: f32, v: f32, x: u32, y: u32) -> Option<f32> {
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
