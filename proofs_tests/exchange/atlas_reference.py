#!/usr/bin/python3
"""An independent Python reference for judging UV atlases (spec/atlas.md, ATLAS-*) and for the
distortion figures of a piecewise-linear map (spec/distortion.md, DIST-*).

It reads an OBJ or PLY atlas (ATLAS-1: a file with a face that is not a triangle, a corner
without texture coordinates, a number that is not finite or an index out of range is refused
with a one-line ValueError), welds seam duplicates (records at one 3D position on the boundary of
the surface over the file's indices; -0 = +0), forms the charts
and decides, per texture:

  * degenerate UV triangles (ATLAS-3), folded faces and mirrored charts (ATLAS-4);
  * T-vertices and torn edges (ATLAS-5);
  * overlapping pairs (ATLAS-6) and contacts (ATLAS-7);

and computes the figures: charts, mirrored charts, seam length, the two packing ratios and the
distortion figures DIST-1..9. It does not decide ATLAS-2 (the surface's topology) or ATLAS-8
(the comparison with an input mesh), and it does not skip checks when another fails: a face with
a degenerate UV triangle belongs to its chart but takes part in no fold, overlap or contact test.

Every decision is exact. A double is a dyadic rational (``Fraction(x)`` holds it exactly); within
one texture all UV coordinates are multiplied by one common power of two, which turns them into
Python integers with the same ratios, so orient2d, the chart sums, the overlap and the contact
tests are exact integer (hence exact rational) arithmetic. 3D collinearity (T-vertices) and the
torn-edge distance use ``Fraction``. Floats are used only for the figures (distortion via the SVD
of each face's Jacobian, packing via shapely's polygon union, Debian package python3-shapely).

Usage:  atlas_reference.py FILE [--json]
prints one JSON object (indented, or on one line with --json) with the keys folded_faces,
overlapping_pairs, contacts, degenerate_uv (0-based face indices in file order; pairs [f, g]
with f < g, sorted), t_vertices ([w, a, b]: file vertex w, the first of its position, strictly
inside the boundary edge a-b), torn_edges ([f, g]: the two faces across the torn edge), charts,
mirrored_charts, chart_sign_disagreements (the lowest face of each chart whose compensated float
sum of orient2d has another sign than the exact sum; empty in practice), seam_length,
packing_unit_square, packing_bounding_square, distortion, faces and textures. A file that breaks
ATLAS-1 is refused with a one-line message on stderr and exit code 2.
"""

import bisect
import json
import math
import re
import struct
import sys
from fractions import Fraction

import numpy as np

__all__ = ["Atlas", "read_atlas", "read_obj", "read_ply", "analyze", "overlaps_and_contacts",
           "distortion_figures", "weighted_percentile", "orient2d_exact"]


# --------------------------------------------------------------------------------------------
# The atlas: positions per file vertex, and per face its three vertex indices, its three UV
# points (doubles as read) and its texture key.

class Atlas:
    """A triangle mesh whose every face corner carries (u, v).

    positions: list of (x, y, z) floats, one per vertex of the file (0-based)
    faces:     list of (i, j, k) file vertex indices, one per face in file order
    uvs:       list of ((u0, v0), (u1, v1), (u2, v2)) floats, per face corner
    textures:  list of a hashable texture key per face (OBJ: the usemtl name or None;
               PLY: texnumber)
    """

    def __init__(self, positions, faces, uvs, textures=None, path="<atlas>"):
        self.path = path
        self.positions = [tuple(float(c) for c in p) for p in positions]
        self.faces = [tuple(int(i) for i in f) for f in faces]
        self.uvs = [tuple((float(u), float(v)) for (u, v) in t) for t in uvs]
        self.textures = list(textures) if textures is not None else [None] * len(self.faces)
        if not (len(self.faces) == len(self.uvs) == len(self.textures)):
            raise ValueError("%s: faces, uvs and textures differ in length" % path)
        for n, f in enumerate(self.faces):
            if len(f) != 3 or len(self.uvs[n]) != 3:
                raise ValueError("%s: face %d: not a triangle" % (path, n))
            for i in f:
                if not 0 <= i < len(self.positions):
                    raise ValueError("%s: face %d: vertex index %d out of range (0..%d)"
                                     % (path, n, i, len(self.positions) - 1))
            for c in self.uvs[n]:
                if not (math.isfinite(c[0]) and math.isfinite(c[1])):
                    raise ValueError("%s: face %d: texture coordinate is not finite" % (path, n))
        for n, p in enumerate(self.positions):
            if not all(math.isfinite(c) for c in p):
                raise ValueError("%s: vertex %d: coordinate is not finite" % (path, n))


# --------------------------------------------------------------------------------------------
# Reading (ATLAS-1)

_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?\Z")
_INTEGER = re.compile(r"[+-]?\d+\Z")


def _number(tok, where):
    if _NUMBER.match(tok):
        x = float(tok)
        if not math.isfinite(x):
            raise ValueError("%s: number '%s' is not finite (out of double range)" % (where, tok))
        return x
    try:
        x = float(tok)
    except ValueError:
        x = None
    if x is not None and not math.isfinite(x):
        raise ValueError("%s: number '%s' is not finite" % (where, tok))
    raise ValueError("%s: expected a number, found '%s'" % (where, tok))


