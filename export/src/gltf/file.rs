//! Writing a laid-out GLB: the header and JSON chunk, the geometry and textures, then the
//! placements from one streaming pass, each instance's buffered and put at its offsets.

use std::path::Path;

use sylva_base::file::AtomicFile;
use sylva_forest::{ForestBuilder, PlacementBlock, Rect, tree_tint, tree_wind};
use sylva_terrain::{HeightField, TerrainMesh};

use super::builder::padding;
use super::document::Document;
use super::indices::IndexWidth;
use super::placement_words::{self, PLACEMENT_BYTES, SECTION_WORDS};
use super::shared::put_tree_sections;
use super::{Node, NodeLookup, glb_header};
use crate::census::{check_transform, kept_trees};
use crate::error::{ExportError, Invalid};
use crate::spill::TreeSpill;

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
    // Each buffer is padded to a whole number of 4-byte words, as the layout reserved it.
    let mut put = |w: &mut AtomicFile, bytes: &[u8]| -> Result<(), ExportError> {
        w.put(bytes)?;
        w.put(&[0; 3][..padding(bytes.len())])?;
        written += bytes.len() + padding(bytes.len());
        Ok(())
    };
    if let Some(t) = terrain {
        put(w, bytemuck::cast_slice(&t.vertices))?;
        put(
            w,
            &IndexWidth::for_vertices(t.vertices.len()).encode(&t.indices),
        )?;
        put(w, bytemuck::cast_slice(&document.terrain_colours))?;
    }
    for subset in &document.embedded {
        let sections = (&subset.bark[..], &subset.leaves[..]);
        put_tree_sections(document.layout, &subset.vertices, sections, |bytes| {
            put(w, bytes)
        })?;
    }
    for image in document.images.iter() {
        put(w, image)?;
    }
    debug_assert_eq!(written, document.placement_base);
    Ok(())
}

/// Placement bytes put between requests that the disk catch up
/// ([`AtomicFile::start_writeback`]).
const WRITEBACK_BYTES: usize = 128 << 20;

/// One node's placements not yet written, section by section, and how many it has written.
#[derive(Debug, Default)]
struct NodeBuffer {
    sections: [Vec<u32>; 5],
    written: usize,
}

/// A block's placements as the file holds them, grouped by node: the runs `(node, count)` in
/// ascending node order (each node's placements in the forest's order), and their words
/// section by section in the same order.
#[derive(Debug, Default)]
struct BlockRuns {
    runs: Vec<(u32, u32)>,
    sections: [Vec<u32>; 5],
}

/// What one placement in the file places: a placement of the block, or a tree's impostor.
#[derive(Debug, Clone, Copy)]
enum Placed {
    Instance(u32),
    Impostor(u32),
}

/// Every placement of `block` with its node: its instances' placements and, in a file with
/// impostors, each canopy tree's impostor; `u32::MAX` for instances the file leaves out.
fn block_nodes(
    block: &PlacementBlock,
    lookup: NodeLookup<'_>,
) -> Result<Vec<(u32, Placed)>, Invalid> {
    let mut out = Vec::with_capacity(block.placements.len());
    match lookup {
        NodeLookup::Flat(node_of) => {
            for (k, p) in block.placements.iter().enumerate() {
                check_transform(&p.transform)?;
                let node = node_of
                    .get(p.variant as usize)
                    .and_then(|v| v.get(p.instance as usize))
                    .copied()
                    .ok_or(Invalid::UnknownInstance)?;
                out.push((node, Placed::Instance(k as u32)));
            }
        }
        NodeLookup::Cells(nodes) => {
            let cells: Vec<u32> = block.trees.iter().map(|t| nodes.cell_of(t)).collect();
            for (k, p) in block.placements.iter().enumerate() {
                check_transform(&p.transform)?;
                let &cell = cells.get(p.tree as usize).ok_or(Invalid::UnknownInstance)?;
                let node = nodes
                    .node(cell, p.variant as usize, p.instance as usize)
                    .unwrap_or(u32::MAX);
                out.push((node, Placed::Instance(k as u32)));
            }
            // Each tree of a variant with an impostor places it once, at its root.
            for (t, (tree, &cell)) in block.trees.iter().zip(&cells).enumerate() {
                let Some(node) = nodes.impostor(cell, usize::from(tree.variant)) else {
                    continue;
                };
                check_transform(&tree.root())?;
                out.push((node, Placed::Impostor(t as u32)));
            }
        }
    }
    Ok(out)
}

