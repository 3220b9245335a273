//! One way to build a glTF document: views, accessors, attributes, materials, meshes and
//! nodes added to a typed [`Root`], and the length of the GLB's own buffer so far. The
//! streamed writer lays out sections it writes later; the in-memory writer
//! appends their bytes as it goes.

use super::schema::{
    Accessor, Attributes, Buffer, BufferView, GPU_INSTANCING, GpuInstancing, Image,
    InstanceAttributes, LEVELS_OF_DETAIL, MESH_QUANTIZATION, Material, Mesh, Node, NodeExtensions,
    Pbr, Primitive, Root, Sampler, Scene, Texture, TextureRef,
};
use sylva_forest::{CLUSTER_SHADE_MEAN, Species};

use super::extras::VertexLayout;
use super::indices::IndexWidth;
use super::placement_words::WIND_TREE_REACH;
use super::{BYTE, ELEMENT_ARRAY_BUFFER, FLOAT, UNSIGNED_BYTE, position_bounds};
use crate::error::{ExportError, Invalid};

/// Zero bytes that bring `len` to a whole number of 4-byte words.
pub(super) fn padding(len: usize) -> usize {
    (4 - len % 4) % 4
}

/// A leaf colour before the cluster shades (mean [`CLUSTER_SHADE_MEAN`]) darken it.
fn unshaded(leaf: [f32; 3]) -> [f32; 3] {
    leaf.map(|c| (c / CLUSTER_SHADE_MEAN).min(1.0))
}

/// What a crown shades itself that a flat card cannot: the cards' colour factor, so that
/// a card lit as facing the sky looks as dark as the crown it stands for. Chosen by eye
/// against branch instances beside impostors in three.js.
const CARD_SHADE: f32 = 0.7;

/// A glTF document being assembled.
#[derive(Debug, Default)]
pub(super) struct DocumentBuilder {
    pub(super) root: Root,
    /// Bytes of buffer 0 (the GLB's BIN chunk) laid out so far, a whole number of words.
    pub(super) bin_len: usize,
    /// Whether an attribute is quantized (`KHR_mesh_quantization`, which the file then
    /// requires: an importer without it would misread the normals).
    pub(super) quantized: bool,
    /// Nodes that no scene lists though nothing holds them as a child or a level: what
    /// extras name (a cell's impostors), for the clients that read them.
    pub(super) outside_scene: Vec<usize>,
}

/// Where the four buffers of a tree mesh are: one view of its vertices and one of their
/// extras (as `extras::VertexLayout` lays them out), and the bark and leaf indices (none
/// when empty).
#[derive(Debug, Clone, Copy)]
pub(super) struct TreeViews {
    pub(super) vertices: usize,
    pub(super) extras: usize,
    pub(super) bark: Option<usize>,
    pub(super) leaves: Option<usize>,
}

impl DocumentBuilder {
    /// Reserves `len` bytes at the end of buffer 0, padded to a word; returns their offset.
    pub(super) fn reserve(&mut self, len: usize) -> usize {
        let at = self.bin_len;
        self.bin_len += len + padding(len);
        at
    }

    /// A view of `len` new bytes at the end of buffer 0.
    pub(super) fn view(&mut self, len: usize, stride: Option<u32>, target: Option<u32>) -> usize {
        let at = self.reserve(len);
        self.view_in(0, at, len, stride, target)
    }

    /// A view into `buffer`: 0 is the GLB's own, 1 the shared geometry file of a world.
    pub(super) fn view_in(
        &mut self,
        buffer: usize,
        offset: usize,
        length: usize,
        stride: Option<u32>,
        target: Option<u32>,
    ) -> usize {
        self.root.buffer_views.push(BufferView {
            buffer,
            byte_offset: offset,
            byte_length: length,
            byte_stride: stride,
            target,
        });
        self.root.buffer_views.len() - 1
    }

