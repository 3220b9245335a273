//! A small software rasteriser: a tree mesh seen along one direction in an orthographic
//! view, with its bark and leaf textures, alpha-tested cards and a depth buffer. It draws the
//! views of impostor atlases and measures silhouettes, with no GPU, so tests and CI make
//! them as a user's machine does.

use glam::{Vec2, Vec3};
use sylva_turtle::Mesh;

use crate::texture::{Texture, srgb_to_linear};

/// How a species' tree looks: colours (linear RGB) and textures.
#[derive(Debug, Clone)]
pub struct TreeLook {
    /// Bark colour, multiplied by the bark texture.
    pub bark: [f32; 3],
    /// Leaf colour, multiplied by the leaf texture.
    pub leaf: [f32; 3],
    /// The bark texture (tiled).
    pub bark_texture: Texture,
    /// The leaf card texture; its alpha cuts the cards.
    pub leaf_texture: Texture,
}

impl TreeLook {
    /// The look of `species`: its colours with its leaf and bark textures.
    pub fn of(species: &sylva_forest::Species) -> TreeLook {
        TreeLook {
            bark: species.bark,
            leaf: species.leaf,
            bark_texture: Texture::bark(species.bark_pattern),
            leaf_texture: Texture::leaf(species.leaf_shape),
        }
    }

    /// Untextured, for silhouettes: the colours alone, every card whole.
    pub fn plain(bark: [f32; 3], leaf: [f32; 3]) -> TreeLook {
        let white = Texture {
            width: 1,
            height: 1,
            rgba: vec![255; 4],
        };
        TreeLook {
            bark,
            leaf,
            bark_texture: white.clone(),
            leaf_texture: white,
        }
    }
}

/// An orthographic view of a tree: the square of side `2 half` about `centre`, seen from
/// `toward` (a unit vector from the tree to the viewer), `size` pixels across.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrthoView {
    /// The middle of the picture, in the mesh's space.
    pub centre: Vec3,
    /// From the tree towards the viewer (unit).
    pub toward: Vec3,
    /// Half the picture's side, in the mesh's units.
    pub half: f32,
    /// Pixels across (and down).
    pub size: u32,
}

impl OrthoView {
    /// The picture's right and up directions: right is horizontal (perpendicular to +Y and
    /// `toward`), up completes the frame; looking straight down, right is +X and up is -Z.
    pub fn axes(toward: Vec3) -> (Vec3, Vec3) {
        let right = Vec3::Y.cross(toward);
        let right = if right.length_squared() > 1e-8 {
            right.normalize()
        } else {
            Vec3::X
        };
        (right, toward.cross(right).normalize())
    }
}

/// What a view saw, per pixel (rows from the top).
#[derive(Debug, Clone, PartialEq)]
pub struct Picture {
    /// Pixels across and down.
    pub size: u32,
    /// Linear colour of what covers the pixel (black where nothing does).
    pub colour: Vec<[f32; 3]>,
    /// Share of the pixel covered, 0 to 1.
    pub coverage: Vec<f32>,
    /// The surface's normal in the mesh's space, facing the viewer (zero where uncovered).
    pub normal: Vec<[f32; 3]>,
    /// Nearness of the nearest surface: its distance towards the viewer from the view's
    /// centre over `half`, in `[-1, 1]` (−1 where uncovered).
    pub depth: Vec<f32>,
    /// Share of the covered part that is leaves rather than bark.
    pub leaf: Vec<f32>,
}

impl Picture {
    /// Pixels at least half covered.
    pub fn covered(&self) -> usize {
        self.coverage.iter().filter(|&&c| c >= 0.5).count()
    }

