#!/usr/bin/env python3
# Measures what makes the worst faces of a `fhr-param 1` parameterization (spec/param.md) bad: per face
# of T′ the anisotropy σ₁/σ₂ of spec/distortion.md (DIST-1, with DIST-3's area weights), then, for the
# worst faces and for every face above σ₁/σ₂ = 10, which side of the map is thin (the surface triangle
# or its image), how close the curves of §3 come there to a vertex of T, to another curve or to a
# corner x_j (along the edges of T), and the shape of the face's patch against its domain triangle.
# The findings are in paper_notes/distortion_causes.md.
"""The causes of the worst faces of a parameterization (paper_notes/distortion_causes.md).

For each input — a `fhr-param 1` file, a directory holding `param.fhrp` (as `fhr run --out DIR`
writes it), or a mesh that `fhr run` is run on first (with --fhr and --faces) — the input mesh T is
the one named by `report.json` beside the file (or --mesh), and the kinds of the curves
(geodesic/restricted) are read from `geodesics.obj` beside it when it exists.

Per face of T′ (spec/distortion.md): σ₁ ≥ σ₂ of the affine map from the face's image (its domain
triangle laid flat in its own 3D shape, at the barycentric coordinates β of its corners) onto the
surface triangle. Per patch, σ′ = σ / s with s² = (patch's surface area) / (domain triangle's
area): σ₂′ ≪ 1 says the surface is thin where the image is not, σ₁′ ≫ 1 that the image is thin
where the surface is not ("thin side": surface when 1/σ₂′ ≥ σ₁′).

Closeness is measured along the edges of T, relative to the edge's length (T′'s extra vertices
are points of T's edges, spec/partition.md PART-2): on one edge of T, the gap between neighbouring
vertices of T′ — a curve's node and an end of the edge on no curve ("vertex": the curve passes
near a vertex of T), nodes or ends on two different curves ("curve": two curves side by side), a
corner x_j and a node of a curve not ending at x_j ("corner").

Cause of a face (the first that applies):
  curve-restricted / curve-geodesic / corner / vertex: a gap at the face's corners (or, if none is
      below --gap, at its neighbours' corners) is below --gap: the least of the curve and corner
      gaps, unless the vertex gap is 10 times smaller (a vertex of T between two close curves is
      close to them too); "restricted" when one of the two curves is a restricted path
      (spec/partition.md PART-10);
  corner angle: none nearby, and the corner of the patch nearest the face in the image has, on the
                surface, an angle at least 3 times larger or smaller than in its domain triangle;
  neck:         none nearby, but two sides of the face's patch come within --gap somewhere;
  side turn:    a corner of the face lies on a side where the patch's angle is not within
                [π/1.5, 1.5π] (a sharp turn of a curve; chord length maps it onto a straight side);
  other.

Usage: distortion_causes.py INPUT... [--worst N] [--patches K] [--gap G] [--mesh T]
                            [--fhr FHR --faces N [--work DIR]]"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

THRESHOLD = 10.0          # spec/distortion.md DIST-7 `above_10`
SEPARATION = 1e-4         # src/fhr/partition/detail/restricted.hpp separation_fraction


def fail(message):
    print("distortion_causes.py: error: " + message, file=sys.stderr)
    sys.exit(2)


# ---------------------------------------------------------------------------------------------- reading

def read_off(path):
    try:
        tokens = open(path).read().split()
    except OSError as e:
        fail("%s: %s" % (path, e.strerror))
    if not tokens or not tokens[0].endswith("OFF"):
        fail("%s: not an OFF mesh (T is read as OFF only)" % path)
    nv, nf = int(tokens[1]), int(tokens[2])
    v = np.array(tokens[4:4 + 3 * nv], dtype=float).reshape(nv, 3)
    rest = np.array(tokens[4 + 3 * nv:4 + 3 * nv + 4 * nf], dtype=np.int64).reshape(nf, 4)
    if (rest[:, 0] != 3).any():
        fail("%s: a face that is not a triangle" % path)
    return v, rest[:, 1:]


def read_param(path):
    try:
        tokens = open(path).read().split()
    except OSError as e:
        fail("%s: %s" % (path, e.strerror))
    if tokens[:2] != ["fhr-param", "1"]:
        fail("%s: not a fhr-param 1 file" % path)
    i, out = 2, []
    for name, width in (("domain_vertices", 3), ("domain_faces", 3), ("surface_vertices", 3), ("surface_faces", 13)):
        if i >= len(tokens) or tokens[i] != name:
            fail("%s: no section %s where expected" % (path, name))
        n = int(tokens[i + 1])
        out.append(np.array(tokens[i + 2:i + 2 + n * width], dtype=float).reshape(n, width))
        i += 2 + n * width
    dv, df, sv, sf = out
    return dv, df.astype(np.int64), sv, sf[:, :3].astype(np.int64), sf[:, 3].astype(np.int64), sf[:, 4:].reshape(-1, 3, 3)


def read_curve_kinds(path, dv):
    """geodesics.obj (spec/cli.md CLI-RUN-1): one polyline per domain edge under `g KIND`, keyed here by
    the corners its ends are at: {(j, k): kind}, j < k."""
    kinds = {}
    if not os.path.exists(path):
        return kinds
    verts, kind = [], None
    for line in open(path):
        w = line.split()
        if not w:
            continue
        if w[0] == "v":
            verts.append([float(x) for x in w[1:4]])
        elif w[0] == "g":
            kind = w[1] if len(w) > 1 else None
        elif w[0] == "l":
            ends = [verts[int(w[1]) - 1], verts[int(w[-1]) - 1]]
            j, k = (int(np.argmin(np.linalg.norm(dv - np.array(e), axis=1))) for e in ends)
            kinds[(min(j, k), max(j, k))] = kind
    return kinds


# ---------------------------------------------------------------------------------------------- geometry

def frame2d(X):
    """Triangles (n,3,3) in a frame of their own plane, edge 1 along x: corners (0,0), (l1,0), (a,b)."""
    e1, e2 = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]
    l1 = np.linalg.norm(e1, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        x = e1 / l1[:, None]
    a = np.einsum("ij,ij->i", e2, x)
    b = np.linalg.norm(e2 - a[:, None] * x, axis=1)
    return l1, a, b


def singular_values(Q, P):
    """DIST-1: σ₁ ≥ σ₂ of the affine maps from the image triangles Q onto the surface triangles P, from
    the upper triangular J = P Q⁻¹ in the two frames: σ₁ = √(E² + G²) + √(F² + G²), σ₂ = |det J| / σ₁."""
    q1, qa, qb = frame2d(Q)
    p1, pa, pb = frame2d(P)
    with np.errstate(divide="ignore", invalid="ignore"):
        j11, j12, j22 = p1 / q1, (pa - p1 * qa / q1) / qb, pb / qb
        e, f, g = (j11 + j22) / 2, (j11 - j22) / 2, j12 / 2
        s1 = np.hypot(e, g) + np.hypot(f, g)
        s2 = np.abs(j11 * j22) / s1
    return s1, s2


def areas(X):
    return 0.5 * np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)


def angles(X):
    """The three angles (degrees) of each triangle (n,3,3), at corners 0, 1, 2."""
    out = np.empty((len(X), 3))
    for k in range(3):
        a, b = X[:, (k + 1) % 3] - X[:, k], X[:, (k + 2) % 3] - X[:, k]
        with np.errstate(divide="ignore", invalid="ignore"):
            c = np.einsum("ij,ij->i", a, b) / (np.linalg.norm(a, axis=1) * np.linalg.norm(b, axis=1))
        out[:, k] = np.degrees(np.arccos(np.clip(np.nan_to_num(c, nan=1.0), -1, 1)))
    return out


def locate_on_edges(TV, E, P):
    """For points P on edges of T: the nearest edge (index into E, or -1), the parameter t from E[:, 0]
    and the distance. A uniform grid of cells of the median edge length holds each edge in the cells
    its bounding box meets; a point looks in its own cell."""
    a, b = TV[E[:, 0]], TV[E[:, 1]]
    h = float(np.median(np.linalg.norm(b - a, axis=1)))
    lo = TV.min(axis=0) - h
    pad = 1e-9 * h
    cmin = np.floor((np.minimum(a, b) - pad - lo) / h).astype(np.int64)
    cmax = np.floor((np.maximum(a, b) + pad - lo) / h).astype(np.int64)
    dims = np.floor((TV.max(axis=0) + h - lo) / h).astype(np.int64) + 2
    n = cmax - cmin + 1
    count = n.prod(axis=1)
    eid = np.repeat(np.arange(len(E)), count)
    local = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
    nx, ny = n[eid, 0], n[eid, 1]
    key = ((cmin[eid, 0] + local % nx) * dims[1] + cmin[eid, 1] + (local // nx) % ny) * dims[2] \
        + cmin[eid, 2] + local // (nx * ny)
    order = np.argsort(key, kind="stable")
    key, eid = key[order], eid[order]
    c = np.floor((P - lo) / h).astype(np.int64)
    pkey = (c[:, 0] * dims[1] + c[:, 1]) * dims[2] + c[:, 2]
    start, stop = np.searchsorted(key, pkey, "left"), np.searchsorted(key, pkey, "right")
    m = stop - start
    pid = np.repeat(np.arange(len(P)), m)
    cand = eid[np.repeat(start, m) + np.arange(m.sum()) - np.repeat(np.cumsum(m) - m, m)]
    A, d = a[cand], b[cand] - a[cand]
    t = np.einsum("ij,ij->i", P[pid] - A, d) / np.einsum("ij,ij->i", d, d)
    dist = np.linalg.norm(P[pid] - (A + np.clip(t, 0, 1)[:, None] * d), axis=1)
    o = np.lexsort((dist, pid))
    first = o[np.r_[True, pid[o][1:] != pid[o][:-1]]] if len(o) else o
    edge, tt, dd = np.full(len(P), -1), np.full(len(P), np.nan), np.full(len(P), np.inf)
    edge[pid[first]], tt[pid[first]], dd[pid[first]] = cand[first], t[first], dist[first]
    return edge, tt, dd


def triangle_aspect(lengths):
    """σ₁/σ₂ of the affine map from an equilateral triangle onto a plane triangle with these side
    lengths; inf when they make none."""
    a, b, c = sorted(lengths)
    if a + b <= c or c <= 0:
        return np.inf
    x = (c * c + b * b - a * a) / (2 * c)
    P = np.array([[c, x], [0.0, np.sqrt(max(b * b - x * x, 0.0))]])
    Q = np.array([[1.0, 0.5], [0.0, np.sqrt(3) / 2]])
    s = np.linalg.svd(P @ np.linalg.inv(Q), compute_uv=False)
    return s[0] / s[1] if s[1] > 0 else np.inf


# ---------------------------------------------------------------------------------------------- the map

class Map:
    """A parameterization and its input mesh T: per face σ and weights, per vertex of T′ its carrier in
    D (a corner, a curve, the inside of a patch) and in T (a vertex, or a point of an edge), the gaps."""

    def __init__(self, param_path, mesh_path, obj_path):
        self.TV, self.TF = read_off(mesh_path)
        self.dv, self.df, self.sv, self.F, self.patch, self.B = read_param(param_path)
        self.kinds = read_curve_kinds(obj_path, self.dv)
        TV, TF, F, B = self.TV, self.TF, self.F, self.B
        nT, nV, nDV, nD = len(TV), len(self.sv), len(self.dv), len(self.df)
        if nV < nT or not np.array_equal(self.sv[:nT], TV):
            fail("%s: its first surface vertices are not the vertices of %s (spec/partition.md PART-2)"
                 % (param_path, mesh_path))
        self.nT, self.nDV = nT, nDV
        # faces: the image (domain triangle in its own 3D plane, at β) and the surface triangle
        self.image = np.einsum("fkc,fcx->fkx", B, self.dv[self.df[self.patch]])
        self.surface = self.sv[F]
        self.s1, self.s2 = singular_values(self.image, self.surface)
        AP, AQ = areas(self.surface), areas(self.image)
        ok = np.isfinite(self.s1) & np.isfinite(self.s2) & (self.s2 > 0) & (AP > 0) & (AQ > 0)
        k2 = AP[ok].sum() / AQ[ok].sum()
        self.AP = AP
        self.weight = np.where(ok, k2 * AQ, 0.0)                                   # DIST-3
        self.aniso = np.where(ok, self.s1 / np.where(ok, self.s2, 1.0), np.inf)
        scale = np.sqrt(np.bincount(self.patch, AP, nD) / areas(self.dv[self.df]))
        self.s1p, self.s2p = self.s1 / scale[self.patch], self.s2 / scale[self.patch]
        # carriers in D (exact zeros of β, PARAM-7): 1 nonzero = corner x_j, 2 = on a curve, 3 = inside
        nz = B != 0
        cnt = nz.sum(axis=2)
        dverts = self.df[self.patch]
        key = np.full(F.shape, -1, dtype=np.int64)
        for i in range(3):
            ids = np.sort(np.where(nz[:, i, :], dverts, nDV), axis=1)
            c = cnt[:, i]
            key[:, i] = np.where(c == 1, ids[:, 0], np.where(c == 2, nDV + ids[:, 0] * nDV + ids[:, 1], -1))
        self.dcount = np.zeros(nV, dtype=np.int64)
        self.dcount[F.ravel()] = cnt.ravel()
        self.dkey = np.full(nV, -1, dtype=np.int64)   # corner j: j; curve (j, k): nDV + j·nDV + k; inside: -1
        self.dkey[F.ravel()] = key.ravel()
        # edges of T′ on curves: the face across is in another patch (or there is none)
        half = np.stack([F, np.roll(F, -1, axis=1)], axis=2).reshape(-1, 2)
        hface = np.repeat(np.arange(len(F)), 3)
        nV64 = np.int64(nV)
        fwd = half[:, 0] * nV64 + half[:, 1]
        rev = half[:, 1] * nV64 + half[:, 0]
        o = np.argsort(fwd)
        pos = np.searchsorted(fwd[o], rev)
        pos = np.minimum(pos, len(o) - 1)
        found = fwd[o][pos] == rev
        across = np.where(found, hface[o][pos], -1)
        self.curve_edges = ((across < 0) | (self.patch[np.maximum(across, 0)] != self.patch[hface])).reshape(-1, 3).sum(axis=1)
        # carriers in T: every vertex of T′ beyond T's lies on an edge of T
        E = np.unique(np.sort(np.concatenate([TF[:, [0, 1]], TF[:, [1, 2]], TF[:, [2, 0]]]), axis=1), axis=0)
        self.E = E
        elen = np.linalg.norm(TV[E[:, 1]] - TV[E[:, 0]], axis=1)
        e, t, d = locate_on_edges(TV, E, self.sv[nT:])
        on = (e >= 0) & (d <= 1e-9 * elen[np.maximum(e, 0)]) & (t > 0) & (t < 1)
        self.vedge = np.full(nV, -1, dtype=np.int64)
        self.vt = np.full(nV, np.nan)
        self.vedge[nT:][on], self.vt[nT:][on] = e[on], t[on]
        self._gaps()

    # curves are named by their domain edge (j, k), j < k
    def curve(self, key):
        if key < self.nDV:
            return None
        key -= self.nDV
        return (int(key // self.nDV), int(key % self.nDV))

    def kind(self, key):
        c = self.curve(key)
        return self.kinds.get(c, "?") if c is not None else None

    def _gaps(self):
        """Per vertex of T′: near_vertex, near_curve (with the other curve), near_corner (with the
        passing curve): the least gap along an edge of T between it and a neighbour on that edge
        (module doc), relative to the edge's length; inf when none."""
        nV, nDV = len(self.sv), self.nDV
        self.near_vertex = np.full(nV, np.inf)
        self.near_curve = np.full(nV, np.inf)
        self.near_curve_other = np.full(nV, -1, dtype=np.int64)
        self.near_corner = np.full(nV, np.inf)
        self.near_corner_other = np.full(nV, -1, dtype=np.int64)
        nodes = np.nonzero(self.vedge >= 0)[0]
        used = np.zeros(len(self.E), bool)
        used[self.vedge[nodes]] = True
        ends = np.nonzero(used)[0]
        m_edge = np.concatenate([self.vedge[nodes], ends, ends])
        m_t = np.concatenate([self.vt[nodes], np.zeros(len(ends)), np.ones(len(ends))])
        m_v = np.concatenate([nodes, self.E[ends, 0], self.E[ends, 1]])
        o = np.lexsort((m_t, m_edge))
        m_edge, m_t, m_v = m_edge[o], m_t[o], m_v[o]
        m_key = self.dkey[m_v]
        same = m_edge[1:] == m_edge[:-1]
        gap = m_t[1:] - m_t[:-1]
        for x, y in ((m_v[:-1], m_v[1:]), (m_v[1:], m_v[:-1])):
            kx, ky = self.dkey[x], self.dkey[y]
            # x a vertex of T on no curve, y on a curve: the curve passes near x
            sel = same & (kx < 0) & (ky >= nDV)
            np.minimum.at(self.near_vertex, x[sel], gap[sel])
            np.minimum.at(self.near_vertex, y[sel], gap[sel])
            # x and y on two different curves
            sel = same & (kx >= nDV) & (ky >= nDV) & (kx != ky)
            order = np.argsort(-gap[sel])                 # the last write is the least gap
            xs, ys, gs = x[sel][order], y[sel][order], gap[sel][order]
            for v, other in ((xs, ky[sel][order]), (ys, kx[sel][order])):
                better = gs < self.near_curve[v]
                vv, oo, g2 = v[better], other[better], gs[better]
                self.near_curve[vv], self.near_curve_other[vv] = g2, oo
            # x a corner x_j, y on a curve that does not end at x_j
            cj = (np.maximum(ky, nDV) - nDV) // nDV
            ck = (np.maximum(ky, nDV) - nDV) % nDV
            sel = same & (kx >= 0) & (kx < nDV) & (ky >= nDV) & (cj != kx) & (ck != kx)
            order = np.argsort(-gap[sel])
            xs, ys, gs, ks = x[sel][order], y[sel][order], gap[sel][order], ky[sel][order]
            for v in (xs, ys):
                better = gs < self.near_corner[v]
                self.near_corner[v[better]], self.near_corner_other[v[better]] = gs[better], ks[better]

    def containing_T_face(self, f):
        """The face of T holding face f of T′: the one face of T whose closure holds its three corners."""
        if not hasattr(self, "_vfaces"):
            self._vfaces = [[] for _ in range(self.nT)]
            for i, (a, b, c) in enumerate(self.TF):
                self._vfaces[a].append(i)
                self._vfaces[b].append(i)
                self._vfaces[c].append(i)
        sets = []
        for v in self.F[f]:
            if v < self.nT:
                sets.append(set(self._vfaces[v]))
            elif self.vedge[v] >= 0:
                a, b = self.E[self.vedge[v]]
                sets.append(set(self._vfaces[a]) & set(self._vfaces[b]))
            else:
                return -1
        common = set.intersection(*sets)
        return min(common) if len(common) == 1 else -1


