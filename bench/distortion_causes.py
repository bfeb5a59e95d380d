#!/usr/bin/env python3
"""The worst faces of a parameterization, and what makes them so (paper_notes/atlas.md): for a `fhr-param 1` file, the faces of T′ with the largest anisotropy σ₁/σ₂
(spec/distortion.md DIST-1, computed here with numpy's SVD), each classified by where the
anisotropy comes from:
  - "sliver of T′": the surface triangle's own anisotropy (against an equilateral triangle of its
    area) is at least 10 times its image's: the surface triangle is the needle or cap;
  - "squeezed image": the image's is at least 10 times the surface triangle's;
  - "both" otherwise.
and by where the face lies: how many of its corners are on the patch's boundary (a curve: one β
exactly 0) and on a corner of D (two β exactly 0).

Usage: distortion_causes.py PARAM.fhrp [--worst N]  (prints one row per face, then the counts)"""
import argparse
import sys

import numpy as np


def read_param(path):
    tokens = open(path).read().split()
    assert tokens[:2] == ["fhr-param", "1"], "%s: not a fhr-param 1 file" % path
    i = 2

    def section(name, width):
        nonlocal i
        assert tokens[i] == name
        n = int(tokens[i + 1])
        rows = np.array(tokens[i + 2:i + 2 + n * width], dtype=float).reshape(n, width)
        i += 2 + n * width
        return rows

    dv = section("domain_vertices", 3)
    df = section("domain_faces", 3).astype(int)
    sv = section("surface_vertices", 3)
    sf = section("surface_faces", 13)
    return dv, df, sv, sf


def aspect(a, b, c):
    """σ₁/σ₂ of the map from an equilateral triangle of the same area onto triangle abc (3D)."""
    e = np.array([[0.0, 0.0], [1.0, 0.0], [0.5, np.sqrt(3) / 2]])
    P = np.column_stack([b - a, c - a])
    Q = np.column_stack([e[1] - e[0], e[2] - e[0]])
    s = np.linalg.svd(P @ np.linalg.inv(Q), compute_uv=False)
    return s[0] / s[1] if s[1] > 0 else np.inf


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("param")
    parser.add_argument("--worst", type=int, default=20)
    o = parser.parse_args()
    dv, df, sv, sf = read_param(o.param)
    faces = sf[:, :3].astype(int)
    patch = sf[:, 3].astype(int)
    beta = sf[:, 4:].reshape(-1, 3, 3)
    image = np.einsum("fkc,fcx->fkx", beta, dv[df[patch]])  # image corners in 3D (the domain triangle's plane)
    surface = sv[faces]
    rows = []
    for f in range(len(faces)):
        q, p = image[f], surface[f]
        Q = np.column_stack([q[1] - q[0], q[2] - q[0]])
        P = np.column_stack([p[1] - p[0], p[2] - p[0]])
        # The map from the image plane onto the surface triangle: in an orthonormal frame of the image plane.
        basis, _ = np.linalg.qr(Q)
        s = np.linalg.svd(P @ np.linalg.inv(basis.T @ Q), compute_uv=False)
        ratio = s[0] / s[1] if s[1] > 0 else np.inf
        rows.append((ratio, f))
    rows.sort(reverse=True)
    counts, boundary_corners = {}, 0
    print("%8s %12s %10s %10s %8s %8s %6s  %s" % ("face", "σ1/σ2", "T' aspect", "image asp", "on curve", "on D vx", "patch", "cause"))
    for ratio, f in rows[:o.worst]:
        t_aspect = aspect(*surface[f])
        i_aspect = aspect(*image[f])
        zeros = (beta[f] == 0).sum(axis=1)
        on_curve, at_corner = int((zeros >= 1).sum()), int((zeros >= 2).sum())
        if t_aspect >= 10 * i_aspect:
            cause = "sliver of T'"
        elif i_aspect >= 10 * t_aspect:
            cause = "squeezed image"
        else:
            cause = "both"
        counts[cause] = counts.get(cause, 0) + 1
        boundary_corners += on_curve == 3
        print("%8d %12.4g %10.4g %10.4g %8d %8d %6d  %s" % (f, ratio, t_aspect, i_aspect, on_curve, at_corner, patch[f], cause))
    worst = min(o.worst, len(rows))
    print("causes of the %d worst faces: %s; with all three corners on the patch's boundary: %d" % (
        worst, ", ".join("%s %d" % kv for kv in sorted(counts.items())), boundary_corners))
    return 0


if __name__ == "__main__":
    sys.exit(main())
