"""The Python package fhr (spec/python.md; spec/library.md for the calls underneath).

Run by `./run test` with Debian's /usr/bin/python3 and the package staged in the build tree
(PYTHONPATH=build/src/python); FHR is the `fhr` command of the same build, FHR_CGAL_MESHES the
folder of libcgal-demo's meshes (default: out/cgal-data/data/meshes, where ./run extracts them). The CLI is the independent reference for bytes and verdicts.
"""

import gzip
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings

import fhr
import fhr.testing

ROOT = Path(__file__).resolve().parents[2]
FHR = os.environ["FHR"]
MESHES = Path(os.environ.get("FHR_CGAL_MESHES", ROOT / "out/cgal-data/data/meshes"))
FANDISK = MESHES / "fandisk.off"


def cli(*args, check=True):
    return subprocess.run([FHR, *map(str, args)], capture_output=True, text=True, check=check)


@pytest.fixture(scope="module")
def fandisk():
    if not FANDISK.exists():
        pytest.fail("fandisk.off is missing from %s: ./run extracts libcgal-demo's meshes" % MESHES)
    return fhr.read_mesh(str(FANDISK))


@pytest.fixture(scope="module")
def fandisk_run(fandisk, tmp_path_factory):
    """fhr.parameterize and `fhr run` on the fandisk with the paper's 114 faces and its map (the
    reference outputs' run, spec/cli.md CLI-RUN-9)."""
    out = tmp_path_factory.mktemp("cli")
    cli("run", FANDISK, "--faces", 114, "--map", "paper", "--out", out)
    V, F = fandisk
    return fhr.parameterize(V, F, faces=114, map="paper"), out


# --- arrays in and out ------------------------------------------------------------------------

# PY-1
def test_read_mesh_gives_libigl_arrays(fandisk):
    V, F = fandisk
    assert V.shape == (6475, 3) and V.dtype == np.float64
    assert F.shape == (12946, 3) and F.dtype == np.int64
    assert fhr.info(V, F) == {"vertices": 6475, "faces": 12946, "edges": 19419, "euler_characteristic": 2,
                              "boundary_loops": 0, "components": 1, "genus": 0}


# PY-1
def test_lossless_dtypes_and_layouts_are_accepted(fandisk):
    V, F = fandisk
    expected = fhr.info(V, F)
    assert fhr.info(V.astype(np.float32), F.astype(np.int32)) == expected
    assert fhr.info(np.asfortranarray(V), F.astype(np.uint16)) == expected
    assert fhr.info(V[::1], np.ascontiguousarray(F[:, [0, 1, 2]]).astype(np.uint64)) == expected
    strided = np.zeros((len(V), 6))
    strided[:, ::2] = V
    assert fhr.info(strided[:, ::2], F) == expected  # a non-contiguous view


# PY-1, FMT-WRITE-2
def test_write_then_read_is_bit_exact(fandisk, tmp_path):
    V, F = fandisk
    for ext in ("off", "obj", "ply"):
        path = str(tmp_path / ("m." + ext))
        fhr.write_mesh(path, V, F)
        V2, F2 = fhr.read_mesh(path)
        assert np.array_equal(V2, V) and np.array_equal(F2, F)


@pytest.mark.parametrize("make, words", [
    (lambda V, F: (V[:, :2], F), "V must have shape (n, 3)"),
    (lambda V, F: (V, F[:, :2]), "F must have shape (n, 3)"),
    (lambda V, F: (V, F.ravel()), "F must have shape (n, 3)"),
    (lambda V, F: (np.where(np.arange(len(V))[:, None] == 2, np.nan, V), F), "V[2] is not finite"),
    (lambda V, F: (V, np.where(F == 3, len(V), F)), "outside [0, 4)"),
    (lambda V, F: (V, np.where(F == 3, -1, F)), "vertex index -1"),
    (lambda V, F: (V, F.astype(np.float64)), "F must hold integers"),
    (lambda V, F: (V.astype(str), F), "V must hold numbers"),
    (lambda V, F: (V, np.vstack([F, [[0, 1, 2]]])), ""),  # a face twice: an edge in three faces
    (lambda V, F: (V, np.array([[0, 1, 1]] + F[1:].tolist())), "repeats"),
])
# PY-1, PY-2
def test_bad_arrays_raise_invalid_input_naming_the_problem(make, words):
    # The tetrahedron; each case breaks it in one way (INV-IN-* of spec/mesh.md for the mesh rules).
    V = np.array([[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]], dtype=float)
    F = np.array([[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]])
    assert fhr.info(V, F)["genus"] == 0
    bad_V, bad_F = make(V, F)
    with pytest.raises(fhr.InvalidInput) as caught:
        fhr.parameterize(bad_V, bad_F, faces=4)
    assert isinstance(caught.value, ValueError)
    assert words in str(caught.value)
    assert str(caught.value)  # always a one-line message


