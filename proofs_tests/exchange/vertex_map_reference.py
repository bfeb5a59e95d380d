#!/usr/bin/python3
"""An independent Python reference for judging a per-vertex map of a triangle mesh T onto a base
mesh D (spec/vertex_map.md, VMAP-*), written from the specification alone.

It reads T and D (OFF: `OFF`, the counts, the vertices, the faces `3 i j k`, keeping the file's
numbering and corner order) and the map in any of the four formats of the spec's table (plain
`.vmap`, `.corr`, `.vtpm`, `.ijv`; chosen by the extension or by --format). A file that breaks
VMAP-1, an OFF file that cannot be read, or a mesh that is not an oriented manifold (each edge in
at most two faces, each directed edge in one, the faces at every vertex one fan: VMAP-3, which
this reference assumes and does not judge) is refused with a one-line ValueError.

Reading: `#` starts a comment in every format; blank lines are skipped; an index is an integer
token, a weight a decimal number or nan/inf (an overflowing decimal such as 1e400 reads as inf and
is judged under VMAP-2); the two counts of vtpm may share a line or take one line each.

It then decides, exactly:

  * VMAP-2: every vertex's record resolved to a point of D (a face d and weights; vtpm through
    its halfedge, ijv through the face holding the named vertices), finite weights, each
    >= -1e-12 and |sum - 1| <= 1e-12 (1e-12 is the double nearest to 10^-12, compared exactly);
    the image is w/sum w with negative weights read as 0, held as Fractions, its carrier the
    vertex, edge or face of D spanned by the positive weights;
  * the rule `adjacent` (VMAP-5): a segment in a face of D holding both carriers, else the
    shortest valid straight segment through a fan of faces around a vertex s of D, unfolded in
    double arithmetic by the spec's formula (Python floats are IEEE doubles, evaluated in the
    order written), the candidate's validity decided exactly on those doubles, its length in
    double from the end points rounded to double, ties to the first candidate in the order
    (s, position of f0 around s, m);
  * VMAP-6: coincident images, and pairs of T edges whose pieces (straight segments in one face
    of D with exact barycentric end points; a piece on an edge of D belongs to both faces) share a
    point other than the image of a common end, or overlap collinearly;
  * VMAP-7: folded faces, by the corner test (exact in a face of D holding both first pieces,
    else in the unfolding around the corner's image);
  * VMAP-8: vertices whose tangents do not wind once (interior) or do not advance from one
    boundary edge to the other without turning back (boundary);
  * VMAP-9: boundary edges of T whose image is not inside the boundary of D, and interior
    vertices of T whose image is on it.

It does not decide VMAP-3 or VMAP-4 (topology) and skips a decision only where its input does not
exist: edges with an end without an image have no image (they are listed among the edges without
one), and a corner (VMAP-7) or vertex (VMAP-8) needing an edge without an image is not judged. A
first piece of length zero (two ends with one image) has no tangent: its corners are folded and
its ends fail VMAP-8.

Fixed choices where the spec leaves the order open: the position 0 around an interior vertex of D
is its face of lowest index, around a boundary vertex the first face counter-clockwise (whose
first spoke is a boundary edge), and a fan around a boundary vertex may hold all its faces; the
ijv face of one named vertex is the lowest-index face at it, of two the lowest-index face at
their edge; a VMAP-7 corner at a point inside an edge (p, q) of D, with the first tangent in the
face holding the halfedge p -> q, is unfolded around q (faces (q, r, p) then (q, p, t)), the
spoke passed being the direction from the point to p.

Usage:  vertex_map_reference.py MAP --domain D.off --mesh T.off [--format plain|corr|vtpm|ijv]
                                [--json]
prints one JSON object (indented, or on one line with --json) with the keys vertices, faces (of
T), vertices_without_image (VMAP-2), edges_without_image ([u, v], u < v, 0-based vertices of T,
sorted), crossing_pairs ([[u1, v1], [u2, v2]], each edge (min, max), the pair sorted),
coincident_vertices ([a, b], a < b), folded_faces (0-based faces of T), winding_failures
(vertices of T) and boundary_failures ({"edges": [[u, v], ...], "vertices": [...]}), all sorted.
A file that cannot be read is refused with a one-line message on stderr and exit code 2.
"""

import argparse
import json
import math
import re
import sys
from fractions import Fraction

__all__ = ["Mesh", "Manifold", "Image", "read_off", "read_map", "resolve", "analyze", "unfold",
           "FORMATS"]

FORMATS = {"plain": ".vmap", "corr": ".corr", "vtpm": ".vtpm", "ijv": ".ijv"}
TOL = Fraction(1e-12)

_INTEGER = re.compile(r"[+-]?\d+\Z")
_REAL = re.compile(r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf|infinity|nan)\Z", re.I)


# --------------------------------------------------------------------------------------------
# Meshes

