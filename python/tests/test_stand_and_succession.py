"""A grown stand and a forest over time."""

import numpy as np
import pytest

import sylva


def test_a_stand_grows_each_tree_and_writes_it(tmp_path):
    positions = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]])
    stand = sylva.grow_stand(positions, species="birch", seed=2, generations=5, voxel=0.2)
    trees = stand.trees()
    assert len(trees) == 3
    assert all(t.triangle_count > 0 and t.name == "birch" for t in trees)
    # Each tree stands where it was planted.
    for t, (x, z) in zip(trees, positions):
        root = t.skeleton["starts"][0]
        assert abs(root[0] - x) < 0.5 and abs(root[2] - z) < 0.5
    assert stand.stats["segments"] > 0
    assert stand.write_glb(tmp_path / "stand.glb") > 0
    with pytest.raises(sylva.SylvaError, match="n x 2"):
        sylva.grow_stand(np.zeros((3, 3)))
    with pytest.raises(sylva.SylvaError, match="one for each"):
        sylva.grow_stand(positions, species=["oak", "birch"])


def test_a_stand_grows_on_terrain_given():
    z, x = np.mgrid[0:65, 0:65].astype(np.float32)
    slope = 0.2 * x  # rising 20 cm a metre eastward
    stand = sylva.grow_stand(
        [[20.0, 30.0], [40.0, 30.0]], species="birch", generations=4, voxel=0.2,
        terrain=slope, spacing=1.0,
    )
    roots = [t.skeleton["starts"][0] for t in stand.trees()]
    # Each tree stands on the slope where it was planted.
    assert abs(roots[0][1] - 4.0) < 0.5 and abs(roots[1][1] - 8.0) < 0.5
    with pytest.raises(sylva.SylvaError, match="spacing"):
        sylva.grow_stand([[1.0, 1.0]], terrain=slope)


def test_a_succession_gives_its_yearly_table():
    heard = []
    table = sylva.succession(area=100, years=12, seed=4, progress=lambda *a: heard.append(a))
    assert len(heard) == 12 and heard[-1] == ("years", 12, 12)
    years = table["year"]
    assert years.dtype == np.float64
    assert list(years) == list(range(len(years)))
    assert len(table["events"]) == len(years)
    for name in ("stems_per_ha", "basal_area_m2_per_ha", "canopy_cover", "oak_stems_per_ha"):
        assert len(table[name]) == len(years), name
    assert np.all(table["canopy_cover"] >= 0) and np.all(table["canopy_cover"] <= 1)
    again = sylva.succession(area=100, years=12, seed=4)
    assert np.array_equal(table["stems_per_ha"], again["stems_per_ha"])
    with pytest.raises(sylva.SylvaError, match="years"):
        sylva.succession(years=0)
