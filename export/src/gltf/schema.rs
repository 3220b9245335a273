//! The parts of the glTF 2.0 JSON schema that sylva writes, as typed structs serialised with
//! serde. Field order is the order keys appear in the file; absent options and empty arrays
//! are left out, as the schema asks (`minItems: 1`). Extensions these structs do not model go
//! in [`Root::extensions`] and [`Node::extras`] as `serde_json::Value`.

use serde::Serialize;
use serde_json::Value;

/// The name glTF gives the extension that places one mesh many times from accessors.
pub(super) const GPU_INSTANCING: &str = "EXT_mesh_gpu_instancing";
/// Normalized integer vertex attributes (the trees' normals and tangents).
pub(super) const MESH_QUANTIZATION: &str = "KHR_mesh_quantization";
/// Microsoft's levels of detail: a node names the nodes that draw it coarser.
pub(super) const LEVELS_OF_DETAIL: &str = "MSFT_lod";

/// The whole JSON chunk.
#[derive(Debug, Default, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Root {
    pub(super) asset: Asset,
    pub(super) scene: usize,
    pub(super) scenes: Vec<Scene>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) nodes: Vec<Node>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) meshes: Vec<Mesh>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) materials: Vec<Material>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) accessors: Vec<Accessor>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) buffer_views: Vec<BufferView>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) images: Vec<Image>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) textures: Vec<Texture>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) samplers: Vec<Sampler>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) buffers: Vec<Buffer>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) extensions_used: Vec<String>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) extensions_required: Vec<String>,
    /// Document-level extensions, by name.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) extensions: Option<Value>,
}

/// Which glTF this is and who wrote it.
#[derive(Debug, Serialize)]
pub(super) struct Asset {
    pub(super) version: &'static str,
    pub(super) generator: &'static str,
}

impl Default for Asset {
    fn default() -> Self {
        Asset {
            version: "2.0",
            generator: "sylva",
        }
    }
}

/// The nodes drawn.
#[derive(Debug, Serialize)]
pub(super) struct Scene {
    pub(super) nodes: Vec<usize>,
}

/// A node: a mesh placed once by its own transform, or many times by instancing accessors.
#[derive(Debug, Default, Serialize)]
pub(super) struct Node {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) name: Option<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mesh: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) translation: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) rotation: Option<[f32; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) scale: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) extensions: Option<NodeExtensions>,
    /// Child nodes: a scene lists only the nodes that are nobody's child.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(super) children: Vec<usize>,
    /// Application data (engines' importers keep it as custom properties).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) extras: Option<Value>,
}

impl Node {
    /// A node of `mesh` named `name`, at the origin.
    pub(super) fn of_mesh(name: impl Into<String>, mesh: usize) -> Node {
        Node {
            name: Some(name.into()),
            mesh: Some(mesh),
            ..Node::default()
        }
    }
}

/// The extensions a node carries.
#[derive(Debug, Default, Serialize)]
pub(super) struct NodeExtensions {
    #[serde(
        rename = "EXT_mesh_gpu_instancing",
        skip_serializing_if = "Option::is_none"
    )]
    pub(super) gpu_instancing: Option<GpuInstancing>,
    #[serde(rename = "MSFT_lod", skip_serializing_if = "Option::is_none")]
    pub(super) lod: Option<LevelsOfDetail>,
}

/// MSFT_lod on a node: the nodes that draw it at lower levels of detail, finest first. The
/// node itself is the highest level; a client without the extension draws only it.
#[derive(Debug, Serialize)]
pub(super) struct LevelsOfDetail {
    pub(super) ids: Vec<usize>,
}

/// EXT_mesh_gpu_instancing: the node's mesh drawn once per element of these accessors.
#[derive(Debug, Serialize)]
pub(super) struct GpuInstancing {
    pub(super) attributes: InstanceAttributes,
}

/// Per-instance accessors: the three the extension defines and sylva's own (underscored, as
/// the extension asks of application attributes).
#[derive(Debug, Serialize)]
pub(super) struct InstanceAttributes {
    #[serde(rename = "TRANSLATION")]
    pub(super) translation: usize,
    #[serde(rename = "ROTATION")]
    pub(super) rotation: usize,
    #[serde(rename = "SCALE")]
    pub(super) scale: usize,
    /// Each tree's tint, as three.js and others read it: the instance colour.
    #[serde(rename = "_COLOR_0")]
    pub(super) colour: usize,
    /// Each tree's base, as an offset from the placement over the node's
    /// `extras.sylva_wind_tree_reach`, and its phase, for wind shaders (`tree_wind`).
    #[serde(rename = "_WIND_TREE", skip_serializing_if = "Option::is_none")]
    pub(super) wind: Option<usize>,
}

