//! Bark relief that tiles: ridges, plates and lenticels over periodic noise.

use sylva_base::hash::{hash_cell, mix, unit_f32};
use sylva_forest::BarkPattern;

/// Periodic value noise on a lattice of `cells` (across, along) over a tile of side `n`
/// pixels: it wraps at the tile's edges, so the texture tiles.
pub(super) fn periodic_noise(x: u32, y: u32, n: u32, cells: (u32, u32), salt: u64) -> f32 {
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
pub(super) fn bark_relief(pattern: BarkPattern, x: u32, y: u32, n: u32) -> f32 {
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
