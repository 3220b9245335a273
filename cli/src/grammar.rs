//! The grammar `derive` and `tree` work on: a file, or a bundled preset, with the
//! generations and seed to derive it at.

use std::path::PathBuf;

use clap::Args;
use sylva::lsys::{LSystem, PRESETS, Preset, preset};
use sylva::turtle::TurtleOptions;

use crate::Failure;

/// The grammar's flags.
#[derive(Debug, Args)]
pub(crate) struct GrammarArgs {
    /// A grammar file (sylva's notation, cpfg's .l or L-Py's .lpy), or a vlab model folder
    /// (its .l file reads the files beside it that it includes).
    #[arg(conflicts_with = "preset")]
    file: Option<PathBuf>,
    /// A bundled grammar (listed below; the command's own when neither is given).
    #[arg(long, value_name = "NAME")]
    preset: Option<String>,
    /// Generations to derive (default: the grammar's own, or 4).
    #[arg(long, value_name = "N")]
    pub(crate) generations: Option<u32>,
    /// Seed of stochastic productions.
    #[arg(long, default_value_t = 0)]
    pub(crate) seed: u64,
}

/// A grammar ready to derive.
pub(crate) struct Grammar {
    pub(crate) lsystem: LSystem,
    pub(crate) generations: u32,
    /// The preset it came from (`None` for a file).
    pub(crate) preset: Option<&'static Preset>,
}

/// The presets' names, for `--help`.
pub(crate) fn presets_help() -> String {
    let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
    format!("Presets: {}", names.join(", "))
}

impl GrammarArgs {
    /// The grammar the flags name, or the preset `fallback`.
    pub(crate) fn load(&self, fallback: &str) -> Result<Grammar, Failure> {
        if let Some(path) = &self.file {
            // A vlab model is a folder: its .l file reads the files beside it.
            let model = path.is_dir() || path.extension().is_some_and(|e| e == "l");
            let lsystem = if model {
                LSystem::from_model_dir(path)?
            } else {
                LSystem::from_file(path)?
            };
            // cpfg models say how long to derive them.
            let steps = lsystem.derivation_length().unwrap_or(4);
            return Ok(Grammar {
                generations: self.generations.unwrap_or(steps),
                lsystem,
                preset: None,
            });
        }
        let name = self.preset.as_deref().unwrap_or(fallback);
        let p = preset(name).ok_or_else(|| {
            Failure::usage(format!(
                "no preset called '{name}' (see --help for the list)"
            ))
        })?;
        Ok(Grammar {
            lsystem: p.lsystem()?,
            generations: self.generations.unwrap_or(p.generations),
            preset: Some(p),
        })
    }
}

impl Grammar {
    /// The turtle it draws with: a preset's own, or for a file its dialect's symbols and
    /// its model's surfaces and contours (cpfg models draw with cpfg's turtle).
    pub(crate) fn turtle(&self) -> TurtleOptions {
        match self.preset {
            Some(p) => TurtleOptions::for_preset(p),
            None => TurtleOptions::for_grammar(&self.lsystem),
        }
    }
}