# PY-1, INV-IN-7
def test_a_non_manifold_vertex_is_refused():
    # Two tetrahedra sharing one vertex: closed, but the shared vertex has two fans (INV-IN-7).
    V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [-1, 0, 0], [0, -1, 0], [0, 0, -1]], dtype=float)
    F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3], [0, 4, 5], [0, 6, 4], [0, 5, 6], [4, 6, 5]])
    with pytest.raises(fhr.InvalidInput, match="non-manifold vertex"):
        fhr.info(V, F)


# --- the generator, §2 and §3 -------------------------------------------------------------------

# PY-3
def test_generate_gives_the_bits_of_fhr_generate(tmp_path):
    path = tmp_path / "g.off"
    cli("generate", "--genus", 2, "--faces", 400, "--seed", 9, "--noise", 0.1, "--out", path)
    V, F = fhr.generate(2, 400, seed=9, noise=0.1)
    V2, F2 = fhr.read_mesh(str(path))
    assert np.array_equal(V, V2) and np.array_equal(F, F2)
    assert fhr.info(V, F)["genus"] == 2


def read_off_arrays(path):
    """An OFF file as written by `fhr generate`, read without fhr's builder (which refuses boundary)."""
    lines = Path(path).read_text().split("\n")
    nv, nf = map(int, lines[1].split()[:2])
    V = np.array([[float(x) for x in line.split()] for line in lines[2:2 + nv]])
    F = np.array([[int(x) for x in line.split()[1:]] for line in lines[2 + nv:2 + nv + nf]], dtype=np.int64)
    return V, F


# PY-3, spec/generator.md
def test_generate_with_holes_and_components_gives_the_bits_of_fhr_generate(tmp_path):
    path = tmp_path / "g.off"
    cli("generate", "--genus", 1, "--holes", 3, "--components", 2, "--faces", 301, "--seed", 4, "--noise", 0.25,
        "--out", path)
    V, F = fhr.generate(1, 301, seed=4, noise=0.25, holes=3, components=2)
    V2, F2 = read_off_arrays(path)
    assert np.array_equal(V, V2) and np.array_equal(F, F2)
    counts = fhr.info(V, F)
    assert (counts["faces"], counts["genus"], counts["boundary_loops"], counts["components"]) == (301, 1, 3, 2)
    # Hand-computed in proofs_tests/generate/test_random_mesh.cpp: 60 + 60 + 10 faces.
    assert fhr.min_faces(2, 5, 3) == 130 and fhr.min_faces(2) == 100


# PY-3, spec/generator.md GEN-8: every family, its knobs by keyword, the bits of `fhr generate`
@pytest.mark.parametrize("family,knobs,cli_knobs", [
    ("smooth", {"amplitude": 0.125}, ["--amplitude", 0.125]),
    ("quality", {"smallest_angle": 1e-5}, ["--smallest-angle", 1e-5]),
    ("valence", {"high_valence": 60}, ["--high-valence", 60]),
    ("density", {"edge_ratio": 2e4}, ["--edge-ratio", 2e4]),
    ("degenerate", {"grid_cells": 16}, ["--grid-cells", 16]),
    ("immersed", {}, []),
])
def test_generate_families_give_the_bits_of_fhr_generate(tmp_path, family, knobs, cli_knobs):
    path = tmp_path / "g.off"
    faces = max(600, fhr.min_faces(1, family=family, **knobs))
    cli("generate", "--family", family, "--genus", 1, "--faces", faces, "--seed", 3, *cli_knobs, "--out", path)
    V, F = fhr.generate(1, faces, seed=3, family=family, **knobs)
    V2, F2 = read_off_arrays(path)
    assert np.array_equal(V, V2) and np.array_equal(F, F2)
    assert fhr.info(V, F)["genus"] == 1 and len(F) == faces


