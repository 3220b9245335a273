#![doc = include_str!("../README.md")]
//!
//! # Crates
//!
//! - [`lsys`]: L-system grammars and seeded rewriting.

pub use sylva_lsys as lsys;
