//! Streaming: the world cut into square cells; cells near the camera are generated off the
//! main thread and spawned as entities, cells left behind are despawned. Fine cells carry
//! every placement at every level of detail (Bevy's visibility ranges choose one per
//! distance) and an impostor per canopy tree; coarse cells, farther out, the impostors alone.
//! A cell's content is a pure function of the forest and the cell.

use std::collections::HashMap;
use std::sync::Arc;

use bevy::mesh::MeshTag;
use bevy::prelude::*;
use bevy::tasks::{AsyncComputeTaskPool, Task, futures::check_ready};
use sylva::forest::{ForestBuilder, ForestError, PlacementBlock, Rect, tree_wind};
use sylva::instancing::{CompactTree, Similarity};
use sylva::terrain::HeightField;
use sylva::terrain::glam::Vec2;

use crate::assets::{ForestAssets, MESH_LEVELS};
use crate::wind::WindMaterial;
use crate::{Forest, ForestCamera, ForestPart, ForestStatus};

/// A cell: column, row, and whether it is fine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub(crate) struct CellKey {
    x: u32,
    z: u32,
    fine: bool,
}

/// One placement (or one tree's impostor) ready to spawn.
#[derive(Debug, Clone, Copy)]
struct Placed {
    variant: u16,
    instance: u32,
    transform: Transform,
    /// The tree's wind phase in 1/65536ths (the shader reads it as the mesh tag).
    tag: u32,
}

/// What a cell spawns.
#[derive(Debug, Default)]
struct CellContent {
    placements: Vec<Placed>,
    impostors: Vec<Placed>,
}

/// The cells spawned and those being generated.
#[derive(Resource, Default)]
pub(crate) struct Cells {
    resident: HashMap<CellKey, Vec<Entity>>,
    pending: HashMap<CellKey, Task<Result<CellContent, ForestError>>>,
}

fn transform(s: &Similarity) -> Transform {
    Transform {
        translation: Vec3::from_array(s.translation.to_array()),
        rotation: Quat::from_array(s.rotation.normalize().to_array()),
        scale: Vec3::splat(s.scale),
    }
}

fn tag(tree: &CompactTree) -> u32 {
    (tree_wind(tree)[3].clamp(0.0, 0.99998) * 65536.0) as u32
}

/// The content of cell `rect`: a pure function of the forest and the cell.
fn generate(
    builder: &ForestBuilder,
    terrain: &(dyn HeightField + Send + Sync),
    rect: Rect,
    fine: bool,
) -> Result<CellContent, ForestError> {
    let variants = builder.variants();
    let canopy = |t: &CompactTree| {
        variants
            .get(usize::from(t.variant))
            .is_some_and(|v| !v.seedling)
    };
    let impostor = |t: &CompactTree| Placed {
        variant: t.variant,
        instance: 0,
        transform: transform(&t.root()),
        tag: tag(t),
    };
    let mut content = CellContent::default();
    if !fine {
        let trees = builder.trees(terrain, rect);
        content.impostors = trees.iter().filter(|t| canopy(t)).map(impostor).collect();
        return Ok(content);
    }
    builder.stream(terrain, rect, &mut |block: &PlacementBlock| {
        for p in &block.placements {
            let tree = block.trees.get(p.tree as usize);
            content.placements.push(Placed {
                variant: p.variant as u16,
                instance: p.instance,
                transform: transform(&p.transform),
                tag: tree.map_or(0, tag),
            });
        }
        content
            .impostors
            .extend(block.trees.iter().filter(|t| canopy(t)).map(impostor));
        Ok(())
    })?;
    Ok(content)
}

impl Cells {
    /// The cells a camera at `eye` wants, nearest first.
    fn wanted(forest: &Forest, fine_distance: f32, eye: Vec2) -> Vec<(f32, CellKey)> {
        let s = &forest.settings;
        let cell = s.cell.max(1.0);
        let size = forest.region.max - forest.region.min;
        let count = |side: f32| (side / cell).ceil().max(1.0) as u32;
        let (nx, nz) = (count(size.x), count(size.y));
        let local = eye - Vec2::new(forest.region.min.x, forest.region.min.y);
        let span = |at: f32, n: u32| {
            let lo = ((at - s.view_distance) / cell).floor().max(0.0) as u32;
            let hi = (((at + s.view_distance) / cell).floor().max(0.0) as u32).min(n - 1);
            lo..=hi
        };
        let mut out = Vec::new();
        for z in span(local.y, nz) {
            for x in span(local.x, nx) {
                let lo = Vec2::new(x as f32, z as f32) * cell;
                let hi = (lo + Vec2::splat(cell)).min(size);
                let d = local.distance(local.clamp(lo, hi));
                if d <= s.view_distance {
                    out.push((
                        d,
                        CellKey {
                            x,
                            z,
                            fine: d <= fine_distance,
                        },
                    ));
                }
            }
        }
        out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        out
    }