# PY-3: a knob of another family, an unknown knob or family is a ValueError naming it
def test_generate_refuses_foreign_and_unknown_knobs():
    with pytest.raises(ValueError, match="roundness is a knob of the smooth family"):
        fhr.generate(1, 500, roundness=0.2)
    with pytest.raises(ValueError, match="unknown knob 'sharpness'"):
        fhr.generate(1, 500, family="smooth", sharpness=1.0)
    with pytest.raises(ValueError, match="unknown family 'spiky'"):
        fhr.generate(1, 500, family="spiky")
    with pytest.raises(ValueError, match="noise is a knob of the block family only"):
        fhr.generate(1, 500, noise=0.1, family="quality")


# PY-6, spec/generator.md GEN-2, GEN-3
@settings(max_examples=40, derandomize=True, deadline=None)
@given(fhr.testing.meshes(genus=(0, 2), faces=(12, 1500), holes=(0, 5), components=(1, 3)))
def test_meshes_with_holes_and_components_have_them(mesh):
    counts = fhr.info(mesh.V, mesh.F)
    r = mesh.recipe
    assert (counts["faces"], counts["genus"], counts["boundary_loops"], counts["components"]) == (
        r.faces, r.genus, r.holes, r.components), mesh


# PY-4
def test_decimate_keeps_vertices_of_t(fandisk):
    V, F = fandisk
    DV, DF, t_vertex = fhr.decimate(V, F, 114)
    assert DF.shape == (114, 3) and len(DV) == len(t_vertex) == 59
    assert np.array_equal(DV, V[t_vertex])


# PY-4
def test_geodesic_runs_on_the_surface(fandisk):
    V, F = fandisk
    length, points, surface = fhr.geodesic(V, F, 0, 100)
    assert len(surface) == len(points) and surface[0] == ("vertex", 0) and surface[-1] == ("vertex", 100)
    for (kind, *where), xyz in zip(surface, points):
        if kind == "vertex":
            assert np.array_equal(V[where[0]], xyz)
        else:
            a, b, t = where
            assert np.linalg.norm((1 - t) * V[a] + t * V[b] - xyz) <= 1e-15 * np.abs(V).max()
    assert np.array_equal(points[0], V[0]) and np.array_equal(points[-1], V[100])
    polyline = np.linalg.norm(np.diff(points, axis=0), axis=1).sum()
    assert abs(polyline - length) <= 1e-12 * length
    assert length >= np.linalg.norm(V[100] - V[0])
    with pytest.raises(fhr.InvalidInput, match="out of range"):
        fhr.geodesic(V, F, 0, len(V))


# --- the method and the oracle -------------------------------------------------------------------

# PY-3
def test_param_file_is_byte_identical_to_the_cli(fandisk_run, tmp_path):
    p, out = fandisk_run
    assert p.certified and p.oracle["valid"]
    path = tmp_path / "python.fhrp"
    p.write_param(str(path))
    assert path.read_bytes() == (out / "param.fhrp").read_bytes()
    # And the reviewed reference output of the paper's run.
    reference = ROOT / "reference_outputs/fandisk/param.fhrp.gz"
    assert path.read_bytes() == gzip.decompress(reference.read_bytes())


# PY-4
def test_the_arrays_are_the_file(fandisk, fandisk_run):
    p, _ = fandisk_run
    V, _ = fandisk
    RV, RF = p.refined
    DV, DF = p.domain
    assert np.array_equal(RV[:len(V)], V)  # T's vertices first, unmoved
    assert DF.shape == (114, 3) and RF.shape[0] == len(p.face_patch) == len(p.face_beta)
    assert p.face_patch.min() == 0 and p.face_patch.max() == 113
    assert np.all(p.face_beta >= 0) and np.allclose(p.face_beta.sum(axis=2), 1, atol=1e-12)


