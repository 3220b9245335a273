//! The part of a variant's instance cache that one file's placements use: a 100 m forest
//! places a few hundred of a cache's thousands of instances, and its file should hold only
//! their triangles and the vertices those reference.

use sylva_instancing::{InstanceCache, Span};
use sylva_turtle::Vertex;

use super::extras::VertexLayout;
use super::shared::section_lengths;

/// The used instances' geometry of one cache: the vertices their triangles reference, in the
/// cache's order, and their bark and leaf triangles renumbered onto them, instance after
/// instance in the cache's order. When every instance is used, these are the cache's own
/// buffers, byte for byte.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct CacheSubset {
    pub(super) vertices: Vec<Vertex>,
    pub(super) bark: Vec<u32>,
    pub(super) leaves: Vec<u32>,
    /// Per cache instance, where its bark and leaf triangles sit in `bark` and `leaves`;
    /// `None` for instances the file does not use.
    spans: Vec<Option<(Span, Span)>>,
}

impl CacheSubset {
    /// The subset of `cache` that instances `used` (indices into its instances, in any
    /// order, repeats allowed) draw. Indices outside the cache are left out.
    pub(super) fn of(cache: &InstanceCache, used: &[usize]) -> CacheSubset {
        let spans: Vec<(Span, Span)> = cache.instances.iter().map(|i| (i.bark, i.leaves)).collect();
        CacheSubset::of_parts(&cache.vertices, (&cache.bark, &cache.leaves), &spans, used)
    }

    /// The subset of a cache given as its parts (a coarser level's triangles over the
    /// level's vertices, say): `spans` gives each instance's bark and leaf spans of `bark`
    /// and `leaves`.
    pub(super) fn of_parts(
        all_vertices: &[Vertex],
        (all_bark, all_leaves): (&[u32], &[u32]),
        instance_spans: &[(Span, Span)],
        used: &[usize],
    ) -> CacheSubset {
        let mut wanted = vec![false; instance_spans.len()];
        for &i in used {
            if let Some(w) = wanted.get_mut(i) {
                *w = true;
            }
        }
        let used = || {
            instance_spans
                .iter()
                .zip(&wanted)
                .filter(|(_, w)| **w)
                .map(|(spans, _)| spans)
        };
        // Instances share triangles (a crown's span holds its branches'), so the subset keeps
        // the union of the used spans, in cache order.
        let bark_ranges = Ranges::union(used().map(|s| s.0), all_bark.len());
        let leaf_ranges = Ranges::union(used().map(|s| s.1), all_leaves.len());
        // Which vertices those triangles reference, numbered anew in cache order.
        let mut kept = vec![false; all_vertices.len()];
        for &i in bark_ranges
            .indices(all_bark)
            .chain(leaf_ranges.indices(all_leaves))
        {
            if let Some(k) = kept.get_mut(i as usize) {
                *k = true;
            }
        }
        let mut vertices = Vec::new();
        let new_index: Vec<u32> = kept
            .iter()
            .zip(all_vertices)
            .map(|(&k, v)| {
                let n = vertices.len() as u32;
                if k {
                    vertices.push(*v);
                }
                n
            })
            .collect();
        let renumber = |ranges: &Ranges, of: &[u32]| -> Vec<u32> {
            ranges.indices(of).map(|&i| new_index[i as usize]).collect()
        };
        let bark = renumber(&bark_ranges, all_bark);
        let leaves = renumber(&leaf_ranges, all_leaves);
        let spans = instance_spans
            .iter()
            .zip(&wanted)
            .map(|(&(b, l), &w)| w.then(|| (bark_ranges.moved(b), leaf_ranges.moved(l))))
            .collect();
        CacheSubset {
            vertices,
            bark,
            leaves,
            spans,
        }
    }

    /// Where instance `instance`'s bark and leaf triangles sit in this subset's buffers.
    pub(super) fn spans(&self, instance: usize) -> Option<(Span, Span)> {
        self.spans.get(instance).copied().flatten()
    }

    /// Bytes of its vertices, vertex extras, bark indices and leaf indices in `layout`.
    pub(super) fn section_lengths(&self, layout: VertexLayout) -> [usize; 4] {
        section_lengths(layout, &self.vertices, &self.bark, &self.leaves)
    }
}

/// A union of ranges of an index array, each with where it starts once the ranges are laid
/// end to end.
#[derive(Debug, Clone, Default)]
struct Ranges {
    /// `(start, end, start in the laid-out array)`, sorted, disjoint, not touching.
    ranges: Vec<(u32, u32, u32)>,
}