class Mesh:
    """positions: list of (x, y, z) floats; faces: list of (i, j, k), 0-based, in file order."""

    def __init__(self, positions, faces, path="<mesh>"):
        self.path = path
        self.positions = [tuple(float(c) for c in p) for p in positions]
        self.faces = [tuple(int(i) for i in f) for f in faces]


def _lines(path):
    """(line number, tokens) of every line with tokens, '#' comments removed."""
    with open(path, "rb") as fh:
        text = fh.read().decode("latin-1")
    for lineno, line in enumerate(text.split("\n"), 1):
        toks = line.split("#", 1)[0].split()
        if toks:
            yield lineno, toks


def _int(tok, where):
    if not _INTEGER.match(tok):
        raise ValueError("%s: expected an integer, found '%s'" % (where, tok))
    return int(tok)


def _real(tok, where):
    if not _REAL.match(tok):
        raise ValueError("%s: expected a number, found '%s'" % (where, tok))
    return float(tok)


def read_off(path):
    """An OFF triangle mesh: `OFF`, `nv nf ne`, nv lines `x y z`, nf lines `3 i j k`."""
    it = _lines(path)
    try:
        lineno, toks = next(it)
    except StopIteration:
        raise ValueError("%s: empty file" % path) from None
    if toks[0] != "OFF":
        raise ValueError("%s:%d: not an OFF file (first token is not 'OFF')" % (path, lineno))
    toks = toks[1:]
    if not toks:
        try:
            lineno, toks = next(it)
        except StopIteration:
            raise ValueError("%s: no counts" % path) from None
    if len(toks) < 2:
        raise ValueError("%s:%d: expected the counts of vertices and faces" % (path, lineno))
    nv, nf = (_int(t, "%s:%d" % (path, lineno)) for t in toks[:2])
    positions, faces = [], []
    for n in range(nv + nf):
        try:
            lineno, toks = next(it)
        except StopIteration:
            raise ValueError("%s: unexpected end of file (%d vertices and %d faces announced)"
                             % (path, nv, nf)) from None
        where = "%s:%d" % (path, lineno)
        if n < nv:
            if len(toks) != 3:
                raise ValueError("%s: vertex %d: expected 3 numbers" % (where, n))
            p = tuple(_real(t, where) for t in toks)
            if not all(math.isfinite(c) for c in p):
                raise ValueError("%s: vertex %d: coordinate is not finite" % (where, n))
            positions.append(p)
        else:
            if _int(toks[0], where) != 3 or len(toks) < 4:
                raise ValueError("%s: face %d: not a triangle" % (where, n - nv))
            f = tuple(_int(t, where) for t in toks[1:4])
            if not all(0 <= i < nv for i in f):
                raise ValueError("%s: face %d: vertex index out of range" % (where, n - nv))
            faces.append(f)
    for lineno, _ in it:
        raise ValueError("%s:%d: data after the last face" % (path, lineno))
    return Mesh(positions, faces, path)


class Manifold:
    """The oriented-manifold structure of a mesh: the face of every directed edge, the faces of
    every edge and, per vertex, its faces in counter-clockwise order (f_i = (s, a_i, a_{i+1}))."""

    def __init__(self, mesh, name):
        self.mesh = mesh
        self.faces = mesh.faces
        n = len(mesh.positions)
        self.halfedge = {}  # (a, b) -> face holding a -> b
        self.edge_faces = {}  # (min, max) -> sorted faces
        vertex_faces = [[] for _ in range(n)]
        for f, tri in enumerate(mesh.faces):
            if len(set(tri)) != 3:
                raise ValueError("%s: face %d repeats a vertex" % (name, f))
            for k in range(3):
                a, b = tri[k], tri[(k + 1) % 3]
                if (a, b) in self.halfedge:
                    raise ValueError("%s: edge %d-%d in two faces of the same direction (not an "
                                     "oriented manifold)" % (name, a, b))
                self.halfedge[(a, b)] = f
                self.edge_faces.setdefault((min(a, b), max(a, b)), []).append(f)
                vertex_faces[tri[k]].append(f)
        for e, fs in self.edge_faces.items():
            fs.sort()
        self.boundary_edges = {e for e, fs in self.edge_faces.items() if len(fs) == 1}
        self.boundary_vertices = {v for e in self.boundary_edges for v in e}
        # rings: per vertex (faces in ccw order, spokes a_0..a_k, closed)
        self.rings = []
        for s in range(n):
            fs = vertex_faces[s]
            if not fs:
                self.rings.append(([], [], False))
                continue
            closed = s not in self.boundary_vertices
            if closed:
                start = min(fs)
            else:
                starts = [f for f in fs if (self._after(f, s), s) not in self.halfedge]
                if len(starts) != 1:
                    raise ValueError("%s: vertex %d: its faces are not one fan" % (name, s))
                start = starts[0]
            ring, spokes = [], [self._after(start, s)]
            f = start
            while True:
                ring.append(f)
                b = self._after(f, s, 2)
                spokes.append(b)
                f = self.halfedge.get((s, b))
                if f is None or f == start:
                    break
            if len(ring) != len(fs):
                raise ValueError("%s: vertex %d: its faces are not one fan" % (name, s))
            self.rings.append((ring, spokes, closed))
        self.position_in_ring = [{f: i for i, f in enumerate(r[0])} for r in self.rings]

    def _after(self, f, s, steps=1):
        """The corner `steps` after s in face f."""
        tri = self.faces[f]
        return tri[(tri.index(s) + steps) % 3]


