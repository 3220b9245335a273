//! A forest GLB in cells with its levels of detail (issue 59): the scene holds the terrain and
//! a node per cell, each cell a node per variant, each variant its instanced nodes at full
//! detail; every variant node's MSFT_lod levels and its impostor are outside the scene, the
//! levels over the full level's own placements, the impostor a placement per tree; and the
//! file without cells and levels is the flat file it was.

use std::collections::{BTreeSet, HashMap};

use serde_json::Value;
use sylva_export::{GltfOptions, write_glb};
use sylva_testkit::{export_case, scratch};

fn json_of(path: &std::path::Path) -> Value {
    let bytes = std::fs::read(path).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&bytes[20..20 + json_len]).unwrap()
}

fn node(json: &Value, k: u64) -> &Value {
    &json["nodes"][k as usize]
}

fn indices(v: &Value) -> Vec<u64> {
    v.as_array()
        .map(|a| a.iter().map(|x| x.as_u64().unwrap()).collect())
        .unwrap_or_default()
}

/// Every node reachable from `roots` through children.
fn reachable(json: &Value, roots: &[u64]) -> BTreeSet<u64> {
    let mut seen = BTreeSet::new();
    let mut stack = roots.to_vec();
    while let Some(n) = stack.pop() {
        if seen.insert(n) {
            stack.extend(indices(&node(json, n)["children"]));
        }
    }
    seen
}

/// The TRANSLATION accessor and its count of an instanced node.
fn placements(json: &Value, k: u64) -> Option<(u64, u64)> {
    let ext = node(json, k)["extensions"].get("EXT_mesh_gpu_instancing")?;
    let t = ext["attributes"]["TRANSLATION"].as_u64().unwrap();
    Some((t, json["accessors"][t as usize]["count"].as_u64().unwrap()))
}

#[test]
fn a_forest_in_cells_carries_its_levels_outside_the_scene() {
    let (b, map, region) = export_case();
    let path = scratch("levels");
    let stats = write_glb(
        &b,
        &map,
        region,
        Some(&map.mesh(1).unwrap()),
        &GltfOptions::default(),
        &path,
    )
    .unwrap();
    let json = json_of(&path);
    // MSFT_lod is used, never required: a client without it draws full detail.
    let used: Vec<&str> = json["extensionsUsed"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_str().unwrap())
        .collect();
    assert!(used.contains(&"MSFT_lod"), "{used:?}");
    assert!(
        !json["extensionsRequired"]
            .as_array()
            .unwrap()
            .iter()
            .any(|v| v == "MSFT_lod")
    );
    // The scene: the terrain and the cells (192 m of 64 m cells: 3 x 3, and one seedling cell).
    let roots = indices(&json["scenes"][0]["nodes"]);
    let cells: Vec<u64> = roots
        .iter()
        .copied()
        .filter(|&k| node(&json, k).get("extras").is_some())
        .collect();
    assert_eq!(roots.len(), cells.len() + 1, "the terrain and the cells");
    assert_eq!(stats.cells, cells.len());
    assert!(
        (2..=10).contains(&cells.len()),
        "{} cells of {} m",
        cells.len(),
        stats.cell_size
    );
    let scene = reachable(&json, &roots);
    let mut full_placements = 0;
    let mut impostor_placements = 0;
    let mut groups = 0;
    for &cell in &cells {
        let c = &node(&json, cell)["extras"]["sylva_cell"];
        assert!(c["min"][0].as_f64().unwrap() < c["max"][0].as_f64().unwrap());
        for group in indices(&node(&json, cell)["children"]) {
            groups += 1;
            let g = node(&json, group);
            // The full level: instanced nodes whose placements stand in the cell's trees.
            let full: HashMap<u64, u64> = indices(&g["children"])
                .iter()
                .filter_map(|&k| placements(&json, k))
                .collect();
            assert!(!full.is_empty());
            full_placements += full.values().sum::<u64>();
            let levels = &g["extras"]["sylva_levels"];
            let from: Vec<f64> = levels["from"]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect();
            assert!(from.windows(2).all(|w| w[0] <= w[1]), "{from:?}");
            // The coarser levels: outside the scene, over the full level's accessors.
            let ids = indices(&g["extensions"]["MSFT_lod"]["ids"]);
            assert_eq!(ids.len(), 2, "the default chain's two coarser levels");
            let coverage = g["extras"]["MSFT_screencoverage"].as_array().unwrap();
            assert_eq!(coverage.len(), ids.len() + 1);
            for id in ids {
                assert!(!scene.contains(&id));
                for k in indices(&node(&json, id)["children"]) {
                    let (t, n) = placements(&json, k).unwrap();
                    assert_eq!(
                        full.get(&t),
                        Some(&n),
                        "a level places what its full level does"
                    );
                }
            }
            // The impostor: outside the scene, a placement per tree.
            let imp = levels["impostor"]
                .as_u64()
                .expect("every variant has an impostor");
            assert!(!scene.contains(&imp));
            let (_, n) = placements(&json, imp).unwrap();
            impostor_placements += n;
        }
    }
    assert!(groups >= cells.len());
    // Full detail holds every placement once; the impostors hold every tree once.
    assert_eq!(full_placements, stats.placements as u64);
    assert_eq!(impostor_placements, stats.trees as u64);
    assert_eq!(stats.impostor_placements, stats.trees);
    assert_eq!(
        stats.levels, 4,
        "full detail, two coarser levels and the impostor"
    );
    std::fs::remove_file(&path).ok();
}

#[test]
fn without_cells_and_levels_the_file_is_flat() {
    let (b, map, region) = export_case();
    let path = scratch("flat");
    let options = GltfOptions::default()
        .with_cell_size(None)
        .with_levels(None);
    let stats = write_glb(&b, &map, region, None, &options, &path).unwrap();
    let json = json_of(&path);
    // A node per instance, all in the scene, no levels.
    let roots = indices(&json["scenes"][0]["nodes"]);
    assert_eq!(roots.len(), json["nodes"].as_array().unwrap().len());
    assert_eq!(roots.len(), stats.instance_nodes);
    assert!(
        !json["extensionsUsed"]
            .as_array()
            .unwrap()
            .iter()
            .any(|v| v == "MSFT_lod")
    );
    assert_eq!(
        (stats.cells, stats.levels, stats.impostor_placements),
        (1, 1, 0)
    );
    // Cells alone: the same placements, grouped; more nodes, each of fewer placements.
    let cells_path = scratch("cells-only");
    let cells = write_glb(
        &b,
        &map,
        region,
        None,
        &GltfOptions::default().with_levels(None),
        &cells_path,
    )
    .unwrap();
    assert_eq!(cells.placements, stats.placements);
    assert!(cells.instance_nodes > stats.instance_nodes);
    assert!(
        !json_of(&cells_path)["extensionsUsed"]
            .as_array()
            .unwrap()
            .iter()
            .any(|v| v == "MSFT_lod")
    );
    std::fs::remove_file(&path).ok();
    std::fs::remove_file(&cells_path).ok();
}
