//! glTF 2.0 binary (.glb) export, streamed: the terrain, one mesh per used cached instance,
//! and each instance's placements through EXT_mesh_gpu_instancing.
//!
//! A forest of a million trees has millions of placements, more than should sit in memory at
//! once. The writer streams the forest twice or more: a first pass counts the placements of
//! every instance, which fixes the whole layout (JSON and binary offsets); then each pass
//! gathers the placements of a range of instances (at most [`CHUNK_BYTES`] of them) and
//! writes them where the layout says. Memory holds the caches, the JSON text and one chunk.
//! The file is written beside its destination under a temporary name and renamed when
//! complete, so an error (a bad path, a full disk) never leaves a half-written file.

use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufWriter, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use sylva_terrain::{HeightField, TerrainMesh};
use sylva_turtle::Vertex;

use crate::density::Rect;
use crate::error::ForestError;
use crate::forest::{ForestBuilder, Variant};
use crate::stream::{PlacementBlock, StreamStats};
use crate::texture::{BarkPattern, LeafShape, Texture};
use crate::variety::tree_tint;

/// Export settings.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GltfOptions {
    /// Terrain tint, linear RGB, multiplied with the ground colours by slope and altitude
    /// ([`sylva_terrain::ground`]) that the terrain's vertices carry.
    pub terrain_colour: [f32; 3],
    /// Roughness of every material (all are dielectric: metallic 0).
    pub roughness: f32,
    /// Most bytes of placements gathered in memory per writing pass (at least one instance's
    /// worth is always gathered). Smaller means less memory and more passes; the file is the
    /// same. Default [`CHUNK_BYTES`].
    pub chunk_bytes: usize,
}

impl Default for GltfOptions {
    fn default() -> Self {
        GltfOptions {
            terrain_colour: [1.0, 1.0, 1.0],
            roughness: 0.9,
            chunk_bytes: CHUNK_BYTES,
        }
    }
}

/// What was written.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct GlbStats {
    /// File size in bytes.
    pub bytes: usize,
    /// Trees in the forest.
    pub trees: usize,
    /// Of which seedlings.
    pub seedlings: usize,
    /// Instance meshes written (one node each).
    pub instance_nodes: usize,
    /// Instance placements written.
    pub placements: usize,
    /// Placements of instances with no geometry (a branch introduced at the last generation
    /// of a species without leaf symbols), left out of the file.
    pub empty_placements: usize,
    /// Times the forest was streamed: one count, then one per chunk of placements.
    pub passes: usize,
}

/// Default of [`GltfOptions::chunk_bytes`]: 64 MiB, 1.6 million placements of 40 bytes.
pub const CHUNK_BYTES: usize = 64 << 20;

const ARRAY_BUFFER: u32 = 34962;
const ELEMENT_ARRAY_BUFFER: u32 = 34963;
const FLOAT: u32 = 5126;
const UNSIGNED_INT: u32 = 5125;
/// Bytes of one placement in the file: translation, rotation, scale (as three floats) and the
/// tree's tint.
const PLACEMENT_BYTES: usize = 12 + 16 + 12 + 12;

/// One instance that is drawn: a node with its own instancing accessors.
#[derive(Debug, Clone, Copy)]
struct Node {
    variant: usize,
    instance: usize,
    /// First placement of this node in the T/R/S sections, counted in placements.
    first: usize,
    count: usize,
}

