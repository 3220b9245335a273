//! The GLB's layout, decided before any byte is written: the JSON chunk as text and the offset
//! of every buffer in the BIN chunk.

use std::fmt::Write as _;

use sylva_forest::ForestBuilder;
use sylva_instancing::Similarity;
use sylva_terrain::TerrainMesh;
use sylva_turtle::Vertex;

use super::shared::{self, SharedLayout};
use super::{
    ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, GltfOptions, Node, UNSIGNED_INT, position_bounds,
};
use crate::error::ExportError;

/// The JSON chunk and the binary layout, decided before any byte is written.
#[derive(Debug)]
pub(super) struct Document {
    pub(super) json: String,
    /// Variants whose buffers this file embeds, in order (none when they are shared).
    pub(super) used_variants: Vec<usize>,
    /// The leaf textures as PNG, in layout order after the cache buffers.
    pub(super) images: Vec<Vec<u8>>,
    /// The terrain's ground colours, after its indices.
    pub(super) terrain_colours: Vec<[f32; 3]>,
    /// Offset in the BIN chunk where the placement sections start.
    pub(super) placement_base: usize,
    pub(super) bin_len: usize,
    pub(super) total: usize,
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
        self.view_in(0, offset, length, stride, target)
    }

    /// A view into buffer `buffer`: 0 is the GLB's own, 1 the shared geometry file.
    fn view_in(
        &mut self,
        buffer: u32,
        offset: usize,
        length: usize,
        stride: Option<u32>,
        target: Option<u32>,
    ) -> usize {
        let mut v =
            format!("{{\"buffer\":{buffer},\"byteOffset\":{offset},\"byteLength\":{length}");
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

    /// A dielectric material of `colour`, over `texture` when given, with a tangent-space
    /// normal texture when given. A leaf card is double-sided, its texture's alpha cut at one
    /// half.
    fn material(
        &mut self,
        name: &str,
        colour: [f32; 3],
        roughness: f32,
        (texture, normal): (Option<usize>, Option<usize>),
        leaf_card: bool,
    ) -> usize {
        let texture = texture.map_or(String::new(), |t| {
            format!(",\"baseColorTexture\":{{\"index\":{t}}}")
        });
        let normal = normal.map_or(String::new(), |t| {
            format!(",\"normalTexture\":{{\"index\":{t}}}")
        });
        let card = if leaf_card {
            ",\"alphaMode\":\"MASK\",\"alphaCutoff\":0.5,\"doubleSided\":true"
        } else {
            ""
        };
        self.materials.push(format!(
            "{{\"name\":{},\"pbrMetallicRoughness\":{{\"baseColorFactor\":[{},{},{},1.0]{texture},\"metallicFactor\":0.0,\"roughnessFactor\":{roughness}}}{normal}{card}}}",
            quoted(name),
            colour[0],
            colour[1],
            colour[2]
        ));
        self.materials.len() - 1
    }

    /// Position (with bounds), normal and uv accessors over interleaved vertices that start
    /// with those three (terrain vertices, 32 bytes); for tree vertices (48 bytes), also their
    /// `_WIND` ([`sylva_turtle::Vertex::wind`], after the uv) and the `TANGENT`s in the view
    /// `tree`.
    fn vertex_attributes(
        &mut self,
        view: usize,
        positions: impl Iterator<Item = [f32; 3]>,
        tree: Option<usize>,
    ) -> String {
        let (lo, hi, count) = position_bounds(positions);
        let position = self.accessor(view, 0, FLOAT, count, "VEC3", Some((lo, hi)));
        let normal = self.accessor(view, 12, FLOAT, count, "VEC3", None);
        let uv = self.accessor(view, 24, FLOAT, count, "VEC2", None);
        let wind = match tree {
            Some(tangents) => {
                let w = self.accessor(view, 32, FLOAT, count, "VEC4", None);
                let t = self.accessor(tangents, 0, FLOAT, count, "VEC4", None);
                format!(",\"_WIND\":{w},\"TANGENT\":{t}")
            }
            None => String::new(),
        };
        format!("{{\"POSITION\":{position},\"NORMAL\":{normal},\"TEXCOORD_0\":{uv}{wind}}}")
    }
}

/// Zero bytes that bring `len` to a whole number of 4-byte words.
pub(super) fn padding(len: usize) -> usize {
    (4 - len % 4) % 4
}

