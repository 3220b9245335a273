//! A kept world made ready to draw tiles: its species' instance caches, its terrain and its
//! tile scheme, built from its description the way `sylva tiles` builds them from its flags,
//! so a served tile is the batch writer's tile byte for byte.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, OnceLock};

use sylva::export::{TileScheme, TilesetOptions};
use sylva::forest::{ForestBuilder, ForestConfig, Rect};
use sylva::terrain::dem::{DemFormat, ElevationModel, ReadOptions};
use sylva::terrain::glam::Vec2;
use sylva::terrain::{DiamondSquare, EdgeMode, Heightmap};

use crate::cache::Cache;
use crate::description::{MAX_SIDE, TerrainDescription, WorldDescription};
use crate::error::ApiError;
use crate::id::WorldId;

/// A world ready to draw.
#[derive(Debug)]
pub(crate) struct BuiltWorld {
    /// Its species' caches and placement.
    pub(crate) builder: ForestBuilder,
    /// Its ground.
    pub(crate) map: Heightmap,
    /// How it is cut into tiles.
    pub(crate) scheme: TileScheme,
    /// Where it stands on the globe.
    pub(crate) options: TilesetOptions,
}

/// The format of an uploaded elevation model, from its first bytes (or, for SRTM `.hgt`,
/// which has none, its length).
pub(crate) fn upload_format(bytes: &[u8]) -> Option<DemFormat> {
    let hgt = [2 * 1201 * 1201, 2 * 3601 * 3601].contains(&bytes.len());
    DemFormat::of(std::path::Path::new(""), &bytes[..bytes.len().min(16)])
        .or(hgt.then_some(DemFormat::Hgt))
}

/// Reads an uploaded elevation model with the description's spacing and height range for
/// what the file does not say; answers its square heightmap and its own extent. Blocking.
fn uploaded_terrain(
    cache: &Cache,
    id: &str,
    spacing: Option<f32>,
    range: Option<[f32; 2]>,
) -> Result<(Heightmap, [f32; 2]), ApiError> {
    let id = WorldId::parse(id)
        .ok_or_else(|| ApiError::bad_request("bad_description", "bad heightmap id"))?;
    let bytes = std::fs::read(cache.heightmap_path(&id)).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => ApiError::bad_request(
            "unknown_heightmap",
            format!("no heightmap {id}: upload it with POST /heightmaps first"),
        ),
        _ => ApiError::internal(format!("heightmap {id}: {e}")),
    })?;
    let bad = |m: String| ApiError::bad_request("bad_heightmap", format!("heightmap {id}: {m}"));
    let format = upload_format(&bytes).ok_or_else(|| bad("not an elevation model".into()))?;
    let options = ReadOptions {
        spacing,
        height_range: range,
        raw_size: None,
    };
    let model = ElevationModel::parse(&bytes, format, &options).map_err(|e| bad(e.to_string()))?;
    if !model.spacing_from_file && spacing.is_none() {
        return Err(bad(
            "the file does not say how far apart its samples are: give \"spacing\" in the terrain"
                .into(),
        ));
    }
    model.to_heightmap().map_err(|e| bad(e.to_string()))
}

/// Builds a world (seconds: hero trees for every species). Blocking.
pub(crate) fn build(description: &WorldDescription, cache: &Cache) -> Result<BuiltWorld, ApiError> {
    let fail = |e: &(dyn std::error::Error + 'static)| ApiError::generation(e, "the world");
    let species = description.species()?;
    // The world is the model's own extent, which the square map covers.
    let (map, side) = match &description.terrain {
        TerrainDescription::Heightmap {
            id,
            spacing,
            height_range,
        } => {
            let (map, extent) = uploaded_terrain(cache, id, *spacing, *height_range)?;
            if !extent.iter().all(|e| (10.0..=MAX_SIDE).contains(e)) {
                return Err(ApiError::bad_request(
                    "bad_heightmap",
                    format!(
                        "the heightmap covers {:.0} x {:.0} m: expected 10 to {MAX_SIDE} a side (set its spacing)",
                        extent[0], extent[1]
                    ),
                ));
            }
            (map, extent)
        }
        TerrainDescription::Generated {
            seed,
            roughness,
            relief,
            smoothing,
        } => {
            let side = description.area;
            // The batch tools' default terrain (`sylva::presets::terrain`) when left as is.
            let mut map = DiamondSquare::new(257)
                .with_seed(seed.unwrap_or(description.seed))
                .with_spacing(side / 256.0)
                .with_roughness(*roughness)
                .with_amplitude(side * relief)
                .generate()
                .map_err(|e| fail(&e))?;
            if *smoothing > 0.0 {
                map.smooth(*smoothing, EdgeMode::Mirror)
                    .map_err(|e| fail(&e))?;
            }
            (map, [side, side])
        }
    };
    let mut config = ForestConfig::new(species);
    config.seed = description.seed;
    config.budget = description.budget_mb as usize * (1 << 20);
    let mut builder = ForestBuilder::new(config).map_err(|e| fail(&e))?;
    if let Some(d) = description.density {
        builder.density_mut().patch = (10_000.0 / d).sqrt();
    }
    let region = Rect::new(Vec2::ZERO, Vec2::new(side[0], side[1]));
    let scheme = TileScheme::new(region, description.tile_size, description.group)
        .map_err(|e| ApiError::bad_request("bad_description", e.to_string()))?;
    let [lon, lat] = description.origin;
    let options = TilesetOptions::default().with_origin((lon, lat));
    Ok(BuiltWorld {
        builder,
        map,
        scheme,
        options,
    })
}

/// One world's slot: built once, by whichever job needs it first.
type Slot = Arc<OnceLock<Result<Arc<BuiltWorld>, ApiError>>>;

/// The worlds held in memory, the most recently used last: at most `capacity`, each its
/// caches (the budget) and terrain, so memory is bounded by the count.
#[derive(Debug)]
pub(crate) struct Worlds {
    slots: Mutex<VecDeque<(WorldId, Slot)>>,
    capacity: usize,
}

impl Worlds {
    /// Room for `capacity` worlds (at least 1).
    pub(crate) fn new(capacity: usize) -> Worlds {
        Worlds {
            slots: Mutex::new(VecDeque::new()),
            capacity: capacity.max(1),
        }
    }

    /// The world `id`, built now unless held (jobs needing it meanwhile wait for the one
    /// build). Blocking.
    pub(crate) fn get(&self, id: &WorldId, cache: &Cache) -> Result<Arc<BuiltWorld>, ApiError> {
        let slot = {
            let mut slots = self.slots.lock().unwrap_or_else(|p| p.into_inner());
            let slot = match slots.iter().position(|(k, _)| k == id) {
                Some(i) => slots.remove(i).map(|(_, s)| s).unwrap_or_default(),
                None => Slot::default(),
            };
            slots.push_back((id.clone(), slot.clone()));
            while slots.len() > self.capacity {
                slots.pop_front();
            }
            slot
        };
        let built = slot
            .get_or_init(|| {
                let description = cache.description(id)?;
                build(&description, cache).map(Arc::new)
            })
            .clone();
        if built.is_err() {
            // A failure is not kept: the next request tries again (a heightmap unreadable
            // for a moment, say), and a world that cannot be built fails again as fast.
            let mut slots = self.slots.lock().unwrap_or_else(|p| p.into_inner());
            slots.retain(|(_, s)| !Arc::ptr_eq(s, &slot));
        }
        built
    }

    /// How many worlds are held.
    pub(crate) fn len(&self) -> usize {
        self.slots.lock().map(|s| s.len()).unwrap_or(0)
    }
}
