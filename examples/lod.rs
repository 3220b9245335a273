//! The level-of-detail chain of each default species: the whole tree at full detail, at each
//! coarser level and as its impostor, drawn side by side on the CPU, with the triangles each
//! level costs, how its silhouette compares with the full tree's from five directions, and
//! the distance at which it takes over (1080p, 60 degrees, two pixels of error). The
//! README's picture of the chain is this program's output.
//!
//! ```text
//! cargo run --release --example lod [OUT.png]
//! ```

use sylva::export::lod::{
    Impostor, LodChain, OrthoView, Picture, TreeLook, calibrate_leaves, compare_silhouettes, draw,
    simplify_mesh, variant_tree,
};
use sylva::forest::{ForestBuilder, ForestConfig};
use sylva::terrain::glam::Vec3;

/// Pixels across each picture of the sheet.
const SIZE: u32 = 192;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "lod.png".into());
    let builder = ForestBuilder::new(ForestConfig::new(sylva::presets::species()?))?;
    let species = &builder.config().species;
    let chain = LodChain::default();
    let directions = [
        Vec3::X,
        Vec3::Z,
        Vec3::new(1.0, 1.0, 0.0).normalize(),
        Vec3::new(-0.5, 0.3, 0.8).normalize(),
        Vec3::Y,
    ];
    let mut rows: Vec<Vec<Picture>> = Vec::new();
    for variant in builder.variants().iter().filter(|v| !v.seedling) {
        let s = &species[variant.species];
        let full = variant_tree(variant, 1)?;
        let look = TreeLook::of(s);
        let start = std::time::Instant::now();
        let impostor = Impostor::render(&full, &look, &chain.impostor);
        let drawn = start.elapsed();
        let card = s.turtle.leaf_size[0].max(s.turtle.leaf_size[1]);
        let (lo, hi) = full.bounds().ok_or("an empty tree")?;
        let side = OrthoView {
            centre: (lo + hi) * 0.5,
            toward: Vec3::new(0.0, 0.15, 1.0).normalize(),
            half: 0.55 * (hi - lo).max_element(),
            size: SIZE,
        };
        let mut row = vec![draw(&full, &look, &side)];
        println!("{}: {} triangles", s.name, full.triangle_count());
        for (k, level) in chain.levels.iter().enumerate() {
            let start = std::time::Instant::now();
            let level = calibrate_leaves(&full, &look, level);
            let tuned = start.elapsed();
            let coarse = simplify_mesh(&full, &level);
            let matches = compare_silhouettes(&full, &coarse, &look, &directions, 256);
            let worst = matches.iter().map(|m| m.overlap).fold(1.0f32, f32::min);
            let ratio: f32 =
                matches.iter().map(|m| m.coverage_ratio).sum::<f32>() / matches.len() as f32;
            println!(
                "  LOD{}: {} triangles ({:.0}%), coverage {:.2} of the full tree's, overlap at worst {:.2}; from {:.0} m (cards tuned in {:.0} ms)",
                k + 1,
                coarse.triangle_count(),
                100.0 * coarse.triangle_count() as f32 / full.triangle_count() as f32,
                ratio,
                worst,
                chain.distance_for(level.bark_error.max(level.leaf_error(card))),
                tuned.as_secs_f64() * 1e3,
            );
            // What the example shows: each level is cheaper and keeps the silhouette.
            assert!(coarse.triangle_count() < full.triangle_count());
            assert!(worst > 0.5 && (0.75..1.3).contains(&ratio), "{matches:?}");
            row.push(draw(&coarse, &look, &side));
        }
        println!(
            "  impostor: {} x {} views of {} px, a texel of {:.2} m; from {:.0} m (drawn in {:.0} ms)",
            impostor.grid,
            impostor.grid,
            impostor.view_size,
            impostor.texel(),
            chain.impostor_distance(&impostor),
            drawn.as_secs_f64() * 1e3,
        );
        row.push(impostor_view(&impostor, SIZE));
        rows.push(row);
    }
    let sheet = Picture::sheet(&rows, [0.55, 0.68, 0.85]);
    std::fs::write(&out, sheet.png())?;
    println!("wrote {out}");
    Ok(())
}

/// The impostor's view nearest the horizon facing +Z, cut from its atlas and scaled to `size`.
fn impostor_view(impostor: &Impostor, size: u32) -> Picture {
    let grid = impostor.grid;
    let (mut best, mut at) = (-2.0f32, (0, 0));
    for j in 0..grid {
        for i in 0..grid {
            let d = Impostor::view_direction(grid, i, j).dot(Vec3::new(0.0, 0.15, 1.0).normalize());
            if d > best {
                (best, at) = (d, (i, j));
            }
        }
    }
    let n = impostor.view_size;
    let mut picture = Picture {
        size,
        colour: vec![[0.0; 3]; (size * size) as usize],
        coverage: vec![0.0; (size * size) as usize],
        normal: vec![[0.0; 3]; (size * size) as usize],
        depth: vec![-1.0; (size * size) as usize],
        leaf: vec![0.0; (size * size) as usize],
    };
    let side = impostor.colour.width;
    for y in 0..size {
        for x in 0..size {
            let (sx, sy) = (x * n / size, y * n / size);
            let k = (((at.1 * n + sy) * side + at.0 * n + sx) * 4) as usize;
            let p = &impostor.colour.rgba[k..k + 4];
            let i = (y * size + x) as usize;
            picture.colour[i] = [p[0], p[1], p[2]].map(sylva::export::srgb_to_linear);
            picture.coverage[i] = f32::from(p[3]) / 255.0;
        }
    }
    picture
}
