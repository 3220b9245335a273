"""The same seeds give the same arrays as the Rust API: these values are pinned by the Rust
test `what_python_reads_of_an_oak_and_a_world` (tests/pinned_outputs.rs), over the same
bytes; and the same forest is the same file as the `sylva` command writes."""

import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

import sylva


def fnv1a(*arrays):
    """FNV-1a (64 bits) over the arrays' little-endian bytes, one after another."""
    h = 0xCBF29CE484222325
    for a in arrays:
        for b in np.ascontiguousarray(a).astype(a.dtype.newbyteorder("<")).tobytes():
            h = ((h ^ b) * 0x100000001B3) & 0xFFFFFFFFFFFFFFFF
    return h


def test_the_oak_of_seed_1_is_the_rust_apis():
    oak = sylva.tree("oak", seed=1)
    assert oak.vertex_count == 34_386
    assert fnv1a(oak.positions, oak.bark, oak.leaves) == 0xCE840083BDB67140


def test_the_placements_of_a_150_m_world_of_seed_3_are_the_rust_apis():
    p = sylva.Forest(area=150, seed=3).placements()
    assert len(p["position"]) == 10_104
    columns = [p["position"], p["rotation"], p["scale"], p["variant"], p["instance"]]
    assert fnv1a(*columns) == 0x807486D9EB2FA626


def test_any_thread_count_gives_the_same_arrays():
    """Rayon's pool size is read once per process, so each count runs in its own."""
    script = (
        "import sylva, hashlib;"
        "p = sylva.Forest(area=120, seed=5).placements();"
        "print(hashlib.sha256(b''.join(p[k].tobytes() for k in sorted(p))).hexdigest())"
    )
    digests = set()
    for threads in ("1", "2", "3"):
        env = dict(os.environ, RAYON_NUM_THREADS=threads)
        out = subprocess.run(
            [sys.executable, "-c", script], env=env, capture_output=True, text=True, check=True
        )
        digests.add(out.stdout.strip())
    assert len(digests) == 1


@pytest.mark.skipif(not os.environ.get("SYLVA_CLI"), reason="SYLVA_CLI names the sylva command")
def test_a_forest_is_the_file_the_sylva_command_writes(tmp_path):
    cli = os.environ["SYLVA_CLI"]
    subprocess.run(
        [cli, "forest", "--area", "150", "--seed", "3", "-q",
         "--out", str(tmp_path / "cli.glb"), "--heightmap", str(tmp_path / "cli.png")],
        check=True,
    )
    figures = sylva.Forest(area=150, seed=3).write_glb(tmp_path / "py.glb")
    cli_bytes = (tmp_path / "cli.glb").read_bytes()
    assert figures["bytes"] == len(cli_bytes)
    assert (tmp_path / "py.glb").read_bytes() == cli_bytes