def read_obj(path):
    """Reads `v`, `vt`, `f` (corners i/t or i/t/n; 1-based or negative indices) and `usemtl`;
    every other statement is ignored."""
    with open(path, "rb") as fh:
        text = fh.read().decode("latin-1")
    positions, texcoords = [], []
    raw_faces = []  # (line, face number, [(vertex index, texcoord index)], texture)
    texture = None
    for lineno, line in enumerate(text.split("\n"), 1):
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        parts = line.split()
        kw = parts[0]
        where = "%s:%d" % (path, lineno)
        if kw == "v":
            if len(parts) not in (4, 5, 7):
                raise ValueError("%s: vertex %d: expected 3, 4 or 6 numbers" % (where, len(positions)))
            vals = [_number(t, "%s: vertex %d" % (where, len(positions))) for t in parts[1:]]
            positions.append((vals[0], vals[1], vals[2]))
        elif kw == "vt":
            if len(parts) not in (3, 4):
                raise ValueError("%s: texture coordinate %d: expected 2 or 3 numbers"
                                 % (where, len(texcoords)))
            vals = [_number(t, "%s: texture coordinate %d" % (where, len(texcoords))) for t in parts[1:]]
            texcoords.append((vals[0], vals[1]))
        elif kw == "f":
            fno = len(raw_faces)
            fwhere = "%s: face %d" % (where, fno)
            corners = parts[1:]
            if len(corners) != 3:
                raise ValueError("%s: has %d corners (an atlas face is a triangle)" % (fwhere, len(corners)))
            resolved = []
            for c in corners:
                fields = c.split("/")
                if len(fields) < 2 or fields[1] == "":
                    raise ValueError("%s: corner '%s' has no texture coordinate" % (fwhere, c))
                if len(fields) > 3 or not _INTEGER.match(fields[0]) or not _INTEGER.match(fields[1]) \
                        or (len(fields) == 3 and fields[2] != "" and not _INTEGER.match(fields[2])):
                    raise ValueError("%s: malformed corner '%s'" % (fwhere, c))
                vi, ti = int(fields[0]), int(fields[1])
                pair = []
                for value, count, what in ((vi, len(positions), "vertex"), (ti, len(texcoords), "texture")):
                    if value == 0:
                        raise ValueError("%s: %s index 0 (OBJ indices are 1-based)" % (fwhere, what))
                    if value < 0:
                        if count + value < 0:
                            raise ValueError("%s: relative %s index %d out of range" % (fwhere, what, value))
                        pair.append(count + value)
                    else:
                        pair.append(value - 1)
                resolved.append(tuple(pair))
            raw_faces.append((lineno, fno, resolved, texture))
        elif kw == "usemtl":
            texture = line[len("usemtl"):].strip()
        # every other statement is ignored
    if not raw_faces:
        raise ValueError("%s: no faces" % path)
    faces, uvs, textures = [], [], []
    for lineno, fno, corners, tex in raw_faces:
        for vi, ti in corners:
            if vi >= len(positions):
                raise ValueError("%s:%d: face %d: vertex index %d out of range (1..%d)"
                                 % (path, lineno, fno, vi + 1, len(positions)))
            if ti >= len(texcoords):
                raise ValueError("%s:%d: face %d: texture index %d out of range (1..%d)"
                                 % (path, lineno, fno, ti + 1, len(texcoords)))
        faces.append(tuple(vi for vi, _ in corners))
        uvs.append(tuple(texcoords[ti] for _, ti in corners))
        textures.append(tex)
    return Atlas(positions, faces, uvs, textures, path)


_PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
    "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


def _ply_header(data, path):
    pos = 0
    lines = []
    while True:
        nl = data.find(b"\n", pos)
        if nl < 0:
            raise ValueError("%s: PLY header without end_header" % path)
        line = data[pos:nl].rstrip(b"\r").decode("latin-1")
        pos = nl + 1
        lines.append(line)
        if line.strip() == "end_header":
            break
    if not lines or lines[0].strip() != "ply":
        raise ValueError("%s:1: not a PLY file (first line is not 'ply')" % path)
    fmt = None
    elements = []  # [name, count, [(name, kind, type, count type)], header line]
    for lineno, line in enumerate(lines[1:-1], 2):
        parts = line.split()
        if not parts or parts[0] in ("comment", "obj_info"):
            continue
        where = "%s:%d" % (path, lineno)
        if parts[0] == "format":
            if len(parts) != 3 or parts[1] not in ("ascii", "binary_little_endian", "binary_big_endian") \
                    or parts[2] != "1.0":
                raise ValueError("%s: unsupported format line '%s'" % (where, line))
            fmt = parts[1]
        elif parts[0] == "element":
            if len(parts) != 3 or not _INTEGER.match(parts[2]) or int(parts[2]) < 0:
                raise ValueError("%s: malformed element line '%s'" % (where, line))
            elements.append([parts[1], int(parts[2]), [], lineno])
        elif parts[0] == "property":
            if not elements:
                raise ValueError("%s: property before any element" % where)
            if len(parts) == 5 and parts[1] == "list":
                if parts[2] not in _PLY_TYPES or parts[3] not in _PLY_TYPES or _PLY_TYPES[parts[2]] in "fd":
                    raise ValueError("%s: bad list property '%s'" % (where, line))
                elements[-1][2].append((parts[4], "list", _PLY_TYPES[parts[3]], _PLY_TYPES[parts[2]]))
            elif len(parts) == 3 and parts[1] in _PLY_TYPES:
                elements[-1][2].append((parts[2], "scalar", _PLY_TYPES[parts[1]], None))
            else:
                raise ValueError("%s: bad property line '%s'" % (where, line))
        else:
            raise ValueError("%s: unexpected header line '%s'" % (where, line))
    if fmt is None:
        raise ValueError("%s: PLY header without a format line" % path)
    return fmt, elements, pos, len(lines)


