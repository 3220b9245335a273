"""Procedural forests from Python.

sylva derives L-system grammars (sylva's notation, cpfg and L-Py), draws trees as NumPy
arrays with their skeletons, builds forests of many species on generated or real terrain
and writes them as glTF, USD and 3D Tiles, grows stands of trees that compete for light,
and runs forests over time. It is a thin layer over the sylva Rust crates: the same
arguments give the same arrays and the same files as the Rust API and the `sylva` command.

    >>> import sylva
    >>> oak = sylva.tree("oak", seed=1)
    >>> oak.positions.shape[1]
    3
    >>> forest = sylva.Forest(area=100, seed=1)
    >>> placements = forest.placements()
    >>> placements["position"].shape[1]
    3

Long work (a forest, a stand, a succession, tiles) releases the GIL and reports to an
optional ``progress(stage, done, total)`` callback; an exception raised there stops it.
Mistakes raise :class:`SylvaError`, and text with a mistake at a place
:class:`ParseError` with its ``line`` and ``column``.
"""

from ._sylva import (
    Forest,
    Grammar,
    ParseError,
    Stand,
    SylvaError,
    Tree,
    __version__,
    grow_stand,
    presets,
    species_names,
    succession,
    tree,
)

__all__ = [
    "Forest",
    "Grammar",
    "ParseError",
    "Stand",
    "SylvaError",
    "Tree",
    "__version__",
    "grow_stand",
    "presets",
    "species_names",
    "succession",
    "tree",
]
