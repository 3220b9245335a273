//! vlab models are folders, not single files: a model's `.l` file and the files beside it
//! that it reads. This finds the `.l` file of a folder, reads the files its `#include`s name
//! and the function files its view file (`.v`) names, from inside the folder only.

use std::path::{Path, PathBuf};

use crate::engine::lsystem::LSystem;
use crate::error::GrammarFileError;
use crate::model::dialect::Dialect;
use crate::spline::{MAX_FUNCTIONS, SplineFunction};
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

/// The view file of the model `file`: the `.v` beside it of the same name, else the only
/// `.v` in its folder, else none.
fn view_file(file: &Path, folder: &Path) -> Option<PathBuf> {
    let same = file.with_extension("v");
    if same.is_file() {
        return Some(same);
    }
    let mut views = std::fs::read_dir(folder)
        .ok()?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.is_file() && p.extension().is_some_and(|e| e == "v"));
    let only = views.next()?;
    views.next().is_none().then_some(only)
}

/// The function files the model's view file names, in order: `function: FILE [SAMPLES]`
/// lines (ids from 1 in their order) or a `function set: FILE` (its functions, named).
fn functions(
    file: &Path,
    folder: &Path,
    includes: &mut ModelFolder,
) -> Result<Vec<SplineFunction>, GrammarFileError> {
    let Some(view) = view_file(file, folder) else {
        return Ok(Vec::new());
    };
    let text = sylva_base::text_file::read(&view, MAX_GRAMMAR_BYTES as u64)?;
    let problem = |line: usize, message: String| GrammarFileError::Model {
        path: view.clone(),
        message: format!("line {line}: {message}"),
    };
    let mut out = Vec::new();
    for (k, line) in text.lines().enumerate() {
        let line = line.trim();
        if let Some(rest) = line.strip_prefix("function set:") {
            let name = rest.trim();
            let set = includes
                .read(name)
                .map_err(|e| problem(k + 1, format!("{name}: {e}")))?;
            out = SplineFunction::parse_set(&set)
                .map_err(|e| problem(k + 1, format!("{name}: {e}")))?;
        } else if let Some(rest) = line.strip_prefix("function:") {
            let mut parts = rest.split_whitespace();
            let name = parts.next().unwrap_or_default();
            let samples = parts.next().and_then(|s| s.parse().ok());
            let text = includes
                .read(name)
                .map_err(|e| problem(k + 1, format!("{name}: {e}")))?;
            let mut function = SplineFunction::parse_func(&text, samples)
                .map_err(|e| problem(k + 1, format!("{name}: {e}")))?;
            // Only a set's names are defined as their ids: a file's name is its own (and
            // often a variable's, `turn` for turn.func).
            function.name = None;
            out.push(function);
        }
        if out.len() > MAX_FUNCTIONS {
            return Err(problem(
                k + 1,
                format!("more than {MAX_FUNCTIONS} functions"),
            ));
        }
    }
    Ok(out)
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
    let functions = functions(&file, &folder, &mut includes)?;
    let dialect = match Dialect::of_path(&file) {
        Dialect::Sylva => Dialect::declared_in(&text),
        named => named,
    };
    parse_with(&text, dialect, Some(&mut includes), functions).map_err(|e| {
        GrammarFileError::Parse {
            path: match e.file {
                Some(name) => folder.join(name),
                None => file.clone(),
            },
            error: e.error,
        }
    })
}
