"""Checks of the Python atlas reference (atlas_reference.py) on tiny atlases written here, each
with its answer worked out by hand: the distortion examples of spec/distortion.md (DIST-*), and
folds, mirrored charts, overlaps, contacts, torn edges, T-vertices, degenerate UV triangles,
welding, packing and the readers of spec/atlas.md (ATLAS-*).

Run with Debian's interpreter: /usr/bin/python3 -m pytest proofs_tests/exchange/test_atlas_reference.py
"""

import json
import math
import random
import struct
import subprocess
import sys
from fractions import Fraction
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent))
import atlas_reference as ar  # noqa: E402

REL = 1e-12
SCRIPT = Path(__file__).resolve().parent / "atlas_reference.py"


def approx(x):
    return pytest.approx(x, rel=REL, abs=0)


def write_obj(path, positions, faces, textures=None):
    """faces: list of ((i, j, k), ((u, v), (u, v), (u, v))), 0-based vertex indices; each corner
    gets its own vt line. textures: a usemtl name per face (None: no usemtl before it)."""
    lines = ["v %r %r %r" % tuple(p) for p in positions]
    current = None
    t = 0
    for n, (f, uv) in enumerate(faces):
        if textures is not None and textures[n] != current:
            current = textures[n]
            lines.append("usemtl %s" % current)
        lines.extend("vt %r %r" % tuple(c) for c in uv)
        lines.append("f %d/%d %d/%d %d/%d" % (f[0] + 1, t + 1, f[1] + 1, t + 2, f[2] + 1, t + 3))
        t += 3
    path.write_text("\n".join(lines) + "\n")
    return path


def run(tmp_path, positions, faces, textures=None, name="a.obj"):
    return ar.analyze(ar.read_atlas(write_obj(tmp_path / name, positions, faces, textures)))


def flat(points):
    """UV points (u, v) lifted to 3D (u, v, 0): a surface that is its own atlas."""
    return [(u, v, 0.0) for (u, v) in points]


def separate(tris):
    """Triangles given by UV points, each with its own three 3D vertices (at the UV points,
    shifted in z by the triangle's number so that nothing welds)."""
    positions, faces = [], []
    for n, tri in enumerate(tris):
        faces.append(((3 * n, 3 * n + 1, 3 * n + 2), tri))
        positions.extend((u, v, float(n)) for (u, v) in tri)
    return positions, faces


# ---------------------------------------------------------------------------------------------
# DIST-* worked examples (spec/distortion.md)

IDENTITY_IMG = [(0, 0), (1, 0), (0, 1)]
IDENTITY_SURF = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]


def test_dist_identity():
    d = ar.distortion_figures([IDENTITY_IMG], [IDENTITY_SURF])
    assert d["degenerate"] == 0
    assert d["l2_stretch"] == approx(1.0)
    assert d["linf_stretch"] == approx(1.0)
    assert d["symmetric_dirichlet"] == approx(4.0)
    for key in ("p50", "p99", "p999", "max"):
        assert d["anisotropy"][key] == approx(1.0)
    assert d["anisotropy"]["above_10"] == 0
    assert d["area_distortion"]["p99"] == approx(1.0)
    assert d["area_distortion"]["max"] == approx(1.0)


def test_dist_stretch_by_two():
    d = ar.distortion_figures([IDENTITY_IMG], [[(0, 0, 0), (2, 0, 0), (0, 1, 0)]])
    assert d["l2_stretch"] == approx(math.sqrt(1.25))
    assert d["linf_stretch"] == approx(math.sqrt(2))
    assert d["symmetric_dirichlet"] == approx(5.0)
    for key in ("p50", "p99", "p999", "max"):
        assert d["anisotropy"][key] == approx(2.0)
    assert d["area_distortion"]["p99"] == approx(1.0)
    assert d["area_distortion"]["max"] == approx(1.0)


def test_dist_two_faces_percentiles():
    # face 0: identity, image area 1/2; face 1: image (0,0),(3,0),(0,1), sigma = 1, 1/3, area 3/2.
    # k = 1/sqrt 2; weights 1/4, 3/4; sigma' = (sqrt2, sqrt2) and (sqrt2, sqrt2/3).
    d = ar.distortion_figures([IDENTITY_IMG, [(0, 0), (3, 0), (0, 1)]], [IDENTITY_SURF, IDENTITY_SURF])
    assert d["l2_stretch"] == approx(math.sqrt(4 / 3))  # 1/4 * 2 + 3/4 * (2 + 2/9) / 2
    assert d["linf_stretch"] == approx(math.sqrt(2))
    assert d["symmetric_dirichlet"] == approx(20 / 3)  # 1/4 * 5 + 3/4 * 65/9
    assert d["anisotropy"]["p50"] == approx(3.0)  # faces with x <= 1 weigh 1/4 < 1/2
    assert d["anisotropy"]["p99"] == approx(3.0)
    assert d["anisotropy"]["max"] == approx(3.0)
    assert d["anisotropy"]["above_10"] == 0
    # area distortion: face 0 max(2, 1/2) = 2 (weight 1/4), face 1 max(2/3, 3/2) = 3/2 (weight 3/4)
    assert d["area_distortion"]["p99"] == approx(2.0)
    assert d["area_distortion"]["max"] == approx(2.0)
    assert d["degenerate"] == 0


