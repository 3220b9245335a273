#!/usr/bin/env python3
"""Checks a sylva USD forest with Pixar's own code (PyPI usd-core).

Runs every validator that `usdchecker` runs (USD's validation framework: stage metadata,
material bindings, shader and texture rules, encapsulation, missing references), then reads
the point instancer back as a client would and checks what it holds.

usage: check.py FILE.usda [PLACEMENTS]
  PLACEMENTS: the instance count the file must hold (`sylva forest --stats` prints it).
Prints one line of figures; exits 1 on any validation error or wrong count.
"""
import sys
import time

from pxr import Sdf, Usd, UsdGeom, UsdShade, UsdValidation


def main():
    path = sys.argv[1]
    expected = int(sys.argv[2]) if len(sys.argv) > 2 else None
    start = time.time()
    stage = Usd.Stage.Open(path)
    opened = time.time() - start
    failures = []

    validators = UsdValidation.ValidationRegistry().GetOrLoadAllValidators()
    errors = UsdValidation.ValidationContext(validators).Validate(stage)
    for e in errors:
        failures.append(f"{e.GetName()}: {e.GetMessage()}")

    if stage.GetDefaultPrim().GetPath() != Sdf.Path("/Forest"):
        failures.append("defaultPrim is not /Forest")
    if UsdGeom.GetStageUpAxis(stage) != UsdGeom.Tokens.y:
        failures.append("upAxis is not Y")
    if UsdGeom.GetStageMetersPerUnit(stage) != 1.0:
        failures.append("metersPerUnit is not 1")

    instancer = UsdGeom.PointInstancer(stage.GetPrimAtPath("/Forest/Trees"))
    if not instancer:
        failures.append("no point instancer at /Forest/Trees")
        report(failures, {})
    prototypes = instancer.GetPrototypesRel().GetTargets()
    ids = instancer.GetProtoIndicesAttr().Get()
    positions = instancer.GetPositionsAttr().Get()
    orientations = instancer.GetOrientationsAttr().Get()
    scales = instancer.GetScalesAttr().Get()
    count = len(ids)
    for name, array in (("positions", positions), ("orientations", orientations), ("scales", scales)):
        if len(array) != count:
            failures.append(f"{len(array)} {name} for {count} protoIndices")
    if count and (min(ids) < 0 or max(ids) >= len(prototypes)):
        failures.append(f"protoIndices outside the {len(prototypes)} prototypes")
    if expected is not None and count != expected:
        failures.append(f"{count} instances, expected {expected}")
    used = set(ids)
    if len(used) != len(prototypes):
        failures.append(f"{len(prototypes) - len(used)} prototypes never placed")

    # Every prototype is meshes, each bound to a preview surface whose textures exist.
    meshes = 0
    triangles = 0
    for target in prototypes:
        prim = stage.GetPrimAtPath(target)
        if not prim:
            failures.append(f"prototype {target} missing")
            continue
        for p in Usd.PrimRange(prim):
            if not p.IsA(UsdGeom.Mesh):
                continue
            mesh = UsdGeom.Mesh(p)
            counts = mesh.GetFaceVertexCountsAttr().Get()
            triangles += len(counts)
            meshes += 1
            material, _ = UsdShade.MaterialBindingAPI(p).ComputeBoundMaterial()
            if not material:
                failures.append(f"{p.GetPath()} has no material")
    textures = 0
    for p in stage.Traverse():
        shader = UsdShade.Shader(p)
        if shader and shader.GetIdAttr().Get() == "UsdUVTexture":
            asset = shader.GetInput("file").Get()
            if not asset or not asset.resolvedPath:
                failures.append(f"{p.GetPath()}: texture {asset} does not resolve")
            textures += 1
    bounds = UsdGeom.Boundable(instancer.GetPrim()).GetExtentAttr().Get()
    figures = {
        "open_s": round(opened, 2),
        "instances": count,
        "prototypes": len(prototypes),
        "meshes": meshes,
        "prototype_triangles": triangles,
        "textures": textures,
        "extent": [list(bounds[0]), list(bounds[1])] if bounds else None,
        "validators": len(validators),
        "errors": len(errors),
    }
    report(failures, figures)


def report(failures, figures):
    print(" ".join(f"{k}={v}" for k, v in figures.items()))
    for f in failures[:20]:
        print("FAIL:", f, file=sys.stderr)
    if failures:
        print(f"{len(failures)} failures", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    main()
