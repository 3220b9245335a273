#!/usr/bin/env python3
"""Finds import circles between the modules of each crate.

A module uses another when its code (tests left out) names it by a `crate::` or `super::`
path. Two sibling modules are in a circle when each reaches the other through such uses, at
any depth (`lsys::engine::block` and `lsys::engine::compile`, or `viewer::scene` and
`viewer::cells`). A child using its parent's items is not a circle: that is how Rust
modules share a parent's private items.

usage: tools/import_cycles.py CRATE_SRC_DIR...   (exit status 1 when any circle is found)
"""
import os
import re
import sys

CRATE_PATH = re.compile(r"crate::((?:[a-z_0-9]+::)*[a-z_0-9]+)")
SUPER_PATH = re.compile(r"(?<![a-z_:])((?:super::)+(?:[a-z_0-9]+::)*[a-z_0-9]+)")


def modules(src):
    """Every module of the crate at `src`, by path, with its code before any test module."""
    found = {}
    for folder, _, files in os.walk(src):
        for name in files:
            if not name.endswith(".rs"):
                continue
            path = os.path.join(folder, name)
            parts = os.path.relpath(path, src)[:-3].split(os.sep)
            if parts[-1] in ("mod", "lib", "main"):
                parts = parts[:-1]
            with open(path, encoding="utf-8") as f:
                found[tuple(parts)] = f.read().split("#[cfg(test)]")[0]
    return found


def longest_module(mods, segments):
    for n in range(len(segments), 0, -1):
        if tuple(segments[:n]) in mods:
            return tuple(segments[:n])
    return None


def uses(mods):
    """(user, used) module pairs."""
    edges = set()
    for module, code in mods.items():
        targets = [longest_module(mods, p.split("::")) for p in CRATE_PATH.findall(code)]
        for path in SUPER_PATH.findall(code):
            segments, base = path.split("::"), list(module)
            while segments and segments[0] == "super":
                base, segments = base[:-1], segments[1:]
            targets.append(longest_module(mods, base + segments))
        edges.update((module, t) for t in targets if t and t != module)
    return edges


def circles(edges):
    """Pairs of sibling modules that reach each other."""
    siblings = {}
    for a, b in edges:
        i = 0
        while i < min(len(a), len(b)) and a[i] == b[i]:
            i += 1
        if i < len(a) and i < len(b):
            siblings.setdefault(a[: i + 1], set()).add(b[: i + 1])

    def reaches(start, goal):
        seen, todo = set(), [start]
        while todo:
            for n in siblings.get(todo.pop(), ()):
                if n == goal:
                    return True
                if n not in seen:
                    seen.add(n)
                    todo.append(n)
        return False

    return sorted(
        {tuple(sorted(("::".join(a), "::".join(b)))) for a in siblings for b in siblings[a] if reaches(b, a)}
    )


def main(dirs):
    found = False
    for src in dirs:
        for a, b in circles(uses(modules(src))):
            print(f"{src}: {a} and {b} use each other")
            found = True
    if not found:
        print(f"no import circles in {len(dirs)} crates")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
