//! Parses arbitrary text as a grammar and as a word; a grammar that parses is derived under
//! tight limits and printed back, which must parse again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_lsys::{LSystem, Limits, Word};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    let _ = text.parse::<Word>();
    if let Ok(g) = LSystem::parse(text) {
        let limits = Limits::default().with_max_modules(20_000).with_max_params(20_000).with_max_generations(8);
        let _ = g.derive_with(8, 1, &limits);
        LSystem::parse(&g.to_string()).expect("printed grammar parses back");
    }
});
