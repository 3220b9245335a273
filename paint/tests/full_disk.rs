//! Masks are a user's work: a save that fails part way, on a full disk or interrupted between
//! its renames, leaves the previous set loadable and says what happened.
//!
//! The full-disk case needs a small filesystem: CI mounts a 1 MiB tmpfs and names it in
//! `SYLVA_SMALL_DISK` (`.ci/run`). Without it that case is skipped, unless `CI` is set, when
//! its absence fails the test.

use sylva_base::file::previous_folder;
use sylva_forest::Rect;
use sylva_paint::{PaintError, PaintLayer, load_masks, save_masks};
use sylva_terrain::glam::Vec2;

const NAMES: [&str; 3] = ["oak", "birch", "pine"];

fn bounds() -> Rect {
    Rect::new(Vec2::ZERO, Vec2::splat(300.0))
}

/// A layer whose masks compress poorly: `cell` metres per cell, values from a hash.
fn noisy_layer(cell: f32, salt: u64) -> PaintLayer {
    let mut layer = PaintLayer::new(bounds(), cell, NAMES.len()).unwrap();
    for i in 0..layer.width() * layer.depth() {
        let h = sylva_base::hash::mix(i as u64 ^ salt.wrapping_mul(0x9e37_79b9_7f4a_7c15));
        let v = [
            (h & 0x3fff) as u16,
            ((h >> 16) & 0x3fff) as u16,
            ((h >> 32) & 0x3fff) as u16,
        ];
        layer.set(i, &v).unwrap();
    }
    layer
}

#[test]
fn a_save_on_a_full_disk_keeps_the_previous_set() {
    let Ok(disk) = std::env::var("SYLVA_SMALL_DISK") else {
        assert!(
            std::env::var_os("CI").is_none(),
            "CI must mount a small tmpfs and name it in SYLVA_SMALL_DISK"
        );
        eprintln!("SYLVA_SMALL_DISK is not set: the full-disk case is skipped");
        return;
    };
    let dir = std::path::Path::new(&disk).join("masks");
    let _ = std::fs::remove_dir_all(&dir);
    // 100 x 100 cells: three masks of at most 20 KB each fit in 1 MiB.
    let small = noisy_layer(3.0, 1);
    save_masks(&small, &NAMES, &dir).unwrap();
    // 600 x 600 cells: three masks of about 600 KB each (noise barely compresses) do not.
    let large = noisy_layer(0.5, 2);
    let err = save_masks(&large, &NAMES, &dir).unwrap_err();
    let PaintError::File(file) = &err else {
        panic!("expected a file error, got {err:?}");
    };
    assert_eq!(file.kind(), std::io::ErrorKind::StorageFull, "{err}");
    assert!(err.to_string().contains("free some space"), "{err}");
    // The previous set is whole, and nothing of the failed save is left to fill the disk.
    assert_eq!(load_masks(&dir, &NAMES, bounds()).unwrap(), small);
    let left: Vec<_> = std::fs::read_dir(&disk)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .collect();
    assert_eq!(left, ["masks"], "leftovers on the small disk");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_save_interrupted_between_its_renames_is_found_and_named() {
    let root = std::env::temp_dir().join(format!("sylva-interrupted-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    let dir = root.join("masks");
    let layer = noisy_layer(10.0, 3);
    save_masks(&layer, &NAMES, &dir).unwrap();
    // As a save stopped after moving the old set aside and before moving the new one in.
    std::fs::rename(&dir, previous_folder(&dir)).unwrap();
    let err = load_masks(&dir, &NAMES, bounds()).unwrap_err();
    assert!(matches!(err, PaintError::Interrupted { .. }), "{err:?}");
    assert!(err.to_string().contains("rename it to"), "{err}");
    // The next save replaces it and clears the copy aside.
    save_masks(&layer, &NAMES, &dir).unwrap();
    assert_eq!(load_masks(&dir, &NAMES, bounds()).unwrap(), layer);
    assert!(!previous_folder(&dir).exists());
    std::fs::remove_dir_all(&root).unwrap();
}

#[test]
fn masks_are_not_saved_over_a_folder_of_other_files() {
    let root = std::env::temp_dir().join(format!("sylva-not-masks-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    std::fs::write(root.join("notes.txt"), "mine").unwrap();
    let err = save_masks(&noisy_layer(10.0, 4), &NAMES, &root).unwrap_err();
    assert!(matches!(err, PaintError::NotMaskFolder { .. }), "{err:?}");
    assert_eq!(
        std::fs::read_to_string(root.join("notes.txt")).unwrap(),
        "mine"
    );
    std::fs::remove_dir_all(&root).unwrap();
}
