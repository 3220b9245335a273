//! Worlds as tiles: a tile is the same bytes whichever process, thread or order writes it;
//! the tileset's structure; bad tile ids and schemes.

use serde_json::Value;
use sylva_export::{
    Level, TileId, TileScheme, TilesetOptions, tile_path, write_tile, write_tileset,
};
use sylva_forest::Rect;
use sylva_terrain::glam::Vec2;
use sylva_terrain::{DiamondSquare, Heightmap};

fn world() -> (sylva_forest::ForestBuilder, Heightmap, TileScheme) {
    let map = DiamondSquare::new(33)
        .with_spacing(240.0 / 32.0)
        .with_seed(3)
        .with_amplitude(6.0)
        .generate()
        .unwrap();
    let scheme = TileScheme::new(Rect::new(Vec2::ZERO, Vec2::splat(240.0)), 60.0, 2).unwrap();
    (sylva_testkit::builder(5), map, scheme)
}

fn dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("sylva-tiles-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn a_tile_is_the_same_bytes_whoever_writes_it_and_in_whatever_order() {
    let (builder, map, scheme) = world();
    let ids = scheme.ids();
    assert_eq!(ids.len(), 4 + 16);
    let (a, b) = (dir("a"), dir("b"));
    for &id in &ids {
        write_tile(&builder, &map, &scheme, id, &a).unwrap();
    }
    // The other copy in reverse order, from two threads, with a builder built anew.
    let (builder_b, _, _) = world();
    std::thread::scope(|s| {
        let (first, second) = ids.split_at(ids.len() / 2);
        for part in [first, second] {
            let (builder_b, map, scheme, b) = (&builder_b, &map, &scheme, &b);
            s.spawn(move || {
                for &id in part.iter().rev() {
                    write_tile(builder_b, map, scheme, id, b).unwrap();
                }
            });
        }
    });
    for &id in &ids {
        let (x, y) = (
            std::fs::read(tile_path(&a, id)).unwrap(),
            std::fs::read(tile_path(&b, id)).unwrap(),
        );
        assert!(x == y, "tile {id} differs");
    }
    std::fs::remove_dir_all(&a).ok();
    std::fs::remove_dir_all(&b).ok();
}

