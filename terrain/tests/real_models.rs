//! Real elevation models (`tests/data/dems`, sources and licences in its README) read in each
//! format: their sizes, spacing in metres, known heights, nodata, and their square heightmaps.

use std::path::PathBuf;

use sylva_terrain::dem::{ElevationModel, Georeference, ReadOptions};

fn model(name: &str) -> ElevationModel {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests/data/dems", name]
        .iter()
        .collect();
    ElevationModel::read(&path, &ReadOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

fn range(m: &ElevationModel) -> (f32, f32) {
    m.heights
        .iter()
        .fold((f32::MAX, f32::MIN), |(lo, hi), &h| (lo.min(h), hi.max(h)))
}

#[test]
fn srtm_hgt_white_mountains() {
    let m = model("N44W072.hgt");
    assert_eq!((m.width, m.height, m.nodata), (1201, 1201, 0));
    // Mount Washington is the tile's top.
    assert_eq!(range(&m), (115.0, 1908.0));
    // 3 arc-seconds at 44.5 degrees north.
    assert!(
        (m.spacing[0] - 66.2).abs() < 0.2 && (m.spacing[1] - 92.6).abs() < 0.2,
        "{:?}",
        m.spacing
    );
    assert_eq!(
        m.georeference,
        Some(Georeference::Geographic {
            longitude: -72.0,
            latitude: 45.0,
            step: [1.0 / 1200.0; 2]
        })
    );
    let (map, extent) = m.to_heightmap().unwrap();
    assert_eq!(map.size(), 2049);
    assert!((extent[1] - 1200.0 * m.spacing[1]).abs() < 1.0);
}

#[test]
fn ascii_grids_of_nasadem_and_srtm() {
    let bijou = model("west_bijou_escarpment.asc");
    assert_eq!((bijou.width, bijou.height, bijou.nodata), (129, 67, 0));
    let (lo, hi) = range(&bijou);
    assert!(
        (1689.0..1691.0).contains(&lo) && (1806.0..1808.0).contains(&hi),
        "{lo} {hi}"
    );
    assert!((bijou.spacing[1] - 30.8).abs() < 0.2, "{:?}", bijou.spacing);
    let front = model("front_range_srtmgl3.asc");
    assert_eq!((front.width, front.height), (144, 144));
    let (lo, hi) = range(&front);
    assert!(
        (2185.0..2187.0).contains(&lo) && (3344.0..3346.0).contains(&hi),
        "{lo} {hi}"
    );
    let (map, _) = front.to_heightmap().unwrap();
    assert_eq!(map.size(), 257);
}

#[test]
fn a_float_geotiff_with_nodata_filled() {
    let m = model("dem-hills.tiff");
    assert_eq!((m.width, m.height, m.nodata), (333, 218, 949));
    let (lo, hi) = range(&m);
    // Filled cells stay within the heights around them.
    assert!(lo >= 137.0 && hi <= 169.0, "{lo} {hi}");
    // 1/3 arc-second at 39.4 degrees north: about 7.9 m by 10.3 m.
    assert!(
        (m.spacing[0] - 7.95).abs() < 0.1 && (m.spacing[1] - 10.28).abs() < 0.1,
        "{:?}",
        m.spacing
    );
    let (map, extent) = m.to_heightmap().unwrap();
    assert_eq!(map.size(), 513);
    assert!(extent[0] > extent[1]);
    // --spacing overrides the file's.
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "tests/data/dems/dem-hills.tiff"]
        .iter()
        .collect();
    let flat = ElevationModel::read(&path, &ReadOptions::default().with_spacing(2.0)).unwrap();
    assert_eq!(flat.spacing, [2.0, 2.0]);
}

#[test]
fn the_real_models_fractal_character() {
    use sylva_terrain::analysis::FractalAnalysis;
    for name in [
        "N44W072.hgt",
        "front_range_srtmgl3.asc",
        "west_bijou_escarpment.asc",
        "dem-hills.tiff",
    ] {
        let a = FractalAnalysis::of_model(&model(name));
        println!(
            "{name}: H {:.3} (spectrum {:.3}) over {:.0}..{:.0} m, axes {:.3?}, anisotropy {:.2}, heights {:.0}..{:.0}",
            a.hurst,
            a.spectrum_fit.hurst,
            a.variogram_fit.scale_range[0],
            a.variogram_fit.scale_range[1],
            a.hurst_axes,
            a.anisotropy,
            a.heights.min,
            a.heights.max
        );
        // Real land is rough but not noise: H between the extremes, over a range of scales.
        assert!(a.hurst > 0.2 && a.hurst < 1.05, "{name}: H {}", a.hurst);
        assert!(
            a.variogram_fit.scale_range[1] > 3.0 * a.variogram_fit.scale_range[0],
            "{name}: {:?}",
            a.variogram_fit.scale_range
        );
    }
}

#[test]
fn terrain_made_to_match_real_land() {
    use sylva_terrain::analysis::FractalAnalysis;
    use sylva_terrain::{Heightmap, refine, synthesize_like};
    for name in [
        "front_range_srtmgl3.asc",
        "west_bijou_escarpment.asc",
        "dem-hills.tiff",
    ] {
        let m = model(name);
        let real = FractalAnalysis::of_model(&m);
        let map = m.square_heightmap().unwrap();
        let made =
            FractalAnalysis::of(&synthesize_like(&real, map.size(), map.spacing(), 1).unwrap());
        let h = made.hurst_over(real.variogram_fit.scale_range).unwrap();
        assert!(
            (h - real.hurst).abs() < 0.15,
            "{name}: made {h:.3}, real {:.3}",
            real.hurst
        );
        assert!((made.heights.std_dev - real.heights.std_dev).abs() < 0.1 * real.heights.std_dev);
        // Fractal interpolation from a quarter of the samples keeps every one of them.
        let quarter = (map.size() - 1) / 4 + 1;
        let coarse = Heightmap::from_heights(
            quarter,
            map.spacing() * 4.0,
            (0..quarter * quarter)
                .map(|i| map.get(i % quarter * 4, i / quarter * 4))
                .collect(),
        )
        .unwrap();
        let fine = refine(&coarse, 2, &FractalAnalysis::of(&coarse), 1).unwrap();
        assert_eq!(fine.size(), map.size());
        for i in 0..quarter * quarter {
            assert_eq!(
                fine.get(i % quarter * 4, i / quarter * 4),
                coarse.get(i % quarter, i / quarter)
            );
        }
    }
}
