//! `POST /worlds`, `GET /worlds/{id}` and a world's files: `tileset.json`, `shared.bin`,
//! `impostors/variant_K.png` and `tiles/{tile}.glb`, generated on first request.

use std::path::PathBuf;
use std::sync::Arc;

use axum::Json;
use axum::extract::{Path, Request, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::json;
use sha2::{Digest, Sha256};
use sylva::export::{ExportError, Level, TileId, TileScheme, write_tile, write_tileset};
use sylva::forest::Rect;
use sylva::terrain::glam::Vec2;

use crate::cache::GENERATOR;
use sylva::world::limits::MAX_DESCRIPTION_BYTES;
use sylva::world::{TerrainDescription, WorldDescription, WorldId};

use crate::error::ApiError;
use crate::files;
use crate::state::Server;

/// `POST /worlds`: keeps a world description, answers its id and URLs (201).
pub(crate) async fn create(
    State(server): State<Arc<Server>>,
    request: Request,
) -> Result<Response, ApiError> {
    let body = crate::body::read(request, MAX_DESCRIPTION_BYTES).await?;
    let description = WorldDescription::parse(&body)?;
    // Inline species are parsed now, so a mistake in one is this answer's, with its line;
    // and each one's tree is costed now (its word derived, its stems counted: the memory of
    // a word), so a grammar bomb is this answer's 422, not the death of every later request.
    let species = description.species()?;
    let costed = tokio::task::spawn_blocking(move || {
        species.iter().try_for_each(|s| s.check_cost().map(drop))
    })
    .await
    .map_err(|e| ApiError::internal(e.to_string()))?;
    costed.map_err(|e| ApiError::unprocessable(e.to_string()))?;
    // A world on generated ground knows its tiles now: a world this server would refuse to
    // cut into tiles (too many, or tiles wider than the world) is refused here, with what it
    // would cost and what to change, not accepted and then refused at every request.
    scheme_of(&description).map_err(|e| ApiError::unprocessable(e.to_string()))?;
    let keeper = server.clone();
    let (id, notes) = tokio::task::spawn_blocking(move || {
        // A model's ground is made now, so a model that makes no world (too large without
        // a crop, no spacing) is this answer's 400, and the window taken of a large one is
        // said in its notes.
        let notes = match &description.terrain {
            TerrainDescription::Heightmap { id, .. } => {
                let ground =
                    description.ground(|id| crate::world::uploaded_model(&keeper.cache, id))?;
                // A served world names its window by the terrain's "crop", not a flag.
                ground.notes_naming(&format!("heightmap {id}"), |w| {
                    format!(
                        "\"crop\": [{}, {}, {}, {}] in the terrain names this window",
                        w.column, w.row, w.width, w.height
                    )
                })
            }
            TerrainDescription::Generated { .. } => Vec::new(),
        };
        let id = keeper.cache.keep_description(&description)?;
        Ok::<_, ApiError>((id, notes))
    })
    .await
    .map_err(|e| ApiError::internal(e.to_string()))??;
    let location = format!("/worlds/{id}");
    let body = Json(json!({
        "id": id.as_str(),
        "description": location,
        "tileset": format!("/worlds/{id}/tileset.json"),
        "page": format!("/?world={id}"),
        "notes": notes,
    }));
    let mut response = (StatusCode::CREATED, body).into_response();
    if let Ok(v) = HeaderValue::from_str(&location) {
        response.headers_mut().insert(header::LOCATION, v);
    }
    Ok(response)
}

/// A world's id from its path segment: an unknown world for anything not shaped like one.
fn world_id(segment: &str) -> Result<WorldId, ApiError> {
    WorldId::parse(segment).ok_or_else(|| {
        ApiError::not_found(
            "unknown_world",
            format!(
                "'{}' is not a world id (32 hex digits, as POST /worlds answers)",
                segment.chars().take(80).collect::<String>()
            ),
        )
    })
}

/// `GET /worlds/{id}`: the kept description, in canonical form.
pub(crate) async fn description(
    State(server): State<Arc<Server>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let id = world_id(&id)?;
    let path = server.cache.description_path(&id);
    if !tokio::fs::try_exists(&path).await.unwrap_or(false) {
        return Err(ApiError::not_found(
            "unknown_world",
            format!("no world {id}"),
        ));
    }
    files::send(&path, &etag(&id, "description"), &headers).await
}

/// One of a world's files.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum WorldFile {
    Tileset,
    Shared,
    Impostor(u32),
    Tile(TileId),
}

impl WorldFile {
    /// Its path in the world's folder.
    fn relative(self) -> PathBuf {
        match self {
            WorldFile::Tileset => "tileset.json".into(),
            WorldFile::Shared => "shared.bin".into(),
            WorldFile::Impostor(k) => format!("impostors/variant_{k}.png").into(),
            WorldFile::Tile(t) => format!("tiles/{t}.glb").into(),
        }
    }

    /// The generation that makes it: the root (tileset, shared geometry and impostor atlases
    /// together) or one tile.
    fn job(self) -> String {
        match self {
            WorldFile::Tile(t) => format!("tiles/{t}"),
            _ => "root".into(),
        }
    }
}

/// A strong tag for a world's file: its bytes are a pure function of the generator, the
/// world and the file's name.
fn etag(id: &WorldId, file: &str) -> String {
    let digest = Sha256::digest(format!("{GENERATOR}\n{id}\n{file}").as_bytes());
    format!("\"{}\"", WorldId::of(&digest[..8]))
}

