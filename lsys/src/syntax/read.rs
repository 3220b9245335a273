//! Reading grammar text: the dialect's front end (sylva's lines, cpfg's `.l` sections, L-Py's
//! declarative subset) feeding the shared [`GrammarParser`], which checks and builds the
//! L-system.

use crate::engine::lsystem::LSystem;
use crate::error::ParseError;
use crate::model::dialect::Dialect;
use crate::model_files::ModelFiles;
use crate::syntax::comments::{strip_block_comments, strip_line_comments};
use crate::syntax::cursor::Cursor;
use crate::syntax::parser::{CPFG_LONG_NAMES, GrammarParser, MAX_GRAMMAR_BYTES};
use crate::syntax::preprocessor::{Includes, preprocess_with};
use crate::syntax::statement_parser::assigned_names;

/// Parses `text` in the dialect it declares ([`Dialect::declared_in`]).
pub(crate) fn parse(text: &str) -> Result<LSystem, ParseError> {
    parse_dialect(text, Dialect::declared_in(text))
}

/// Parses `text` as `dialect`.
pub(crate) fn parse_dialect(text: &str, dialect: Dialect) -> Result<LSystem, ParseError> {
    parse_with(text, dialect, None, ModelFiles::default()).map_err(|e| e.error)
}

/// A parse error and the included file it is in (`None`: the model's own text).
#[derive(Debug)]
pub(crate) struct SourcedError {
    pub(crate) file: Option<String>,
    pub(crate) error: ParseError,
}

impl From<ParseError> for SourcedError {
    fn from(error: ParseError) -> Self {
        SourcedError { file: None, error }
    }
}

/// Parses `text` as `dialect`, cpfg's `#include`s read by `includes` when given, its
/// expressions reading `files` (the names of a function set's functions are defined as
/// their ids, as cpfg defines them); errors in the lines of an included file name that file and
/// its own line.
pub(crate) fn parse_with(
    text: &str,
    dialect: Dialect,
    includes: Option<&mut dyn Includes>,
    files: ModelFiles,
) -> Result<LSystem, SourcedError> {
    if text.len() > MAX_GRAMMAR_BYTES {
        return Err(ParseError::new(
            1,
            1,
            format!("grammar text longer than {MAX_GRAMMAR_BYTES} bytes"),
        )
        .into());
    }
    // Editors on Windows may start the file with a byte-order mark; it is not text.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let src: Vec<char> = text.chars().collect();
    let src = strip_block_comments(&src)?;
    let mut p = GrammarParser::new(dialect, assigned_names(&src));
    p.functions = files.functions.len();
    p.curves = files.curves.len();
    match dialect {
        Dialect::Sylva => {
            for (n, line) in src.split(|&c| c == '\n').enumerate() {
                let line = line.strip_suffix(&['\r']).unwrap_or(line);
                p.line(&mut Cursor::new(line, n + 1))?;
            }
        }
        Dialect::Cpfg => {
            // cpfg files go through the C preprocessor, which ends a line at '//' and
            // expands macros.
            let src = strip_line_comments(&src);
            let named: Vec<(String, String)> = files
                .functions
                .iter()
                .enumerate()
                .filter_map(|(k, f)| Some((f.name.clone()?, (k + 1).to_string())))
                .collect();
            let pre = preprocess_with(&src, includes, &named)?;
            let src = pre.lines.join(&'\n');
            p.globals = assigned_names(&src);
            p.add_long_names(CPFG_LONG_NAMES.iter().copied());
            // `~` and a surface's letter draw that surface: one module.
            let surfaces: Vec<String> = files
                .surfaces
                .iter()
                .map(|s| format!("~{}", s.letter))
                .collect();
            p.add_long_names(surfaces.iter().map(String::as_str));
            // Lines of included files moved the model's own: each error goes back to the
            // file and line it came from.
            let place = |e: ParseError| {
                let Some(origin) = e
                    .location
                    .line
                    .checked_sub(1)
                    .and_then(|k| pre.origins.get(k))
                else {
                    return SourcedError::from(e);
                };
                let mut error = e;
                error.location.line = origin.line;
                SourcedError {
                    file: (origin.file > 0).then(|| pre.files[origin.file].clone()),
                    error,
                }
            };
            crate::syntax::cpfg::read(&src, &mut p).map_err(place)?;
            return Ok(p.finish().map_err(place)?.with_files(files));
        }
        Dialect::LPy => {
            // The declarative subset has no statement blocks: a name assigned in Python
            // code is Python's, not a block variable.
            p.globals.clear();
            // L-Py's own modules of several characters ('#' starts a comment there).
            p.add_long_names(CPFG_LONG_NAMES.iter().copied().filter(|n| *n != "#"));
            crate::syntax::lpy::read(&src, &mut p)?
        }
    }
    Ok(p.finish()?.with_files(files))
}