def test_dist_degenerate_face_left_out():
    d = ar.distortion_figures([IDENTITY_IMG, [(0, 0), (1, 0), (2, 0)]], [IDENTITY_SURF, IDENTITY_SURF])
    assert d["degenerate"] == 1
    assert d["l2_stretch"] == approx(1.0)
    assert d["linf_stretch"] == approx(1.0)
    assert d["symmetric_dirichlet"] == approx(4.0)
    assert d["anisotropy"]["max"] == approx(1.0)
    assert d["area_distortion"]["max"] == approx(1.0)


def test_dist_every_face_degenerate_gives_null():
    d = ar.distortion_figures([[(0, 0), (1, 0), (2, 0)]], [IDENTITY_SURF])
    assert d["degenerate"] == 1
    assert d["l2_stretch"] is None and d["linf_stretch"] is None and d["symmetric_dirichlet"] is None
    assert d["anisotropy"]["p50"] is None and d["area_distortion"]["max"] is None
    json.dumps(d, allow_nan=False)  # no NaN or infinity anywhere


def test_dist_above_10_and_3d_image():
    # image (0,0,0),(20,0,0),(0,1,0) (a 3D image) onto the identity surface: sigma = 1, 1/20
    d = ar.distortion_figures([[(0, 0, 0), (20, 0, 0), (0, 1, 0)]], [IDENTITY_SURF])
    assert d["anisotropy"]["above_10"] == 1
    assert d["anisotropy"]["max"] == approx(20.0)


def test_weighted_percentile_rule():
    # the faces with x <= 1 weigh exactly p * total: 1 is the answer ("at least")
    assert ar.weighted_percentile([3.0, 1.0], [0.5, 0.5], 0.5) == 1.0
    assert ar.weighted_percentile([3.0, 1.0], [0.5, 0.25], 0.5) == 3.0
    assert ar.weighted_percentile([5.0, 1.0, 2.0], [1.0, 1.0, 1.0], 0.999) == 5.0


def test_atlas_distortion_uses_uv_as_image(tmp_path):
    # the stretch example as an atlas: 3D (0,0,0),(2,0,0),(0,1,0), UV the unit triangle
    r = run(tmp_path, [(0, 0, 0), (2, 0, 0), (0, 1, 0)], [((0, 1, 2), IDENTITY_IMG)])
    assert r["distortion"]["symmetric_dirichlet"] == approx(5.0)
    assert r["distortion"]["linf_stretch"] == approx(math.sqrt(2))


# ---------------------------------------------------------------------------------------------
# Exact arithmetic

def test_integer_scaling_is_exact():
    rng = random.Random(7)
    for _ in range(300):
        pts = [tuple(rng.choice([1, -1]) * rng.random() * 2.0 ** rng.randint(-80, 80) for _ in range(2))
               for _ in range(3)]
        if rng.random() < 0.3:  # exactly collinear: the third point on the line through the first two
            pts[2] = (pts[0][0] + 2 * (pts[1][0] - pts[0][0]), pts[0][1] + 2 * (pts[1][1] - pts[0][1]))
        k = ar._common_scale(c for p in pts for c in p)
        ints = [(ar._to_int(u, k), ar._to_int(v, k)) for (u, v) in pts]
        for (u, v), (iu, iv) in zip(pts, ints):
            assert Fraction(iu, 2 ** k) == Fraction(u) and Fraction(iv, 2 ** k) == Fraction(v)
        a, b, c = ints
        o = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        assert Fraction(o, 4 ** k) == ar.orient2d_exact(*pts)


# ---------------------------------------------------------------------------------------------
# Folds, mirrored charts, degenerate UV triangles (ATLAS-3, ATLAS-4)

QUAD = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]


def test_fold_is_one_fold_and_one_overlapping_pair(tmp_path):
    # vertex 3 (1,1) is mapped to (0.4, 0.4): face 1 turns clockwise over face 0
    uv = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.4, 0.4)]
    faces = [((0, 1, 2), (uv[0], uv[1], uv[2])), ((1, 3, 2), (uv[1], uv[3], uv[2]))]
    r = run(tmp_path, flat(QUAD), faces)
    assert r["charts"] == 1
    assert r["folded_faces"] == [1]
    assert r["overlapping_pairs"] == [[0, 1]]
    assert r["contacts"] == []
    assert r["mirrored_charts"] == 0
    assert r["degenerate_uv"] == []


def test_zero_chart_sum_counts_as_positive(tmp_path):
    # vertex 3 mapped onto vertex 0's UV point: face 1 is face 0 mirrored, the chart's sum is 0
    uv = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 0.0)]
    faces = [((0, 1, 2), (uv[0], uv[1], uv[2])), ((1, 3, 2), (uv[1], uv[3], uv[2]))]
    r = run(tmp_path, flat(QUAD), faces)
    assert r["charts"] == 1
    assert r["folded_faces"] == [1]
    assert r["mirrored_charts"] == 0
    assert r["overlapping_pairs"] == [[0, 1]]