    /// An accessor of `count` elements of `kind` (`"VEC3"`, …) at `offset` in `view`.
    pub(super) fn accessor(
        &mut self,
        view: usize,
        offset: usize,
        component: u32,
        count: usize,
        kind: &'static str,
    ) -> usize {
        self.root.accessors.push(Accessor {
            buffer_view: view,
            byte_offset: offset,
            component_type: component,
            count,
            kind,
            normalized: false,
            min: None,
            max: None,
        });
        self.root.accessors.len() - 1
    }

    /// A float VEC3 accessor of `positions` in `view` at `offset`, with the bounds glTF asks
    /// of positions.
    pub(super) fn positions(
        &mut self,
        view: usize,
        offset: usize,
        positions: impl IntoIterator<Item = [f32; 3]>,
    ) -> usize {
        let (lo, hi, count) = position_bounds(positions);
        let a = self.accessor(view, offset, FLOAT, count, "VEC3");
        self.root.accessors[a].min = Some(lo);
        self.root.accessors[a].max = Some(hi);
        a
    }

    /// `count` indices of `width` at `offset` bytes into `view`.
    pub(super) fn indices(
        &mut self,
        view: usize,
        offset: usize,
        (width, count): (IndexWidth, usize),
    ) -> usize {
        self.accessor(view, offset, width.component(), count, "SCALAR")
    }

    /// An index view of `len` bytes at `offset` in `buffer`, none when empty.
    pub(super) fn index_view(&mut self, buffer: usize, offset: usize, len: usize) -> Option<usize> {
        (len > 0).then(|| self.view_in(buffer, offset, len, None, Some(ELEMENT_ARRAY_BUFFER)))
    }

    /// Position (with bounds), normal and uv accessors over interleaved vertices that start
    /// with those three (terrain vertices, 32 bytes).
    fn surface_attributes(
        &mut self,
        view: usize,
        positions: impl Iterator<Item = [f32; 3]>,
    ) -> Attributes {
        let position = self.positions(view, 0, positions);
        let count = self.root.accessors[position].count;
        Attributes {
            position,
            normal: Some(self.accessor(view, 12, FLOAT, count, "VEC3")),
            uv: Some(self.accessor(view, 24, FLOAT, count, "VEC2")),
            ..Attributes::default()
        }
    }

    /// The attributes of tree vertices in `layout`: positions, uvs and `_WIND`
    /// ([`sylva_turtle::Vertex::wind`]) as floats; `NORMAL`s and `TANGENT`s as floats, or
    /// in [`VertexLayout::Quantized`] as normalized bytes (`KHR_mesh_quantization`, which
    /// the file then requires); the leaf clusters' shades as normalized byte `COLOR_0`s.
    ///
    /// `_WIND` is the only attribute of sylva's own (a leading underscore) on a primitive:
    /// Blender 5.0's glTF importer pairs a mesh's custom attributes with their data in set
    /// order, so two of different sizes fail its import in about half of its runs
    /// (`ValueError` in `do_primitives`), and two of one size swap silently. The seasons'
    /// per-vertex data is what `_WIND` and `NORMAL` already hold
    /// ([`sylva_forest::vertex_phenology`], `docs/engines.md`).
    pub(super) fn tree_attributes(
        &mut self,
        views: TreeViews,
        positions: impl Iterator<Item = [f32; 3]>,
        layout: VertexLayout,
    ) -> Attributes {
        let position = self.positions(views.vertices, 0, positions);
        let count = self.root.accessors[position].count;
        let at = layout.offsets();
        let view = |(k, offset): (usize, usize)| ([views.vertices, views.extras][k], offset);
        let quantized = layout == VertexLayout::Quantized;
        let (component, normalized) = if quantized {
            (BYTE, true)
        } else {
            (FLOAT, false)
        };
        let mut accessor = |(view, offset), component, kind, normalized| {
            let a = self.accessor(view, offset, component, count, kind);
            self.root.accessors[a].normalized = normalized;
            Some(a)
        };
        let attributes = Attributes {
            position,
            normal: accessor(view(at.normal), component, "VEC3", normalized),
            tangent: accessor(view(at.tangent), component, "VEC4", normalized),
            colour: accessor((views.extras, at.colour), UNSIGNED_BYTE, "VEC4", true),
            uv: accessor((views.vertices, at.uv), FLOAT, "VEC2", false),
            wind: accessor((views.vertices, at.wind), FLOAT, "VEC4", false),
        };
        self.quantized |= quantized;
        attributes
    }