/// Writes the forest of `region` on `terrain`, and optionally a terrain mesh, as a binary glTF
/// at `path`. The file declares EXT_mesh_gpu_instancing; every node of an instance mesh
/// carries TRANSLATION, ROTATION and SCALE accessors of equal count, float components and unit
/// quaternions. The output is a pure function of its inputs, at any thread count.
///
/// ```
/// use sylva_forest::{ForestBuilder, ForestConfig, GltfOptions, Rect, Species, write_glb};
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let mut leafy = Species::from_preset("kenwood-leafy", 4)?;
/// leafy.turtle.step = 0.5;
/// let mut config = ForestConfig::new(vec![leafy]);
/// config.budget = 4 << 20;
/// let builder = ForestBuilder::new(config)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(200.0) };
/// let path = std::env::temp_dir().join("sylva-doctest-forest.glb");
/// let region = Rect::new(Vec2::ZERO, Vec2::splat(200.0));
/// let stats = write_glb(&builder, &ground, region, None, &GltfOptions::default(), &path)?;
/// assert_eq!(std::fs::metadata(&path).unwrap().len() as usize, stats.bytes);
/// assert!(stats.placements >= stats.trees);
/// # std::fs::remove_file(&path).ok();
/// # Ok::<(), sylva_forest::ForestError>(())
/// ```
pub fn write_glb(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    terrain_mesh: Option<&TerrainMesh>,
    options: &GltfOptions,
    path: &Path,
) -> Result<GlbStats, ForestError> {
    let variants = builder.variants();
    let terrain_mesh = terrain_mesh.filter(|t| !t.indices.is_empty());
    if let Some(t) = terrain_mesh {
        check_mesh(
            t.vertices.iter().map(|v| (&v.position, &v.normal)),
            &t.indices,
        )?;
    }
    for v in variants {
        check_mesh(
            v.cache
                .vertices
                .iter()
                .map(|v: &Vertex| (&v.position, &v.normal)),
            v.cache.bark.iter().chain(&v.cache.leaves),
        )?;
        let (bark, leaves) = (v.cache.bark.len(), v.cache.leaves.len());
        if v.cache
            .instances
            .iter()
            .any(|i| i.bark.end() as usize > bark || i.leaves.end() as usize > leaves)
        {
            return Err(ForestError::InvalidExport(
                "an instance spans past its cache's indices".into(),
            ));
        }
    }

    // Pass 1: count the placements of every instance, checking each transform.
    let mut counts: Vec<Vec<u32>> = variants
        .iter()
        .map(|v| vec![0; v.cache.instances.len()])
        .collect();
    let counted = builder.stream(terrain, region, &mut |block: &PlacementBlock| {
        for p in &block.placements {
            let t = &p.transform;
            if !(t.is_finite() && t.scale > 0.0) || (t.rotation.length() - 1.0).abs() > 1e-3 {
                return Err(ForestError::InvalidExport(format!(
                    "placement {t:?} is not a valid TRS transform"
                )));
            }
            let slot = counts
                .get_mut(p.variant as usize)
                .and_then(|c| c.get_mut(p.instance as usize))
                .ok_or_else(|| {
                    ForestError::InvalidExport("a placement of an unknown instance".into())
                })?;
            *slot = slot.saturating_add(1);
        }
        Ok(())
    })?;

    // The layout: which instances become nodes, and where every byte goes.
    let mut nodes = Vec::new();
    let mut node_of: Vec<Vec<u32>> = Vec::with_capacity(variants.len());
    let mut placements = 0usize;
    let mut empty_placements = 0usize;
    for (v, variant) in variants.iter().enumerate() {
        let mut map = vec![u32::MAX; variant.cache.instances.len()];
        for (i, inst) in variant.cache.instances.iter().enumerate() {
            let count = counts[v][i] as usize;
            if count == 0 {
                continue;
            }
            if inst.bark.is_empty() && inst.leaves.is_empty() {
                empty_placements += count;
                continue;
            }
            map[i] = nodes.len() as u32;
            nodes.push(Node {
                variant: v,
                instance: i,
                first: placements,
                count,
            });
            placements += count;
        }
        node_of.push(map);
    }
    drop(counts);
    let document = Document::lay_out(builder, terrain_mesh, options, &nodes, placements)?;

    let temporary = temporary_path(path)?;
    let written = write_file(&temporary, &document, |file| {
        write_geometry(file, variants, terrain_mesh, &document)?;
        write_placements(
            file,
            builder,
            terrain,
            region,
            &nodes,
            &node_of,
            document.bin_start() + document.placement_base,
            placements,
            options.chunk_bytes,
        )
    });
    let passes = match written {
        Ok(passes) => passes,
        Err(e) => {
            // Nothing half-written stays behind.
            let _ = std::fs::remove_file(&temporary);
            return Err(e);
        }
    };
    std::fs::rename(&temporary, path).map_err(|e| {
        let _ = std::fs::remove_file(&temporary);
        io_error(path, &e)
    })?;
    let StreamStats {
        trees, seedlings, ..
    } = counted;
    Ok(GlbStats {
        bytes: document.total,
        trees,
        seedlings,
        instance_nodes: nodes.len(),
        placements,
        empty_placements,
        passes: 1 + passes,
    })
}

fn io_error(path: &Path, e: &std::io::Error) -> ForestError {
    ForestError::Io {
        path: path.display().to_string(),
        message: e.to_string(),
    }
}