def test_unfolded_quad_is_clean(tmp_path):
    faces = [((0, 1, 2), (QUAD[0], QUAD[1], QUAD[2])), ((1, 3, 2), (QUAD[1], QUAD[3], QUAD[2]))]
    r = run(tmp_path, flat(QUAD), faces)
    assert (r["charts"], r["folded_faces"], r["overlapping_pairs"], r["contacts"]) == (1, [], [], [])
    assert r["seam_length"] == 0.0
    assert r["packing_unit_square"] == approx(1.0)
    assert r["packing_bounding_square"] == approx(1.0)


def test_mirrored_chart_is_not_a_fold(tmp_path):
    mirrored = [(-u, v) for (u, v) in QUAD]  # every UV triangle clockwise
    faces = [((0, 1, 2), (mirrored[0], mirrored[1], mirrored[2])),
             ((1, 3, 2), (mirrored[1], mirrored[3], mirrored[2]))]
    r = run(tmp_path, flat(QUAD), faces)
    assert r["mirrored_charts"] == 1
    assert r["folded_faces"] == []
    assert r["overlapping_pairs"] == []
    assert r["chart_sign_disagreements"] == []


def test_degenerate_uv_triangle(tmp_path):
    faces = [((0, 1, 2), ((0.0, 0.0), (0.5, 0.5), (1.0, 1.0)))]
    r = run(tmp_path, flat(QUAD[:3]), faces)
    assert r["degenerate_uv"] == [0]
    assert r["folded_faces"] == []
    assert r["distortion"]["degenerate"] == 1


# ---------------------------------------------------------------------------------------------
# Overlaps and contacts (ATLAS-6, ATLAS-7)

def test_touching_at_a_vertex_from_different_charts_is_a_contact(tmp_path):
    positions, faces = separate([((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), ((1.0, 0.0), (2.0, 0.0), (1.0, 1.0))])
    r = run(tmp_path, positions, faces)
    assert r["charts"] == 2
    assert r["contacts"] == [[0, 1]]
    assert r["overlapping_pairs"] == []


def test_shared_corner_is_legitimate(tmp_path):
    # a bow tie: faces 0 and 1 share welded vertex 0 at UV (0,0) and nothing else
    positions = flat([(0.0, 0.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)])
    faces = [((0, 1, 2), ((0.0, 0.0), (1.0, -1.0), (1.0, 1.0))),
             ((0, 3, 4), ((0.0, 0.0), (-1.0, 1.0), (-1.0, -1.0)))]
    r = run(tmp_path, positions, faces)
    assert r["charts"] == 2
    assert r["contacts"] == []
    assert r["overlapping_pairs"] == []


def test_minus_zero_is_the_same_uv_point(tmp_path):
    # the same bow tie, but face 1's corner at vertex 0 reads -0.0: the same UV point (as numbers)
    positions = flat([(0.0, 0.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0)])
    faces = [((0, 1, 2), ((0.0, 0.0), (1.0, -1.0), (1.0, 1.0))),
             ((0, 3, 4), ((-0.0, 0.0), (-1.0, 1.0), (-1.0, -1.0)))]
    r = run(tmp_path, positions, faces)
    assert r["contacts"] == []
    # and another UV point for vertex 0, on face 0's side: the two sides touch along a segment
    faces[1] = ((0, 3, 4), ((0.5, -0.5), (-1.0, 1.0), (-1.0, -1.0)))
    r = run(tmp_path, positions, faces)
    assert r["contacts"] == [[0, 1]]


def test_one_shared_corner_and_a_common_segment_is_a_contact(tmp_path):
    # faces 0 and 1 share vertex 0 at (0,0); face 1's edge from it runs along face 0's edge 0-2
    positions = flat([(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.0, 2.0), (-1.0, 1.0)])
    faces = [((0, 1, 2), ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))),
             ((0, 3, 4), ((0.0, 0.0), (0.0, 2.0), (-1.0, 1.0)))]
    r = run(tmp_path, positions, faces)
    assert r["contacts"] == [[0, 1]]
    assert r["overlapping_pairs"] == []


EDGE_A = ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))
EDGE_B = ((0.75, 0.25), (1.0, 1.0), (0.25, 0.75))  # its edge 2-0 lies on u + v = 1, inside A's


def test_edge_on_edge_touch_is_a_contact(tmp_path):
    r = run(tmp_path, *separate([EDGE_A, EDGE_B]))
    assert r["contacts"] == [[0, 1]]
    assert r["overlapping_pairs"] == []
    assert ar.overlaps_and_contacts(ar.read_atlas(tmp_path / "a.obj")) == ([], [(0, 1)])


@pytest.mark.parametrize("shift, contacts, overlaps", [(2.0 ** -45, [], []), (-(2.0 ** -45), [], [[0, 1]])])
def test_edge_on_edge_decided_exactly(tmp_path, shift, contacts, overlaps):
    moved = tuple((u + shift, v) for (u, v) in EDGE_B)
    r = run(tmp_path, *separate([EDGE_A, moved]))
    assert r["contacts"] == contacts
    assert r["overlapping_pairs"] == overlaps


