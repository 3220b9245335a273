//! USD export, streamed: a forest as one `UsdGeomPointInstancer` whose prototypes are the
//! cached instances its placements use and whose arrays are the placements, with the terrain
//! and `UsdPreviewSurface` materials, as text (`.usda`), the textures as PNG beside it.
//!
//! Like the GLB writer, a first pass counts the placements of every instance, which decides
//! the prototypes; a second spells every placement on the core that placed it into scratch
//! files beside the destination (one per array), which the file then takes in order. Memory
//! holds the caches and a wave of blocks' text, however many trees there are.

mod instancer;
mod material;
mod mesh;
mod text;

use std::path::{Path, PathBuf};

use sylva_base::file::AtomicFile;
use sylva_forest::{ForestBuilder, Rect, StreamStats};
use sylva_terrain::{HeightField, TerrainMesh};

use crate::census::{Drawn, Node, check_geometry, count_placements, drawn_instances};
use crate::error::ExportError;
use crate::spill::TreeSpill;
use instancer::Arrays;
use material::{MATERIALS, SpeciesMaterials, write_terrain_material};
use mesh::MeshData;
use text::{identifier, tuple};

/// USD export settings. Like every options struct of sylva: public fields, [`Default`], and a
/// `with_*` method per field for chaining.
///
/// ```
/// use sylva_export::UsdOptions;
/// let options = UsdOptions::default().with_roughness(0.7);
/// assert_eq!(options.roughness, 0.7);
/// ```
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct UsdOptions {
    /// Terrain tint, linear RGB, multiplied into the ground colours by slope and altitude
    /// ([`sylva_terrain::ground`]) that the terrain's vertices carry as `displayColor`.
    /// Default: [1, 1, 1] (no tint).
    pub terrain_colour: [f32; 3],
    /// Roughness of every material (all are dielectric: metallic 0). Default: 0.9.
    pub roughness: f32,
}

impl Default for UsdOptions {
    fn default() -> Self {
        UsdOptions {
            terrain_colour: [1.0, 1.0, 1.0],
            roughness: 0.9,
        }
    }
}

impl UsdOptions {
    /// Sets [`UsdOptions::terrain_colour`].
    #[must_use]
    pub fn with_terrain_colour(mut self, terrain_colour: [f32; 3]) -> Self {
        self.terrain_colour = terrain_colour;
        self
    }

    /// Sets [`UsdOptions::roughness`].
    #[must_use]
    pub fn with_roughness(mut self, roughness: f32) -> Self {
        self.roughness = roughness;
        self
    }
}

/// What [`write_usda`] wrote.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct UsdStats {
    /// Size of the `.usda` file in bytes (the images not included).
    pub bytes: u64,
    /// PNG images written beside it.
    pub images: usize,
    /// Trees in the forest.
    pub trees: usize,
    /// Of which seedlings.
    pub seedlings: usize,
    /// Prototypes of the point instancer: the instances placed at least once that have
    /// geometry.
    pub prototypes: usize,
    /// Placements written, the point instancer's instances.
    pub placements: usize,
    /// Placements of instances with no geometry, left out.
    pub empty_placements: usize,
    /// Times the forest was streamed: once to count, once to write.
    pub passes: usize,
}

/// The folder of `path` (`.` for a bare file name) and the name, relative to it, of the
/// folder its images go in: `forest.usda` puts them in `forest_textures/`.
fn image_folder(path: &Path) -> Result<(PathBuf, String), ExportError> {
    let usda = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("usda"));
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned());
    let (true, Some(stem)) = (usda, stem) else {
        return Err(ExportError::NotUsda {
            path: path.to_path_buf(),
        });
    };
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((folder, format!("{stem}_textures")))
}

