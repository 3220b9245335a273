//! A forest file's node tree when its trees are in cells: a node per cell, under it a node
//! per variant, and under that the variant's instanced nodes. With levels of detail, each
//! variant's node declares `MSFT_lod`: its coarser levels are nodes outside the scene over
//! the same instancing accessors (the same placements, coarser meshes), and
//! `extras.MSFT_screencoverage` says when each is drawn. `extras.sylva_levels` gives the same
//! as distances, for clients that pick a level per tree, and names the impostor's node (its
//! cards placed once per tree), also outside the scene.
//!
//! The impostor is not one of MSFT_lod's levels: Babylon.js 9.28, which reads MSFT_lod to
//! load the levels one after another (ending at full detail), never finishes loading a file
//! whose coarsest level is the impostor's instanced cards (with the mesh levels alone it
//! loads at once); and a level that places trees rather than branches is not a coarser copy
//! of its node, as MSFT_lod's levels are.

use std::collections::HashMap;

use serde_json::json;
use sylva_forest::ForestBuilder;
use sylva_instancing::Span;

use super::builder::DocumentBuilder;
use super::cells::CellGrid;
use super::layer::{VariantLayout, instance_primitives};
use super::levels::ForestLevels;
use super::placement_words::{SECTION_ACCESSORS, SECTION_WORDS};
use super::schema::{LevelsOfDetail, Node as JsonNode, NodeExtensions};
use crate::census::Node;

/// The meshes made so far, by variant, layer and instance (`None`: it draws nothing there).
type MeshCache = HashMap<(usize, usize, usize), Option<usize>>;

/// How a file's nodes are grouped: its cells and, when it has them, its levels.
#[derive(Debug, Clone, Copy)]
pub(super) struct Grouping<'a> {
    pub(super) grid: &'a CellGrid,
    pub(super) levels: Option<&'a ForestLevels>,
}

/// Every variant's layers: their layouts (the cache at each level, then the impostor's
/// cards) and where an instance's triangles sit in a layer.
pub(super) struct Layers<'a> {
    pub(super) layouts: &'a [Vec<VariantLayout>],
    pub(super) spans: &'a dyn Fn(usize, usize, usize) -> Option<(Span, Span)>,
}

/// The screen's vertical field of view, radians, for a screen of `pixels_per_radian` 1080
/// rows high: what `MSFT_screencoverage`'s shares of the screen are worked out on.
fn field_of_view(pixels_per_radian: f32) -> f32 {
    1080.0 / pixels_per_radian.max(1e-3)
}

/// Lays out the nodes of `nodes` (by cell, then variant; each variant's impostor last)
/// grouped by cell and variant, with their instancing accessors in `sections`.
pub(super) fn lay_out_groups(
    d: &mut DocumentBuilder,
    builder: &ForestBuilder,
    nodes: &[Node],
    grouping: Grouping<'_>,
    layers: &Layers<'_>,
    sections: [usize; 5],
) {
    let mut meshes: MeshCache = HashMap::new();
    let mut cells: Vec<(u32, Vec<usize>)> = Vec::new();
    let mut start = 0;
    while start < nodes.len() {
        let (cell, variant) = (nodes[start].cell, nodes[start].variant);
        let end = start
            + nodes[start..]
                .iter()
                .take_while(|n| n.cell == cell && n.variant == variant)
                .count();
        let group = lay_out_group(
            d,
            builder,
            &nodes[start..end],
            grouping,
            layers,
            (sections, &mut meshes),
        );
        match cells.last_mut() {
            Some((c, groups)) if *c == cell => groups.push(group),
            _ => cells.push((cell, vec![group])),
        }
        start = end;
    }
    for (cell, groups) in cells {
        let place = grouping.grid.cell(cell);
        let kind = if place.seedlings {
            "seedling cell"
        } else {
            "cell"
        };
        d.root.nodes.push(JsonNode {
            name: Some(format!("{kind} {} {}", place.column, place.row)),
            children: groups,
            extras: Some(json!({ "sylva_cell": {
                "column": place.column,
                "row": place.row,
                "min": place.rect.min.to_array(),
                "max": place.rect.max.to_array(),
                "seedlings": place.seedlings,
            }})),
            ..JsonNode::default()
        });
    }
}

