//! One species being edited: its species-file text and its grammar's text, checked and
//! previewed after every change (Carey's L-system tab).

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use sylva::forest::{ForestError, Species};
use sylva::turtle::Mesh;

/// Where a problem with the texts lies, for the panel to point at.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Problem {
    /// Whether it is in the grammar's text (else the species file's).
    pub(crate) in_grammar: bool,
    /// 1-based line and column, when the problem has a place.
    pub(crate) at: Option<(usize, usize)>,
    pub(crate) message: String,
}

impl std::fmt::Display for Problem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let text = if self.in_grammar {
            "grammar"
        } else {
            "species"
        };
        match self.at {
            Some((line, column)) => {
                write!(f, "{text}, line {line}, column {column}: {}", self.message)
            }
            None => write!(f, "{text}: {}", self.message),
        }
    }
}

/// One tree of a species that reads.
#[derive(Debug, Clone)]
pub(crate) struct Preview {
    pub(crate) triangles: usize,
    /// How long reading the texts, deriving and meshing took.
    pub(crate) millis: f64,
    /// The species the texts make (the forest is built from it) and its tree, shared (the
    /// panel's 3D view draws it in the species' colours).
    pub(crate) species: Species,
    pub(crate) mesh: Arc<Mesh>,
}

/// One species in the editor.
#[derive(Debug, Clone)]
pub(crate) struct Document {
    pub(crate) name: String,
    /// The species file's text; its `grammar:` line names [`Document::grammar_file`].
    pub(crate) species_text: String,
    /// The grammar's text, in the notation it declares.
    pub(crate) grammar_text: String,
    /// The species file on disk it came from, if any (bundled species have none).
    pub(crate) species_path: Option<PathBuf>,
    /// The grammar file on disk it came from, if any (a preset has none).
    pub(crate) grammar_path: Option<PathBuf>,
    /// The preview tree's seed.
    pub(crate) seed: u64,
    /// The texts as they stand: a species and its tree, or what is wrong.
    pub(crate) outcome: Result<Preview, Problem>,
}

impl Document {
    /// A document of species-file text read from `path` (on disk or bundled): a grammar
    /// that is a preset becomes text of its own (`NAME.lsys`) with the preset's angle and
    /// tropism written into the species, so that it can be edited; a grammar file is read.
    pub(crate) fn open(path: &Path, species_text: &str, on_disk: bool) -> Result<Document, String> {
        let mut species_text = species_text.to_string();
        let grammar_ref = setting(&species_text, "grammar")
            .ok_or_else(|| format!("{}: no 'grammar:' line", path.display()))?;
        let name = setting(&species_text, "name").unwrap_or_else(|| {
            path.file_stem()
                .map_or("species".into(), |s| s.to_string_lossy().into_owned())
        });
        let (grammar_text, grammar_path) = match sylva::lsys::preset(&grammar_ref) {
            Some(p) => {
                if setting(&species_text, "angle").is_none() {
                    set_setting(&mut species_text, "angle", &p.angle.to_string());
                }
                if let (Some((d, e)), None) = (p.tropism, setting(&species_text, "tropism")) {
                    let value = format!("{} {} {} {e}", d[0], d[1], d[2]);
                    set_setting(&mut species_text, "tropism", &value);
                }
                (p.source.to_string(), None)
            }
            None if on_disk => {
                let file = path.parent().unwrap_or(Path::new(".")).join(&grammar_ref);
                if file.is_dir() {
                    return Err(format!(
                        "{}: its grammar is a vlab model folder, edited in its own files",
                        path.display()
                    ));
                }
                let text =
                    sylva::base::text_file::read(&file, sylva::lsys::MAX_GRAMMAR_BYTES as u64)
                        .map_err(|e| e.to_string())?;
                (text, Some(file))
            }
            None => {
                return Err(format!(
                    "{}: grammar '{grammar_ref}' is not bundled",
                    path.display()
                ));
            }
        };
        let species_path = on_disk.then(|| path.to_path_buf());
        Ok(Document::new(
            name,
            species_text,
            grammar_text,
            species_path,
            grammar_path,
        ))
    }

    /// A document of a project's species given inline (its world file's species file and
    /// grammar texts); the project's own files of that name, when there, are the ones
    /// watched.
    pub(crate) fn inline(
        folder: &Path,
        species_text: &str,
        grammar_text: Option<&str>,
    ) -> Result<Document, String> {
        let name = setting(species_text, "name")
            .ok_or_else(|| format!("{}: a species without a 'name:' line", folder.display()))?;
        let species_path = folder.join(format!("{name}.species"));
        let Some(grammar_text) = grammar_text else {
            // A preset grammar: opened as a bundled species is.
            return Document::open(&species_path, species_text, false);
        };
        let grammar_path = folder.join(format!("{name}.lsys"));
        let existing = |p: PathBuf| p.is_file().then_some(p);
        Ok(Document::new(
            name,
            species_text.to_string(),
            grammar_text.to_string(),
            existing(species_path),
            existing(grammar_path),
        ))
    }

