//! `sylva corpus`: loads every cpfg model (`.l` file with an `Lsystem:` line) and L-Py model
//! (`.lpy`) under a folder, derives its stated derivation length, meshes it, and prints a
//! Markdown table: model, result, reason.
//!
//! The virtual laboratory's models (AlgorithmicBotany/vlab, folder `oofs`) are the corpus
//! this was made for. Each is read as a model folder (`LSystem::from_model_dir`): its
//! `#include`s and the function files its view file names are the files beside it. Models
//! that need files of other kinds (curves, surfaces for `~`, an environment program for
//! `?E`) are listed but counted apart: the question asked of the rest is whether they load, derive and mesh.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use sylva::lsys::{GrammarFileError, LSystem, Limits};
use sylva::turtle::{MeshBuilder, SymbolTable, TurtleOptions, interpret};

use crate::Failure;

/// `sylva corpus`'s flags.
#[derive(Debug, Args)]
pub(crate) struct CorpusArgs {
    /// The folder of models, searched recursively.
    dir: PathBuf,
    /// Write the table to this Markdown file instead of stdout.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Fail (exit status 1) when fewer than this percentage of the models that need no other
    /// files mesh.
    #[arg(long, value_name = "P", default_value_t = 0.0)]
    min_percent: f64,
}

/// Most modules a corpus model may derive: enough for the models, small enough that a run
/// over a hundred of them stays quick.
const MAX_MODULES: usize = 2_000_000;

/// What a model needs from beside its own file, if anything (judged from its text).
fn external_files(text: &str) -> Option<&'static str> {
    let code: String = text
        .lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n");
    if code.contains("curve(") || code.contains("curveGAL") {
        Some("curve files (curve)")
    } else if code.contains("?E") {
        Some("an environment program (?E)")
    } else if code
        .char_indices()
        .any(|(i, c)| c == '~' && code[i + 1..].starts_with(|n: char| n.is_ascii_alphabetic()))
    {
        Some("surface files (~)")
    } else {
        None
    }
}

/// The result of one model: `Ok` with the modules and triangles, or the reason it failed.
fn try_model(path: &Path) -> Result<(u32, usize, usize), String> {
    let read = if path.extension().is_some_and(|e| e == "l") {
        LSystem::from_model_dir(path)
    } else {
        LSystem::from_file(path)
    };
    let grammar = read.map_err(|e| match e {
        GrammarFileError::Parse { error, .. } => error.to_string(),
        other => other.to_string(),
    })?;
    let steps = grammar.derivation_length().unwrap_or(1);
    let limits = Limits::DEFAULT.with_max_modules(MAX_MODULES);
    let word = grammar
        .derive_with(steps, 1, &limits)
        .and_then(|w| grammar.interpretation(&w, 1))
        .map_err(|e| format!("derivation: {e}"))?;
    let options =
        TurtleOptions::default().with_symbols(SymbolTable::for_dialect(grammar.dialect()));
    let mut mesh = MeshBuilder::new(&options);
    interpret(&word, &options, &mut mesh).map_err(|e| format!("turtle: {e}"))?;
    let triangles = mesh.finish().triangle_count();
    if triangles == 0 {
        return Err(format!(
            "meshed to no triangles ({} modules after {steps} steps)",
            word.len()
        ));
    }
    // Printed in sylva's notation, the model reads back and derives the same word.
    let printed = grammar.to_string();
    let again = LSystem::parse_with_functions(
        &printed,
        sylva::lsys::Dialect::Sylva,
        grammar.functions().to_vec(),
    )
    .map_err(|e| format!("printed back, it does not parse: {e}"))?;
    let word_again = again
        .derive_with(steps, 1, &limits)
        .and_then(|w| again.interpretation(&w, 1))
        .map_err(|e| format!("printed back, its derivation fails: {e}"))?;
    if word_again.to_string() != word.to_string() {
        return Err("printed back, it derives another word".to_string());
    }
    Ok((steps, word.len(), triangles))
}

fn models(dir: &Path, out: &mut Vec<PathBuf>) -> std::io::Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)?.collect::<Result<_, _>>()?;
    entries.sort_by_key(|e| e.path());
    for e in entries {
        let path = e.path();
        if path.is_dir() {
            models(&path, out)?;
        } else if path.extension().is_some_and(|x| x == "lpy")
            || path.extension().is_some_and(|x| x == "l")
                && std::fs::read_to_string(&path)
                    .is_ok_and(|t| t.lines().any(|l| l.trim_start().starts_with("Lsystem:")))
        {
            out.push(path);
        }
    }
    Ok(())
}

pub(crate) fn run(args: CorpusArgs) -> Result<(), Failure> {
    let CorpusArgs {
        dir,
        out,
        min_percent,
    } = args;
    let mut paths = Vec::new();
    models(&dir, &mut paths).map_err(|e| Failure::job(format!("{}: {e}", dir.display())))?;
    if paths.is_empty() {
        return Err(Failure::job(format!(
            "no cpfg models (.l files with 'Lsystem:') under {}",
            dir.display()
        )));
    }
    let mut table = String::from("| model | needs | result | reason |\n|---|---|---|---|\n");
    let (mut standalone, mut standalone_ok, mut ok, mut unsupported) = (0, 0, 0, 0);
    for path in &paths {
        let name = path
            .strip_prefix(&dir)
            .unwrap_or(path)
            .display()
            .to_string();
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let needs = external_files(&text);
        let result = try_model(path);
        let (verdict, reason) = match &result {
            Ok((steps, modules, triangles)) => (
                "meshes",
                format!(
                    "{steps} steps, {modules} modules, {triangles} triangles; round trip through sylva's notation derives the same word"
                ),
            ),
            Err(e) if e.contains("unsupported:") => ("refused", e.clone()),
            Err(e) => ("fails", e.clone()),
        };
        ok += usize::from(result.is_ok());
        unsupported += usize::from(verdict == "refused");
        if needs.is_none() {
            standalone += 1;
            standalone_ok += usize::from(result.is_ok());
        }
        table.push_str(&format!(
            "| {name} | {} | {verdict} | {} |\n",
            needs.unwrap_or("-"),
            reason.replace('|', "\\|")
        ));
    }
    let percent = 100.0 * standalone_ok as f64 / standalone.max(1) as f64;
    let summary = format!(
        "{} models: {ok} load, derive and mesh; {unsupported} refused as unsupported; {} fail. \
         Of the {standalone} that need no other files, {standalone_ok} mesh ({:.0}%).",
        paths.len(),
        paths.len() - ok - unsupported,
        percent
    );
    match out {
        Some(file) => {
            let text = format!("{summary}\n\n{table}");
            sylva::base::file::write(&file, |w| w.write_all(text.as_bytes()))?;
            println!("{summary}\nwrote {}", file.display());
        }
        None => println!("{summary}\n\n{table}"),
    }
    if percent < min_percent {
        return Err(Failure::job(format!(
            "{percent:.0}% of the stand-alone models mesh, fewer than the {min_percent}% required"
        )));
    }
    Ok(())
}