def test_overlap_counts_within_one_texture_only(tmp_path):
    tris = [((0.0, 0.0), (1.0, 0.0), (0.0, 1.0)), ((0.2, 0.2), (1.2, 0.2), (0.2, 1.2))]
    same = run(tmp_path, *separate(tris), textures=["m", "m"], name="same.obj")
    assert same["overlapping_pairs"] == [[0, 1]]
    other = run(tmp_path, *separate(tris), textures=["m", "n"], name="other.obj")
    assert other["overlapping_pairs"] == []
    assert other["contacts"] == []
    # the second triangle loses two corners of area 0.02 outside [0,1]^2 (0.46 inside); the two
    # share the triangle u, v >= 0.2, u + v <= 1 of area 0.18, counted once in one texture
    assert same["packing_unit_square"] == approx(0.5 + 0.46 - 0.18)
    assert same["packing_bounding_square"] == approx((0.5 + 0.5 - 0.18) / 1.2 ** 2)
    assert other["packing_unit_square"] == approx((0.5 + 0.46) / 2)
    assert other["packing_bounding_square"] == approx((0.5 + 0.5) / (1.0 + 1.0))


def test_duplicate_uv_triangle_in_another_chart_overlaps(tmp_path):
    tri = ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))
    r = run(tmp_path, *separate([tri, tri]))
    assert r["overlapping_pairs"] == [[0, 1]]
    assert r["contacts"] == []


# ---------------------------------------------------------------------------------------------
# Cracks (ATLAS-5)

def quad_with_face1_corner(corner):
    """The unit quad in two faces; face 1's UV at vertex 2 is `corner` (face 0 has (0,1))."""
    faces = [((0, 1, 2), (QUAD[0], QUAD[1], QUAD[2])), ((1, 3, 2), (QUAD[1], QUAD[3], corner))]
    return flat(QUAD), faces


def test_torn_edge(tmp_path):
    r = run(tmp_path, *quad_with_face1_corner((0.0, 1.0 + 1e-9)))
    assert r["torn_edges"] == [[0, 1]]
    assert r["charts"] == 2
    assert r["seam_length"] == approx(math.sqrt(2))  # edge 1-2 over sqrt(area 1)


def test_a_real_seam_is_not_torn(tmp_path):
    r = run(tmp_path, *quad_with_face1_corner((0.0, 1.1)))
    assert r["torn_edges"] == []
    assert r["charts"] == 2


def test_both_ends_apart_is_not_a_torn_edge(tmp_path):
    # ATLAS-5 (b) asks for one end shared: with both ends 1e-9 apart the edge is a seam, not torn
    faces = [((0, 1, 2), (QUAD[0], QUAD[1], QUAD[2])),
             ((1, 3, 2), ((1.0 + 1e-9, 0.0), QUAD[3], (0.0, 1.0 + 1e-9)))]
    r = run(tmp_path, flat(QUAD), faces)
    assert r["torn_edges"] == []
    assert r["charts"] == 2


def test_t_vertex(tmp_path):
    # face 0 spans (0,0)-(2,0); faces 1 and 2 below it use vertex 4 = (1,0) on that edge
    pts = [(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (1.0, -1.0), (1.0, 0.0)]
    faces = [((0, 1, 2), (pts[0], pts[1], pts[2])), ((0, 3, 4), (pts[0], pts[3], pts[4])),
             ((4, 3, 1), (pts[4], pts[3], pts[1]))]
    r = run(tmp_path, flat(pts), faces)
    assert r["t_vertices"] == [[4, 0, 1]]
    # in UV, faces 1 and 2 run along face 0's edge beyond their shared corner: contacts
    assert r["contacts"] == [[0, 1], [0, 2]]
    assert r["overlapping_pairs"] == []


def test_no_t_vertex_when_the_edge_is_split(tmp_path):
    pts = [(0.0, 0.0), (2.0, 0.0), (1.0, 1.0), (1.0, -1.0), (1.0, 0.0)]
    faces = [((0, 4, 2), (pts[0], pts[4], pts[2])), ((4, 1, 2), (pts[4], pts[1], pts[2])),
             ((0, 3, 4), (pts[0], pts[3], pts[4])), ((4, 3, 1), (pts[4], pts[3], pts[1]))]
    r = run(tmp_path, flat(pts), faces)
    assert r["t_vertices"] == []
    assert r["contacts"] == []
    assert r["charts"] == 1


def test_minus_zero_welds(tmp_path):
    # vertex 3 at (-0, 0, 0) welds with vertex 0 at (0, 0, 0) (equal as numbers): no T-vertex
    positions = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (-0.0, 0.0, 0.0), (-1.0, 0.0, 0.0),
                 (0.0, -1.0, 0.0)]
    faces = [((0, 1, 2), ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))),
             ((3, 4, 5), ((3.0, 3.0), (2.0, 3.0), (3.0, 2.0)))]
    r = run(tmp_path, positions, faces)
    assert r["t_vertices"] == []
    assert r["charts"] == 2


