"""sylva in Blender: "sylva tree" and "sylva forest" in Add > Mesh.

A tree becomes a mesh object with its species' bark and leaf materials. A forest becomes
its terrain, one hidden prototype object per branch instance, and a point cloud with one
point per placement whose geometry-nodes modifier instances the prototypes on the points
(Instance on Points, picking each point's prototype, with its rotation and scale): 50,000
trees are a few thousand small meshes and instances Blender draws without copying them.

The functions work headless too (``bpy`` from PyPI)::

    import sylva, sylva.blender
    sylva.blender.register()
    bpy.ops.mesh.sylva_forest_add(area=200, seed=1)
    # or, without the operator:
    sylva.blender.forest_object(sylva.Forest(area=200, seed=1))

sylva's coordinates are y-up metres; Blender's are z-up, so (x, y, z) becomes (x, -z, y).
Install the wheel into Blender's Python, then the add-on zip that
``python -m sylva.blender sylva_addon.zip`` writes (Edit > Preferences > Add-ons > Install
from Disk).
"""

import os
import tempfile

import bpy
import numpy as np
from bpy.props import BoolProperty, EnumProperty, FloatProperty, IntProperty, StringProperty

import sylva

bl_info = {
    "name": "sylva",
    "author": "the sylva developers",
    "version": (0, 1, 0),
    "blender": (4, 2, 0),
    "location": "View3D > Add > Mesh > sylva tree, sylva forest",
    "description": "Procedural trees and forests (L-systems, instancing) from the sylva package",
    "category": "Add Mesh",
}

# A rotation of +90 degrees about x takes sylva's y-up frame to Blender's z-up one.
_UP = np.array([np.cos(np.pi / 4), np.sin(np.pi / 4), 0.0, 0.0])  # w, x, y, z

SEASONS = [
    ("summer", "Summer", "Day 200: full leaves"),
    ("spring", "Spring", "Day 135: leaves flushing"),
    ("autumn", "Autumn", "Day 290: autumn colour"),
    ("winter", "Winter", "Day 20: bare deciduous crowns"),
]


def z_up(points):
    """Points (n x 3, y-up) in Blender's z-up frame."""
    points = np.asarray(points, dtype=np.float32)
    return np.stack([points[:, 0], -points[:, 2], points[:, 1]], axis=1)


def _quaternion_product(a, b):
    """Products of quaternions (n x 4, w x y z)."""
    aw, ax, ay, az = (a[..., k] for k in range(4))
    bw, bx, by, bz = (b[..., k] for k in range(4))
    return np.stack(
        [
            aw * bw - ax * bx - ay * by - az * bz,
            aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw,
        ],
        axis=-1,
    )


def z_up_rotations(xyzw):
    """sylva's rotations (n x 4, x y z w, y-up) as Blender's (n x 4, w x y z, z-up)."""
    q = np.asarray(xyzw, dtype=np.float64)[:, [3, 0, 1, 2]]
    inverse = _UP * np.array([1.0, -1.0, -1.0, -1.0])
    return _quaternion_product(_quaternion_product(_UP[None, :], q), inverse[None, :]).astype(
        np.float32
    )


def _image(name, png):
    """A packed Blender image from PNG bytes."""
    with tempfile.TemporaryDirectory() as folder:
        path = os.path.join(folder, name + ".png")
        with open(path, "wb") as f:
            f.write(png)
        image = bpy.data.images.load(path)
        image.pack()
    image.name = name
    return image