def _ply_records_ascii(text_lines, first_lineno, elements, path):
    """Yields (element name, record number, line, {property: value}) for every record."""
    it = iter(enumerate(text_lines, first_lineno))
    for name, count, props, _ in elements:
        for r in range(count):
            for lineno, line in it:
                if line.strip():
                    break
            else:
                raise ValueError("%s: %s %d: unexpected end of data" % (path, name, r))
            toks = line.split()
            where = "%s:%d: %s %d" % (path, lineno, name, r)
            values, k = {}, 0
            for pname, kind, typ, ctyp in props:
                if kind == "scalar":
                    if k >= len(toks):
                        raise ValueError("%s: too few values" % where)
                    values[pname] = _ply_ascii_value(toks[k], typ, where)
                    k += 1
                else:
                    if k >= len(toks):
                        raise ValueError("%s: too few values" % where)
                    n = _ply_ascii_value(toks[k], ctyp, where)
                    if n < 0 or k + 1 + n > len(toks):
                        raise ValueError("%s: list '%s' runs past the line" % (where, pname))
                    values[pname] = [_ply_ascii_value(t, typ, where) for t in toks[k + 1:k + 1 + n]]
                    k += 1 + n
            if k != len(toks):
                raise ValueError("%s: %d values beyond the declared properties" % (where, len(toks) - k))
            yield name, r, lineno, values
    for lineno, line in it:
        if line.strip():
            raise ValueError("%s:%d: unexpected data after the last element" % (path, lineno))


def _ply_ascii_value(tok, typ, where):
    if typ in "fd":
        return _number(tok, where)
    if not _INTEGER.match(tok):
        raise ValueError("%s: expected an integer, found '%s'" % (where, tok))
    return int(tok)


def _ply_records_binary(data, pos, elements, endian, path):
    for name, count, props, _ in elements:
        if all(kind == "scalar" for _, kind, _, _ in props):
            dtype = np.dtype([(p, endian + t) for p, _, t, _ in props])
            need = dtype.itemsize * count
            if pos + need > len(data):
                raise ValueError("%s: %s: unexpected end of data" % (path, name))
            arr = np.frombuffer(data, dtype=dtype, count=count, offset=pos)
            pos += need
            cols = {p: arr[p].tolist() for p, _, _, _ in props}
            for r in range(count):
                yield name, r, None, {p: cols[p][r] for p in cols}
            continue
        for r in range(count):
            values = {}
            for pname, kind, typ, ctyp in props:
                try:
                    if kind == "scalar":
                        (values[pname],) = struct.unpack_from(endian + typ, data, pos)
                        pos += struct.calcsize(typ)
                    else:
                        (n,) = struct.unpack_from(endian + ctyp, data, pos)
                        pos += struct.calcsize(ctyp)
                        values[pname] = list(struct.unpack_from("%s%d%s" % (endian, n, typ), data, pos))
                        pos += n * struct.calcsize(typ)
                except struct.error:
                    raise ValueError("%s: %s %d: unexpected end of data" % (path, name, r)) from None
            yield name, r, None, values
    if pos != len(data):
        raise ValueError("%s: unexpected data after the last element" % path)


