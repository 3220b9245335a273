"""Type stubs of sylva's native module (the names the package re-exports)."""

import os
from typing import Callable, Dict, List, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

Progress = Callable[[str, int, int], object]
"""``progress(stage, done, total)``: told as long work goes; raising stops the work."""

Season = Union[int, float, str]
"""A day of the year, 1 to 365, or "spring", "summer", "autumn" or "winter"."""

PathLike = Union[str, "os.PathLike[str]"]
Region = Tuple[Tuple[float, float], Tuple[float, float]]

class SylvaError(Exception):
    """Anything sylva refuses; the message says what and how to put it right."""

class ParseError(SylvaError):
    """A grammar or species file with a mistake at a place."""

    line: int
    column: int
    path: Optional[str]
    reason: str

class Skeleton(TypedDict):
    starts: npt.NDArray[np.float32]
    ends: npt.NDArray[np.float32]
    radii: npt.NDArray[np.float32]
    parents: npt.NDArray[np.int64]

class InstanceMesh(TypedDict):
    positions: npt.NDArray[np.float32]
    normals: npt.NDArray[np.float32]
    uvs: npt.NDArray[np.float32]
    bark: npt.NDArray[np.uint32]
    leaves: npt.NDArray[np.uint32]

class Trees(TypedDict):
    position: npt.NDArray[np.float32]
    yaw: npt.NDArray[np.float32]
    scale: npt.NDArray[np.float32]
    variant: npt.NDArray[np.uint16]
    species: npt.NDArray[np.uint16]
    seed: npt.NDArray[np.uint32]

class Placements(TypedDict):
    position: npt.NDArray[np.float32]
    rotation: npt.NDArray[np.float32]
    scale: npt.NDArray[np.float32]
    variant: npt.NDArray[np.uint32]
    instance: npt.NDArray[np.uint32]
    tree: npt.NDArray[np.uint32]

class Variant(TypedDict):
    species: int
    seedling: bool
    generations: int
    form: str
    instances: int

class Material(TypedDict):
    bark_colour: Tuple[float, float, float]
    leaf_colour: Tuple[float, float, float]
    bark_texture: bytes
    leaf_texture: bytes
    alpha_cutoff: float

class Grammar:
    """An L-system grammar, ready to derive."""

    def __init__(self, text: str, *, dialect: Optional[str] = None) -> None: ...
    @staticmethod
    def from_file(path: PathLike) -> "Grammar": ...
    @staticmethod
    def preset(name: str) -> "Grammar": ...
    @property
    def generations(self) -> int: ...
    @property
    def dialect(self) -> str: ...
    def derive(self, generations: Optional[int] = None, *, seed: int = 0) -> str: ...

class Tree:
    """One tree: its mesh as arrays, its skeleton, and the species it is drawn as."""

    @property
    def name(self) -> str: ...
    @property
    def seed(self) -> int: ...
    @property
    def positions(self) -> npt.NDArray[np.float32]: ...
    @property
    def normals(self) -> npt.NDArray[np.float32]: ...
    @property
    def uvs(self) -> npt.NDArray[np.float32]: ...
    @property
    def wind(self) -> npt.NDArray[np.float32]: ...
    @property
    def bark(self) -> npt.NDArray[np.uint32]: ...
    @property
    def leaves(self) -> npt.NDArray[np.uint32]: ...
    @property
    def skeleton(self) -> Skeleton: ...
    @property
    def material(self) -> Material: ...
    @property
    def vertex_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    def write_glb(self, path: PathLike) -> int: ...
    def write_obj(self, path: PathLike) -> int: ...

class Forest:
    """A forest: species on ground, built once as the ``sylva`` command builds it."""

    def __init__(
        self,
        *,
        area: Optional[float] = None,
        species: Optional[Sequence[str]] = None,
        seed: int = 1,
        terrain: Union[PathLike, npt.ArrayLike, None] = None,
        spacing: Optional[float] = None,
        crop: Optional[Tuple[int, int, int, int]] = None,
        density: Optional[float] = None,
        budget_mb: Optional[int] = None,
        season: Optional[Season] = None,
        year: Optional[int] = None,
        progress: Optional[Progress] = None,
    ) -> None: ...
    @property
    def side(self) -> float: ...
    @property
    def region(self) -> Region: ...
    @property
    def seed(self) -> int: ...
    @property
    def notes(self) -> List[str]: ...
    @property
    def heights(self) -> npt.NDArray[np.float32]: ...
    @property
    def spacing(self) -> float: ...
    @property
    def species(self) -> List[str]: ...
    def materials(self) -> List[Material]: ...
    def variants(self) -> List[Variant]: ...
    def trees(self) -> Trees: ...
    def placements(self, region: Optional[Region] = None) -> Placements: ...
    def instance_mesh(self, variant: int, instance: int) -> InstanceMesh: ...
    def write_glb(
        self, path: PathLike, *, instancing: bool = True, progress: Optional[Progress] = None
    ) -> Dict[str, int]: ...
    def write_usd(self, path: PathLike) -> Dict[str, int]: ...
    def write_tiles(
        self,
        path: PathLike,
        *,
        tile_size: float = 250.0,
        group: int = 4,
        progress: Optional[Progress] = None,
    ) -> Dict[str, int]: ...
    def write_heightmap(self, path: PathLike) -> int: ...

class Stand:
    """A grown stand: its trees and what growing them did."""

    def trees(self) -> List[Tree]: ...
    @property
    def stats(self) -> Dict[str, int]: ...
    def write_glb(self, path: PathLike) -> int: ...

def presets() -> List[str]: ...
def species_names() -> List[str]: ...
def tree(
    species: Optional[str] = None,
    *,
    grammar: Optional[Grammar] = None,
    seed: int = 0,
    generations: Optional[int] = None,
    season: Optional[Season] = None,
) -> Tree: ...
def grow_stand(
    positions: npt.ArrayLike,
    *,
    species: Union[str, Sequence[str], None] = None,
    seed: int = 1,
    generations: Optional[int] = None,
    voxel: float = 0.1,
    terrain: Union[PathLike, npt.ArrayLike, None] = None,
    spacing: Optional[float] = None,
    progress: Optional[Progress] = None,
) -> Stand: ...
def succession(
    *,
    area: float = 200.0,
    years: int = 100,
    species: Optional[Sequence[str]] = None,
    seed: int = 1,
    progress: Optional[Progress] = None,
) -> Dict[str, Union[npt.NDArray[np.float64], List[List[str]]]]: ...
