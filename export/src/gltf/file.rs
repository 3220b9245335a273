//! Writing a laid-out GLB: the header and JSON chunk, the geometry and textures, then the
//! placements chunk by chunk, each chunk gathered from one streaming pass.

use std::path::Path;

use sylva_base::file::AtomicFile;
use sylva_forest::{ForestBuilder, PlacementBlock, Rect, tree_tint, tree_wind};
use sylva_terrain::{HeightField, TerrainMesh};

use super::builder::padding;
use super::document::Document;
use super::extras::vertex_extras;
use super::{Node, PLACEMENT_BYTES, glb_header};
use crate::error::{ExportError, Invalid};

/// Writes `path` whole or not at all: the GLB header, the JSON chunk and the BIN chunk
/// header, then the binary content by `body`; returns what `body` returns.
pub(super) fn write_file(
    path: &Path,
    document: &Document,
    body: impl FnOnce(&mut AtomicFile) -> Result<usize, ExportError>,
) -> Result<usize, ExportError> {
    let header = glb_header(
        document.total,
        &document.json,
        (document.bin_len > 0).then_some(document.bin_len),
    )?;
    let mut w = AtomicFile::create(path)?;
    w.put(&header)?;
    let passes = body(&mut w)?;
    let end = w.size()?;
    if end != document.total as u64 {
        return Err(Invalid::Layout {
            written: end,
            layout: document.total as u64,
        }
        .into());
    }
    w.commit()?;
    Ok(passes)
}

/// Terrain and cache buffers (the parts of the caches the file embeds), in layout order,
/// each padded to 4 bytes.
pub(super) fn write_geometry(
    w: &mut AtomicFile,
    terrain: Option<&TerrainMesh>,
    document: &Document,
) -> Result<(), ExportError> {
    let mut written = 0usize;
    let mut put = |w: &mut AtomicFile, bytes: &[u8]| -> Result<(), ExportError> {
        w.put(bytes)?;
        written += bytes.len();
        Ok(())
    };
    if let Some(t) = terrain {
        put(w, bytemuck::cast_slice(&t.vertices))?;
        put(w, bytemuck::cast_slice(&t.indices))?;
        put(w, bytemuck::cast_slice(&document.terrain_colours))?;
    }
    for subset in &document.embedded {
        put(w, bytemuck::cast_slice(&subset.vertices))?;
        put(
            w,
            bytemuck::cast_slice(&vertex_extras(
                &subset.vertices,
                &subset.bark,
                &subset.leaves,
            )),
        )?;
        put(w, bytemuck::cast_slice(&subset.bark))?;
        put(w, bytemuck::cast_slice(&subset.leaves))?;
    }
    // Every buffer above is a whole number of 4-byte words; images are padded to one.
    for image in document.images.iter() {
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
pub(super) fn write_placements(
    w: &mut AtomicFile,
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    nodes: &[Node],
    node_of: &[Vec<u32>],
    base: usize,
    total: usize,
    chunk_bytes: usize,
) -> Result<usize, ExportError> {
    let (t_base, r_base, s_base, c_base, w_base) = (
        base,
        base + 12 * total,
        base + 28 * total,
        base + 40 * total,
        base + 52 * total,
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
        let mut wind = vec![0f32; 4 * count];
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
                let tree = block.trees.get(p.tree as usize);
                c[3 * *k..3 * *k + 3].copy_from_slice(&tree.map_or([1.0; 3], tree_tint));
                wind[4 * *k..4 * *k + 4].copy_from_slice(&tree.map_or([0.0; 4], tree_wind));
                *k += 1;
            }
            Ok(())
        })?;
        for (section, data, width) in [
            (t_base, &t, 12),
            (r_base, &r, 16),
            (s_base, &s, 12),
            (c_base, &c, 12),
            (w_base, &wind, 16),
        ] {
            w.put_at((section + first * width) as u64, bytemuck::cast_slice(data))?;
        }
        passes += 1;
        start = end;
    }
    Ok(passes)
}