    fn rect(forest: &Forest, key: CellKey) -> Rect {
        let cell = forest.settings.cell.max(1.0);
        let min = forest.region.min + Vec2::new(key.x as f32, key.z as f32) * cell;
        Rect::new(min, (min + Vec2::splat(cell)).min(forest.region.max))
    }
}

/// Asks for the cells the camera wants (a few at a time, nearest first), and despawns those
/// no longer wanted once whatever stands in for them has arrived.
pub(crate) fn stream_cells(
    mut commands: Commands,
    forest: Res<Forest>,
    assets: Option<Res<ForestAssets>>,
    camera: Query<&GlobalTransform, With<ForestCamera>>,
    mut cells: ResMut<Cells>,
    mut status: ResMut<ForestStatus>,
) {
    let (Some(assets), Ok(camera)) = (assets, camera.single()) else {
        return;
    };
    let eye = camera.translation();
    let fine_distance = forest.settings.fine_distance.unwrap_or_else(|| {
        // Fine cells reach as far as any variant's impostor takes over, and a cell more.
        let farthest = assets
            .variants
            .iter()
            .filter(|v| v.impostor.is_some())
            .map(|v| v.ranges[MESH_LEVELS].start_margin.end)
            .fold(0.0f32, f32::max);
        farthest.min(forest.settings.view_distance) + forest.settings.cell
    });
    let wanted = Cells::wanted(&forest, fine_distance, Vec2::new(eye.x, eye.z));
    let wanted_keys: HashMap<CellKey, f32> = wanted.iter().map(|&(d, k)| (k, d)).collect();
    // Generation off the main thread, a few cells at a time.
    let pool = AsyncComputeTaskPool::get();
    for &(_, key) in &wanted {
        if cells.pending.len() >= forest.settings.tasks.max(1) {
            break;
        }
        if cells.resident.contains_key(&key) || cells.pending.contains_key(&key) {
            continue;
        }
        let (builder, terrain) = (Arc::clone(&forest.builder), Arc::clone(&forest.terrain));
        let rect = Cells::rect(&forest, key);
        let task = pool.spawn(async move { generate(&builder, terrain.as_ref(), rect, key.fine) });
        cells.pending.insert(key, task);
    }
    // Work no longer wanted is dropped (dropping a task cancels it).
    cells.pending.retain(|k, _| wanted_keys.contains_key(k));
    // A resident cell stays while wanted, or while it stands in for its other level.
    let standing_in: Vec<CellKey> = wanted
        .iter()
        .filter(|(_, k)| !cells.resident.contains_key(k))
        .map(|(_, k)| CellKey {
            fine: !k.fine,
            ..*k
        })
        .collect();
    let gone: Vec<CellKey> = cells
        .resident
        .keys()
        .filter(|k| !wanted_keys.contains_key(k) && !standing_in.contains(k))
        .copied()
        .collect();
    for key in gone {
        if let Some(entities) = cells.resident.remove(&key) {
            for e in entities {
                commands.entity(e).despawn();
            }
        }
    }
    status.resident = cells.resident.len();
    // Wanted and not spawned yet, whether in generation or waiting for its turn.
    status.pending = wanted
        .iter()
        .filter(|(_, k)| !cells.resident.contains_key(k))
        .count();
    status.entities = cells.resident.values().map(Vec::len).sum();
}

