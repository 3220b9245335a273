//! An impostor as plain geometry, for clients without an impostor shader: three upright
//! cards about the trunk's axis at 60 degrees from each other and one level card across the
//! crown, each showing the atlas view that looks straight at it, both ways. 24 triangles, alpha-cut,
//! that any glTF viewer draws.

use glam::{Vec2, Vec3};
use sylva_turtle::{Mesh, Vertex};

use super::impostor::{Impostor, layout};
use super::raster::OrthoView;
use crate::texture::Texture;

/// The views the cards show: the horizon views nearest 0, 60 and 120 degrees round the tree,
/// and the view nearest straight down, as lattice points `(i, j)`.
fn card_views(grid: u32) -> Vec<(u32, u32)> {
    let nearest = |d: Vec3, border_only: bool| {
        let mut best = ((0, 0), f32::NEG_INFINITY);
        for j in 0..grid {
            for i in 0..grid {
                let on_border = i == 0 || j == 0 || i == grid - 1 || j == grid - 1;
                if border_only && !on_border {
                    continue;
                }
                let score = Impostor::view_direction(grid, i, j).dot(d);
                if score > best.1 {
                    best = ((i, j), score);
                }
            }
        }
        best.0
    };
    let mut views: Vec<(u32, u32)> = [0.0f32, 60.0, 120.0]
        .iter()
        .map(|a| {
            let a = a.to_radians();
            nearest(Vec3::new(a.sin(), 0.0, a.cos()), true)
        })
        .collect();
    views.push(nearest(Vec3::Y, false));
    views
}

/// The alpha cutoff of the cards' material: the views' alpha is each texel's coverage, and a
/// third keeps a crown's fringe up close and its coverage through a client's first few
/// mipmaps, where one half would thin crowns out with distance.
pub const CARD_ALPHA_CUTOFF: f32 = 0.3;

/// Padding about each view in the cards' texture, as a share of the view's side: clear
/// texels, so that a client's mipmaps do not blend one view into the next.
const PAD_SHARE: u32 = 8;

/// The layout of the cards' texture for views of `size` pixels: the padding and the side of
/// each padded tile (four tiles in a row).
fn strip_layout(size: u32) -> (u32, u32) {
    let pad = (size / PAD_SHARE).max(2);
    (pad, size + 2 * pad)
}

impl Impostor {
    /// The texture of the impostor's cards ([`impostor_cards`]): the four views they show in
    /// a row, each padded with clear texels (its colour carried out into them) so that a
    /// client's mipmaps keep the views apart. A few hundred kilobytes where the atlas is a
    /// megabyte or more.
    pub fn cards_texture(&self) -> Texture {
        let size = self.view_size;
        let (pad, tile) = strip_layout(size);
        let (width, height) = (4 * tile, tile);
        let mut rgba = vec![0u8; (width * height * 4) as usize];
        let side = self.colour.width;
        for (k, (i, j)) in card_views(self.grid).into_iter().enumerate() {
            for y in 0..tile {
                for x in 0..tile {
                    // The nearest texel of the view: the padding repeats the view's edge,
                    // clear.
                    let sx = x.saturating_sub(pad).min(size - 1);
                    let sy = y.saturating_sub(pad).min(size - 1);
                    let from = (((j * size + sy) * side + i * size + sx) * 4) as usize;
                    let to = ((y * width + k as u32 * tile + x) * 4) as usize;
                    let inside = (pad..pad + size).contains(&x) && (pad..pad + size).contains(&y);
                    let Some(texel) = self.colour.rgba.get(from..from + 4) else {
                        continue;
                    };
                    rgba[to..to + 3].copy_from_slice(&texel[..3]);
                    rgba[to + 3] = if inside { texel[3] } else { 0 };
                }
            }
        }
        Texture {
            width,
            height,
            rgba,
        }
    }
}