impl Ranges {
    /// The union of `spans`, clipped to an array of `len`.
    fn union(spans: impl Iterator<Item = Span>, len: usize) -> Ranges {
        let len = len as u32;
        let mut spans: Vec<(u32, u32)> = spans
            .map(|s| (s.start.min(len), s.start.saturating_add(s.count).min(len)))
            .filter(|(a, b)| a < b)
            .collect();
        spans.sort_unstable();
        let mut ranges: Vec<(u32, u32, u32)> = Vec::new();
        let mut laid = 0;
        for (a, b) in spans {
            match ranges.last_mut() {
                Some(last) if a <= last.1 => {
                    laid += b.saturating_sub(last.1);
                    last.1 = last.1.max(b);
                }
                _ => {
                    ranges.push((a, b, laid));
                    laid += b - a;
                }
            }
        }
        Ranges { ranges }
    }

    /// The indices of `of` the ranges hold, in order.
    fn indices<'a>(&'a self, of: &'a [u32]) -> impl Iterator<Item = &'a u32> + 'a {
        self.ranges
            .iter()
            .flat_map(move |&(a, b, _)| &of[a as usize..b as usize])
    }

    /// Where `span` (inside one of the ranges) lies once they are laid end to end.
    fn moved(&self, span: Span) -> Span {
        if span.count == 0 {
            return Span::new(0, 0);
        }
        let k = self.ranges.partition_point(|r| r.0 <= span.start);
        match k.checked_sub(1).and_then(|k| self.ranges.get(k)) {
            Some(&(a, _, laid)) => Span::new(laid + (span.start - a), span.count),
            None => Span::new(0, 0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva_instancing::{HeroOptions, build_cache};

    fn cache() -> InstanceCache {
        let grammar = sylva_lsys::preset("kenwood-leafy")
            .unwrap()
            .lsystem()
            .unwrap();
        let options = HeroOptions::default()
            .with_budget(1 << 20)
            .with_generations(5)
            .with_seed(3);
        build_cache(&grammar, &options).unwrap().cache
    }

    /// Every instance's triangles, as corner positions.
    fn corners(vertices: &[Vertex], indices: &[u32], span: Span) -> Vec<[f32; 3]> {
        indices[span.range()]
            .iter()
            .map(|&i| vertices[i as usize].position)
            .collect()
    }

    /// All instances used: the cache's own buffers, byte for byte.
    #[test]
    fn the_whole_cache_is_its_own_subset() {
        let cache = cache();
        let all: Vec<usize> = (0..cache.instances.len()).collect();
        let subset = CacheSubset::of(&cache, &all);
        // Compared by length and equality, not printed: the buffers are long.
        assert!(subset.vertices == cache.vertices, "vertices differ");
        assert!(subset.bark == cache.bark, "bark indices differ");
        assert!(subset.leaves == cache.leaves, "leaf indices differ");
        for (k, inst) in cache.instances.iter().enumerate() {
            let empty = |s: Span| if s.count == 0 { Span::new(0, 0) } else { s };
            assert_eq!(
                subset.spans(k),
                Some((empty(inst.bark), empty(inst.leaves)))
            );
        }
    }

    /// A few instances: only the vertices they reference, and each instance draws the same
    /// triangles as in the whole cache; unused instances have no spans.
    #[test]
    fn a_subset_keeps_its_instances_triangles_and_nothing_else() {
        let cache = cache();
        let drawn: Vec<usize> = (0..cache.instances.len())
            .filter(|&k| !cache.instances[k].bark.is_empty())
            .collect();
        assert!(drawn.len() > 4, "{}", drawn.len());
        let used = [drawn[1], drawn[3], drawn[1]];
        let subset = CacheSubset::of(&cache, &used);
        assert!(subset.vertices.len() < cache.vertices.len());
        for &k in &used {
            let inst = &cache.instances[k];
            let (bark, leaves) = subset.spans(k).expect("a used instance has spans");
            assert!(
                corners(&subset.vertices, &subset.bark, bark)
                    == corners(&cache.vertices, &cache.bark, inst.bark),
                "instance {k}'s bark moved"
            );
            assert!(
                corners(&subset.vertices, &subset.leaves, leaves)
                    == corners(&cache.vertices, &cache.leaves, inst.leaves),
                "instance {k}'s leaves moved"
            );
        }
        assert_eq!(subset.spans(drawn[0]), None);
        assert_eq!(subset.spans(usize::MAX), None);
        // Every vertex kept is referenced.
        let mut referenced = vec![false; subset.vertices.len()];
        for &i in subset.bark.iter().chain(&subset.leaves) {
            referenced[i as usize] = true;
        }
        assert!(referenced.into_iter().all(|r| r));
    }
}
