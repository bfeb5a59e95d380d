"""The atlas oracle (`fhr verify` on an atlas, spec/atlas.md) against the independent exact checker
atlas_reference.py, written apart from it: on fhr's own textured.obj (valid), on atlases with
planted folds and overlaps, and as a property over random meshes of several genera projected
onto a plane (folds, overlaps and contacts by the hundred), the sets of folded faces, overlapping
pairs and contacts must be equal, and the distortion figures (spec/distortion.md) agree within
stated tolerances. Run with Debian's /usr/bin/python3; FHR names the built `fhr` and
FHR_CGAL_MESHES the libcgal-demo meshes."""
import json
import os
import random
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from programs import fhr, mesh  # noqa: E402
import atlas_reference  # noqa: E402


def oracle(path, *extra):
    proc = fhr("verify", path, "--json", "--list", *extra, check=False)
    assert proc.returncode in (0, 1), proc.stderr
    verdict = json.loads(proc.stdout)
    assert verdict["kind"] == "atlas"
    assert (proc.returncode == 0) == verdict["valid"]
    return verdict


def assert_same_figures(ours, theirs):
    """The sets exactly; the figures within tolerances: the distortion's σ to 1e-9 relative (both
    compute it in double, by different formulas: the Gram matrices here, an SVD there), the
    percentiles to 1e-6 (neighbouring faces may be picked where a running sum ties), the packing to
    1e-9 (a slab union here, GEOS there)."""
    assert ours["folded_face_list"] == theirs["folded_faces"]
    assert [tuple(p) for p in ours["overlapping_pair_list"]] == [tuple(p) for p in theirs["overlapping_pairs"]]
    assert [tuple(p) for p in ours["contact_list"]] == [tuple(p) for p in theirs["contacts"]]
    assert ours["charts"] == theirs["charts"]
    assert ours["mirrored_charts"] == theirs["mirrored_charts"]
    a, b = ours["distortion"], theirs["distortion"]
    assert a["degenerate"] == b["degenerate"]
    for key in ("l2_stretch", "linf_stretch", "symmetric_dirichlet"):
        assert a[key] == pytest.approx(b[key], rel=1e-9), key
    for key in ("p50", "p99", "p999", "max"):
        assert a["anisotropy"][key] == pytest.approx(b["anisotropy"][key], rel=1e-6), key
    assert a["anisotropy"]["above_10"] == b["anisotropy"]["above_10"]
    assert a["area_distortion"]["max"] == pytest.approx(b["area_distortion"]["max"], rel=1e-9)
    for key in ("packing_unit_square", "packing_bounding_square", "seam_length"):
        assert ours[key] == pytest.approx(theirs[key], rel=1e-9, abs=1e-12), key


def reference(path):
    return atlas_reference.analyze(atlas_reference.read_atlas(path))


@pytest.fixture(scope="module")
def fandisk_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("fandisk")
    fhr("run", mesh("fandisk.off"), "--faces", "114", "--out", out)
    return out


