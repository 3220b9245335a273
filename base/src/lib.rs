//! What every sylva crate needs and none owns: the seeded, position-keyed hash that makes
//! outputs a pure function of (seed, position), text-file reading with a size limit, and
//! file writes that cannot tear.
//!
//! ```
//! use sylva_base::hash::{hash_cell, unit_f32};
//!
//! // The same seed and cell give the same number on every machine and thread.
//! let a = unit_f32(hash_cell(7, -3, 12, 0));
//! assert_eq!(a, unit_f32(hash_cell(7, -3, 12, 0)));
//! assert!((0.0..1.0).contains(&a));
//! ```
//!
//! # Feature flags
//!
//! None.
//!
//! # Conventions
//!
//! Hashes are integer arithmetic only (wrapping multiplies, shifts, xors), so they give the
//! same bits on every platform.

mod destination;
pub mod file;
mod file_error;
pub mod hash;
pub mod range;
mod scratch;
pub mod text_file;