    /// A document of these texts, read and previewed; its grammar line names `NAME.lsys`.
    fn new(
        name: String,
        mut species_text: String,
        grammar_text: String,
        species_path: Option<PathBuf>,
        grammar_path: Option<PathBuf>,
    ) -> Document {
        set_setting(&mut species_text, "grammar", &format!("{name}.lsys"));
        let mut document = Document {
            name,
            species_text,
            grammar_text,
            species_path,
            grammar_path,
            seed: 1,
            outcome: Err(Problem {
                in_grammar: false,
                at: None,
                message: "not read yet".into(),
            }),
        };
        document.rebuild();
        document
    }

    /// The species the texts make, or what is wrong with them.
    pub(crate) fn species(&self) -> Result<Species, Problem> {
        Species::parse_detached(
            &self.species_text,
            Path::new(&self.name),
            Some(&self.grammar_text),
        )
        .map_err(problem)
    }

    /// The name the grammar's text is saved under, beside the species file.
    pub(crate) fn grammar_file(&self) -> String {
        format!("{}.lsys", self.name)
    }

    /// Reads the texts again and, when they read, derives and meshes one tree.
    pub(crate) fn rebuild(&mut self) {
        let started = Instant::now();
        self.outcome = self.species().and_then(|species| {
            let mesh = species
                .mesh(species.generations, self.seed)
                .map_err(problem)?;
            Ok(Preview {
                triangles: mesh.triangle_count(),
                millis: started.elapsed().as_secs_f64() * 1e3,
                mesh: Arc::new(mesh),
                species,
            })
        });
    }
}

/// What a failed read or build says, placed in the text it is about.
fn problem(error: ForestError) -> Problem {
    match error {
        ForestError::SpeciesFile {
            file,
            line,
            column,
            message,
        } => Problem {
            // Errors in a detached grammar name "<species> (grammar)".
            in_grammar: file.to_string_lossy().ends_with("(grammar)"),
            at: Some((line, column)),
            message,
        },
        other => Problem {
            in_grammar: true,
            at: None,
            message: other.to_string(),
        },
    }
}

/// The value of the species file's `key:` line, if it has one (comments stripped).
pub(crate) fn setting(text: &str, key: &str) -> Option<String> {
    text.lines().find_map(|line| {
        let line = line.split('#').next()?;
        let (k, v) = line.split_once(':')?;
        (k.trim() == key).then(|| v.trim().to_string())
    })
}

/// Sets the species file's `key:` line to `value`: the line is rewritten where it stands
/// (its comment kept), or added at the end.
pub(crate) fn set_setting(text: &mut String, key: &str, value: &str) {
    let mut out = String::with_capacity(text.len() + key.len() + value.len() + 4);
    let mut found = false;
    for line in text.lines() {
        let (body, comment) = match line.find('#') {
            Some(k) => (&line[..k], &line[k..]),
            None => (line, ""),
        };
        match body.split_once(':') {
            Some((k, _)) if !found && k.trim() == key => {
                found = true;
                out.push_str(&format!("{key}: {value}"));
                if !comment.is_empty() {
                    out.push_str("  ");
                    out.push_str(comment);
                }
            }
            _ => out.push_str(line),
        }
        out.push('\n');
    }
    if !found {
        out.push_str(&format!("{key}: {value}\n"));
    }
    *text = out;
}

#[cfg(test)]
mod tests {
    use super::*;

    fn oak() -> Document {
        let oak = &sylva::presets::BUNDLED[0];
        Document::open(Path::new(oak.path), oak.text, false).unwrap()
    }

    #[test]
    fn a_bundled_species_opens_with_its_grammar_as_text() {
        let d = oak();
        assert_eq!(d.name, "oak");
        assert_eq!(
            setting(&d.species_text, "grammar").as_deref(),
            Some("oak.lsys")
        );
        // The preset's angle came along, so the tree is the bundled one.
        let preview = d.outcome.as_ref().unwrap();
        let bundled = sylva::presets::species().unwrap().remove(0);
        let same = bundled.mesh(bundled.generations, 1).unwrap();
        assert_eq!(preview.triangles, same.triangle_count());
    }

    #[test]
    fn errors_point_into_the_text_they_are_in() {
        let mut d = oak();
        d.grammar_text.push_str("\nA -> B(1,");
        d.rebuild();
        let p = d.outcome.unwrap_err();
        assert!(p.in_grammar, "{p}");
        let lines = d.grammar_text.lines().count();
        assert_eq!(p.at.map(|a| a.0), Some(lines), "{p}");
        let mut d = oak();
        set_setting(&mut d.species_text, "generations", "many");
        d.rebuild();
        let p = d.outcome.unwrap_err();
        assert!(!p.in_grammar && p.at.is_some(), "{p}");
    }

    #[test]
    fn settings_are_rewritten_in_place_and_change_the_tree() {
        let mut d = oak();
        let before = d.outcome.as_ref().unwrap().triangles;
        let lines = d.species_text.lines().count();
        set_setting(&mut d.species_text, "generations", "5");
        assert_eq!(d.species_text.lines().count(), lines);
        assert_eq!(
            setting(&d.species_text, "generations").as_deref(),
            Some("5")
        );
        d.rebuild();
        assert!(d.outcome.as_ref().unwrap().triangles < before);
        set_setting(&mut d.species_text, "weight", "2");
        assert!(
            d.species_text.ends_with("weight: 2\n")
                || setting(&d.species_text, "weight").as_deref() == Some("2")
        );
    }
}
