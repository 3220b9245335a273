"""The Blender add-on through PyPI's bpy (skipped where bpy is not installed): its operators
build a tree as a mesh with its materials and a forest as instances of its prototypes, one
per placement; its zip installs as a legacy add-on."""

import ast
import subprocess
import sys
import zipfile

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")

import sylva  # noqa: E402
import sylva.blender  # noqa: E402


@pytest.fixture(scope="module", autouse=True)
def addon():
    sylva.blender.register()
    yield
    sylva.blender.unregister()


def test_a_tree_is_a_mesh_with_bark_and_leaf_materials():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    assert bpy.ops.mesh.sylva_tree_add(species="birch", seed=2) == {"FINISHED"}
    obj = bpy.context.view_layer.objects.active
    tree = sylva.tree("birch", seed=2)
    assert len(obj.data.vertices) == tree.vertex_count
    assert len(obj.data.polygons) == tree.triangle_count
    assert [m.name for m in obj.data.materials] == ["birch bark", "birch leaves"]
    # z-up: the tree stands on its root and rises along +z.
    zs = np.array([v.co.z for v in obj.data.vertices])
    assert zs.min() > -1.0 and zs.max() == pytest.approx(tree.positions[:, 1].max(), rel=1e-5)


def test_a_forest_is_one_instance_a_placement():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    assert bpy.ops.mesh.sylva_forest_add(area=80.0, seed=3, species="oak, spruce") == {"FINISHED"}
    forest = sylva.Forest(area=80.0, seed=3, species=["oak", "spruce"])
    placements = forest.placements()
    depsgraph = bpy.context.evaluated_depsgraph_get()
    # An instance is only valid while the depsgraph iterates.
    where = np.array(
        [tuple(i.matrix_world.translation) for i in depsgraph.object_instances if i.is_instance]
    )
    assert len(where) == len(placements["position"])
    # Each instance stands where its placement does (z-up).
    expected = sylva.blender.z_up(placements["position"])
    assert np.allclose(np.sort(where, axis=0), np.sort(expected, axis=0), atol=1e-3)
    unique = len({(v, i) for v, i in zip(placements["variant"], placements["instance"])})
    prototypes = bpy.data.collections["sylva forest prototypes"]
    assert len(prototypes.objects) == unique
    assert "sylva forest terrain" in bpy.data.objects


def test_a_bad_setting_is_reported_not_raised():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    with pytest.raises(RuntimeError, match="unknown species"):
        bpy.ops.mesh.sylva_forest_add(area=50.0, species="baobab")


def test_the_rotations_turn_with_the_frame():
    # A quarter turn about sylva's y (up) is a quarter turn about Blender's z.
    q = np.array([[0.0, np.sin(np.pi / 4), 0.0, np.cos(np.pi / 4)]])
    assert np.allclose(sylva.blender.z_up_rotations(q), [[np.cos(np.pi / 4), 0, 0, np.sin(np.pi / 4)]], atol=1e-6)


def test_the_addon_zip_carries_bl_info(tmp_path):
    out = tmp_path / "sylva_addon.zip"
    subprocess.run([sys.executable, "-m", "sylva.blender", str(out)], check=True)
    with zipfile.ZipFile(out) as z:
        source = z.read("sylva_addon/__init__.py").decode()
    info = next(
        ast.literal_eval(n.value)
        for n in ast.parse(source).body
        if isinstance(n, ast.Assign) and n.targets[0].id == "bl_info"
    )
    assert info["category"] == "Add Mesh" and info["blender"] >= (4, 2, 0)