/// A hidden name beside `path` for the file while it is written.
fn temporary_path(path: &Path) -> Result<PathBuf, ForestError> {
    let name = path.file_name().ok_or_else(|| ForestError::Io {
        path: path.display().to_string(),
        message: "not a file name".into(),
    })?;
    let mut hidden = std::ffi::OsString::from(".");
    hidden.push(name);
    hidden.push(format!(".{}.partial", std::process::id()));
    Ok(path.with_file_name(hidden))
}

/// Creates `path`, writes the GLB header, the JSON chunk and the BIN chunk header, then lets
/// `body` write the binary content; returns what `body` returns.
fn write_file(
    path: &Path,
    document: &Document,
    body: impl FnOnce(&mut BufWriter<File>) -> Result<usize, ForestError>,
) -> Result<usize, ForestError> {
    let io = |e: std::io::Error| io_error(path, &e);
    let file = File::create(path).map_err(io)?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let total = u32::try_from(document.total).map_err(|_| {
        ForestError::InvalidExport(format!(
            "{} bytes is beyond the 4 GiB a GLB can hold",
            document.total
        ))
    })?;
    w.write_all(b"glTF").map_err(io)?;
    w.write_all(&2u32.to_le_bytes()).map_err(io)?;
    w.write_all(&total.to_le_bytes()).map_err(io)?;
    w.write_all(&(document.json.len() as u32).to_le_bytes())
        .map_err(io)?;
    w.write_all(b"JSON").map_err(io)?;
    w.write_all(document.json.as_bytes()).map_err(io)?;
    if document.bin_len > 0 {
        w.write_all(&(document.bin_len as u32).to_le_bytes())
            .map_err(io)?;
        w.write_all(b"BIN\0").map_err(io)?;
    }
    let passes = body(&mut w)?;
    w.flush().map_err(io)?;
    let file = w.into_inner().map_err(|e| io(e.into_error()))?;
    let end = file.metadata().map_err(io)?.len();
    if end as usize != document.total {
        return Err(ForestError::InvalidExport(format!(
            "wrote {end} bytes where the layout has {}",
            document.total
        )));
    }
    file.sync_all().map_err(io)?;
    Ok(passes)
}

/// Terrain and cache buffers, in layout order, each padded to 4 bytes.
fn write_geometry(
    w: &mut BufWriter<File>,
    variants: &[Variant],
    terrain: Option<&TerrainMesh>,
    document: &Document,
) -> Result<(), ForestError> {
    let io = |e: std::io::Error| ForestError::Io {
        path: "glb output".into(),
        message: e.to_string(),
    };
    let mut written = 0usize;
    let mut put = |w: &mut BufWriter<File>, bytes: &[u8]| -> Result<(), ForestError> {
        w.write_all(bytes).map_err(io)?;
        written += bytes.len();
        Ok(())
    };
    if let Some(t) = terrain {
        put(w, bytemuck::cast_slice(&t.vertices))?;
        put(w, bytemuck::cast_slice(&t.indices))?;
        put(w, bytemuck::cast_slice(&document.terrain_colours))?;
    }
    for &v in &document.used_variants {
        let cache = &variants[v].cache;
        put(w, bytemuck::cast_slice(&cache.vertices))?;
        put(w, bytemuck::cast_slice(&cache.bark))?;
        put(w, bytemuck::cast_slice(&cache.leaves))?;
    }
    // Every buffer above is a whole number of 4-byte words; images are padded to one.
    for image in &document.images {
        put(w, image)?;
        put(w, &[0; 3][..padding(image.len())])?;
    }
    debug_assert_eq!(written, document.placement_base);
    Ok(())
}

