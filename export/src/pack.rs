//! Asset packs: a forest's trees as files for engines' own tools. Per species variant a GLB
//! of its levels of detail (`NAME_LOD0` .. `NAME_LODn` under a node `NAME`, the last level the
//! impostor's cards) with its impostor atlas beside it (colour, normals, depth as PNG), the
//! region's trees as placements (CSV and JSON) for scatter tools, and `pack.json` saying what
//! is where. The folder is replaced whole or not at all.

use std::fmt::Write as _;
use std::path::Path;

use rayon::prelude::*;
use serde_json::json;
use sylva_forest::{ForestBuilder, ForestError, Rect};
use sylva_terrain::HeightField;
use sylva_turtle::Mesh;

use crate::error::ExportError;
use crate::gltf::{LodCards, LodMesh, write_lod_glb};
use crate::lod::{CARD_ALPHA_CUTOFF, LodChain, VariantLods, impostor_cards, simplify_mesh};

/// What [`write_asset_pack`] wrote.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct PackStats {
    /// Species variants, a GLB each.
    pub variants: usize,
    /// Levels of detail written over all variants (the impostors' cards included).
    pub levels: usize,
    /// Trees in the placements files.
    pub trees: usize,
    /// Files written.
    pub files: usize,
    /// Their bytes.
    pub bytes: u64,
}

/// A name fit for a file and an engine's node: letters, digits, `_` and `-`.
fn file_name(text: &str) -> String {
    let name: String = text
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '_'
            }
        })
        .collect();
    if name.is_empty() { "tree".into() } else { name }
}

/// Whether a folder entry is a pack's own.
fn ours(name: &str) -> bool {
    name.starts_with('.')
        || [".glb", ".png", ".csv", ".json"]
            .iter()
            .any(|ext| name.ends_with(ext))
}

/// Writes the asset pack of `builder`'s species into `dir`, with the trees of `region` on
/// `terrain` as its placements, levels and impostors by `chain`. The folder must be new,
/// empty or a pack's: it is replaced whole.
///
/// ```
/// use sylva_export::lod::LodChain;
/// use sylva_export::write_asset_pack;
/// use sylva_forest::{ForestBuilder, ForestConfig, Rect, Species};
/// use sylva_terrain::{FlatPlane, glam::Vec2};
///
/// let config = ForestConfig::new(vec![Species::from_preset("sylva-hazel", 3)?])
///     .with_budget(1 << 20);
/// let builder = ForestBuilder::new(config)?;
/// let ground = FlatPlane { height: 0.0, min: Vec2::ZERO, max: Vec2::splat(40.0) };
/// let dir = std::env::temp_dir().join(format!("sylva-pack-doc-{}", std::process::id()));
/// let mut chain = LodChain::default();
/// chain.impostor = chain.impostor.with_view_size(32);
/// let stats = write_asset_pack(&builder, &ground, Rect::new(Vec2::ZERO, Vec2::splat(40.0)), &chain, &dir)?;
/// assert_eq!(stats.variants, builder.variants().len());
/// assert!(dir.join("pack.json").exists() && dir.join("placements.csv").exists());
/// # std::fs::remove_dir_all(&dir).ok();
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn write_asset_pack(
    builder: &ForestBuilder,
    terrain: &dyn HeightField,
    region: Rect,
    chain: &LodChain,
    dir: &Path,
) -> Result<PackStats, ExportError> {
    if let Some(entry) = sylva_base::file::foreign_entry(dir, ours) {
        return Err(ExportError::NotPackFolder {
            folder: dir.to_path_buf(),
            entry,
        });
    }
    let species = &builder.config().species;
    let variants = builder.variants();
    let lods: Vec<VariantLods> = variants
        .par_iter()
        .map(|v| VariantLods::build(v, &species[v.species], chain))
        .collect::<Result<_, _>>()
        .map_err(ForestError::from)?;
    // Each variant's name: its species and form, made unique.
    let mut names: Vec<String> = Vec::with_capacity(variants.len());
    for v in variants {
        let form = if v.seedling { "young" } else { "canopy" };
        let base = format!("{}_{form}", file_name(&species[v.species].name));
        let mut name = base.clone();
        let mut k = 2;
        while names.contains(&name) {
            name = format!("{base}_{k}");
            k += 1;
        }
        names.push(name);
    }
    let trees = builder.trees(terrain, region);
    let mut failure: Option<ExportError> = None;
    let mut stats = PackStats::default();
    let filled = sylva_base::file::replace_folder(dir, |staging| {
        let result = fill(staging, builder, &lods, &names, &trees, chain);
        match result {
            Ok(s) => {
                stats = s;
                Ok(())
            }
            Err(e) => {
                let message = e.to_string();
                failure = Some(e);
                Err(std::io::Error::other(message))
            }
        }
    });
    if let Some(e) = failure {
        return Err(e);
    }
    filled?;
    Ok(stats)
}

