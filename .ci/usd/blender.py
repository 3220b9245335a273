#!/usr/bin/env python3
"""Opens a sylva USD forest in Blender (PyPI bpy: Blender as a Python module), counts what
its importer made of the point instancer, and renders it with Cycles on the CPU.

usage: blender.py FILE.usda OUT.png [PLACEMENTS] [--size WxH] [--samples N] [--eye F]
  --eye F: the camera's distance from the forest's centre, as a share of its side (0.55)
Prints one line of figures; exits 1 when the instance count is not PLACEMENTS or nothing was
instanced.
"""
import math
import os
import sys
import time

import bpy
import mathutils

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from blender_render import render  # noqa: E402


def arguments():
    args = sys.argv[1:]
    options = {"size": "640x360", "samples": "16", "eye": "0.55"}
    rest = []
    while args:
        a = args.pop(0)
        if a.startswith("--"):
            options[a[2:]] = args.pop(0)
        else:
            rest.append(a)
    path, out = rest[0], rest[1]
    expected = int(rest[2]) if len(rest) > 2 else None
    w, h = (int(v) for v in options["size"].split("x"))
    return path, out, expected, (w, h), int(options["samples"]), float(options["eye"])


def main():
    path, out, expected, (width, height), samples, distance = arguments()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    start = time.time()
    result = bpy.ops.wm.usd_import(filepath=path)
    imported = time.time() - start
    if "FINISHED" not in result:
        sys.exit(f"the USD importer returned {result}")

    # Blender makes the point instancer a point cloud whose geometry-nodes modifier instances
    # a collection per prototype on its points: count the instances that evaluates to.
    depsgraph = bpy.context.evaluated_depsgraph_get()
    start = time.time()
    instancers = [o for o in bpy.data.objects if o.type == "POINTCLOUD" and o.modifiers]
    instances = 0
    prototypes = set()
    for o in instancers:
        geometry = o.evaluated_get(depsgraph).evaluated_geometry()
        points = geometry.instances_pointcloud()
        instances += len(points.points) if points else 0
        prototypes.update(r.name for r in geometry.instance_references())
    # The scene's extent, for the camera: every evaluated object's world bounds.
    lo = mathutils.Vector((math.inf,) * 3)
    hi = mathutils.Vector((-math.inf,) * 3)
    for o in bpy.data.objects:
        if o.type in ("MESH", "POINTCLOUD"):
            for corner in o.evaluated_get(depsgraph).bound_box:
                p = o.matrix_world @ mathutils.Vector(corner)
                lo = mathutils.Vector(map(min, lo, p))
                hi = mathutils.Vector(map(max, hi, p))
    counted = time.time() - start
    figures = {
        "import_s": round(imported, 1),
        "count_s": round(counted, 1),
        "objects": len(bpy.data.objects),
        "instancers": len(instancers),
        "instances": instances,
        "prototypes": len(prototypes),
    }

    # A camera over one corner looking across the forest, a sun, a sky.
    scene = bpy.context.scene
    centre = (lo + hi) / 2
    span = max(hi.x - lo.x, hi.y - lo.y, 1.0)
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    scene.collection.objects.link(camera)
    eye = centre + distance * span * mathutils.Vector((-1.0, -1.0, 0.64))
    camera.location = eye
    camera.rotation_euler = (centre - eye).to_track_quat("-Z", "Y").to_euler()
    camera.data.lens = 28
    camera.data.clip_end = 10 * span
    scene.camera = camera
    figures["render_s"] = render(scene, out, (width, height), samples)
    print(" ".join(f"{k}={v}" for k, v in figures.items()))
    if instances == 0:
        sys.exit("the forest imported with no instances")
    if expected is not None and instances != expected:
        sys.exit(f"{instances} instances, expected {expected}")


if __name__ == "__main__":
    main()
