//! A run's output files, checked before its work: each one a file the run may replace
//! (not a device, a FIFO or a folder: `sylva_base::file::writable_destination`), and no file
//! named twice (`--out X --heightmap X` wrote the heightmap over the forest).

use std::path::{Path, PathBuf};

use crate::Failure;

/// Checks `outputs`, each named by its flag and path: an error for one the run may not
/// replace (exit 1) or for two naming one file (exit 2). Paths are compared as the files
/// they would write: a link's target, in its folder's own name.
pub(crate) fn check_outputs(outputs: &[(&str, &Path)]) -> Result<(), Failure> {
    let mut files: Vec<(&str, &Path, PathBuf)> = Vec::new();
    for &(flag, path) in outputs {
        let file = canonical(&sylva::base::file::writable_destination(path)?);
        if let Some((other, _, _)) = files.iter().find(|(_, _, f)| *f == file) {
            return Err(Failure::usage(format!(
                "{other} and {flag} both name {}: give each output its own file",
                path.display()
            )));
        }
        files.push((flag, path, file));
    }
    Ok(())
}

/// `file` in its folder's canonical name (the file itself may not exist yet).
fn canonical(file: &Path) -> PathBuf {
    let folder = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let folder = std::fs::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
    folder.join(file.file_name().unwrap_or_default())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_file_named_twice_is_refused_with_both_flags() {
        let e = check_outputs(&[
            ("--out", Path::new("x.glb")),
            ("--heightmap", Path::new("./x.glb")),
        ])
        .unwrap_err();
        assert_eq!(e.code(), 2);
        assert!(
            e.to_string().contains("--out and --heightmap both name"),
            "{e}"
        );
        assert!(
            check_outputs(&[
                ("--out", Path::new("x.glb")),
                ("--heightmap", Path::new("x.png"))
            ])
            .is_ok()
        );
    }
}
