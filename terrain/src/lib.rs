//! Fractal terrain: diamond-square heightmaps, Gaussian smoothing, erosion, sampling, meshes
//! and PNG / RAW export.
//!
//! ```
//! use sylva_terrain::{DiamondSquare, EdgeMode, HeightField};
//!
//! let mut map = DiamondSquare::new(257).with_seed(7).with_roughness(0.8).with_spacing(2.0).generate()?;
//! map.smooth(2.0, EdgeMode::Mirror)?;
//! let h = map.height(100.0, 200.0);               // bilinear, anywhere on the map
//! assert!(map.normal(100.0, 200.0).y > 0.0);      // normals point up
//! let mesh = map.mesh(4)?;                         // a coarser level of detail
//! assert_eq!(mesh.vertices.len(), 65 * 65);
//! # let _ = h;
//! # Ok::<(), sylva_terrain::TerrainError>(())
//! ```
//!
//! Generation follows the Garden of Eden thesis, section 4: midpoint displacement by the
//! diamond-square algorithm with roughness H, then a Gaussian filter; extension 7.6's erosion
//! is here too, as [`ThermalErosion`] and [`HydraulicErosion`].
//!
//! # Conventions
//!
//! +Y is up; a map lies in the x-z plane from its origin to `origin + extent` on both axes.
//! Sample (x, z) is at index `z * size + x`. Heights and spacing share one unit (metres in
//! the examples).
//!
//! # Feature flags
//!
//! - `serde`: `Serialize`/`Deserialize` for [`HeightRange`].

pub mod analysis;
pub mod dem;
mod diamond_square;
mod erosion;
mod error;
mod field;
pub mod ground;
mod hash;
mod heightmap;
mod io;
mod matching;
mod mesh;
mod raycast;
mod smooth;
mod spectral;

pub use diamond_square::DiamondSquare;
pub use erosion::{HydraulicErosion, ThermalErosion};
pub use error::{OutOfRange, TerrainError};
pub use field::{FlatPlane, HeightField};
pub use glam;
pub use heightmap::{HeightStats, Heightmap, MAX_LEVELS};
pub use io::HeightRange;
pub use matching::{hillshade, match_distribution, refine, synthesize_like};
pub use mesh::{TerrainMesh, TerrainVertex};
pub use raycast::RayHit;
pub use smooth::{EdgeMode, MAX_SIGMA};
pub use spectral::SpectralSynthesis;
