//! Trees of any age: how each bundled species grows with the years (its Chapman-Richards
//! height curve) and how a tree of each age is drawn: the generation its grammar is derived
//! to, the scale, and what that makes its crown, trunk and leaves; then each species at four
//! ages and in its damaged forms (broken top, dieback, dead, snag, fallen), drawn to one
//! scale on the CPU. The README's table of ages and its picture of forms are this program's
//! output.
//!
//! ```text
//! cargo run --release --example ages [OUT.png]
//! ```

use sylva::export::lod::{OrthoView, Picture, TreeLook, draw, variant_tree};
use sylva::forest::{ForestBuilder, ForestConfig, TreeForm};
use sylva::terrain::glam::Vec3;
use sylva::turtle::Mesh;

/// The ages in the table, years.
const AGES: [f32; 7] = [3.0, 10.0, 17.0, 30.0, 50.0, 80.0, 150.0];
/// The ages drawn, years.
const DRAWN_AGES: [f32; 4] = [5.0, 15.0, 40.0, 100.0];
/// Pixels across each picture.
const SIZE: u32 = 160;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::env::args().nth(1).unwrap_or_else(|| "ages.png".into());
    let config = ForestConfig::new(sylva::presets::species()?)
        .with_budget(32 << 20)
        .with_all_ages(true);
    let builder = ForestBuilder::new(config)?;
    println!(
        "| species | age (years) | height (m) | drawn as | scale | crown width (m) | trunk above its flare, drawn (cm) | stem diameter at 1.3 m, allometry (cm) | leaf cards |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    let mut rows = Vec::new();
    for (i, species) in builder.config().species.iter().enumerate() {
        let life = &species.life;
        for age in AGES {
            let height = life.height(age);
            let Some((TreeForm::Live(g), scale)) = builder.live_form(i, height) else {
                continue;
            };
            let mesh = species.mesh(g, 1)?;
            let (lo, hi) = mesh.bounds().ok_or("an empty tree")?;
            let width = (hi.x - lo.x).max(hi.z - lo.z) * scale;
            println!(
                "| {} | {age} | {height:.1} | generation {g} | {scale:.2} | {width:.1} | {:.0} | {:.0} | {} |",
                species.name,
                200.0 * trunk_radius(species, g)? * scale,
                100.0 * life.diameter(height),
                mesh.leaves.len() / 6,
            );
            // What the table shows: older is taller and wider, never fewer leaves.
            assert!(height > 0.0 && width > 0.0);
        }
        // The picture: the ages, then the damaged forms of a tree of the canopy's height.
        let look = TreeLook::of(species);
        let mut trees: Vec<(Mesh, f32)> = Vec::new();
        for age in DRAWN_AGES {
            let (form, scale) = builder
                .live_form(i, life.height(age))
                .ok_or("no live form")?;
            trees.push((form_mesh(&builder, i, form)?, scale));
        }
        let &(_, canopy) = builder.form_heights(i).last().ok_or("no forms")?;
        let tall = life.height(100.0) / canopy;
        for form in TreeForm::DAMAGED {
            trees.push((form_mesh(&builder, i, form)?, tall));
        }
        let half = 0.55
            * trees
                .iter()
                .filter_map(|(m, s)| m.bounds().map(|(lo, hi)| (hi - lo).max_element() * s))
                .fold(0.0f32, f32::max);
        let row: Vec<Picture> = trees
            .iter()
            .map(|(mesh, scale)| {
                let scaled = scaled(mesh, *scale);
                // Every tree stands on the picture's floor, in its middle (a fallen one's
                // length too), seen from a little above.
                let middle = scaled.bounds().map_or(0.0, |(lo, hi)| 0.5 * (lo.x + hi.x));
                let view = OrthoView {
                    centre: Vec3::new(middle, half * 0.95, 0.0),
                    toward: Vec3::new(0.0, 0.1, 1.0).normalize(),
                    half,
                    size: SIZE,
                };
                draw(&scaled, &look, &view)
            })
            .collect();
        rows.push(row);
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
    std::fs::write(&out, Picture::sheet(&rows, [0.55, 0.68, 0.85]).png())?;
    println!(
        "wrote {out}: per species, ages {DRAWN_AGES:?} then broken top, dieback, dead, snag and fallen"
    );
    Ok(())
}

/// One tree of `species` in `form`, assembled from its variant's cache as a forest draws it.
fn form_mesh(
    builder: &ForestBuilder,
    species: usize,
    form: TreeForm,
) -> Result<Mesh, Box<dyn std::error::Error>> {
    let v = builder
        .variant_of(species, form)
        .ok_or("no variant of the form")?;
    Ok(variant_tree(&builder.variants()[usize::from(v)], 3)?)
}

/// The mesh grown by `scale` about its root.
fn scaled(mesh: &Mesh, scale: f32) -> Mesh {
    let mut out = mesh.clone();
    for v in &mut out.vertices {
        v.position = v.position.map(|x| x * scale);
    }
    out
}

/// The radius the turtle gives the first segment of `species`' tree at `generations` (seed
/// 1): its trunk, above the root flare.
fn trunk_radius(
    species: &sylva::forest::Species,
    generations: u32,
) -> Result<f32, Box<dyn std::error::Error>> {
    let word = species.grammar.derive(generations, 1)?;
    let word = species.grammar.interpretation(&word, 1)?;
    let mut skeleton = sylva::turtle::Skeleton::default();
    sylva::turtle::interpret(&word, &species.turtle, &mut skeleton)?;
    Ok(skeleton.bones.first().map_or(0.0, |b| b.start_radius))
}