    /// The terrain's mesh and node: its vertices (32 bytes each) in `vertices`, `indices`
    /// indices (of their width) in `index_view`, and its ground colours by slope and altitude as `COLOR_0`
    /// (`colours` of them in `colour_view`), drawn with `material`.
    pub(super) fn terrain(
        &mut self,
        vertices: usize,
        positions: impl Iterator<Item = [f32; 3]>,
        (index_view, indices): (Option<usize>, (IndexWidth, usize)),
        (colour_view, colours): (usize, usize),
        material: usize,
    ) {
        let mut attributes = self.surface_attributes(vertices, positions);
        let indices = index_view.map(|v| self.indices(v, 0, indices));
        attributes.colour = Some(self.accessor(colour_view, 0, FLOAT, colours, "VEC3"));
        let mesh = self.mesh(
            "terrain".into(),
            vec![Primitive {
                attributes,
                indices,
                material,
            }],
        );
        self.root.nodes.push(Node::of_mesh("terrain", mesh));
    }

    /// A dielectric material of `colour`, over `texture` when given, with a tangent-space
    /// normal texture when given. A leaf card (`cutoff` given) is double-sided, its
    /// texture's alpha cut at `cutoff`.
    pub(super) fn material(
        &mut self,
        name: String,
        colour: [f32; 3],
        roughness: f32,
        (texture, normal): (Option<usize>, Option<usize>),
        cutoff: Option<f32>,
    ) -> usize {
        let leaf_card = cutoff.is_some();
        let [r, g, b] = colour;
        self.root.materials.push(Material {
            name,
            pbr_metallic_roughness: Pbr {
                base_color_factor: Some([r, g, b, 1.0]),
                base_color_texture: texture.map(|index| TextureRef { index }),
                metallic_factor: 0.0,
                roughness_factor: roughness,
            },
            normal_texture: normal.map(|index| TextureRef { index }),
            alpha_mode: leaf_card.then_some("MASK"),
            alpha_cutoff: cutoff,
            double_sided: leaf_card,
            extras: None,
        });
        self.root.materials.len() - 1
    }

    /// An impostor's cards' material: `texture`'s colour darkened by [`CARD_SHADE`], its alpha
    /// cut at `cutoff`, one-sided (the cards are drawn both ways, so neither side's normal is
    /// flipped).
    pub(super) fn card_material(&mut self, name: String, texture: usize, cutoff: f32) -> usize {
        let shade = [CARD_SHADE; 3];
        let index = self.material(name, shade, 0.9, (Some(texture), None), Some(cutoff));
        if let Some(m) = self.root.materials.get_mut(index) {
            m.double_sided = false;
        }
        index
    }

    /// A species' bark material, over its colour and normal textures when given, and its
    /// leaf-card material, over its leaf texture when given: `(bark, leaves)`. The leaves'
    /// colour is the species' over [`CLUSTER_SHADE_MEAN`] (at most 1), so that their
    /// `COLOR_0` shades vary the clusters about the species' colour; the cards' alpha is cut
    /// where the leaf shape's coverage survives a client's mipmaps
    /// ([`Texture::alpha_cutoff`](crate::Texture::alpha_cutoff)).
    pub(super) fn species_materials(
        &mut self,
        species: &Species,
        roughness: f32,
        (leaf, bark, normal): (Option<usize>, Option<usize>, Option<usize>),
    ) -> (usize, usize) {
        let bark_name = format!("{} bark", species.name);
        let leaf_name = format!("{} leaves", species.name);
        let bark = self.material(bark_name, species.bark, roughness, (bark, normal), None);
        let leaves = self.material(
            leaf_name,
            unshaded(species.leaf),
            roughness,
            (leaf, None),
            Some(crate::texture::card_alpha_cutoff(species.leaf_shape)),
        );
        if let Some(m) = self.root.materials.get_mut(leaves) {
            m.extras = Some(super::season::phenology_extras(species));
        }
        (bark, leaves)
    }

