"""Generates a tiled world on a Dask cluster: one task per tile, each running
`sylva tiles --tile ID` (a pure function of the flags and the id, so any worker on any
machine writes the same bytes), then the root (`--tileset-only`) once the tiles are done.

usage:
  python3 tools/dask_tiles.py --sylva target/release/sylva --out DIR \
      [--workers N | --scheduler ADDRESS] -- --area 11000 --tile-size 500 [other tiles flags]

Without --scheduler it starts a local cluster of N single-threaded worker processes (on a
real cluster, start `dask scheduler` and `dask worker` processes and pass the scheduler's
address; every worker needs the sylva binary at the same path and DIR on a shared disk).
Prints one JSON object: tiles, wall time, and per worker the tiles it wrote, the seconds
it spent and the peak memory of its tile processes.
"""

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import time


def tile_ids(area, tile, group=4):
    """The ids sylva's TileScheme gives: coarse tiles, then fine ones."""
    n = -(-area // tile)  # ceil
    c = -(-n // group)
    ids = [f"c_{x}_{y}" for y in range(c) for x in range(c)]
    ids += [f"f_{x}_{y}" for y in range(n) for x in range(n)]
    return ids


def write_tile(sylva, out, flags, tile):
    """Runs one tile job; returns (tile, seconds, worker, peak child memory in MB, trees)."""
    start = time.monotonic()
    done = subprocess.run([sylva, "tiles", *flags, "--out", out, "--tile", tile], check=True,
                          stdout=subprocess.PIPE, text=True)
    seconds = time.monotonic() - start
    # ru_maxrss of the children of this worker process: its largest tile job so far (KiB).
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024
    # The job reports "wrote PATH (N trees, ...)".
    found = re.search(r"\((\d+) trees", done.stdout)
    return tile, seconds, os.getpid(), peak, int(found.group(1)) if found else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--sylva", required=True, help="the sylva command's binary")
    parser.add_argument("--out", required=True, help="the tile folder")
    parser.add_argument("--workers", type=int, default=os.cpu_count() or 1)
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    parser.add_argument("flags", nargs=argparse.REMAINDER,
                        help="after --: sylva tiles' flags (--area and --tile-size needed)")
    args = parser.parse_args()
    flags = [f for f in args.flags if f != "--"]
    try:
        area = float(flags[flags.index("--area") + 1])
        tile = float(flags[flags.index("--tile-size") + 1])
    except (ValueError, IndexError):
        sys.exit("give the tiles flags --area METRES and --tile-size METRES after --")

    from dask.distributed import Client, LocalCluster

    cluster = None
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True,
                               dashboard_address=None)
        client = Client(cluster)
    ids = tile_ids(int(area), int(tile))
    start = time.monotonic()
    futures = client.map(write_tile, [args.sylva] * len(ids), [args.out] * len(ids),
                         [flags] * len(ids), ids, pure=False)
    results = client.gather(futures)
    # The last step: the root and the shared geometry, once every tile is written.
    subprocess.run([args.sylva, "tiles", *flags, "--out", args.out, "--tileset-only"], check=True,
                   stdout=subprocess.DEVNULL)
    wall = time.monotonic() - start
    workers = {}
    trees = sum(n for tile, _, _, _, n in results if tile.startswith("f_"))
    for _, seconds, pid, peak, _ in results:
        w = workers.setdefault(pid, {"tiles": 0, "seconds": 0.0, "peak_mb": 0.0})
        w["tiles"] += 1
        w["seconds"] += seconds
        w["peak_mb"] = max(w["peak_mb"], peak)
    print(json.dumps({
        "tiles": len(ids),
        "trees": trees,
        "workers": len(workers),
        "wall_s": round(wall, 2),
        "per_worker": [{k: round(v, 2) if isinstance(v, float) else v for k, v in w.items()}
                       for w in workers.values()],
    }))
    client.close()
    if cluster:
        cluster.close()


if __name__ == "__main__":
    main()
