"""The MeshLab adapters peers/meshlab-* (shared code: peers/meshlab_common.py): each runs Debian's
meshlabserver under xvfb-run on a mesh and leaves at OUT an OBJ atlas in which every face corner
has a `vt`; meshlab-iso refuses (exit 3) a closed mesh of two components and a mesh with a hole,
as MeshLab's iso-parameterization does; a missing mesh is exit 2; `--help` exits 0 and names the
MeshLab filters. The atlases themselves are judged by `fhr verify`, not here.

The meshes are made here: an icosahedron subdivided three times onto the unit sphere (1280 faces,
closed, genus 0 — MeshLab's iso-parameterization accepts it from one subdivision, 80 faces, on),
two such spheres apart, and the sphere with one face taken out.

Run with Debian's interpreter: /usr/bin/python3 -m pytest proofs_tests/peers/test_meshlab.py.
The adapters are found relative to this file (the repository is two folders up). meshlabserver,
xvfb-run and xauth must be installed: `./run` installs Debian's meshlab, xvfb and xauth."""

import math
import os
import shutil
import subprocess
from pathlib import Path

import pytest

from oracle import fhr_verify

ROOT = Path(__file__).resolve().parents[2]
PEERS = ROOT / "peers"

# adapter name -> the MeshLab filter names its --help must contain
ADAPTERS = {
    "meshlab-iso": ["Iso Parametrization: Main", "Iso Parametrization Build Atlased Mesh"],
    "meshlab-trivial": ["Parametrization: Trivial Per-Triangle"],
    "meshlab-flat": ["Parametrization: Flat Plane"],
    "meshlab-voronoi": ["Parametrization: Voronoi Atlas"],
}


@pytest.fixture(scope="module", autouse=True)
def meshlab_installed():
    missing = [tool for tool in ("meshlabserver", "xvfb-run", "xauth") if shutil.which(tool) is None]
    if missing:
        pytest.fail(f"{', '.join(missing)} not found: ./run installs Debian's meshlab, xvfb and xauth")


def run(adapter, *args, timeout=120):
    env = dict(os.environ, FHR_PEER_TIMEOUT=str(timeout))
    return subprocess.run([str(PEERS / adapter), *[str(a) for a in args]], capture_output=True,
                          text=True, env=env, timeout=timeout + 30)


# --- meshes -------------------------------------------------------------------------------------

def icosphere(level):
    """The icosahedron, each triangle split in four LEVEL times, vertices pushed onto the unit
    sphere: 20 * 4^LEVEL faces, outward-oriented."""
    t = (1 + math.sqrt(5)) / 2
    vertices = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t),
                (0, -1, -t), (0, 1, -t), (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    vertices = [tuple(c / math.sqrt(sum(x * x for x in v)) for c in v) for v in vertices]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    for _ in range(level):
        middle = {}

        def mid(a, b):
            key = (min(a, b), max(a, b))
            if key not in middle:
                p = [(vertices[a][i] + vertices[b][i]) / 2 for i in range(3)]
                norm = math.sqrt(sum(x * x for x in p))
                vertices.append(tuple(x / norm for x in p))
                middle[key] = len(vertices) - 1
            return middle[key]

        split = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            split += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = split
    return vertices, faces


def write_off(path, vertices, faces):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        f.writelines("%.17g %.17g %.17g\n" % v for v in vertices)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)
    return path


@pytest.fixture(scope="module")
def meshes(tmp_path_factory):
    folder = tmp_path_factory.mktemp("meshes")
    vertices, faces = icosphere(3)
    n = len(vertices)
    moved = [(x + 3.0, y, z) for x, y, z in vertices]
    return {
        "sphere": write_off(folder / "sphere.off", vertices, faces),
        "two_spheres": write_off(folder / "two_spheres.off", vertices + moved,
                                 faces + [(a + n, b + n, c + n) for a, b, c in faces]),
        # one face taken out: a triangular hole, one boundary loop
        "holed": write_off(folder / "holed.off", vertices, faces[1:]),
    }


def atlas_faces(path):
    """The faces of the OBJ at PATH, each a list of (vertex, texcoord) indices; asserts that every
    corner names a `vt` that exists."""
    vt = 0
    faces = []
    with open(path) as f:
        for line in f:
            head, _, rest = line.partition(" ")
            if head == "vt":
                vt += 1
            elif head == "f":
                corners = []
                for corner in rest.split():
                    parts = corner.split("/")
                    assert len(parts) >= 2 and parts[1], f"corner {corner!r} without vt: {line!r}"
                    t = int(parts[1])
                    assert 1 <= t <= vt, f"corner {corner!r} names a missing vt"
                    corners.append((int(parts[0]), t))
                assert len(corners) == 3, line
                faces.append(corners)
    return faces


