//! `sylva.Grammar`: an L-system read from text (sylva's notation, cpfg or L-Py), a file, a
//! vlab model folder or a bundled preset, and derived from a seed.

use std::path::PathBuf;

use pyo3::prelude::*;
use sylva::lsys::{Dialect, LSystem, PRESETS, Preset, preset};
use sylva::turtle::TurtleOptions;

use crate::errors::{Raise, invalid};

/// Generations a grammar that names none is derived for.
const DEFAULT_GENERATIONS: u32 = 4;

/// An L-system grammar, ready to derive.
///
/// Grammar(text, *, dialect=None) parses text in sylva's notation (ABOP's), cpfg's or
/// L-Py's; without `dialect` ("sylva", "cpfg" or "lpy") the text's own declaration decides
/// (cpfg when a line starts with `Lsystem:`). A mistake raises ParseError with its line and
/// column. Grammar.from_file reads a file or a vlab model folder, Grammar.preset a bundled
/// grammar (sylva.presets() lists them).
#[pyclass(module = "sylva", name = "Grammar", frozen)]
#[derive(Debug)]
pub(crate) struct Grammar {
    pub(crate) lsystem: LSystem,
    /// Generations it is derived for when none are asked: the model's own, or 4.
    pub(crate) generations: u32,
    /// The preset it came from, whose turtle settings it is drawn with.
    pub(crate) preset: Option<&'static Preset>,
}

#[pymethods]
impl Grammar {
    #[new]
    #[pyo3(signature = (text, *, dialect = None))]
    fn new(py: Python<'_>, text: String, dialect: Option<String>) -> PyResult<Grammar> {
        let dialect = match dialect.as_deref() {
            None => None,
            Some("sylva" | "abop") => Some(Dialect::Sylva),
            Some("cpfg") => Some(Dialect::Cpfg),
            Some("lpy") => Some(Dialect::LPy),
            Some(other) => {
                return Err(invalid(format!(
                    "dialect '{other}': expected 'sylva', 'cpfg' or 'lpy'"
                )));
            }
        };
        let lsystem = py
            .detach(|| match dialect {
                Some(d) => LSystem::parse_dialect(&text, d),
                None => LSystem::parse(&text),
            })
            .raise()?;
        Ok(Grammar::of(lsystem))
    }

    /// Reads a grammar file (sylva's notation, cpfg's .l, L-Py's .lpy) or a vlab model
    /// folder, whose .l file reads the files beside it that it includes. A mistake raises
    /// ParseError naming the file, line and column.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Grammar> {
        let model = path.is_dir() || path.extension().is_some_and(|e| e == "l");
        let lsystem = py
            .detach(|| {
                if model {
                    LSystem::from_model_dir(&path)
                } else {
                    LSystem::from_file(&path)
                }
            })
            .raise()?;
        Ok(Grammar::of(lsystem))
    }

    /// A bundled grammar by name (sylva.presets() lists them), at its published
    /// generations.
    #[staticmethod]
    fn preset(name: &str) -> PyResult<Grammar> {
        let p = preset(name).ok_or_else(|| {
            invalid(format!(
                "no preset called '{name}' (sylva.presets() lists them)"
            ))
        })?;
        Ok(Grammar {
            lsystem: p.lsystem().raise()?,
            generations: p.generations,
            preset: Some(p),
        })
    }

    /// Generations it is derived for when none are asked: a preset's published figure's,
    /// a cpfg model's derivation length, else 4.
    #[getter]
    fn generations(&self) -> u32 {
        self.generations
    }

    /// The dialect it was written in: "sylva", "cpfg" or "lpy".
    #[getter]
    fn dialect(&self) -> &'static str {
        match self.lsystem.dialect() {
            Dialect::Cpfg => "cpfg",
            Dialect::LPy => "lpy",
            _ => "sylva",
        }
    }

    /// The word after `generations` (default: Grammar.generations) rewritings, stochastic
    /// productions drawn from `seed`, in the grammar's notation. The same seed gives the
    /// same word on any machine. A word past the rewriting's limits raises SylvaError.
    #[pyo3(signature = (generations = None, *, seed = 0))]
    fn derive(&self, py: Python<'_>, generations: Option<u32>, seed: u64) -> PyResult<String> {
        let generations = generations.unwrap_or(self.generations);
        let word = py
            .detach(|| self.lsystem.derive(generations, seed))
            .raise()?;
        Ok(word.to_string())
    }

    /// The grammar printed in sylva's notation; it parses back to the same grammar.
    fn __str__(&self) -> String {
        self.lsystem.to_string()
    }

    fn __repr__(&self) -> String {
        match self.preset {
            Some(p) => format!("<sylva.Grammar preset '{}'>", p.name),
            None => format!(
                "<sylva.Grammar ({}, {} generations)>",
                self.dialect(),
                self.generations
            ),
        }
    }
}

impl Grammar {
    /// A grammar read from text or a file, derived for its model's length or 4.
    fn of(lsystem: LSystem) -> Grammar {
        Grammar {
            generations: lsystem.derivation_length().unwrap_or(DEFAULT_GENERATIONS),
            lsystem,
            preset: None,
        }
    }

    /// The turtle it is drawn with: a preset's own, or its dialect's symbols and its
    /// model's surfaces.
    pub(crate) fn turtle(&self) -> TurtleOptions {
        match self.preset {
            Some(p) => TurtleOptions::for_preset(p),
            None => TurtleOptions::for_grammar(&self.lsystem),
        }
    }
}

/// The bundled grammars' names, for Grammar.preset.
#[pyfunction]
pub(crate) fn presets() -> Vec<&'static str> {
    PRESETS.iter().map(|p| p.name).collect()
}
