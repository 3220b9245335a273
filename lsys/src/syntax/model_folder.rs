//! vlab models are folders, not single files: a model's `.l` file and the files beside it
//! that it reads. This finds the `.l` file of a folder and reads the files its `#include`s
//! name, from inside the folder only.

use std::path::{Path, PathBuf};

use crate::engine::lsystem::LSystem;
use crate::error::GrammarFileError;
use crate::model::dialect::Dialect;
use crate::syntax::parser::MAX_GRAMMAR_BYTES;
use crate::syntax::preprocessor::Includes;
use crate::syntax::read::parse_with;

/// Most bytes of included files one model may read, all together.
const MAX_INCLUDED_BYTES: u64 = 4 * MAX_GRAMMAR_BYTES as u64;

/// The files of one model folder, read for `#include`.
struct ModelFolder {
    /// The folder, canonical: every file read must lie inside it.
    root: PathBuf,
    /// Bytes read so far.
    read: u64,
}

impl Includes for ModelFolder {
    fn read(&mut self, name: &str) -> Result<String, String> {
        let relative = Path::new(name);
        if relative.is_absolute() {
            return Err("an absolute path: a model includes the files of its own folder".into());
        }
        let path = self
            .root
            .join(relative)
            .canonicalize()
            .map_err(|e| format!("no such file in the model's folder ({e})"))?;
        if !path.starts_with(&self.root) {
            return Err("outside the model's folder".into());
        }
        let text = sylva_base::text_file::read(&path, MAX_GRAMMAR_BYTES as u64)
            .map_err(|e| e.to_string())?;
        self.read += text.len() as u64;
        if self.read > MAX_INCLUDED_BYTES {
            return Err(format!(
                "the included files come to more than {MAX_INCLUDED_BYTES} bytes"
            ));
        }
        Ok(text)
    }
}

/// The model file of `path`: the path itself when it is a file, else the one `.l` file in
/// the folder (an error when there is none or several, which are named).
fn model_file(path: &Path) -> Result<PathBuf, GrammarFileError> {
    let problem = |message: String| GrammarFileError::Model {
        path: path.to_path_buf(),
        message,
    };
    if !path.is_dir() {
        return Ok(path.to_path_buf());
    }
    let entries = std::fs::read_dir(path).map_err(|e| problem(e.to_string()))?;
    let mut models: Vec<PathBuf> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == "l"))
        .collect();
    models.sort();
    match models.len() {
        1 => Ok(models.remove(0)),
        0 => Err(problem("no .l file in the folder: not a cpfg model".into())),
        _ => {
            let names: Vec<String> = models
                .iter()
                .filter_map(|m| m.file_name().map(|n| n.to_string_lossy().into_owned()))
                .collect();
            Err(problem(format!(
                "several .l files ({}): give the one to read",
                names.join(", ")
            )))
        }
    }
}

/// Reads the model at `path` (a folder or a `.l` file inside one) with the files beside it
/// that it includes.
pub(crate) fn read_model(path: &Path) -> Result<LSystem, GrammarFileError> {
    let file = model_file(path)?;
    let text = sylva_base::text_file::read(&file, MAX_GRAMMAR_BYTES as u64)?;
    let folder = match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let root = folder.canonicalize().map_err(|e| GrammarFileError::Model {
        path: folder.clone(),
        message: e.to_string(),
    })?;
    let mut includes = ModelFolder { root, read: 0 };
    let dialect = match Dialect::of_path(&file) {
        Dialect::Sylva => Dialect::declared_in(&text),
        named => named,
    };
    parse_with(&text, dialect, Some(&mut includes)).map_err(|e| GrammarFileError::Parse {
        path: match e.file {
            Some(name) => folder.join(name),
            None => file.clone(),
        },
        error: e.error,
    })
}
