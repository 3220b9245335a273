//! A vlab model folder of fuzzed files: the bytes up to the first NUL are the model's `.l`
//! file, the rest an included `a.h` (which may include itself or reach outside the folder):
//! reading the model ends in a grammar or an error, never a panic, a hang or a runaway.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_lsys::LSystem;

fuzz_target!(|data: &[u8]| {
    let (model, included) = match data.iter().position(|&b| b == 0) {
        Some(k) => (&data[..k], &data[k + 1..]),
        None => (data, &[][..]),
    };
    let dir = std::env::temp_dir().join(format!("sylva-fuzz-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("model.l"), model).unwrap();
    std::fs::write(dir.join("a.h"), included).unwrap();
    let _ = LSystem::from_model_dir(&dir);
});
