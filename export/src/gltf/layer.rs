//! A layer of a forest file's geometry: a used variant's cache at one level of detail, or
//! its impostor's cards, with the views, attributes and materials its instances' meshes
//! share; and an instance's primitives over it.

use sylva_instancing::Span;
use sylva_turtle::Vertex;

use super::ARRAY_BUFFER;
use super::builder::{DocumentBuilder, TreeViews};
use super::extras::VertexLayout;
use super::indices::IndexWidth;
use super::schema::{Attributes, Primitive};

/// A layer's views, attributes and materials, which its instances' meshes share: a used
/// variant's cache at one level of detail, or its impostor's cards.
#[derive(Debug, Clone, Copy)]
pub(super) struct VariantLayout {
    attributes: Attributes,
    views: TreeViews,
    /// The width of its indices, by its vertex count.
    width: IndexWidth,
    bark_material: usize,
    leaf_material: usize,
}

/// The views of a layer's four buffers (`vertices` and the lengths of the sections for
/// them, its extras and its bark and leaf indices) in `buffer` at `at`, its attributes, and
/// the bark and leaf materials it is drawn with.
pub(super) fn lay_out_variant(
    d: &mut DocumentBuilder,
    (vertices, lengths, layout): (&[Vertex], [usize; 4], VertexLayout),
    (buffer, at): (usize, [usize; 4]),
    (bark_material, leaf_material): (usize, usize),
) -> VariantLayout {
    let [vbytes, ebytes, bbytes, lbytes] = lengths;
    let stride = layout.vertex_bytes() as u32;
    let views = TreeViews {
        vertices: d.view_in(buffer, at[0], vbytes, Some(stride), Some(ARRAY_BUFFER)),
        extras: d.view_in(
            buffer,
            at[1],
            ebytes,
            Some(layout.extras_bytes() as u32),
            Some(ARRAY_BUFFER),
        ),
        bark: d.index_view(buffer, at[2], bbytes),
        leaves: d.index_view(buffer, at[3], lbytes),
    };
    let attributes = d.tree_attributes(views, vertices.iter().map(|v| v.position), layout);
    VariantLayout {
        attributes,
        views,
        width: IndexWidth::for_vertices(vertices.len()),
        bark_material,
        leaf_material,
    }
}

/// The bark and leaf primitives of an instance whose triangles sit at `spans` (bark, leaves)
/// in its variant's views.
pub(super) fn instance_primitives(
    d: &mut DocumentBuilder,
    (bark, leaves): (Span, Span),
    shared: &VariantLayout,
) -> Vec<Primitive> {
    let mut primitives = Vec::new();
    for (view, span, material) in [
        (shared.views.bark, bark, shared.bark_material),
        (shared.views.leaves, leaves, shared.leaf_material),
    ] {
        if let (Some(view), false) = (view, span.is_empty()) {
            let width = shared.width;
            let at = span.start as usize * width.bytes();
            let indices = d.indices(view, at, (width, span.count as usize));
            primitives.push(Primitive {
                attributes: shared.attributes,
                indices: Some(indices),
                material,
            });
        }
    }
    primitives
}
