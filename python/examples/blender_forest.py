"""The sylva add-on in Blender, headless: a tree and a 200 m forest built through the add-on's
operators (Add > Mesh > sylva tree, sylva forest), their objects and instances counted, and
each rendered with Cycles.

    python blender_forest.py OUT_FOLDER [--size 640x360] [--samples 16]

Needs bpy (PyPI, Python 3.11) and the sylva wheel in the same Python. Prints one JSON line of
figures; fails when the forest's instances are not its placements.
"""

import argparse
import json
import math
import os
import sys
import time

import bpy
import numpy as np

import sylva
import sylva.blender


def cycles(size, samples):
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    width, height = size
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    world = bpy.data.worlds.new("sky")
    if bpy.app.version < (5, 0, 0) and not world.use_nodes:
        world.use_nodes = True
    background = next(n for n in world.node_tree.nodes if n.type == "BACKGROUND")
    background.inputs["Color"].default_value = (0.45, 0.6, 0.85, 1.0)
    background.inputs["Strength"].default_value = 0.8
    scene.world = world
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 4.0
    sun.rotation_euler = (math.radians(40), math.radians(15), math.radians(30))
    scene.collection.objects.link(sun)


def look(at, eye, lens=35.0):
    """A camera at `eye` looking at `at` (Blender's z-up metres)."""
    scene = bpy.context.scene
    camera = bpy.data.objects.new("camera", bpy.data.cameras.new("camera"))
    camera.data.lens = lens
    camera.data.clip_end = 5000.0
    scene.collection.objects.link(camera)
    camera.location = eye
    direction = np.subtract(at, eye)
    pitch = math.atan2(math.hypot(direction[0], direction[1]), -direction[2])
    yaw = math.atan2(direction[1], direction[0]) - math.pi / 2
    camera.rotation_euler = (pitch, 0.0, yaw)
    scene.camera = camera


def render(path):
    bpy.context.scene.render.filepath = path
    start = time.time()
    bpy.ops.render.render(write_still=True)
    return time.time() - start


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("out")
    parser.add_argument("--size", default="640x360")
    parser.add_argument("--samples", type=int, default=16)
    args = parser.parse_args()
    size = tuple(int(v) for v in args.size.split("x"))
    os.makedirs(args.out, exist_ok=True)
    sylva.blender.register()
    figures = {}

    bpy.ops.wm.read_factory_settings(use_empty=True)
    start = time.time()
    assert bpy.ops.mesh.sylva_tree_add(species="oak", seed=1) == {"FINISHED"}
    figures["tree_s"] = round(time.time() - start, 2)
    tree = bpy.context.view_layer.objects.active
    figures["tree_vertices"] = len(tree.data.vertices)
    figures["tree_materials"] = [m.name for m in tree.data.materials]
    cycles(size, args.samples)
    top = max(v.co.z for v in tree.data.vertices)
    look((0.0, 0.0, 0.5 * top), (0.0, -2.6 * top, 0.55 * top), lens=40.0)
    figures["tree_render_s"] = round(render(os.path.join(args.out, "blender_tree.png")), 1)

    bpy.ops.wm.read_factory_settings(use_empty=True)
    start = time.time()
    assert bpy.ops.mesh.sylva_forest_add(area=200.0, seed=1) == {"FINISHED"}
    figures["forest_s"] = round(time.time() - start, 2)
    placements = len(sylva.Forest(area=200.0, seed=1).placements()["position"])
    depsgraph = bpy.context.evaluated_depsgraph_get()
    instances = sum(1 for i in depsgraph.object_instances if i.is_instance)
    figures.update(objects=len(bpy.data.objects), instances=instances, placements=placements)
    cycles(size, args.samples)
    look((100.0, -100.0, 0.0), (100.0, -330.0, 120.0), lens=30.0)
    figures["forest_render_s"] = round(render(os.path.join(args.out, "blender_forest.png")), 1)
    print(json.dumps(figures))
    if instances != placements:
        print(f"the forest has {instances} instances for {placements} placements", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
