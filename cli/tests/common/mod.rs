//! What the `sylva` command's integration tests share: running it, its stderr, scratch
//! folders.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The `sylva` binary under test.
pub(crate) const SYLVA: &str = env!("CARGO_BIN_EXE_sylva");

/// A scratch folder of this name, emptied (the same name each run, so runs reuse it).
pub(crate) fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sylva-cli-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `sylva` with `args`.
pub(crate) fn sylva(args: &[&str]) -> Output {
    Command::new(SYLVA).args(args).output().expect("sylva runs")
}

/// What a run wrote to stderr.
pub(crate) fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}