# ---------------------------------------------------------------------------------------------- patches

def patch_table(M):
    """Per patch: faces, corner angles on the surface (sum of its faces' angles at the corner) and in
    the domain triangle, chord lengths of its sides and the domain triangle's side lengths, the least
    and greatest angle of the patch at a vertex inside a side, its neck (least near_curve/near_corner
    at a vertex of it), and its sides' kinds."""
    nD = len(M.df)
    order = np.argsort(M.patch, kind="stable")
    bounds = np.searchsorted(M.patch[order], np.arange(nD + 1))
    sang = angles(M.surface)
    neck_v = np.minimum(M.near_curve, M.near_corner)
    side_turn = np.full(len(M.sv), np.nan)
    rows = []
    for d in range(nD):
        fs = order[bounds[d]:bounds[d + 1]]
        Bd = M.B[fs]
        corner_angle = np.array([sang[fs][Bd[:, :, c] == 1.0].sum() for c in range(3)])
        side_len = np.zeros(3)
        for k in range(3):
            i, j = k, (k + 1) % 3
            both = (Bd[:, i, :] == 0) & (Bd[:, j, :] == 0)
            L = np.linalg.norm(M.surface[fs, j] - M.surface[fs, i], axis=1)
            side_len += np.array([L[both[:, c]].sum() for c in range(3)])
        # the patch's angle at each vertex inside a side
        on_side = (M.dcount[M.F[fs]] == 2)
        vs, an = M.F[fs][on_side], sang[fs][on_side]
        acc = np.bincount(vs, an, len(M.sv))
        uv = np.unique(vs)
        side_turn[uv] = acc[uv]                          # a vertex inside a side lies in two patches: kept per patch below
        dpos = M.dv[M.df[d]]
        dside = np.array([np.linalg.norm(dpos[(c + 2) % 3] - dpos[(c + 1) % 3]) for c in range(3)])
        dang = np.zeros(3)
        for c in range(3):
            a, b = dpos[(c + 1) % 3] - dpos[c], dpos[(c + 2) % 3] - dpos[c]
            dang[c] = np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1, 1)))
        dvs = M.df[d]
        kinds = []
        for c in range(3):
            j, k = dvs[(c + 1) % 3], dvs[(c + 2) % 3]
            kinds.append(M.kinds.get((min(j, k), max(j, k)), "?"))
        verts = np.unique(M.F[fs])
        rows.append(dict(patch=d, faces=fs, corner_angle=corner_angle, domain_angle=dang, side_len=side_len,
                         domain_side=dside, kinds=kinds, side_angles={int(v): float(acc[v]) for v in uv},
                         side_angle_min=float(acc[uv].min()) if len(uv) else np.nan,
                         side_angle_max=float(acc[uv].max()) if len(uv) else np.nan,
                         neck=float(neck_v[verts].min()), near_vertex=float(M.near_vertex[verts].min())))
    return rows