def texel_densities(run):
    """Per patch: √(UV area / surface area) of textured.obj's faces of that patch (the patch of each
    face from param.fhrp, whose faces textured.obj keeps in order)."""
    tokens = open(run / "param.fhrp").read().split()  # spec/param.md: "fhr-param 1", then counted blocks
    at = 2
    counts = {}
    for name, width in (("domain_vertices", 3), ("domain_faces", 3), ("surface_vertices", 3)):
        assert tokens[at] == name
        counts[name] = int(tokens[at + 1])
        at += 2 + width * counts[name]
    assert tokens[at] == "surface_faces"
    n_sf = int(tokens[at + 1])
    at += 2
    patch = [int(tokens[at + 13 * f + 3]) for f in range(n_sf)]
    v, vt, faces = [], [], []
    for line in open(run / "textured.obj"):
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            v.append(tuple(map(float, t[1:4])))
        elif t[0] == "vt":
            vt.append(tuple(map(float, t[1:3])))
        elif t[0] == "f":
            faces.append([tuple(int(x) - 1 for x in c.split("/")[:2]) for c in t[1:4]])
    assert len(faces) == n_sf
    uv_area, surface = {}, {}
    for f, corners in enumerate(faces):
        (a, ta), (b, tb), (c, tc) = corners
        ab = [v[b][i] - v[a][i] for i in range(3)]
        ac = [v[c][i] - v[a][i] for i in range(3)]
        cross = (ab[1] * ac[2] - ab[2] * ac[1], ab[2] * ac[0] - ab[0] * ac[2], ab[0] * ac[1] - ab[1] * ac[0])
        surface[patch[f]] = surface.get(patch[f], 0.0) + 0.5 * sum(x * x for x in cross) ** 0.5
        u = (vt[tb][0] - vt[ta][0]) * (vt[tc][1] - vt[ta][1]) - (vt[tb][1] - vt[ta][1]) * (vt[tc][0] - vt[ta][0])
        uv_area[patch[f]] = uv_area.get(patch[f], 0.0) + 0.5 * u
    return [(uv_area[d] / surface[d]) ** 0.5 for d in sorted(surface)]


def assert_usable_atlas(run, surface):
    """textured.obj as one can texture with it (spec/cli.md CLI-RUN-1): valid against its input,
    no mirrored chart, no contact, one chart per patch, the same texel density in every chart
    within 1 %, the anisotropy of the map (per face: each chart is its domain triangle, scaled),
    an L2 stretch at most 1 % above the map's own."""
    ours = oracle(run / "textured.obj", "--mesh", surface, "--no-mirror", "--strict")
    assert ours["valid"], ours["first_failure"]
    param = json.loads(fhr("verify", run / "param.fhrp", "--json").stdout)
    assert ours["charts"] == param["domain"]["faces"] and ours["mirrored_charts"] == 0 and ours["contacts"] == 0
    densities = texel_densities(run)
    assert max(densities) / min(densities) <= 1.01
    assert ours["distortion"]["anisotropy"]["max"] == pytest.approx(param["distortion"]["anisotropy"]["max"], rel=1e-6)
    assert ours["distortion"]["l2_stretch"] <= 1.01 * param["distortion"]["l2_stretch"]
    assert_same_figures(ours, reference(run / "textured.obj"))
    return ours


# ATLAS-2..8: fhr's own atlas is valid, also against its input mesh, and usable; the fandisk's charts
# fill at least 60 % of the unit square.
def test_fhr_textured_obj_of_the_fandisk_is_valid(fandisk_run):
    ours = assert_usable_atlas(fandisk_run, mesh("fandisk.off"))
    assert ours["charts"] == 114
    assert ours["packing_unit_square"] >= 0.6


def test_fhr_textured_obj_of_a_genus_3_mesh_is_valid(tmp_path):
    surface = tmp_path / "g3.off"
    fhr("generate", "--genus", "3", "--faces", "3000", "--seed", "5", "--out", surface)
    fhr("run", surface, "--faces", "200", "--out", tmp_path / "run")
    assert_usable_atlas(tmp_path / "run", surface)


def planted(source, target, moves):
    """A copy of an OBJ atlas with some `vt` lines replaced: moves maps a 0-based vt to (u, v)."""
    lines, k = [], 0
    for line in open(source):
        if line.startswith("vt "):
            if k in moves:
                line = "vt %.17g %.17g\n" % moves[k]
            k += 1
        lines.append(line)
    open(target, "w").write("".join(lines))


