//! Trees that grow into their environment: the voxel growth paper's system, with the
//! improvements its authors list.
//!
//! An L-system's word is split into one command list per branch and every branch grows a
//! segment per iteration, in a seeded random order (nature's order, not the turtle's
//! depth-first one). Space is a [`VoxelGrid`] of occupancy bits with 8³ bricks that let
//! rays skip empty space. Before a segment is placed its swept volume (a capsule of the
//! branch's radius) is tested; on collision up to N directions in a cone are tried, and if
//! none is free the branch and its subtree stop. Light at each bud is the fraction of rays
//! towards the sun's path and over the sky that escape ([`Sky`]); it scales the segment,
//! stops branches below a threshold and turns them towards the light by quaternion
//! interpolation. Trees grown in one [`Stand`] shade and block each other. Grammars can ask
//! for light and free space through a query module ([`GrowthOptions::query`]).
//!
//! ```
//! use std::sync::Arc;
//! use sylva_growth::{GrowthOptions, Response, Stand, TreeSpec, VoxelGrid, voxelise_triangles};
//! use sylva_growth::glam::Vec3;
//! use sylva_turtle::{MeshBuilder, TurtleOptions};
//!
//! // A wall beside the tree's base.
//! let mut grid = VoxelGrid::new(Vec3::new(-3.0, 0.0, -3.0), Vec3::new(3.0, 5.0, 3.0), 0.1)?;
//! let wall = [Vec3::new(0.6, 0.0, -3.0), Vec3::new(0.6, 5.0, -3.0), Vec3::new(0.6, 5.0, 3.0), Vec3::new(0.6, 0.0, 3.0)];
//! voxelise_triangles(&mut grid, &wall, &[0, 1, 2, 0, 2, 3]);
//! let mut stand = Stand::new(grid, GrowthOptions::default());
//! stand.add(TreeSpec {
//!     base: Vec3::ZERO,
//!     grammar: Arc::new("axiom: A\nA -> F(0.4)[&(35)A]/(137)[&(35)A]".parse()?),
//!     generations: 7,
//!     seed: 3,
//!     start: 0,
//!     turtle: TurtleOptions::default().with_width(0.04),
//!     response: Response::default(),
//! });
//! let (trees, stats) = stand.grow()?;
//! // No segment crosses the wall.
//! assert!(trees[0].segments.iter().all(|s| (s.frame.position + s.frame.heading() * s.length).x < 0.6));
//! let mut mesh = MeshBuilder::new(&TurtleOptions::default());
//! trees[0].emit(&mut mesh);
//! assert!(mesh.finish().triangle_count() > 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod branches;
mod environment;
mod error;
mod grid;
mod grown;
mod light;
mod obj;
mod options;
mod ray;
mod stand;
mod voxelise;

pub use environment::LightEnvironment;
pub use error::GrowthError;
pub use glam;
pub use grid::{BRICK, MAX_VOXELS, VoxelGrid};
pub use grown::{GrownSegment, GrownTree};
pub use light::{Light, Sky, SunPath};
pub use obj::{MAX_OBJ_BYTES, read_obj};
pub use options::{GrowthOptions, GrowthStats, Response, TreeSpec};
pub use ray::{March, march};
pub use stand::Stand;
pub use voxelise::{
    capsule_is_free, distance_to_segment, voxelise_capsule, voxelise_ground, voxelise_triangles,
};
