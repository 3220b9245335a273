//! Whole-tree proxies for coarse tiles: per variant a trunk and a crown of a few dozen
//! triangles, sized from the variant's cached geometry, so that a far tree costs 76
//! triangles instead of thousands.

use glam::Vec3;
use sylva_turtle::{Frame, GeometrySink, Mesh, MeshBuilder, Segment, TurtleOptions};

use crate::forest::Variant;

/// A variant's size: height of its geometry and the horizontal radius of its crown.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// Height of the variant's geometry above its root, metres (unscaled).
    pub height: f32,
    /// Horizontal radius of its crown, metres (unscaled).
    pub crown: f32,
}

impl Extent {
    /// The extent of a variant's cached geometry (its largest hero).
    pub fn of(variant: &Variant) -> Extent {
        let (mut height, mut crown) = (0.0f32, 0.0f32);
        for v in &variant.cache.vertices {
            let [x, y, z] = v.position;
            height = height.max(y);
            crown = crown.max((x * x + z * z).sqrt());
        }
        Extent {
            height: height.max(0.5),
            crown: crown.max(0.3),
        }
    }
}

/// The whole-tree proxy of a tree of `extent`, as coarse tiles and the viewer's far trees
/// draw it: a six-sided trunk to 40% of its height (bark, in the mesh's bark triangles) and an
/// ellipsoid crown of 64 triangles from 30% to the top (in its leaf triangles), 76 triangles
/// in all.
///
/// ```
/// use sylva_forest::{Extent, tree_proxy};
/// let m = tree_proxy(Extent { height: 12.0, crown: 4.0 });
/// assert_eq!(m.triangle_count(), 76);
/// ```
pub fn tree_proxy(extent: Extent) -> Mesh {
    let h = extent.height;
    let mut options = TurtleOptions::default();
    options.radial_segments = 6;
    let mut builder = MeshBuilder::new(&options);
    let radius = (h * 0.015).clamp(0.03, 0.5);
    builder.begin();
    builder.segment(&Segment {
        id: 0,
        parent: None,
        continues_parent: false,
        frame: Frame::IDENTITY,
        length: h * 0.4,
        start_radius: radius,
        end_radius: radius * 0.7,
        depth: 0,
    });
    builder.axis_end(0);
    builder.end();
    let mut mesh = builder.finish();
    // The crown: rings of 8 around an ellipsoid, 4 bands, closed by two fans.
    let (centre, vertical, horizontal) = (Vec3::Y * (h * 0.65), h * 0.35, extent.crown);
    let first = mesh.vertices.len() as u32;
    let (bands, around) = (4u32, 8u32);
    let point = |band: u32, k: u32| {
        let phi = std::f32::consts::PI * band as f32 / bands as f32;
        let theta = std::f32::consts::TAU * k as f32 / around as f32;
        let d = Vec3::new(phi.sin() * theta.cos(), phi.cos(), phi.sin() * theta.sin());
        (
            centre + Vec3::new(d.x * horizontal, d.y * vertical, d.z * horizontal),
            d,
        )
    };
    for band in 0..=bands {
        for k in 0..around {
            let (p, d) = point(band, k);
            mesh.vertices.push(sylva_turtle::Vertex {
                position: p.to_array(),
                normal: d.normalize_or(Vec3::Y).to_array(),
                uv: [k as f32 / around as f32, band as f32 / bands as f32],
                wind: [0.0, h * 0.3, 0.0, 1.0],
            });
        }
    }
    for band in 0..bands {
        for k in 0..around {
            let a = first + band * around + k;
            let b = first + band * around + (k + 1) % around;
            let (c, d) = (a + around, b + around);
            mesh.leaves.extend_from_slice(&[a, b, d, a, d, c]);
        }
    }
    mesh
}