/// A JSON string literal.
fn quoted(text: &str) -> String {
    serde_json::to_string(text).unwrap_or_else(|_| "\"\"".into())
}

impl Document {
    /// File offset of the BIN chunk's content: after the GLB header, the JSON chunk and the
    /// BIN chunk's own header.
    pub(super) fn bin_start(&self) -> usize {
        12 + 8 + self.json.len() + 8
    }

    /// The layout for `nodes` holding `placements` in all. With `one_node_each` (the
    /// fallback for importers without EXT_mesh_gpu_instancing) every placement is a node of
    /// its own, its transform given here, per node in the order of `nodes`, and the file has
    /// no placement sections.
    pub(super) fn lay_out(
        builder: &ForestBuilder,
        terrain: Option<&TerrainMesh>,
        options: &GltfOptions,
        nodes: &[Node],
        placements: usize,
        one_node_each: Option<&[Vec<Similarity>]>,
    ) -> Result<Document, ExportError> {
        let placements = if one_node_each.is_some() {
            0
        } else {
            placements
        };
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
            let attributes = a.vertex_attributes(view, t.vertices.iter().map(|v| v.position), None);
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
            let material = a.material(
                "terrain",
                options.terrain_colour,
                options.roughness,
                (None, None),
                false,
            );
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
        // Geometry shared with other files (tiles of one world) lives in buffer 1, laid out
        // for every variant and texture of the world; otherwise the used variants' buffers
        // and textures follow the terrain in this file.
        let shared_layout = options
            .shared_geometry
            .as_ref()
            .map(|uri| (uri, SharedLayout::of(builder)));
        // One texture per leaf shape, then bark colour and normal map per pattern; images in
        // that order.
        let (shapes, patterns) = match &shared_layout {
            Some((_, layout)) => (layout.shapes.clone(), layout.patterns.clone()),
            None => {
                let (mut shapes, mut patterns) = (Vec::new(), Vec::new());
                for &v in &used_variants {
                    let s = &species[variants[v].species];
                    if !shapes.contains(&s.leaf_shape) {
                        shapes.push(s.leaf_shape);
                    }
                    if !patterns.contains(&s.bark_pattern) {
                        patterns.push(s.bark_pattern);
                    }
                }
                (shapes, patterns)
            }
        };
        let first_bark = shapes.len();
        let first_normal = first_bark + patterns.len();
        let images: Vec<Vec<u8>> = match &shared_layout {
            Some(_) => Vec::new(),
            None => shared::images(&shapes, &patterns).to_vec(),
        };
        for &v in &used_variants {
            let variant = &variants[v];
            let cache = &variant.cache;
            let vbytes = size_of_val(cache.vertices.as_slice());
            let tbytes = 16 * cache.vertices.len();
            let (bbytes, lbytes) = (4 * cache.bark.len(), 4 * cache.leaves.len());
            // Where the four buffers are: (buffer, offsets).
            let (buffer, at) = match &shared_layout {
                Some((_, layout)) => {
                    let s = layout.variants[v];
                    (1, [s.vertices, s.tangents, s.bark, s.leaves])
                }
                None => (
                    0,
                    [
                        section(vbytes).0,
                        section(tbytes).0,
                        section(bbytes).0,
                        section(lbytes).0,
                    ],
                ),
            };
            let stride = size_of::<Vertex>() as u32;
            let view = a.view_in(buffer, at[0], vbytes, Some(stride), Some(ARRAY_BUFFER));
            let tangents = a.view_in(buffer, at[1], tbytes, None, Some(ARRAY_BUFFER));
            let attributes = a.vertex_attributes(
                view,
                cache.vertices.iter().map(|v| v.position),
                Some(tangents),
            );
            let index_view = |a: &mut Arrays, at: usize, len: usize| {
                (len > 0).then(|| a.view_in(buffer, at, len, None, Some(ELEMENT_ARRAY_BUFFER)))
            };
            let bark = index_view(&mut a, at[2], bbytes);
            let leaves = index_view(&mut a, at[3], lbytes);
            let s = &species[variant.species];
            let pattern = patterns.iter().position(|&p| p == s.bark_pattern);
            let bark_material = a.material(
                &format!("{} bark", s.name),
                s.bark,
                options.roughness,
                (
                    pattern.map(|k| first_bark + k),
                    pattern.map(|k| first_normal + k),
                ),
                false,
            );
            let texture = shapes.iter().position(|&shape| shape == s.leaf_shape);
            let leaf_material = a.material(
                &format!("{} leaves", s.name),
                s.leaf,
                options.roughness,
                (texture, None),
                true,
            );
            shared[v] = Some((attributes, bark, leaves, bark_material, leaf_material));
        }
        let mut image_views = Vec::new();
        match &shared_layout {
            Some((_, layout)) => {
                for &(at, len) in &layout.images {
                    image_views.push(a.view_in(1, at, len, None, None));
                }
            }
            None => {
                for image in &images {
                    let at = section(image.len() + padding(image.len())).0;
                    image_views.push(a.view(at, image.len(), None, None));
                }
            }
        }
        let placement_base = section(0).0;
        // The placement sections (translation, rotation, scale, tint, wind), none when every
        // placement is a node of its own.
        let mut placement_view = |a: &mut Arrays, width: usize| {
            if one_node_each.is_some() {
                0
            } else {
                a.view(
                    section(width * placements).0,
                    width * placements,
                    None,
                    None,
                )
            }
        };
        let t_view = placement_view(&mut a, 12);
        let r_view = placement_view(&mut a, 16);
        let s_view = placement_view(&mut a, 12);
        let c_view = placement_view(&mut a, 12);
        let w_view = placement_view(&mut a, 16);
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
            let name = &species[variant.species].name;
            let tag = if variant.seedling { "seedling" } else { "tree" };
            if let Some(each) = one_node_each {
                a.meshes.push(format!(
                    "{{\"name\":{},\"primitives\":[{}]}}",
                    quoted(&format!("{name} {tag} branch {} age {}", inst.id, inst.age)),
                    primitives.join(",")
                ));
                let mesh = a.meshes.len() - 1;
                let k = nodes
                    .iter()
                    .position(|n| std::ptr::eq(n, node))
                    .unwrap_or(0);
                for x in each.get(k).into_iter().flatten() {
                    let q = x.rotation.normalize();
                    a.nodes.push(format!(
                        "{{\"mesh\":{mesh},\"translation\":[{},{},{}],\"rotation\":[{},{},{},{}],\"scale\":[{s},{s},{s}]}}",
                        x.translation.x, x.translation.y, x.translation.z, q.x, q.y, q.z, q.w,
                        s = x.scale
                    ));
                }
                continue;
            }
            let t = a.accessor(t_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            let r = a.accessor(r_view, 16 * node.first, FLOAT, node.count, "VEC4", None);
            let s = a.accessor(s_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            // Each tree's tint, as three.js and others read it: the instance colour.
            let c = a.accessor(c_view, 12 * node.first, FLOAT, node.count, "VEC3", None);
            // Each tree's base and phase, for wind shaders (`tree_wind`).
            let w = a.accessor(w_view, 16 * node.first, FLOAT, node.count, "VEC4", None);
            a.meshes.push(format!(
                "{{\"name\":{},\"primitives\":[{}]}}",
                quoted(&format!(
                    "{name} {tag} branch {} age {} #{}",
                    inst.id, inst.age, node.instance
                )),
                primitives.join(",")
            ));
            a.nodes.push(format!(
                "{{\"name\":{},\"mesh\":{},\"extensions\":{{\"EXT_mesh_gpu_instancing\":{{\"attributes\":{{\"TRANSLATION\":{t},\"ROTATION\":{r},\"SCALE\":{s},\"_COLOR_0\":{c},\"_WIND_TREE\":{w}}}}}}}}}",
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
        match &shared_layout {
            Some((uri, layout)) => {
                let _ = write!(
                    json,
                    ",\"buffers\":[{{\"byteLength\":{}}},{{\"uri\":{},\"byteLength\":{}}}]",
                    bin_len.max(4),
                    quoted(uri),
                    layout.len
                );
            }
            None if bin_len > 0 => {
                let _ = write!(json, ",\"buffers\":[{{\"byteLength\":{bin_len}}}]");
            }
            None => {}
        }
        if !nodes.is_empty() && one_node_each.is_none() {
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
            used_variants: if shared_layout.is_some() {
                Vec::new()
            } else {
                used_variants
            },
            images,
            terrain_colours,
            placement_base,
            bin_len,
        })
    }
}
