//! Reads arbitrary bytes as a 16-bit PNG heightmap and as 16- and 32-bit RAW. Whatever the
//! header claims, reading ends in a heightmap or an error, within bounded memory.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_terrain::{HeightRange, Heightmap};

fuzz_target!(|data: &[u8]| {
    let range = HeightRange { min: -10.0, max: 100.0 };
    if let Ok(map) = Heightmap::read_png16(std::io::Cursor::new(data), Some((range, 2.0))) {
        assert!(map.heights().iter().all(|h| h.is_finite()));
    }
    let _ = Heightmap::from_raw16(data, range, 1.0);
    if let Ok(map) = Heightmap::from_raw32(data, 1.0) {
        assert!(map.heights().iter().all(|h| h.is_finite()));
    }
});