    /// Rows of pictures (all of one size) laid out as one sRGB image over `background`
    /// (linear RGB), each blended over it by its coverage; short rows end in background.
    ///
    /// ```
    /// use sylva_export::lod::Picture;
    ///
    /// let red = Picture {
    ///     size: 2,
    ///     colour: vec![[1.0, 0.0, 0.0]; 4],
    ///     coverage: vec![1.0; 4],
    ///     normal: vec![[0.0; 3]; 4],
    ///     depth: vec![0.0; 4],
    ///     leaf: vec![0.0; 4],
    /// };
    /// let sheet = Picture::sheet(&[vec![red.clone(), red], vec![]], [0.0, 0.0, 1.0]);
    /// assert_eq!((sheet.width, sheet.height), (4, 4));
    /// assert_eq!(&sheet.rgba[..4], &[255, 0, 0, 255]);
    /// assert_eq!(&sheet.rgba[sheet.rgba.len() - 4..], &[0, 0, 255, 255]);
    /// ```
    pub fn sheet(rows: &[Vec<Picture>], background: [f32; 3]) -> Texture {
        let size = rows.iter().flatten().map(|p| p.size).max().unwrap_or(0);
        let columns = rows.iter().map(Vec::len).max().unwrap_or(0) as u32;
        let (w, h) = (columns * size, rows.len() as u32 * size);
        let mut rgba = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h {
            for x in 0..w {
                let (row, column) = ((y / size) as usize, (x / size) as usize);
                let (colour, cover) =
                    rows[row]
                        .get(column)
                        .filter(|p| p.size == size)
                        .map_or(([0.0; 3], 0.0), |p| {
                            let k = ((y % size) * size + x % size) as usize;
                            (p.colour[k], p.coverage[k])
                        });
                let c = [0, 1, 2].map(|i| {
                    crate::texture::linear_to_srgb(
                        colour[i] * cover + background[i] * (1.0 - cover),
                    )
                });
                rgba.extend_from_slice(&[c[0], c[1], c[2], 255]);
            }
        }
        Texture {
            width: w,
            height: h,
            rgba,
        }
    }
}

/// One sample of the supersampled buffer.
#[derive(Clone, Copy)]
struct Sample {
    depth: f32,
    colour: Vec3,
    normal: Vec3,
    leaf: bool,
}

/// Samples per pixel along each axis.
const SUPERSAMPLE: u32 = 2;

/// `mesh` seen in `view`, with `look`'s colours and textures, cards cut where their texture's
/// alpha is below one half; each pixel the average of 2 x 2 samples.
///
/// ```
/// use sylva_export::lod::{OrthoView, TreeLook, draw};
/// use glam::Vec3;
/// let mut species = sylva_forest::Species::from_preset("sylva-hazel", 3)?;
/// species.turtle.symbols.set("L", sylva_turtle::Command::Leaf);
/// let mesh = species.mesh(3, 1)?;
/// let (lo, hi) = mesh.bounds().unwrap();
/// let view = OrthoView { centre: (lo + hi) * 0.5, toward: Vec3::Z, half: (hi - lo).max_element(), size: 64 };
/// let picture = draw(&mesh, &TreeLook::of(&species), &view);
/// assert!(picture.covered() > 100);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn draw(mesh: &Mesh, look: &TreeLook, view: &OrthoView) -> Picture {
    let n = (view.size * SUPERSAMPLE) as usize;
    let mut samples: Vec<Option<Sample>> = vec![None; n * n];
    let (right, up) = OrthoView::axes(view.toward);
    let scale = n as f32 / (2.0 * view.half.max(1e-6));
    let project = |p: Vec3| {
        let d = p - view.centre;
        Vec3::new(
            d.dot(right) * scale + n as f32 * 0.5,
            n as f32 * 0.5 - d.dot(up) * scale,
            d.dot(view.toward) / view.half.max(1e-6),
        )
    };
    let linear = |c: [f32; 3]| Vec3::from(c);
    let (bark_colour, leaf_colour) = (linear(look.bark), linear(look.leaf));
    let texel = |t: &Texture, uv: Vec2, tile: bool| -> [u8; 4] {
        let (w, h) = (t.width.max(1), t.height.max(1));
        let (u, v) = if tile {
            (uv.x.rem_euclid(1.0), uv.y.rem_euclid(1.0))
        } else {
            (uv.x.clamp(0.0, 1.0), uv.y.clamp(0.0, 1.0))
        };
        let x = ((u * w as f32) as u32).min(w - 1);
        let y = ((v * h as f32) as u32).min(h - 1);
        let i = ((y * w + x) * 4) as usize;
        t.rgba
            .get(i..i + 4)
            .and_then(|s| s.try_into().ok())
            .unwrap_or([255; 4])
    };
    // sRGB bytes to linear, looked up rather than worked out per texel.
    let linear: [f32; 256] = std::array::from_fn(|i| srgb_to_linear(i as u8));
    let mut triangle = |tri: &[u32], leaf: bool| {
        let vertex = |k: usize| mesh.vertices.get(tri[k] as usize);
        let (Some(a), Some(b), Some(c)) = (vertex(0), vertex(1), vertex(2)) else {
            return;
        };
        let corners = [a, b, c];
        let p = corners.map(|v| project(Vec3::from(v.position)));
        let area = (p[1].x - p[0].x) * (p[2].y - p[0].y) - (p[2].x - p[0].x) * (p[1].y - p[0].y);
        if area.abs() < 1e-12 {
            return;
        }
        let lo = p[0].min(p[1]).min(p[2]);
        let hi = p[0].max(p[1]).max(p[2]);
        let (x0, x1) = (
            lo.x.floor().max(0.0) as usize,
            (hi.x.ceil().max(0.0) as usize).min(n),
        );
        let (y0, y1) = (
            lo.y.floor().max(0.0) as usize,
            (hi.y.ceil().max(0.0) as usize).min(n),
        );
        if x0 >= x1 || y0 >= y1 {
            return;
        }
        // Each barycentric weight is linear in the pixel: w = ex * x + ey * y + e0, the edge
        // function of the opposite edge over the area.
        let edge = |a: Vec3, b: Vec3| {
            let (ex, ey) = (-(b.y - a.y) / area, (b.x - a.x) / area);
            (ex, ey, -(ex * a.x + ey * a.y))
        };
        let edges = [edge(p[1], p[2]), edge(p[2], p[0]), edge(p[0], p[1])];
        let (texture, tile) = if leaf {
            (&look.leaf_texture, false)
        } else {
            (&look.bark_texture, true)
        };
        let base = if leaf { leaf_colour } else { bark_colour };
        let uvs = corners.map(|v| Vec2::from(v.uv));
        let normals = corners.map(|v| Vec3::from(v.normal));
        for y in y0..y1 {
            let py = y as f32 + 0.5;
            for x in x0..x1 {
                let px = x as f32 + 0.5;
                let w = edges.map(|(ex, ey, e0)| ex * px + ey * py + e0);
                if w[0] < 0.0 || w[1] < 0.0 || w[2] < 0.0 {
                    continue;
                }
                let depth = w[0] * p[0].z + w[1] * p[1].z + w[2] * p[2].z;
                let slot = &mut samples[y * n + x];
                if slot.is_some_and(|s| s.depth >= depth) {
                    continue;
                }
                let uv = uvs[0] * w[0] + uvs[1] * w[1] + uvs[2] * w[2];
                let t = texel(texture, uv, tile);
                if leaf && t[3] < 128 {
                    continue;
                }
                let colour = base
                    * Vec3::new(
                        linear[t[0] as usize],
                        linear[t[1] as usize],
                        linear[t[2] as usize],
                    );
                let normal = (normals[0] * w[0] + normals[1] * w[1] + normals[2] * w[2])
                    .normalize_or(view.toward);
                // Cards are seen from both sides: their normal faces the viewer.
                let normal = if normal.dot(view.toward) < 0.0 && leaf {
                    -normal
                } else {
                    normal
                };
                *slot = Some(Sample {
                    depth,
                    colour,
                    normal,
                    leaf,
                });
            }
        }
    };
    for tri in mesh.bark.chunks_exact(3) {
        triangle(tri, false);
    }
    for tri in mesh.leaves.chunks_exact(3) {
        triangle(tri, true);
    }
    resolve(&samples, view.size)
}

