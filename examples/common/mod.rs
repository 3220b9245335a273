//! Helpers shared by the examples.
#![allow(dead_code, reason = "each example uses only some of these helpers")]

/// Peak resident memory of this process in bytes (Linux `/proc`); 0 where unavailable.
pub(crate) fn peak_rss() -> u64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<u64>().ok())
        })
        .map_or(0, |kb| kb * 1024)
}

/// Parses a flag's value, naming the flag in the error.
pub(crate) fn parse_value<T: std::str::FromStr>(
    name: &str,
    value: Option<String>,
) -> Result<T, String>
where
    T::Err: std::fmt::Display,
{
    let v = value.ok_or_else(|| format!("{name} needs a value"))?;
    v.parse().map_err(|e| format!("{name} '{v}': {e}"))
}

/// Prints the usage to stdout and exits with success, as `--help` should.
pub(crate) fn print_help(usage: &str) -> ! {
    println!("{usage}");
    std::process::exit(0)
}

/// Ends an example: errors go to stderr with a failure status.
pub(crate) fn finish(result: Result<(), String>) -> std::process::ExitCode {
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            std::process::ExitCode::FAILURE
        }
    }
}

/// The forest example's five species (oak, birch, spruce, pine, hazel), read from the species
/// files compiled in, so the examples run from any folder.
pub(crate) fn default_species() -> Result<Vec<sylva::forest::Species>, String> {
    const FILES: [(&str, &str); 5] = [
        (
            "examples/species/oak.species",
            include_str!("../species/oak.species"),
        ),
        (
            "examples/species/birch.species",
            include_str!("../species/birch.species"),
        ),
        (
            "examples/species/spruce.species",
            include_str!("../species/spruce.species"),
        ),
        (
            "examples/species/pine.species",
            include_str!("../species/pine.species"),
        ),
        (
            "examples/species/hazel.species",
            include_str!("../species/hazel.species"),
        ),
    ];
    FILES
        .iter()
        .map(|(path, text)| {
            sylva::forest::Species::parse_file(text, std::path::Path::new(path))
                .map_err(|e| e.to_string())
        })
        .collect()
}

/// The forest example's terrain: smoothed diamond-square, 257 samples a side over `side`
/// metres, relief 6% of the side.
pub(crate) fn default_terrain(seed: u64, side: f32) -> Result<sylva::terrain::Heightmap, String> {
    use sylva::terrain::{DiamondSquare, EdgeMode};
    let ds = DiamondSquare::new(257)
        .with_seed(seed)
        .with_spacing(side / 256.0)
        .with_roughness(0.75)
        .with_amplitude(side * 0.06);
    let mut map = ds.generate().map_err(|e| e.to_string())?;
    map.smooth(2.0, EdgeMode::Mirror)
        .map_err(|e| e.to_string())?;
    Ok(map)
}