def read_ply(path):
    """Reads ascii and binary PLY: vertex x, y, z with optional per-vertex u v / s t /
    texture_u texture_v; face vertex_indices (or vertex_index), optional texcoord (6 numbers,
    wins over the per-vertex coordinates) and texnumber (0 when absent)."""
    with open(path, "rb") as fh:
        data = fh.read()
    fmt, elements, pos, header_lines = _ply_header(data, path)
    by_name = {e[0]: e for e in elements}
    if "vertex" not in by_name or "face" not in by_name:
        raise ValueError("%s: PLY file without vertex or face element" % path)
    vprops = {p[0]: p for p in by_name["vertex"][2]}
    fprops = {p[0]: p for p in by_name["face"][2]}
    for c in "xyz":
        if c not in vprops or vprops[c][1] != "scalar":
            raise ValueError("%s: vertex element without scalar property %s" % (path, c))
    index_name = "vertex_indices" if "vertex_indices" in fprops else (
        "vertex_index" if "vertex_index" in fprops else None)
    if index_name is None or fprops[index_name][1] != "list":
        raise ValueError("%s: face element without a vertex_indices list" % path)
    uv_names = None
    for a, b in (("u", "v"), ("s", "t"), ("texture_u", "texture_v")):
        if a in vprops and b in vprops:
            uv_names = (a, b)
            break
    per_face = "texcoord" in fprops and fprops["texcoord"][1] == "list"
    if uv_names is None and not per_face:
        raise ValueError("%s: no texture coordinates (neither per-vertex u v nor per-face texcoord)" % path)
    if fmt == "ascii":
        body = data[pos:].decode("latin-1").split("\n")
        records = _ply_records_ascii([l.rstrip("\r") for l in body], header_lines + 1, elements, path)
    else:
        records = _ply_records_binary(data, pos, elements, "<" if fmt == "binary_little_endian" else ">", path)
    positions, vertex_uv, faces, uvs, textures = [], [], [], [], []
    face_where = []
    for name, r, lineno, values in records:
        where = "%s%s: %s %d" % (path, "" if lineno is None else ":%d" % lineno, name, r)
        if name == "vertex":
            p = tuple(float(values[c]) for c in "xyz")
            if not all(math.isfinite(c) for c in p):
                raise ValueError("%s: coordinate is not finite" % where)
            positions.append(p)
            if uv_names is not None:
                uv = (float(values[uv_names[0]]), float(values[uv_names[1]]))
                if not (math.isfinite(uv[0]) and math.isfinite(uv[1])):
                    raise ValueError("%s: texture coordinate is not finite" % where)
                vertex_uv.append(uv)
        elif name == "face":
            idx = values[index_name]
            if len(idx) != 3:
                raise ValueError("%s: has %d vertices (an atlas face is a triangle)" % (where, len(idx)))
            faces.append(tuple(int(i) for i in idx))
            face_where.append(where)
            if per_face:
                tc = values["texcoord"]
                if len(tc) != 6:
                    raise ValueError("%s: texcoord has %d numbers (6 expected)" % (where, len(tc)))
                tc = [float(x) for x in tc]
                if not all(math.isfinite(x) for x in tc):
                    raise ValueError("%s: texture coordinate is not finite" % where)
                uvs.append(((tc[0], tc[1]), (tc[2], tc[3]), (tc[4], tc[5])))
            else:
                uvs.append(None)
            textures.append(int(values["texnumber"]) if "texnumber" in values else 0)
    if not faces:
        raise ValueError("%s: no faces" % path)
    for n, f in enumerate(faces):
        for i in f:
            if not 0 <= i < len(positions):
                raise ValueError("%s: vertex index %d out of range (0..%d)" % (face_where[n], i, len(positions) - 1))
        if uvs[n] is None:
            uvs[n] = tuple(vertex_uv[i] for i in f)
    return Atlas(positions, faces, uvs, textures, path)


def read_atlas(path):
    lower = str(path).lower()
    if lower.endswith(".obj"):
        return read_obj(path)
    if lower.endswith(".ply"):
        return read_ply(path)
    raise ValueError("%s: unknown format (an atlas is .obj or .ply)" % path)


# --------------------------------------------------------------------------------------------
# Exact arithmetic helpers

def orient2d_exact(a, b, c):
    """The exact orient2d of three points of doubles, as a Fraction (positive: counter-clockwise)."""
    ax, ay = Fraction(a[0]), Fraction(a[1])
    return (Fraction(b[0]) - ax) * (Fraction(c[1]) - ay) - (Fraction(b[1]) - ay) * (Fraction(c[0]) - ax)


def _common_scale(values):
    """The smallest K such that every double in values times 2**K is an integer."""
    k = 0
    for x in values:
        d = x.as_integer_ratio()[1]
        k = max(k, d.bit_length() - 1)
    return k


def _to_int(x, k):
    n, d = x.as_integer_ratio()
    return n << (k - (d.bit_length() - 1))


def _sign(x):
    return (x > 0) - (x < 0)


def _bits2(u, v):
    # exact equality as numbers: adding +0.0 turns -0.0 into +0.0 and changes nothing else
    return struct.pack("<2d", u + 0.0, v + 0.0)


class _UnionFind:
    def __init__(self, n):
        self.parent = list(range(n))

    def find(self, i):
        p = self.parent
        root = i
        while p[root] != root:
            root = p[root]
        while p[i] != root:
            p[i], i = root, p[i]
        return root

    def union(self, i, j):
        ri, rj = self.find(i), self.find(j)
        if ri != rj:
            if ri < rj:
                self.parent[rj] = ri
            else:
                self.parent[ri] = rj


# --------------------------------------------------------------------------------------------
# The analysis

