//! The branch-level instance cache of Kenwood, Gain and Marais (2014), with the refinements of
//! the Carey report: grammars rewritten into instancing form, a byte-budgeted cache filled by
//! hero trees, and trees assembled from cached branches.
//!
//! ```
//! use sylva_instancing::{build_cache, Assembler, CompactTree, HeroOptions, Placements};
//!
//! let grammar = sylva_lsys::preset("kenwood-leafy").unwrap().lsystem()?;
//! let built = build_cache(&grammar, &HeroOptions::default().with_budget(4 << 20).with_generations(5))?;
//! let trees: Vec<CompactTree> = (0..100)
//!     .map(|i| CompactTree { position: [i as f32 * 10.0, 0.0, 0.0], scale: 1.0, seed: i, ..Default::default() })
//!     .collect();
//! let mut placements = Placements::for_cache(&built.cache);
//! let placed = Assembler::new().expand(&built.cache, &trees, &mut placements)?;
//! assert!(placed >= 100);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # How it works
//!
//! 1. **Rewriting** ([`internal::InstancingGrammar`]): every top-level `[...]` of a successor that holds
//!    a non-terminal is a branch; identical branches share an id; id 0 is the whole tree. Each
//!    branch becomes an independent stochastic choice: with probability P a get-instance exit
//!    `◆(id, #)`, else the branch itself between `⟦(id, #)` and `⟧(id, #)`. This reaches the
//!    distribution of the paper's 2^B right-hand sides ([`internal::InstancingGrammar::explicit`]) with
//!    one right-hand side per production.
//! 2. **Heroes** ([`build_cache`]): hero trees are derived and meshed through the turtle's
//!    marker symbols (a `GeometrySink` that records them); each recorded range becomes an [`Instance`] with its
//!    frame M and exit points, until the byte budget is used. P rises as the cache fills.
//! 3. **Assembly** ([`Assembler`]): a [`CompactTree`] (28 bytes) is expanded from its seed:
//!    start from a whole-tree instance at the root frame D, place each instance at
//!    T = D * M^-1 and follow each exit E with D * E, on an explicit stack.
//!
//! # Exactness
//!
//! A key (id, age) stands for one subtree when the grammar is deterministic and a branch's
//! parameters depend only on its age (always so without parameters): then every assembled
//! tree equals the directly derived tree, triangle for triangle, at any instancing
//! probability (the test suite checks this). Where the same branch at the same age carries
//! different parameters on different paths (ABOP's Honda tree), or the turtle uses absolute
//! directions (tropism, `$`), a reused instance approximates the branch it replaces, as in the
//! paper. Stochastic grammars always assemble into valid derivations.
//!
//! # Completeness
//!
//! Hero creation records, never instances, a branch whose (id, age) has no cached instance
//! yet. So every exit of every cached instance has a candidate, every assembled tree is
//! complete, and assembly never derives or meshes anything: where Carey builds a missing
//! branch inline at assembly time, this crate makes the case impossible.

mod assemble;
mod cache;
mod error;
mod filling;
mod hero;
mod options;
mod recorder;
mod rewrite;
mod similarity;
mod span;

pub use assemble::{Assembler, AssemblyLimits, CompactTree, Placements, REPEAT_PROBES};
pub use cache::{CANDIDATE_BYTES, EXIT_BYTES, Exit, INSTANCE_BYTES, Instance, InstanceCache};
pub use error::InstancingError;
pub use hero::{HeroCache, HeroStats, build_cache};
pub use options::HeroOptions;
pub use rewrite::Markers;
pub use similarity::Similarity;
pub use span::Span;

/// The grammar rewriting behind hero creation, exposed for tests and research: branch
/// detection, the compact instancing form the heroes are derived from, and the paper's
/// explicit form with 2^B right-hand sides per production, against which the compact form's
/// distribution is checked. Not needed to build or assemble trees.
pub mod internal {
    pub use crate::rewrite::{Branch, InstancingGrammar, probability_at_ages};
}