def _material(name, colour, png, cutoff=None):
    """A Principled BSDF material: `png`'s colour times `colour` (linear RGB); with
    `cutoff`, a leaf card whose texture's alpha is cut there."""
    material = bpy.data.materials.new(name)
    if bpy.app.version < (5, 0, 0) and not material.use_nodes:
        material.use_nodes = True
    nodes, links = material.node_tree.nodes, material.node_tree.links
    bsdf = next(n for n in nodes if n.type == "BSDF_PRINCIPLED")
    texture = nodes.new("ShaderNodeTexImage")
    texture.image = _image(name, png)
    tint = nodes.new("ShaderNodeVectorMath")
    tint.operation = "MULTIPLY"
    tint.inputs[1].default_value = tuple(colour)
    links.new(texture.outputs["Color"], tint.inputs[0])
    links.new(tint.outputs[0], bsdf.inputs["Base Color"])
    bsdf.inputs["Roughness"].default_value = 0.85 if cutoff is None else 0.6
    if cutoff is not None:
        cut = nodes.new("ShaderNodeMath")
        cut.operation = "GREATER_THAN"
        cut.inputs[1].default_value = cutoff
        links.new(texture.outputs["Alpha"], cut.inputs[0])
        links.new(cut.outputs[0], bsdf.inputs["Alpha"])
        if hasattr(material, "surface_render_method"):
            material.surface_render_method = "DITHERED"
    return material


def species_materials(name, material):
    """The bark and leaf materials of a species, from Tree.material or Forest.materials()."""
    bark = _material(f"{name} bark", material["bark_colour"], material["bark_texture"])
    leaves = _material(
        f"{name} leaves",
        material["leaf_colour"],
        material["leaf_texture"],
        material["alpha_cutoff"],
    )
    return bark, leaves


def _polygon_mesh(name, points, polygons):
    """A Blender mesh of `points` (n x 3, y-up, turned z-up) and `polygons` (m x k vertex
    indices, k corners each)."""
    polygons = np.asarray(polygons, dtype=np.int32)
    count, corners = polygons.shape
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(points))
    mesh.vertices.foreach_set("co", z_up(points).ravel())
    mesh.loops.add(corners * count)
    mesh.loops.foreach_set("vertex_index", polygons.ravel())
    mesh.polygons.add(count)
    mesh.polygons.foreach_set("loop_start", np.arange(0, corners * count, corners, dtype=np.int32))
    return mesh


def mesh_data(name, positions, normals, uvs, bark, leaves, materials):
    """A Blender mesh of sylva's arrays: bark triangles first with material 0, then leaf
    triangles with material 1; positions and normals turned z-up, uvs flipped as glTF's
    importer flips them."""
    triangles = np.concatenate([bark, leaves]).astype(np.int32).reshape(-1, 3)
    mesh = _polygon_mesh(name, positions, triangles)
    kinds = np.concatenate([np.zeros(len(bark), np.int32), np.ones(len(leaves), np.int32)])
    mesh.polygons.foreach_set("material_index", kinds)
    layer = mesh.uv_layers.new(name="UVMap")
    corner_uvs = np.asarray(uvs, dtype=np.float32)[triangles.ravel()]
    corner_uvs[:, 1] = 1.0 - corner_uvs[:, 1]
    layer.data.foreach_set("uv", corner_uvs.ravel())
    for m in materials:
        mesh.materials.append(m)
    mesh.update()
    mesh.validate()
    mesh.shade_smooth()
    mesh.normals_split_custom_set_from_vertices(z_up(normals))
    return mesh


def _link(obj, collection):
    (collection or bpy.context.scene.collection).objects.link(obj)
    return obj


def tree_object(tree, name=None, collection=None):
    """A mesh object of a sylva.Tree with its species' materials, at the origin."""
    name = name or f"sylva {tree.name}"
    bark, leaves = species_materials(tree.name, tree.material)
    mesh = mesh_data(
        name, tree.positions, tree.normals, tree.uvs, tree.bark, tree.leaves, [bark, leaves]
    )
    return _link(bpy.data.objects.new(name, mesh), collection)


