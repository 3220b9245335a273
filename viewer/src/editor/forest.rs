//! The forest tab's settings (Carey's forest tab): the world's seed and side, its terrain
//! (generated: seed, roughness, relief, smoothing, erosion; or the user's elevation model)
//! and its density, kept as the server's own world description so that a saved project is
//! what `sylva forest --project` and `sylva serve` take.

use std::path::{Path, PathBuf};

use sylva::forest::Species;
use sylva::world::limits::{MAX_BUDGET_MB, MAX_SIDE, MIN_SIDE};
use sylva::world::{Project, model_id, read_model_bytes};
use sylva::world::{SpeciesEntry, TerrainDescription, WorldDescription};

use crate::world::SceneOptions;

/// A species given inline in a world file: its species file's text, and its grammar's
/// unless it names a preset.
pub(crate) type InlineSpecies = (String, Option<String>);

/// The world's settings as the forest tab edits them.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ForestSettings {
    /// The world's description without its species (the editor's documents are those).
    pub(crate) description: WorldDescription,
    /// The user's elevation model, when the terrain is one (the description names it by its
    /// bytes' id).
    pub(crate) model: Option<PathBuf>,
}

impl ForestSettings {
    /// Settings for the world the viewer's flags describe: `seed`, a side of `side` metres,
    /// generated terrain as the viewer makes it by default, the species' own density, an
    /// instance-cache budget of `budget_mb` (within the description's 1 to 128; none: sized
    /// to the forest).
    pub(crate) fn of_flags(seed: u64, side: f32, budget_mb: Option<usize>) -> ForestSettings {
        ForestSettings {
            description: WorldDescription {
                seed,
                area: side.clamp(MIN_SIDE, MAX_SIDE),
                budget_mb: budget_mb.map(|mb| mb.clamp(1, MAX_BUDGET_MB as usize) as u32),
                ..WorldDescription::default()
            },
            model: None,
        }
    }

    /// The settings a project folder holds, if it has a world file; its species are
    /// answered apart, as (species file, grammar) texts.
    pub(crate) fn of_project(
        folder: &Path,
    ) -> Result<Option<(ForestSettings, Vec<InlineSpecies>)>, String> {
        if !folder.join(sylva::world::WORLD_FILE).is_file() {
            return Ok(None);
        }
        let project = Project::read(folder).map_err(|e| e.to_string())?;
        let mut description = project.description.clone();
        let species = std::mem::take(&mut description.species)
            .into_iter()
            .filter_map(|s| match s {
                SpeciesEntry::Inline { file, grammar } => Some((file, grammar)),
                // A bundled species by name: its own file, as the bundle holds it.
                SpeciesEntry::Bundled(name) => sylva::presets::bundled(&name)
                    .map(|b| (b.text.to_string(), b.grammar.map(str::to_string))),
            })
            .collect();
        let model = match &description.terrain {
            TerrainDescription::Heightmap { id, .. } => {
                Some(project.model().ok_or_else(|| {
                    format!("{}: no heightmap.* file holds {id}", folder.display())
                })?)
            }
            TerrainDescription::Generated { .. } => None,
        };
        Ok(Some((ForestSettings { description, model }, species)))
    }

    /// Uses the elevation model in `file` as the terrain (its spacing from the file, or
    /// `spacing` metres); an error when it cannot be read as one.
    pub(crate) fn use_model(&mut self, file: &Path, spacing: Option<f32>) -> Result<(), String> {
        let bytes = read_model_bytes(file).map_err(|e| e.to_string())?;
        let mut trial = self.clone();
        trial.description.terrain = TerrainDescription::Heightmap {
            id: model_id(&bytes).as_str().to_owned(),
            spacing,
            height_range: None,
            crop: None,
        };
        trial.description.check().map_err(|e| e.to_string())?;
        trial
            .description
            .ground(|_| Ok(bytes))
            .map_err(|e| format!("{}: {e}", file.display()))?;
        trial.model = Some(file.to_path_buf());
        *self = trial;
        Ok(())
    }

    /// The world's description with `species` inline (species file, grammar text).
    pub(crate) fn with_species(&self, species: Vec<(String, String)>) -> WorldDescription {
        WorldDescription {
            species: species
                .into_iter()
                .map(|(file, grammar)| SpeciesEntry::Inline {
                    file,
                    grammar: Some(grammar),
                })
                .collect(),
            ..self.description.clone()
        }
    }

    /// `base` (the viewer's flags) made into these settings' world with `species`: its
    /// ground made now (milliseconds for generated ground).
    pub(crate) fn scene_options(
        &self,
        base: &SceneOptions,
        species: Vec<Species>,
    ) -> Result<SceneOptions, String> {
        let d = &self.description;
        let ground = d
            .ground(|_| {
                let file = self.model.as_deref().unwrap_or(Path::new(""));
                Ok(read_model_bytes(file)?)
            })
            .map_err(|e| e.to_string())?;
        Ok(SceneOptions {
            seed: d.seed,
            side: d.area,
            trees: None,
            species,
            budget: d.budget_mb.map(|mb| mb as usize * (1 << 20)),
            terrain: None,
            ground: Some((ground.map, ground.extent)),
            density: d.density,
            ..base.clone()
        })
    }
}
