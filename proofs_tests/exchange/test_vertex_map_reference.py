"""Checks of the Python per-vertex map reference (vertex_map_reference.py, spec/vertex_map.md) on
small meshes written here, each verdict worked out by hand: identity maps in the four formats,
folds, swapped entries, edges without an image, coincident images, boundaries, refinements of D
whose edges cross D's, and the readers (VMAP-1, VMAP-2); and of the fixture writer
(vertex_map_fixtures.py) on a tiny `fhr-param 1` file.

Run with Debian's interpreter:
/usr/bin/python3 -m pytest proofs_tests/exchange/test_vertex_map_reference.py -q -p no:cacheprovider
"""

import json
import math
import subprocess
import sys
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import vertex_map_fixtures as fx  # noqa: E402
import vertex_map_reference as vmr  # noqa: E402

SCRIPT = HERE / "vertex_map_reference.py"

CLEAN = {"vertices_without_image": [], "edges_without_image": [], "crossing_pairs": [],
         "coincident_vertices": [], "folded_faces": [], "winding_failures": [],
         "boundary_failures": {"edges": [], "vertices": []}}

# a tetrahedron, faces counter-clockwise seen from outside
TET_P = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
TET_F = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
# a regular octahedron: equator 0..3, poles 4 (+z) and 5 (-z)
OCT_P = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 0.0, 0.0), (0.0, -1.0, 0.0), (0.0, 0.0, 1.0),
         (0.0, 0.0, -1.0)]
OCT_F = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4), (1, 0, 5), (2, 1, 5), (3, 2, 5), (0, 3, 5)]
# the unit square in z = 0, as two triangles along the diagonal 0-2
SQ_P = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)]
SQ_F = [(0, 1, 2), (0, 2, 3)]
# a strip of four unit squares: bottom vertices 0..4 at (i, 0), top 5..9 at (i, 1)
STRIP_P = [(float(i), 0.0, 0.0) for i in range(5)] + [(float(i), 1.0, 0.0) for i in range(5)]
STRIP_F = [f for i in range(4) for f in ((i, i + 1, i + 6), (i, i + 6, i + 5))]
# a 4 x 4 grid of vertices (i, j) = 4j + i, each square cut along its diagonal (i, j)-(i+1, j+1)
GRID_P = [(float(i), float(j), 0.0) for j in range(4) for i in range(4)]
GRID_F = [f for j in range(3) for i in range(3)
          for f in ((4 * j + i, 4 * j + i + 1, 4 * j + i + 5), (4 * j + i, 4 * j + i + 5, 4 * j + i + 4))]


def identity(positions, faces):
    """Every vertex onto itself: the first face at it, weight 1 on its corner."""
    out = []
    for v in range(len(positions)):
        f = next(i for i, tri in enumerate(faces) if v in tri)
        out.append((f, tuple(1.0 if c == v else 0.0 for c in faces[f])))
    return out


def judge(tmp_path, T, D, vmap, ext=".vmap"):
    fx.write_off(tmp_path / "T.off", *T)
    fx.write_off(tmp_path / "D.off", *D)
    fx.write_map(tmp_path / ("map" + ext), vmap, D[1], len(D[0]))
    return vmr.judge(tmp_path / ("map" + ext), tmp_path / "D.off", tmp_path / "T.off")


def verdict(result):
    return {k: v for k, v in result.items() if k not in ("vertices", "faces")}


def with_changes(**changes):
    out = dict(CLEAN)
    out.update(changes)
    return out


# ---------------------------------------------------------------------------------------------
# Valid maps

@pytest.mark.parametrize("ext", [".vmap", ".corr", ".vtpm", ".ijv"])
def test_identity_of_a_tetrahedron_in_every_format(tmp_path, ext):
    result = judge(tmp_path, (TET_P, TET_F), (TET_P, TET_F), identity(TET_P, TET_F), ext)
    assert (result["vertices"], result["faces"]) == (4, 4)
    assert verdict(result) == CLEAN


def test_identity_of_a_square_with_boundary(tmp_path):
    assert verdict(judge(tmp_path, (SQ_P, SQ_F), (SQ_P, SQ_F), identity(SQ_P, SQ_F))) == CLEAN