/// Groups `block`'s placements by node and spells them as the file's words, each transform
/// checked. Tints and wind data are worked out once per tree, not per placement. Runs on the
/// core that placed the block, so the writer only copies whole runs.
fn block_runs(block: PlacementBlock, lookup: NodeLookup<'_>) -> Result<BlockRuns, Invalid> {
    let tints: Vec<[f32; 3]> = block.trees.iter().map(tree_tint).collect();
    let winds: Vec<[f32; 4]> = block.trees.iter().map(tree_wind).collect();
    let mut placed = block_nodes(&block, lookup)?;
    // A stable sort keeps each node's placements in the forest's order.
    placed.sort_by_key(|&(node, _)| node);
    let mut out = BlockRuns {
        runs: Vec::new(),
        sections: SECTION_WORDS.map(|words| Vec::with_capacity(words * placed.len())),
    };
    for &(node, what) in &placed {
        if node == u32::MAX {
            // An instance without geometry: not in the file.
            continue;
        }
        match out.runs.last_mut() {
            Some((n, count)) if *n == node => *count += 1,
            _ => out.runs.push((node, 1)),
        }
        let (x, tree) = match what {
            Placed::Instance(k) => {
                let p = &block.placements[k as usize];
                (p.transform, p.tree as usize)
            }
            Placed::Impostor(t) => (block.trees[t as usize].root(), t as usize),
        };
        let [t, r, s, c, w] = &mut out.sections;
        t.extend(placement_words::floats(&x.translation.to_array()));
        r.extend(placement_words::rotation(x.rotation));
        s.extend(placement_words::floats(&[x.scale; 3]));
        c.extend(placement_words::floats(
            tints.get(tree).unwrap_or(&[1.0; 3]),
        ));
        w.extend(placement_words::wind(
            winds.get(tree).copied().unwrap_or_default(),
            x.translation.to_array(),
        ));
    }
    Ok(out)
}

/// Streams the forest once, from the trees the counting pass kept in `spill`, and writes
/// every placement at its place in the T, R, S, tint and wind sections (which start at file
/// offset `base`). Blocks are expanded and turned into the file's words on every core while
/// the previous wave is written ([`ForestBuilder::stream_map_from`]); each node's placements
/// are buffered and written at their place whenever the node holds its share of
/// `chunk_bytes`, so memory stays within about `chunk_bytes` however many placements there
/// are. Returns the passes over the forest (1).
#[allow(
    clippy::too_many_arguments,
    reason = "one call site; the pieces are all different"
)]
pub(super) fn write_placements(
    w: &mut AtomicFile,
    builder: &ForestBuilder,
    (terrain, region, spill): (&(dyn HeightField + Sync), Rect, &TreeSpill),
    (nodes, lookup): (&[Node], NodeLookup<'_>),
    base: usize,
    total: usize,
    chunk_bytes: usize,
) -> Result<usize, ExportError> {
    let mut section_base = [0usize; 5];
    let mut at = base;
    for (k, words) in SECTION_WORDS.iter().enumerate() {
        section_base[k] = at;
        at += 4 * words * total;
    }
    // Each node's share of the memory, in placements: at least one.
    let flush_at = (chunk_bytes / (PLACEMENT_BYTES * nodes.len().max(1))).max(1);
    let mut buffers: Vec<NodeBuffer> = (0..nodes.len()).map(|_| NodeBuffer::default()).collect();
    // Bytes put since the disk was last asked to catch up.
    let mut unsynced = 0usize;
    let mut flush = |w: &mut AtomicFile, node: &Node, buffer: &mut NodeBuffer| {
        let count = buffer.sections[0].len() / SECTION_WORDS[0];
        for (k, words) in SECTION_WORDS.iter().enumerate() {
            let offset = section_base[k] + 4 * words * (node.first + buffer.written);
            w.put_at(offset as u64, bytemuck::cast_slice(&buffer.sections[k]))?;
            buffer.sections[k].clear();
        }
        buffer.written += count;
        // The disk writes behind the placing, so that the final flush finds little left.
        unsynced += count * PLACEMENT_BYTES;
        if unsynced >= WRITEBACK_BYTES {
            w.start_writeback()?;
            unsynced = 0;
        }
        Ok::<(), ExportError>(())
    };
    let runs = |block: PlacementBlock| block_runs(block, lookup);
    let trees = |block: usize, rect: Rect| kept_trees(builder, terrain, spill, (block, rect));
    builder.stream_map_from(region, &trees, &|_| true, &runs, &mut |runs| {
        let runs = runs?;
        let mut from = [0usize; 5];
        for &(node, count) in &runs.runs {
            let at = from;
            for (k, words) in SECTION_WORDS.iter().enumerate() {
                from[k] += words * count as usize;
            }
            let (Some(buffer), Some(node)) =
                (buffers.get_mut(node as usize), nodes.get(node as usize))
            else {
                continue;
            };
            for k in 0..SECTION_WORDS.len() {
                buffer.sections[k].extend_from_slice(&runs.sections[k][at[k]..from[k]]);
            }
            if buffer.sections[0].len() / SECTION_WORDS[0] >= flush_at {
                flush(w, node, buffer)?;
            }
        }
        Ok(())
    })?;
    for (node, buffer) in nodes.iter().zip(&mut buffers) {
        flush(w, node, buffer)?;
        if buffer.written != node.count {
            return Err(Invalid::Layout {
                written: buffer.written as u64,
                layout: node.count as u64,
            }
            .into());
        }
    }
    Ok(1)
}