    /// A mesh; returns its index.
    pub(super) fn mesh(&mut self, name: String, primitives: Vec<Primitive>) -> usize {
        self.root.meshes.push(Mesh { name, primitives });
        self.root.meshes.len() - 1
    }

    /// A node drawing `mesh` once per element of the instancing accessors: translation,
    /// rotation, scale, tint and (when given) wind, whose reach the node's extras then say.
    pub(super) fn instanced_node(
        &mut self,
        name: String,
        mesh: usize,
        [translation, rotation, scale, colour]: [usize; 4],
        wind: Option<usize>,
    ) {
        self.root.nodes.push(Node {
            name: Some(name),
            mesh: Some(mesh),
            extensions: Some(NodeExtensions {
                gpu_instancing: Some(GpuInstancing {
                    attributes: InstanceAttributes {
                        translation,
                        rotation,
                        scale,
                        colour,
                        wind,
                    },
                }),
                lod: None,
            }),
            // A wind shader needs the reach to read `_WIND_TREE`'s offsets in metres.
            extras: wind.map(|_| serde_json::json!({ "sylva_wind_tree_reach": WIND_TREE_REACH })),
            ..Node::default()
        });
    }

    /// PNG images stored in buffer views, each a texture of its own: `(view, tiled)`, with
    /// sampler 0 (edges clamped, for leaf cards) or when `tiled` 1 (repeated, for bark).
    pub(super) fn images(&mut self, views: impl IntoIterator<Item = (usize, bool)>) {
        for (buffer_view, tiled) in views {
            self.root.images.push(Image {
                buffer_view: Some(buffer_view),
                mime_type: Some("image/png"),
                uri: None,
            });
            self.root.textures.push(Texture {
                sampler: usize::from(tiled),
                source: self.root.images.len() - 1,
            });
        }
        if !self.root.images.is_empty() {
            self.root.samplers = Sampler::clamped_and_repeated();
        }
    }

    /// A PNG image in a file of its own at `uri` (relative to the GLB), clamped at its
    /// edges; returns its texture's index.
    pub(super) fn image_file(&mut self, uri: String) -> usize {
        self.root.images.push(Image {
            buffer_view: None,
            mime_type: None,
            uri: Some(uri),
        });
        self.root.textures.push(Texture {
            sampler: 0,
            source: self.root.images.len() - 1,
        });
        self.root.samplers = Sampler::clamped_and_repeated();
        self.root.textures.len() - 1
    }

    /// Adds buffer 0 when anything was laid out in it (at least `min` bytes long, so that a
    /// file with a second buffer always has a first).
    pub(super) fn own_buffer(&mut self, min: usize) {
        if self.bin_len > 0 || min > 0 {
            self.root.buffers.push(Buffer {
                uri: None,
                byte_length: self.bin_len.max(min),
            });
        }
    }