# --------------------------------------------------------------------------------------------
# Reading maps (VMAP-1)

def read_map(path, fmt, n_t, n_d):
    """The records of a map file: per vertex of T a tuple ('face', d, (w0, w1, w2)),
    ('halfedge', h0, h1, alpha, beta), ('vertices', [(j, w), ...]) or None (no image).
    Indices of D are 0-based; weights are floats (possibly NaN or infinite)."""
    lines = list(_lines(path))
    records = [None] * n_t
    if fmt == "plain":
        if not lines or lines[0][1] != ["fhr-vertex-map", "1"]:
            raise ValueError("%s:%d: the first line is not 'fhr-vertex-map 1'"
                             % (path, lines[0][0] if lines else 1))
        body = lines[1:]
        if not body or len(body[0][1]) != 1:
            raise ValueError("%s: expected the number of vertices after the header" % path)
        _count(path, body[0], n_t, "vertices of T")
        _fixed_records(path, body[1:], n_t, records, _plain_record)
    elif fmt == "corr":
        _fixed_records(path, lines, n_t, records, _corr_record)
    elif fmt == "vtpm":
        if lines and len(lines[0][1]) == 2:
            counts, body = [(lines[0][0], [t]) for t in lines[0][1]], lines[1:]
        elif len(lines) > 1 and len(lines[0][1]) == 1 and len(lines[1][1]) == 1:
            counts, body = lines[:2], lines[2:]
        else:
            raise ValueError("%s: expected the counts of the vertices of T and of D" % path)
        _count(path, counts[0], n_t, "vertices of T")
        _count(path, counts[1], n_d, "vertices of D")
        _fixed_records(path, body, n_t, records, _vtpm_record)
    elif fmt == "ijv":
        seen = {}
        for lineno, toks in lines:
            where = "%s:%d" % (path, lineno)
            if len(toks) != 3:
                raise ValueError("%s: expected 'i j w', found %d tokens" % (where, len(toks)))
            i, j = _int(toks[0], where), _int(toks[1], where)
            w = _real(toks[2], where)
            if not 1 <= i <= n_t:
                raise ValueError("%s: vertex %d of T out of range (1..%d)" % (where, i, n_t))
            entries = seen.setdefault(i - 1, [])
            if any(jj == j - 1 for jj, _ in entries):
                raise ValueError("%s: vertex %d: vertex %d of D named twice" % (where, i - 1, j))
            if len(entries) == 3:
                raise ValueError("%s: vertex %d: more than three lines" % (where, i - 1))
            entries.append((j - 1, w))
        for i, entries in seen.items():
            records[i] = ("vertices", entries)
    else:
        raise ValueError("%s: unknown map format '%s'" % (path, fmt))
    return records


def _count(path, line, expected, what):
    lineno, toks = line
    n = _int(toks[0], "%s:%d" % (path, lineno))
    if n != expected:
        raise ValueError("%s:%d: %d records announced, the mesh has %d %s"
                         % (path, lineno, n, expected, what))


def _fixed_records(path, lines, n_t, records, parse):
    if len(lines) != n_t:
        raise ValueError("%s: %d records for %d vertices of T" % (path, len(lines), n_t))
    for v, (lineno, toks) in enumerate(lines):
        records[v] = parse(toks, "%s:%d: vertex %d" % (path, lineno, v))


def _tokens(toks, where, n):
    if len(toks) != n:
        raise ValueError("%s: expected %d tokens, found %d" % (where, n, len(toks)))


def _plain_record(toks, where):
    _tokens(toks, where, 4)
    d = _int(toks[0], where)
    w = tuple(_real(t, where) for t in toks[1:])
    return None if d == -1 else ("face", d, w)


def _corr_record(toks, where):
    _tokens(toks, where, 4)
    t = _int(toks[0], where)
    w = tuple(_real(x, where) for x in toks[1:])
    return None if t == -1 else ("face", t - 1, w)


def _vtpm_record(toks, where):
    _tokens(toks, where, 4)
    h0, h1 = _int(toks[0], where), _int(toks[1], where)
    a, b = _real(toks[2], where), _real(toks[3], where)
    return None if (h0, h1) == (-1, -1) else ("halfedge", h0, h1, a, b)


