//! `GET /trees/{species}.glb?seed=S&age=A`: one tree of a bundled species (the thesis's tree
//! API), as `sylva tree --species` draws it, at the age asked for on the species' height curve.

use std::sync::Arc;

use axum::extract::{Path, RawQuery, State};
use axum::http::{HeaderMap, HeaderValue, StatusCode, header};
use axum::response::{IntoResponse, Response};
use sylva::forest::tree_at_age;

use crate::cache::GENERATOR;
use crate::error::ApiError;
use crate::files::IMMUTABLE;
use crate::state::Server;

/// Oldest age asked for, years (older than any species lives).
pub const MAX_AGE: f32 = 1000.0;

/// What the query asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
struct TreeQuery {
    seed: u64,
    age: Option<f32>,
}

/// Reads `seed=` and `age=`; anything else, or a value out of range, is a 400 naming it.
fn parse_query(query: Option<&str>) -> Result<TreeQuery, ApiError> {
    let mut out = TreeQuery { seed: 1, age: None };
    for pair in query.unwrap_or("").split('&').filter(|p| !p.is_empty()) {
        let (key, value) = pair.split_once('=').unwrap_or((pair, ""));
        let shown: String = value.chars().take(40).collect();
        match key {
            "seed" => {
                out.seed = value.parse().map_err(|_| {
                    ApiError::bad_request(
                        "bad_query",
                        format!(
                            "seed '{shown}': expected a whole number from 0 to {}",
                            u64::MAX
                        ),
                    )
                })?;
            }
            "age" => {
                let age: f32 = value.parse().map_err(|_| {
                    ApiError::bad_request(
                        "bad_query",
                        format!("age '{shown}': expected years, a number"),
                    )
                })?;
                if !(age > 0.0 && age <= MAX_AGE) {
                    return Err(ApiError::bad_request(
                        "bad_query",
                        format!("age {age}: expected more than 0 and at most {MAX_AGE} years"),
                    ));
                }
                out.age = Some(age);
            }
            other => {
                return Err(ApiError::bad_request(
                    "bad_query",
                    format!(
                        "unknown parameter '{}': a tree takes seed and age",
                        other.chars().take(40).collect::<String>()
                    ),
                ));
            }
        }
    }
    Ok(out)
}

/// `GET /trees/{species}.glb`.
pub(crate) async fn tree(
    State(server): State<Arc<Server>>,
    Path(name): Path<String>,
    RawQuery(query): RawQuery,
    headers: HeaderMap,
) -> Result<Response, ApiError> {
    let species_name = name.strip_suffix(".glb").unwrap_or(&name);
    let index = server
        .species
        .iter()
        .position(|s| s.name == species_name)
        .ok_or_else(|| {
            let names: Vec<&str> = server.species.iter().map(|s| s.name.as_str()).collect();
            ApiError::not_found(
                "unknown_species",
                format!(
                    "no species '{}': trees are {}.glb",
                    species_name.chars().take(80).collect::<String>(),
                    names.join(".glb, ")
                ),
            )
        })?;
    let q = parse_query(query.as_deref())?;
    let age = q
        .age
        .map_or_else(|| "canopy".to_string(), |a| a.to_string());
    let key = format!("tree/{species_name}/{}/{age}", q.seed);
    let tag = format!("\"{}-{}-{}-{age}\"", GENERATOR, species_name, q.seed);
    let glb = match server.trees.get(&key) {
        Some(glb) => glb,
        None => {
            let worker = server.clone();
            let stored = key.clone();
            server
                .jobs
                .run(&key, move || {
                    let glb = draw(&worker, index, q)?;
                    worker.trees.put(stored, glb);
                    Ok(())
                })
                .await?;
            // Just made (a store keeps its newest tree whatever its size), unless trees made
            // since by others pushed it out: then it is drawn again for this answer.
            match server.trees.get(&key) {
                Some(glb) => glb,
                None => {
                    let worker = server.clone();
                    tokio::task::spawn_blocking(move || draw(&worker, index, q))
                        .await
                        .map_err(|e| ApiError::internal(e.to_string()))?
                        .map(Arc::new)?
                }
            }
        }
    };
    let mut response = if crate::files::matches(&headers, &tag) {
        StatusCode::NOT_MODIFIED.into_response()
    } else {
        let mut r = (StatusCode::OK, glb.as_ref().clone()).into_response();
        r.headers_mut().insert(
            header::CONTENT_TYPE,
            HeaderValue::from_static("model/gltf-binary"),
        );
        r
    };
    let h = response.headers_mut();
    h.insert(header::CACHE_CONTROL, HeaderValue::from_static(IMMUTABLE));
    if let Ok(v) = HeaderValue::from_str(&tag) {
        h.insert(header::ETAG, v);
    }
    Ok(response)
}

/// Draws the tree. Blocking.
fn draw(server: &Server, index: usize, q: TreeQuery) -> Result<Vec<u8>, ApiError> {
    let species = &server.species[index];
    let fail = |e: &(dyn std::error::Error + 'static)| ApiError::generation(e, "the tree");
    let (generations, scale) = match q.age {
        Some(age) => tree_at_age(species, age).map_err(|e| fail(&e))?,
        None => (species.generations, 1.0),
    };
    let mut mesh = species.mesh(generations, q.seed).map_err(|e| fail(&e))?;
    if scale != 1.0 {
        for v in &mut mesh.vertices {
            v.position = v.position.map(|x| x * scale);
        }
    }
    sylva::export::tree_glb(species, &mesh).map_err(|e| fail(&e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn queries_name_what_is_wrong() {
        assert_eq!(parse_query(None).unwrap(), TreeQuery { seed: 1, age: None });
        assert_eq!(
            parse_query(Some("seed=7&age=40")).unwrap(),
            TreeQuery {
                seed: 7,
                age: Some(40.0)
            }
        );
        for (q, said) in [
            ("seed=99999999999999999999999999", "seed"),
            ("seed=-1", "seed"),
            ("age=1e30", "age"),
            ("age=NaN", "age"),
            ("age=0", "age"),
            ("colour=red", "colour"),
        ] {
            let e = parse_query(Some(q)).unwrap_err();
            assert_eq!(e.status.as_u16(), 400);
            assert!(e.message.contains(said), "{q}: {}", e.message);
        }
    }
}
