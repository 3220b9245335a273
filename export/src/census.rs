//! The census of a forest before any file is written: which instances its placements use
//! and how often, counted in one streaming pass, with every transform and mesh checked. The
//! counts fix a file's whole layout (glTF offsets, USD prototypes) before a byte is written.

use sylva_forest::{ForestBuilder, Rect, StreamStats, Variant};
use sylva_instancing::{CompactTree, Similarity};
use sylva_terrain::{HeightField, TerrainMesh};
use sylva_turtle::Vertex;

use crate::error::{ExportError, Invalid};
use crate::spill::TreeSpill;

/// One instance that is drawn: a glTF node with its own instancing accessors, a USD
/// prototype.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Node {
    pub(crate) variant: usize,
    pub(crate) instance: usize,
    /// Its first placement in the file's placement sections, counted in placements: the
    /// placements of all nodes before it.
    pub(crate) first: usize,
    /// Its placements.
    pub(crate) count: usize,
    /// The cell its trees stand in (0 in a file without cells).
    pub(crate) cell: u32,
    /// Whether it places its variant's impostor, once per tree, rather than an instance
    /// (`instance` is then the variant's instance count).
    pub(crate) impostor: bool,
}

/// Placements of every instance of every variant (by variant, then instance), and what
/// streaming the forest would hold: counted on every core without computing a transform
/// ([`ForestBuilder::count_instances_keeping`]), each block's trees kept in `spill` for the
/// writing pass, which checks each transform ([`check_transform`]).
pub(crate) fn count_placements(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    spill: &TreeSpill,
) -> Result<(Vec<Vec<u32>>, StreamStats), ExportError> {
    let keep = |block: usize, trees: &[CompactTree]| -> Result<(), ExportError> {
        Ok(spill.keep(block, trees)?)
    };
    let counted = builder.count_instances_keeping(terrain, region, &keep)?;
    Ok((counted.counts, counted.stats))
}

/// The trees of block `block` (of rectangle `rect`) as the counting pass kept them in
/// `spill`, placed again if it did not.
pub(crate) fn kept_trees(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    spill: &TreeSpill,
    (block, rect): (usize, Rect),
) -> Result<Vec<CompactTree>, ExportError> {
    Ok(spill
        .trees(block)?
        .unwrap_or_else(|| builder.trees(terrain, rect)))
}

/// A placement is a translation, a unit rotation and a positive scale, all finite: what
/// glTF's instancing attributes and USD's point instancer can hold.
pub(crate) fn check_transform(t: &Similarity) -> Result<(), Invalid> {
    if !(t.is_finite() && t.scale > 0.0) || (t.rotation.length() - 1.0).abs() > 1e-3 {
        return Err(Invalid::Transform(*t));
    }
    Ok(())
}

/// The instances a forest draws, as nodes in order, and what they hold.
pub(crate) struct Drawn {
    pub(crate) nodes: Vec<Node>,
    /// Per variant and instance, its node (`u32::MAX`: none).
    pub(crate) node_of: Vec<Vec<u32>>,
    pub(crate) placements: usize,
    /// Placements of instances with no geometry, left out.
    pub(crate) empty_placements: usize,
    /// Branch triangles the placements draw.
    pub(crate) triangles: u64,
}

/// A node for every instance placed at least once that has geometry, its placements laid end
/// to end after the previous node's.
pub(crate) fn drawn_instances(variants: &[Variant], counts: &[Vec<u32>]) -> Drawn {
    let mut drawn = Drawn {
        nodes: Vec::new(),
        node_of: Vec::with_capacity(variants.len()),
        placements: 0,
        empty_placements: 0,
        triangles: 0,
    };
    for (v, variant) in variants.iter().enumerate() {
        let mut map = vec![u32::MAX; variant.cache.instances.len()];
        for (i, inst) in variant.cache.instances.iter().enumerate() {
            let count = counts[v][i] as usize;
            if count == 0 {
                continue;
            }
            if !inst.has_geometry() {
                drawn.empty_placements += count;
                continue;
            }
            map[i] = drawn.nodes.len() as u32;
            drawn.nodes.push(Node {
                variant: v,
                instance: i,
                first: drawn.placements,
                count,
                cell: 0,
                impostor: false,
            });
            drawn.placements += count;
            drawn.triangles += count as u64 * u64::from((inst.bark.count + inst.leaves.count) / 3);
        }
        drawn.node_of.push(map);
    }
    drawn
}

/// Every variant's cache and the terrain mesh, if any, checked as [`check_mesh`] does, and
/// every instance's spans within its cache's indices.
pub(crate) fn check_geometry(
    variants: &[Variant],
    terrain_mesh: Option<&TerrainMesh>,
) -> Result<(), ExportError> {
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
            return Err(Invalid::InstanceSpan.into());
        }
    }
    Ok(())
}

/// Every vertex finite with a unit normal, every index in range.
pub(crate) fn check_mesh<'a>(
    vertices: impl ExactSizeIterator<Item = (&'a [f32; 3], &'a [f32; 3])>,
    indices: impl IntoIterator<Item = &'a u32>,
) -> Result<(), ExportError> {
    let n = vertices.len() as u32;
    for (p, normal) in vertices {
        if !p.iter().all(|c| c.is_finite()) {
            return Err(Invalid::VertexPosition.into());
        }
        let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        if !(len - 1.0).abs().lt(&1e-3) {
            return Err(Invalid::Normal(*normal).into());
        }
    }
    if indices.into_iter().any(|&i| i >= n) {
        return Err(Invalid::Index.into());
    }
    Ok(())
}
