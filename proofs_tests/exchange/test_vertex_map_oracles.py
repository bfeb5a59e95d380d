"""The per-vertex map oracle (`fhr verify --vertex-map`, spec/vertex_map.md) against the independent
exact checker vertex_map_reference.py, written apart from it from the specification alone.

Fixtures come from fhr's own maps (vertex_map_fixtures.py): every vertex of T′ with the β of a
face of T′ holding it — the rule `adjacent` then reproduces fhr's map, valid in every format — and
the same map given on the vertices of T only, a different map whose edges cross the curves and
take the rule's fans. On each, and on planted faults (two distant vertices swapped, one vertex
moved across an edge of D), the two checkers must agree on the verdict, the set of folded faces,
the edges without an image and the number of crossing pairs. Run with Debian's /usr/bin/python3;
FHR names the built `fhr` and FHR_CGAL_MESHES the libcgal-demo meshes."""
import json
import os
import sys

import pytest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from programs import fhr, mesh  # noqa: E402
import vertex_map_fixtures as fixtures  # noqa: E402
import vertex_map_reference as reference  # noqa: E402

FORMATS = (".vmap", ".corr", ".vtpm", ".ijv")


def oracle(map_path, domain, mesh):
    proc = fhr("verify", "--vertex-map", map_path, "--domain", domain, "--mesh", mesh, "--json", "--list", check=False)
    assert proc.returncode in (0, 1), proc.stderr
    verdict = json.loads(proc.stdout)
    assert verdict["kind"] == "vertex_map" and verdict["rule"] == "adjacent"
    assert (proc.returncode == 0) == verdict["valid"]
    return verdict


def judge(map_path, domain, mesh):
    """The reference's verdict, with the oracle's counterpart keys."""
    r = reference.judge(str(map_path), str(domain), str(mesh))
    valid = not any(r[k] for k in ("vertices_without_image", "edges_without_image", "crossing_pairs",
                                   "coincident_vertices", "folded_faces", "winding_failures"))
    valid = valid and not r["boundary_failures"]["edges"] and not r["boundary_failures"]["vertices"]
    return r, valid


def assert_agree(map_path, domain, mesh):
    ours = oracle(map_path, domain, mesh)
    theirs, valid = judge(map_path, domain, mesh)
    assert ours["folded_face_list"] == theirs["folded_faces"]
    assert ours["edges_without_image_list"] == theirs["edges_without_image"]
    assert ours["crossing_pairs"] == len(theirs["crossing_pairs"]) + len(theirs["coincident_vertices"])
    assert ours["valid"] == valid
    return ours, theirs


def fixture_dir(tmp_path_factory, name, source, faces):
    out = tmp_path_factory.mktemp(name)
    fhr("run", source, "--faces", faces, "--out", out / "run")
    fixtures.write_fixtures(out / "run" / "param.fhrp", out, source)
    return out


@pytest.fixture(scope="module")
def genus1(tmp_path_factory):
    src = tmp_path_factory.mktemp("g1") / "g1.off"
    fhr("generate", "--genus", "1", "--faces", "800", "--seed", "3", "--out", src)
    return fixture_dir(tmp_path_factory, "genus1", src, 40)


@pytest.fixture(scope="module")
def genus3_holes(tmp_path_factory):
    src = tmp_path_factory.mktemp("g3") / "g3.off"
    fhr("generate", "--genus", "3", "--holes", "2", "--faces", "1200", "--seed", "5", "--out", src)
    return fixture_dir(tmp_path_factory, "genus3", src, 60)


@pytest.mark.parametrize("which", ["genus1", "genus3_holes"])
@pytest.mark.parametrize("ext", FORMATS)
def test_fhr_maps_on_t_prime_are_valid_in_every_format(request, which, ext):
    d = request.getfixturevalue(which)
    ours, _ = assert_agree(d / ("Tprime" + ext), d / "D.off", d / "Tprime.off")
    assert ours["valid"], ours["first_failure"]
    assert ours["format"] == {".vmap": "plain", ".corr": "corr", ".vtpm": "vtpm", ".ijv": "ijv"}[ext]
    assert ours["distortion"]["l2_stretch"] >= 1