def test_other_diagonal_maps_through_a_fan(tmp_path):
    # T's diagonal 1-3 crosses D's diagonal 0-2: its image is the segment through the fan of
    # both faces around 0 (or 2); the corner (0; 1, 3) is decided in the unfolding around 0
    T = (SQ_P, [(0, 1, 3), (1, 2, 3)])
    assert verdict(judge(tmp_path, T, (SQ_P, SQ_F), identity(SQ_P, SQ_F))) == CLEAN
    D = vmr.Manifold(vmr.Mesh(SQ_P, SQ_F), "D")
    image = vmr.map_edge(D, vmr.resolve(("face", 0, (0.0, 1.0, 0.0)), D)[0],
                         vmr.resolve(("face", 1, (0.0, 0.0, 1.0)), D)[0])
    assert len(image.points) == 3
    assert image.points[1] == {0: 0.5, 2: 0.5}  # the crossing with the spoke 0-2, exactly


def test_the_shortest_valid_candidate_is_the_image(tmp_path):
    # the octahedron with vertex 0 pushed out to x = 2: from the pole 4 to the pole 5 the fans
    # cross one of the equator's edges; the shortest crosses 1-2 (or 2-3, its mirror image) at
    # its midpoint, the foot of the perpendicular from the pole; those at 0 are longer
    P = [(2.0, 0.0, 0.0)] + OCT_P[1:]
    D = vmr.Manifold(vmr.Mesh(P, OCT_F), "D")
    north = vmr.resolve(("face", 0, (0.0, 0.0, 1.0)), D)[0]
    south = vmr.resolve(("face", 4, (0.0, 0.0, 1.0)), D)[0]
    image = vmr.map_edge(D, north, south)
    assert len(image.points) == 3
    crossing = image.points[1]
    assert set(crossing) in ({1, 2}, {2, 3})
    assert abs(float(crossing[2]) - 0.5) < 1e-15