/// One variant's nodes in one cell: its node at full detail, whose children are the
/// instanced nodes, and with levels the nodes of its coarser levels (named by `MSFT_lod`)
/// and its impostor (named by `extras.sylva_levels`). Returns the node at full detail.
fn lay_out_group(
    d: &mut DocumentBuilder,
    builder: &ForestBuilder,
    run: &[Node],
    grouping: Grouping<'_>,
    layers: &Layers<'_>,
    (sections, meshes): ([usize; 5], &mut MeshCache),
) -> usize {
    let variant = run[0].variant;
    let cell = grouping.grid.cell(run[0].cell);
    let v = &builder.variants()[variant];
    let species = &builder.config().species[v.species].name;
    let form = if v.seedling { "seedling" } else { "tree" };
    let place = format!("{species} {form}, cell {} {}", cell.column, cell.row);
    let levels = grouping.levels.and_then(|l| l.variants.get(variant));
    let mesh_levels = levels.map_or(1, |l| l.mesh_levels());
    let mut level_nodes: Vec<Vec<usize>> = vec![Vec::new(); mesh_levels];
    let mut impostor = None;
    for node in run {
        let accessors = instancing_accessors(d, node, sections);
        if node.impostor {
            let Some(mesh) = layer_mesh(d, meshes, layers, (variant, mesh_levels, 0), || {
                format!("{species} {form} impostor")
            }) else {
                continue;
            };
            d.instanced_node(format!("{place} impostors"), mesh, accessors.0, accessors.1);
            impostor = Some(d.root.nodes.len() - 1);
            d.outside_scene.extend(impostor);
            continue;
        }
        let inst = &v.cache.instances[node.instance];
        for (k, nodes_at) in level_nodes.iter_mut().enumerate() {
            let key = (variant, k, node.instance);
            let lod = if k == 0 {
                String::new()
            } else {
                format!(" LOD{k}")
            };
            let Some(mesh) = layer_mesh(d, meshes, layers, key, || {
                format!(
                    "{species} {form} branch {} age {} #{}{lod}",
                    inst.id, inst.age, node.instance
                )
            }) else {
                continue;
            };
            let name = format!("{species} {form} instance {}{lod}", node.instance);
            d.instanced_node(name, mesh, accessors.0, accessors.1);
            nodes_at.push(d.root.nodes.len() - 1);
            if k > 0 {
                // The full level's node says the wind's reach; its levels share its data.
                if let Some(n) = d.root.nodes.last_mut() {
                    n.extras = None;
                }
            }
        }
    }
    let mut coarser: Vec<usize> = Vec::new();
    for (k, children) in level_nodes.iter().enumerate().skip(1) {
        d.root.nodes.push(JsonNode {
            name: Some(format!("{place} LOD{k}")),
            children: children.clone(),
            ..JsonNode::default()
        });
        coarser.push(d.root.nodes.len() - 1);
    }
    let extras = grouping.levels.zip(levels).map(|(forest, levels)| {
        // A group's share of the screen when its nearest tree is `d` away: its bounding
        // sphere (the cell's) seen from its centre, about half a cell's diagonal farther.
        let radius = 0.5 * (cell.rect.max - cell.rect.min).length();
        let fov = field_of_view(forest.chain.pixels_per_radian);
        let coverage = |d: f32| (2.0 * radius / ((d + radius) * fov)).min(1.0);
        // A share per mesh level; the last says where nothing is drawn: seedling forms past
        // their reach, never for canopy trees (a client that reads MSFT_lod but not the
        // impostor keeps the coarsest mesh).
        let mut screen: Vec<f32> = levels.from[..coarser.len()]
            .iter()
            .map(|&d| coverage(d))
            .collect();
        screen.push(levels.reach.map_or(0.0, coverage));
        json!({
            "MSFT_screencoverage": screen,
            "sylva_levels": {
                "from": levels.from,
                "reach": levels.reach,
                "impostor": impostor,
                "pixel_error": forest.chain.pixel_error,
                "pixels_per_radian": forest.chain.pixels_per_radian,
                "fade": forest.chain.fade,
            },
        })
    });
    d.root.nodes.push(JsonNode {
        name: Some(place),
        children: level_nodes.swap_remove(0),
        extensions: (!coarser.is_empty()).then_some(NodeExtensions {
            gpu_instancing: None,
            lod: Some(LevelsOfDetail { ids: coarser }),
        }),
        extras,
        ..JsonNode::default()
    });
    d.root.nodes.len() - 1
}

/// The instancing accessors of `node`'s placements: translation, rotation, scale and tint,
/// and its wind.
fn instancing_accessors(
    d: &mut DocumentBuilder,
    node: &Node,
    sections: [usize; 5],
) -> ([usize; 4], Option<usize>) {
    let [t, r, s, c, w] = [0, 1, 2, 3, 4].map(|k| {
        let (component, kind, normalized) = SECTION_ACCESSORS[k];
        let at = 4 * SECTION_WORDS[k] * node.first;
        let a = d.accessor(sections[k], at, component, node.count, kind);
        d.root.accessors[a].normalized = normalized;
        a
    });
    ([t, r, s, c], Some(w))
}

/// The mesh of instance `instance` of `variant` at layer `layer`, made the first time it is
/// asked for (named by `name`); `None` when it draws nothing there.
fn layer_mesh(
    d: &mut DocumentBuilder,
    meshes: &mut MeshCache,
    layers: &Layers<'_>,
    (variant, layer, instance): (usize, usize, usize),
    name: impl FnOnce() -> String,
) -> Option<usize> {
    *meshes.entry((variant, layer, instance)).or_insert_with(|| {
        let layout = layers.layouts.get(variant)?.get(layer)?;
        let spans = (layers.spans)(variant, layer, instance)?;
        let primitives = instance_primitives(d, spans, layout);
        (!primitives.is_empty()).then(|| d.mesh(name(), primitives))
    })
}
