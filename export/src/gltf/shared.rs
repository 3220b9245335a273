//! Geometry shared by many GLB files: every variant's cache buffers and the textures, in one
//! binary file that tiles reference as an external glTF buffer, so that a world of tiles
//! holds its instance geometry once instead of once per tile.

use std::collections::HashMap;
use std::path::Path;
use std::sync::{Arc, Mutex, OnceLock};

use sylva_base::file::{AtomicFile, FileError};
use sylva_forest::{BarkPattern, ForestBuilder, LeafShape, Species};
use sylva_turtle::Vertex;

use super::builder::padding;
use super::extras::VertexLayout;
use super::indices::IndexWidth;
use crate::error::ExportError;
use crate::texture::Texture;

/// How the shared file lays out tree vertices: tiles are instanced, and their importers
/// (CesiumJS, three.js's tiles renderer) read quantized normals.
pub(super) const SHARED_LAYOUT: VertexLayout = VertexLayout::Quantized;

/// Where one variant's buffers sit in the shared file (byte offsets).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct VariantSpans {
    pub(super) vertices: usize,
    pub(super) extras: usize,
    pub(super) bark: usize,
    pub(super) leaves: usize,
}

/// The shared file's layout: a pure function of the builder (its species and caches).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct SharedLayout {
    pub(super) variants: Vec<VariantSpans>,
    /// The textures of all species.
    pub(super) textures: TextureSet,
    /// Images (leaf shapes, then bark colours, then bark normal maps): offset and length.
    pub(super) images: Vec<(usize, usize)>,
    pub(super) len: usize,
}

/// Bytes of the four sections a tree mesh is written in, in `layout`: its vertices, their
/// extras (tangents and leaf shades among them), its bark indices and its leaf indices (of
/// the width its vertex count allows).
pub(super) fn section_lengths(
    layout: VertexLayout,
    vertices: &[Vertex],
    bark: &[u32],
    leaves: &[u32],
) -> [usize; 4] {
    let width = IndexWidth::for_vertices(vertices.len()).bytes();
    [
        layout.vertex_bytes() * vertices.len(),
        layout.extras_bytes() * vertices.len(),
        width * bark.len(),
        width * leaves.len(),
    ]
}

/// Puts a tree mesh's four sections (see [`section_lengths`]) in `layout` with `put`,
/// which pads each.
pub(super) fn put_tree_sections<E>(
    layout: VertexLayout,
    vertices: &[Vertex],
    (bark, leaves): (&[u32], &[u32]),
    mut put: impl FnMut(&[u8]) -> Result<(), E>,
) -> Result<(), E> {
    let width = IndexWidth::for_vertices(vertices.len());
    put(&layout.vertices(vertices))?;
    put(&layout.extras(vertices, bark, leaves))?;
    put(&width.encode(bark))?;
    put(&width.encode(leaves))
}

impl SharedLayout {
    pub(super) fn of(builder: &ForestBuilder) -> SharedLayout {
        let textures = TextureSet::of(&builder.config().species);
        let mut at = 0usize;
        let mut take = |len: usize| {
            let start = at;
            at += len + padding(len);
            start
        };
        let variants = builder
            .variants()
            .iter()
            .map(|v| {
                let c = &v.cache;
                let [vertices, extras, bark, leaves] =
                    section_lengths(SHARED_LAYOUT, &c.vertices, &c.bark, &c.leaves);
                VariantSpans {
                    vertices: take(vertices),
                    extras: take(extras),
                    bark: take(bark),
                    leaves: take(leaves),
                }
            })
            .collect();
        let images = textures
            .images()
            .iter()
            .map(|png| (take(png.len()), png.len()))
            .collect();
        SharedLayout {
            variants,
            textures,
            images,
            len: at,
        }
    }
}

/// Which texture is which: one per leaf shape, then bark colour and normal map per pattern,
/// each in order of first use; images in that order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct TextureSet {
    pub(super) shapes: Vec<LeafShape>,
    pub(super) patterns: Vec<BarkPattern>,
}

