//! One interface for building many trees, with the instanced method and the naive baseline
//! behind it, so the two can be timed side by side.

use sylva_lsys::{LSystem, Limits};
use sylva_turtle::{MeshBuilder, TurtleOptions, interpret};

use crate::assemble::{Assembler, CompactTree, Placements};
use crate::cache::InstanceCache;
use crate::error::InstancingError;

/// What building a set of trees produced.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct BuildReport {
    /// Trees built.
    pub trees: usize,
    /// Instance placements (the naive method counts one per tree).
    pub placements: usize,
    /// Triangles that will be drawn.
    pub triangles: u64,
    /// Bytes of geometry that had to be created for these trees.
    pub new_geometry_bytes: u64,
}

/// Builds the renderable form of trees of one species.
pub trait TreeBuilder {
    /// Builds `trees` and reports what it made.
    fn build(&mut self, trees: &[CompactTree]) -> Result<BuildReport, InstancingError>;
}

/// The instanced method: trees are expanded into placements of cached instances.
#[derive(Debug)]
pub struct InstancedBuilder<'c> {
    cache: &'c InstanceCache,
    assembler: Assembler,
    /// The placements of everything built so far.
    pub placements: Placements,
}

impl<'c> InstancedBuilder<'c> {
    /// A builder drawing on `cache`.
    pub fn new(cache: &'c InstanceCache) -> Self {
        InstancedBuilder {
            cache,
            assembler: Assembler::new(),
            placements: Placements::for_cache(cache),
        }
    }
}

impl TreeBuilder for InstancedBuilder<'_> {
    fn build(&mut self, trees: &[CompactTree]) -> Result<BuildReport, InstancingError> {
        let placed = self
            .assembler
            .expand(self.cache, trees, &mut self.placements)?;
        let triangles = self
            .placements
            .groups
            .iter()
            .zip(&self.cache.instances)
            .map(|(g, inst)| g.len() as u64 * u64::from(inst.bark.1 + inst.leaves.1) / 3)
            .sum();
        Ok(BuildReport {
            trees: trees.len(),
            placements: placed,
            triangles,
            new_geometry_bytes: 0,
        })
    }
}

/// The naive baseline: every tree is derived and meshed in full.
#[derive(Debug, Clone)]
pub struct NaiveBuilder {
    grammar: LSystem,
    generations: u32,
    turtle: TurtleOptions,
    limits: Limits,
}

impl NaiveBuilder {
    /// A naive builder for one species.
    pub fn new(grammar: LSystem, generations: u32, turtle: TurtleOptions) -> Self {
        NaiveBuilder {
            grammar,
            generations,
            turtle,
            limits: Limits::default(),
        }
    }
}

impl TreeBuilder for NaiveBuilder {
    fn build(&mut self, trees: &[CompactTree]) -> Result<BuildReport, InstancingError> {
        let mut report = BuildReport {
            trees: trees.len(),
            ..BuildReport::default()
        };
        for tree in trees {
            let word =
                self.grammar
                    .derive_with(self.generations, u64::from(tree.seed), &self.limits)?;
            let mut builder = MeshBuilder::new(&self.turtle);
            interpret(&word, &self.turtle, &mut builder)?;
            let mut mesh = builder.finish();
            let root = tree.root().to_affine();
            for v in &mut mesh.vertices {
                v.position = root.transform_point3(v.position.into()).to_array();
                v.normal = root
                    .transform_vector3(v.normal.into())
                    .normalize_or_zero()
                    .to_array();
            }
            report.placements += 1;
            report.triangles += mesh.triangle_count() as u64;
            report.new_geometry_bytes += mesh.byte_size() as u64;
        }
        Ok(report)
    }
}