@pytest.mark.parametrize("which", ["genus1", "genus3_holes"])
def test_the_same_maps_on_the_vertices_of_t_agree(request, which):
    d = request.getfixturevalue(which)
    assert_agree(d / "T_only.vmap", d / "D.off", d / "T.off")


def test_two_distant_vertices_swapped_are_named(genus1, tmp_path):
    vmap = fixtures.read_plain_map(genus1 / "Tprime.vmap")
    a, b = 7, len(vmap) - 7
    fixtures.write_map(tmp_path / "swapped.vmap", fixtures.swap(vmap, a, b), fixtures.read_off(genus1 / "D.off")[1], 0)
    ours, theirs = assert_agree(tmp_path / "swapped.vmap", genus1 / "D.off", genus1 / "Tprime.off")
    assert not ours["valid"] and ours["first_failure"] in ("VMAP-5", "VMAP-6")  # far apart: edges without a fan
    # Every edge at a or b now joins distant points: no fan holds it, and only those edges.
    assert ours["edges_without_image_list"]
    assert all(a in e or b in e for e in ours["edges_without_image_list"])
    faces = fixtures.read_off(genus1 / "Tprime.off")[1]
    assert sum(1 for f in faces if a in f) + sum(1 for f in faces if b in f) == len(ours["edges_without_image_list"])


def test_a_vertex_moved_across_a_domain_edge_is_named(genus1, tmp_path):
    vmap = fixtures.read_plain_map(genus1 / "Tprime.vmap")
    positions, dfaces = fixtures.read_off(genus1 / "D.off")
    v = next(i for i, (d, w) in enumerate(vmap) if min(w) > 0.01)  # well inside its patch
    fixtures.write_map(tmp_path / "moved.vmap", fixtures.move_across_edge(vmap, dfaces, v), dfaces, len(positions))
    ours, _ = assert_agree(tmp_path / "moved.vmap", genus1 / "D.off", genus1 / "Tprime.off")
    assert not ours["valid"]
    faces = fixtures.read_off(genus1 / "Tprime.off")[1]
    assert any(v in faces[f] for f in ours["folded_face_list"])


def test_the_bulls_map_on_its_own_vertices_folds_and_both_checkers_name_the_same_faces(tmp_path_factory):
    d = fixture_dir(tmp_path_factory, "bull", mesh("bull.off"), 100)
    assert oracle(d / "Tprime.vmap", d / "D.off", d / "Tprime.off")["valid"]
    ours, _ = assert_agree(d / "T_only.vmap", d / "D.off", d / "T.off")
    assert ours["folded_faces"] > 0 and ours["crossing_pairs"] > 0


def test_vertex_map_command_line(genus1, tmp_path):
    d = genus1
    human = fhr("verify", "--vertex-map", d / "Tprime.corr", "--domain", d / "D.off", "--mesh", d / "Tprime.off")
    assert human.stdout.startswith(str(d / "Tprime.corr") + ": valid")
    assert "VMAP-7    pass" in human.stdout
    bad = tmp_path / "bad.corr"
    bad.write_text("1 0.5 0.5\n")
    proc = fhr("verify", "--vertex-map", bad, "--domain", d / "D.off", "--mesh", d / "Tprime.off", check=False)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "bad.corr:1" in proc.stderr
    proc = fhr("verify", "--vertex-map", d / "Tprime.vmap", "--domain", d / "D.off", "--mesh", d / "Tprime.off",
               "--rule", "geodesic", check=False)
    assert proc.returncode == 2 and "not implemented" in proc.stderr
    proc = fhr("verify", "--vertex-map", d / "Tprime.vmap", "--domain", d / "D.off", check=False)
    assert proc.returncode == 2 and "--mesh" in proc.stderr
    plain = tmp_path / "map.txt"
    plain.write_text((d / "Tprime.vmap").read_text())
    proc = fhr("verify", "--vertex-map", plain, "--domain", d / "D.off", "--mesh", d / "Tprime.off", check=False)
    assert proc.returncode == 2 and "--format" in proc.stderr
    assert fhr("verify", "--vertex-map", plain, "--domain", d / "D.off", "--mesh", d / "Tprime.off",
               "--format", "plain").returncode == 0
