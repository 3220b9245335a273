"""Writes the sylva add-on as a zip that Blender installs (Edit > Preferences > Add-ons >
Install from Disk): ``python -m sylva.blender sylva_addon.zip``. The add-on is a small
shim: Blender reads its bl_info, and it loads sylva.blender from the sylva package, which
must be installed into Blender's Python (``python -m pip install sylva-*.whl`` with
Blender's own python)."""

import ast
import inspect
import sys
import zipfile

SHIM = '''"""sylva: procedural trees and forests in Add > Mesh (the sylva package must be installed
into Blender's Python)."""

bl_info = {bl_info}


def register():
    from sylva.blender import register as sylva_register

    sylva_register()


def unregister():
    from sylva.blender import unregister as sylva_unregister

    sylva_unregister()
'''


def bl_info_text():
    """The add-on's bl_info, read from sylva.blender's source without importing bpy."""
    import importlib.util

    spec = importlib.util.find_spec("sylva.blender")
    tree = ast.parse(open(spec.origin, encoding="utf-8").read())
    for node in tree.body:
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "bl_info":
            return ast.unparse(node.value)
    raise RuntimeError("sylva.blender has no bl_info")


def main(argv):
    if len(argv) != 1 or not argv[0].endswith(".zip"):
        print(inspect.cleandoc(__doc__), file=sys.stderr)
        return 2
    with zipfile.ZipFile(argv[0], "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("sylva_addon/__init__.py", SHIM.format(bl_info=bl_info_text()))
    print(f"wrote {argv[0]}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
