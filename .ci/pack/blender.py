#!/usr/bin/env python3
"""Opens every tree of a sylva asset pack in Blender (PyPI bpy: Blender as a Python module),
counts the levels of detail its glTF importer made of each (objects NAME_LOD0 .. NAME_LODn
under NAME, as pack.json lists them), and renders one tree's levels side by side with Cycles.

usage: blender.py PACK_DIR OUT.png [--tree NAME] [--size WxH] [--samples N]
Prints one JSON line of figures; exits 1 when a tree's levels are not those pack.json names.
"""
import json
import math
import os
import re
import sys
import time

import bpy
import mathutils

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from blender_render import render  # noqa: E402


def arguments():
    args = sys.argv[1:]
    options = {"size": "960x300", "samples": "16", "tree": "oak_canopy"}
    rest = []
    while args:
        a = args.pop(0)
        if a.startswith("--"):
            options[a[2:]] = args.pop(0)
        else:
            rest.append(a)
    w, h = (int(v) for v in options["size"].split("x"))
    return rest[0], rest[1], options["tree"], (w, h), int(options["samples"])


def import_levels(path):
    """Imports one GLB into an empty scene; returns {level: object} of its LOD children and
    their parent's name."""
    bpy.ops.wm.read_factory_settings(use_empty=True)
    result = bpy.ops.import_scene.gltf(filepath=path)
    if "FINISHED" not in result:
        sys.exit(f"the glTF importer returned {result} for {path}")
    levels = {}
    parents = set()
    for o in bpy.data.objects:
        m = re.fullmatch(r"(.+)_LOD(\d+)", o.name)
        if m and o.type == "MESH":
            levels[int(m.group(2))] = o
            parents.add(o.parent.name if o.parent else None)
    return levels, parents


def triangles(o):
    mesh = o.data
    mesh.calc_loop_triangles()
    return len(mesh.loop_triangles)


def main():
    folder, out, shown, (width, height), samples = arguments()
    pack = json.load(open(os.path.join(folder, "pack.json")))
    figures = {"trees": 0, "levels": 0, "import_s": 0.0, "problems": 0}
    for variant in pack["variants"]:
        start = time.time()
        levels, parents = import_levels(os.path.join(folder, variant["file"]))
        figures["import_s"] += time.time() - start
        expected = [l["node"] for l in variant["levels"]]
        if "impostor" in variant:
            expected.append(variant["impostor"]["node"])
        names = [levels[k].name for k in sorted(levels)]
        counts = [triangles(levels[k]) for k in sorted(levels)]
        figures["trees"] += 1
        figures["levels"] += len(levels)
        print(f"{variant['name']}: {len(levels)} levels under {sorted(p or '' for p in parents)}, triangles {counts}")
        if names != expected or parents != {variant["name"]}:
            print(f"  expected {expected} under {variant['name']}", file=sys.stderr)
            figures["problems"] += 1
        # Each mesh level is coarser than the one before.
        meshes = counts[: len(variant["levels"])]
        if any(b >= a for a, b in zip(meshes, meshes[1:])):
            print(f"  levels do not get coarser: {counts}", file=sys.stderr)
            figures["problems"] += 1
    figures["import_s"] = round(figures["import_s"], 1)

    # One tree's levels side by side, each moved along x by its width, seen from the side.
    levels, _ = import_levels(os.path.join(folder, f"{shown}.glb"))
    scene = bpy.context.scene
    depsgraph = bpy.context.evaluated_depsgraph_get()
    width_of = 0.0
    height_of = 0.0
    for o in levels.values():
        xs = [(o.matrix_world @ mathutils.Vector(c)) for c in o.bound_box]
        width_of = max(width_of, max(p.x for p in xs) - min(p.x for p in xs))
        height_of = max(height_of, max(p.z for p in xs))
    step = width_of * 1.1
    for k, o in levels.items():
        o.parent = None
        o.location.x = (k - (len(levels) - 1) / 2) * step
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    camera.data.type = "ORTHO"
    camera.data.ortho_scale = max(step * len(levels), height_of * width / height) * 1.05
    camera.location = (0, -10 * step, height_of / 2)
    camera.rotation_euler = (math.radians(90), 0, 0)
    camera.data.clip_end = 100 * step
    scene.camera = camera
    figures["render_s"] = render(scene, out, (width, height), samples, (50, 0, -30), 0.8)
    print(json.dumps(figures))
    if figures["problems"]:
        sys.exit(f"{figures['problems']} trees whose levels are not what pack.json says")


if __name__ == "__main__":
    main()