    /// The JSON chunk: one scene of every node, `EXT_mesh_gpu_instancing` declared used and
    /// required when a node uses it (an importer without it would stack every placement's
    /// mesh at the origin; required, it refuses the file and the user reaches for
    /// `--no-instancing`), padded with spaces to a whole number of words.
    pub(super) fn into_json(mut self) -> Result<String, ExportError> {
        // A node that is another's child, or another's coarser level, is not a scene's root:
        // a client without MSFT_lod never reaches the coarser levels.
        let extensions = || self.root.nodes.iter().filter_map(|n| n.extensions.as_ref());
        let lower: Vec<usize> = extensions()
            .filter_map(|e| e.lod.as_ref())
            .flat_map(|l| l.ids.iter().copied())
            .collect();
        let instanced = extensions().any(|e| e.gpu_instancing.is_some());
        let levels = !lower.is_empty();
        let below: std::collections::BTreeSet<usize> = self
            .root
            .nodes
            .iter()
            .flat_map(|n| n.children.iter().copied())
            .chain(lower)
            .chain(self.outside_scene.iter().copied())
            .collect();
        self.root.scenes = vec![Scene {
            nodes: (0..self.root.nodes.len())
                .filter(|k| !below.contains(k))
                .collect(),
        }];
        if instanced {
            self.root.extensions_used.push(GPU_INSTANCING.into());
            self.root.extensions_required.push(GPU_INSTANCING.into());
        }
        // Used, not required: a client without it draws every node at full detail.
        if levels {
            self.root.extensions_used.push(LEVELS_OF_DETAIL.into());
        }
        if self.quantized {
            self.root.extensions_used.push(MESH_QUANTIZATION.into());
            self.root.extensions_required.push(MESH_QUANTIZATION.into());
        }
        let mut json =
            serde_json::to_string(&self.root).map_err(|e| Invalid::Json(e.to_string()))?;
        json.extend(std::iter::repeat_n(' ', padding(json.len())));
        Ok(json)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The JSON text of a small document, key for key: absent options and empty arrays left
    /// out, the chunk padded to a word.
    #[test]
    fn a_small_document_serialises_as_the_schema_asks() {
        let mut d = DocumentBuilder::default();
        let view = d.view(6, None, Some(ELEMENT_ARRAY_BUFFER));
        assert_eq!(d.bin_len, 8, "views are padded to words");
        let indices = d.indices(view, 0, (IndexWidth::Int, 3));
        let positions = d.view(36, Some(12), None);
        let position = d.positions(positions, 0, [[0.0, 1.0, 0.5], [2.0, -1.0, 0.0], [1.0; 3]]);
        let material = d.material(
            "leaf".into(),
            [0.5, 0.25, 1.0],
            0.9,
            (Some(0), None),
            Some(0.5),
        );
        let attributes = Attributes {
            position,
            ..Attributes::default()
        };
        let primitives = vec![Primitive {
            attributes,
            indices: Some(indices),
            material,
        }];
        let mesh = d.mesh("card".into(), primitives);
        d.instanced_node("cards".into(), mesh, [1, 1, 1, 1], None);
        d.own_buffer(0);
        let json = d.into_json().unwrap();
        assert_eq!(json.len() % 4, 0);
        assert_eq!(
            json.trim_end(),
            concat!(
                r#"{"asset":{"version":"2.0","generator":"sylva"},"scene":0,"scenes":[{"nodes":[0]}],"#,
                r#""nodes":[{"name":"cards","mesh":0,"extensions":{"EXT_mesh_gpu_instancing":{"attributes":{"TRANSLATION":1,"ROTATION":1,"SCALE":1,"_COLOR_0":1}}}}],"#,
                r#""meshes":[{"name":"card","primitives":[{"attributes":{"POSITION":1},"indices":0,"material":0}]}],"#,
                r#""materials":[{"name":"leaf","pbrMetallicRoughness":{"baseColorFactor":[0.5,0.25,1.0,1.0],"baseColorTexture":{"index":0},"metallicFactor":0.0,"roughnessFactor":0.9},"alphaMode":"MASK","alphaCutoff":0.5,"doubleSided":true}],"#,
                r#""accessors":[{"bufferView":0,"byteOffset":0,"componentType":5125,"count":3,"type":"SCALAR"},{"bufferView":1,"byteOffset":0,"componentType":5126,"count":3,"type":"VEC3","min":[0.0,-1.0,0.0],"max":[2.0,1.0,1.0]}],"#,
                r#""bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":6,"target":34963},{"buffer":0,"byteOffset":8,"byteLength":36,"byteStride":12}],"#,
                r#""buffers":[{"byteLength":44}],"extensionsUsed":["EXT_mesh_gpu_instancing"],"extensionsRequired":["EXT_mesh_gpu_instancing"]}"#
            )
        );
    }
}