/// Writes every file of the pack into `staging`.
fn fill(
    staging: &Path,
    builder: &ForestBuilder,
    lods: &[VariantLods],
    names: &[String],
    trees: &[sylva_instancing::CompactTree],
    chain: &LodChain,
) -> Result<PackStats, ExportError> {
    let species = &builder.config().species;
    let variants = builder.variants();
    let mut stats = PackStats {
        variants: variants.len(),
        trees: trees.len(),
        ..PackStats::default()
    };
    let mut manifest = Vec::new();
    let put = |name: &str, bytes: &[u8], stats: &mut PackStats| -> Result<(), ExportError> {
        let path = staging.join(name);
        std::fs::write(&path, bytes).map_err(|e| sylva_base::file::FileError::new(&path, e))?;
        stats.files += 1;
        stats.bytes += bytes.len() as u64;
        Ok(())
    };
    for ((v, lod), name) in variants.iter().zip(lods).zip(names) {
        let s = &species[v.species];
        let meshes: Vec<Mesh> = std::iter::once(lod.tree.clone())
            .chain(lod.levels.iter().map(|l| simplify_mesh(&lod.tree, l)))
            .collect();
        let from = |k: usize| {
            if k == 0 {
                0.0
            } else {
                lod.errors
                    .get(k - 1)
                    .map_or(f32::INFINITY, |&e| chain.distance_for(e))
            }
        };
        let levels: Vec<LodMesh<'_>> = meshes
            .iter()
            .enumerate()
            .map(|(k, mesh)| LodMesh {
                mesh,
                from: from(k),
            })
            .collect();
        let card_mesh = lod.impostor.as_ref().map(impostor_cards);
        let atlas = lod.impostor.as_ref().map(|i| i.cards_texture().png());
        let cards = card_mesh
            .as_ref()
            .zip(atlas.as_deref())
            .map(|(mesh, atlas)| LodCards {
                mesh,
                from: from(meshes.len()),
                atlas,
                cutoff: CARD_ALPHA_CUTOFF,
            });
        let glb = format!("{name}.glb");
        let bytes = write_lod_glb(name, s, &levels, cards, &staging.join(&glb))?;
        stats.files += 1;
        stats.bytes += bytes as u64;
        stats.levels += levels.len() + usize::from(cards.is_some());
        let mut entry = json!({
            "name": name,
            "species": s.name,
            "form": if v.seedling { "young" } else { "canopy" },
            "file": glb,
            "levels": levels.iter().enumerate().map(|(k, l)| json!({
                "node": format!("{name}_LOD{k}"),
                "triangles": l.mesh.triangle_count(),
                "from_distance_1080p": l.from,
            })).collect::<Vec<_>>(),
        });
        if let (Some(impostor), Some(cards)) = (&lod.impostor, cards) {
            let files = [
                ("colour", impostor.colour.png()),
                ("normal", impostor.normal.png()),
                ("depth", impostor.depth.png()),
            ];
            for (kind, png) in &files {
                put(&format!("{name}_impostor_{kind}.png"), png, &mut stats)?;
            }
            entry["impostor"] = json!({
                "node": format!("{name}_LOD{}", levels.len()),
                "from_distance_1080p": cards.from,
                "colour": format!("{name}_impostor_colour.png"),
                "normal": format!("{name}_impostor_normal.png"),
                "depth": format!("{name}_impostor_depth.png"),
                "grid": impostor.grid,
                "view_size": impostor.view_size,
                "centre": impostor.centre,
                "radius": impostor.radius,
                "mapping": "hemi-octahedral: view (i, j) of the N x N grid looks from the unit direction at uv = (i, j) / (N - 1), where a direction (x, y, z), y up, maps to uv = ((p + q) / 2 + 1/2, (p - q) / 2 + 1/2) with (p, q) = (x, z) / (|x| + y + |z|); it fills column i, row j of the atlas, rows from the top",
                "normal_encoding": "rgb = n / 2 + 1/2 in the tree's space; alpha = share of leaves",
                "depth_encoding": "grey = nearness towards the viewer over the radius, 0.5 at the centre's plane",
            });
        }
        manifest.push(entry);
    }
    // Placements: one row per tree, in the order the forest places them.
    let (mut csv, mut rows) = (
        String::from("variant,species,form,x,y,z,yaw_degrees,scale,seed\n"),
        Vec::with_capacity(trees.len()),
    );
    for t in trees {
        let v = usize::from(t.variant);
        let (Some(variant), Some(name)) = (variants.get(v), names.get(v)) else {
            continue;
        };
        let s = &species[variant.species].name;
        let form = if variant.seedling { "young" } else { "canopy" };
        let [x, y, z] = t.position;
        let yaw = t.yaw.to_degrees();
        let _ = writeln!(
            csv,
            "{name},{s},{form},{x:.3},{y:.3},{z:.3},{yaw:.2},{:.4},{}",
            t.scale, t.seed
        );
        rows.push(json!({
            "variant": name,
            "position": [x, y, z],
            "yaw_degrees": yaw,
            "scale": t.scale,
            "seed": t.seed,
        }));
    }
    put("placements.csv", csv.as_bytes(), &mut stats)?;
    let placements = json!({ "up": "+Y", "units": "metres", "trees": rows });
    put(
        "placements.json",
        placements.to_string().as_bytes(),
        &mut stats,
    )?;
    let pack = json!({
        "generator": "sylva",
        "lod_naming": "each GLB holds a node NAME with children NAME_LOD0 (full detail) .. NAME_LODn (the impostor's cards, when it has one); every child's mesh is named like it and its extras give sylva_lod, triangles and from_distance_1080p",
        "switch_distances": format!("from screen-space error: {} pixels at {:.1} pixels per radian (1080 rows, 60 degrees)", chain.pixel_error, chain.pixels_per_radian),
        "variants": manifest,
        "placements": { "csv": "placements.csv", "json": "placements.json", "trees": trees.len() },
    });
    put("pack.json", pack.to_string().as_bytes(), &mut stats)?;
    Ok(stats)
}