/// Spawns the cells whose generation has finished.
pub(crate) fn spawn_cells(
    mut commands: Commands,
    mut cells: ResMut<Cells>,
    assets: Option<ResMut<ForestAssets>>,
    mut meshes: ResMut<Assets<Mesh>>,
    mut status: ResMut<ForestStatus>,
) {
    let Some(mut assets) = assets else { return };
    let done: Vec<(CellKey, Result<CellContent, ForestError>)> = cells
        .pending
        .iter_mut()
        .filter_map(|(k, task)| check_ready(task).map(|r| (*k, r)))
        .collect();
    for (key, content) in done {
        cells.pending.remove(&key);
        let content = match content {
            Ok(c) => c,
            Err(e) => {
                status.error = Some(e.to_string());
                continue;
            }
        };
        let mut entities = Vec::new();
        for p in &content.placements {
            let variant = usize::from(p.variant);
            let Some(v) = assets.variants.get(variant) else {
                continue;
            };
            let (bark, leaves, ranges) = (v.bark.clone(), v.leaves.clone(), v.ranges.clone());
            for (level, range) in ranges.iter().take(MESH_LEVELS).enumerate() {
                for (is_bark, material) in [(true, &bark), (false, &leaves)] {
                    let key = (p.variant, p.instance, level as u8, is_bark);
                    let Some(mesh) = assets.instance_mesh(key, &mut meshes) else {
                        continue;
                    };
                    entities.push(
                        commands
                            .spawn((
                                Mesh3d(mesh),
                                MeshMaterial3d::<WindMaterial>(material.clone()),
                                p.transform,
                                range.clone(),
                                MeshTag(p.tag),
                                ForestPart,
                            ))
                            .id(),
                    );
                }
            }
        }
        status.placements += content.placements.len();
        for p in &content.impostors {
            let Some(v) = assets.variants.get(usize::from(p.variant)) else {
                continue;
            };
            let Some((mesh, material)) = &v.impostor else {
                continue;
            };
            entities.push(
                commands
                    .spawn((
                        Mesh3d(mesh.clone()),
                        MeshMaterial3d(material.clone()),
                        p.transform,
                        v.ranges[MESH_LEVELS].clone(),
                        ForestPart,
                    ))
                    .id(),
            );
        }
        cells.resident.insert(key, entities);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use sylva::forest::{ForestConfig, Species};
    use sylva::terrain::FlatPlane;

    fn forest(side: f32) -> Forest {
        let mut config = ForestConfig::new(vec![
            Species::from_preset("sylva-hazel", 3).expect("species"),
        ]);
        config.budget = 1 << 20;
        let builder = ForestBuilder::new(config).expect("builder");
        let ground = FlatPlane {
            height: 0.0,
            min: Vec2::ZERO,
            max: Vec2::splat(side),
        };
        Forest::new(
            builder,
            Arc::new(ground),
            Rect::new(Vec2::ZERO, Vec2::splat(side)),
        )
    }

    /// The camera wants the cells within the view distance, nearest first, fine within the
    /// fine distance and coarse beyond.
    #[test]
    fn the_nearest_cells_come_first() {
        let forest = forest(1000.0);
        let wanted = Cells::wanted(&forest, 150.0, Vec2::new(510.0, 490.0));
        assert!(wanted.windows(2).all(|w| w[0].0 <= w[1].0));
        assert_eq!((wanted[0].1.x, wanted[0].1.z), (5, 4));
        for (d, k) in &wanted {
            assert!(*d <= forest.settings.view_distance);
            assert_eq!(k.fine, *d <= 150.0);
        }
        assert!(wanted.iter().any(|(_, k)| !k.fine));
    }

    /// A fine cell holds every placement of its trees and an impostor per canopy tree; a
    /// coarse one the impostors alone; both are the same every time.
    #[test]
    fn cells_are_pure_functions_of_the_forest() {
        let forest = forest(200.0);
        let rect = Cells::rect(
            &forest,
            CellKey {
                x: 0,
                z: 0,
                fine: true,
            },
        );
        let fine = generate(&forest.builder, forest.terrain.as_ref(), rect, true).expect("fine");
        let coarse =
            generate(&forest.builder, forest.terrain.as_ref(), rect, false).expect("coarse");
        assert!(fine.placements.len() > fine.impostors.len());
        assert!(coarse.placements.is_empty());
        assert_eq!(fine.impostors.len(), coarse.impostors.len());
        let again = generate(&forest.builder, forest.terrain.as_ref(), rect, true).expect("fine");
        let key = |c: &CellContent| {
            c.placements
                .iter()
                .map(|p| {
                    (
                        p.variant,
                        p.instance,
                        p.transform.translation.to_array().map(f32::to_bits),
                    )
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(key(&fine), key(&again));
    }
}