/// A mesh: its primitives drawn together.
#[derive(Debug, Serialize)]
pub(super) struct Mesh {
    pub(super) name: String,
    pub(super) primitives: Vec<Primitive>,
}

/// Triangles of one material over vertex attributes.
#[derive(Debug, Clone, Serialize)]
pub(super) struct Primitive {
    pub(super) attributes: Attributes,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) indices: Option<usize>,
    pub(super) material: usize,
}

/// Vertex attribute accessors, in the order sylva writes them.
#[derive(Debug, Clone, Copy, Default, Serialize)]
pub(super) struct Attributes {
    #[serde(rename = "POSITION")]
    pub(super) position: usize,
    #[serde(rename = "NORMAL", skip_serializing_if = "Option::is_none")]
    pub(super) normal: Option<usize>,
    #[serde(rename = "TEXCOORD_0", skip_serializing_if = "Option::is_none")]
    pub(super) uv: Option<usize>,
    /// [`sylva_turtle::Vertex::wind`]: where a vertex sits on its tree, for wind shaders.
    #[serde(rename = "_WIND", skip_serializing_if = "Option::is_none")]
    pub(super) wind: Option<usize>,
    #[serde(rename = "TANGENT", skip_serializing_if = "Option::is_none")]
    pub(super) tangent: Option<usize>,
    /// Ground colours by slope and altitude.
    #[serde(rename = "COLOR_0", skip_serializing_if = "Option::is_none")]
    pub(super) colour: Option<usize>,
}

/// A metallic-roughness material.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Material {
    pub(super) name: String,
    pub(super) pbr_metallic_roughness: Pbr,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) normal_texture: Option<TextureRef>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) alpha_mode: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) alpha_cutoff: Option<f32>,
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(super) double_sided: bool,
    /// Application data: a leaf material's `sylva_phenology` ([`super::season`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) extras: Option<Value>,
}

/// The metallic-roughness factors and textures.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Pbr {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) base_color_factor: Option<[f32; 4]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) base_color_texture: Option<TextureRef>,
    pub(super) metallic_factor: f32,
    pub(super) roughness_factor: f32,
}

/// A material's use of a texture.
#[derive(Debug, Serialize)]
pub(super) struct TextureRef {
    pub(super) index: usize,
}

/// A typed view of a buffer view.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Accessor {
    pub(super) buffer_view: usize,
    pub(super) byte_offset: usize,
    pub(super) component_type: u32,
    pub(super) count: usize,
    #[serde(rename = "type")]
    pub(super) kind: &'static str,
    /// Integers read as fractions of their maximum (colours in bytes).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(super) normalized: bool,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) min: Option<[f32; 3]>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) max: Option<[f32; 3]>,
}

/// A range of a buffer.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct BufferView {
    pub(super) buffer: usize,
    pub(super) byte_offset: usize,
    pub(super) byte_length: usize,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) byte_stride: Option<u32>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) target: Option<u32>,
}

/// A buffer: the GLB's BIN chunk (no URI) or an external file.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Buffer {
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) uri: Option<String>,
    pub(super) byte_length: usize,
}

/// An image stored in a buffer view.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Image {
    /// The image's bytes in a buffer view, or none for an image in a file of its own.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) buffer_view: Option<usize>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) mime_type: Option<&'static str>,
    /// The file of an image outside the GLB, relative to it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(super) uri: Option<String>,
}

/// An image with the sampler that reads it.
#[derive(Debug, Serialize)]
pub(super) struct Texture {
    pub(super) sampler: usize,
    pub(super) source: usize,
}

/// Filtering and wrapping.
#[derive(Debug, Serialize)]
#[serde(rename_all = "camelCase")]
pub(super) struct Sampler {
    pub(super) mag_filter: u32,
    pub(super) min_filter: u32,
    pub(super) wrap_s: u32,
    pub(super) wrap_t: u32,
}

const LINEAR: u32 = 9729;
const LINEAR_MIPMAP_LINEAR: u32 = 9987;
const CLAMP_TO_EDGE: u32 = 33071;
const REPEAT: u32 = 10497;

impl Sampler {
    /// The two samplers sylva's textures use, linear with mipmaps: 0 clamps its edges (leaf
    /// cards), 1 repeats (bark).
    pub(super) fn clamped_and_repeated() -> Vec<Sampler> {
        [CLAMP_TO_EDGE, REPEAT]
            .into_iter()
            .map(|wrap| Sampler {
                mag_filter: LINEAR,
                min_filter: LINEAR_MIPMAP_LINEAR,
                wrap_s: wrap,
                wrap_t: wrap,
            })
            .collect()
    }
}
