//! Kenwood's instance cache: hero trees fill a byte budget with whole branches, and many
//! trees are then assembled from a few placements each instead of being derived and meshed.
//!
//! ```text
//! cargo run --release --example instancing [TREES]
//! ```

use std::time::Instant;

use sylva::instancing::{Assembler, CompactTree, HeroOptions, build_cache};
use sylva::lsys::preset;
use sylva::turtle::TurtleOptions;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(10_000), |n| n.parse())?;
    let p = preset("kenwood-leafy").ok_or("the kenwood-leafy preset is bundled")?;
    let options = HeroOptions::default()
        .with_budget(16 << 20)
        .with_generations(6)
        .with_turtle(
            TurtleOptions::default()
                .with_angle(p.angle as f32)
                .with_width(0.1),
        );
    let start = Instant::now();
    let built = build_cache(&p.lsystem()?, &options)?;
    let hero_time = start.elapsed();
    let mut assembler = Assembler::new();
    let start = Instant::now();
    let mut placements = 0;
    for i in 0..n {
        let tree = CompactTree {
            position: [(i % 100) as f32 * 12.0, 0.0, (i / 100) as f32 * 12.0],
            yaw: i as f32,
            scale: 1.0,
            seed: i as u32,
            variant: 0,
            crown_class: 0,
            crown_classes: 0,
        };
        placements += assembler.expand_with(&built.cache, &tree, |_, _| {})?;
    }
    let expand = start.elapsed().as_secs_f64();
    // Each tree is a few whole branches, not thousands of segments.
    assert!(placements >= n && placements < n * 200);
    println!(
        "{} instances in {:.1} MB of cache from heroes in {:.0} ms; {n} trees, {:.1} placements each, {:.2} M placements/s",
        built.cache.instances.len(),
        built.cache.bytes() as f64 / (1 << 20) as f64,
        hero_time.as_secs_f64() * 1e3,
        placements as f64 / n as f64,
        placements as f64 / expand.max(1e-9) / 1e6
    );
    Ok(())
}