# ---------------------------------------------------------------------------------------------- causes

CAUSES = ["curve-restricted", "curve-geodesic", "corner", "vertex", "corner angle", "neck", "side turn", "other"]


def classify(M, PT, faces, gap0):
    """Per face of `faces`: (cause, gap, detail)."""
    F = M.F
    nV = len(M.sv)
    # 1-ring: the least gap of each kind at any corner of a face sharing a vertex with f
    per_face = {}
    for name, arr in (("vertex", M.near_vertex), ("curve", M.near_curve), ("corner", M.near_corner)):
        own = arr[F].min(axis=1)
        vmin = np.full(nV, np.inf)
        np.minimum.at(vmin, F.ravel(), np.repeat(own, 3))
        per_face[name] = (own, vmin[F].min(axis=1))
    out = []
    for f in faces:
        found = None
        for level in (0, 1):
            gv, gc, go = (per_face[n][level][f] for n in ("vertex", "curve", "corner"))
            # two curves close to each other (or a curve and a corner) come first: a vertex of T
            # between them is close to them too; the vertex counts when it is 10 times closer
            pair = min((gc, "curve"), (go, "corner"))
            if pair[0] < gap0 and not gv * 10 < pair[0]:
                found = (pair[0], pair[1], level)
                break
            if gv < gap0:
                found = (gv, "vertex", level)
                break
        if found:
            g, n, level = found
            where = "at its corners" if level == 0 else "beside it"
            if n == "curve":
                # the pair of curves: find the vertex realising it
                vs = F[f] if level == 0 else np.unique(F[np.any(np.isin(F, F[f]), axis=1)])
                v = vs[np.argmin(M.near_curve[vs])]
                k1, k2 = M.kind(M.dkey[v]), M.kind(M.near_curve_other[v])
                cause = "curve-restricted" if "restricted" in (k1, k2) else "curve-geodesic"
                out.append((cause, g, "%s and %s curve %s" % (k1, k2, where)))
            elif n == "corner":
                vs = F[f] if level == 0 else np.unique(F[np.any(np.isin(F, F[f]), axis=1)])
                v = vs[np.argmin(M.near_corner[vs])]
                out.append(("corner", g, "%s curve past a corner %s" % (M.kind(M.near_corner_other[v]), where)))
            else:
                out.append(("vertex", g, "curve near a vertex of T %s" % where))
            continue
        P = PT[M.patch[f]]
        c = int(np.argmax(M.B[f].mean(axis=0)))
        ratio = P["corner_angle"][c] / P["domain_angle"][c]
        if ratio >= 3 or ratio <= 1 / 3:
            out.append(("corner angle", ratio, "corner %.1f° on T, %.1f° in D" % (P["corner_angle"][c], P["domain_angle"][c])))
            continue
        if P["neck"] < gap0:
            out.append(("neck", P["neck"], "patch's sides %.2g apart elsewhere" % P["neck"]))
            continue
        turns = [P["side_angles"][int(v)] for v in F[f] if M.dcount[v] == 2 and int(v) in P["side_angles"]]
        bad_turn = [a for a in turns if a > 270 or a < 120]
        if bad_turn:
            out.append(("side turn", bad_turn[0], "patch angle %.0f° at a side vertex" % bad_turn[0]))
            continue
        out.append(("other", np.nan, ""))
    return out


