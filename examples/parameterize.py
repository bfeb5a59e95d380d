#!/usr/bin/env python3
"""examples/parameterize.py -- the paper's method from Python, the twin of examples/parameterize.cpp:
read a closed mesh T, map it onto a domain D of the given size (fhr.parameterize: §2 decimation, §3
partition keeping D, §4 certified patch maps, the independent oracle), and print for each vertex v
of T the face of D and the barycentric coordinates of psi(v), in the same lines as the C++ example:
"v d b0 b1 b2" (the first face of T' around v decides, as there).

Usage: python3 parameterize.py MESH FACES > params.txt   (needs the fhr package: README)
"""
import sys

import numpy as np

import fhr


def main(mesh_path, faces):
    V, F = fhr.read_mesh(mesh_path)
    p = fhr.parameterize(V, F, faces=faces, map="paper")  # the paper's §4 map, as examples/parameterize.cpp
    if not p.certified:
        sys.exit("parameterize: not certified: %s" % p.oracle["first_failure"])
    # T' keeps T's vertices under their own numbers; take each one's first corner in face order.
    corners = p.refined[1].ravel()  # corner c is corner c % 3 of face c // 3
    vertices, first = np.unique(corners, return_index=True)
    first = first[vertices < len(V)]
    beta = p.face_beta.reshape(-1, 3)
    patch = np.repeat(p.face_patch, 3)
    for v, c in enumerate(first):
        b = beta[c]
        print("%d %d %.17g %.17g %.17g" % (v, patch[c], b[0], b[1], b[2]))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: parameterize.py MESH FACES")
    try:
        main(sys.argv[1], int(sys.argv[2]))
    except fhr.InvalidInput as e:
        sys.exit("parameterize: %s" % e)