# ---------------------------------------------------------------------------------------------
# Charts, welding, packing, readers (ATLAS-1)

def test_textures_split_charts(tmp_path):
    faces = [((0, 1, 2), (QUAD[0], QUAD[1], QUAD[2])), ((1, 3, 2), (QUAD[1], QUAD[3], QUAD[2]))]
    r = run(tmp_path, flat(QUAD), faces, textures=["a", "b"])
    assert r["charts"] == 2
    assert r["seam_length"] == approx(math.sqrt(2))
    assert r["torn_edges"] == []
    assert r["packing_unit_square"] == approx(0.5)  # 1/2 in each of two textures
    assert r["packing_bounding_square"] == approx(0.5)  # 1/2 + 1/2 over two unit squares


def test_packing_clipped_and_bounding_square(tmp_path):
    r = run(tmp_path, flat([(0.0, 0.0), (2.0, 0.0), (0.0, 2.0)]),
            [((0, 1, 2), ((0.0, 0.0), (2.0, 0.0), (0.0, 2.0)))])
    assert r["packing_unit_square"] == approx(1.0)  # [0,1]^2 lies inside u + v <= 2
    assert r["packing_bounding_square"] == approx(0.5)  # area 2 over the square of side 2


def ply_bytes(fmt, vertices, faces, vertex_props=("u", "v"), face_extra=None):
    """vertices: tuples (x, y, z, a, b); faces: index triples; face_extra: per face
    (texcoord list or None, texnumber or None)."""
    head = ["ply", "format %s 1.0" % fmt, "element vertex %d" % len(vertices),
            "property double x", "property float y", "property double z"]
    head += ["property double %s" % p for p in vertex_props]
    head += ["element face %d" % len(faces), "property list uchar int vertex_indices"]
    has_tc = face_extra is not None and face_extra[0][0] is not None
    has_tn = face_extra is not None and face_extra[0][1] is not None
    if has_tc:
        head.append("property list uchar double texcoord")
    if has_tn:
        head.append("property int texnumber")
    head.append("end_header")
    out = ("\n".join(head) + "\n").encode()
    if fmt == "ascii":
        lines = [" ".join(repr(float(c)) for c in v[:3 + len(vertex_props)]) for v in vertices]
        for n, f in enumerate(faces):
            parts = ["3"] + [str(i) for i in f]
            if has_tc:
                parts += ["6"] + [repr(float(c)) for c in face_extra[n][0]]
            if has_tn:
                parts.append(str(face_extra[n][1]))
            lines.append(" ".join(parts))
        return out + ("\n".join(lines) + "\n").encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    for v in vertices:
        out += struct.pack(e + "dfd" + "d" * len(vertex_props), *v[:3 + len(vertex_props)])
    for n, f in enumerate(faces):
        out += struct.pack(e + "B3i", 3, *f)
        if has_tc:
            out += struct.pack(e + "B6d", 6, *face_extra[n][0])
        if has_tn:
            out += struct.pack(e + "i", face_extra[n][1])
    return out


# the unit quad cut along its diagonal 1-2 with duplicated seam vertices: face 1's copies of
# vertices 1 and 2 (file vertices 3, 4) carry UV shifted by (2, 0)
SEAM_VERTICES = [(0, 0, 0, 0, 0), (1, 0, 0, 1, 0), (0, 1, 0, 0, 1),
                 (1, 0, 0, 3, 0), (0, 1, 0, 2, 1), (1, 1, 0, 3, 1)]
SEAM_FACES = [(0, 1, 2), (3, 5, 4)]


@pytest.mark.parametrize("fmt", ["ascii", "binary_little_endian", "binary_big_endian"])
def test_ply_per_vertex_uv_welds_seam_copies(tmp_path, fmt):
    path = tmp_path / "seam.ply"
    path.write_bytes(ply_bytes(fmt, SEAM_VERTICES, SEAM_FACES))
    atlas = ar.read_atlas(path)
    assert atlas.uvs[1] == ((3.0, 0.0), (3.0, 1.0), (2.0, 1.0))
    r = ar.analyze(atlas)
    assert r["charts"] == 2
    assert r["seam_length"] == approx(math.sqrt(2))  # the copies weld: one seam edge 1-2
    assert r["t_vertices"] == []
    assert r["contacts"] == [] and r["overlapping_pairs"] == []
    assert r["packing_bounding_square"] == approx(1.0 / 9.0)  # area 1 over the square of side 3


@pytest.mark.parametrize("fmt", ["ascii", "binary_little_endian"])
def test_ply_same_uv_copies_form_one_chart(tmp_path, fmt):
    vertices = [v[:3] + ((v[0], v[1]) if n >= 3 else v[3:]) for n, v in enumerate(SEAM_VERTICES)]
    path = tmp_path / "joined.ply"
    path.write_bytes(ply_bytes(fmt, vertices, SEAM_FACES))
    r = ar.analyze(ar.read_atlas(path))
    assert r["charts"] == 1
    assert r["seam_length"] == 0.0


