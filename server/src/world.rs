//! A kept world made ready to draw tiles: its species' instance caches, its terrain and its
//! tile scheme, built from its description the way `sylva tiles` builds them from its flags,
//! so a served tile is the batch writer's tile byte for byte.

use std::collections::VecDeque;
use std::sync::{Arc, Mutex, OnceLock};

use sylva::export::{TileScheme, TilesetOptions};
use sylva::forest::ForestBuilder;
use sylva::terrain::Heightmap;
use sylva::world::{Quiet, WorldDescription, WorldError, WorldId};

use crate::cache::Cache;
use crate::error::ApiError;

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

/// Builds a world through the world layer (seconds: hero trees for every species). Blocking.
pub(crate) fn build(description: &WorldDescription, cache: &Cache) -> Result<BuiltWorld, ApiError> {
    // The ground first: a missing model is reported before seconds of hero trees.
    let ground = description.ground(|id| uploaded_model(cache, id))?;
    let world = description.world_builder()?.build(ground, &Quiet)?;
    let scheme = TileScheme::new(world.region(), description.tile_size, description.group)
        .map_err(|e| ApiError::bad_request("bad_description", e.to_string()))?;
    let [lon, lat] = description.origin;
    let options = TilesetOptions::default().with_origin((lon, lat));
    Ok(BuiltWorld {
        builder: world.forest,
        map: world.ground.map,
        scheme,
        options,
    })
}

/// The bytes of the elevation model uploaded as `id`.
pub(crate) fn uploaded_model(cache: &Cache, id: &WorldId) -> Result<Vec<u8>, WorldError> {
    let path = cache.heightmap_path(id);
    std::fs::read(&path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => WorldError::UnknownModel {
            id: id.as_str().to_owned(),
            hint: "upload it with POST /heightmaps first".into(),
        },
        _ => WorldError::File(sylva::base::file::FileError::new(&path, e)),
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
