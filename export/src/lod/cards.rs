//! An impostor as plain geometry, for clients without an impostor shader: three upright
//! cards about the trunk's axis at 60 degrees from each other and one level card across the
//! crown, each showing the atlas view that looks straight at it. Eight triangles, alpha-cut,
//! that any glTF viewer draws.

use glam::{Vec2, Vec3};
use sylva_turtle::{Mesh, Vertex};

use super::impostor::Impostor;
use super::raster::OrthoView;

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

/// The impostor's cards: leaf triangles whose texture coordinates address its atlas.
///
/// ```
/// use sylva_export::lod::{Impostor, ImpostorOptions, TreeLook, impostor_cards};
/// let species = sylva_forest::Species::from_preset("sylva-hazel", 3)?;
/// let mesh = species.mesh(3, 1)?;
/// let impostor = Impostor::render(&mesh, &TreeLook::of(&species), &ImpostorOptions::default().with_view_size(32));
/// let cards = impostor_cards(&impostor);
/// assert_eq!(cards.triangle_count(), 8);
/// assert!(cards.vertices.iter().all(|v| (0.0..=1.0).contains(&v.uv[0]) && (0.0..=1.0).contains(&v.uv[1])));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn impostor_cards(impostor: &Impostor) -> Mesh {
    cards(impostor.grid, Vec3::from(impostor.centre), impostor.radius)
}

/// The cards of an impostor of `grid` views framing the sphere (`centre`, `r`): all they
/// need of the impostor, so a writer that refers to an atlas drawn elsewhere places them
/// without drawing it ([`Impostor::frame`] gives the sphere of a tree).
pub fn cards(grid: u32, centre: Vec3, r: f32) -> Mesh {
    let grid = grid.clamp(2, 32);
    let mut mesh = Mesh::default();
    for (i, j) in card_views(grid) {
        let toward = Impostor::view_direction(grid, i, j);
        let (right, up) = OrthoView::axes(toward);
        // The picture's corners: (0, 0) is its top left, at centre - right r + up r.
        let tile = Vec2::new(i as f32, j as f32);
        let first = mesh.vertices.len() as u32;
        for (x, y) in [(0.0f32, 1.0f32), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)] {
            let p = centre + right * ((2.0 * x - 1.0) * r) + up * ((1.0 - 2.0 * y) * r);
            // Half a texel in from the tile's edges, so filtering stays within the view.
            let inset = Vec2::new(x, y).clamp(Vec2::splat(0.004), Vec2::splat(0.996));
            let uv = (tile + inset) / grid as f32;
            mesh.vertices.push(Vertex {
                position: p.to_array(),
                normal: toward.to_array(),
                uv: uv.to_array(),
                wind: [0.0, 0.0, 0.0, 0.0],
            });
        }
        mesh.leaves
            .extend_from_slice(&[first, first + 1, first + 2, first, first + 2, first + 3]);
    }
    mesh
}