/// Streams the forest once per chunk of nodes, gathering those nodes' placements in memory
/// and writing them to the T, R and S sections, which start at file offset `base`. Returns
/// the number of passes.
#[allow(
    clippy::too_many_arguments,
    reason = "one call site; the pieces are all different"
)]
fn write_placements(
    w: &mut BufWriter<File>,
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    nodes: &[Node],
    node_of: &[Vec<u32>],
    base: usize,
    total: usize,
    chunk_bytes: usize,
) -> Result<usize, ForestError> {
    let io = |e: std::io::Error| ForestError::Io {
        path: "glb output".into(),
        message: e.to_string(),
    };
    let (t_base, r_base, s_base, c_base) = (
        base,
        base + 12 * total,
        base + 28 * total,
        base + 40 * total,
    );
    let mut passes = 0;
    let mut start = 0;
    while start < nodes.len() {
        // The nodes of this pass: as many as fit in a chunk (at least one).
        let mut end = start + 1;
        while end < nodes.len()
            && (nodes[end].first + nodes[end].count - nodes[start].first) * PLACEMENT_BYTES
                <= chunk_bytes
        {
            end += 1;
        }
        let first = nodes[start].first;
        let count = nodes[end - 1].first + nodes[end - 1].count - first;
        let mut t = vec![0f32; 3 * count];
        let mut r = vec![0f32; 4 * count];
        let mut s = vec![0f32; 3 * count];
        let mut c = vec![0f32; 3 * count];
        let mut cursor: Vec<usize> = nodes[start..end].iter().map(|n| n.first - first).collect();
        let range = start as u32..end as u32;
        // Only the variants of this chunk's nodes need their trees expanded.
        let (first_variant, last_variant) = (nodes[start].variant, nodes[end - 1].variant);
        let wanted = |v: u16| (first_variant..=last_variant).contains(&usize::from(v));
        builder.stream_variants(terrain, region, &wanted, &mut |block: &PlacementBlock| {
            for p in &block.placements {
                let node = node_of[p.variant as usize][p.instance as usize];
                if !range.contains(&node) {
                    continue;
                }
                let k = &mut cursor[(node - range.start) as usize];
                let x = &p.transform;
                let q = x.rotation.normalize();
                t[3 * *k..3 * *k + 3].copy_from_slice(&x.translation.to_array());
                r[4 * *k..4 * *k + 4].copy_from_slice(&q.to_array());
                s[3 * *k..3 * *k + 3].copy_from_slice(&[x.scale; 3]);
                let tint = block.trees.get(p.tree as usize).map_or([1.0; 3], tree_tint);
                c[3 * *k..3 * *k + 3].copy_from_slice(&tint);
                *k += 1;
            }
            Ok(())
        })?;
        for (section, data, width) in [
            (t_base, &t, 12),
            (r_base, &r, 16),
            (s_base, &s, 12),
            (c_base, &c, 12),
        ] {
            w.seek(SeekFrom::Start((section + first * width) as u64))
                .map_err(io)?;
            w.write_all(bytemuck::cast_slice(data)).map_err(io)?;
        }
        passes += 1;
        start = end;
    }
    Ok(passes)
}

/// Every vertex finite with a unit normal, every index in range.
fn check_mesh<'a>(
    vertices: impl ExactSizeIterator<Item = (&'a [f32; 3], &'a [f32; 3])>,
    indices: impl IntoIterator<Item = &'a u32>,
) -> Result<(), ForestError> {
    let n = vertices.len() as u32;
    for (p, normal) in vertices {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(ForestError::InvalidExport(
                "a vertex position is not finite".into(),
            ));
        }
        let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        if !(len - 1.0).abs().lt(&1e-3) {
            return Err(ForestError::InvalidExport(format!(
                "normal {normal:?} is not unit length"
            )));
        }
    }
    if indices.into_iter().any(|&i| i >= n) {
        return Err(ForestError::InvalidExport("index out of range".into()));
    }
    Ok(())
}

/// The JSON chunk and the binary layout, decided before any byte is written.
#[derive(Debug)]
struct Document {
    json: String,
    /// Variants with at least one node, in order.
    used_variants: Vec<usize>,
    /// The leaf textures as PNG, in layout order after the cache buffers.
    images: Vec<Vec<u8>>,
    /// The terrain's ground colours, after its indices.
    terrain_colours: Vec<[f32; 3]>,
    /// Offset in the BIN chunk where the placement sections start.
    placement_base: usize,
    bin_len: usize,
    total: usize,
}

/// Collects glTF arrays as JSON text: a forest has too many nodes for a tree of values.
#[derive(Debug, Default)]
struct Arrays {
    views: Vec<String>,
    accessors: Vec<String>,
    meshes: Vec<String>,
    nodes: Vec<String>,
    materials: Vec<String>,
}

impl Arrays {
    fn view(
        &mut self,
        offset: usize,
        length: usize,
        stride: Option<u32>,
        target: Option<u32>,
    ) -> usize {
        let mut v = format!("{{\"buffer\":0,\"byteOffset\":{offset},\"byteLength\":{length}");
        if let Some(s) = stride {
            let _ = write!(v, ",\"byteStride\":{s}");
        }
        if let Some(t) = target {
            let _ = write!(v, ",\"target\":{t}");
        }
        v.push('}');
        self.views.push(v);
        self.views.len() - 1
    }

