//! The levels of detail of an instance cache: every level's triangles over the cache's
//! vertices (plus the grown leaf cards), with each instance's spans at that level, so a
//! placement of instance `i` draws `levels[k].spans[i]` at level `k`.

use sylva_instancing::{InstanceCache, Span};
use sylva_turtle::Vertex;

use super::simplify::{LodLevel, Simplified, simplify};

/// One level of an instance cache.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LevelSpans {
    /// The level it was made at.
    pub level: Option<LodLevel>,
    /// Bark triangles (three indices each) into [`CacheLods::vertices`].
    pub bark: Vec<u32>,
    /// Leaf triangles into [`CacheLods::vertices`].
    pub leaves: Vec<u32>,
    /// Per cached instance, its bark and leaf spans of `bark` and `leaves`.
    pub spans: Vec<(Span, Span)>,
}

impl LevelSpans {
    /// Triangles at this level.
    pub fn triangle_count(&self) -> usize {
        (self.bark.len() + self.leaves.len()) / 3
    }
}

/// Every level of one instance cache, the full one first.
///
/// ```
/// use sylva_export::lod::{CacheLods, LodLevel};
/// use sylva_instancing::{HeroOptions, build_cache};
///
/// let grammar = sylva_lsys::preset("sylva-birch").unwrap().lsystem()?;
/// let cache = build_cache(&grammar, &HeroOptions::default().with_budget(1 << 20).with_generations(5))?.cache;
/// let lods = CacheLods::of(&cache, &[LodLevel { bark_error: 0.03, leaf_keep: 0.5, leaf_growth: None }]);
/// assert_eq!(lods.levels.len(), 2);
/// assert!(lods.levels[1].triangle_count() < lods.levels[0].triangle_count());
/// // Each instance keeps a span at every level, within that level's buffers.
/// for (bark, leaves) in &lods.levels[1].spans {
///     assert!(bark.end() as usize <= lods.levels[1].bark.len());
///     assert!(leaves.end() as usize <= lods.levels[1].leaves.len());
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CacheLods {
    /// The cache's vertices, then each level's grown leaf cards.
    pub vertices: Vec<Vertex>,
    /// Level 0 (the cache as it is), then one per [`LodLevel`] asked for.
    pub levels: Vec<LevelSpans>,
}

impl CacheLods {
    /// The cache at full detail and at each of `levels`.
    pub fn of(cache: &InstanceCache, levels: &[LodLevel]) -> CacheLods {
        let full = LevelSpans {
            level: None,
            bark: cache.bark.clone(),
            leaves: cache.leaves.clone(),
            spans: cache.instances.iter().map(|i| (i.bark, i.leaves)).collect(),
        };
        let mut vertices = cache.vertices.clone();
        let mut out = vec![full];
        for level in levels {
            let s = simplify(&cache.vertices, &cache.bark, &cache.leaves, level);
            // This level's grown cards go after those of the levels before.
            let offset = (vertices.len() - cache.vertices.len()) as u32;
            let base = cache.vertices.len() as u32;
            let shift = |i: u32| if i >= base { i + offset } else { i };
            vertices.extend_from_slice(&s.extra);
            let span = |before: &[u32], span: Span| {
                let (start, end) = Simplified::map_span(before, span.start, span.end());
                Span::between(start, end)
            };
            let spans = cache
                .instances
                .iter()
                .map(|i| {
                    (
                        span(&s.bark_before, i.bark),
                        span(&s.leaves_before, i.leaves),
                    )
                })
                .collect();
            out.push(LevelSpans {
                level: Some(*level),
                bark: s.bark,
                leaves: s.leaves.into_iter().map(shift).collect(),
                spans,
            });
        }
        CacheLods {
            vertices,
            levels: out,
        }
    }
}
