//! Parses arbitrary text in each dialect other than sylva's own (cpfg's `.l` files with
//! their preprocessor, multi-line statements and blocks; L-Py's declarative subset); a
//! grammar that parses is derived under tight limits and printed back in sylva's notation,
//! which must parse again.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_lsys::{Dialect, LSystem, Limits};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else { return };
    for dialect in [Dialect::Cpfg, Dialect::LPy] {
        if let Ok(g) = LSystem::parse_dialect(text, dialect) {
            let limits = Limits::default()
                .with_max_modules(20_000)
                .with_max_params(20_000)
                .with_max_generations(8)
                .with_max_statements(1_000_000);
            if let Ok(word) = g.derive_with(8, 1, &limits) {
                let _ = g.interpretation(&word, 1);
            }
            LSystem::parse(&g.to_string()).expect("printed grammar parses back");
        }
    }
});