# ATLAS-4, ATLAS-6: faults planted in a real atlas are found, the same by both checkers.
def test_planted_folds_and_overlaps_in_fhr_atlas(fandisk_run, tmp_path):
    source = fandisk_run / "textured.obj"
    uv = [tuple(map(float, line.split()[1:3])) for line in open(source) if line.startswith("vt ")]
    rng = random.Random(3)
    moves = {}
    for k in rng.sample(range(len(uv)), 12):
        u, v = uv[k]
        moves[k] = (u + rng.uniform(-0.05, 0.05), v + rng.uniform(-0.05, 0.05))
    bad = tmp_path / "bad.obj"
    planted(source, bad, moves)
    ours = oracle(bad)
    assert not ours["valid"]
    assert ours["folded_faces"] + ours["overlapping_pairs"] > 0
    assert_same_figures(ours, reference(bad))


def projected_atlas(surface, target, axis_seed):
    """An atlas of `surface` (OFF) by parallel projection onto a random plane, one vt per vertex:
    faces seen from behind fold, and the two sides of the surface overlap."""
    rng = random.Random(axis_seed)
    text = open(surface).read().split()
    assert text[0] == "OFF"
    n, m = int(text[1]), int(text[2])
    values = text[4:]
    points = [tuple(float(x) for x in values[3 * i:3 * i + 3]) for i in range(n)]
    faces = [tuple(int(x) for x in values[3 * n + 4 * j + 1:3 * n + 4 * j + 4]) for j in range(m)]
    a = [rng.uniform(-1, 1) for _ in range(3)]
    b = [rng.uniform(-1, 1) for _ in range(3)]
    with open(target, "w") as out:
        for p in points:
            out.write("v %.17g %.17g %.17g\n" % p)
        for p in points:
            out.write("vt %.17g %.17g\n" % (sum(x * y for x, y in zip(a, p)), sum(x * y for x, y in zip(b, p))))
        for f in faces:
            out.write("f %d/%d %d/%d %d/%d\n" % tuple(i + 1 for i in f for _ in range(2)))


# ATLAS-4, -6, -7 and DIST-*: a property over random meshes of genus 0-3, with and without boundary.
@pytest.mark.parametrize("genus,holes,seed", [(0, 0, 1), (1, 0, 2), (2, 0, 3), (3, 0, 4), (0, 2, 5), (1, 3, 6)])
def test_projected_random_meshes_agree_with_the_exact_reference(tmp_path, genus, holes, seed):
    surface = tmp_path / "s.off"
    fhr("generate", "--genus", genus, "--holes", holes, "--faces", 600 + 48 * genus, "--seed", seed, "--out", surface)
    path = tmp_path / "projected.obj"
    projected_atlas(surface, path, seed)
    ours = oracle(path, "--mesh", surface)
    theirs = reference(path)
    if theirs["degenerate_uv"]:  # ATLAS-3 fails: the oracle then skips the pair checks
        assert ours["first_failure"] == "ATLAS-3"
        return
    assert ours["folded_faces"] > 0 and ours["overlapping_pairs"] > 0
    assert_same_figures(ours, theirs)


# CLI-RUN-2, DIST-*: fhr run's report gives the distortion fhr verify measures on its param.fhrp.
def test_run_report_distortion_is_the_oracles(fandisk_run):
    report = json.loads((fandisk_run / "report.json").read_text())["parameterization"]["distortion"]
    verdict = json.loads(fhr("verify", fandisk_run / "param.fhrp", "--json").stdout)
    worst = report.pop("worst_patches")
    assert report == verdict["distortion"]
    assert len(worst) == 5
    assert worst[0]["max_anisotropy"] == verdict["distortion"]["anisotropy"]["max"]
    assert all(a["max_anisotropy"] >= b["max_anisotropy"] for a, b in zip(worst, worst[1:]))
    assert sum(w["faces_above_10"] for w in worst) <= verdict["distortion"]["anisotropy"]["above_10"]


SQUARE = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"


def write(path, text):
    path.write_text(text)
    return path


