//! Parses arbitrary text as a species file. Grammar paths it names resolve under a directory
//! that does not exist, so every grammar is a preset or a clean file error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_forest::Species;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = Species::parse_file(text, std::path::Path::new("/nonexistent-sylva-fuzz/x.species"));
});
