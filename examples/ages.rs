//! Trees of any age: how each bundled species grows with the years (its Chapman-Richards
//! height curve) and how a tree of each age is drawn: the generation its grammar is derived
//! to, the scale, and what that makes its crown, trunk and leaves. The README's table of
//! ages is this program's output.
//!
//! ```text
//! cargo run --release --example ages
//! ```

use sylva::forest::{ForestBuilder, ForestConfig, TreeForm};

/// The ages shown, years.
const AGES: [f32; 7] = [3.0, 10.0, 17.0, 30.0, 50.0, 80.0, 150.0];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let config = ForestConfig::new(sylva::presets::species()?)
        .with_budget(32 << 20)
        .with_all_ages(true);
    let builder = ForestBuilder::new(config)?;
    println!(
        "| species | age (years) | height (m) | drawn as | scale | crown width (m) | trunk at its base (cm) | stem diameter at 1.3 m (cm) | leaf cards |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for (i, species) in builder.config().species.iter().enumerate() {
        let life = &species.life;
        let mut meshes = std::collections::HashMap::new();
        for age in AGES {
            let height = life.height(age);
            let Some((TreeForm::Live(g), scale)) = builder.live_form(i, height) else {
                continue;
            };
            if !meshes.contains_key(&g) {
                meshes.insert(g, species.mesh(g, 1)?);
            }
            let mesh = &meshes[&g];
            let (lo, hi) = mesh.bounds().unwrap_or_default();
            let width = (hi.x - lo.x).max(hi.z - lo.z) * scale;
            // The trunk's base: the widest ring within the first 10 cm of the drawn tree.
            let base = mesh
                .vertices
                .iter()
                .filter(|v| v.position[1] < 0.1)
                .map(|v| v.position[0].hypot(v.position[2]))
                .fold(0.0f32, f32::max);
            println!(
                "| {} | {age} | {height:.1} | generation {g} | {scale:.2} | {width:.1} | {:.0} | {:.0} | {} |",
                species.name,
                200.0 * base * scale,
                100.0 * life.diameter(height),
                mesh.leaves.len() / 6,
            );
        }
    }
    println!();
    for (i, species) in builder.config().species.iter().enumerate() {
        let forms: Vec<String> = builder
            .form_heights(i)
            .iter()
            .map(|(g, h)| format!("{g}: {h:.1} m"))
            .collect();
        println!(
            "{} drawn heights by generation: {}",
            species.name,
            forms.join(", ")
        );
    }
    Ok(())
}