/// Writes the forest of `region` on `terrain`, and optionally a terrain mesh, as USD text at
/// `path` (which must end in `.usda`), and its species' textures as PNG in a folder beside
/// it (`forest.usda`: `forest_textures/`). The stage is Y-up in metres with `/Forest` its
/// default prim: `/Forest/Materials`, `/Forest/Terrain` and the point instancer
/// `/Forest/Trees`, whose prototypes (under `/Forest/Trees/Prototypes`) are the instances the
/// placements use, each a bark and a leaf mesh. Every file is written whole or not at all;
/// the output is a pure function of the inputs, at any thread count.
///
/// ```
/// use sylva_export::{UsdOptions, write_usda};
/// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
///     .with_budget(1 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(40.0) };
/// let folder = std::env::temp_dir().join(format!("sylva-usd-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&folder).unwrap();
/// let path = folder.join("hazels.usda");
/// let region = Rect::new(Vec2::ZERO, Vec2::splat(40.0));
/// let stats = write_usda(&builder, &ground, region, None, &UsdOptions::default(), &path)?;
/// let text = std::fs::read_to_string(&path).unwrap();
/// assert!(text.starts_with("#usda 1.0"));
/// assert!(text.contains("def PointInstancer \"Trees\""));
/// assert!(stats.placements >= stats.trees && stats.prototypes > 0);
/// // Bark, its normal map and the leaves, as PNG beside the file.
/// assert_eq!(std::fs::read_dir(folder.join("hazels_textures")).unwrap().count(), stats.images);
/// assert_eq!(stats.images, 3);
/// # std::fs::remove_dir_all(&folder).ok();
/// # Ok::<(), sylva_export::ExportError>(())
/// ```
pub fn write_usda(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Sync),
    region: Rect,
    terrain_mesh: Option<&TerrainMesh>,
    options: &UsdOptions,
    path: &Path,
) -> Result<UsdStats, ExportError> {
    let (folder, images) = image_folder(path)?;
    let variants = builder.variants();
    let species = &builder.config().species;
    let terrain_mesh = terrain_mesh.filter(|t| !t.indices.is_empty());
    check_geometry(variants, terrain_mesh)?;

    // Pass 1: which instances are placed, and how often, keeping each block's trees.
    let spill = TreeSpill::create(path, builder.blocks(region)?.len())?;
    let (counts, counted) = count_placements(builder, terrain, region, &spill)?;
    let Drawn {
        nodes,
        node_of,
        placements,
        empty_placements,
        ..
    } = drawn_instances(variants, &counts);
    drop(counts);

    // Materials and images for the species the prototypes draw.
    let mut used_species: Vec<usize> = nodes.iter().map(|n| variants[n.variant].species).collect();
    used_species.sort_unstable();
    used_species.dedup();
    let prims = species_prims(builder);
    let materials: Vec<Option<SpeciesMaterials>> = (0..species.len())
        .map(|s| {
            used_species
                .contains(&s)
                .then(|| SpeciesMaterials::new(&prims[s], &format!("./{images}")))
        })
        .collect();
    let mut image_count = 0;
    for (s, m) in materials.iter().enumerate() {
        if let Some(m) = m {
            image_count += m.write_images(&species[s], &folder)?;
        }
    }

    // Each prototype's reach from its origin bounds the instancer's extent.
    let radius: Vec<f32> = nodes
        .iter()
        .map(|n| {
            let c = &variants[n.variant].cache;
            let inst = &c.instances[n.instance];
            inst.bark
                .range()
                .map(|k| c.bark[k])
                .chain(inst.leaves.range().map(|k| c.leaves[k]))
                .map(|i| glam::Vec3::from(c.vertices[i as usize].position).length())
                .fold(0.0, f32::max)
        })
        .collect();

    // Pass 2: every placement, spelt into scratch files.
    let arrays = Arrays::stream(
        builder,
        (terrain, region, &spill),
        (&node_of, &radius),
        path,
    )?;
    drop(spill);
    if arrays.placements != placements {
        return Err(crate::error::Invalid::Layout {
            written: arrays.placements as u64,
            layout: placements as u64,
        }
        .into());
    }

    let mut file = AtomicFile::create(path)?;
    let mut head = String::from(
        "#usda 1.0\n(\n    defaultPrim = \"Forest\"\n    doc = \"A forest by sylva: a point instancer of cached branch instances on a terrain.\"\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\ndef Xform \"Forest\"\n{\n    def Scope \"Materials\"\n    {\n",
    );
    let mut material_text = String::new();
    for (s, m) in materials.iter().enumerate() {
        if let Some(m) = m {
            m.write(&mut material_text, &species[s], options.roughness);
        }
    }
    let terrain_material = format!("{MATERIALS}/terrain");
    if terrain_mesh.is_some() {
        write_terrain_material(&mut material_text, &terrain_material, options.roughness);
    }
    // Materials sit one level deeper than the writer's indent.
    for line in material_text.lines() {
        head.push_str("    ");
        head.push_str(line);
        head.push('\n');
    }
    head.push_str("    }\n");
    file.put(head.as_bytes())?;
    if let Some(t) = terrain_mesh {
        let tint = options.terrain_colour;
        let snow = crate::phenology::snow_lying(builder);
        let colours = t
            .ground_colours_under_snow(snow)
            .into_iter()
            .map(|c| [c[0] * tint[0], c[1] * tint[1], c[2] * tint[2]])
            .collect();
        let mut text = String::new();
        MeshData::of_terrain(t, colours).write(
            &mut text,
            ("    ", "Terrain"),
            &terrain_material,
            false,
        );
        file.put(text.as_bytes())?;
    }

    // The instancer: its extent, arrays and prototypes.
    let mut opening =
        String::from("    def PointInstancer \"Trees\"\n    {\n        float3[] extent = [");
    tuple(&mut opening, &arrays.extent[0]);
    opening.push_str(", ");
    tuple(&mut opening, &arrays.extent[1]);
    opening.push_str("]\n");
    file.put(opening.as_bytes())?;
    arrays.write(&mut file, "        ")?;
    let names: Vec<String> = nodes
        .iter()
        .enumerate()
        .map(|(k, n)| prototype_name(builder, &prims, k, n))
        .collect();
    let mut relation = String::from("        rel prototypes = [\n");
    for (k, name) in names.iter().enumerate() {
        let comma = if k + 1 < names.len() { "," } else { "" };
        relation.push_str(&format!(
            "            </Forest/Trees/Prototypes/{name}>{comma}\n"
        ));
    }
    relation.push_str("        ]\n\n        def Scope \"Prototypes\"\n        {\n");
    file.put(relation.as_bytes())?;
    write_prototypes(&mut file, builder, &nodes, &names, &materials)?;
    file.put(b"        }\n    }\n}\n")?;
    let bytes = file.size()?;
    file.commit()?;
    let StreamStats {
        trees, seedlings, ..
    } = counted;
    Ok(UsdStats {
        bytes,
        images: image_count,
        trees,
        seedlings,
        prototypes: nodes.len(),
        placements,
        empty_placements,
        passes: 2,
    })
}