# D: two triangles (0, 1, 2), (1, 0, 3) along the interior edge 0-1 (a = (0, 0), b = (2, 0),
# c = (1.5, 1), d = (1.5, -1)); T adds m = (1, 0) on that edge (vertex 4) and joins c-d, which
# crosses the edge 0-1 at (1.5, 0), between m and b.
REF_P = [(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (1.5, 1.0, 0.0), (1.5, -1.0, 0.0), (1.0, 0.0, 0.0)]
REF_T = (REF_P, [(0, 4, 2), (4, 3, 2), (3, 1, 2), (4, 0, 3)])
REF_D = (REF_P[:4], [(0, 1, 2), (1, 0, 3)])
REF_MAP = [(0, (1.0, 0.0, 0.0)), (0, (0.0, 1.0, 0.0)), (0, (0.0, 0.0, 1.0)), (1, (0.0, 0.0, 1.0)),
           (0, (0.5, 0.5, 0.0))]


def test_refinement_with_an_edge_across_an_edge_of_D(tmp_path):
    # the corner (4; 3, 2) has its tangents in the two faces: unfolded across the edge 0-1
    assert verdict(judge(tmp_path, REF_T, REF_D, REF_MAP)) == CLEAN


def test_vertex_on_an_edge_of_D_moved_past_a_crossing_folds(tmp_path):
    vmap = list(REF_MAP)
    vmap[4] = (0, (0.125, 0.875, 0.0))  # m at (1.75, 0): beyond the crossing of c-d
    assert verdict(judge(tmp_path, REF_T, REF_D, vmap)) == with_changes(
        crossing_pairs=[[[0, 4], [2, 3]]],  # c-d crosses the image of a-m
        folded_faces=[1],  # (m, d, c) turns clockwise at m
        winding_failures=[2, 3])  # at c and d the tangent to m now lies beyond the one to b


def test_corner_inside_an_edge_of_D_is_unfolded_across_it(tmp_path):
    # c = (-3, 1): the line c-d meets the line of a-b at x = -0.75, outside the edge, so c-d has
    # no image and the face (m, d, c) is judged at m alone, where its tangents (toward d in one
    # face, toward c in the other) turn by more than pi through the direction of b
    D = ([(0.0, 0.0, 0.0), (2.0, 0.0, 0.0), (-3.0, 1.0, 0.0), (1.5, -1.0, 0.0)], REF_D[1])
    assert verdict(judge(tmp_path, REF_T, D, REF_MAP)) == with_changes(
        edges_without_image=[[2, 3]], folded_faces=[1])


def test_corner_at_a_saddle_turns_through_the_spokes(tmp_path):
    # D: eight faces around vertex 0 with their rims alternately at z = +1 and -1, so that each
    # angle at 0 is about 98 degrees (785 in all). T: the two triangles (0, 1, 5) and (0, 5, 1).
    # From spoke 1 to spoke 5 is four faces either way, 392 degrees: the tangents' cross product
    # alone (sin 32 > 0) would call both corners at 0 convex; the spokes at 196 degrees do not.
    ring = [(math.cos(math.pi * i / 4), math.sin(math.pi * i / 4), 1.0 if i % 2 else -1.0)
            for i in range(8)]
    P = [(0.0, 0.0, 0.0)] + ring
    D = (P, [(0, i + 1, (i + 1) % 8 + 1) for i in range(8)])
    T = (P, [(0, 1, 5), (0, 5, 1)])
    vmap = identity(*D)
    # (T is closed, so its vertices 1 and 5 are interior and their images on the rim of D)
    assert verdict(judge(tmp_path, T, D, vmap)) == with_changes(
        edges_without_image=[[1, 5]], folded_faces=[0, 1],
        boundary_failures={"edges": [], "vertices": [1, 5]})


# ---------------------------------------------------------------------------------------------
# Broken maps

def test_fold_by_moving_one_vertex_of_a_tetrahedron(tmp_path):
    vmap = identity(TET_P, TET_F)
    vmap[3] = (0, (1 / 3, 1 / 3, 1 / 3))  # the apex onto the centroid of the face opposite it
    assert verdict(judge(tmp_path, (TET_P, TET_F), (TET_P, TET_F), vmap)) == with_changes(
        folded_faces=[1, 2, 3], winding_failures=[0, 1, 2, 3])


def test_fold_by_moving_a_vertex_across_an_edge_of_D(tmp_path):
    vmap = identity(GRID_P, GRID_F)
    f = GRID_F.index((5, 6, 10))
    vmap[5] = (f, (1.0, 0.0, 0.0))
    moved = fx.move_across_edge(vmap, GRID_F, 5, (6, 10), 0.01)
    assert moved[5] == (GRID_F.index((6, 11, 10)), (0.495, 0.01, 0.495))
    # 5 now lies at (2.01, 1.505): its edges to 0 and 4 have no fan, those to 1 and 9 cross 6-10
    assert verdict(judge(tmp_path, (GRID_P, GRID_F), (GRID_P, GRID_F), moved)) == with_changes(
        edges_without_image=[[0, 5], [4, 5]],
        crossing_pairs=[[[1, 5], [6, 10]], [[5, 9], [6, 10]]],
        folded_faces=[f],
        winding_failures=[6, 10])


def test_swapped_poles_reverse_every_face(tmp_path):
    vmap = fx.swap(identity(OCT_P, OCT_F), 4, 5)
    # every edge still maps onto an edge of D, but the map is a reflection
    assert verdict(judge(tmp_path, (OCT_P, OCT_F), (OCT_P, OCT_F), vmap)) == with_changes(
        folded_faces=list(range(8)), winding_failures=list(range(6)))


def test_edge_whose_ends_share_no_fan(tmp_path):
    vmap = identity(STRIP_P, STRIP_F)
    vmap[0] = (7, (1 / 3, 1 / 3, 1 / 3))  # into the last square (3, 9, 8)
    # its three edges have no image; everything that needs them is not judged
    assert verdict(judge(tmp_path, (STRIP_P, STRIP_F), (STRIP_P, STRIP_F), vmap)) == with_changes(
        edges_without_image=[[0, 1], [0, 5], [0, 6]])


def test_coincident_pair(tmp_path):
    vmap = identity(STRIP_P, STRIP_F)
    vmap[1] = vmap[2]  # (1, 0) onto (2, 0)
    result = verdict(judge(tmp_path, (STRIP_P, STRIP_F), (STRIP_P, STRIP_F), vmap))
    assert result["coincident_vertices"] == [[1, 2]]
    # 0 -> (2, 0) runs through the vertex (1, 0) of D: no valid fan
    assert result["edges_without_image"] == [[0, 1]]
    # 1-7 and 2-7 have one image; 1-6 and 1-7 leave (2, 0) beside 2's edges without sharing an end
    assert result["crossing_pairs"] == [[[1, 6], [2, 7]], [[1, 7], [2, 7]], [[1, 7], [2, 8]]]
    assert result["folded_faces"] == [2]  # (1, 2, 7) is flat: its corner at 1 has no tangent
    assert result["winding_failures"] == [2, 7]


def test_boundary_edge_pulled_inside(tmp_path):
    vmap = identity(SQ_P, SQ_F)
    vmap[1] = (0, (0.2, 0.6, 0.2))  # the corner (1, 0) into the face, at (0.8, 0.2)
    assert verdict(judge(tmp_path, (SQ_P, SQ_F), (SQ_P, SQ_F), vmap)) == with_changes(
        boundary_failures={"edges": [[0, 1], [1, 2]], "vertices": []})


def test_interior_vertex_on_the_boundary(tmp_path):
    P = SQ_P + [(0.5, 0.5, 0.0)]
    F = [(0, 1, 4), (1, 2, 4), (2, 3, 4), (3, 0, 4)]
    vmap = identity(P, F)
    vmap[4] = (0, (0.5, 0.5, 0.0))  # the centre onto the midpoint of the boundary edge 0-1
    result = verdict(judge(tmp_path, (P, F), (P, F), vmap))
    assert result["boundary_failures"] == {"edges": [], "vertices": [4]}
    assert result["crossing_pairs"] == [[[0, 1], [0, 4]], [[0, 1], [1, 4]], [[0, 1], [2, 4]],
                                        [[0, 1], [3, 4]]]
    assert result["folded_faces"] == [0]  # (0, 1, 4) is flat


# ---------------------------------------------------------------------------------------------
# Reading (VMAP-1 refuses, VMAP-2 judges)

def write_tet(tmp_path):
    fx.write_off(tmp_path / "T.off", TET_P, TET_F)
    fx.write_off(tmp_path / "D.off", TET_P, TET_F)


@pytest.mark.parametrize("name, text, message", [
    ("a.vmap", "fhr-vertex-map 1\n4\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", "3 records for 4"),
    ("b.vmap", "fhr-vertex-map 1\n4\n0 1 0 0\n0 0 1\n0 0 0 1\n1 0 0 1\n", "expected 4 tokens"),
    ("c.vmap", "fhr-vertex-map 2\n4\n", "fhr-vertex-map 1"),
    ("d.corr", "1 1 0 0\n1 0 1 x\n1 0 0 1\n2 0 0 1\n", "expected a number"),
    ("e.vtpm", "4 5\n0 2 0 0\n0 2 1 0\n0 2 0 1\n1 2 0 1\n", "the mesh has 4 vertices of D"),
    ("f.ijv", "1 1 1\n5 2 1\n", "vertex 5 of T out of range"),
    ("g.ijv", "1 1 0.5\n1 1 0.5\n", "named twice"),
    ("h.ijv", "1 1 0.25\n1 2 0.25\n1 3 0.25\n1 4 0.25\n", "more than three lines"),
])
def test_unreadable_maps_are_refused(tmp_path, name, text, message):
    write_tet(tmp_path)
    (tmp_path / name).write_text(text)
    with pytest.raises(ValueError, match=message):
        vmr.judge(tmp_path / name, tmp_path / "D.off", tmp_path / "T.off")
    run = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path / name), "--domain",
                          str(tmp_path / "D.off"), "--mesh", str(tmp_path / "T.off")],
                         capture_output=True, text=True)
    assert run.returncode == 2
    assert len(run.stderr.strip().splitlines()) == 1