# PY-4
def test_phi_at_the_domain_corners_is_the_domain_vertex(fandisk_run):
    p, _ = fandisk_run
    DV, DF = p.domain
    for k in range(3):
        beta = np.zeros((len(DF), 3))
        beta[:, k] = 1
        assert np.array_equal(p.phi(np.arange(len(DF)), beta), DV[DF[:, k]])
    with pytest.raises(fhr.InvalidInput):
        p.phi(np.array([114]), np.array([[1.0, 0, 0]]))


# PY-3
def test_a_corrupted_file_fails_with_the_cli_check(fandisk, fandisk_run, tmp_path):
    V, F = fandisk
    _, out = fandisk_run
    lines = (out / "param.fhrp").read_text().split("\n")
    face = lines[-2].split()
    face[5] = "0.75"  # the first corner's β no longer sums to 1 (PARAM-5)
    lines[-2] = " ".join(face)
    bad = tmp_path / "bad.fhrp"
    bad.write_text("\n".join(lines))
    for path, valid in ((bad, False), (out / "param.fhrp", True)):
        ours = fhr.verify(str(path), mesh=(V, F))
        theirs = json.loads(cli("verify", path, "--mesh", FANDISK, "--json", check=False).stdout)
        assert ours["valid"] == theirs["valid"] == valid
        assert ours == {key: theirs[key] for key in ours}  # every check, count and message alike
    assert ours["first_failure"] is None
    assert fhr.verify(str(bad), mesh=(V, F))["first_failure"] == "PARAM-5"


# PY-2
def test_an_unreadable_file_is_invalid_input(tmp_path):
    bad = tmp_path / "bad.fhrp"
    bad.write_text("fhr-param 2\n")
    with pytest.raises(fhr.InvalidInput, match="bad.fhrp:1"):
        fhr.verify(str(bad))


# PY-2
def test_options_out_of_range_are_invalid_input(fandisk):
    V, F = fandisk
    with pytest.raises(fhr.InvalidInput):
        fhr.parameterize(V, F, faces=113)  # odd
    with pytest.raises(fhr.InvalidInput, match="weights"):
        fhr.parameterize(V, F, faces=114, weights="cotangent")


