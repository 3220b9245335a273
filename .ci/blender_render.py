"""What the Blender scripts share: a sun and a sky, and a Cycles render on the CPU."""
import math
import time

import bpy


def render(scene, out, size, samples, sun_angles=(40, 0, 30), sky=0.6):
    """Lights `scene` with a sun (Euler angles in degrees) and a sky of strength `sky`,
    renders it with Cycles at `size` (width, height) to `out`; returns the seconds taken."""
    sun = bpy.data.objects.new("sun", bpy.data.lights.new("sun", "SUN"))
    sun.data.energy = 4.0
    sun.rotation_euler = tuple(math.radians(a) for a in sun_angles)
    scene.collection.objects.link(sun)
    world = bpy.data.worlds.new("sky")
    if world.node_tree is None:
        world.use_nodes = True  # Blender before 5.0 made worlds without nodes
    background = world.node_tree.nodes["Background"]
    background.inputs[0].default_value = (0.55, 0.7, 0.9, 1)
    background.inputs[1].default_value = sky
    scene.world = world
    scene.render.engine = "CYCLES"
    scene.cycles.device = "CPU"
    scene.cycles.samples = samples
    scene.cycles.use_denoising = False
    scene.render.resolution_x, scene.render.resolution_y = size
    scene.render.resolution_percentage = 100
    scene.render.filepath = out
    start = time.time()
    bpy.ops.render.render(write_still=True)
    return round(time.time() - start, 1)
