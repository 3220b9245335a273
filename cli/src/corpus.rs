//! `sylva corpus`: loads every cpfg model (`.l` file with an `Lsystem:` line) and L-Py model
//! (`.lpy`) under a folder, derives its stated derivation length, meshes it, and prints a
//! Markdown table: model, result, reason.
//!
//! The virtual laboratory's models (AlgorithmicBotany/vlab, folder `oofs`) are the corpus
//! this was made for. Each is read as a model folder (`LSystem::from_model_dir`): its
//! `#include`s and the function, curve, contour and surface files its view file names are
//! the files beside it, and the table says which it read. Models that answer `?E` queries
//! through an environment program (a separate process cpfg talks to) are marked: sylva
//! runs none.

use std::io::Write;
use std::path::{Path, PathBuf};

use clap::Args;
use sylva::lsys::{GrammarFileError, LSystem, Limits, ModelFiles};
use sylva::turtle::{MeshBuilder, TurtleOptions, interpret};

use crate::Failure;

/// `sylva corpus`'s flags.
#[derive(Debug, Args)]
pub(crate) struct CorpusArgs {
    /// The folder of models, searched recursively.
    dir: PathBuf,
    /// Write the table to this Markdown file instead of stdout.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Fail (exit status 1) when fewer than this percentage of the models mesh.
    #[arg(long, value_name = "P", default_value_t = 0.0)]
    min_percent: f64,
}

/// Most modules a corpus model may derive: enough for the models, small enough that a run
/// over a hundred of them stays quick.
const MAX_MODULES: usize = 2_000_000;

/// Whether a model queries an environment program (`?E`, outside comments).
fn needs_environment(text: &str) -> bool {
    text.lines()
        .any(|l| !l.trim_start().starts_with("//") && l.contains("?E"))
}

/// What one model that meshes came to.
struct Meshed {
    steps: u32,
    modules: usize,
    triangles: usize,
    /// The files beside it that it read, counted by kind ("2 functions, 1 surface"), or "-".
    read: String,
}

/// The files `files` holds, counted by kind.
fn files_read(files: &ModelFiles) -> String {
    let counts = [
        (files.functions.len(), "function"),
        (files.curves.len(), "curve"),
        (files.contours.len(), "contour"),
        (files.surfaces.len(), "surface"),
    ];
    let parts: Vec<String> = counts
        .iter()
        .filter(|(n, _)| *n > 0)
        .map(|(n, kind)| format!("{n} {kind}{}", if *n == 1 { "" } else { "s" }))
        .collect();
    if parts.is_empty() {
        "-".to_string()
    } else {
        parts.join(", ")
    }
}

/// The result of one model: what it came to, or the reason it failed.
fn try_model(path: &Path) -> Result<Meshed, String> {
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
    let options = TurtleOptions::for_grammar(&grammar);
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
    let again = LSystem::parse_with_files(
        &printed,
        sylva::lsys::Dialect::Sylva,
        grammar.files().clone(),
    )
    .map_err(|e| format!("printed back, it does not parse: {e}"))?;
    let word_again = again
        .derive_with(steps, 1, &limits)
        .and_then(|w| again.interpretation(&w, 1))
        .map_err(|e| format!("printed back, its derivation fails: {e}"))?;
    if word_again.to_string() != word.to_string() {
        return Err("printed back, it derives another word".to_string());
    }
    Ok(Meshed {
        steps,
        modules: word.len(),
        triangles,
        read: files_read(grammar.files()),
    })
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
    let mut table = String::from("| model | reads | result | reason |\n|---|---|---|---|\n");
    let (mut environment, mut ok, mut unsupported) = (0, 0, 0);
    for path in &paths {
        let name = path
            .strip_prefix(&dir)
            .unwrap_or(path)
            .display()
            .to_string();
        let text = std::fs::read_to_string(path).unwrap_or_default();
        let result = try_model(path);
        let environmental = needs_environment(&text);
        environment += usize::from(environmental);
        let (read, verdict, mut reason) = match &result {
            Ok(m) => (
                m.read.as_str(),
                "meshes",
                format!(
                    "{} steps, {} modules, {} triangles; round trip through sylva's notation derives the same word",
                    m.steps, m.modules, m.triangles
                ),
            ),
            Err(e) if e.contains("unsupported:") => ("", "refused", e.clone()),
            Err(e) => ("", "fails", e.clone()),
        };
        if environmental {
            reason.push_str(" (queries an environment program, ?E)");
        }
        ok += usize::from(result.is_ok());
        unsupported += usize::from(verdict == "refused");
        table.push_str(&format!(
            "| {name} | {read} | {verdict} | {} |\n",
            reason.replace('|', "\\|")
        ));
    }
    let percent = 100.0 * ok as f64 / paths.len() as f64;
    let summary = format!(
        "{} models: {ok} load, derive and mesh ({percent:.0}%); {unsupported} refused as \
         unsupported; {} fail. {environment} query an environment program (?E), which sylva \
         does not run.",
        paths.len(),
        paths.len() - ok - unsupported,
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
            "{percent:.0}% of the models mesh, fewer than the {min_percent}% required"
        )));
    }
    Ok(())
}