# ---------------------------------------------------------------------------------------------- report

def g3(x):
    if x is None or (isinstance(x, float) and np.isnan(x)):
        return "-"
    if np.isinf(x):
        return "inf"
    return "%.3g" % x


def weighted_percentile(x, w, p):
    o = np.argsort(x, kind="stable")
    c = np.cumsum(w[o])
    return x[o][np.searchsorted(c, p * c[-1])]


def analyse(name, param_path, mesh_path, obj_path, o):
    M = Map(param_path, mesh_path, obj_path)
    PT = patch_table(M)
    ok = np.isfinite(M.aniso)
    bad = np.nonzero(ok & (M.aniso > THRESHOLD))[0]
    W = M.weight
    total_w = W.sum()
    bad_w = W[bad].sum()
    restricted = sum(1 for k in M.kinds.values() if k == "restricted")
    print("## %s" % name)
    print()
    print("T′ %d faces, D %d faces, %d curves (%d restricted); σ₁/σ₂ p99 %s, p99.9 %s, max %s; %d faces above %g "
          "holding %.3g %% of the image area" % (
              len(M.F), len(M.df), len(M.kinds), restricted,
              g3(weighted_percentile(M.aniso[ok], W[ok], 0.99)), g3(weighted_percentile(M.aniso[ok], W[ok], 0.999)),
              g3(M.aniso[ok].max()), len(bad), THRESHOLD, 100 * bad_w / total_w))
    print()
    worst = np.argsort(-np.where(ok, M.aniso, -1), kind="stable")[:o.worst]
    causes_worst = classify(M, PT, worst, o.gap)
    sang, iang = angles(M.surface[worst]).min(axis=1), angles(M.image[worst]).min(axis=1)
    print("| face | patch | σ₁/σ₂ | σ₁′ | σ₂′ | area T′/image | min ∠ T′ | min ∠ image | area / T face | corners on curves | edges on curves | at x_j | thin side | gap | cause |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r, f in enumerate(worst):
        tf = M.containing_T_face(f)
        rel = M.AP[f] / areas(M.TV[M.TF[tf:tf + 1]])[0] if tf >= 0 else np.nan
        on_curve = int((M.dcount[M.F[f]] <= 2).sum())
        at_corner = "yes" if (M.dcount[M.F[f]] == 1).any() else "no"
        thin = "surface" if 1 / M.s2p[f] >= M.s1p[f] else "image"
        cause, gap, detail = causes_worst[r]
        print("| %d | %d | %s | %s | %s | %s | %.2g° | %.2g° | %s | %d | %d | %s | %s | %s | %s (%s) |" % (
            f, M.patch[f], g3(M.aniso[f]), g3(M.s1p[f]), g3(M.s2p[f]), g3(M.s1p[f] * M.s2p[f]), sang[r], iang[r],
            g3(rel), on_curve, M.curve_edges[f], at_corner, thin, g3(gap), cause, detail))
    print()
    causes_bad = classify(M, PT, bad, o.gap)
    names = [c for c, _, _ in causes_bad]
    thin_bad = np.where(1 / M.s2p[bad] >= M.s1p[bad], "surface", "image")
    print("| cause | of the %d worst | faces above %g | share of their area | thin side surface/image |" % (len(worst), THRESHOLD))
    print("|---|---|---|---|---|")
    for c in CAUSES:
        n_w = sum(1 for x, _, _ in causes_worst if x == c)
        sel = np.array([x == c for x in names], dtype=bool)
        if n_w == 0 and not sel.any():
            continue
        print("| %s | %d | %d | %.3f | %d/%d |" % (c, n_w, sel.sum(), W[bad][sel].sum() / bad_w if bad_w else 0,
                                                (thin_bad[sel] == "surface").sum(), (thin_bad[sel] == "image").sum()))
    print()
    share = np.bincount(M.patch[bad], W[bad], len(M.df)) / (bad_w if bad_w else 1)
    top = [d for d in np.argsort(-share, kind="stable")[:o.patches] if share[d] > 0]
    print("| patch | share of area above %g | faces above / all | max σ₁/σ₂ | sides | corner angles T′ (D) | side angles min–max | patch aspect T′ (D) | neck | main cause |" % THRESHOLD)
    print("|---|---|---|---|---|---|---|---|---|---|")
    for d in top:
        P = PT[d]
        fs = P["faces"]
        in_bad = np.isin(bad, fs)
        cs = [names[i] for i in np.nonzero(in_bad)[0]]
        wsum = {}
        for i in np.nonzero(in_bad)[0]:
            wsum[names[i]] = wsum.get(names[i], 0) + W[bad[i]]
        main = max(wsum, key=wsum.get) if wsum else "-"
        print("| %d | %.3f | %d/%d | %s | %s | %s | %s–%s° | %s (%s) | %s | %s |" % (
            d, share[d], len(cs), len(fs), g3(M.aniso[fs].max()), "".join(k[0] for k in P["kinds"]),
            " ".join("%.1f (%.1f)" % (a, b) for a, b in zip(P["corner_angle"], P["domain_angle"])),
            "%.0f" % P["side_angle_min"], "%.0f" % P["side_angle_max"],
            g3(triangle_aspect(P["side_len"])), g3(triangle_aspect(P["domain_side"])), g3(P["neck"]), main))
    print()
    return M, PT


def resolve(arg, o, work):
    """An input: (name, param path, mesh path, geodesics.obj path)."""
    if not os.path.exists(arg):
        fail("%s: no such file or directory" % arg)
    if os.path.isdir(arg):
        param = os.path.join(arg, "param.fhrp")
        if not os.path.exists(param):
            fail("%s: no param.fhrp in it" % arg)
    elif arg.endswith(".fhrp"):
        param = arg
    else:
        if not o.fhr or not o.faces:
            fail("%s: a mesh is run through `fhr run` first: give --fhr and --faces" % arg)
        work = work or tempfile.mkdtemp(prefix="distortion_causes_")
        out = os.path.join(work, os.path.splitext(os.path.basename(arg))[0])
        r = subprocess.run([o.fhr, "run", arg, "--faces", str(o.faces), "--out", out], capture_output=True, text=True)
        if r.returncode != 0:
            fail("%s: fhr run exited with %d: %s" % (arg, r.returncode, r.stderr.strip().splitlines()[-1:]))
        param = os.path.join(out, "param.fhrp")
    folder = os.path.dirname(os.path.abspath(param))
    mesh = o.mesh
    if mesh is None:
        report = os.path.join(folder, "report.json")
        if not os.path.exists(report):
            fail("%s: no report.json beside it to name the input mesh: give --mesh" % param)
        mesh = json.load(open(report))["input"]["path"]
    if not os.path.exists(mesh):
        fail("%s: no such file (the input mesh)" % mesh)
    name = os.path.splitext(os.path.basename(mesh))[0]
    return name, param, mesh, os.path.join(folder, "geodesics.obj")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("inputs", nargs="+", help="param.fhrp files, `fhr run` output directories, or meshes")
    parser.add_argument("--worst", type=int, default=20, help="faces listed per input (20)")
    parser.add_argument("--patches", type=int, default=8, help="patches listed per input (8)")
    parser.add_argument("--gap", type=float, default=0.05, help="a gap below this (relative to an edge of T) is a cause (0.05)")
    parser.add_argument("--mesh", help="the input mesh T (else report.json's input.path)")
    parser.add_argument("--fhr", help="the fhr binary, to run meshes given as inputs")
    parser.add_argument("--faces", type=int, help="--faces for `fhr run` on meshes given as inputs")
    parser.add_argument("--work", help="where `fhr run` writes for meshes given as inputs (a temporary directory)")
    o = parser.parse_args()
    if o.mesh and len(o.inputs) > 1:
        fail("--mesh names the mesh of one input only")
    for arg in o.inputs:
        analyse(*resolve(arg, o, o.work), o)
    return 0


if __name__ == "__main__":
    sys.exit(main())