@pytest.mark.parametrize("fmt", ["ascii", "binary_big_endian"])
def test_ply_texcoord_wins_and_texnumber_separates(tmp_path, fmt):
    vertices = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (0, 1, 1)]
    tri = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]
    faces = [(0, 1, 2), (3, 4, 5)]
    path = tmp_path / "tc.ply"
    path.write_bytes(ply_bytes(fmt, [v + (9, 9) for v in vertices], faces, face_extra=[(tri, 0), (tri, 0)]))
    atlas = ar.read_atlas(path)
    assert atlas.uvs[0] == ((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))  # not the per-vertex (9, 9)
    assert ar.analyze(atlas)["overlapping_pairs"] == [[0, 1]]
    path.write_bytes(ply_bytes(fmt, [v + (9, 9) for v in vertices], faces, face_extra=[(tri, 0), (tri, 1)]))
    atlas = ar.read_atlas(path)
    assert atlas.textures == [0, 1]
    assert ar.analyze(atlas)["overlapping_pairs"] == []


def test_obj_negative_indices(tmp_path):
    text = "\n".join([
        "v 0 0 0", "v 1 0 0", "v 0 1 0", "vt 0 0", "vt 1 0", "vt 0 1", "f -3/-3 -2/-2 -1/-1",
        "v 1 1 0", "vt 0.4 0.4", "f 2/-3 -1/-1/1 3/3",
    ]) + "\n"
    path = tmp_path / "neg.obj"
    path.write_text(text)
    atlas = ar.read_atlas(path)
    assert atlas.faces == [(0, 1, 2), (1, 3, 2)]
    assert atlas.uvs[1] == ((1.0, 0.0), (0.4, 0.4), (0.0, 1.0))
    r = ar.analyze(atlas)
    # the fold example written with relative indices: one chart, face 1 folded over face 0
    assert r["charts"] == 1
    assert r["folded_faces"] == [1]
    assert r["overlapping_pairs"] == [[0, 1]]


def test_obj_usemtl_and_ignored_statements(tmp_path):
    text = "\n".join([
        "mtllib x.mtl", "o thing", "v 0 0 0", "v 1 0 0", "v 0 1 0", "vn 0 0 1", "vt 0 0", "vt 1 0", "vt 0 1",
        "s 1", "g group", "f 1/1/1 2/2/1 3/3/1", "usemtl second", "f 1/1 2/2 3/3",
    ]) + "\n"
    path = tmp_path / "mtl.obj"
    path.write_text(text)
    atlas = ar.read_atlas(path)
    assert atlas.textures == [None, "second"]
    assert ar.analyze(atlas)["overlapping_pairs"] == []


