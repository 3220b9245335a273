//! Levels of detail: coarser meshes of every cached instance and whole tree
//! ([`simplify_mesh`], [`CacheLods`]), impostors drawn on the CPU ([`Impostor`]), and the
//! distances at which each takes over.

mod cache;
mod cards;
mod chain;
mod compare;
mod impostor;
mod leaves;
mod raster;
mod simplify;
mod tree;
mod variant;

pub use cache::{CacheLods, LevelSpans};
pub use cards::{CARD_ALPHA_CUTOFF, cards, impostor_cards};
pub use chain::{LodChain, PIXELS_PER_RADIAN_1080P};
pub use compare::{SilhouetteMatch, calibrate_leaves, compare_silhouettes};
pub use impostor::{
    Impostor, ImpostorOptions, MAX_ATLAS_SIDE, hemi_octahedral_direction, hemi_octahedral_uv,
};
pub use raster::{OrthoView, Picture, TreeLook, draw};
pub use simplify::{LodLevel, simplify_mesh};
pub use tree::variant_tree;
pub use variant::VariantLods;
