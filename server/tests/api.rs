//! The server as a client sees it: kept worlds, the batch writer's bytes, caching headers and
//! ranges, one tree, and every kind of bad request answered with a 4xx in JSON.

mod common;

use common::{Client, SMALL_WORLD, inline_species_world, options, scratch, start, world};
use hyper::{Method, StatusCode};
use sylva::world::limits::MAX_DESCRIPTION_BYTES;
use sylva_server::WorldDescription;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_served_world_is_the_batch_writers_world() {
    let server = start(options(scratch("batch"))).await;
    let id = world(server.address, SMALL_WORLD).await;
    // Posting it again, written otherwise, names the same world.
    let again = world(server.address, &SMALL_WORLD.replace("200", "200.0")).await;
    assert_eq!(id, again);
    let mut c = Client::connect(server.address).await;
    let description = c.get(&format!("/worlds/{id}")).await;
    assert_eq!(description.status, StatusCode::OK);
    assert_eq!(description.json()["area"], 200.0);

    // The batch writer's world from the same description.
    let parsed = WorldDescription::parse(SMALL_WORLD.as_bytes()).unwrap();
    let batch = scratch("batch-out");
    let species: Vec<_> = sylva::presets::species()
        .unwrap()
        .into_iter()
        .filter(|s| s.name == "birch")
        .collect();
    let mut config = sylva::forest::ForestConfig::new(species);
    config.seed = parsed.seed;
    config.budget = 4 << 20;
    let builder = sylva::forest::ForestBuilder::new(config).unwrap();
    let map = sylva::presets::terrain(parsed.seed, 200.0).unwrap();
    let region = sylva::forest::Rect::new(
        sylva::terrain::glam::Vec2::ZERO,
        sylva::terrain::glam::Vec2::splat(200.0),
    );
    let scheme = sylva::export::TileScheme::new(region, 50.0, 2).unwrap();
    sylva::export::write_tileset(
        &builder,
        &map,
        &scheme,
        &batch,
        &sylva::export::TilesetOptions::default(),
    )
    .unwrap();
    for tile in ["f_1_2", "c_1_0"] {
        sylva::export::write_tile(&builder, &map, &scheme, tile.parse().unwrap(), &batch).unwrap();
    }
    for (url, file) in [
        ("tileset.json", "tileset.json"),
        ("shared.bin", "shared.bin"),
        ("impostors/variant_0.png", "impostors/variant_0.png"),
        ("tiles/f_1_2.glb", "tiles/f_1_2.glb"),
        ("tiles/c_1_0.glb", "tiles/c_1_0.glb"),
    ] {
        let a = c.get(&format!("/worlds/{id}/{url}")).await;
        assert_eq!(
            a.status,
            StatusCode::OK,
            "{url}: {}",
            String::from_utf8_lossy(&a.body)
        );
        assert_eq!(
            a.body,
            std::fs::read(batch.join(file)).unwrap(),
            "{url} differs from the batch writer's"
        );
        assert_eq!(
            a.headers["cache-control"],
            "public, max-age=31536000, immutable"
        );
    }
    server.stop().await;
    let _ = std::fs::remove_dir_all(&batch);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn etags_and_ranges_answer_as_http_says() {
    let server = start(options(scratch("ranges"))).await;
    let id = world(server.address, SMALL_WORLD).await;
    let mut c = Client::connect(server.address).await;
    let path = format!("/worlds/{id}/tiles/f_0_0.glb");
    let whole = c.get(&path).await;
    assert_eq!(whole.status, StatusCode::OK);
    assert_eq!(&whole.body[..4], b"glTF");
    assert_eq!(whole.headers["content-type"], "model/gltf-binary");
    let tag = whole.headers["etag"].to_str().unwrap().to_owned();
    let len = whole.body.len();

    let cached = c
        .send(Method::GET, &path, &[("if-none-match", &tag)], vec![])
        .await
        .unwrap();
    assert_eq!(cached.status, StatusCode::NOT_MODIFIED);
    assert!(cached.body.is_empty());

    let part = c
        .send(Method::GET, &path, &[("range", "bytes=12-19")], vec![])
        .await
        .unwrap();
    assert_eq!(part.status, StatusCode::PARTIAL_CONTENT);
    assert_eq!(part.body, whole.body[12..20]);
    assert_eq!(
        part.headers["content-range"],
        format!("bytes 12-19/{len}").as_str()
    );
    let tail = c
        .send(Method::GET, &path, &[("range", "bytes=-4")], vec![])
        .await
        .unwrap();
    assert_eq!(tail.body, whole.body[len - 4..]);
    let past = c
        .send(
            Method::GET,
            &path,
            &[("range", &format!("bytes={len}-"))],
            vec![],
        )
        .await
        .unwrap();
    assert_eq!(past.status, StatusCode::RANGE_NOT_SATISFIABLE);
    assert_eq!(
        past.headers["content-range"],
        format!("bytes */{len}").as_str()
    );
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn one_tree_at_an_age() {
    let server = start(options(scratch("trees"))).await;
    let mut c = Client::connect(server.address).await;
    let young = c.get("/trees/birch.glb?seed=3&age=8").await;
    let old = c.get("/trees/birch.glb?seed=3&age=80").await;
    for a in [&young, &old] {
        assert_eq!(
            a.status,
            StatusCode::OK,
            "{}",
            String::from_utf8_lossy(&a.body)
        );
        assert_eq!(&a.body[..4], b"glTF");
    }
    // An older tree is drawn from a later generation: more geometry.
    assert!(
        old.body.len() > young.body.len(),
        "{} <= {}",
        old.body.len(),
        young.body.len()
    );
    // The same URL is the same bytes (and its tag), from the store.
    let again = c.get("/trees/birch.glb?seed=3&age=80").await;
    assert_eq!(again.body, old.body);
    assert_eq!(again.headers["etag"], old.headers["etag"]);
    server.stop().await;
}

/// Every request here is the client's mistake: each must be a 4xx with a JSON error, never
/// a 5xx, and the server must go on serving.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_requests_are_4xx_in_json() {
    let server = start(options(scratch("bad"))).await;
    let id = world(server.address, SMALL_WORLD).await;
    let mut c = Client::connect(server.address).await;
    let big = format!(
        "{{\"species\": [{}]}}",
        vec!["\"oak\""; MAX_DESCRIPTION_BYTES / 6].join(",")
    );
    let deep = format!("{}{}", "[".repeat(100_000), "]".repeat(100_000));
    let posts: Vec<(&str, Vec<u8>, u16)> = vec![
        ("/worlds", b"{\"area\": ".to_vec(), 400),
        ("/worlds", b"not json".to_vec(), 400),
        ("/worlds", vec![0xff, 0xfe, 0x00], 400),
        ("/worlds", deep.into_bytes(), 400),
        ("/worlds", big.into_bytes(), 413),
        ("/worlds", br#"{"species": ["baobab"]}"#.to_vec(), 400),
        (
            "/worlds",
            br#"{"species": [{"file": "grammar: nonsense ((("}]}"#.to_vec(),
            400,
        ),
        // An inline species never reads the server's disk.
        (
            "/worlds",
            br#"{"species": [{"file": "grammar: /etc/passwd"}]}"#.to_vec(),
            400,
        ),
        (
            "/worlds",
            br#"{"species": [{"file": "grammar: ../../Cargo.toml"}]}"#.to_vec(),
            400,
        ),
        (
            "/worlds",
            br#"{"species": [{"file": "grammar: x.lsys", "grammar": "axiom: A\nA -> B("}]}"#
                .to_vec(),
            400,
        ),
        ("/worlds", br#"{"area": 1e12}"#.to_vec(), 400),
        ("/worlds", br#"{"tile_size": 0.001}"#.to_vec(), 400),
        // Issue 60: inside every field's range, but a million tiles (a 1.1 GB tileset.json)
        // grew the server until it died; and a world narrower than its tiles was accepted,
        // then refused at every request. Both are refused when posted.
        (
            "/worlds",
            br#"{"area": 20000, "tile_size": 20, "group": 1}"#.to_vec(),
            422,
        ),
        ("/worlds", br#"{"area": 100}"#.to_vec(), 422),
        (
            "/worlds",
            br#"{"seed": 123456789012345678901234567890}"#.to_vec(),
            400,
        ),
        (
            "/worlds",
            br#"{"terrain": {"heightmap": {"id": "0123456789abcdef0123456789abcdef"}}}"#.to_vec(),
            400,
        ),
        (
            "/worlds",
            br#"{"terrain": {"heightmap": {"id": "../../../etc/passwd"}}}"#.to_vec(),
            400,
        ),
        ("/heightmaps", b"GIF89a not a png".to_vec(), 400),
    ];
    for (path, body, want) in posts {
        let shown = String::from_utf8_lossy(&body[..body.len().min(60)]).into_owned();
        // A connection per request: one whose body was refused unread is closed after it.
        let a = Client::connect(server.address)
            .await
            .post(path, &body)
            .await;
        assert_eq!(
            a.status.as_u16(),
            want,
            "POST {path} {shown}: {}",
            String::from_utf8_lossy(&a.body)
        );
        assert!(a.json()["message"].is_string(), "POST {path} {shown}");
    }
    let w = format!("/worlds/{id}");
    let long = "9".repeat(5000);
    let gets = [
        (format!("{w}/tiles/f_99_0.glb"), 404),
        (format!("{w}/tiles/c_0_4294967295.glb"), 404),
        (format!("{w}/tiles/f_{long}_0.glb"), 404),
        (format!("{w}/tiles/x_0_0.glb"), 404),
        (format!("{w}/tiles/f_0_0"), 404),
        (
            format!("{w}/tiles/..%2F..%2F..%2Fdescriptions%2F{id}.json"),
            404,
        ),
        (format!("{w}/impostors/..%2Fshared.bin"), 404),
        (format!("{w}/impostors/variant_99999999999.png"), 404),
        (
            "/worlds/..%2F..%2Fetc%2Fpasswd/tileset.json".to_string(),
            404,
        ),
        (
            "/worlds/ffffffffffffffffffffffffffffffff/tileset.json".to_string(),
            404,
        ),
        ("/worlds/ffffffffffffffffffffffffffffffff".to_string(), 404),
        ("/worlds/%00/tiles/f_0_0.glb".to_string(), 404),
        ("/modules/..%2F..%2FCargo.toml".to_string(), 404),
        ("/modules/three/../../Cargo.toml".to_string(), 404),
        ("/trees/baobab.glb".to_string(), 404),
        ("/trees/..%2Fbirch.glb".to_string(), 404),
        (
            "/trees/birch.glb?seed=999999999999999999999999999999".to_string(),
            400,
        ),
        ("/trees/birch.glb?age=1e300".to_string(), 400),
        ("/trees/birch.glb?age=-5".to_string(), 400),
        (format!("/trees/birch.glb?seed={long}"), 400),
        ("/trees/birch.glb?generations=100000".to_string(), 400),
        ("/no/such/endpoint".to_string(), 404),
    ];
    for (path, want) in gets {
        let a = c.get(&path).await;
        let shown: String = path.chars().take(90).collect();
        assert_eq!(
            a.status.as_u16(),
            want,
            "GET {shown}: {}",
            String::from_utf8_lossy(&a.body)
        );
        assert!(a.json()["message"].is_string(), "GET {shown}");
    }
    // A body declared far over the limit is refused from its head, before it is read.
    let answer = head_only(server.address, "POST /worlds", 5 << 30).await;
    assert!(answer.starts_with("HTTP/1.1 413"), "{answer}");
    let answer = head_only(server.address, "POST /heightmaps", 1 << 40).await;
    assert!(answer.starts_with("HTTP/1.1 413"), "{answer}");
    // Wrong methods are refused too (axum's 405).
    let a = c.send(Method::DELETE, &w, &[], vec![]).await.unwrap();
    assert_eq!(a.status, StatusCode::METHOD_NOT_ALLOWED);
    // And the server still serves.
    assert_eq!(
        c.get(&format!("{w}/tiles/f_0_0.glb")).await.status,
        StatusCode::OK
    );
    server.stop().await;
}

/// Sends a request's head declaring `length` bytes of body, sends none, and reads the answer.
async fn head_only(address: std::net::SocketAddr, request: &str, length: u64) -> String {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut stream = tokio::net::TcpStream::connect(address).await.unwrap();
    let head = format!("{request} HTTP/1.1\r\nhost: test\r\ncontent-length: {length}\r\n\r\n");
    stream.write_all(head.as_bytes()).await.unwrap();
    let mut answer = vec![0; 4096];
    let n = tokio::time::timeout(std::time::Duration::from_secs(10), stream.read(&mut answer))
        .await
        .expect("no answer in 10 s")
        .unwrap();
    String::from_utf8_lossy(&answer[..n]).into_owned()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_world_on_an_uploaded_heightmap() {
    let server = start(options(scratch("upload"))).await;
    let mut png = Vec::new();
    // 300 m of the default terrain, its range and spacing in the file's sylva chunk.
    sylva::presets::terrain(4, 300.0)
        .unwrap()
        .write_png16(&mut png)
        .unwrap();
    let mut c = Client::connect(server.address).await;
    let up = c.post("/heightmaps", &png).await;
    assert_eq!(
        up.status,
        StatusCode::CREATED,
        "{}",
        String::from_utf8_lossy(&up.body)
    );
    let heightmap = up.json()["id"].as_str().unwrap().to_owned();
    // The same bytes again: the same id.
    assert_eq!(
        c.post("/heightmaps", &png).await.json()["id"],
        heightmap.as_str()
    );
    let id = world(
        server.address,
        &format!(r#"{{"terrain": {{"heightmap": {{"id": "{heightmap}"}}}}, "tile_size": 100, "group": 2, "budget_mb": 4, "species": ["pine"]}}"#),
    )
    .await;
    // The world is the heightmap's 300 m: three fine tiles a side.
    let tile = c.get(&format!("/worlds/{id}/tiles/f_2_2.glb")).await;
    assert_eq!(
        tile.status,
        StatusCode::OK,
        "{}",
        String::from_utf8_lossy(&tile.body)
    );
    assert_eq!(&tile.body[..4], b"glTF");
    let outside = c.get(&format!("/worlds/{id}/tiles/f_3_0.glb")).await;
    assert_eq!(outside.status, StatusCode::NOT_FOUND);
    assert_eq!(outside.json()["error"], "unknown_tile");
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn many_asking_for_one_new_tile_get_one_tile() {
    let server = start(options(scratch("one-flight"))).await;
    let id = world(server.address, SMALL_WORLD).await;
    let path = format!("/worlds/{id}/tiles/f_2_1.glb");
    let mut askers = Vec::new();
    for _ in 0..32 {
        let (address, path) = (server.address, path.clone());
        askers.push(tokio::spawn(async move {
            Client::connect(address).await.get(&path).await
        }));
    }
    let mut bodies = Vec::new();
    for a in askers {
        let answer = a.await.unwrap();
        assert_eq!(answer.status, StatusCode::OK);
        bodies.push(answer.body);
    }
    assert!(bodies.windows(2).all(|w| w[0] == w[1]));
    let status = Client::connect(server.address)
        .await
        .get("/status")
        .await
        .json();
    assert_eq!(status["generations_queued"], 0);
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_world_of_an_inline_species_with_its_grammar() {
    let server = start(options(scratch("inline"))).await;
    let species = r#"name: bush\ngrammar: bush.lsys\ngenerations: 4\nleaves: A\n"#;
    let grammar = r#"axiom: A\nA -> F[+A][-A]F[&A]A\n"#;
    let id = world(server.address, &inline_species_world(species, grammar)).await;
    let mut c = Client::connect(server.address).await;
    let tile = c.get(&format!("/worlds/{id}/tiles/f_1_1.glb")).await;
    assert_eq!(
        tile.status,
        StatusCode::OK,
        "{}",
        String::from_utf8_lossy(&tile.body)
    );
    assert_eq!(&tile.body[..4], b"glTF");
    server.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_world_on_a_real_elevation_model() {
    let server = start(options(scratch("real-dem"))).await;
    let dems = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../terrain/tests/data/dems");
    let mut c = Client::connect(server.address).await;
    for (file, tiles) in [
        ("west_bijou_escarpment.asc", (7, 5)),
        ("dem-hills.tiff", (6, 5)),
    ] {
        let bytes = std::fs::read(dems.join(file)).unwrap();
        let up = c.post("/heightmaps", &bytes).await;
        assert_eq!(
            up.status,
            StatusCode::CREATED,
            "{file}: {}",
            String::from_utf8_lossy(&up.body)
        );
        let heightmap = up.json()["id"].as_str().unwrap().to_owned();
        let id = world(
            server.address,
            &format!(r#"{{"terrain": {{"heightmap": {{"id": "{heightmap}"}}}}, "tile_size": 450, "group": 2, "budget_mb": 4, "species": ["pine"]}}"#),
        )
        .await;
        // The world is the model's own extent, longer east-west than north-south.
        let (nx, nz) = tiles;
        let last = c
            .get(&format!("/worlds/{id}/tiles/f_{}_{}.glb", nx - 1, nz - 1))
            .await;
        assert_eq!(
            last.status,
            StatusCode::OK,
            "{file}: {}",
            String::from_utf8_lossy(&last.body)
        );
        let beyond = c.get(&format!("/worlds/{id}/tiles/f_{}_0.glb", nx)).await;
        assert_eq!(beyond.status, StatusCode::NOT_FOUND, "{file}");
    }
    server.stop().await;
}

/// A project folder as the viewer's editor saves it is taken as it stands: its elevation
/// model uploaded gets the id its world file names, and its world file posted makes a
/// world whose tiles are served.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_saved_project_is_taken_as_posted() {
    use sylva::world::{Project, WORLD_FILE};
    let server = start(options(scratch("project"))).await;
    let folder = scratch("project-folder");
    let model = std::path::Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../terrain/tests/data/dems/west_bijou_escarpment.asc"
    ));
    let description = WorldDescription {
        species: vec![sylva_server::SpeciesEntry::Bundled("birch".into())],
        tile_size: 50.0,
        budget_mb: Some(4),
        ..WorldDescription::default()
    };
    let written = Project::write(&folder, &description, Some(model)).unwrap();
    let mut c = Client::connect(server.address).await;
    let upload = c
        .post(
            "/heightmaps",
            &std::fs::read(folder.join("heightmap.asc")).unwrap(),
        )
        .await;
    assert_eq!(upload.status, StatusCode::CREATED);
    let sylva_server::TerrainDescription::Heightmap { id: model_id, .. } = &written.terrain else {
        panic!("{:?}", written.terrain)
    };
    assert_eq!(upload.json()["id"], model_id.as_str());
    let posted = std::fs::read(folder.join(WORLD_FILE)).unwrap();
    let answer = c.post("/worlds", &posted).await;
    assert_eq!(
        answer.status,
        StatusCode::CREATED,
        "{}",
        String::from_utf8_lossy(&answer.body)
    );
    assert_eq!(answer.json()["id"], written.id().as_str());
    let tileset = c
        .get(&format!("/worlds/{}/tileset.json", written.id()))
        .await;
    assert_eq!(
        tileset.status,
        StatusCode::OK,
        "{}",
        String::from_utf8_lossy(&tileset.body)
    );
    server.stop().await;
    let _ = std::fs::remove_dir_all(&folder);
}

/// An elevation model larger than a world makes one on the first try: the world takes its
/// middle 20 km, and the answer's notes say which window and how to name another; a crop
/// outside the model is the description's mistake. (An uploaded `.hgt` has no name to say
/// where it lies, so its spacing is given.)
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_model_larger_than_a_world_gives_its_middle() {
    let server = start(options(scratch("large-model"))).await;
    let mut c = Client::connect(server.address).await;
    let hgt = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../terrain/tests/data/dems/N44W072.hgt"
    ))
    .unwrap();
    let upload = c.post("/heightmaps", &hgt).await;
    assert_eq!(upload.status, StatusCode::CREATED);
    let id = upload.json()["id"].as_str().unwrap().to_owned();
    let answer = c
        .post(
            "/worlds",
            format!(r#"{{"terrain": {{"heightmap": {{"id": "{id}", "spacing": 30}}}}, "budget_mb": 4, "species": ["pine"]}}"#).as_bytes(),
        )
        .await;
    assert_eq!(
        answer.status,
        StatusCode::CREATED,
        "{}",
        String::from_utf8_lossy(&answer.body)
    );
    let notes = answer.json()["notes"].to_string();
    assert!(
        notes.contains("took the middle") && notes.contains(r#"\"crop\": [267, 267, 667, 667]"#),
        "{notes}"
    );
    let outside = c
        .post(
            "/worlds",
            format!(r#"{{"terrain": {{"heightmap": {{"id": "{id}", "spacing": 30, "crop": [1190, 0, 30, 30]}}}}}}"#).as_bytes(),
        )
        .await;
    assert_eq!(outside.status, StatusCode::BAD_REQUEST);
    assert_eq!(outside.json()["error"], "bad_description");
    server.stop().await;
}
