//! `sylva serve`: worlds on demand over HTTP (the `sylva-server` crate), until Ctrl-C.

use std::net::{IpAddr, Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::time::Duration;

use clap::Args;
use sylva_server::ServerOptions;

use crate::Failure;

/// `sylva serve`'s flags.
#[derive(Debug, Args)]
#[command(
    after_help = "Endpoints: POST /worlds (a world description, JSON) answers its id; \
    GET /worlds/ID/tileset.json, /shared.bin and /tiles/TILE.glb are its 3D Tiles, generated on \
    first request and kept in the cache folder; POST /heightmaps takes a 16-bit PNG; \
    GET /trees/SPECIES.glb?seed=S&age=A is one tree; GET / opens a world in the browser. \
    Several servers may share one cache folder."
)]
pub(crate) struct ServeArgs {
    /// The port to listen on (0: any free one, printed at start).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// The address to listen on (loopback by default; 0.0.0.0 for every interface).
    #[arg(long, value_name = "IP", default_value_t = IpAddr::V4(Ipv4Addr::LOCALHOST))]
    bind: IpAddr,
    /// The cache folder: kept worlds, uploads and every generated file.
    #[arg(long, value_name = "DIR", default_value = "sylva-cache")]
    cache: PathBuf,
    /// Generations at once (default: the machine's cores).
    #[arg(long, value_name = "N")]
    workers: Option<usize>,
    /// Generations queued beyond which requests get 503 with Retry-After.
    #[arg(long, value_name = "N", default_value_t = 256)]
    max_queued: usize,
    /// Seconds a request waits for its generation before a 503 asking it to retry (the
    /// generation goes on and is kept).
    #[arg(long, value_name = "S", default_value_t = 120)]
    generation_timeout: u64,
    /// Requests in progress beyond which new ones get 503.
    #[arg(long, value_name = "N", default_value_t = 4096)]
    max_requests: usize,
    /// Connections open at once beyond which a new one is answered 503 with Retry-After and
    /// closed.
    #[arg(long, value_name = "N", default_value_t = 512)]
    max_connections: usize,
    /// Seconds a client may take to send a request's head before its connection is closed.
    #[arg(long, value_name = "S", default_value_t = 10)]
    header_timeout: u64,
    /// Worlds held built in memory (each about its instance-cache budget and terrain).
    #[arg(long, value_name = "N", default_value_t = 4)]
    worlds_in_memory: usize,
    /// A folder holding the npm packages three and 3d-tiles-renderer (a node_modules), which
    /// the browser page imports.
    #[arg(long, value_name = "DIR")]
    web_modules: Option<PathBuf>,
}

pub(crate) fn run(args: ServeArgs) -> Result<(), Failure> {
    if args.workers == Some(0)
        || args.max_queued == 0
        || args.max_requests == 0
        || args.max_connections == 0
    {
        return Err(Failure::usage(
            "--workers, --max-queued, --max-requests and --max-connections must be positive",
        ));
    }
    if args.header_timeout == 0 || args.header_timeout > 600 {
        return Err(Failure::usage(
            "--header-timeout: expected 1 to 600 seconds",
        ));
    }
    if args.generation_timeout == 0 || args.generation_timeout > 3600 {
        return Err(Failure::usage(
            "--generation-timeout: expected 1 to 3600 seconds",
        ));
    }
    let defaults = ServerOptions::default();
    let options = ServerOptions {
        address: SocketAddr::new(args.bind, args.port),
        cache: args.cache,
        workers: args.workers.unwrap_or(defaults.workers),
        max_queued: args.max_queued,
        generation_timeout: Duration::from_secs(args.generation_timeout),
        max_requests: args.max_requests,
        max_connections: args.max_connections,
        header_timeout: Duration::from_secs(args.header_timeout),
        worlds_in_memory: args.worlds_in_memory.max(1),
        web_modules: args.web_modules,
        ..defaults
    };
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| Failure::job(format!("starting the server: {e}")))?;
    runtime.block_on(async move {
        let listener = tokio::net::TcpListener::bind(options.address)
            .await
            .map_err(|e| Failure::job(format!("listening on {}: {e}", options.address)))?;
        let address = listener
            .local_addr()
            .map_err(|e| Failure::job(e.to_string()))?;
        // The first line says where: a script starting the server on port 0 reads it.
        println!(
            "sylva serve: listening on http://{address}/ (cache {})",
            options.cache.display()
        );
        let shutdown = async {
            let _ = tokio::signal::ctrl_c().await;
        };
        sylva_server::serve(listener, options, shutdown)
            .await
            .map_err(|e| Failure::job(e.message))
    })
}