/// Each pixel from its 2 x 2 samples.
fn resolve(samples: &[Option<Sample>], size: u32) -> Picture {
    let (m, n) = (size as usize, (size * SUPERSAMPLE) as usize);
    let count = m * m;
    let mut picture = Picture {
        size,
        colour: vec![[0.0; 3]; count],
        coverage: vec![0.0; count],
        normal: vec![[0.0; 3]; count],
        depth: vec![-1.0; count],
        leaf: vec![0.0; count],
    };
    let s = SUPERSAMPLE as usize;
    for y in 0..m {
        for x in 0..m {
            let (mut covered, mut leaves) = (0usize, 0usize);
            let (mut colour, mut normal, mut depth) = (Vec3::ZERO, Vec3::ZERO, -1.0f32);
            for dy in 0..s {
                for dx in 0..s {
                    if let Some(sample) = samples[(y * s + dy) * n + x * s + dx] {
                        covered += 1;
                        leaves += usize::from(sample.leaf);
                        colour += sample.colour;
                        normal += sample.normal;
                        depth = depth.max(sample.depth);
                    }
                }
            }
            if covered == 0 {
                continue;
            }
            let i = y * m + x;
            picture.colour[i] = (colour / covered as f32).to_array();
            picture.coverage[i] = covered as f32 / (s * s) as f32;
            picture.normal[i] = normal.normalize_or_zero().to_array();
            picture.depth[i] = depth.clamp(-1.0, 1.0);
            picture.leaf[i] = leaves as f32 / covered as f32;
        }
    }
    picture
}
