//! The streamed GLB's layout, decided before any byte is written: the JSON chunk and the
//! offset of every section of the BIN chunk.

use std::sync::Arc;

use sylva_forest::ForestBuilder;
use sylva_instancing::{Similarity, Span};
use sylva_terrain::TerrainMesh;

use super::builder::DocumentBuilder;
use super::extras::VertexLayout;
use super::groups::{Grouping, Layers, lay_out_groups};
use super::indices::IndexWidth;
use super::layer::{VariantLayout, instance_primitives, lay_out_variant};
use super::levels::{CARDS_CUTOFF, VariantLevels};
use super::placement_words::{SECTION_ACCESSORS, SECTION_WORDS};
use super::schema::{Buffer, Node as JsonNode};
use super::shared::{SHARED_LAYOUT, SharedLayout, TextureSet, section_lengths};
use super::subset::CacheSubset;
use super::{ARRAY_BUFFER, GltfOptions, Node};
use crate::error::ExportError;

/// The JSON chunk and the binary layout, decided before any byte is written.
#[derive(Debug)]
pub(super) struct Document {
    pub(super) json: String,
    /// The parts of the variants' caches this file embeds, in layout order (none when the
    /// geometry is shared).
    pub(super) embedded: Vec<CacheSubset>,
    /// The leaf textures as PNG, in layout order after the cache buffers.
    pub(super) images: Arc<Vec<Vec<u8>>>,
    /// The terrain's ground colours, after its indices.
    pub(super) terrain_colours: Vec<[f32; 3]>,
    /// How its tree vertices are laid out.
    pub(super) layout: VertexLayout,
    /// Offset in the BIN chunk where the placement sections start.
    pub(super) placement_base: usize,
    pub(super) bin_len: usize,
    pub(super) total: usize,
}

/// The terrain's sections (vertices, indices, ground colours), material, mesh and node; returns
/// the ground colours, which the writer puts after the indices.
fn lay_out_terrain(
    d: &mut DocumentBuilder,
    t: &TerrainMesh,
    snow: f32,
    options: &GltfOptions,
) -> Vec<[f32; 3]> {
    let vbytes = size_of_val(t.vertices.as_slice());
    let vertices = d.view(vbytes, Some(32), Some(ARRAY_BUFFER));
    let width = IndexWidth::for_vertices(t.vertices.len());
    let ibytes = width.bytes() * t.indices.len();
    let at = d.reserve(ibytes);
    let indices = d.index_view(0, at, ibytes);
    let terrain_colours = t.ground_colours_under_snow(snow);
    let colours = d.view(12 * terrain_colours.len(), None, Some(ARRAY_BUFFER));
    let material = d.material(
        "terrain".into(),
        options.terrain_colour,
        options.roughness,
        (None, None),
        None,
    );
    d.terrain(
        vertices,
        t.vertices.iter().map(|v| v.position),
        (indices, (width, t.indices.len())),
        (colours, terrain_colours.len()),
        material,
    );
    terrain_colours
}

/// How an instance's placements are written: as instancing accessors into the placement
/// sections (translation, rotation, scale, tint, wind), or as a node each.
#[derive(Debug, Clone, Copy)]
enum Placed<'a> {
    Instanced([usize; 5]),
    Nodes(&'a [Similarity]),
}

