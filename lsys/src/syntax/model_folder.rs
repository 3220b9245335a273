//! vlab models are folders, not single files: a model's `.l` file and the files beside it
//! that it reads. This finds the `.l` file of a folder, reads the files its `#include`s name
//! and the data files its view file (`.v`) names, from inside the folder only.

use std::path::{Path, PathBuf};

use crate::curve::{Curve, DEFAULT_CURVE_SAMPLES, MAX_CURVES};
use crate::engine::lsystem::LSystem;
use crate::error::GrammarFileError;
use crate::model::dialect::Dialect;
use crate::model_files::ModelFiles;
use crate::spline::{MAX_FUNCTIONS, SplineFunction};
use crate::surface::{DEFAULT_DIVISIONS, MAX_DIVISIONS, MAX_QUADS, MAX_SURFACES, Surface};
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
/// the folder, or of several the one L-system (an error when there is none or several,
/// which are named).
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
    // vlab folders keep control panels in `.l` files too (`panel.l`): of several, the
    // model is the one L-system.
    if models.len() > 1 {
        let systems: Vec<PathBuf> = models
            .iter()
            .filter(|m| {
                sylva_base::text_file::read(m, MAX_GRAMMAR_BYTES as u64)
                    .is_ok_and(|t| t.lines().any(|l| l.trim_start().starts_with("Lsystem:")))
            })
            .cloned()
            .collect();
        if systems.len() == 1 {
            models = systems;
        }
    }
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

/// The data files the model's view file names, in order: `function: FILE [SAMPLES]` lines
/// (ids from 1 in their order) or a `function set: FILE` (its functions, named), `curve:
/// FILE [SAMPLES]` (ids from 1), `contour: [ID] FILE [SAMPLES]` and `surface: [LETTER] FILE
/// [SCALE [S T]]` (the letter, when not given, the file name's first), and `contour sides:`.
fn model_files(
    file: &Path,
    folder: &Path,
    includes: &mut ModelFolder,
) -> Result<ModelFiles, GrammarFileError> {
    let mut out = ModelFiles::default();
    let Some(view) = view_file(file, folder) else {
        return Ok(out);
    };
    let text = sylva_base::text_file::read(&view, MAX_GRAMMAR_BYTES as u64)?;
    let problem = |line: usize, message: String| GrammarFileError::Model {
        path: view.clone(),
        message: format!("line {line}: {message}"),
    };
    for (k, line) in text.lines().enumerate() {
        let Some((key, rest)) = line.trim().split_once(':') else {
            continue;
        };
        let key = key.trim();
        if key == "contour sides" {
            let sides = rest
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|s| (3..=1024).contains(s));
            out.contour_sides = Some(sides.ok_or_else(|| {
                problem(
                    k + 1,
                    format!("contour sides '{}': expected 3 to 1024", rest.trim()),
                )
            })?);
            continue;
        }
        if !matches!(
            key,
            "function set" | "function" | "curve" | "contour" | "surface"
        ) {
            continue;
        }
        let mut words: Vec<&str> = rest.split_whitespace().collect();
        // A contour's id and a surface's letter come before the file's name.
        let label = match (key, words.as_slice()) {
            ("contour" | "surface", [first, _, ..]) if !first.contains('.') => {
                Some(words.remove(0))
            }
            _ => None,
        };
        let Some((&name, numbers)) = words.split_first() else {
            return Err(problem(k + 1, format!("{key}: no file named")));
        };
        let number = |i: usize| numbers.get(i).and_then(|n| n.parse::<f64>().ok());
        let samples = number(0).filter(|n| *n >= 0.0).map(|n| n as usize);
        let text = includes
            .read(name)
            .map_err(|e| problem(k + 1, format!("{name}: {e}")))?;
        let read = |e: String| problem(k + 1, format!("{name}: {e}"));
        match key {
            "function set" => out.functions = SplineFunction::parse_set(&text).map_err(read)?,
            "function" => {
                let mut function = SplineFunction::parse_func(&text, samples).map_err(read)?;
                // Only a set's names are defined as their ids: a file's name is its own
                // (and often a variable's, `turn` for turn.func).
                function.name = None;
                out.functions.push(function);
            }
            "curve" => out.curves.push(Curve::parse(&text, samples).map_err(read)?),
            "contour" => {
                let id = match label {
                    Some(id) => id.parse().map_err(|_| {
                        problem(k + 1, format!("contour id '{id}': expected a number"))
                    })?,
                    None => out.contours.len() as u32 + 1,
                };
                // Measured finely: cpfg spaces a contour's points evenly along its length.
                let samples = samples
                    .unwrap_or(DEFAULT_CURVE_SAMPLES)
                    .max(DEFAULT_CURVE_SAMPLES);
                out.contours
                    .push((id, Curve::parse(&text, Some(samples)).map_err(read)?));
            }
            _ => {
                let letter = label.unwrap_or(name).chars().next().unwrap_or('?');
                let mut surface = Surface::parse(&text, letter).map_err(read)?;
                surface.scale = number(0).filter(|v| v.is_finite()).unwrap_or(1.0);
                let divisions = |i: usize| {
                    number(i).map_or(DEFAULT_DIVISIONS, |d| {
                        d.clamp(1.0, f64::from(MAX_DIVISIONS)) as u32
                    })
                };
                surface.divisions = [divisions(1), divisions(2)];
                out.surfaces.push(surface);
                let quads: usize = out.surfaces.iter().map(Surface::quad_count).sum();
                if quads > MAX_QUADS {
                    return Err(problem(
                        k + 1,
                        format!("the surfaces come to {quads} quads: at most {MAX_QUADS}"),
                    ));
                }
            }
        }
        if out.functions.len() > MAX_FUNCTIONS
            || out.curves.len() + out.contours.len() > MAX_CURVES
            || out.surfaces.len() > MAX_SURFACES
        {
            return Err(problem(
                k + 1,
                format!(
                    "too many files: at most {MAX_FUNCTIONS} functions, {MAX_CURVES} curves and contours, {MAX_SURFACES} surfaces"
                ),
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
    let files = model_files(&file, &folder, &mut includes)?;
    let dialect = match Dialect::of_path(&file) {
        Dialect::Sylva => Dialect::declared_in(&text),
        named => named,
    };
    parse_with(&text, dialect, Some(&mut includes), files).map_err(|e| GrammarFileError::Parse {
        path: match e.file {
            Some(name) => folder.join(name),
            None => file.clone(),
        },
        error: e.error,
    })
}
