//! Reads arbitrary bytes as an elevation model in each format sylva takes (GeoTIFF, SRTM
//! .hgt, ESRI ASCII grid, 16-bit PNG and RAW; the first byte picks which): never a panic, a
//! hang or an allocation beyond the limits; a model that reads resamples onto a heightmap
//! and gives a window of its samples.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_terrain::dem::{DemFormat, ElevationModel, ReadOptions, Window};

fuzz_target!(|data: &[u8]| {
    let Some((&pick, bytes)) = data.split_first() else { return };
    let format = match pick % 5 {
        0 => DemFormat::GeoTiff,
        1 => DemFormat::Hgt,
        2 => DemFormat::AsciiGrid,
        3 => DemFormat::Png16,
        _ => DemFormat::Raw16,
    };
    let options = ReadOptions::default().with_height_range(0.0, 100.0).with_spacing(2.0);
    if let Ok(model) = ElevationModel::parse(bytes, format, &options) {
        assert_eq!(model.heights.len(), model.width * model.height);
        assert!(model.heights.iter().all(|h| h.is_finite()));
        let _ = model.to_heightmap();
        // A window picked by the first byte: inside, it has its samples; outside, an error.
        let window = Window { column: usize::from(pick % 7), row: usize::from(pick / 7 % 7), width: 2, height: 3 };
        if let Ok(part) = model.crop(window) {
            assert_eq!(part.heights.len(), 6);
            assert_eq!(part.heights[0], model.heights[window.row * model.width + window.column]);
        }
    }
});