impl TextureSet {
    /// The leaf shapes and bark patterns of `species`, in order of first use.
    pub(super) fn of<'a>(species: impl IntoIterator<Item = &'a Species>) -> TextureSet {
        let mut set = TextureSet {
            shapes: Vec::new(),
            patterns: Vec::new(),
        };
        for s in species {
            if !set.shapes.contains(&s.leaf_shape) {
                set.shapes.push(s.leaf_shape);
            }
            if !set.patterns.contains(&s.bark_pattern) {
                set.patterns.push(s.bark_pattern);
            }
        }
        set
    }

    /// The first bark texture: those before it are leaf cards (edges clamped), those from it
    /// on tile.
    pub(super) fn first_bark(&self) -> usize {
        self.shapes.len()
    }

    /// The leaf texture of `species` and its bark's colour and normal textures.
    pub(super) fn of_species(
        &self,
        species: &Species,
    ) -> (Option<usize>, Option<usize>, Option<usize>) {
        let leaf = self.shapes.iter().position(|&s| s == species.leaf_shape);
        let pattern = self
            .patterns
            .iter()
            .position(|&p| p == species.bark_pattern);
        (
            leaf,
            pattern.map(|k| self.first_bark() + k),
            pattern.map(|k| self.first_bark() + self.patterns.len() + k),
        )
    }

    /// The images, as PNG.
    pub(super) fn images(&self) -> Arc<Vec<Vec<u8>>> {
        images(&self.shapes, &self.patterns)
    }
}

/// The PNG images of `shapes` and `patterns`: leaves, bark colours, bark normal maps.
/// Encoded once per set and kept: every tile of a world lays out the same images, and
/// encoding them again for each tile cost more than placing a small tile's trees.
fn images(shapes: &[LeafShape], patterns: &[BarkPattern]) -> Arc<Vec<Vec<u8>>> {
    type Key = (Vec<LeafShape>, Vec<BarkPattern>);
    type Encoded = Mutex<HashMap<Key, Arc<Vec<Vec<u8>>>>>;
    static ENCODED: OnceLock<Encoded> = OnceLock::new();
    let key = (shapes.to_vec(), patterns.to_vec());
    let cache = ENCODED.get_or_init(Default::default);
    if let Some(found) = cache.lock().ok().and_then(|c| c.get(&key).cloned()) {
        return found;
    }
    let mut out: Vec<Vec<u8>> = shapes.iter().map(|&s| Texture::leaf(s).png()).collect();
    out.extend(patterns.iter().map(|&p| Texture::bark(p).png()));
    out.extend(patterns.iter().map(|&p| Texture::bark_normal(p).png()));
    let out = Arc::new(out);
    if let Ok(mut c) = cache.lock() {
        c.insert(key, out.clone());
    }
    out
}

/// Writes the geometry every tile of `builder`'s world shares (see
/// [`GltfOptions::shared_geometry`](super::GltfOptions::shared_geometry)) to `path`, under a
/// temporary name renamed when complete. Returns its size in bytes.
///
/// ```
/// use sylva_export::write_shared_geometry;
/// use sylva_forest::{ForestBuilder, ForestConfig, Species};
/// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
///     .with_budget(1 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let path = std::env::temp_dir().join("sylva-doctest-shared.bin");
/// let bytes = write_shared_geometry(&builder, &path)?;
/// assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, bytes);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), sylva_export::ExportError>(())
/// ```
pub fn write_shared_geometry(builder: &ForestBuilder, path: &Path) -> Result<usize, ExportError> {
    let layout = SharedLayout::of(builder);
    let mut w = AtomicFile::create(path)?;
    let mut put = |bytes: &[u8]| -> Result<(), FileError> {
        w.put(bytes)?;
        w.put(&[0; 3][..padding(bytes.len())])
    };
    for v in builder.variants() {
        let c = &v.cache;
        put_tree_sections(SHARED_LAYOUT, &c.vertices, (&c.bark, &c.leaves), &mut put)?;
    }
    for png in layout.textures.images().iter() {
        put(png)?;
    }
    w.commit()?;
    Ok(layout.len)
}