def terrain_object(forest, name="sylva terrain", collection=None, most=513):
    """The forest's terrain as a grid mesh (at most `most` vertices a side)."""
    heights = forest.heights
    stride = max(1, int(np.ceil((len(heights) - 1) / (most - 1))))
    h = heights[::stride, ::stride]
    rows, cols = h.shape
    step = forest.spacing * stride
    z, x = np.mgrid[0:rows, 0:cols].astype(np.float32) * step
    points = np.stack([x.ravel(), h.ravel(), z.ravel()], axis=1)
    a = (np.arange(rows - 1)[:, None] * cols + np.arange(cols - 1)[None, :]).ravel()
    quads = np.stack([a, a + cols, a + cols + 1, a + 1], axis=1)
    mesh = _polygon_mesh(name, points, quads)
    mesh.update()
    mesh.validate()
    mesh.shade_smooth()
    ground = bpy.data.materials.new("sylva ground")
    ground.diffuse_color = (0.16, 0.14, 0.07, 1.0)
    if bpy.app.version < (5, 0, 0) and not ground.use_nodes:
        ground.use_nodes = True
    bsdf = next(n for n in ground.node_tree.nodes if n.type == "BSDF_PRINCIPLED")
    bsdf.inputs["Base Color"].default_value = (0.16, 0.14, 0.07, 1.0)
    bsdf.inputs["Roughness"].default_value = 0.95
    mesh.materials.append(ground)
    return _link(bpy.data.objects.new(name, mesh), collection)


def _instancer(prototypes):
    """A geometry-nodes group that instances `prototypes`' children on its points: each
    point's `prototype` (an index into the collection's children, which Collection Info
    sorts by name), `rotation` and `scale`."""
    group = bpy.data.node_groups.new("sylva instances", "GeometryNodeTree")
    group.interface.new_socket("Geometry", in_out="INPUT", socket_type="NodeSocketGeometry")
    group.interface.new_socket("Geometry", in_out="OUTPUT", socket_type="NodeSocketGeometry")
    nodes, links = group.nodes, group.links
    given, result = nodes.new("NodeGroupInput"), nodes.new("NodeGroupOutput")
    info = nodes.new("GeometryNodeCollectionInfo")
    info.inputs["Collection"].default_value = prototypes
    info.inputs["Separate Children"].default_value = True
    info.inputs["Reset Children"].default_value = True
    place = nodes.new("GeometryNodeInstanceOnPoints")
    place.inputs["Pick Instance"].default_value = True

    def attribute(name, kind):
        node = nodes.new("GeometryNodeInputNamedAttribute")
        node.data_type = kind
        node.inputs["Name"].default_value = name
        return node.outputs["Attribute"]

    links.new(given.outputs[0], place.inputs["Points"])
    links.new(info.outputs[0], place.inputs["Instance"])
    links.new(attribute("prototype", "INT"), place.inputs["Instance Index"])
    links.new(attribute("rotation", "QUATERNION"), place.inputs["Rotation"])
    links.new(attribute("scale", "FLOAT"), place.inputs["Scale"])
    links.new(place.outputs["Instances"], result.inputs[0])
    return group


def forest_object(forest, name="sylva forest", collection=None, terrain=True, progress=None):
    """A sylva.Forest as Blender objects: its terrain (unless `terrain` is False), its branch
    instances as hidden prototype objects in a collection of their own, and a point cloud
    named `name` whose geometry-nodes modifier instances them, one point per placement.
    Returns the point cloud's object. `progress(done, total)` hears the prototypes built."""
    scene = bpy.context.scene
    placements = forest.placements()
    pairs = np.stack([placements["variant"], placements["instance"]], axis=1)
    unique, which = np.unique(pairs, axis=0, return_inverse=True)
    variants = forest.variants()
    materials = [
        species_materials(species, m)
        for species, m in zip(forest.species, forest.materials())
    ]
    prototypes = bpy.data.collections.new(f"{name} prototypes")
    scene.collection.children.link(prototypes)
    for k, (variant, instance) in enumerate(unique):
        mesh = forest.instance_mesh(int(variant), int(instance))
        species = variants[int(variant)]["species"]
        label = f"{name} {k:06d}"
        data = mesh_data(
            label, mesh["positions"], mesh["normals"], mesh["uvs"], mesh["bark"],
            mesh["leaves"], materials[species],
        )
        prototypes.objects.link(bpy.data.objects.new(label, data))
        if progress is not None:
            progress(k + 1, len(unique))
    # The prototypes stand at the origin: only their instances are seen.
    layer = bpy.context.view_layer.layer_collection.children[prototypes.name]
    layer.exclude = True
    prototypes.hide_render = True

    points = bpy.data.meshes.new(name)
    points.vertices.add(len(which))
    points.vertices.foreach_set("co", z_up(placements["position"]).ravel())
    index = points.attributes.new("prototype", "INT", "POINT")
    index.data.foreach_set("value", np.asarray(which, dtype=np.int32).ravel())
    rotation = points.attributes.new("rotation", "QUATERNION", "POINT")
    rotation.data.foreach_set("value", z_up_rotations(placements["rotation"]).ravel())
    scale = points.attributes.new("scale", "FLOAT", "POINT")
    scale.data.foreach_set("value", placements["scale"])
    points.update()
    obj = _link(bpy.data.objects.new(name, points), collection)
    modifier = obj.modifiers.new("sylva instances", "NODES")
    modifier.node_group = _instancer(prototypes)
    if terrain:
        terrain_object(forest, f"{name} terrain", collection)
    return obj


