//! 3D turtle interpretation of L-system words into meshes, skeletons, polygons and leaves.
//!
//! ```
//! use sylva_turtle::{interpret, MeshBuilder, TurtleOptions};
//!
//! let preset = sylva_lsys::preset("abop-1.24a").unwrap();
//! let word = preset.lsystem()?.derive(3, 0)?;
//! let options = TurtleOptions::for_preset(preset);
//! let mut builder = MeshBuilder::new(&options);
//! let stats = interpret(&word, &options, &mut builder)?;
//! let mesh = builder.finish();
//! assert_eq!(stats.segments, 125);
//! assert!(mesh.triangle_count() > 0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The turtle follows ABOP chapter 1.5: a frame of heading H, left L and up U vectors, turned
//! by `+ -` (about U), `& ^` (about L) and `/ \` (about H), with `|` and `$`. What each symbol
//! means is a [`SymbolTable`] the caller can change; unknown symbols are skipped, and symbols
//! marked [`Command::Marker`] reach the sink with their parameters and frame.
//!
//! Output goes through the [`GeometrySink`] trait. This crate ships [`MeshBuilder`]
//! (cylinders or shared-ring frustum tubes, polygons, leaves), [`Skeleton`] and [`NullSink`].
//!
//! # Conventions
//!
//! Right-handed, +Y up; the turtle starts at the origin heading up +Y, with L = -X and U = +Z.
//! Angles in grammar parameters and options are degrees; widths are diameters.
//!
//! Tropism bends by absolute direction, so trees with tropism are not rigidly instanceable.
//!
//! # Feature flags
//!
//! - `serde`: `Serialize`/`Deserialize` for [`Frame`].

mod error;
mod frame;
mod interpret;
mod mesh;
mod model_shapes;
mod obj;
mod options;
mod queries;
mod shapes;
mod sink;
mod skeleton;
mod swell;
mod symbols;
mod tube;

pub use error::TurtleError;
pub use frame::Frame;
pub use glam;
pub use interpret::{InterpretStats, check_stems, interpret};
pub use mesh::{Material, Mesh, Vertex, Wind};
pub use model_shapes::ModelShapes;
pub use obj::write_obj;
pub use options::{BranchShape, MAX_PIECES, StemBreak, Tropism, TurtleOptions};
pub use queries::{Queries, query_frames};
pub use sink::{GeometrySink, NullSink, Segment};
pub use skeleton::{Bone, Skeleton};
pub use symbols::{Command, Sign, SymbolTable};
pub use tube::MeshBuilder;