@pytest.mark.parametrize("body, needle", [
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 4/1 3/1\n", "corners"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3/1\n", "no texture coordinate"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1//1 2//1 3//1\n", "no texture coordinate"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n", "not finite"),
    ("v 0 0 0\nv 1 0 inf\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n", "not finite"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 1e400\nf 1/1 2/1 3/1\n", "not finite"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 4/1\n", "out of range"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/2 3/1\n", "out of range"),
    ("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 -4/1\n", "out of range"),
])
def test_obj_refusals(tmp_path, body, needle):
    path = tmp_path / "bad.obj"
    path.write_text(body)
    with pytest.raises(ValueError) as err:
        ar.read_atlas(path)
    message = str(err.value)
    assert needle in message and "\n" not in message and str(path) in message


def test_ply_refusals(tmp_path):
    path = tmp_path / "bad.ply"
    vertices = [(0, 0, 0, 0, 0), (1, 0, 0, 1, 0), (0, 1, 0, 0, 1)]
    path.write_bytes(ply_bytes("ascii", vertices, [(0, 1, 3)]))
    with pytest.raises(ValueError, match="out of range"):
        ar.read_atlas(path)
    path.write_bytes(ply_bytes("ascii", [v[:3] for v in vertices], [(0, 1, 2)], vertex_props=()))
    with pytest.raises(ValueError, match="no texture coordinates"):
        ar.read_atlas(path)
    header = ("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
              "property list uchar float texcoord\nend_header\n0 0 0\n1 0 0\n0 1 0\n")
    path.write_text(header + "3 0 1 2 6 0 0 1 0 0 1\n")
    assert ar.read_atlas(path).uvs == [((0.0, 0.0), (1.0, 0.0), (0.0, 1.0))]
    path.write_text(header + "3 0 1 2 5 0 0 1 0 0\n")
    with pytest.raises(ValueError, match="texcoord has 5 numbers"):
        ar.read_atlas(path)
    path.write_text(header + "3 0 1 2 6 0 0 1 0 0 nan\n")
    with pytest.raises(ValueError, match="not finite"):
        ar.read_atlas(path)
    path.write_text(header + "4 0 1 2 0 6 0 0 1 0 0 1\n")
    with pytest.raises(ValueError, match="triangle"):
        ar.read_atlas(path)


def test_command_line(tmp_path):
    uv = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (0.4, 0.4)]
    path = write_obj(tmp_path / "fold.obj", flat(QUAD),
                     [((0, 1, 2), (uv[0], uv[1], uv[2])), ((1, 3, 2), (uv[1], uv[3], uv[2]))])
    out = subprocess.run([sys.executable, str(SCRIPT), str(path), "--json"], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    keys = {"folded_faces", "overlapping_pairs", "contacts", "degenerate_uv", "t_vertices", "torn_edges",
            "charts", "mirrored_charts", "seam_length", "packing_unit_square", "packing_bounding_square",
            "distortion"}
    assert keys <= set(result)
    assert result["folded_faces"] == [1] and result["overlapping_pairs"] == [[0, 1]]
    assert set(result["distortion"]) == {"l2_stretch", "linf_stretch", "symmetric_dirichlet", "anisotropy",
                                         "area_distortion", "degenerate"}
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    out = subprocess.run([sys.executable, str(SCRIPT), str(bad)], capture_output=True, text=True)
    assert out.returncode == 2
    assert out.stdout == "" and len(out.stderr.strip().splitlines()) == 1


# ---------------------------------------------------------------------------------------------
# Larger atlases: the sweep against every pair, an independent geometric check of each verdict,
# the SVD against DIST-1's closed formula, and a grid atlas with planted defects

def lattice_soup(seed, n=160):
    """Random triangles on the lattice (k/4, l/4), 0 <= k, l <= 8, lifted to z = 0 so that equal
    lattice points weld: shared corners, exact touches, overlaps and folds all occur."""
    rng = random.Random(seed)
    pts = [(k / 4, l / 4) for k in range(9) for l in range(9)]
    positions = flat(pts)
    faces = []
    while len(faces) < n:
        a, b, c = rng.sample(range(len(pts)), 3)
        if ar.orient2d_exact(pts[a], pts[b], pts[c]) != 0:
            faces.append(((a, b, c), (pts[a], pts[b], pts[c])))
    return positions, faces


def shapely_verdict(atlas, f, g):
    """overlap / contact / None decided with shapely on lattice coordinates (exact there)."""
    from shapely.geometry import Point, Polygon, LineString
    A, B = Polygon(atlas.uvs[f]), Polygon(atlas.uvs[g])
    if not A.intersects(B):
        return None
    if A.intersection(B).area > 1e-9:
        return "overlap"
    shared = [atlas.uvs[f][i] for i in range(3) for j in range(3)
              if atlas.faces[f][i] == atlas.faces[g][j] and atlas.uvs[f][i] == atlas.uvs[g][j]]
    common = A.intersection(B)
    if len(shared) == 1 and common.equals(Point(shared[0])):
        return None
    if len(shared) == 2 and common.equals(LineString(shared)):
        return None
    return "contact"


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_sweep_finds_every_pair_and_verdicts_agree_with_shapely(tmp_path, seed):
    positions, faces = lattice_soup(seed)
    atlas = ar.read_atlas(write_obj(tmp_path / "soup.obj", positions, faces))
    r = ar.analyze(atlas, packing=False)
    prep = ar._Prepared(atlas)
    overlaps, contacts = [], []
    for f in range(len(faces)):
        for g in range(f + 1, len(faces)):
            mine = ar._classify_pair(prep, f, g)
            assert mine == shapely_verdict(atlas, f, g), (f, g)
            (overlaps if mine == "overlap" else contacts if mine == "contact" else []).append([f, g])
    assert r["overlapping_pairs"] == overlaps and r["contacts"] == contacts
    assert overlaps and contacts


def test_svd_agrees_with_dist1_closed_formula():
    """DIST-1's formula evaluated on the exact Gram matrices with 60 significant digits; the SVD's
    sigma_1 / sigma_2 within 1e-13 of it, relative, per unit of sigma_1 / sigma_2."""
    from decimal import Decimal, getcontext
    getcontext().prec = 60
    rng = random.Random(5)
    for _ in range(300):
        q = [(rng.uniform(-1, 1), rng.uniform(-1, 1)) for _ in range(3)]
        p = [tuple(rng.uniform(-1, 1) for _ in range(3)) for _ in range(3)]
        Q = [[Fraction(q[1][k]) - Fraction(q[0][k]), Fraction(q[2][k]) - Fraction(q[0][k])] for k in range(2)]
        P = [[Fraction(p[1][k]) - Fraction(p[0][k]), Fraction(p[2][k]) - Fraction(p[0][k])] for k in range(3)]
        gq = [[sum(Q[k][i] * Q[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
        gp = [[sum(P[k][i] * P[k][j] for k in range(3)) for j in range(2)] for i in range(2)]
        det_q = gq[0][0] * gq[1][1] - gq[0][1] * gq[1][0]
        inv = [[gq[1][1] / det_q, -gq[0][1] / det_q], [-gq[1][0] / det_q, gq[0][0] / det_q]]
        m = [[sum(inv[i][k] * gp[k][j] for k in range(2)) for j in range(2)] for i in range(2)]
        t, d = m[0][0] + m[1][1], m[0][0] * m[1][1] - m[0][1] * m[1][0]
        dec = lambda x: Decimal(x.numerator) / Decimal(x.denominator)  # noqa: E731
        s1 = ((dec(t) + dec(t * t - 4 * d).sqrt()) / 2).sqrt()
        s2 = dec(d).sqrt() / s1
        ratio = float(s1 / s2)
        fig = ar.distortion_figures([q], [p])
        assert fig["anisotropy"]["max"] == pytest.approx(ratio, rel=1e-13 * ratio)
        # one face: k^2 = A_P / A_Q = s1 s2, so sigma_1' = sqrt(s1 / s2)
        assert fig["linf_stretch"] == pytest.approx(math.sqrt(ratio), rel=1e-13 * ratio)


def grid_atlas(cells, block):
    """A height field over [0,1]^2 in cells x cells squares (two faces each), cut into charts of
    block x block squares laid out with a gap of 2 units (a unit is 1/S, S a power of two) and
    defects planted at known places:

      fold:     chart (0,0): vertex (2,2) moved by (+1.5, +1.5) units; its six faces are `ring`
      overlap:  chart (2,0) moved by -3 units in u: it covers one column of chart (1,0)
      contact:  chart (4,0) moved by exactly (-2, +1/2) units: its left boundary lies on chart (3,0)'s
                right boundary, the vertices half a unit apart (so the two charts stay apart)
      mirror:   chart (0,2) reflected in u
      torn:     in chart (2,2), face `torn_face`'s corner at its first vertex moved by 2^-32 units
                inwards: its two edges at that vertex are torn

    Returns (positions, faces, info) with info giving the chart of each face and the plants."""
    n = cells + 1
    nb = -(-cells // block)
    S = 1 << (cells + 2 * nb).bit_length()
    positions = [(i / cells, j / cells, 0.05 * math.sin(7.0 * i / cells) * math.cos(5.0 * j / cells))
                 for j in range(n) for i in range(n)]
    vid = lambda i, j: j * n + i  # noqa: E731
    shift = {(2, 0): (-3, 0), (4, 0): (-2, 0.5)}
    faces, chart_of = [], []
    ring, torn_face = [], None
    torn_cell = (2 * block + block // 2, 2 * block + block // 2)
    for j in range(cells):
        for i in range(cells):
            b = (i // block, j // block)
            for tri in (((i, j), (i + 1, j), (i, j + 1)), ((i + 1, j), (i + 1, j + 1), (i, j + 1))):
                uv = []
                for (x, y) in tri:
                    du, dv = shift.get(b, (0, 0))
                    u, v = x + 2 * b[0] + du, y + 2 * b[1] + dv
                    if b == (0, 0) and (x, y) == (2, 2):
                        u, v = u + 1.5, v + 1.5
                    if b == (0, 2):
                        u = block - x  # the chart's columns 0..block reflected in u
                    uv.append((u / S, v / S))
                if (2, 2) in tri and b == (0, 0):
                    ring.append(len(faces))
                if (i, j) == torn_cell and tri[0] == (i, j):
                    torn_face = len(faces)
                    d = 2.0 ** -32 / S
                    uv[0] = (uv[0][0] + d, uv[0][1] + d)
                faces.append((tuple(vid(x, y) for (x, y) in tri), tuple(uv)))
                chart_of.append(b)
    return positions, faces, {"chart": chart_of, "ring": ring, "torn_face": torn_face, "blocks": nb * nb}


def test_grid_atlas_with_planted_defects(tmp_path):
    positions, faces, info = grid_atlas(40, 8)
    r = run(tmp_path, positions, faces, name="grid.obj")
    chart, ring = info["chart"], set(info["ring"])
    assert r["charts"] == info["blocks"]
    assert r["mirrored_charts"] == 1
    assert r["degenerate_uv"] == [] and r["t_vertices"] == []
    assert r["folded_faces"] and set(r["folded_faces"]) <= ring
    f = info["torn_face"]
    w = faces[f][0][0]  # the moved corner's vertex
    neighbours = [g for g, (vs, _) in enumerate(faces) if g != f and w in vs and len(set(vs) & set(faces[f][0])) == 2]
    assert r["torn_edges"] == sorted([min(f, g), max(f, g)] for g in neighbours) and len(neighbours) == 2
    pair_charts = lambda p: {chart[p[0]], chart[p[1]]}  # noqa: E731
    planted_overlap = [p for p in r["overlapping_pairs"] if pair_charts(p) == {(1, 0), (2, 0)}]
    assert planted_overlap
    assert all(p in planted_overlap or set(p) & ring for p in r["overlapping_pairs"])
    assert any(set(p) & ring for p in r["overlapping_pairs"])
    planted_contact = [p for p in r["contacts"] if pair_charts(p) == {(3, 0), (4, 0)}]
    # each of the 8 boundary edges of chart (3,0) lies half on two of chart (4,0)'s: 15 pairs of
    # boundary faces, besides the faces that touch them at a vertex
    assert len(planted_contact) >= 15
    assert all(p in planted_contact or pair_charts(p) == {(1, 0), (2, 0)} or set(p) & ring for p in r["contacts"])
