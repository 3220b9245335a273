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