# CLI-VERIFY-1..5 for an atlas: exit codes, the verdict line, the JSON keys, --kind, --strict, --no-mirror.
def test_atlas_verdicts_on_the_command_line(tmp_path):
    good = write(tmp_path / "good.obj", SQUARE + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
    proc = fhr("verify", good, check=False)
    assert proc.returncode == 0 and proc.stdout.startswith("%s: valid\n" % good)
    assert "ATLAS-7" in proc.stdout and proc.stderr == ""
    verdict = json.loads(fhr("verify", good, "--json").stdout)
    for key in ("file", "mesh", "kind", "rule", "readable", "valid", "first_failure", "domain", "surface", "checks",
                "distortion", "charts", "mirrored_charts", "folded_faces", "overlapping_pairs", "contacts", "seam_length",
                "packing_unit_square", "packing_bounding_square"):
        assert key in verdict, key
    assert verdict["rule"] is None and verdict["domain"] is None and "folded_face_list" not in verdict
    assert all({"chart", "u", "v"} <= set(c) for c in verdict["checks"])
    # --kind param reads it as a fhr-param file: unreadable.
    assert fhr("verify", good, "--kind", "param", check=False).returncode == 2
    # A fold: exit 1, the verdict names the check, the face, the chart.
    fold = write(tmp_path / "fold.obj", SQUARE + "vt 0 0\nvt 1 0\nvt 1 1\nvt 0.9 0.2\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
    proc = fhr("verify", fold, check=False)
    assert proc.returncode == 1
    assert proc.stdout.splitlines()[0].startswith("%s: INVALID: ATLAS-4: face 1 of chart 0 is folded" % fold)
    first = next(c for c in json.loads(fhr("verify", fold, "--json", check=False).stdout)["checks"] if c["id"] == "ATLAS-4")
    assert (first["result"], first["face"], first["chart"]) == ("fail", 1, 0) and first["u"] is not None
    # A mirrored chart: valid; invalid with --no-mirror.
    mirrored = write(tmp_path / "mirror.obj", SQUARE + "vt 0 0\nvt -1 0\nvt -1 1\nvt 0 1\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n")
    assert fhr("verify", mirrored, check=False).returncode == 0
    assert fhr("verify", mirrored, "--no-mirror", check=False).returncode == 1
    # Two charts touching at a corner: info (valid), invalid with --strict.
    touch = write(tmp_path / "touch.obj", SQUARE + "vt 0 0\nvt 1 0\nvt 1 1\nvt 2 2\nvt 3 2\nvt 2 3\nvt 1 1\n"
                  "f 1/1 2/2 3/3\nf 1/7 3/5 4/6\n")
    proc = fhr("verify", touch, check=False)
    assert proc.returncode == 0, proc.stdout
    assert "info" in next(l for l in proc.stdout.splitlines() if "ATLAS-7" in l)
    assert fhr("verify", touch, "--strict", check=False).returncode == 1


# CLI-VERIFY-3: an unreadable atlas is one error line and exit code 2, no verdict.
@pytest.mark.parametrize("text,says", [
    (SQUARE + "vt 0 0\nf 1/1 2/1 3\n", "corner 2 has no texture coordinates"),
    (SQUARE + "vt 0 nan\nf 1/1 2/1 3/1\n", "not finite"),
    (SQUARE + "vt 0 0\nf 1/1 2/1 9/1\n", "out of range"),
    (SQUARE + "vt 0 0\nf 1/1 2/1 3/1 4/1\n", "has 4 corners"),
    ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
     "property float u\nproperty float v\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
     "0 0 0 0 0\n1 0 0 1 0\n", "truncated"),
])
def test_unreadable_atlas(tmp_path, text, says):
    bad = write(tmp_path / ("bad.ply" if text.startswith("ply") else "bad.obj"), text)
    proc = fhr("verify", bad, check=False)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and proc.stderr.startswith("fhr: error: %s" % bad) and says in proc.stderr
    j = json.loads(fhr("verify", bad, "--json", check=False).stdout)
    assert j["readable"] is False and says in j["error"]