# --------------------------------------------------------------------------------------------
# The points (VMAP-2)

class Image:
    """A point of D: the face d named for it and its exact normalized weights on the vertices of
    D with positive weight (its carrier: one vertex, an edge or the face d)."""

    def __init__(self, d, weights):
        self.d = d
        self.w = weights  # {vertex of D: Fraction > 0}, summing to 1
        self.carrier = tuple(sorted(weights))
        self.key = tuple(sorted(weights.items()))


def resolve(record, D):
    """(Image, None) or (None, reason) for one record of read_map."""
    if record is None:
        return None, "no entry"
    n_d, faces = len(D.mesh.positions), D.faces
    kind = record[0]
    if kind == "face":
        d, w = record[1], record[2]
        if not 0 <= d < len(faces):
            return None, "face %d of D out of range" % d
        corners = faces[d]
    elif kind == "halfedge":
        h0, h1, a, b = record[1:]
        if not (0 <= h0 < n_d and 0 <= h1 < n_d):
            return None, "halfedge %d-%d: vertex of D out of range" % (h0, h1)
        d = D.halfedge.get((h0, h1))
        if d is None:
            return None, "no face of D to the left of the halfedge %d-%d" % (h0, h1)
        if not (math.isfinite(a) and math.isfinite(b)):
            return None, "weight is not finite"
        h2 = D._after(d, h1)
        one = 1 - Fraction(a) - Fraction(b)
        return _image(d, {h0: one, h1: Fraction(a), h2: Fraction(b)})
    else:
        entries = record[1]
        named = [j for j, _ in entries]
        if not all(0 <= j < n_d for j in named):
            return None, "vertex of D out of range"
        d = _face_holding(D, named)
        if d is None:
            return None, "vertices %s of D are not a vertex, edge or face of D" % sorted(named)
        w = tuple(dict(entries).get(c, 0.0) for c in faces[d])
        corners = faces[d]
    if not all(math.isfinite(x) for x in w):
        return None, "weight is not finite"
    return _image(d, {c: Fraction(x) for c, x in zip(corners, w)})


def _face_holding(D, named):
    if len(named) == 1:
        ring = D.rings[named[0]][0]
        return min(ring) if ring else None
    if len(named) == 2:
        fs = D.edge_faces.get((min(named), max(named)))
        return fs[0] if fs else None
    fs = [f for f in D.edge_faces.get((min(named[:2]), max(named[:2])), [])
          if set(D.faces[f]) == set(named)]
    return min(fs) if fs else None


def _image(d, weights):
    if any(x < -TOL for x in weights.values()):
        return None, "weight below -1e-12"
    if abs(sum(weights.values()) - 1) > TOL:
        return None, "weights do not sum to 1 within 1e-12"
    positive = {c: x for c, x in weights.items() if x > 0}
    total = sum(positive.values())
    return Image(d, {c: x / total for c, x in positive.items()}), None


# --------------------------------------------------------------------------------------------
# Exact plane helpers

def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _orient(a, b, c):
    return _cross(_sub(b, a), _sub(c, a))


def _sign(x):
    return (x > 0) - (x < 0)


def _coords(D, f, point):
    """A point of D ({vertex: weight}) in face f's barycentric plane (w1, w2)."""
    tri = D.faces[f]
    return (point.get(tri[1], Fraction(0)), point.get(tri[2], Fraction(0)))


def unfold(positions, s, spokes):
    """The spec's unfolding of the fan around s with spokes a_0..a_{m+1}: the doubles P_0..P_{m+1}
    (s at the origin), computed in the order the spec writes."""
    sx, sy, sz = positions[s]
    e = []
    for a in spokes:
        ax, ay, az = positions[a]
        e.append((ax - sx, ay - sy, az - sz))
    ex, ey, ez = e[0]
    P = [(math.sqrt(ex * ex + ey * ey + ez * ez), 0.0)]
    for i in range(len(spokes) - 1):
        ex, ey, ez = e[i]
        fx, fy, fz = e[i + 1]
        d = ex * fx + ey * fy + ez * fz
        cx, cy, cz = ey * fz - ez * fy, ez * fx - ex * fz, ex * fy - ey * fx
        k = math.sqrt(cx * cx + cy * cy + cz * cz)
        l = ex * ex + ey * ey + ez * ez
        x, y = P[-1]
        P.append(((d * x - k * y) / l, (d * y + k * x) / l))
    return P


def _exact(P):
    return [(Fraction(x), Fraction(y)) for x, y in P]


def _in_fan(point, a, b, Pa, Pb):
    """A point of D in face (s, a, b) placed in the unfolding: w_a * P_a + w_b * P_b."""
    wa, wb = point.get(a, 0), point.get(b, 0)
    return (wa * Pa[0] + wb * Pb[0], wa * Pa[1] + wb * Pb[1])