    fn accessor(
        &mut self,
        view: usize,
        offset: usize,
        component: u32,
        count: usize,
        kind: &str,
        bounds: Option<([f32; 3], [f32; 3])>,
    ) -> usize {
        let mut a = format!(
            "{{\"bufferView\":{view},\"byteOffset\":{offset},\"componentType\":{component},\"count\":{count},\"type\":\"{kind}\""
        );
        if let Some((lo, hi)) = bounds {
            let _ = write!(
                a,
                ",\"min\":[{},{},{}],\"max\":[{},{},{}]",
                lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
            );
        }
        a.push('}');
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    /// A dielectric material; with a texture it is a leaf card: double-sided, the texture's
    /// alpha cut at one half.
    fn material(
        &mut self,
        name: &str,
        colour: [f32; 3],
        roughness: f32,
        texture: Option<usize>,
    ) -> usize {
        let (texture, leaf) = match texture {
            Some(t) => (
                format!(",\"baseColorTexture\":{{\"index\":{t}}}"),
                ",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,\"doubleSided\":true",
            ),
            None => (String::new(), ""),
        };
        self.materials.push(format!(
            "{{\"name\":{},\"pbrMetallicRoughness\":{{\"baseColorFactor\":[{},{},{},1.0]{texture},\"metallicFactor\":0.0,\"roughnessFactor\":{roughness}}}{leaf}}}",
            quoted(name),
            colour[0],
            colour[1],
            colour[2]
        ));
        self.materials.len() - 1
    }

    /// A bark material: the species' colour over the tiling bark texture, when there is one.
    fn bark_material(
        &mut self,
        name: &str,
        colour: [f32; 3],
        roughness: f32,
        texture: Option<usize>,
    ) -> usize {
        let texture = texture.map_or(String::new(), |t| {
            format!(",\"baseColorTexture\":{{\"index\":{t}}}")
        });
        self.materials.push(format!(
            "{{\"name\":{},\"pbrMetallicRoughness\":{{\"baseColorFactor\":[{},{},{},1.0]{texture},\"metallicFactor\":0.0,\"roughnessFactor\":{roughness}}}}}",
            quoted(name),
            colour[0],
            colour[1],
            colour[2]
        ));
        self.materials.len() - 1
    }

    /// Position (with bounds), normal and uv accessors over interleaved 32-byte vertices.
    fn vertex_attributes(
        &mut self,
        view: usize,
        positions: impl Iterator<Item = [f32; 3]>,
    ) -> String {
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        let mut count = 0;
        for p in positions {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
            count += 1;
        }
        let position = self.accessor(view, 0, FLOAT, count, "VEC3", Some((lo, hi)));
        let normal = self.accessor(view, 12, FLOAT, count, "VEC3", None);
        let uv = self.accessor(view, 24, FLOAT, count, "VEC2", None);
        format!("{{\"POSITION\":{position},\"NORMAL\":{normal},\"TEXCOORD_0\":{uv}}}")
    }
}

/// Zero bytes that bring `len` to a whole number of 4-byte words.
fn padding(len: usize) -> usize {
    (4 - len % 4) % 4
}

/// A JSON string literal.
fn quoted(text: &str) -> String {
    serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into())
}

impl Document {
    /// File offset of the BIN chunk's content: after the GLB header, the JSON chunk and the
    /// BIN chunk's own header.
    fn bin_start(&self) -> usize {
        12 + 8 + self.json.len() + 8
    }