# --- the cases ----------------------------------------------------------------------------------

@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_atlas_of_a_sphere(adapter, meshes, tmp_path):
    out = tmp_path / "atlas.obj"
    result = run(adapter, meshes["sphere"], out)
    assert result.returncode == 0, result.stderr
    faces = atlas_faces(out)
    if adapter == "meshlab-iso":
        assert len(faces) >= 1280          # faces crossing a diamond's border are split
    else:
        assert len(faces) == 1280
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.obj"]   # no .mtl, no temporary


@pytest.mark.parametrize("mesh, words", [("two_spheres", "multi component"),
                                          ("holed", "non watertight")])
def test_iso_refuses(mesh, words, meshes, tmp_path):
    out = tmp_path / "atlas.obj"
    result = run("meshlab-iso", meshes[mesh], out)
    assert result.returncode == 3, result.stderr
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("meshlab-iso: ") and words in lines[0], lines
    assert not out.exists()


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_missing_mesh(adapter, tmp_path):
    result = run(adapter, tmp_path / "missing.off", tmp_path / "atlas.obj")
    assert result.returncode == 2
    assert result.stderr.startswith(f"{adapter}: error: ") and result.stderr.count("\n") == 1
    assert not (tmp_path / "atlas.obj").exists()


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_help(adapter):
    result = run(adapter, "--help")
    assert result.returncode == 0
    for name in ADAPTERS[adapter]:
        assert name in result.stdout
    assert "meshlabserver" in result.stdout and "exit" in result.stdout.lower()


# --- judged by the oracle -----------------------------------------------------------------------



@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_every_adapters_atlas_is_judged(adapter, meshes, tmp_path):
    """Each adapter once on the sphere, its atlas judged against the input: the surface is the
    sphere's (ATLAS-8, within the six decimals and float32 positions MeshLab writes), and the
    verdict has the distortion figures. Per-triangle charts (trivial) never fold or overlap."""
    out = tmp_path / "atlas.obj"
    assert run(adapter, meshes["sphere"], out).returncode == 0
    verdict = fhr_verify(out, "--mesh", meshes["sphere"])
    assert verdict["kind"] == "atlas"
    results = {c["id"]: c["result"] for c in verdict["checks"]}
    assert results["ATLAS-8"] == "pass", verdict["checks"]
    assert verdict["distortion"]["l2_stretch"] is not None
    if adapter == "meshlab-trivial":
        assert verdict["valid"], verdict["first_failure"]
        assert verdict["charts"] == 1280


def test_a_fold_and_an_overlap_made_from_a_real_atlas_are_caught(meshes, tmp_path):
    out = tmp_path / "trivial.obj"
    assert run("meshlab-trivial", meshes["sphere"], out).returncode == 0
    assert fhr_verify(out)["valid"]
    lines = out.read_text().splitlines()
    vts = [i for i, line in enumerate(lines) if line.startswith("vt ")]
    first_face = next(line for line in lines if line.startswith("f "))
    a, b, c = (int(corner.split("/")[1]) - 1 for corner in first_face.split()[1:4])
    ua, va = map(float, lines[vts[a]].split()[1:3])
    ub, vb = map(float, lines[vts[b]].split()[1:3])
    uc, vc = map(float, lines[vts[c]].split()[1:3])
    # A fold: corner a reflected through the midpoint of the opposite side turns its face over;
    # one face alone is a chart, so its neighbour in the packing is what it overlaps (a mirrored
    # chart of one face is no fold): the verdict is an overlap or, if none is hit, a mirrored chart.
    folded = list(lines)
    folded[vts[a]] = "vt %.6f %.6f" % (ub + uc - ua, vb + vc - va)
    (tmp_path / "fold.obj").write_text("\n".join(folded) + "\n")
    verdict = fhr_verify(tmp_path / "fold.obj", "--no-mirror")
    assert not verdict["valid"] and verdict["first_failure"] in ("ATLAS-4", "ATLAS-6")
    # An overlap: the face moved onto the middle of the texture, over other charts.
    moved = list(lines)
    for k, (u, v) in zip((a, b, c), ((ua, va), (ub, vb), (uc, vc))):
        moved[vts[k]] = "vt %.6f %.6f" % (u - ua + 0.5, v - va + 0.5)
    (tmp_path / "overlap.obj").write_text("\n".join(moved) + "\n")
    verdict = fhr_verify(tmp_path / "overlap.obj")
    assert not verdict["valid"] and verdict["first_failure"] == "ATLAS-6" and verdict["overlapping_pairs"] > 0