/// Each species' name as a prim name, made unique by its index where two spell the same.
fn species_prims(builder: &ForestBuilder) -> Vec<String> {
    let names: Vec<String> = builder
        .config()
        .species
        .iter()
        .map(|s| identifier(&s.name))
        .collect();
    names
        .iter()
        .enumerate()
        .map(|(k, n)| {
            if names.iter().filter(|m| *m == n).count() > 1 {
                format!("{n}_{k}")
            } else {
                n.clone()
            }
        })
        .collect()
}

/// The prim name of prototype `k`: unique by its number, readable by the rest.
fn prototype_name(builder: &ForestBuilder, prims: &[String], k: usize, node: &Node) -> String {
    let variant = &builder.variants()[node.variant];
    let inst = &variant.cache.instances[node.instance];
    let tag = if variant.seedling { "seedling" } else { "tree" };
    format!(
        "p{k}_{}_{tag}_branch_{}_age_{}",
        prims[variant.species], inst.id, inst.age
    )
}

/// Every prototype, an `Xform` holding its bark and leaf meshes, written one at a time.
fn write_prototypes(
    file: &mut AtomicFile,
    builder: &ForestBuilder,
    nodes: &[Node],
    names: &[String],
    materials: &[Option<SpeciesMaterials>],
) -> Result<(), ExportError> {
    let variants = builder.variants();
    let mut scratch: Vec<Vec<u32>> = variants
        .iter()
        .map(|v| vec![u32::MAX; v.cache.vertices.len()])
        .collect();
    for (node, name) in nodes.iter().zip(names) {
        let variant = &variants[node.variant];
        let (c, inst) = (&variant.cache, &variant.cache.instances[node.instance]);
        let Some(m) = &materials[variant.species] else {
            continue;
        };
        let mut text = format!("            def Xform \"{name}\"\n            {{\n");
        let parts = [
            ("bark", &c.bark[inst.bark.range()], &m.bark, false),
            ("leaves", &c.leaves[inst.leaves.range()], &m.leaves, true),
        ];
        // Leaf cards are drawn from both sides and carry their order in the year.
        for (part, triangles, material, cards) in parts {
            if triangles.is_empty() {
                continue;
            }
            let mesh =
                MeshData::of_triangles(&c.vertices, triangles, cards, &mut scratch[node.variant]);
            let indent = "                ";
            mesh.write(&mut text, (indent, part), material, cards);
        }
        text.push_str("            }\n");
        file.put(text.as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_usda_is_written_and_images_go_beside_it() {
        let (folder, images) = image_folder(Path::new("out/forest.usda")).unwrap();
        assert_eq!(
            (folder, images.as_str()),
            (PathBuf::from("out"), "forest_textures")
        );
        let (folder, _) = image_folder(Path::new("forest.USDA")).unwrap();
        assert_eq!(folder, PathBuf::from("."));
        for bad in ["forest.usdc", "forest.usdz", "forest", "forest.glb"] {
            let e = image_folder(Path::new(bad)).unwrap_err();
            assert!(matches!(e, ExportError::NotUsda { .. }), "{bad}");
            assert!(e.to_string().contains(".usda"), "{e}");
        }
    }
}