    fn lay_out(
        builder: &ForestBuilder,
        terrain: Option<&TerrainMesh>,
        options: &GltfOptions,
        nodes: &[Node],
        placements: usize,
    ) -> Result<Document, ForestError> {
        let variants = builder.variants();
        let species = &builder.config().species;
        let mut a = Arrays::default();
        // Sections of the BIN chunk, laid end to end; every one is a whole number of words.
        let mut offset = 0usize;
        let mut section = |len: usize| {
            let at = offset;
            offset += len;
            (at, offset)
        };
        let mut terrain_colours = Vec::new();
        if let Some(t) = terrain {
            let vbytes = size_of_val(t.vertices.as_slice());
            let view = a.view(section(vbytes).0, vbytes, Some(32), Some(ARRAY_BUFFER));
            let attributes = a.vertex_attributes(view, t.vertices.iter().map(|v| v.position));
            let ibytes = 4 * t.indices.len();
            let iview = a.view(section(ibytes).0, ibytes, None, Some(ELEMENT_ARRAY_BUFFER));
            let indices = a.accessor(iview, 0, UNSIGNED_INT, t.indices.len(), "SCALAR", None);
            terrain_colours = t.ground_colours();
            let cbytes = 12 * terrain_colours.len();
            let cview = a.view(section(cbytes).0, cbytes, None, Some(ARRAY_BUFFER));
            let colours = a.accessor(cview, 0, FLOAT, terrain_colours.len(), "VEC3", None);
            // Ground colours by slope and altitude, as vertex colours.
            let attributes = format!(
                "{},\"COLOR_0\":{colours}}}",
                attributes.trim_end_matches('}')
            );
            let material = a.material("terrain", options.terrain_colour, options.roughness, None);
            a.meshes.push(format!(
                "{{\"name\":\"terrain\",\"primitives\":[{{\"attributes\":{attributes},\"indices\":{indices},\"material\":{material}}}]}}"
            ));
            a.nodes.push(format!(
                "{{\"name\":\"terrain\",\"mesh\":{}}}",
                a.meshes.len() - 1
            ));
        }
        // Per used variant: its buffers' views, shared attributes and two materials.
        let mut used_variants: Vec<usize> = nodes.iter().map(|n| n.variant).collect();
        used_variants.dedup();
        let mut shared = vec![None; variants.len()];
        // One texture per leaf shape in use, in order of first use; its image goes after the
        // cache buffers.
        let mut shapes: Vec<LeafShape> = Vec::new();
        for &v in &used_variants {
            let shape = species[variants[v].species].leaf_shape;
            if !shapes.contains(&shape) {
                shapes.push(shape);
            }
        }
        // Then one bark texture per pattern in use, tiling with their own sampler.
        let mut images: Vec<Vec<u8>> = shapes.iter().map(|&s| Texture::leaf(s).png()).collect();
        let mut patterns: Vec<BarkPattern> = Vec::new();
        for &v in &used_variants {
            let pattern = species[variants[v].species].bark_pattern;
            if !patterns.contains(&pattern) {
                patterns.push(pattern);
            }
        }
        let first_bark = images.len();
        images.extend(patterns.iter().map(|&p| Texture::bark(p).png()));
        for &v in &used_variants {
            let variant = &variants[v];
            let cache = &variant.cache;
            let vbytes = size_of_val(cache.vertices.as_slice());
            let view = a.view(section(vbytes).0, vbytes, Some(32), Some(ARRAY_BUFFER));
            let attributes = a.vertex_attributes(view, cache.vertices.iter().map(|v| v.position));
            let index_view = |a: &mut Arrays, at: usize, len: usize| {
                (len > 0).then(|| a.view(at, 4 * len, None, Some(ELEMENT_ARRAY_BUFFER)))
            };
            let bark_at = section(4 * cache.bark.len()).0;
            let bark = index_view(&mut a, bark_at, cache.bark.len());
            let leaves_at = section(4 * cache.leaves.len()).0;
            let leaves = index_view(&mut a, leaves_at, cache.leaves.len());
            let s = &species[variant.species];
            let bark_texture = patterns
                .iter()
                .position(|&p| p == s.bark_pattern)
                .map(|k| first_bark + k);
            let bark_material = a.bark_material(
                &format!("{} bark", s.name),
                s.bark,
                options.roughness,
                bark_texture,
            );
            let texture = shapes.iter().position(|&shape| shape == s.leaf_shape);
            let leaf_material = a.material(
                &format!("{} leaves", s.name),
                s.leaf,
                options.roughness,
                texture,
            );
            shared[v] = Some((attributes, bark, leaves, bark_material, leaf_material));
        }
        let mut image_views = Vec::new();
        for image in &images {
            let at = section(image.len() + padding(image.len())).0;
            image_views.push(a.view(at, image.len(), None, None));
        }
        let placement_base = section(0).0;
        let t_view = a.view(section(12 * placements).0, 12 * placements, None, None);
        let r_view = a.view(section(16 * placements).0, 16 * placements, None, None);
        let s_view = a.view(section(12 * placements).0, 12 * placements, None, None);
        let c_view = a.view(section(12 * placements).0, 12 * placements, None, None);
        let bin_len = section(0).1;
        for node in nodes {
            let variant = &variants[node.variant];
            let inst = &variant.cache.instances[node.instance];
            let Some((attributes, bark, leaves, bark_material, leaf_material)) =
                &shared[node.variant]
            else {
                continue;
            };
            let mut primitives = Vec::new();
            for (view, span, material) in [
                (bark, inst.bark, bark_material),
                (leaves, inst.leaves, leaf_material),
            ] {
                if let (Some(view), false) = (view, span.is_empty()) {
                    let acc = a.accessor(
                        *view,
                        span.start as usize * 4,
                        UNSIGNED_INT,
                        span.count as usize,
                        "SCALAR",
                        None,
                    );
                    primitives.push(format!(
                        "{{\"attributes\":{attributes},\"indices\":{acc},\"material\":{material}}}"
                    ));
                }
            }
            let t = a.accessor(t_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            let r = a.accessor(r_view, 16 * node.first, FLOAT, node.count, "VEC4", None);
            let s = a.accessor(s_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            // Each tree's tint, as three.js and others read it: the instance colour.
            let c = a.accessor(c_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            let name = &species[variant.species].name;
            let tag = if variant.seedling { "seedling" } else { "tree" };
            a.meshes.push(format!(
                "{{\"name\":{},\"primitives\":[{}]}}",
                quoted(&format!(
                    "{name} {tag} branch {} age {} #{}",
                    inst.id, inst.age, node.instance
                )),
                primitives.join(",")
            ));
            a.nodes.push(format!(
                "{{\"name\":{},\"mesh\":{},\"extensions\":{{\"EXT_mesh_gpu_instancing\":{{\"attributes\":{{\"TRANSLATION\":{t},\"ROTATION\":{r},\"SCALE\":{s},\"_COLOR_0\":{c}}}}}}}}}",
                quoted(&format!("{name} {tag} instance {}", node.instance)),
                a.meshes.len() - 1
            ));
        }
        let scene: Vec<String> = (0..a.nodes.len()).map(|i| i.to_string()).collect();
        let mut json = String::with_capacity(
            a.nodes
                .iter()
                .chain(&a.meshes)
                .chain(&a.accessors)
                .map(String::len)
                .sum::<usize>()
                + 4096,
        );
        let _ = write!(
            json,
            "{{\"asset\":{{\"version\":\"2.0\",\"generator\":\"sylva\"}},\"scene\":0,\"scenes\":[{{\"nodes\":[{}]}}]",
            scene.join(",")
        );
        for (key, items) in [
            ("nodes", &a.nodes),
            ("meshes", &a.meshes),
            ("materials", &a.materials),
            ("accessors", &a.accessors),
            ("bufferViews", &a.views),
        ] {
            if !items.is_empty() {
                let _ = write!(json, ",\"{key}\":[{}]", items.join(","));
            }
        }
        if !image_views.is_empty() {
            let images: Vec<String> = image_views
                .iter()
                .map(|v| format!("{{\"bufferView\":{v},\"mimeType\":\"image/png\"}}"))
                .collect();
            // Leaf cards use sampler 0 (edges clamped), bark sampler 1 (repeated).
            let textures: Vec<String> = (0..image_views.len())
                .map(|i| {
                    let sampler = usize::from(i >= first_bark);
                    format!("{{\"sampler\":{sampler},\"source\":{i}}}")
                })
                .collect();
            // Linear filtering with mipmaps.
            let _ = write!(
                json,
                ",\"images\":[{}],\"textures\":[{}],\"samplers\":[{{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":33071,\"wrapT\":33071}},{{\"magFilter\":9729,\"minFilter\":9987,\"wrapS\":10497,\"wrapT\":10497}}]",
                images.join(","),
                textures.join(",")
            );
        }
        if bin_len > 0 {
            let _ = write!(json, ",\"buffers\":[{{\"byteLength\":{bin_len}}}]");
        }
        if !nodes.is_empty() {
            json.push_str(",\"extensionsUsed\":[\"EXT_mesh_gpu_instancing\"]");
        }
        json.push('}');
        while !json.len().is_multiple_of(4) {
            json.push(' ');
        }
        let bin_chunk = if bin_len > 0 { 8 + bin_len } else { 0 };
        Ok(Document {
            total: 12 + 8 + json.len() + bin_chunk,
            json,
            used_variants,
            images,
            terrain_colours,
            placement_base,
            bin_len,
        })
    }
}