class _Prepared:
    """Welded vertices, per-corner UV keys and exact integer UV coordinates per texture."""

    def __init__(self, atlas):
        self.atlas = atlas
        # welding: records at exactly equal 3D positions (as numbers: -0 = +0) are one vertex when
        # both lie on the boundary of the surface over the file's own indices (a seam of
        # duplicated vertices); coincident records inside that surface stay apart. A welded vertex
        # is named by its first file vertex.
        uses = {}
        for f in atlas.faces:
            for k in range(3):
                edge = tuple(sorted((f[k], f[(k + 1) % 3])))
                uses[edge] = uses.get(edge, 0) + 1
        index_boundary = {v for edge, count in uses.items() if count == 1 for v in edge}
        first = {}
        self.weld = []
        for i, p in enumerate(atlas.positions):
            if i in index_boundary:
                self.weld.append(first.setdefault(struct.pack("<3d", *(x + 0.0 for x in p)), i))
            else:
                self.weld.append(i)
        self.fv = [tuple(self.weld[i] for i in f) for f in atlas.faces]
        self.uvkey = [tuple(_bits2(u, v) for (u, v) in t) for t in atlas.uvs]
        # textures in order of first appearance
        self.texture_faces = {}
        for f, t in enumerate(atlas.textures):
            self.texture_faces.setdefault(t, []).append(f)
        # exact integer UV: one power-of-two scale per texture
        n = len(atlas.faces)
        self.iuv = [None] * n
        self.scale = {}
        for t, fs in self.texture_faces.items():
            k = _common_scale(c for f in fs for p in atlas.uvs[f] for c in p)
            self.scale[t] = k
            for f in fs:
                self.iuv[f] = tuple((_to_int(u, k), _to_int(v, k)) for (u, v) in atlas.uvs[f])
        self.orient = []
        for (a, b, c) in self.iuv:
            self.orient.append((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
        # edges of S: welded pair -> list of (face, local index of the smaller, of the larger)
        self.edges = {}
        for f, (a, b, c) in enumerate(self.fv):
            for i, j in ((0, 1), (1, 2), (2, 0)):
                x, y = (a, b, c)[i], (a, b, c)[j]
                if x == y:
                    continue
                if x > y:
                    x, y, i, j = y, x, j, i
                self.edges.setdefault((x, y), []).append((f, i, j))

    def joined(self, e0, e1):
        (f, i, j), (g, k, l) = e0, e1
        a = self.atlas
        return a.textures[f] == a.textures[g] and self.uvkey[f][i] == self.uvkey[g][k] \
            and self.uvkey[f][j] == self.uvkey[g][l]


def _charts(prep):
    n = len(prep.fv)
    uf = _UnionFind(n)
    seams = []
    for key, inc in prep.edges.items():
        seam = False
        for x in range(len(inc)):
            for y in range(x + 1, len(inc)):
                if prep.joined(inc[x], inc[y]):
                    uf.union(inc[x][0], inc[y][0])
                else:
                    seam = True
        if seam:
            seams.append(key)
    chart_of = [uf.find(f) for f in range(n)]
    charts = {}
    for f, c in enumerate(chart_of):
        charts.setdefault(c, []).append(f)
    return charts, seams


def _chart_signs(prep, charts):
    """Per chart: its sign (+1/-1; a zero sum is positive) from the exact sum of orient2d, and
    whether the compensated float sum (math.fsum of the correctly rounded orient2d values)
    has another sign."""
    signs, disagreements = {}, []
    for c, fs in charts.items():
        tex = prep.atlas.textures[fs[0]]
        exact = sum(prep.orient[f] for f in fs)
        denom = 1 << (2 * prep.scale[tex])
        rounded = math.fsum(float(Fraction(prep.orient[f], denom)) for f in fs)
        s = -1 if exact < 0 else 1
        if (-1 if rounded < 0 else 1) != s:
            disagreements.append(min(fs))
        signs[c] = s
    return signs, sorted(disagreements)


def _candidate_pairs(prep, faces):
    """Pairs (f, g) of the given faces whose closed UV bounding boxes meet (sort and sweep on
    u; comparisons of doubles are exact)."""
    if len(faces) < 2:
        return
    uv = np.array([prep.atlas.uvs[f] for f in faces], dtype=np.float64)  # (m, 3, 2)
    lo, hi = uv.min(axis=1), uv.max(axis=1)
    order = np.argsort(lo[:, 0], kind="stable")
    xs = lo[order, 0]
    xhi, ylo, yhi = hi[order, 0], lo[order, 1], hi[order, 1]
    ends = np.searchsorted(xs, xhi, side="right")
    ids = np.asarray(faces)[order]
    for i in range(len(order)):
        e = ends[i]
        if e <= i + 1:
            continue
        sl = slice(i + 1, e)
        mask = (ylo[sl] <= yhi[i]) & (yhi[sl] >= ylo[i])
        if not mask.any():
            continue
        f = int(ids[i])
        for g in ids[sl][mask].tolist():
            yield (f, g) if f < g else (g, f)


def _classify_pair(prep, f, g):
    """'overlap', 'contact' or None for two non-degenerate faces of one texture."""
    A, B = prep.iuv[f], prep.iuv[g]
    sa, sb = _sign(prep.orient[f]), _sign(prep.orient[g])
    interiors_disjoint = False
    for T, s, U in ((A, sa, B), (B, sb, A)):
        for e in range(3):
            ax, ay = T[e]
            bx, by = T[(e + 1) % 3]
            dx, dy = bx - ax, by - ay
            strict = True
            closed = True
            for px, py in U:
                v = s * (dx * (py - ay) - dy * (px - ax))
                if v >= 0:
                    strict = False
                    if v > 0:
                        closed = False
                        break
            if strict and closed:
                return None  # a strictly separating edge line: the closed triangles are disjoint
            if closed:
                interiors_disjoint = True
    if not interiors_disjoint:
        return "overlap"
    # the closed triangles meet, the interiors do not: what do they legitimately share?
    shared = [(i, j) for i in range(3) for j in range(3)
              if prep.fv[f][i] == prep.fv[g][j] and prep.uvkey[f][i] == prep.uvkey[g][j]]
    corners_f = {i for i, _ in shared}
    corners_g = {j for _, j in shared}
    k = min(len(corners_f), len(corners_g))
    if k == 0:
        return "contact"
    if k >= 2:
        return None  # they meet only along the shared edge (interiors disjoint: opposite sides)
    i, j = shared[0]
    P = A[i]
    cone_a = (_sub(A[(i + 1) % 3], P), _sub(A[(i + 2) % 3], P), sa)
    cone_b = (_sub(B[(j + 1) % 3], P), _sub(B[(j + 2) % 3], P), sb)
    for d in cone_b[:2]:
        if _in_cone(d, cone_a):
            return "contact"
    for d in cone_a[:2]:
        if _in_cone(d, cone_b):
            return "contact"
    return None


def _sub(p, q):
    return (p[0] - q[0], p[1] - q[1])


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _in_cone(d, cone):
    """Is the ray d inside the closed convex cone spanned by u, v (orientation s of (u, v))?"""
    u, v, s = cone
    return s * _cross(u, d) >= 0 and s * _cross(d, v) >= 0


def _overlaps_and_contacts(prep, degenerate):
    overlaps, contacts = [], []
    for t, fs in prep.texture_faces.items():
        live = [f for f in fs if f not in degenerate]
        seen = set()
        for pair in _candidate_pairs(prep, live):
            if pair in seen:
                continue
            seen.add(pair)
            verdict = _classify_pair(prep, *pair)
            if verdict == "overlap":
                overlaps.append(pair)
            elif verdict == "contact":
                contacts.append(pair)
    return sorted(overlaps), sorted(contacts)


def overlaps_and_contacts(atlas):
    """(overlapping pairs, contacts) of an Atlas: sorted lists of (f, g), f < g, 0-based face
    indices in file order; faces with a degenerate UV triangle are left out."""
    prep = _Prepared(atlas)
    return _overlaps_and_contacts(prep, {f for f, o in enumerate(prep.orient) if o == 0})


def _t_vertices(prep):
    """(vertex, a, b): a vertex of the boundary of S strictly inside the boundary edge ab,
    exactly (cross product of b - a and w - a zero, w strictly between)."""
    boundary = [key for key, inc in prep.edges.items() if len(inc) == 1]
    if not boundary:
        return []
    pos = prep.atlas.positions
    verts = sorted({v for e in boundary for v in e}, key=lambda v: pos[v][0])
    xs = [pos[v][0] for v in verts]
    exact = {}

    def fr(v):
        if v not in exact:
            exact[v] = tuple(Fraction(c) for c in pos[v])
        return exact[v]

    found = []
    for a, b in boundary:
        pa, pb = pos[a], pos[b]
        lo = [min(pa[c], pb[c]) for c in range(3)]
        hi = [max(pa[c], pb[c]) for c in range(3)]
        start = bisect.bisect_left(xs, lo[0])
        stop = bisect.bisect_right(xs, hi[0])
        for w in verts[start:stop]:
            if w == a or w == b:
                continue
            pw = pos[w]
            if not (lo[1] <= pw[1] <= hi[1] and lo[2] <= pw[2] <= hi[2]):
                continue
            A, B, W = fr(a), fr(b), fr(w)
            ab = [B[c] - A[c] for c in range(3)]
            aw = [W[c] - A[c] for c in range(3)]
            if ab[1] * aw[2] - ab[2] * aw[1] != 0 or ab[2] * aw[0] - ab[0] * aw[2] != 0 \
                    or ab[0] * aw[1] - ab[1] * aw[0] != 0:
                continue
            bw = [W[c] - B[c] for c in range(3)]
            if sum(ab[c] * aw[c] for c in range(3)) > 0 and sum(-ab[c] * bw[c] for c in range(3)) > 0:
                found.append((w, a, b))
    return sorted(found)


def _texture_boxes(prep):
    boxes = {}
    for t, fs in prep.texture_faces.items():
        us = [p[0] for f in fs for p in prep.atlas.uvs[f]]
        vs = [p[1] for f in fs for p in prep.atlas.uvs[f]]
        boxes[t] = (min(us), min(vs), max(us), max(vs))
    return boxes


def _torn_edges(prep, boxes):
    """(f, g): faces of one texture across an edge of S that share one end's UV point but not
    the other's, whose two UV points lie within eps_UV (Euclidean distance <= eps_UV)."""
    eps = {}
    for t, (u0, v0, u1, v1) in boxes.items():
        e = 1e-6 * math.hypot(u1 - u0, v1 - v0)
        eps[t] = Fraction(e) ** 2
    uvs = prep.atlas.uvs
    found = []
    for key, inc in prep.edges.items():
        for x in range(len(inc)):
            for y in range(x + 1, len(inc)):
                (f, i, j), (g, k, l) = inc[x], inc[y]
                t = prep.atlas.textures[f]
                if t != prep.atlas.textures[g]:
                    continue
                same0 = prep.uvkey[f][i] == prep.uvkey[g][k]
                same1 = prep.uvkey[f][j] == prep.uvkey[g][l]
                if same0 == same1:
                    continue
                p, q = (uvs[f][j], uvs[g][l]) if same0 else (uvs[f][i], uvs[g][k])
                du = Fraction(p[0]) - Fraction(q[0])
                dv = Fraction(p[1]) - Fraction(q[1])
                if du * du + dv * dv <= eps[t]:
                    found.append((f, g) if f < g else (g, f))
    return sorted(found)


def _packing(prep, boxes, degenerate):
    try:
        from shapely.geometry import Polygon, box
        from shapely.ops import unary_union
    except ImportError as exc:  # pragma: no cover - the environment must provide python3-shapely
        raise RuntimeError("the packing figures need shapely (Debian: python3-shapely)") from exc
    inside = union = squares = 0.0
    for t, fs in prep.texture_faces.items():
        polys = [Polygon(prep.atlas.uvs[f]) for f in fs if f not in degenerate]
        u = unary_union(polys) if polys else None
        if u is not None:
            union += u.area
            inside += u.intersection(box(0.0, 0.0, 1.0, 1.0)).area
        u0, v0, u1, v1 = boxes[t]
        squares += max(u1 - u0, v1 - v0) ** 2
    ntex = len(prep.texture_faces)
    return inside / ntex, (union / squares if squares > 0 else None)


def _seam_length(prep, seams):
    pos = np.asarray(prep.atlas.positions, dtype=np.float64)
    faces = np.asarray(prep.fv, dtype=np.int64)
    p = pos[faces]
    area = 0.5 * np.linalg.norm(np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]), axis=1).sum()
    length = math.fsum(math.dist(prep.atlas.positions[a], prep.atlas.positions[b]) for a, b in seams)
    return length / math.sqrt(area) if area > 0 else None