/// An instance's mesh (its bark and leaf primitives over its variant's views, at `spans` in
/// them) and the node or nodes that place it.
fn lay_out_node(
    d: &mut DocumentBuilder,
    builder: &ForestBuilder,
    node: &Node,
    (layout, spans): (&VariantLayout, (Span, Span)),
    placed: Placed,
) {
    let variant = &builder.variants()[node.variant];
    let inst = &variant.cache.instances[node.instance];
    let primitives = instance_primitives(d, spans, layout);
    let name = &builder.config().species[variant.species].name;
    let tag = if variant.seedling { "seedling" } else { "tree" };
    match placed {
        Placed::Nodes(transforms) => {
            let name = format!("{name} {tag} branch {} age {}", inst.id, inst.age);
            let mesh = d.mesh(name, primitives);
            for x in transforms {
                d.root.nodes.push(JsonNode {
                    mesh: Some(mesh),
                    translation: Some(x.translation.to_array()),
                    rotation: Some(x.rotation.normalize().to_array()),
                    scale: Some([x.scale; 3]),
                    ..JsonNode::default()
                });
            }
        }
        Placed::Instanced(sections) => {
            let mesh_name = format!(
                "{name} {tag} branch {} age {} #{}",
                inst.id, inst.age, node.instance
            );
            let mesh = d.mesh(mesh_name, primitives);
            let [t, r, s, c, w] = [0, 1, 2, 3, 4].map(|k| {
                let (component, kind, normalized) = SECTION_ACCESSORS[k];
                let at = 4 * SECTION_WORDS[k] * node.first;
                let a = d.accessor(sections[k], at, component, node.count, kind);
                d.root.accessors[a].normalized = normalized;
                a
            });
            let name = format!("{name} {tag} instance {}", node.instance);
            d.instanced_node(name, mesh, [t, r, s, c], Some(w));
        }
    }
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
    /// no placement sections. With `grouping`, the nodes are gathered under a node per cell
    /// and variant (with the variant's coarser levels and impostor, when it has levels).
    pub(super) fn lay_out(
        builder: &ForestBuilder,
        terrain: Option<&TerrainMesh>,
        options: &GltfOptions,
        (nodes, placements): (&[Node], usize),
        one_node_each: Option<&[Vec<Similarity>]>,
        grouping: Option<Grouping<'_>>,
    ) -> Result<Document, ExportError> {
        let variants = builder.variants();
        let species = &builder.config().species;
        let levels = grouping.and_then(|g| g.levels);
        let mut d = DocumentBuilder::default();
        let terrain_colours = terrain.map_or_else(Vec::new, |t| {
            lay_out_terrain(&mut d, t, crate::phenology::snow_lying(builder), options)
        });
        // Instanced files quantize their normals, as the files shared with them do; the
        // fallback of a node per placement is for importers without instancing (Godot 4),
        // which read no quantization either.
        let layout = match (&options.shared_geometry, one_node_each) {
            (Some(_), _) => SHARED_LAYOUT,
            (None, Some(_)) => VertexLayout::Float,
            (None, None) => VertexLayout::Quantized,
        };
        let mut used_variants: Vec<usize> = nodes.iter().map(|n| n.variant).collect();
        used_variants.sort_unstable();
        used_variants.dedup();
        // Geometry shared with other files (tiles of one world) lives in buffer 1, laid out
        // for every variant and texture of the world; otherwise the used variants' buffers
        // and textures follow the terrain in this file.
        let shared_layout = options
            .shared_geometry
            .as_ref()
            .map(|uri| (uri, SharedLayout::of(builder)));
        let textures = match &shared_layout {
            Some((_, layout)) => layout.textures.clone(),
            None => TextureSet::of(used_variants.iter().map(|&v| &species[variants[v].species])),
        };
        // Images are embedded only when nothing is shared (the shared file holds them); the
        // impostors' card textures follow the species' textures.
        let species_images = textures.images();
        let mut impostor_texture: Vec<Option<usize>> = vec![None; variants.len()];
        let images: Arc<Vec<Vec<u8>>> = match (&shared_layout, levels) {
            (Some(_), _) => Arc::default(),
            (None, None) => species_images.clone(),
            (None, Some(levels)) => {
                let mut all = species_images.as_ref().clone();
                for &v in &used_variants {
                    if let Some((_, png)) = &levels.variants[v].cards {
                        impostor_texture[v] = Some(all.len());
                        all.push(png.clone());
                    }
                }
                Arc::new(all)
            }
        };
        // Per variant, its layers: the cache at each level (the full one first), then the
        // impostor's cards. A file of its own embeds of each only the instances its nodes
        // place and the vertices they reference.
        let mut used: Vec<Vec<usize>> = vec![Vec::new(); variants.len()];
        for n in nodes.iter().filter(|n| !n.impostor) {
            used[n.variant].push(n.instance);
        }
        let mut subsets: Vec<Vec<CacheSubset>> = vec![Vec::new(); variants.len()];
        if shared_layout.is_none() {
            for &v in &used_variants {
                subsets[v] =
                    variant_layers(&variants[v].cache, levels.map(|l| &l.variants[v]), &used[v]);
            }
        }
        let mut shared: Vec<Vec<VariantLayout>> = vec![Vec::new(); variants.len()];
        for &v in &used_variants {
            let c = &variants[v].cache;
            let s = &species[variants[v].species];
            let materials = d.species_materials(s, options.roughness, textures.of_species(s));
            if let Some((_, shared_file)) = &shared_layout {
                let at = shared_file.variants[v];
                let lengths = section_lengths(layout, &c.vertices, &c.bark, &c.leaves);
                let at = (1, [at.vertices, at.extras, at.bark, at.leaves]);
                let geometry = (c.vertices.as_slice(), lengths, layout);
                shared[v].push(lay_out_variant(&mut d, geometry, at, materials));
                continue;
            }
            let meshes = levels.map_or(1, |l| l.variants[v].mesh_levels());
            for (k, subset) in subsets[v].iter().enumerate() {
                let materials = match impostor_texture[v] {
                    Some(texture) if k == meshes => {
                        let name = format!("{} impostor", s.name);
                        let cards = d.card_material(name, texture, CARDS_CUTOFF);
                        (cards, cards)
                    }
                    _ => materials,
                };
                let lengths = subset.section_lengths(layout);
                let at = (0, lengths.map(|len| d.reserve(len)));
                let geometry = (subset.vertices.as_slice(), lengths, layout);
                shared[v].push(lay_out_variant(&mut d, geometry, at, materials));
            }
        }
        let image_views: Vec<usize> = match &shared_layout {
            Some((_, layout)) => layout
                .images
                .iter()
                .map(|&(at, len)| d.view_in(1, at, len, None, None))
                .collect(),
            None => images
                .iter()
                .map(|image| d.view(image.len(), None, None))
                .collect(),
        };
        let placement_base = d.bin_len;
        // The placement sections (translation, rotation, scale, tint, wind), none when every
        // placement is a node of its own.
        let sections = if one_node_each.is_some() {
            [0; 5]
        } else {
            SECTION_WORDS.map(|words| d.view(4 * words * placements, None, None))
        };
        let bin_len = d.bin_len;
        let spans = |variant: usize, layer: usize, instance: usize| -> Option<(Span, Span)> {
            match subsets[variant].get(layer) {
                Some(subset) => subset.spans(instance),
                None => variants[variant]
                    .cache
                    .instances
                    .get(instance)
                    .map(|i| (i.bark, i.leaves)),
            }
        };
        match grouping {
            Some(grouping) => {
                let layers = Layers {
                    layouts: &shared,
                    spans: &spans,
                };
                lay_out_groups(&mut d, builder, nodes, grouping, &layers, sections);
            }
            None => {
                for (k, node) in nodes.iter().enumerate() {
                    let Some(layout) = shared[node.variant].first() else {
                        continue;
                    };
                    let Some(spans) = spans(node.variant, 0, node.instance) else {
                        continue;
                    };
                    let placed = match one_node_each {
                        Some(each) => Placed::Nodes(each.get(k).map_or(&[], Vec::as_slice)),
                        None => Placed::Instanced(sections),
                    };
                    lay_out_node(&mut d, builder, node, (layout, spans), placed);
                }
            }
        }
        // Leaf shapes and impostor cards clamp at their edges; bark tiles.
        let (first_bark, species_count) = (textures.first_bark(), species_images.len());
        d.images(
            image_views
                .iter()
                .enumerate()
                .map(|(k, &v)| (v, (first_bark..species_count).contains(&k))),
        );
        match &shared_layout {
            Some((uri, layout)) => {
                d.own_buffer(4);
                d.root.buffers.push(Buffer {
                    uri: Some(uri.to_string()),
                    byte_length: layout.len,
                });
            }
            None => d.own_buffer(0),
        }
        let json = d.into_json()?;
        let bin_chunk = if bin_len > 0 { 8 + bin_len } else { 0 };
        Ok(Document {
            total: 12 + 8 + json.len() + bin_chunk,
            json,
            embedded: subsets.into_iter().flatten().collect(),
            images,
            terrain_colours,
            layout,
            placement_base,
            bin_len,
        })
    }
}

/// The layers a file embeds of one variant for instances `used`: its cache, then with
/// `levels` each coarser level of it and the impostor's cards (a layer of one instance, 0).
fn variant_layers(
    cache: &sylva_instancing::InstanceCache,
    levels: Option<&VariantLevels>,
    used: &[usize],
) -> Vec<CacheSubset> {
    let mut out = vec![CacheSubset::of(cache, used)];
    let Some(levels) = levels else {
        return out;
    };
    let lods = &levels.lods.cache;
    for level in lods.levels.iter().skip(1) {
        out.push(CacheSubset::of_parts(
            &lods.vertices,
            (&level.bark, &level.leaves),
            &level.spans,
            used,
        ));
    }
    if let Some((cards, _)) = &levels.cards {
        let whole = Span::new(0, cards.leaves.len() as u32);
        out.push(CacheSubset::of_parts(
            &cards.vertices,
            (&[], &cards.leaves),
            &[(Span::new(0, 0), whole)],
            &[0],
        ));
    }
    out
}