# --------------------------------------------------------------------------------------------
# The rule `adjacent`

class EdgeImage:
    """The image of an edge u -> v of T: the polyline of points of D from u's image to v's, and
    per piece the faces of D holding it."""

    def __init__(self, points, piece_faces):
        self.points = points
        self.piece_faces = piece_faces

    def first_piece(self, from_start):
        """(faces, X, Y): the first piece seen from one end, X that end's image."""
        if from_start:
            return self.piece_faces[0], self.points[0], self.points[1]
        return self.piece_faces[-1], self.points[-1], self.points[-2]


def _holds(D, f, img):
    if len(img.carrier) == 3:
        return f == img.d
    tri = D.faces[f]
    return all(c in tri for c in img.carrier)


def _faces_at(D, img):
    if len(img.carrier) == 1:
        return D.rings[img.carrier[0]][0]
    if len(img.carrier) == 2:
        return D.edge_faces.get(img.carrier, [])
    return [img.d]


def map_edge(D, iu, iv):
    """The EdgeImage of an edge from image iu to image iv under the rule, or None."""
    common = sorted(f for f in _faces_at(D, iu) if _holds(D, f, iv))
    if common:
        return EdgeImage([iu.w, iv.w], [tuple(common)])
    verts_u = {c for f in _faces_at(D, iu) for c in D.faces[f]}
    verts_v = {c for f in _faces_at(D, iv) for c in D.faces[f]}
    best = None  # (length, s, m, u first, A, B, exact unfolding, its spokes, its faces)
    for s in sorted(verts_u & verts_v):
        ring, spokes, closed = D.rings[s]
        k = len(ring)
        in_u = [_holds(D, f, iu) for f in ring]
        in_v = [_holds(D, f, iv) for f in ring]
        longest = k - 2 if closed else k - 1  # a fan is shorter than a closed ring
        for p in range(k):
            if not (in_u[p] or in_v[p]):
                continue
            fan_spokes = [spokes[(p + i) % k] for i in range(longest + 2)] if closed else spokes[p:]
            PE = None  # the unfolding from f_p on, made when a candidate needs it
            for m in range(1, longest + 1):
                if not closed and p + m >= k:
                    break
                q = (p + m) % k
                if in_u[p] and in_v[q]:
                    first, last = iu, iv
                elif in_v[p] and in_u[q]:
                    first, last = iv, iu
                else:
                    continue
                if PE is None:
                    PE = _exact(unfold(D.mesh.positions, s, fan_spokes))
                A = _in_fan(first.w, fan_spokes[0], fan_spokes[1], PE[0], PE[1])
                B = _in_fan(last.w, fan_spokes[m], fan_spokes[m + 1], PE[m], PE[m + 1])
                if not _crosses_spokes(A, B, PE[1:m + 1]):
                    continue
                ax, ay, bx, by = float(A[0]), float(A[1]), float(B[0]), float(B[1])
                length = math.sqrt((bx - ax) * (bx - ax) + (by - ay) * (by - ay))
                if best is None or length < best[0]:
                    best = (length, s, m, first is iu, A, B, PE, fan_spokes,
                            [ring[(p + i) % k] for i in range(m + 1)])
    if best is None:
        return None
    _, s, m, forward, A, B, PE, seq, fan = best
    points = [(iu if forward else iv).w]
    d = _sub(B, A)
    for j in range(1, m + 1):
        t = _cross(d, A) / _cross(d, PE[j])
        points.append({s: 1 - t, seq[j]: t})
    points.append((iv if forward else iu).w)
    piece_faces = [(f,) for f in fan]
    if not forward:
        points.reverse()
        piece_faces.reverse()
    return EdgeImage(points, piece_faces)


def _crosses_spokes(A, B, spokes):
    """Does segment AB cross every spoke (O, P) properly (the four orientations non-zero)?"""
    O = (0, 0)
    for P in spokes:
        o1, o2 = _sign(_orient(A, B, O)), _sign(_orient(A, B, P))
        o3, o4 = _sign(_orient(O, P, A)), _sign(_orient(O, P, B))
        if o1 * o2 != -1 or o3 * o4 != -1:
            return False
    return True


# --------------------------------------------------------------------------------------------
# VMAP-6: pieces meeting improperly

