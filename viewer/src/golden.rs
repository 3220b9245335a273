//! Renders the viewer's default scene offscreen and checks the picture: what covers it
//! (terrain, bark, leaves and sky, from a flat material-id render) and how far it is from the
//! committed reference image. Runs on any adapter, Mesa's software drivers included.
//!
//! Without an adapter the test reports and passes, unless `SYLVA_REQUIRE_GPU` is set (CI sets
//! it after installing lavapipe). `SYLVA_BLESS=1` rewrites the reference image:
//! `SYLVA_BLESS=1 cargo test -p sylva-viewer golden`.

use crate::render::{ID_BARK, ID_LEAF, ID_TERRAIN, Mode};
use crate::scene::{self, Camera, Scene, SceneOptions};

const SIZE: (u32, u32) = (320, 180);
const GOLDEN: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/golden/default_scene.png"
);

fn read_png(path: &str) -> Option<Vec<u8>> {
    let file = std::fs::File::open(path).ok()?;
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .ok()?;
    let mut buf = vec![0; reader.output_buffer_size()?];
    let info = reader.next_frame(&mut buf).ok()?;
    buf.truncate(info.buffer_size());
    Some(buf)
}

fn write_png(path: &str, pixels: &[u8]) {
    let file = std::fs::File::create(path).expect("golden file is writable");
    let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), SIZE.0, SIZE.1);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    let mut writer = encoder.write_header().expect("png header");
    writer.write_image_data(pixels).expect("png data");
}

#[test]
fn default_scene_renders_terrain_and_trees() {
    let scene = Scene::build(SceneOptions {
        seed: 1,
        side: 800.0,
        species: scene::default_species().expect("bundled species"),
        budget: 32 << 20,
    })
    .expect("default scene builds");
    let camera = Camera::overview(scene.side, 40.0);
    let offscreen =
        match pollster::block_on(crate::offscreen::Offscreen::new(&scene, SIZE.0, SIZE.1)) {
            Ok(o) => o,
            Err(e) if std::env::var_os("SYLVA_REQUIRE_GPU").is_none() => {
                eprintln!("skipping the headless render: {e}");
                return;
            }
            Err(e) => panic!("{e}"),
        };
    let (ids, _) = offscreen
        .frame(&scene, &camera, Mode::Ids)
        .expect("id render");
    // Coverage of each flat material colour.
    let classify = |p: &[u8]| -> usize {
        let close = |c: [f32; 3]| (0..3).all(|k| (f32::from(p[k]) / 255.0 - c[k]).abs() < 0.1);
        if close(ID_TERRAIN) {
            0
        } else if close(ID_BARK) {
            1
        } else if close(ID_LEAF) {
            2
        } else if p[..3].iter().all(|&v| v < 10) {
            3
        } else {
            4
        }
    };
    let mut counts = [0usize; 5];
    for p in ids.chunks_exact(4) {
        counts[classify(p)] += 1;
    }
    let total = (SIZE.0 * SIZE.1) as f64;
    let [terrain, bark, leaves, sky, other] = counts.map(|c| c as f64 / total);
    eprintln!(
        "coverage: terrain {terrain:.3}, bark {bark:.3}, leaves {leaves:.3}, sky {sky:.3}, other {other:.3} ({counts:?} pixels)"
    );
    assert!(
        (0.15..0.85).contains(&terrain),
        "terrain covers {terrain:.3}"
    );
    assert!((0.05..0.6).contains(&sky), "sky covers {sky:.3}");
    assert!(bark > 0.01, "bark covers {bark:.4}");
    assert!(leaves > 0.01, "leaves cover {leaves:.4}");
    assert!(other < 0.01, "unexpected colours cover {other:.4}");

    let (shaded, stats) = offscreen
        .frame(&scene, &camera, Mode::Shaded)
        .expect("shaded render");
    let adapter = &offscreen.adapter;
    assert!(stats.draws > 100 && stats.instances > 1000, "{stats:?}");
    if std::env::var_os("SYLVA_BLESS").is_some() {
        write_png(GOLDEN, &shaded);
        eprintln!("wrote {GOLDEN} on {adapter}");
        return;
    }
    let golden =
        read_png(GOLDEN).expect("reference image missing: run with SYLVA_BLESS=1 to create it");
    assert_eq!(golden.len(), shaded.len());
    let diffs: Vec<u8> = golden
        .iter()
        .zip(&shaded)
        .map(|(a, b)| a.abs_diff(*b))
        .collect();
    let mean = diffs.iter().map(|&d| f64::from(d)).sum::<f64>() / diffs.len() as f64;
    let far = golden
        .chunks_exact(4)
        .zip(shaded.chunks_exact(4))
        .filter(|(a, b)| a.iter().zip(*b).any(|(x, y)| x.abs_diff(*y) > 24))
        .count();
    let far_fraction = far as f64 / total;
    eprintln!(
        "against the reference ({adapter}): mean difference {mean:.2}, {far_fraction:.4} of pixels far off"
    );
    assert!(
        mean < 3.0 && far_fraction < 0.02,
        "frame differs from {GOLDEN}: mean {mean:.2}, far {far_fraction:.4}"
    );
}
