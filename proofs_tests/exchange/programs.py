"""What the exchange directory's Python tests share: the built `fhr` (environment variable FHR, set
by the meson test) and libcgal-demo's meshes (FHR_CGAL_MESHES), each failing the test with a clear
message when absent."""
import os
import subprocess

import pytest

FHR = os.environ.get("FHR")
MESHES = os.environ.get("FHR_CGAL_MESHES")


def fhr(*args, check=True):
    """Runs the built fhr with `args` (any values, made strings), its output captured as text."""
    if not FHR or not os.path.exists(FHR):
        pytest.fail("FHR must name the built fhr program (the meson test sets it)")
    return subprocess.run([FHR, *map(str, args)], capture_output=True, text=True, check=check)


def mesh(name):
    """The path of libcgal-demo's mesh `name`."""
    if not MESHES:
        pytest.fail("FHR_CGAL_MESHES must name libcgal-demo's meshes (./run extracts them)")
    path = os.path.join(MESHES, name)
    if not os.path.exists(path):
        pytest.fail("%s is missing: ./run extracts libcgal-demo's data.tar.gz into out/cgal-data" % path)
    return path