# --------------------------------------------------------------------------------------------
# Distortion (DIST-1..9)

def weighted_percentile(values, weights, p):
    """DIST-9: the smallest value x_f such that the faces with x <= x_f weigh at least p * sum."""
    values = np.asarray(values, dtype=np.float64)
    weights = np.asarray(weights, dtype=np.float64)
    order = np.argsort(values, kind="stable")
    cum = np.cumsum(weights[order])
    target = p * weights.sum()
    idx = int(np.searchsorted(cum, target, side="left"))
    idx = min(idx, len(order) - 1)
    return float(values[order[idx]])


def distortion_figures(images, surfaces, degenerate=None):
    """DIST-1..9 for faces whose image triangles are images[f] (3 points, 2D or 3D) and surface
    triangles surfaces[f] (3 points, 3D). sigma_1, sigma_2 are the singular values of the affine
    map image -> surface, from numpy's SVD of its 3x2 Jacobian in an orthonormal frame of the
    image plane (found by a QR factorisation of the image's edge matrix). A face is degenerate
    (DIST-2) when an area or a singular value computes to 0 or is not finite, or when the
    optional boolean sequence `degenerate` marks it (the atlas marks the faces whose UV or 3D
    triangle is exactly degenerate)."""
    Q = np.asarray(images, dtype=np.float64)
    P = np.asarray(surfaces, dtype=np.float64)
    n = Q.shape[0]
    if Q.shape[2] == 2:
        Q = np.concatenate([Q, np.zeros((n, 3, 1))], axis=2)
    EQ = np.stack([Q[:, 1] - Q[:, 0], Q[:, 2] - Q[:, 0]], axis=2)  # (n, 3, 2)
    EP = np.stack([P[:, 1] - P[:, 0], P[:, 2] - P[:, 0]], axis=2)
    with np.errstate(all="ignore"):
        AQ = 0.5 * np.linalg.norm(np.cross(EQ[:, :, 0], EQ[:, :, 1]), axis=1)
        AP = 0.5 * np.linalg.norm(np.cross(EP[:, :, 0], EP[:, :, 1]), axis=1)
        ok = (AQ > 0) & (AP > 0) & np.isfinite(AQ) & np.isfinite(AP)
        sig = np.full((n, 2), np.nan)
        if ok.any():
            _, R = np.linalg.qr(EQ[ok])  # EQ = frame @ R, R 2x2: the image edges in 2D
            det = R[:, 0, 0] * R[:, 1, 1] - R[:, 0, 1] * R[:, 1, 0]
            good = det != 0
            Rinv = np.zeros_like(R)
            Rinv[good] = np.linalg.inv(R[good])
            J = EP[ok] @ Rinv  # (m, 3, 2): image (2D frame) -> surface
            s = np.linalg.svd(J, compute_uv=False)  # descending
            s[~good] = np.nan
            sig[ok] = s
    s1, s2 = sig[:, 0], sig[:, 1]
    live = ok & np.isfinite(s1) & np.isfinite(s2) & (s1 > 0) & (s2 > 0)
    if degenerate is not None:
        live &= ~np.asarray(degenerate, dtype=bool)
    degenerate = int(n - live.sum())
    if not live.any():
        return {"l2_stretch": None, "linf_stretch": None, "symmetric_dirichlet": None,
                "anisotropy": {"p50": None, "p99": None, "p999": None, "max": None, "above_10": 0},
                "area_distortion": {"p99": None, "max": None}, "degenerate": degenerate}
    s1, s2, aq, ap = s1[live], s2[live], AQ[live], AP[live]
    k = math.sqrt(math.fsum(ap) / math.fsum(aq))
    t1, t2 = s1 / k, s2 / k
    A = k * k * aq
    W = math.fsum(A)
    aniso = s1 / s2
    area = np.maximum(t1 * t2, 1.0 / (t1 * t2))
    return {
        "l2_stretch": math.sqrt(math.fsum(A * (t1 ** 2 + t2 ** 2) / 2) / W),
        "linf_stretch": float(t1.max()),
        "symmetric_dirichlet": math.fsum(A * (t1 ** 2 + t2 ** 2 + t1 ** -2 + t2 ** -2)) / W,
        "anisotropy": {
            "p50": weighted_percentile(aniso, A, 0.5),
            "p99": weighted_percentile(aniso, A, 0.99),
            "p999": weighted_percentile(aniso, A, 0.999),
            "max": float(aniso.max()),
            "above_10": int((aniso > 10).sum()),
        },
        "area_distortion": {"p99": weighted_percentile(area, A, 0.99), "max": float(area.max())},
        "degenerate": degenerate,
    }