#[test]
fn the_tileset_refines_coarse_proxies_into_fine_branch_tiles() {
    let (builder, map, scheme) = world();
    let d = dir("tileset");
    write_tileset(&builder, &map, &scheme, &d, &TilesetOptions::default()).unwrap();
    for id in scheme.ids() {
        write_tile(&builder, &map, &scheme, id, &d).unwrap();
    }
    let text = std::fs::read_to_string(d.join("tileset.json")).unwrap();
    let t: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(t["asset"]["version"], "1.1");
    let root = &t["root"];
    assert_eq!(root["transform"].as_array().unwrap().len(), 16);
    let coarse = root["children"].as_array().unwrap();
    assert_eq!(coarse.len(), 4);
    let root_error = root["geometricError"].as_f64().unwrap();
    for c in coarse {
        let error = c["geometricError"].as_f64().unwrap();
        assert!(error > 0.0 && error < root_error);
        assert_eq!(c["refine"], "REPLACE");
        let fine = c["children"].as_array().unwrap();
        assert_eq!(fine.len(), 4);
        for f in fine.iter().chain(std::iter::once(c)) {
            let uri = f["content"]["uri"].as_str().unwrap();
            assert!(d.join(uri).is_file(), "{uri}");
            assert_eq!(f["boundingVolume"]["box"].as_array().unwrap().len(), 12);
        }
        assert!(
            fine.iter()
                .all(|f| f["geometricError"].as_f64() == Some(0.0))
        );
    }
    assert!(d.join("shared.bin").is_file());
    // A fine tile refers to the shared file instead of embedding the geometry.
    let glb = std::fs::read(tile_path(
        &d,
        TileId {
            level: Level::Fine,
            x: 1,
            y: 1,
        },
    ))
    .unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    assert_eq!(json["buffers"][1]["uri"], "../shared.bin");
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn fine_tiles_with_levels_are_forest_files_of_their_own() {
    let (builder, map, scheme) = world();
    let scheme = scheme.with_fine_levels(true);
    let d = dir("levels");
    write_tileset(&builder, &map, &scheme, &d, &TilesetOptions::default()).unwrap();
    let id = TileId {
        level: Level::Fine,
        x: 1,
        y: 1,
    };
    write_tile(&builder, &map, &scheme, id, &d).unwrap();
    // Nothing shared: no shared.bin, and the tile refers to no other file.
    assert!(!d.join("shared.bin").exists());
    let glb = std::fs::read(tile_path(&d, id)).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json: Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let buffers = json["buffers"].as_array().unwrap();
    assert!(
        buffers.iter().all(|b| b.get("uri").is_none()),
        "{buffers:?}"
    );
    // Its trees carry their levels and impostors in cells, as a forest file's do.
    let nodes = json["nodes"].as_array().unwrap();
    let grouped: Vec<&Value> = nodes
        .iter()
        .filter(|n| n["extras"]["sylva_levels"].is_object())
        .collect();
    assert!(!grouped.is_empty());
    assert!(
        grouped
            .iter()
            .all(|n| n["extensions"]["MSFT_lod"]["ids"].is_array())
    );
    assert!(nodes.iter().any(|n| n["extras"]["sylva_cell"].is_object()));
    // The same tile without levels is smaller: it shares its geometry.
    let (_, _, shared) = world();
    let e = dir("levels-shared");
    write_tile(&builder, &map, &shared, id, &e).unwrap();
    assert!(std::fs::metadata(tile_path(&e, id)).unwrap().len() < glb.len() as u64);
    std::fs::remove_dir_all(&d).ok();
    std::fs::remove_dir_all(&e).ok();
}

#[test]
fn bad_tile_ids_and_schemes_are_refused() {
    let (builder, map, scheme) = world();
    let d = dir("bad");
    let outside = TileId {
        level: Level::Fine,
        x: 4,
        y: 0,
    };
    let e = write_tile(&builder, &map, &scheme, outside, &d).unwrap_err();
    assert!(e.to_string().contains("outside the world"), "{e}");
    assert!(!tile_path(&d, outside).exists());
    for bad in ["x_1_2", "f_1", "f_1_2_3", "f_-1_2", "c_a_b", ""] {
        assert!(bad.parse::<TileId>().is_err(), "{bad}");
    }
    assert_eq!(
        "c_3_4".parse::<TileId>().unwrap(),
        TileId {
            level: Level::Coarse,
            x: 3,
            y: 4
        }
    );
    let world = Rect::new(Vec2::ZERO, Vec2::splat(20_000.0));
    assert!(TileScheme::new(world, 5.0, 4).is_err(), "tiles under 10 m");
    // Issue 60: 20 km of 20 m tiles was a million tiles and a 1.06 GB tileset.json.
    let e = TileScheme::new(world, 20.0, 1).unwrap_err().to_string();
    assert!(e.contains("1000 x 1000 tiles"), "{e}");
    assert!(e.contains("tileset.json of about 1160 MB"), "{e}");
    assert!(
        e.contains("use tiles of at least 79 m (--tile-size)"),
        "{e}"
    );
    assert!(TileScheme::new(world, 79.0, 1).is_ok());
    assert!(TileScheme::new(world, 78.0, 1).is_err());
    assert!(
        TileScheme::new(world, 30_000.0, 4).is_err(),
        "tiles larger than the world"
    );
    assert!(TileScheme::new(world, 500.0, 0).is_err());
    assert!(TileScheme::new(Rect::new(Vec2::ZERO, Vec2::ZERO), 50.0, 4).is_err());
}