def test_records_without_a_point_are_judged(tmp_path):
    write_tet(tmp_path)
    # 0: no entry; 1: NaN; 2: face out of range; 3: weights summing to 1 + 1e-9
    (tmp_path / "m.vmap").write_text(
        "fhr-vertex-map 1\n4\n-1 0 0 0\n0 nan 0 1\n9 1 0 0\n1 0 0 1.000000001\n")
    result = vmr.judge(tmp_path / "m.vmap", tmp_path / "D.off", tmp_path / "T.off")
    assert result["vertices_without_image"] == [0, 1, 2, 3]
    assert result["edges_without_image"] == [[0, 1], [0, 2], [0, 3], [1, 2], [1, 3], [2, 3]]


def test_tolerances_of_the_weights(tmp_path):
    D = vmr.Manifold(vmr.Mesh(TET_P, TET_F), "D")
    img, _ = vmr.resolve(("face", 0, (1.0 + 1e-13, -1e-13, 1e-13)), D)
    assert img.carrier == (0, 1)  # the weight below zero is read as 0; the rest normalized
    assert sum(img.w.values()) == 1
    assert vmr.resolve(("face", 0, (1.0 + 2e-12, -2e-12, 0.0)), D)[0] is None
    assert vmr.resolve(("face", 0, (1.0, 2e-12, 0.0)), D)[0] is None
    # vtpm: the halfedge 2 -> 1 has face 0 = (0, 2, 1) to its left; h2 = 0
    img, _ = vmr.resolve(("halfedge", 2, 1, 0.25, 0.5), D)
    assert (img.d, img.w) == (0, {2: 0.25, 1: 0.25, 0: 0.5})
    assert vmr.resolve(("halfedge", 1, 2, 0.25, 0.5), D)[0].d == 3  # (1, 2, 3)
    # ijv: two named vertices on an edge of D; three that are not a face
    img, _ = vmr.resolve(("vertices", [(3, 0.5), (1, 0.5)]), D)
    assert img.carrier == (1, 3)
    P = [(float(i), 0.0, 0.0) for i in range(3)] + [(0.0, 1.0, 0.0)]
    flat = vmr.Manifold(vmr.Mesh(P, [(0, 1, 3), (1, 2, 3)]), "D")
    assert vmr.resolve(("vertices", [(0, 0.5), (2, 0.5)]), flat)[0] is None