# PY-4, PY-6
@settings(max_examples=50, derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(fhr.testing.meshes(genus=(0, 2), faces=(100, 2000)))
def test_random_meshes_parameterize_and_verify(mesh):
    domain_faces = max(40, len(mesh.F) // 40 * 2)
    p = fhr.parameterize(mesh.V, mesh.F, faces=domain_faces)
    assert p.certified, mesh
    assert p.oracle["valid"], (mesh, p.oracle["first_failure"])
    assert len(p.domain[1]) == domain_faces


# PY-4, PY-6 with boundary loops and several components (beyond the paper): certified, accepted by the
# oracle, D with T's components, boundary loops and genus; with boundary a component may stop
# above its share of the faces asked, so D has at least as many.
@settings(max_examples=30, derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(fhr.testing.meshes(genus=(0, 2), faces=(100, 2000), holes=(1, 5), components=(1, 3)))
def test_random_surfaces_with_boundary_parameterize_and_verify(mesh):
    domain_faces = max(40, len(mesh.F) // 40)
    p = fhr.parameterize(mesh.V, mesh.F, faces=domain_faces)
    assert p.certified, mesh
    assert p.oracle["valid"], (mesh, p.oracle["first_failure"])
    DV, DF = p.domain
    t, d = fhr.info(mesh.V, mesh.F), fhr.info(DV, DF)
    assert (d["components"], d["boundary_loops"], d["genus"]) == (t["components"], t["boundary_loops"], t["genus"]), mesh
    assert len(DF) >= domain_faces, mesh


# PY-6
def test_the_strategy_shrinks_toward_the_smallest_recipe():
    from hypothesis import find
    smallest = find(fhr.testing.recipes(genus=(1, 3), faces=(100, 800)), lambda r: True)
    assert smallest == fhr.testing.Recipe(1, 100, 0, 0.0)
    # A failing property shrinks to its boundary, not to an arbitrary recipe.
    bigger = find(fhr.testing.recipes(genus=(0, 2), faces=(12, 800)), lambda r: r.faces >= 300 and r.noise > 0)
    assert bigger == fhr.testing.Recipe(0, 300, 0, 0.05)
    # With holes and components: toward the fewest of each, and the fewest faces (here the lower
    # bound 12 of `faces`, above min_faces(0, 1, 1) = 10); with holes the face count may be odd: two
    # components with one hole need min_faces(0, 1, 2) = 10 + 12 = 22, so 23 is the smallest odd one.
    ranges = dict(genus=(0, 2), faces=(12, 800), holes=(1, 5), components=(1, 3))
    assert find(fhr.testing.recipes(**ranges), lambda r: True) == fhr.testing.Recipe(0, 12, 0, 0.0, 1, 1)
    odd = find(fhr.testing.recipes(**ranges), lambda r: r.components == 2 and r.faces % 2 == 1)
    assert odd == fhr.testing.Recipe(0, 23, 0, 0.0, 1, 2)
    assert odd.command() == "fhr generate --genus 0 --holes 1 --components 2 --faces 23 --seed 0 --out mesh.off"


# PY-5
def test_progress_lines_reach_the_callback_and_an_exception_there_stops_the_call(fandisk, tmp_path):
    V, F = fandisk
    lines = []
    fhr.parameterize(V, F, faces=114, progress=lines.append)
    assert any(line.startswith("domain: 59 vertices, 114 faces") for line in lines)
    assert any(line.startswith("parameterization: 114 patches") for line in lines)

    class Stop(Exception):
        pass

    def stop(line):
        raise Stop(line)

    with pytest.raises(Stop, match="domain"):
        fhr.parameterize(V, F, faces=114, progress=stop)


# PY-5
def test_ctrl_c_raises_keyboard_interrupt_and_leaves_fhr_usable(fandisk):
    # SIGINT while the calls run (mostly without the GIL): KeyboardInterrupt, raised between the
    # steps of a call (PyErr_CheckSignals) or between calls; either way fhr works afterwards.
    import signal
    import threading
    V, F = fandisk
    # Python raises KeyboardInterrupt only where SIGINT has its default handler: a shell starts a
    # background job with SIGINT ignored, and the interpreter then keeps it ignored.
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(0.05, lambda: signal.pthread_kill(threading.main_thread().ident, signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            for _ in range(200):  # far longer than 50 ms in all
                fhr.parameterize(V, F, faces=114, levels=2, keep=[5])
    finally:
        timer.cancel()
        signal.signal(signal.SIGINT, previous)
    assert fhr.parameterize(V, F, faces=114).certified


# PY-4
def test_stubs_agree_with_the_module(tmp_path):
    # mypy's stubtest compares src/python/fhr/_fhr.pyi with the built extension.
    import sys
    allowlist = Path(__file__).with_name("stubtest_allowlist.txt")
    check = subprocess.run([sys.executable, "-m", "mypy.stubtest", "fhr._fhr", "--allowlist", str(allowlist)],
                           capture_output=True, text=True, env=dict(os.environ, MYPY_CACHE_DIR=str(tmp_path)))
    assert check.returncode == 0, check.stdout + check.stderr


# PY-4, LIB-6
def test_the_python_example_prints_what_the_cpp_example_prints():
    # examples/parameterize.py and examples/parameterize.cpp: the same lines, byte for byte.
    import sys
    script = ROOT / "examples" / "parameterize.py"
    ours = subprocess.run([sys.executable, str(script), str(FANDISK), "114"], capture_output=True, text=True, check=True)
    theirs = subprocess.run([os.environ["FHR_EXAMPLE_PARAMETERIZE"], str(FANDISK), "114"], capture_output=True, text=True,
                            check=True)
    assert ours.stdout == theirs.stdout
    assert len(ours.stdout.splitlines()) == 6475


# PY-4
def test_psi_inverts_phi_and_the_wavelets_are_there(fandisk):
    V, F = fandisk
    p = fhr.parameterize(V, F, faces=114, levels=2, keep=[5, 20])
    RV, RF = p.refined
    # psi at the corners of T' faces is the file's β; phi maps them back onto the surface.
    faces = np.arange(0, len(RF), 97)
    for k in range(3):
        w = np.zeros((len(faces), 3))
        w[:, k] = 1
        d, beta = p.psi(faces, w)
        assert np.array_equal(d, p.face_patch[faces])
        assert np.array_equal(beta, p.face_beta[faces, k])
        assert np.abs(p.phi(d, beta) - RV[RF[faces, k]]).max() <= 1e-9 * np.abs(V).max()
    w = p.wavelets
    assert w["levels"] == 2 and w["remesh"][1].shape == (114 * 16, 3)
    assert [k["percent"] for k in w["kept"]] == [5, 20]
    assert w["kept"][0]["l2_error"] >= w["kept"][1]["l2_error"] > 0
    assert w["hausdorff"][0] <= w["hausdorff"][1]
    assert fhr.parameterize(V, F, faces=114).wavelets is None


# PY-3
def test_write_gives_the_files_of_fhr_run(fandisk, fandisk_run, tmp_path):
    V, F = fandisk
    p, out = fandisk_run
    p.write(str(tmp_path))
    for name in ("domain.off", "geodesics.obj", "refined.ply", "param.fhrp", "textured.obj"):
        assert (tmp_path / name).read_bytes() == (out / name).read_bytes(), name
    ours, theirs = (json.loads((d / "report.json").read_text()) for d in (tmp_path, out))
    assert ours.keys() == theirs.keys()
    assert all(ours[key] == theirs[key] for key in ours if key != "input")  # domain, partition, §4, oracle
    assert {**ours["input"], "path": None} == {**theirs["input"], "path": None}  # arrays have no file name


# PY-3
def test_verify_a_parameterization_object(fandisk, fandisk_run):
    V, F = fandisk
    p, out = fandisk_run
    assert fhr.verify(p) == fhr.verify(str(out / "param.fhrp"), mesh=(V, F))


# PY-4
def test_a_given_domain_is_kept(fandisk):
    V, F = fandisk
    DV, DF, t_vertex = fhr.decimate(V, F, 200)
    p = fhr.parameterize(V, F, domain=(DV, DF, t_vertex))
    assert p.certified
    assert np.array_equal(p.domain[1], DF) and np.array_equal(p.domain[0], DV)
    with pytest.raises(fhr.InvalidInput, match="exactly one of faces and domain"):
        fhr.parameterize(V, F, faces=114, domain=(DV, DF, t_vertex))
    with pytest.raises(fhr.InvalidInput, match="not a vertex of T"):
        fhr.parameterize(V, F, domain=(DV, DF, np.full(len(DV), len(V))))


# PY-3, PY-4: the atlas oracle on arrays gives the command's verdict on the same atlas as OBJ.
def test_verify_atlas_on_arrays_is_the_commands_verdict(fandisk, fandisk_run, tmp_path):
    V, F = fandisk
    _, out = fandisk_run
    lines = (out / "textured.obj").read_text().split("\n")
    TV = np.array([[float(x) for x in l.split()[1:4]] for l in lines if l.startswith("v ")])
    UV = np.array([[float(x) for x in l.split()[1:3]] for l in lines if l.startswith("vt ")])
    corners = [[c.split("/") for c in l.split()[1:4]] for l in lines if l.startswith("f ")]
    TF = np.array([[int(c[0]) - 1 for c in f] for f in corners])
    FUV = np.array([[int(c[1]) - 1 for c in f] for f in corners])
    ours = fhr.verify_atlas(TV, TF, UV, FUV, mesh=(V, F))
    theirs = json.loads(cli("verify", out / "textured.obj", "--mesh", FANDISK, "--json").stdout)
    assert ours["valid"] and ours["kind"] == "atlas"
    checks = lambda d: [{k: v for k, v in c.items() if k != "first_failure"} for c in d["checks"]]
    assert checks(ours) == checks(theirs)
    assert ours["distortion"] == theirs["distortion"]
    assert ours["charts"] == theirs["charts"] == 114
    assert fhr.verify(str(out / "textured.obj"), mesh=(V, F)) == {k: theirs[k] for k in theirs if k not in ("file", "mesh")}
    # A corner moved far: a fold, named as the command names it.
    UV[FUV[7, 0]] = [5.0, 5.0]
    bad = fhr.verify_atlas(TV, TF, UV, FUV, lists=True)
    assert not bad["valid"] and 7 in bad["folded_face_list"] + [f for p in bad["overlapping_pair_list"] for f in p]


# PY-2: bad atlas arrays are InvalidInput, naming the array.
def test_verify_atlas_refuses_bad_arrays():
    V = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0]])
    F = np.array([[0, 1, 2]])
    assert fhr.verify_atlas(V, F, V[:, :2])["valid"]  # per-vertex UV
    with pytest.raises(fhr.InvalidInput, match="UV"):
        fhr.verify_atlas(V, F, np.array([[0.0, 0.0], [np.nan, 0.0], [0.0, 1.0]]))
    with pytest.raises(fhr.InvalidInput, match="face 0"):
        fhr.verify_atlas(V, F, V[:, :2], FUV=np.array([[0, 1, 7]]))
    with pytest.raises(fhr.InvalidInput, match="textures"):
        fhr.verify_atlas(V, F, V[:, :2], textures=np.array([0, 1]))


# PY-3, PY-4: a per-vertex map (spec/vertex_map.md) on arrays and from a file gives the command's
# verdict; fhr's own map of T′ onto D, each vertex of T′ with the β of a face holding it.
def test_verify_vertex_map_on_arrays_and_files(fandisk_run, tmp_path):
    p, out = fandisk_run
    DV, DF = p.domain
    V, F = p.refined
    faces = np.full(len(V), -1)
    weights = np.zeros((len(V), 3))
    for f, corners in enumerate(F):
        for c in range(3):
            faces[corners[c]] = p.face_patch[f]
            weights[corners[c]] = p.face_beta[f][c]
    ours = fhr.verify_vertex_map(V, F, DV, DF, faces, weights, lists=True)
    assert ours["valid"] and ours["kind"] == "vertex_map" and ours["folded_face_list"] == []
    fhr.write_mesh(str(tmp_path / "D.off"), DV, DF)
    fhr.write_mesh(str(tmp_path / "T.off"), V, F)
    lines = ["fhr-vertex-map 1", str(len(V))] + ["%d %r %r %r" % (d, *w) for d, w in zip(faces, weights.tolist())]
    (tmp_path / "m.vmap").write_text("\n".join(lines) + "\n")
    command = json.loads(cli("verify", "--vertex-map", tmp_path / "m.vmap", "--domain", tmp_path / "D.off",
                             "--mesh", tmp_path / "T.off", "--json").stdout)
    for key in ("file", "mesh", "domain_file"):
        command.pop(key)
    from_file = fhr.verify_vertex_map(str(tmp_path / "m.vmap"), mesh=(V, F), domain=(DV, DF))
    assert from_file["checks"] == command["checks"]
    assert from_file["distortion"] == command["distortion"]
    # One vertex without an image: a ValueError-free verdict naming it (VMAP-2).
    faces[5] = -1
    broken = fhr.verify_vertex_map(V, F, DV, DF, faces, weights)
    assert broken["first_failure"] == "VMAP-2" and broken["checks"][0]["vertex"] == 5
    with pytest.raises(ValueError, match="weights must have shape"):
        fhr.verify_vertex_map(V, F, DV, DF, faces, weights[:-1])


# PY-8
def page_data(path):
    """The JSON document a page embeds (spec/page.md PAGE-3)."""
    html = Path(path).read_text(encoding="utf-8")
    start = html.index('<script id="fhr-data" type="application/json">') + len('<script id="fhr-data" type="application/json">')
    data = json.loads(html[start:html.index("</script>", start)])
    del data["timings"]
    del data["report"]["input"]["path"]
    return data


def test_write_html_is_the_page_of_fhr_run(fandisk, tmp_path):
    if not fhr.page_available():
        pytest.fail("this build holds no page: ./run configures it with -Dpage=enabled")
    out = tmp_path / "cli"
    cli("run", FANDISK, "--faces", 114, "--levels", 2, "--keep", 5, "--html", "--out", out)
    V, F = fandisk
    p = fhr.parameterize(V, F, faces=114, levels=2, keep=[5])
    p.write_html(str(tmp_path / "fandisk.html"))
    python, command = page_data(tmp_path / "fandisk.html"), page_data(out / "index.html")
    assert python["format"] == "fhr-page 1" and python["title"] == "fandisk"
    assert python == command
    with pytest.raises(ValueError, match="up must be"):
        p.write_html(str(tmp_path / "x.html"), up="w")
    with pytest.raises(ValueError, match="at least 1000 faces"):
        p.write_html(str(tmp_path / "x.html"), page_faces=10)
    assert not (tmp_path / "x.html").exists()
