//! Parses arbitrary bytes as a served world's description (`POST /worlds`): never a panic;
//! a description that parses has a canonical form that parses to itself, with the same id,
//! and its inline species files parse or fail cleanly.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_world::WorldDescription;

fuzz_target!(|data: &[u8]| {
    let Ok(description) = WorldDescription::parse(data) else { return };
    let canonical = description.canonical();
    let again = WorldDescription::parse(canonical.as_bytes()).expect("a canonical form parses");
    assert_eq!(again.canonical(), canonical);
    assert_eq!(again.id(), description.id());
    let _ = description.species();
});
