//! sylva: procedural forests from L-systems.
//!
//! This crate re-exports the member crates of the workspace, each usable on its own:
//!
//! - [`lsys`]: L-system grammars and seeded rewriting.
//!
//! ```
//! let g = sylva::lsys::preset("abop-1.24a").unwrap().lsystem().unwrap();
//! assert_eq!(g.derive(1, 0).unwrap().len(), 11);
//! ```

pub use sylva_lsys as lsys;
