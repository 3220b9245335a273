"""One tree as arrays: shapes, types, indices, the skeleton, seasons and files."""

import numpy as np
import pytest

import sylva


@pytest.fixture(scope="module")
def oak():
    return sylva.tree("oak", seed=1)


def test_the_arrays_have_their_shapes_and_types(oak):
    n = oak.vertex_count
    for name, width in (("positions", 3), ("normals", 3), ("uvs", 2), ("wind", 4)):
        a = getattr(oak, name)
        assert a.shape == (n, width) and a.dtype == np.float32, name
    assert oak.bark.dtype == np.uint32 and oak.bark.shape[1] == 3
    assert len(oak.bark) + len(oak.leaves) == oak.triangle_count
    assert oak.bark.max() < n and oak.leaves.max() < n
    assert np.allclose(np.linalg.norm(oak.normals, axis=1), 1.0, atol=1e-3)
    # The root at the origin, the crown above it.
    assert oak.positions[:, 1].min() > -1.0 and oak.positions[:, 1].max() > 5.0


def test_the_skeleton_is_a_tree_of_bones(oak):
    s = oak.skeleton
    k = len(s["parents"])
    assert s["starts"].shape == (k, 3) and s["radii"].shape == (k, 2)
    assert s["parents"][0] == -1
    # Every other bone grows from an earlier one.
    assert np.all(s["parents"][1:] >= 0)
    assert np.all(s["parents"][1:] < np.arange(1, k))
    assert np.all(s["radii"] > 0)


def test_the_same_seed_gives_the_same_tree_and_another_seed_another():
    a, b = sylva.tree("birch", seed=4), sylva.tree("birch", seed=4)
    assert np.array_equal(a.positions, b.positions)
    assert not np.array_equal(a.positions, sylva.tree("birch", seed=5).positions)


def test_winter_takes_a_deciduous_trees_leaves():
    summer = sylva.tree("oak", seed=1, season="summer")
    winter = sylva.tree("oak", seed=1, season=20)
    assert len(winter.leaves) < len(summer.leaves) / 4
    # The same bark, its vertices numbered apart from the leaves'.
    assert np.array_equal(winter.positions[winter.bark], summer.positions[summer.bark])
    with pytest.raises(sylva.SylvaError, match="season"):
        sylva.tree("oak", season="monsoon")


def test_a_grammars_tree(tmp_path):
    g = sylva.Grammar.preset("abop-1.24a")
    t = sylva.tree(grammar=g, generations=3)
    assert t.name == "tree" and t.triangle_count > 100
    with pytest.raises(sylva.SylvaError, match="not both"):
        sylva.tree("oak", grammar=g)


def test_files(oak, tmp_path):
    size = oak.write_glb(tmp_path / "oak.glb")
    data = (tmp_path / "oak.glb").read_bytes()
    assert size == len(data) and data[:4] == b"glTF"
    assert oak.write_obj(tmp_path / "oak.obj") > 0
    assert (tmp_path / "oak.obj").read_text().startswith(("#", "v ", "o ", "mtllib"))


def test_unknown_species_and_species_file_mistakes(tmp_path):
    with pytest.raises(sylva.SylvaError):
        sylva.tree("baobab")
    bad = tmp_path / "bad.species"
    bad.write_text("name: bad\ngrammar: sylva-oak\ngenerations: many\n")
    with pytest.raises(sylva.ParseError) as caught:
        sylva.tree(str(bad))
    assert caught.value.line == 3