def _meet(p0, p1, q0, q1):
    """The intersection of two closed segments: None, a point, or 'overlap' (positive length)."""
    if p0 == p1 or q0 == q1:
        if p0 == p1 and q0 == q1:
            return p0 if p0 == q0 else None
        pt, (a, b) = (p0, (q0, q1)) if p0 == p1 else (q0, (p0, p1))
        return pt if _on_segment(pt, a, b) else None
    o1, o2 = _orient(p0, p1, q0), _orient(p0, p1, q1)
    if o1 == 0 and o2 == 0:
        d = _sub(p1, p0)
        length = d[0] * d[0] + d[1] * d[1]
        t0 = (q0[0] - p0[0]) * d[0] + (q0[1] - p0[1]) * d[1]
        t1 = (q1[0] - p0[0]) * d[0] + (q1[1] - p0[1]) * d[1]
        lo, hi = max(Fraction(0), min(t0, t1)), min(length, max(t0, t1))
        if lo > hi:
            return None
        if lo < hi:
            return "overlap"
        r = lo / length
        return (p0[0] + r * d[0], p0[1] + r * d[1])
    if _sign(o1) * _sign(o2) > 0:
        return None
    o3, o4 = _orient(q0, q1, p0), _orient(q0, q1, p1)
    if _sign(o3) * _sign(o4) > 0:
        return None
    t = o1 / (o1 - o2)
    return (q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1]))


def _on_segment(p, a, b):
    return _orient(a, b, p) == 0 and min(a[0], b[0]) <= p[0] <= max(a[0], b[0]) \
        and min(a[1], b[1]) <= p[1] <= max(a[1], b[1])


def _candidate_pairs(boxes):
    """Index pairs of boxes (xlo, ylo, xhi, yhi) that may meet: a uniform grid of about one cell
    per box over their extent (closed boxes, padded so float rounding loses no contact)."""
    n = len(boxes)
    if n < 48:
        return {(i, j) for i in range(n) for j in range(i + 1, n)}
    x0 = min(b[0] for b in boxes)
    y0 = min(b[1] for b in boxes)
    x1 = max(b[2] for b in boxes)
    y1 = max(b[3] for b in boxes)
    g = max(1, int(math.sqrt(n)))
    cw, ch = max(x1 - x0, 1e-300) / g, max(y1 - y0, 1e-300) / g
    cells = {}
    pad = 1e-9 * max(x1 - x0, y1 - y0, 1e-300)
    for i, (a, b, c, d) in enumerate(boxes):
        for cx in range(max(0, int((a - pad - x0) / cw)), min(g - 1, int((c + pad - x0) / cw)) + 1):
            for cy in range(max(0, int((b - pad - y0) / ch)), min(g - 1, int((d + pad - y0) / ch)) + 1):
                cells.setdefault((cx, cy), []).append(i)
    pairs = set()
    for members in cells.values():
        for x in range(len(members)):
            for y in range(x + 1, len(members)):
                pairs.add((members[x], members[y]))
    return pairs


def crossing_pairs(D, images, edge_images):
    """Sorted pairs of T edges ((u1, v1), (u2, v2)) whose pieces meet improperly (VMAP-6)."""
    per_face = {}
    for e, ei in edge_images.items():
        for n, faces in enumerate(ei.piece_faces):
            for f in faces:
                per_face.setdefault(f, []).append((e, ei.points[n], ei.points[n + 1]))
    found = set()
    for f, pieces in per_face.items():
        segs = [(e, _coords(D, f, a), _coords(D, f, b)) for e, a, b in pieces]
        boxes = [_box(a, b) for _, a, b in segs]
        for i, j in _candidate_pairs(boxes):
            e1, p0, p1 = segs[i]
            e2, q0, q1 = segs[j]
            pair = (e1, e2) if e1 < e2 else (e2, e1)
            if e1 == e2 or pair in found or not _boxes_meet(boxes[i], boxes[j]):
                continue
            common = set(e1) & set(e2)
            allowed = _coords(D, f, images[common.pop()].w) if common else None
            if _improper(p0, p1, q0, q1, allowed):
                found.add(pair)
    return sorted(found)


def _box(a, b):
    """A closed float box holding the exact segment ab (each bound one step outward)."""
    xs, ys = (float(a[0]), float(b[0])), (float(a[1]), float(b[1]))
    return (math.nextafter(min(xs), -math.inf), math.nextafter(min(ys), -math.inf),
            math.nextafter(max(xs), math.inf), math.nextafter(max(ys), math.inf))


def _boxes_meet(a, b):
    return a[0] <= b[2] and b[0] <= a[2] and a[1] <= b[3] and b[1] <= a[3]


def _improper(p0, p1, q0, q1, allowed):
    """Do pieces p and q share a point other than `allowed` (the image of their edges' common
    end, or None), or overlap collinearly?"""
    if allowed is not None and allowed in (p0, p1) and allowed in (q0, q1):
        P = p1 if p0 == allowed else p0
        Q = q1 if q0 == allowed else q0
        if P != allowed and Q != allowed:
            # two segments from one point meet elsewhere only along a common direction
            u, v = _sub(P, allowed), _sub(Q, allowed)
            return _cross(u, v) == 0 and u[0] * v[0] + u[1] * v[1] > 0
    meet = _meet(p0, p1, q0, q1)
    return meet is not None and (meet == "overlap" or meet != allowed)


