"""fhr: Parameterization of Manifold Triangulations (Floater, Hormann, Reimers 2001) for Python.

Meshes are numpy arrays in libigl's convention: V, an (n, 3) float64 array of vertex positions,
and F, an (m, 3) integer array of counter-clockwise triangles. Other dtypes are converted when no
value changes (float32, any integer type in range); every array is validated as strictly as fhr's
file readers validate files (spec/mesh.md), and a bad one raises fhr.InvalidInput (a ValueError)
naming the problem.

    import fhr
    V, F = fhr.read_mesh("fandisk.off")
    p = fhr.parameterize(V, F, faces=114)
    assert p.certified
    p.write_param("fandisk.fhrp")
    assert fhr.verify("fandisk.fhrp", mesh=(V, F))["valid"]

The C++ library underneath is documented in spec/library.md; the module itself is fhr._fhr.
"""

from . import _fhr


class Error(Exception):
    """Base of every error fhr raises on purpose (the library's fhr::Error)."""


class InvalidInput(Error, ValueError):
    """The input is not what the method accepts: a file, an array or an option (exit code 2 in the CLI)."""


class PartitionFailure(Error, RuntimeError):
    """§3: the geodesic network cannot satisfy conditions (1) and (2), and the domain cannot be kept (exit 3)."""


class NumericalFailure(Error, ArithmeticError):
    """A numerical step could not reach its stated tolerance (exit 4)."""


class InternalError(Error, RuntimeError):
    """A broken invariant of fhr's own making: a bug, whatever the input (exit 70)."""


__version__ = _fhr.__version__
read_mesh = _fhr.read_mesh
write_mesh = _fhr.write_mesh
info = _fhr.info
generate = _fhr.generate
min_faces = _fhr.min_faces
decimate = _fhr.decimate
geodesic = _fhr.geodesic
parameterize = _fhr.parameterize
verify = _fhr.verify
verify_atlas = _fhr.verify_atlas
verify_vertex_map = _fhr.verify_vertex_map
Parameterization = _fhr.Parameterization
page_available = _fhr.page_available

__all__ = [
    "Error", "InvalidInput", "PartitionFailure", "NumericalFailure", "InternalError", "Parameterization",
    "read_mesh", "write_mesh", "info", "generate", "min_faces", "decimate", "geodesic", "parameterize", "verify",
    "verify_atlas",
    "verify_vertex_map", "page_available",
]
