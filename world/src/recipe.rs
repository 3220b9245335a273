//! A description's ground and builder, made the same way wherever a description is used:
//! the server's worlds, `sylva forest --project` and the viewer's forest tab.

use sylva_terrain::dem::{ReadOptions, Window};

use crate::builder::WorldBuilder;
use crate::description::{TerrainDescription, WorldDescription};
use crate::error::WorldError;
use crate::ground::{Fit, Ground};
use crate::id::WorldId;

impl WorldDescription {
    /// The world's ground: generated from the terrain's settings, or read from the elevation
    /// model whose id the terrain names, whose bytes `model` gives (the server's upload, a
    /// project's file): the terrain's `crop` when given, else the whole model up to 20 km a
    /// side and its middle 20 km square beyond ([`Fit::WHOLE`]). Blocking: milliseconds for
    /// generated ground, more for large models.
    ///
    /// ```
    /// use sylva_world::WorldDescription;
    /// let d = WorldDescription::parse(br#"{"area": 400, "terrain": {"generated": {"erosion": 1}}}"#)?;
    /// let ground = d.ground(|_| unreachable!("generated ground reads no model"))?;
    /// assert_eq!((ground.map.size(), ground.extent), (257, [400.0, 400.0]));
    /// # Ok::<(), sylva_world::WorldError>(())
    /// ```
    pub fn ground(
        &self,
        model: impl FnOnce(&WorldId) -> Result<Vec<u8>, WorldError>,
    ) -> Result<Ground, WorldError> {
        match &self.terrain {
            TerrainDescription::Heightmap {
                id,
                spacing,
                height_range,
                crop,
            } => {
                let id = WorldId::parse(id)
                    .ok_or_else(|| WorldError::Invalid(format!("heightmap id '{id}'")))?;
                let bytes = model(&id)?;
                let options = ReadOptions {
                    spacing: *spacing,
                    height_range: *height_range,
                    raw_size: None,
                };
                let crop = crop.map(|[column, row, width, height]| Window {
                    column,
                    row,
                    width,
                    height,
                });
                Ground::parse(
                    &bytes,
                    &format!("heightmap {id}"),
                    &options,
                    crop,
                    Fit::WHOLE,
                    "\"spacing\" in the terrain",
                )
            }
            TerrainDescription::Generated {
                seed,
                roughness,
                relief,
                smoothing,
                erosion,
            } => Ground::generated_with(
                seed.unwrap_or(self.seed),
                self.area,
                [*roughness, *relief, *smoothing],
                *erosion,
            ),
        }
    }

    /// The world's builder: its species (parsed: a mistake in an inline one has its line
    /// and column), seed, budget, density, year and season.
    ///
    /// ```
    /// use sylva_world::WorldDescription;
    /// let d = WorldDescription::parse(br#"{"species": ["pine"], "seed": 3, "budget_mb": 4}"#)?;
    /// let builder = d.world_builder()?;
    /// assert_eq!((builder.seed, builder.budget, builder.species.len()), (3, Some(4 << 20), 1));
    /// # Ok::<(), sylva_world::WorldError>(())
    /// ```
    pub fn world_builder(&self) -> Result<WorldBuilder, WorldError> {
        let mut builder = WorldBuilder::new(self.species()?)
            .with_seed(self.seed)
            .with_density(self.density)
            .with_year(self.year)
            .with_season(self.season);
        builder.budget = self.budget_mb.map(|mb| mb as usize * (1 << 20));
        Ok(builder)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Left at its defaults, a description's ground is the default terrain.
    #[test]
    fn default_ground_is_the_presets_terrain() {
        let d = WorldDescription::parse(br#"{"seed": 5, "area": 600}"#).unwrap();
        let ground = d.ground(|_| unreachable!()).unwrap();
        assert_eq!(ground.extent, [600.0, 600.0]);
        assert_eq!(ground.map, crate::presets::terrain(5, 600.0).unwrap());
    }

    /// Erosion moves ground, the same way for the same seed.
    #[test]
    fn erosion_carves_the_same_ground_for_a_seed() {
        let eroded =
            WorldDescription::parse(br#"{"terrain": {"generated": {"erosion": 0.5}}}"#).unwrap();
        let a = eroded.ground(|_| unreachable!()).unwrap();
        let b = eroded.ground(|_| unreachable!()).unwrap();
        let plain = WorldDescription::default()
            .ground(|_| unreachable!())
            .unwrap();
        assert_eq!(a, b);
        assert_ne!(a.map, plain.map);
    }

    /// A model's crop in the description is the window taken; without one, a model no
    /// larger than a world is taken whole.
    #[test]
    fn a_described_crop_is_the_window_taken() {
        let bytes = std::fs::read(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
        ))
        .unwrap();
        let id = crate::model_id(&bytes);
        let json =
            |crop: &str| format!(r#"{{"terrain": {{"heightmap": {{"id": "{id}"{crop}}}}}}}"#);
        let whole = WorldDescription::parse(json("").as_bytes()).unwrap();
        let part =
            WorldDescription::parse(json(r#", "crop": [10, 5, 40, 30]"#).as_bytes()).unwrap();
        assert!(!whole.canonical().contains("crop"));
        assert_ne!(whole.id(), part.id());
        let g = whole.ground(|_| Ok(bytes.clone())).unwrap();
        assert!(g.chosen.is_none() && g.extent[0] > 3000.0);
        let g = part.ground(|_| Ok(bytes.clone())).unwrap();
        assert!(g.extent[0] < 1000.0, "{:?}", g.extent);
    }
}