# --------------------------------------------------------------------------------------------
# VMAP-7 and VMAP-8: tangents at a vertex's image

def _corner_left(D, img, t1, t2):
    """Do the tangents t1, t2 (first pieces (faces, X, Y)) at img turn counter-clockwise by an
    angle strictly between 0 and pi?"""
    (F1, X, Y1), (F2, _, Y2) = t1, t2
    if X == Y1 or X == Y2:
        return False
    common = sorted(set(F1) & set(F2))
    if common:
        f = common[0]
        x = _coords(D, f, X)
        return _cross(_sub(_coords(D, f, Y1), x), _sub(_coords(D, f, Y2), x)) > 0
    if len(img.carrier) == 1:
        s = img.carrier[0]
        ring, spokes, closed = D.rings[s]
        k = len(ring)
        p = D.position_in_ring[s][_sector_face(D, img, F1, X, Y1)]
        m = 1
        while True:
            if m >= k or (not closed and p + m >= k):
                return False
            if ring[(p + m) % k] in F2:
                break
            m += 1
        seq = [spokes[(p + i) % k] for i in range(m + 2)] if closed else spokes[p:p + m + 2]
        PE = _exact(unfold(D.mesh.positions, s, seq))
        T1 = _in_fan(Y1, seq[0], seq[1], PE[0], PE[1])
        T2 = _in_fan(Y2, seq[m], seq[m + 1], PE[m], PE[m + 1])
        return all(_cross(T1, PE[j]) > 0 for j in range(1, m + 1)) and _cross(T1, T2) > 0
    # a point inside an edge (p, q) of D; F1 is the one face holding the halfedge p -> q
    (g1,) = F1
    tri = D.faces[g1]
    i = next(i for i in range(3) if {tri[i], tri[(i + 1) % 3]} == set(img.carrier))
    p, q, r = tri[i], tri[(i + 1) % 3], tri[(i + 2) % 3]
    g2 = D.halfedge[(q, p)]  # F2 is {g2}: the other face at the edge
    t = D._after(g2, p)
    PE = _exact(unfold(D.mesh.positions, q, [r, p, t]))
    x = _in_fan(X, r, p, PE[0], PE[1])
    T1 = _sub(_in_fan(Y1, r, p, PE[0], PE[1]), x)
    T2 = _sub(_in_fan(Y2, p, t, PE[1], PE[2]), x)
    # the spoke passed, from the point toward p, is left of T1 by construction:
    # cross(T1, P_1 - x) = (1 - w_p) * w_r * cross(P_0, P_1) > 0 for T1 strictly inside g1
    return _cross(T1, T2) > 0


def _sector_face(D, img, faces, X, Y):
    """The face of D whose sector around img holds the direction of the piece from X toward Y:
    the one face holding the piece, or, for a piece along an interior edge of D (held by its two
    faces), the face holding the halfedge x -> y of that edge in the piece's direction."""
    if len(faces) == 1:
        return faces[0]
    if len(img.carrier) == 1:
        x = img.carrier[0]
        y = next(c for c in Y if c != x)
    else:
        y = next(c for c in img.carrier if Y.get(c, 0) > X.get(c, 0))
        x = next(c for c in img.carrier if c != y)
    return D.halfedge[(x, y)]


def _position(D, img, tangent):
    """The cyclic position of a tangent among the faces of D around img: (sector, half, direction),
    ordered by _compare."""
    faces, X, Y = tangent
    f = _sector_face(D, img, faces, X, Y)
    tri = D.faces[f]
    if len(img.carrier) == 1:
        s = img.carrier[0]
        sector = D.position_in_ring[s][f]
        start = tri[(tri.index(s) + 1) % 3]
    elif len(img.carrier) == 2:
        i = next(i for i in range(3) if {tri[i], tri[(i + 1) % 3]} == set(img.carrier))
        start = tri[(i + 1) % 3]
        sector = D.edge_faces[img.carrier].index(f)
    else:
        sector, start = 0, tri[0]
    x = _coords(D, f, X)
    r = _sub(_coords(D, f, {start: Fraction(1)}), x)
    d = _sub(_coords(D, f, Y), x)
    c = _cross(r, d)
    half = 0 if c > 0 or (c == 0 and r[0] * d[0] + r[1] * d[1] > 0) else 1
    return (sector, half, d)


def _compare(a, b):
    if a[:2] != b[:2]:
        return -1 if a[:2] < b[:2] else 1
    return -_sign(_cross(a[2], b[2]))


