//! Counting a forest's instances without placing them gives what streaming the forest and
//! counting its placements gives, at any thread count.

use sylva_forest::{PlacementBlock, Rect};
use sylva_terrain::glam::Vec2;
use sylva_testkit::{builder, plane};

#[test]
fn counts_equal_the_streamed_placements_at_any_thread_count() {
    let b = builder(3);
    let ground = plane(700.0);
    // Many blocks, so that threads share the work.
    let region = Rect::new(Vec2::splat(-700.0), Vec2::splat(700.0));
    let mut streamed: Vec<Vec<u32>> = b
        .variants()
        .iter()
        .map(|v| vec![0; v.cache.instances.len()])
        .collect();
    let stats = b
        .stream(&ground, region, &mut |block: &PlacementBlock| {
            for p in &block.placements {
                streamed[p.variant as usize][p.instance as usize] += 1;
            }
            Ok(())
        })
        .unwrap();
    assert!(stats.blocks >= 9, "{} blocks", stats.blocks);
    for threads in [1, 2, 5] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let counted = pool.install(|| b.count_instances(&ground, region)).unwrap();
        assert_eq!(counted.stats, stats, "{threads} threads");
        assert!(counted.counts == streamed, "{threads} threads");
    }
}

#[test]
fn kept_trees_stream_as_the_same_blocks() {
    let b = builder(5);
    let ground = plane(700.0);
    let region = Rect::new(Vec2::splat(-700.0), Vec2::splat(700.0));
    let blocks = b.blocks(region).unwrap();
    let kept = std::sync::Mutex::new(vec![None; blocks.len()]);
    let keep = |block: usize, trees: &[sylva_instancing::CompactTree]| {
        kept.lock().unwrap()[block] = Some(trees.to_vec());
        Ok::<_, sylva_forest::ForestError>(())
    };
    let counted = b.count_instances_keeping(&ground, region, &keep).unwrap();
    let kept = kept.into_inner().unwrap();
    // Every block's trees were kept, as placing that block gives them.
    for (k, rect) in blocks.iter().enumerate() {
        assert_eq!(
            kept[k].as_deref(),
            Some(&b.trees(&ground, *rect)[..]),
            "block {k}"
        );
    }
    // Streaming from the kept trees is streaming the forest.
    let spell = |block: PlacementBlock| (block.trees.len(), block.placements);
    let mut placed = Vec::new();
    let stats = b
        .stream_map::<_, sylva_forest::ForestError>(&ground, region, &|_| true, &spell, &mut |x| {
            placed.push(x);
            Ok(())
        })
        .unwrap();
    let from_kept = |block: usize, _: Rect| Ok(kept[block].clone().unwrap_or_default());
    let mut replayed = Vec::new();
    let again = b
        .stream_map_from(region, &from_kept, &|_| true, &spell, &mut |x| {
            replayed.push(x);
            Ok::<_, sylva_forest::ForestError>(())
        })
        .unwrap();
    assert_eq!(stats, again);
    assert_eq!(stats, counted.stats);
    assert!(placed == replayed, "the same placements in the same order");
}