/// The impostor's cards: leaf triangles whose texture coordinates address its
/// [`Impostor::cards_texture`].
///
/// ```
/// use sylva_export::lod::{Impostor, ImpostorOptions, TreeLook, impostor_cards};
/// let species = sylva_forest::Species::from_preset("sylva-hazel", 3)?;
/// let mesh = species.mesh(3, 1)?;
/// let impostor = Impostor::render(&mesh, &TreeLook::of(&species), &ImpostorOptions::default().with_view_size(32));
/// let cards = impostor_cards(&impostor);
/// assert_eq!(cards.triangle_count(), 24);
/// assert!(cards.vertices.iter().all(|v| (0.0..=1.0).contains(&v.uv[0]) && (0.0..=1.0).contains(&v.uv[1])));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn impostor_cards(impostor: &Impostor) -> Mesh {
    cards(
        (impostor.grid, impostor.view_size),
        Vec3::from(impostor.centre),
        impostor.radius,
    )
}

/// The cards of an impostor of `grid` views of `view_size` pixels framing the sphere
/// (`centre`, `r`): all they need of the impostor, so a writer that refers to a texture drawn
/// elsewhere places them without drawing it ([`Impostor::frame`] gives the sphere of a tree).
pub fn cards((grid, view_size): (u32, u32), centre: Vec3, r: f32) -> Mesh {
    let (grid, size) = layout(grid, view_size);
    let (pad, tile) = strip_layout(size);
    let mut mesh = Mesh::default();
    let views = card_views(grid);
    // Where a point (relative to the centre) falls in the `k`th view's tile of the texture.
    let atlas_uv = |k: usize, d: Vec3| {
        let (i, j) = views[k];
        let (right, up) = OrthoView::axes(Impostor::view_direction(grid, i, j));
        let inside = Vec2::new(d.dot(right) / r * 0.5 + 0.5, 0.5 - d.dot(up) / r * 0.5);
        let texel = Vec2::new((k as u32 * tile + pad) as f32, pad as f32)
            + inside.clamp(Vec2::ZERO, Vec2::ONE) * size as f32;
        texel / Vec2::new((4 * tile) as f32, tile as f32)
    };
    // Every card faces the sky as far as light goes: lit like the top of a crown, and alike,
    // so no card's edge shows where it crosses another.
    let vertex = |p: Vec3, uv: Vec2| Vertex {
        position: (centre + p).to_array(),
        normal: Vec3::Y.to_array(),
        uv: uv.to_array(),
        wind: [0.0, 0.0, 0.0, 0.0],
    };
    // Three upright cards, each in the plane its view looks straight at.
    for (k, &(i, j)) in views[..3].iter().enumerate() {
        let (right, up) = OrthoView::axes(Impostor::view_direction(grid, i, j));
        let first = mesh.vertices.len() as u32;
        for (x, y) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
            let d = (right * x + up * y) * r;
            mesh.vertices.push(vertex(d, atlas_uv(k, d)));
        }
        mesh.leaves
            .extend_from_slice(&[first, first + 1, first + 2, first, first + 2, first + 3]);
    }
    // A level octagon through the centre, inscribed in the sphere, showing the view nearest
    // straight down (projected into that view, so the card stays level however the view
    // leans).
    let first = mesh.vertices.len() as u32;
    for k in 0..8 {
        let a = std::f32::consts::TAU * (k as f32 + 0.5) / 8.0;
        let d = Vec3::new(a.cos(), 0.0, a.sin()) * r;
        mesh.vertices.push(vertex(d, atlas_uv(3, d)));
    }
    for k in 1..7 {
        mesh.leaves
            .extend_from_slice(&[first, first + k + 1, first + k]);
    }
    // Each card again facing the other way: clients flip a double-sided face's normal on its
    // back, which would light the back of every card as if it faced the ground; one-sided
    // cards both ways are lit alike from either side.
    let front = mesh.leaves.clone();
    for t in front.chunks_exact(3) {
        mesh.leaves.extend_from_slice(&[t[0], t[2], t[1]]);
    }
    mesh
}