/// The scheme of a world on generated terrain, known from its description alone (a world on
/// an uploaded heightmap learns its side when built).
/// `None` for such a world; the scheme's error for a description it cannot cut into tiles.
fn scheme_of(description: &WorldDescription) -> Result<Option<TileScheme>, ExportError> {
    match description.terrain {
        TerrainDescription::Generated { .. } => {
            let region = Rect::new(Vec2::ZERO, Vec2::splat(description.area));
            TileScheme::new(region, description.tile_size, description.group).map(Some)
        }
        TerrainDescription::Heightmap { .. } => Ok(None),
    }
}

/// An error unless `tile` is one of `scheme`'s.
fn check_tile(scheme: &TileScheme, tile: TileId) -> Result<(), ApiError> {
    scheme.rect(tile).map(|_| ()).map_err(|_| {
        let (nx, ny) = match tile.level {
            Level::Fine => scheme.fine_count(),
            Level::Coarse => scheme.coarse_count(),
        };
        ApiError::not_found(
            "unknown_tile",
            format!("tile {tile} is not in this world: its level has {nx} x {ny} tiles"),
        )
    })
}

/// Sends a world's file, generating it first if it is not stored yet.
async fn send_world_file(
    server: Arc<Server>,
    id: &str,
    file: WorldFile,
    headers: &HeaderMap,
) -> Result<Response, ApiError> {
    let id = world_id(id)?;
    let dir = server.cache.world_dir(&id);
    let relative = file.relative();
    let path = dir.join(&relative);
    let tag = etag(&id, &relative.to_string_lossy());
    if tokio::fs::try_exists(&path).await.unwrap_or(false) {
        return files::send(&path, &tag, headers).await;
    }
    let reader = server.clone();
    let wanted = id.clone();
    let description = tokio::task::spawn_blocking(move || reader.cache.description(&wanted))
        .await
        .map_err(|e| ApiError::internal(e.to_string()))??;
    if let (WorldFile::Tile(t), Some(scheme)) = (file, scheme_of(&description).ok().flatten()) {
        check_tile(&scheme, t)?;
    }
    let key = format!("{id}/{}", file.job());
    let (worker, target, world_id) = (server.clone(), path.clone(), id.clone());
    server
        .jobs
        .run(&key, move || generate(&worker, &world_id, file, &target))
        .await?;
    if !tokio::fs::try_exists(&path).await.unwrap_or(false) {
        return Err(ApiError::not_found(
            "unknown_file",
            format!("this world has no {}", relative.display()),
        ));
    }
    files::send(&path, &tag, headers).await
}

/// Writes `file` of world `id` into its folder (nothing if another job already has).
/// Blocking.
fn generate(
    server: &Server,
    id: &WorldId,
    file: WorldFile,
    target: &std::path::Path,
) -> Result<(), ApiError> {
    let dir = server.cache.world_dir(id);
    // The root's files are written together, the tileset last: with it in place, an
    // impostor that is missing is one the world does not have.
    let done = match file {
        WorldFile::Tile(_) => target.to_path_buf(),
        _ => dir.join("tileset.json"),
    };
    if done.exists() {
        return Ok(());
    }
    let world = server.worlds.get(id, &server.cache)?;
    match file {
        WorldFile::Tile(tile) => {
            check_tile(&world.scheme, tile)?;
            write_tile(&world.builder, &world.map, &world.scheme, tile, &dir)
                .map_err(|e| ApiError::generation(&e, &format!("tile {tile}")))?;
        }
        _ => {
            write_tileset(
                &world.builder,
                &world.map,
                &world.scheme,
                &dir,
                &world.options,
            )
            .map_err(|e| ApiError::generation(&e, "the tileset"))?;
        }
    }
    Ok(())
}

/// `GET /worlds/{id}/tileset.json`.
pub(crate) async fn tileset(
    State(server): State<Arc<Server>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    send_world_file(server, &id, WorldFile::Tileset, &headers).await
}

/// `GET /worlds/{id}/shared.bin`.
pub(crate) async fn shared(
    State(server): State<Arc<Server>>,
    Path(id): Path<String>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    send_world_file(server, &id, WorldFile::Shared, &headers).await
}

/// `GET /worlds/{id}/impostors/variant_K.png`.
pub(crate) async fn impostor(
    State(server): State<Arc<Server>>,
    Path((id, name)): Path<(String, String)>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let k = name
        .strip_prefix("variant_")
        .and_then(|n| n.strip_suffix(".png"))
        .and_then(|k| k.parse::<u32>().ok())
        .filter(|&k| k < 4096)
        .ok_or_else(|| ApiError::not_found("unknown_file", "impostors are variant_K.png"))?;
    send_world_file(server, &id, WorldFile::Impostor(k), &headers).await
}

/// `GET /worlds/{id}/tiles/{tile}.glb`.
pub(crate) async fn tile(
    State(server): State<Arc<Server>>,
    Path((id, name)): Path<(String, String)>,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let tile = name
        .strip_suffix(".glb")
        .and_then(|t| t.parse::<TileId>().ok())
        .ok_or_else(|| {
            ApiError::not_found(
                "unknown_tile",
                format!(
                    "'{}' is not a tile: tiles are c_X_Y.glb (coarse) and f_X_Y.glb (fine)",
                    name.chars().take(80).collect::<String>()
                ),
            )
        })?;
    send_world_file(server, &id, WorldFile::Tile(tile), &headers).await
}