def _at_cursor(obj, context):
    obj.location = context.scene.cursor.location
    for o in context.selected_objects:
        o.select_set(False)
    obj.select_set(True)
    context.view_layer.objects.active = obj


class SYLVA_OT_tree_add(bpy.types.Operator):
    """Add one sylva tree of a bundled species"""

    bl_idname = "mesh.sylva_tree_add"
    bl_label = "sylva tree"
    bl_options = {"REGISTER", "UNDO"}

    species: EnumProperty(
        name="Species",
        items=[(n, n.capitalize(), f"The bundled {n}") for n in sylva.species_names()],
        default="oak",
    )
    seed: IntProperty(name="Seed", default=1, min=0)
    generations: IntProperty(
        name="Generations", default=0, min=0, max=20, description="0: the species' own"
    )
    season: EnumProperty(name="Season", items=SEASONS, default="summer")

    def execute(self, context):
        try:
            tree = sylva.tree(
                self.species,
                seed=self.seed,
                generations=self.generations or None,
                season=self.season,
            )
        except sylva.SylvaError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        _at_cursor(tree_object(tree), context)
        return {"FINISHED"}


class SYLVA_OT_forest_add(bpy.types.Operator):
    """Add a sylva forest on its terrain, its trees as geometry-nodes instances"""

    bl_idname = "mesh.sylva_forest_add"
    bl_label = "sylva forest"
    bl_options = {"REGISTER", "UNDO"}

    area: FloatProperty(name="Area", default=200.0, min=10.0, max=2000.0, unit="LENGTH")
    seed: IntProperty(name="Seed", default=1, min=0)
    species: StringProperty(
        name="Species",
        default="",
        description="Bundled species, comma-separated (empty: oak, birch, spruce, pine, hazel)",
    )
    season: EnumProperty(name="Season", items=SEASONS, default="summer")
    terrain: BoolProperty(name="Terrain", default=True)

    def execute(self, context):
        names = [n.strip() for n in self.species.split(",") if n.strip()] or None
        wm = context.window_manager
        wm.progress_begin(0, 100)
        try:
            forest = sylva.Forest(
                area=self.area, seed=self.seed, species=names, season=self.season
            )
            obj = forest_object(
                forest,
                terrain=self.terrain,
                progress=lambda done, total: wm.progress_update(int(100 * done / total)),
            )
        except sylva.SylvaError as e:
            self.report({"ERROR"}, str(e))
            return {"CANCELLED"}
        finally:
            wm.progress_end()
        _at_cursor(obj, context)
        return {"FINISHED"}


def _menu(self, context):
    self.layout.separator()
    self.layout.operator(SYLVA_OT_tree_add.bl_idname, icon="OUTLINER_OB_FORCE_FIELD")
    self.layout.operator(SYLVA_OT_forest_add.bl_idname, icon="OUTLINER_OB_POINTCLOUD")


_CLASSES = (SYLVA_OT_tree_add, SYLVA_OT_forest_add)


def register():
    """Adds the operators and their entries in Add > Mesh."""
    for c in _CLASSES:
        bpy.utils.register_class(c)
    bpy.types.VIEW3D_MT_mesh_add.append(_menu)


def unregister():
    """Removes what register added."""
    bpy.types.VIEW3D_MT_mesh_add.remove(_menu)
    for c in reversed(_CLASSES):
        bpy.utils.unregister_class(c)