def test_cli_prints_one_json_object(tmp_path):
    write_tet(tmp_path)
    fx.write_map(tmp_path / "m.ijv", identity(TET_P, TET_F), TET_F, 4)
    run = subprocess.run([sys.executable, str(SCRIPT), str(tmp_path / "m.ijv"), "--domain",
                          str(tmp_path / "D.off"), "--mesh", str(tmp_path / "T.off"), "--json"],
                         capture_output=True, text=True, check=True)
    assert run.stdout.count("\n") == 1
    result = json.loads(run.stdout)
    assert result == dict(CLEAN, vertices=4, faces=4)


# ---------------------------------------------------------------------------------------------
# The fixture writer

def write_param(path, domain, surface, faces):
    """faces: ((a, b, c), d, (beta_a, beta_b, beta_c))."""
    lines = ["fhr-param 1", "domain_vertices %d" % len(domain[0])]
    lines += ["%r %r %r" % p for p in domain[0]]
    lines += ["domain_faces %d" % len(domain[1])] + ["%d %d %d" % f for f in domain[1]]
    lines += ["surface_vertices %d" % len(surface)] + ["%r %r %r" % p for p in surface]
    lines += ["surface_faces %d" % len(faces)]
    lines += [" ".join(str(x) for x in list(c) + [d] + [b for beta in betas for b in beta])
              for c, d, betas in faces]
    path.write_text("\n".join(lines) + "\n")


def test_fixtures_from_a_param_file(tmp_path):
    # T': the tetrahedron with the face (0, 2, 1) split at its centroid (vertex 4)
    unit = {0: (1.0, 0.0, 0.0), 2: (0.0, 1.0, 0.0), 1: (0.0, 0.0, 1.0), 4: (1 / 3, 1 / 3, 1 / 3)}
    faces = [((0, 2, 4), 0, (unit[0], unit[2], unit[4])),
             ((2, 1, 4), 0, (unit[2], unit[1], unit[4])),
             ((1, 0, 4), 0, (unit[1], unit[0], unit[4]))]
    for d, tri in enumerate(TET_F[1:], 1):
        faces.append((tri, d, tuple(tuple(1.0 if k == i else 0.0 for k in range(3))
                                    for i in range(3))))
    write_param(tmp_path / "p.fhrp", (TET_P, TET_F), TET_P + [(1 / 3, 1 / 3, 0.0)], faces)
    fx.write_off(tmp_path / "tet.off", TET_P, TET_F)
    out = tmp_path / "out"
    written = fx.write_fixtures(tmp_path / "p.fhrp", out, tmp_path / "tet.off")
    assert sorted(p.name for p in written) == sorted(
        ["Tprime.off", "D.off", "Tprime.vmap", "Tprime.corr", "Tprime.vtpm", "Tprime.ijv",
         "T.off", "T_only.vmap"])
    assert (out / "Tprime.vtpm").read_text().splitlines()[:2] == ["5 4", "0 2 0.0 0.0"]
    assert (out / "Tprime.ijv").read_text().splitlines()[-3:] == [
        "5 1 %r" % (1 / 3), "5 3 %r" % (1 / 3), "5 2 %r" % (1 / 3)]
    for ext in (".vmap", ".corr", ".vtpm", ".ijv"):
        result = vmr.judge(out / ("Tprime" + ext), out / "D.off", out / "Tprime.off")
        assert (result["vertices"], verdict(result)) == (5, CLEAN)
    assert (out / "T_only.vmap").read_text().splitlines()[1] == "4"
    assert verdict(vmr.judge(out / "T_only.vmap", out / "D.off", out / "T.off")) == CLEAN
    swapped = fx.swap(fx.read_plain_map(out / "Tprime.vmap"), 0, 4)
    fx.write_map(out / "swapped.corr", swapped, TET_F, 4)
    result = vmr.judge(out / "swapped.corr", out / "D.off", out / "Tprime.off")
    assert result["folded_faces"] != []