def _winds_once(D, img, tangents, closed):
    if any(X == Y for _, X, Y in tangents):
        return False
    pos = [_position(D, img, t) for t in tangents]
    if closed:
        wraps = sum(1 for i in range(len(pos)) if _compare(pos[(i + 1) % len(pos)], pos[i]) < 0)
        return wraps == 1
    first = pos[0]

    def key_less(a, b):
        ka, kb = int(_compare(a, first) < 0), int(_compare(b, first) < 0)
        return ka < kb if ka != kb else _compare(a, b) < 0

    return all(key_less(pos[i - 1], pos[i]) for i in range(1, len(pos)))


# --------------------------------------------------------------------------------------------
# The analysis

def analyze(T_mesh, D_mesh, records):
    """Every decision listed in the module docstring, as one dict."""
    T = Manifold(T_mesh, T_mesh.path)
    D = Manifold(D_mesh, D_mesh.path)
    images, missing = [], []
    for v, rec in enumerate(records):
        img, _ = resolve(rec, D)
        images.append(img)
        if img is None:
            missing.append(v)
    edge_images, no_image = {}, []
    for e in sorted(T.edge_faces):
        u, v = e
        ei = map_edge(D, images[u], images[v]) if images[u] and images[v] else None
        if ei is None:
            no_image.append(list(e))
        else:
            edge_images[e] = ei

    def tangent(u, v):
        e = (min(u, v), max(u, v))
        return edge_images[e].first_piece(u == e[0]) if e in edge_images else None

    groups = {}
    for v, img in enumerate(images):
        if img is not None:
            groups.setdefault(img.key, []).append(v)
    coincident = sorted([a, b] for vs in groups.values() for i, a in enumerate(vs) for b in vs[i + 1:])

    folded = []
    for f, tri in enumerate(T.faces):
        for k in range(3):
            u, v, w = tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]
            t1, t2 = tangent(u, v), tangent(u, w)
            if t1 is not None and t2 is not None and not _corner_left(D, images[u], t1, t2):
                folded.append(f)
                break

    winding = []
    for u, (ring, spokes, closed) in enumerate(T.rings):
        if not ring:
            continue
        nbrs = spokes[:-1] if closed else spokes
        tangents = [tangent(u, v) for v in nbrs]
        if all(t is not None for t in tangents) and not _winds_once(D, images[u], tangents, closed):
            winding.append(u)

    bad_edges = [list(e) for e in sorted(T.boundary_edges) if e in edge_images
                 and not _on_boundary(D, set(images[e[0]].carrier) | set(images[e[1]].carrier))]
    bad_vertices = [v for v, img in enumerate(images)
                    if img is not None and v not in T.boundary_vertices and T.rings[v][0]
                    and _on_boundary(D, set(img.carrier))]

    return {
        "vertices": len(T_mesh.positions),
        "faces": len(T_mesh.faces),
        "vertices_without_image": missing,
        "edges_without_image": no_image,
        "crossing_pairs": [[list(a), list(b)] for a, b in crossing_pairs(D, images, edge_images)],
        "coincident_vertices": coincident,
        "folded_faces": folded,
        "winding_failures": winding,
        "boundary_failures": {"edges": bad_edges, "vertices": bad_vertices},
    }


def _on_boundary(D, support):
    """Is the vertex or edge of D spanned by `support` on the boundary of D?"""
    if len(support) == 1:
        return next(iter(support)) in D.boundary_vertices
    if len(support) == 2:
        return tuple(sorted(support)) in D.boundary_edges
    return False


def format_of(path, fmt=None):
    if fmt is not None:
        if fmt not in FORMATS:
            raise ValueError("unknown map format '%s' (plain, corr, vtpm or ijv)" % fmt)
        return fmt
    for name, ext in FORMATS.items():
        if str(path).lower().endswith(ext):
            return name
    raise ValueError("%s: unknown map format (.vmap, .corr, .vtpm or .ijv, or --format)" % path)


def judge(map_path, domain_path, mesh_path, fmt=None):
    """Reads the three files and returns analyze's dict."""
    D_mesh, T_mesh = read_off(domain_path), read_off(mesh_path)
    records = read_map(map_path, format_of(map_path, fmt), len(T_mesh.positions),
                       len(D_mesh.positions))
    return analyze(T_mesh, D_mesh, records)


def main(argv=None):
    parser = argparse.ArgumentParser(prog="vertex_map_reference.py",
                                     description="Judge a per-vertex map (spec/vertex_map.md).")
    parser.add_argument("map")
    parser.add_argument("--domain", required=True)
    parser.add_argument("--mesh", required=True)
    parser.add_argument("--format", choices=sorted(FORMATS))
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args(argv)
    try:
        result = judge(args.map, args.domain, args.mesh, args.format)
    except (ValueError, OSError) as exc:
        print("vertex_map_reference: error: %s" % str(exc).splitlines()[0], file=sys.stderr)
        return 2
    print(json.dumps(result, separators=(",", ":")) if args.json else json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
