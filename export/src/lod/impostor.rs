//! Impostors: a tree drawn from many directions into one atlas, so that far away it is one
//! camera-facing card that shows the tree as seen from where the camera stands.
//!
//! The directions cover the upper hemisphere on a hemi-octahedral lattice: the unit
//! direction `(x, y, z)` (y up, `y >= 0`) maps to the square by
//! `s = |x| + y + |z|`, `(p, q) = (x / s, z / s)`, `uv = ((p + q) / 2 + 1/2, (p - q) / 2 + 1/2)`;
//! the square's middle looks straight down and its border along the horizon. View `(i, j)` of
//! a grid of `N x N` looks from the lattice point `uv = (i / (N - 1), j / (N - 1))`, so the
//! border views stand on the horizon (trees are mostly seen from the side), and it fills the
//! atlas' tile in column `i`, row `j`. A client finds the three views around its own direction
//! and blends them.

use glam::{Vec2, Vec3};
use rayon::prelude::*;
use sylva_turtle::Mesh;

use super::raster::{OrthoView, Picture, TreeLook, draw};
use crate::texture::{Texture, linear_to_srgb};

/// The widest atlas drawn, in pixels: views shrink so that `grid * view_size` stays within it
/// (three 8192-pixel RGBA images are 768 MiB).
pub const MAX_ATLAS_SIDE: u32 = 8192;

/// How an impostor is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct ImpostorOptions {
    /// Views along each side of the hemi-octahedral grid (2 to 32). Default: 8.
    pub grid: u32,
    /// Pixels across each view (8 to 1024, and at most [`MAX_ATLAS_SIDE`] over `grid`).
    /// Default: 128.
    pub view_size: u32,
}

impl Default for ImpostorOptions {
    /// 8 x 8 views of 128 pixels: a 1024-pixel atlas, a texel of 1/64 of the tree's
    /// bounding diameter.
    fn default() -> Self {
        ImpostorOptions {
            grid: 8,
            view_size: 128,
        }
    }
}

impl ImpostorOptions {
    /// Sets [`ImpostorOptions::grid`].
    #[must_use]
    pub fn with_grid(mut self, grid: u32) -> Self {
        self.grid = grid;
        self
    }

    /// Sets [`ImpostorOptions::view_size`].
    #[must_use]
    pub fn with_view_size(mut self, view_size: u32) -> Self {
        self.view_size = view_size;
        self
    }
}

/// A tree's impostor: its atlas of views and the sphere they frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Impostor {
    /// Views along each side.
    pub grid: u32,
    /// Pixels across each view.
    pub view_size: u32,
    /// The centre of the sphere every view frames, in the tree's space.
    pub centre: [f32; 3],
    /// Its radius: each view is a square of side twice this about the centre.
    pub radius: f32,
    /// Colour (sRGB) and coverage (alpha); uncovered texels carry their neighbours' colour
    /// so that filtering does not darken the edges.
    pub colour: Texture,
    /// The surface normal in the tree's space (`rgb = n / 2 + 1/2`) and, in alpha, the share
    /// of leaves in what covers the texel (0: bark).
    pub normal: Texture,
    /// Nearness towards the viewer (grey, `0.5` at the centre's plane, `1` a radius nearer).
    pub depth: Texture,
}

/// The unit direction at the point `uv` of the hemi-octahedral square.
///
/// ```
/// use sylva_export::lod::{hemi_octahedral_direction, hemi_octahedral_uv};
/// use glam::{Vec2, Vec3};
/// assert!(hemi_octahedral_direction(Vec2::splat(0.5)).abs_diff_eq(Vec3::Y, 1e-6));
/// let d = Vec3::new(0.3, 0.5, -0.8).normalize();
/// assert!(hemi_octahedral_direction(hemi_octahedral_uv(d)).abs_diff_eq(d, 1e-5));
/// ```
pub fn hemi_octahedral_direction(uv: Vec2) -> Vec3 {
    let (a, b) = (2.0 * uv.x - 1.0, 2.0 * uv.y - 1.0);
    let (p, q) = (0.5 * (a + b), 0.5 * (a - b));
    let y = 1.0 - p.abs() - q.abs();
    Vec3::new(p, y.max(0.0), q).normalize_or(Vec3::Y)
}

/// The point of the hemi-octahedral square for the direction `d` (below the horizon, its
/// mirror above).
pub fn hemi_octahedral_uv(d: Vec3) -> Vec2 {
    let d = Vec3::new(d.x, d.y.abs(), d.z);
    let s = (d.x.abs() + d.y + d.z.abs()).max(1e-12);
    let (p, q) = (d.x / s, d.z / s);
    Vec2::new(0.5 * (p + q) + 0.5, 0.5 * (p - q) + 0.5)
}

impl Impostor {
    /// The direction view `(i, j)` of a `grid`-wide lattice looks from.
    pub fn view_direction(grid: u32, i: u32, j: u32) -> Vec3 {
        let last = grid.max(2) as f32 - 1.0;
        hemi_octahedral_direction(Vec2::new(i as f32 / last, j as f32 / last))
    }