def _degenerate_3d(positions, face):
    """Are the three 3D corners exactly collinear (exact cross product zero)?"""
    a, b, c = (tuple(Fraction(x) for x in positions[i]) for i in face)
    e = [b[k] - a[k] for k in range(3)]
    g = [c[k] - a[k] for k in range(3)]
    return e[1] * g[2] == e[2] * g[1] and e[2] * g[0] == e[0] * g[2] and e[0] * g[1] == e[1] * g[0]


# --------------------------------------------------------------------------------------------

def analyze(atlas, packing=True):
    """Every check and figure of spec/atlas.md except ATLAS-2 and ATLAS-8, as one dict."""
    prep = _Prepared(atlas)
    degenerate = {f for f, o in enumerate(prep.orient) if o == 0}
    charts, seams = _charts(prep)
    signs, disagreements = _chart_signs(prep, charts)
    folded = []
    for c, fs in charts.items():
        s = signs[c]
        folded.extend(f for f in fs if prep.orient[f] != 0 and _sign(prep.orient[f]) != s)
    overlaps, contacts = _overlaps_and_contacts(prep, degenerate)
    boxes = _texture_boxes(prep)
    result = {
        "faces": len(atlas.faces),
        "textures": len(prep.texture_faces),
        "folded_faces": sorted(folded),
        "overlapping_pairs": [list(p) for p in overlaps],
        "contacts": [list(p) for p in contacts],
        "degenerate_uv": sorted(degenerate),
        "t_vertices": [list(t) for t in _t_vertices(prep)],
        "torn_edges": [list(p) for p in _torn_edges(prep, boxes)],
        "charts": len(charts),
        "mirrored_charts": sum(1 for s in signs.values() if s < 0),
        "chart_sign_disagreements": disagreements,
        "seam_length": _seam_length(prep, seams),
    }
    if packing:
        result["packing_unit_square"], result["packing_bounding_square"] = _packing(prep, boxes, degenerate)
    pos = np.asarray(atlas.positions, dtype=np.float64)
    surfaces = pos[np.asarray(atlas.faces, dtype=np.int64)]
    images = np.asarray(atlas.uvs, dtype=np.float64)
    exact_degenerate = [f in degenerate or _degenerate_3d(atlas.positions, atlas.faces[f])
                        for f in range(len(atlas.faces))]
    result["distortion"] = distortion_figures(images, surfaces, exact_degenerate)
    return result


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    args = [a for a in argv if a != "--json"]
    if len(args) != 1 or args[0].startswith("-"):
        print("usage: atlas_reference.py FILE [--json]", file=sys.stderr)
        return 2
    try:
        atlas = read_atlas(args[0])
    except (ValueError, OSError) as exc:
        print("atlas_reference: error: %s" % str(exc).splitlines()[0], file=sys.stderr)
        return 2
    result = analyze(atlas)
    if "--json" in argv:
        print(json.dumps(result, separators=(",", ":")))
    else:
        print(json.dumps(result, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
