//! A vlab model folder of fuzzed files. The bytes are cut at NULs: the model's `.l` file, an
//! included `a.h` (which may include itself or reach outside the folder), the view file
//! `model.v` (which may name any files), and the data file that `d.func`, `d.con` and `d.s`
//! all hold. Reading the model ends in a grammar or an error, never a panic, a hang or a
//! runaway; the data readers and the surface's quads are run on the data file directly too.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sylva_lsys::LSystem;
use sylva_lsys::curve::Curve;
use sylva_lsys::spline::SplineFunction;
use sylva_lsys::surface::Surface;

fuzz_target!(|data: &[u8]| {
    let mut parts = data.splitn(4, |&b| b == 0);
    let model = parts.next().unwrap_or_default();
    let included = parts.next().unwrap_or_default();
    let view = parts.next().unwrap_or_default();
    let file = parts.next().unwrap_or_default();
    let dir = std::env::temp_dir().join(format!("sylva-fuzz-model-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("model.l"), model).unwrap();
    std::fs::write(dir.join("a.h"), included).unwrap();
    std::fs::write(dir.join("model.v"), view).unwrap();
    for name in ["d.func", "d.con", "d.s"] {
        std::fs::write(dir.join(name), file).unwrap();
    }
    if let Ok(model) = LSystem::from_model_dir(&dir) {
        let _ = model.derive_with(2, 0, &sylva_lsys::Limits::DEFAULT.with_max_modules(10_000));
    }
    if let Ok(text) = std::str::from_utf8(file) {
        let _ = SplineFunction::parse_func(text, None);
        if let Ok(curve) = Curve::parse(text, None) {
            let _ = (curve.length(), curve.at_length(0.5));
        }
        if let Ok(surface) = Surface::parse(text, 'l') {
            let _ = surface.quads();
        }
    }
});
