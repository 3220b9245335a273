//! Why a subcommand failed, as one line for stderr and an exit status.

use std::fmt;

/// A subcommand's failure: the library's error (its message names the file, the value and
/// what to do) or a check of the command line's own.
#[derive(Debug)]
pub(crate) struct Failure {
    message: String,
    code: u8,
}

impl Failure {
    /// A flag's value the command refuses (exit status 2, as for a command line that does not
    /// parse).
    pub(crate) fn usage(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            code: 2,
        }
    }

    /// The job failed (exit status 1).
    pub(crate) fn job(message: impl Into<String>) -> Failure {
        Failure {
            message: message.into(),
            code: 1,
        }
    }

    /// The exit status.
    pub(crate) fn code(&self) -> u8 {
        self.code
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        // One line: a library message never spans lines, but a source chain might.
        f.write_str(&self.message.replace('\n', " "))
    }
}

impl<E: std::error::Error> From<E> for Failure {
    fn from(e: E) -> Self {
        Failure::job(e.to_string())
    }
}

/// Refuses a run whose outputs name one file twice (`--out X --heightmap X` wrote the
/// heightmap over the forest): each output is named by its flag and path; paths are
/// compared as the files they would be (the same folder, the same name).
pub(crate) fn distinct_outputs(outputs: &[(&str, &std::path::Path)]) -> Result<(), Failure> {
    let file_of = |path: &std::path::Path| {
        let folder = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p,
            _ => std::path::Path::new("."),
        };
        let folder = std::fs::canonicalize(folder).unwrap_or_else(|_| folder.to_path_buf());
        // A link is written through to its target (sylva_base::file::AtomicFile).
        let named = folder.join(path.file_name().unwrap_or_default());
        std::fs::canonicalize(&named).unwrap_or(named)
    };
    for (k, (flag, path)) in outputs.iter().enumerate() {
        for (other, other_path) in &outputs[..k] {
            if file_of(path) == file_of(other_path) {
                return Err(Failure::usage(format!(
                    "{other} and {flag} both name {}: give each output its own file",
                    path.display()
                )));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn one_file_named_twice_is_refused_with_both_flags() {
        let e = distinct_outputs(&[
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
            distinct_outputs(&[
                ("--out", Path::new("x.glb")),
                ("--heightmap", Path::new("x.png"))
            ])
            .is_ok()
        );
    }
}
