//! A description's ground and forest recipe, made the same way wherever a description is
//! used: the server's worlds, `sylva forest --project` and the viewer's forest tab.

use sylva::forest::{ForestBuilder, ForestConfig};
use sylva::terrain::dem::{DemFormat, ElevationModel, ReadOptions};
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap, HydraulicErosion};

use crate::description::{MAX_SIDE, TerrainDescription, WorldDescription};
use crate::error::ApiError;
use crate::id::WorldId;

/// Samples along a side of generated terrain (the batch tools' default terrain's).
const GENERATED_SIZE: usize = 257;

/// The format of an elevation model's bytes, from its first bytes (or, for SRTM `.hgt`,
/// which has none, its length).
pub(crate) fn model_format(bytes: &[u8]) -> Option<DemFormat> {
    let hgt = [2 * 1201 * 1201, 2 * 3601 * 3601].contains(&bytes.len());
    DemFormat::of(std::path::Path::new(""), &bytes[..bytes.len().min(16)])
        .or(hgt.then_some(DemFormat::Hgt))
}

impl WorldDescription {
    /// The world's ground as a square heightmap, and the extent in metres (x, z) the world
    /// covers on it: generated from the terrain's settings, or read from the elevation model
    /// whose id the terrain names, whose bytes `model` gives (the server's upload, a
    /// project's file). Blocking: milliseconds for generated ground, more for large models.
    ///
    /// ```
    /// use sylva_server::WorldDescription;
    /// let d = WorldDescription::parse(br#"{"area": 400, "terrain": {"generated": {"erosion": 1}}}"#)?;
    /// let (map, extent) = d.ground(|_| unreachable!("generated ground reads no model"))?;
    /// assert_eq!((map.size(), extent), (257, [400.0, 400.0]));
    /// # Ok::<(), sylva_server::ApiError>(())
    /// ```
    pub fn ground(
        &self,
        model: impl FnOnce(&WorldId) -> Result<Vec<u8>, ApiError>,
    ) -> Result<(Heightmap, [f32; 2]), ApiError> {
        match &self.terrain {
            TerrainDescription::Heightmap {
                id,
                spacing,
                height_range,
            } => {
                let id = WorldId::parse(id)
                    .ok_or_else(|| ApiError::bad_request("bad_description", "bad heightmap id"))?;
                let bytes = model(&id)?;
                let (map, extent) = read_model(&id, &bytes, *spacing, *height_range)?;
                if !extent.iter().all(|e| (10.0..=MAX_SIDE).contains(e)) {
                    return Err(ApiError::bad_request(
                        "bad_heightmap",
                        format!(
                            "the heightmap covers {:.0} x {:.0} m: expected 10 to {MAX_SIDE} a side (set its spacing)",
                            extent[0], extent[1]
                        ),
                    ));
                }
                Ok((map, extent))
            }
            TerrainDescription::Generated {
                seed,
                roughness,
                relief,
                smoothing,
                erosion,
            } => {
                let fail =
                    |e: &(dyn std::error::Error + 'static)| ApiError::generation(e, "the terrain");
                let side = self.area;
                let seed = seed.unwrap_or(self.seed);
                // The batch tools' default terrain (`sylva::presets::terrain`) when left as is.
                let mut map = DiamondSquare::new(GENERATED_SIZE)
                    .with_seed(seed)
                    .with_spacing(side / (GENERATED_SIZE - 1) as f32)
                    .with_roughness(*roughness)
                    .with_amplitude(side * relief)
                    .generate()
                    .map_err(|e| fail(&e))?;
                if *smoothing > 0.0 {
                    map.smooth(*smoothing, EdgeMode::Mirror)
                        .map_err(|e| fail(&e))?;
                }
                if *erosion > 0.0 {
                    let droplets = (erosion * (GENERATED_SIZE * GENERATED_SIZE) as f32) as u32;
                    HydraulicErosion::new(droplets, seed ^ 0xe205_1011)
                        .apply(&mut map)
                        .map_err(|e| fail(&e))?;
                }
                Ok((map, [side, side]))
            }
        }
    }

    /// The world's forest recipe: its species' instance caches (seconds: hero trees for
    /// every species), its seed, budget and density. Blocking.
    pub fn builder(&self) -> Result<ForestBuilder, ApiError> {
        self.builder_with(|_| {})
    }

    /// [`WorldDescription::builder`] with the configuration adjusted first by `adjust` (a
    /// batch tool's own flags: where trees may stand, trees of every age).
    pub fn builder_with(
        &self,
        adjust: impl FnOnce(&mut ForestConfig),
    ) -> Result<ForestBuilder, ApiError> {
        let mut config = ForestConfig::new(self.species()?);
        config.seed = self.seed;
        config.budget = self.budget_mb as usize * (1 << 20);
        adjust(&mut config);
        let mut builder =
            ForestBuilder::new(config).map_err(|e| ApiError::generation(&e, "the world"))?;
        if let Some(d) = self.density {
            builder.density_mut().patch = (10_000.0 / d).sqrt();
        }
        Ok(builder)
    }
}

/// Reads an elevation model's bytes with the description's spacing and height range for
/// what the file does not say; answers its square heightmap and its own extent.
fn read_model(
    id: &WorldId,
    bytes: &[u8],
    spacing: Option<f32>,
    range: Option<[f32; 2]>,
) -> Result<(Heightmap, [f32; 2]), ApiError> {
    let bad = |m: String| ApiError::bad_request("bad_heightmap", format!("heightmap {id}: {m}"));
    let format = model_format(bytes).ok_or_else(|| bad("not an elevation model".into()))?;
    let options = ReadOptions {
        spacing,
        height_range: range,
        raw_size: None,
    };
    let model = ElevationModel::parse(bytes, format, &options).map_err(|e| bad(e.to_string()))?;
    if !model.spacing_from_file && spacing.is_none() {
        return Err(bad(
            "the file does not say how far apart its samples are: give \"spacing\" in the terrain"
                .into(),
        ));
    }
    model.to_heightmap().map_err(|e| bad(e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Left at its defaults, a description's ground is the batch tools' default terrain.
    #[test]
    fn default_ground_is_the_presets_terrain() {
        let d = WorldDescription::parse(br#"{"seed": 5, "area": 600}"#).unwrap();
        let (map, extent) = d.ground(|_| unreachable!()).unwrap();
        assert_eq!(extent, [600.0, 600.0]);
        assert_eq!(map, sylva::presets::terrain(5, 600.0).unwrap());
    }

    /// Erosion moves ground, the same way for the same seed.
    #[test]
    fn erosion_carves_the_same_ground_for_a_seed() {
        let eroded =
            WorldDescription::parse(br#"{"terrain": {"generated": {"erosion": 0.5}}}"#).unwrap();
        let (a, _) = eroded.ground(|_| unreachable!()).unwrap();
        let (b, _) = eroded.ground(|_| unreachable!()).unwrap();
        let (plain, _) = WorldDescription::default()
            .ground(|_| unreachable!())
            .unwrap();
        assert_eq!(a, b);
        assert_ne!(a, plain);
    }
}
