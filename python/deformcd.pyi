"""Type stubs for the deformcd package: the names its __init__.py re-exports from the compiled
pybind11 module deformcd._deformcd; see help(deformcd). deformcd.study is plain Python."""

import os
from typing import Mapping, Optional, Sequence, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str
BUILT_FOR: str  # the interpreter the compiled module was built for
has_gl: bool
broadphases: Tuple[str, ...]
backends: Tuple[str, ...]

class Error(RuntimeError): ...
class InputError(Error): ...
class GlError(Error): ...
class SimulationError(Error):
    stage: str  # "simulation" or "response" (the contact response)
    frame: Optional[int]
    body: Optional[int]
    body_name: Optional[str]
    node: Optional[int]

_MeshDict = Mapping[str, object]  # {"vertices", "faces", "self_collision"?, "name"?}
_Mesh = Union[Tuple[npt.ArrayLike, npt.ArrayLike], _MeshDict]

class _Contacts(TypedDict):
    body_a: npt.NDArray[np.int64]   # (k,)
    face_a: npt.NDArray[np.int64]   # (k,)
    body_b: npt.NDArray[np.int64]   # (k,)
    face_b: npt.NDArray[np.int64]   # (k,)
    nodes_a: npt.NDArray[np.int64]  # (k, 3)
    nodes_b: npt.NDArray[np.int64]  # (k, 3)
    segment: npt.NDArray[np.float32]  # (k, 2, 3)
    coplanar: npt.NDArray[np.bool_]   # (k,)

class _FrameTimes(TypedDict):
    simulation_s: float
    collision_s: float
    proximity_s: float
    response_s: float

class _ResponseCounts(TypedDict):
    vertex_face: int
    edge_edge: int
    untangle: int
    penetrating: int
    between_bodies: int
    searches: int
    widenings: int
    self_searches: int
    substeps: int
    iterations: int
    asleep: int

class _Census(TypedDict):
    between_pairs: int
    self_pairs: int
    inside_vertices: int

class _Counts(TypedDict):
    contacts: int
    box_pairs: int
    colliding_faces: int
    candidates: int

def read_surface(path: Union[str, os.PathLike[str]]) -> Tuple[npt.NDArray[np.float64], npt.NDArray[np.int64]]: ...

class Detector:
    def __init__(
        self,
        meshes: Sequence[_Mesh],
        backend: str = "auto",
        broadphase: str = "bvh",
        threads: int = 0,
        mesh_pairs: Optional[Sequence[Tuple[int, int]]] = None,
    ) -> None: ...
    def set_positions(self, mesh: int, positions: npt.ArrayLike) -> None: ...
    def positions(self, mesh: int) -> npt.NDArray[np.float32]: ...
    def detect(self) -> None: ...
    def prepare(self) -> None: ...
    def contacts(self) -> _Contacts: ...
    def counts(self) -> _Counts: ...
    def face_flags(self, mesh: Optional[int] = None) -> npt.NDArray[np.bool_]: ...
    broadphase: str
    @property
    def mesh_count(self) -> int: ...
    @property
    def face_count(self) -> int: ...
    def vertex_count(self, mesh: int) -> int: ...
    def faces(self, mesh: int) -> npt.NDArray[np.int64]: ...
    def face_offset(self, mesh: int) -> int: ...
    @property
    def backend(self) -> str: ...
    @property
    def device(self) -> str: ...
    @property
    def notice(self) -> str: ...

class World:
    @staticmethod
    def from_scene(
        path: Union[str, os.PathLike[str]],
        frames: Optional[int] = None,
        backend: str = "cpu",
        broadphase: str = "bvh",
        threads: int = 0,
        measure_stage_times: bool = False,
    ) -> World: ...
    def step(self, n: int = 1) -> None: ...
    def detect(self) -> None: ...
    def positions(self, body: int) -> npt.NDArray[np.float32]: ...
    def velocities(self, body: int) -> npt.NDArray[np.float32]: ...
    def faces(self, body: int) -> npt.NDArray[np.int64]: ...
    def contacts(self) -> _Contacts: ...
    def counts(self) -> _Counts: ...
    def last_frame_times(self) -> _FrameTimes: ...
    def response_counts(self) -> _ResponseCounts: ...
    def intersection_census(self) -> _Census: ...
    def face_flags(self, body: Optional[int] = None) -> npt.NDArray[np.bool_]: ...
    @property
    def frame(self) -> int: ...
    @property
    def frames(self) -> int: ...
    @property
    def body_count(self) -> int: ...
    def body_name(self, body: int) -> str: ...
    def asleep(self, body: int) -> bool: ...
    @property
    def body_names(self) -> list[str]: ...
    broadphase: str
    gravity: Sequence[float]
    @property
    def backend(self) -> str: ...
    @property
    def device(self) -> str: ...
    @property
    def notice(self) -> str: ...
    @property
    def estimated_max_substep(self) -> float: ...