    /// `mesh` drawn from every view of `options`' grid with `look`.
    ///
    /// ```
    /// use sylva_export::lod::{Impostor, ImpostorOptions, TreeLook};
    /// let species = sylva_forest::Species::from_preset("sylva-hazel", 3)?;
    /// let mesh = species.mesh(3, 1)?;
    /// let impostor = Impostor::render(&mesh, &TreeLook::of(&species), &ImpostorOptions::default().with_grid(4).with_view_size(32));
    /// assert_eq!((impostor.colour.width, impostor.colour.height), (128, 128));
    /// // The view from straight above (the middle of the lattice) is not empty.
    /// assert!(impostor.colour.rgba.chunks_exact(4).any(|p| p[3] > 0));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn render(mesh: &Mesh, look: &TreeLook, options: &ImpostorOptions) -> Impostor {
        let (grid, size) = layout(options.grid, options.view_size);
        let (centre, radius) = Impostor::frame(mesh);
        let views: Vec<(u32, u32)> = (0..grid)
            .flat_map(|j| (0..grid).map(move |i| (i, j)))
            .collect();
        let pictures: Vec<Picture> = views
            .par_iter()
            .map(|&(i, j)| {
                let view = OrthoView {
                    centre,
                    toward: Impostor::view_direction(grid, i, j),
                    half: radius,
                    size,
                };
                draw(mesh, look, &view)
            })
            .collect();
        let side = grid * size;
        let blank = || Texture {
            width: side,
            height: side,
            rgba: vec![0; (side * side * 4) as usize],
        };
        let (mut colour, mut normal, mut depth) = (blank(), blank(), blank());
        for (&(i, j), picture) in views.iter().zip(&pictures) {
            let filled = dilate(picture, 4);
            for y in 0..size {
                for x in 0..size {
                    let k = (y * size + x) as usize;
                    let at = ((((j * size + y) * side) + i * size + x) * 4) as usize;
                    let c = filled[k];
                    let cover = (picture.coverage[k] * 255.0).round() as u8;
                    colour.rgba[at..at + 4].copy_from_slice(&[
                        linear_to_srgb(c[0]),
                        linear_to_srgb(c[1]),
                        linear_to_srgb(c[2]),
                        cover,
                    ]);
                    let n = picture.normal[k];
                    let byte = |v: f32| ((v * 0.5 + 0.5).clamp(0.0, 1.0) * 255.0).round() as u8;
                    let leaf = (picture.leaf[k] * 255.0).round() as u8;
                    normal.rgba[at..at + 4].copy_from_slice(&[
                        byte(n[0]),
                        byte(n[1]),
                        byte(n[2]),
                        leaf,
                    ]);
                    let d = byte(picture.depth[k]);
                    depth.rgba[at..at + 4].copy_from_slice(&[d, d, d, 255]);
                }
            }
        }
        Impostor {
            grid,
            view_size: size,
            centre: centre.to_array(),
            radius,
            colour,
            normal,
            depth,
        }
    }

    /// The size of one texel in the tree's units: how far the impostor may be off at most,
    /// before blending between views.
    pub fn texel(&self) -> f32 {
        2.0 * self.radius / self.view_size as f32
    }
}

/// The grid and view size an impostor is drawn with for the ones asked: each within its
/// range, the atlas within [`MAX_ATLAS_SIDE`].
pub(crate) fn layout(grid: u32, view_size: u32) -> (u32, u32) {
    let grid = grid.clamp(2, 32);
    (grid, view_size.clamp(8, 1024).min(MAX_ATLAS_SIDE / grid))
}

impl Impostor {
    /// The sphere every view of `mesh`'s impostor frames: about the middle of its bounds,
    /// holding every vertex.
    pub fn frame(mesh: &Mesh) -> (Vec3, f32) {
        bounding_sphere(mesh)
    }
}

fn bounding_sphere(mesh: &Mesh) -> (Vec3, f32) {
    let Some((lo, hi)) = mesh.bounds() else {
        return (Vec3::ZERO, 1.0);
    };
    let centre = (lo + hi) * 0.5;
    let radius = mesh
        .vertices
        .iter()
        .map(|v| Vec3::from(v.position).distance(centre))
        .fold(0.0f32, f32::max);
    (centre, radius.max(1e-3))
}

/// The picture's colours with uncovered pixels given the mean of their covered neighbours,
/// `steps` rings out.
fn dilate(picture: &Picture, steps: u32) -> Vec<[f32; 3]> {
    let n = picture.size as usize;
    let mut colour = picture.colour.clone();
    let mut known: Vec<bool> = picture.coverage.iter().map(|&c| c > 0.0).collect();
    for _ in 0..steps {
        let (mut next, mut next_known) = (colour.clone(), known.clone());
        for y in 0..n {
            for x in 0..n {
                if known[y * n + x] {
                    continue;
                }
                let (mut sum, mut count) = (Vec3::ZERO, 0);
                for (dx, dy) in [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)] {
                    let (nx, ny) = (x as i64 + dx, y as i64 + dy);
                    if nx >= 0 && ny >= 0 && (nx as usize) < n && (ny as usize) < n {
                        let k = ny as usize * n + nx as usize;
                        if known[k] {
                            sum += Vec3::from(colour[k]);
                            count += 1;
                        }
                    }
                }
                if count > 0 {
                    next[y * n + x] = (sum / count as f32).to_array();
                    next_known[y * n + x] = true;
                }
            }
        }
        colour = next;
        known = next_known;
    }
    colour
}
