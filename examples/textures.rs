//! Every procedural texture the exporter and the viewer draw, on one contact sheet: the leaf
//! cards of each `LeafShape` (over black, where they are transparent) above the colour of
//! each `BarkPattern` and two of their normal maps. The README's picture of them is this
//! program's output.
//!
//! ```text
//! cargo run --example textures [OUT.png]
//! ```

use std::io::Write;

use sylva::export::Texture;
use sylva::export::limits::{CUTOFF_MIP_LEVEL, TEXTURE_SIZE};
use sylva::forest::{BarkPattern, LeafShape};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "textures.png".into());
    let leaves: Vec<Texture> = LeafShape::ALL.into_iter().map(Texture::leaf).collect();
    let mut barks: Vec<Texture> = BarkPattern::ALL.into_iter().map(Texture::bark).collect();
    barks.push(Texture::bark_normal(BarkPattern::Furrowed));
    barks.push(Texture::bark_normal(BarkPattern::Scaly));
    for (shape, t) in LeafShape::ALL.iter().zip(&leaves) {
        // A card is leaf somewhere and clear somewhere, or it would draw a square.
        let alpha = t.rgba.chunks_exact(4).map(|p| p[3]);
        let opaque = alpha.clone().filter(|&a| a == 255).count() as f64 / (t.rgba.len() / 4) as f64;
        assert!(opaque > 0.05 && opaque < 0.95, "{shape:?}: {opaque}");
        // The cutoff glTF files give the card: where its coverage survives mipmaps.
        let cutoff = t.alpha_cutoff(CUTOFF_MIP_LEVEL);
        assert!((0.1..=0.5).contains(&cutoff));
        println!(
            "{:>12}: {:.0}% of the card is leaf, alpha cut at {cutoff:.2}",
            shape.name(),
            100.0 * opaque
        );
    }
    let n = TEXTURE_SIZE;
    let columns = leaves.len().max(barks.len()) as u32;
    let mut sheet = Texture {
        width: n * columns,
        height: 2 * n,
        rgba: vec![0; (4 * n * columns * 2 * n) as usize],
    };
    for (row, textures) in [leaves, barks].iter().enumerate() {
        for (column, t) in textures.iter().enumerate() {
            for y in 0..n {
                for x in 0..n {
                    let from = ((y * t.width + x) * 4) as usize;
                    let [r, g, b, a] = [0, 1, 2, 3].map(|c| u32::from(t.rgba[from + c]));
                    // Straight alpha over black.
                    let over = |c: u32| (c * a / 255) as u8;
                    let to =
                        (((row as u32 * n + y) * sheet.width + column as u32 * n + x) * 4) as usize;
                    sheet.rgba[to..to + 4].copy_from_slice(&[over(r), over(g), over(b), 255]);
                }
            }
        }
    }
    sylva::base::file::write(&out, |w| w.write_all(&sheet.png()))?;
    println!("wrote {out}: {} x {} pixels", sheet.width, sheet.height);
    Ok(())
}
