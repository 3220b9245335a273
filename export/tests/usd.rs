//! USD export: a point instancer whose arrays hold every placement the glTF holds, well-formed
//! usda, the same bytes at any thread count, textures beside the file, and nothing written
//! for a bad name.

use sylva_export::{ExportError, GltfOptions, UsdOptions, write_glb, write_usda};
use sylva_testkit::{export_case, fnv1a, scratch};

/// The elements of the array attribute `name` (`int[] protoIndices = [...]`), split at the
/// commas between them.
fn array<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
    let start = text.find(&format!(" {name} = [")).expect(name);
    let body = &text[start..];
    let open = body.find('[').unwrap() + 1;
    let close = body.find(']').unwrap();
    let body = &body[open..close];
    if body.is_empty() {
        return Vec::new();
    }
    // Tuples hold commas of their own: split between elements only.
    let mut depth = 0;
    let mut items = Vec::new();
    let mut from = 0;
    for (k, c) in body.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth -= 1,
            ',' if depth == 0 => {
                items.push(body[from..k].trim());
                from = k + 1;
            }
            _ => {}
        }
    }
    items.push(body[from..].trim());
    items
}

#[test]
fn the_instancer_holds_every_placement_the_gltf_holds() {
    let (b, map, region) = export_case();
    let mesh = map.mesh(1).unwrap();
    // The flat glTF: a node per used instance, as the instancer has a prototype per used
    // instance (a glTF in cells has a node per instance and cell).
    let flat = GltfOptions::default()
        .with_cell_size(None)
        .with_levels(None);
    let glb = write_glb(&b, &map, region, Some(&mesh), &flat, &scratch("usd-glb")).unwrap();
    let path = scratch("usd").with_file_name("forest.usda");
    let stats = write_usda(&b, &map, region, Some(&mesh), &UsdOptions::default(), &path).unwrap();
    assert_eq!(
        (stats.trees, stats.placements, stats.empty_placements),
        (glb.trees, glb.placements, glb.empty_placements)
    );
    assert_eq!(stats.prototypes, glb.instance_nodes);
    assert_eq!(stats.passes, 2);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.len() as u64, stats.bytes);
    assert!(text.starts_with("#usda 1.0\n"));
    for metadata in [
        "defaultPrim = \"Forest\"",
        "upAxis = \"Y\"",
        "metersPerUnit = 1",
    ] {
        assert!(text.contains(metadata), "{metadata}");
    }
    // Every array has an element per placement, and each index names a prototype.
    let ids = array(&text, "protoIndices");
    assert_eq!(ids.len(), stats.placements);
    for name in ["positions", "orientations", "scales"] {
        assert_eq!(array(&text, name).len(), stats.placements, "{name}");
    }
    let prototypes = array(&text, "prototypes");
    assert_eq!(prototypes.len(), stats.prototypes);
    assert!(
        prototypes
            .iter()
            .all(|p| p.starts_with("</Forest/Trees/Prototypes/p"))
    );
    let mut used = vec![false; stats.prototypes];
    for id in &ids {
        used[id.parse::<usize>().unwrap()] = true;
    }
    assert!(used.iter().all(|&u| u), "every prototype is placed");
    // Orientations are unit quaternions, real part first.
    for q in array(&text, "orientations").iter().take(500) {
        let parts: Vec<f32> = q
            .trim_matches(|c| c == '(' || c == ')')
            .split(',')
            .map(|v| v.trim().parse().unwrap())
            .collect();
        let length = parts.iter().map(|v| v * v).sum::<f32>().sqrt();
        assert!((length - 1.0).abs() < 1e-3, "{q}");
    }
    // usda's lists take line breaks after commas only; braces balance.
    assert!(text.lines().all(|l| !l.trim_start().starts_with(',')));
    assert_eq!(text.matches('{').count(), text.matches('}').count());
    // Each species drawn has its bark, bark normal and leaf images beside the file.
    let images = path.with_file_name("forest_textures");
    let pngs = std::fs::read_dir(&images).unwrap().count();
    assert_eq!(pngs, stats.images);
    assert!(pngs >= 3 && pngs.is_multiple_of(3));
    assert!(text.contains("@./forest_textures/"));
    // The scratch files are gone.
    let folder = path.parent().unwrap();
    let left: Vec<_> = std::fs::read_dir(folder)
        .unwrap()
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains("sylva"))
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

#[test]
fn the_file_is_the_same_at_any_thread_count() {
    let (b, map, region) = export_case();
    let write = |threads: usize| {
        let path = scratch(&format!("usd-threads-{threads}")).with_file_name("forest.usda");
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| write_usda(&b, &map, region, None, &UsdOptions::default(), &path))
            .unwrap();
        std::fs::read(&path).unwrap()
    };
    let reference = write(1);
    // Known answer: the bytes of this seed's file. A change here is a change of format (or of
    // the forest); say which in the commit. Issue 50: patches sized by the crowns' cover
    // seen from above (more trees), denser needle cards, cutoffs below each card's mean alpha;
    // the seasons' `primvars:sylva:phenology`, leaf materials' `sylva_phenology` data and the
    // instancer's `primvars:sylva:tree_phase`.
    assert_eq!(
        (reference.len(), fnv1a(&reference)),
        (7_528_439, 14_363_994_580_956_980_292),
        "the pinned file changed"
    );
    for threads in [2, 5] {
        assert!(
            write(threads) == reference,
            "{threads} threads changed the file"
        );
    }
}

#[test]
fn a_name_that_is_not_usda_writes_nothing() {
    let (b, map, region) = export_case();
    for name in ["forest.usdc", "forest.usdz", "forest"] {
        let path = scratch("usd-bad").with_file_name(name);
        let e = write_usda(&b, &map, region, None, &UsdOptions::default(), &path).unwrap_err();
        assert!(matches!(e, ExportError::NotUsda { .. }), "{e}");
        assert!(e.to_string().contains(".usda"), "{e}");
        assert!(!path.exists());
        assert!(!path.with_file_name("forest_textures").exists());
    }
}
