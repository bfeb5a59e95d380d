# Type stubs of the extension fhr._fhr (src/python/module.cpp and the topics it binds); checked against the module by
# mypy's stubtest in ./run test. Shapes: V (n, 3) float64, F (m, 3) int64.
from typing import Any, Callable, Optional, Sequence, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

_Vertices = npt.NDArray[np.float64]
_Faces = npt.NDArray[np.int64]

__version__: str

class Parameterization:
    @property
    def certified(self) -> bool: ...
    @property
    def domain(self) -> Tuple[_Vertices, _Faces]: ...
    @property
    def refined(self) -> Tuple[_Vertices, _Faces]: ...
    @property
    def face_patch(self) -> npt.NDArray[np.int64]: ...
    @property
    def face_beta(self) -> npt.NDArray[np.float64]: ...
    @property
    def oracle(self) -> dict[str, Any]: ...
    @property
    def wavelets(self) -> Optional[dict[str, Any]]: ...
    def phi(self, faces: npt.ArrayLike, beta: npt.ArrayLike) -> _Vertices: ...
    def psi(self, faces: npt.ArrayLike, weights: npt.ArrayLike) -> Tuple[npt.NDArray[np.int64], npt.NDArray[np.float64]]: ...
    def write_param(self, path: str) -> None: ...
    def write(self, dir: str, figures: bool = ...) -> None: ...
    def write_html(self, path: str, up: str = ..., page_faces: int = ...) -> None: ...

def page_available() -> bool: ...
def read_mesh(path: str) -> Tuple[_Vertices, _Faces]: ...
def write_mesh(path: str, V: npt.ArrayLike, F: npt.ArrayLike) -> None: ...
def info(V: npt.ArrayLike, F: npt.ArrayLike) -> dict[str, int]: ...
def generate(
    genus: int, faces: int, seed: int = ..., noise: float = ..., holes: int = ..., components: int = ...,
    family: str = ..., **knobs: float
) -> Tuple[_Vertices, _Faces]: ...
def min_faces(genus: int, holes: int = ..., components: int = ..., family: str = ..., **knobs: float) -> int: ...
def decimate(V: npt.ArrayLike, F: npt.ArrayLike, faces: int) -> Tuple[_Vertices, _Faces, npt.NDArray[np.int64]]: ...
def geodesic(
    V: npt.ArrayLike, F: npt.ArrayLike, source: int, target: int
) -> Tuple[float, _Vertices, list[Union[Tuple[str, int], Tuple[str, int, int, float]]]]: ...
def parameterize(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    faces: int = ...,
    domain: Optional[Tuple[npt.ArrayLike, npt.ArrayLike, npt.ArrayLike]] = ...,
    weights: str = ...,
    map: str = ...,
    levels: int = ...,
    keep: Sequence[float] = ...,
    progress: Optional[Callable[[str], object]] = ...,
) -> Parameterization: ...
@overload
def verify(
    parameterization: Parameterization, mesh: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ..., paper: bool = ...
) -> dict[str, Any]: ...
@overload
def verify(
    path: str,
    mesh: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ...,
    no_mirror: bool = ...,
    strict: bool = ...,
    paper: bool = ...,
) -> dict[str, Any]: ...
def verify_atlas(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    UV: npt.ArrayLike,
    FUV: Optional[npt.ArrayLike] = ...,
    textures: Optional[npt.ArrayLike] = ...,
    mesh: Optional[Tuple[npt.ArrayLike, npt.ArrayLike]] = ...,
    no_mirror: bool = ...,
    strict: bool = ...,
    lists: bool = ...,
) -> dict[str, Any]: ...
@overload
def verify_vertex_map(
    V: npt.ArrayLike,
    F: npt.ArrayLike,
    DV: npt.ArrayLike,
    DF: npt.ArrayLike,
    faces: npt.ArrayLike,
    weights: npt.ArrayLike,
    lists: bool = ...,
) -> dict[str, Any]: ...
@overload
def verify_vertex_map(
    path: str,
    mesh: Tuple[npt.ArrayLike, npt.ArrayLike],
    domain: Tuple[npt.ArrayLike, npt.ArrayLike],
    format: Optional[str] = ...,
    lists: bool = ...,
) -> dict[str, Any]: ...
