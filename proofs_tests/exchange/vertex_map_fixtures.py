#!/usr/bin/python3
"""Fixtures for per-vertex maps (spec/vertex_map.md): from a `fhr-param 1` file (spec/param.md;
gzip-compressed when its name ends in .gz) the refined surface T', the domain D and the map of
every vertex of T' onto D, in the four formats of the spec's table; optionally the map of the
input mesh T's vertices alone; and perturbations of a map that break it on purpose.

Each vertex of T' takes the patch of the first face of T' (in file order) holding it and that
face's barycentric triple for the corner: the domain face d and its weights (w0, w1, w2) on d's
corners in D's order. The four writers put it as

  plain  `d w0 w1 w2` after the lines `fhr-vertex-map 1` and the vertex count;
  corr   `d+1 w0 w1 w2`;
  vtpm   `h0 h1 alpha beta` with the halfedge h0 -> h1 of d from its corner 0 to its corner 1,
         alpha = w1, beta = w2, after the counts of the vertices of T and of D;
  ijv    `i+1 j+1 w` for every corner j of d with a non-zero weight w;

a vertex without an image is `-1 0 0 0`, `-1 0 0 0`, `-1 -1 0 0` and no line. Numbers are written
in shortest round-trip form (Python's repr).

Usage:
  vertex_map_fixtures.py write PARAM OUTDIR [--mesh T.off]
      writes OUTDIR/Tprime.off, OUTDIR/D.off and OUTDIR/Tprime.{vmap,corr,vtpm,ijv}; with --mesh,
      also OUTDIR/T.off (a copy) and OUTDIR/T_only.vmap, the map of T's vertices, each matched
      to the vertex of T' at exactly its position.
  vertex_map_fixtures.py perturb MAP.vmap --domain D.off --out OUT [--swap A B] [--move V]
                                 [--edge A B] [--eps E]
      reads a plain map, swaps the entries of vertices A and B and/or moves vertex V's image across
      an edge of its face (the given one, or the edge opposite its smallest weight) into the
      neighbouring face, at a distance eps (barycentric) beyond it, and writes OUT in the format
      of its extension.
A file that cannot be read is refused with a one-line message and exit code 2.
"""

import argparse
import gzip
import shutil
import sys
from pathlib import Path

__all__ = ["read_param", "read_off", "write_off", "map_of_param", "restrict_to_mesh", "write_map",
           "read_plain_map", "swap", "move_across_edge", "write_fixtures"]

EXTENSIONS = {".vmap": "plain", ".corr": "corr", ".vtpm": "vtpm", ".ijv": "ijv"}


def _text(path):
    path = str(path)
    opener = gzip.open if path.endswith(".gz") else open
    with opener(path, "rb") as fh:
        return fh.read().decode("latin-1")


def _tokens(path):
    """Every whitespace-separated token with its line number, '#' comments removed."""
    for lineno, line in enumerate(_text(path).split("\n"), 1):
        for tok in line.split("#", 1)[0].split():
            yield lineno, tok


def read_param(path):
    """A `fhr-param 1` file as a dict: domain_vertices [(x, y, z)], domain_faces [(i, j, k)],
    surface_vertices [(x, y, z)], surface_faces [((a, b, c), d, (beta_a, beta_b, beta_c))]."""
    toks = _tokens(path)

    def take(what):
        try:
            return next(toks)
        except StopIteration:
            raise ValueError("%s: unexpected end of file (expected %s)" % (path, what)) from None

    def number(kind, what):
        lineno, tok = take(what)
        try:
            return kind(tok)
        except ValueError:
            raise ValueError("%s:%d: expected %s, found '%s'" % (path, lineno, what, tok)) from None

    if (take("the header")[1], take("the header")[1]) != ("fhr-param", "1"):
        raise ValueError("%s: the header is not 'fhr-param 1'" % path)
    out = {}
    for section, width in (("domain_vertices", 3), ("domain_faces", 3),
                           ("surface_vertices", 3), ("surface_faces", 13)):
        lineno, name = take(section)
        if name != section:
            raise ValueError("%s:%d: expected section '%s', found '%s'" % (path, lineno, section, name))
        n = number(int, "the count of " + section)
        kind = float if section.endswith("vertices") else int
        rows = []
        for _ in range(n):
            if section == "surface_faces":
                corners = tuple(number(int, "a corner") for _ in range(3))
                d = number(int, "a patch")
                beta = tuple(tuple(number(float, "a barycentric coordinate") for _ in range(3))
                             for _ in range(3))
                rows.append((corners, d, beta))
            else:
                rows.append(tuple(number(kind, "a record of " + section) for _ in range(width)))
        out[section] = rows
    for lineno, tok in toks:
        raise ValueError("%s:%d: data after the last face ('%s')" % (path, lineno, tok))
    return out


def read_off(path):
    """(positions, faces) of an OFF triangle mesh, in file order."""
    toks = _tokens(path)
    first = next(toks, (1, None))
    if first[1] != "OFF":
        raise ValueError("%s:%d: not an OFF file" % (path, first[0]))
    try:
        nv, nf = int(next(toks)[1]), int(next(toks)[1])
        next(toks)
        positions = [tuple(float(next(toks)[1]) for _ in range(3)) for _ in range(nv)]
        faces = []
        for _ in range(nf):
            if int(next(toks)[1]) != 3:
                raise ValueError("%s: a face is not a triangle" % path)
            faces.append(tuple(int(next(toks)[1]) for _ in range(3)))
    except StopIteration:
        raise ValueError("%s: unexpected end of file" % path) from None
    return positions, faces


def write_off(path, positions, faces):
    lines = ["OFF", "%d %d 0" % (len(positions), len(faces))]
    lines += ["%r %r %r" % tuple(p) for p in positions]
    lines += ["3 %d %d %d" % tuple(f) for f in faces]
    Path(path).write_text("\n".join(lines) + "\n")


def map_of_param(param):
    """Per vertex of T': (domain face, (w0, w1, w2)) from the first face holding it, or None."""
    vmap = [None] * len(param["surface_vertices"])
    for corners, d, beta in param["surface_faces"]:
        for v, b in zip(corners, beta):
            if vmap[v] is None:
                vmap[v] = (d, b)
    return vmap


def restrict_to_mesh(vmap, tprime_positions, mesh_positions, mesh_path="T"):
    """The entries of the vertices of T' at exactly the positions of T's vertices, in T's order."""
    where = {}
    for v, p in enumerate(tprime_positions):
        where.setdefault(tuple(x + 0.0 for x in p), v)
    out = []
    for i, p in enumerate(mesh_positions):
        v = where.get(tuple(x + 0.0 for x in p))
        if v is None:
            raise ValueError("%s: vertex %d is not a vertex of T'" % (mesh_path, i))
        out.append(vmap[v])
    return out


def write_map(path, vmap, domain_faces, n_domain, fmt=None):
    """Writes vmap (entries (d, (w0, w1, w2)) or None) in fmt, or the format of path's extension."""
    fmt = fmt or EXTENSIONS.get(Path(path).suffix.lower())
    if fmt is None:
        raise ValueError("%s: unknown map extension (.vmap, .corr, .vtpm or .ijv)" % path)
    lines = []
    if fmt == "plain":
        lines += ["fhr-vertex-map 1", str(len(vmap))]
        lines += ["-1 0 0 0" if e is None else "%d %r %r %r" % ((e[0],) + tuple(e[1])) for e in vmap]
    elif fmt == "corr":
        lines += ["-1 0 0 0" if e is None else "%d %r %r %r" % ((e[0] + 1,) + tuple(e[1]))
                  for e in vmap]
    elif fmt == "vtpm":
        lines.append("%d %d" % (len(vmap), n_domain))
        for e in vmap:
            if e is None:
                lines.append("-1 -1 0 0")
            else:
                f = domain_faces[e[0]]
                lines.append("%d %d %r %r" % (f[0], f[1], e[1][1], e[1][2]))
    elif fmt == "ijv":
        for i, e in enumerate(vmap):
            if e is not None:
                lines += ["%d %d %r" % (i + 1, j + 1, w)
                          for j, w in zip(domain_faces[e[0]], e[1]) if w != 0]
    else:
        raise ValueError("unknown map format '%s'" % fmt)
    Path(path).write_text("\n".join(lines) + "\n" if lines else "")


def read_plain_map(path):
    """The entries of a plain map (fhr-vertex-map 1) as write_map takes them."""
    rows = [line.split("#", 1)[0].split() for line in _text(path).split("\n")]
    rows = [r for r in rows if r]
    if not rows or rows[0] != ["fhr-vertex-map", "1"] or len(rows) < 2 or len(rows) != int(rows[1][0]) + 2:
        raise ValueError("%s: not a plain map with as many records as announced" % path)
    return [None if int(r[0]) == -1 else (int(r[0]), tuple(float(x) for x in r[1:4]))
            for r in rows[2:]]


def swap(vmap, a, b):
    """A copy of vmap with the entries of vertices a and b exchanged."""
    if not (0 <= a < len(vmap) and 0 <= b < len(vmap)):
        raise ValueError("vertex %d or %d out of range (0..%d)" % (a, b, len(vmap) - 1))
    out = list(vmap)
    out[a], out[b] = out[b], out[a]
    return out


def move_across_edge(vmap, domain_faces, v, edge=None, eps=1e-3):
    """A copy of vmap with v's image moved into the face of D across an edge (a, b) of its face
    d (default: the edge opposite d's corner of smallest weight): the point of (a, b) with the
    weights of a and b in their ratio in v's entry (the midpoint when both are 0), scaled by
    1 - eps, and eps on the third corner of the face across."""
    if not 0 <= v < len(vmap) or vmap[v] is None:
        raise ValueError("vertex %d has no entry to move" % v)
    d, w = vmap[v]
    tri = domain_faces[d]
    if edge is None:
        k = min(range(3), key=lambda i: w[i])
        edge = (tri[(k + 1) % 3], tri[(k + 2) % 3])
    a, b = edge
    if a not in tri or b not in tri or a == b:
        raise ValueError("%d-%d is not an edge of face %d of D" % (a, b, d))
    across = [f for f, g in enumerate(domain_faces) if f != d and a in g and b in g]
    if not across:
        raise ValueError("edge %d-%d of D is on the boundary: no face across it" % (a, b))
    wa, wb = w[tri.index(a)], w[tri.index(b)]
    la, lb = (wa / (wa + wb), wb / (wa + wb)) if wa + wb > 0 else (0.5, 0.5)
    e = across[0]
    weights = {a: (1 - eps) * la, b: (1 - eps) * lb}
    out = list(vmap)
    out[v] = (e, tuple(weights.get(c, eps) for c in domain_faces[e]))
    return out


def write_fixtures(param_path, out_dir, mesh_path=None):
    """The files of `write` (see the module docstring); returns the paths written."""
    param = read_param(param_path)
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = [out / "Tprime.off", out / "D.off"]
    write_off(written[0], param["surface_vertices"], [c for c, _, _ in param["surface_faces"]])
    write_off(written[1], param["domain_vertices"], param["domain_faces"])
    vmap = map_of_param(param)
    n_domain = len(param["domain_vertices"])
    for ext in EXTENSIONS:
        written.append(out / ("Tprime" + ext))
        write_map(written[-1], vmap, param["domain_faces"], n_domain)
    if mesh_path is not None:
        positions, _ = read_off(mesh_path)
        only = restrict_to_mesh(vmap, param["surface_vertices"], positions, mesh_path)
        written += [out / "T.off", out / "T_only.vmap"]
        shutil.copyfile(mesh_path, written[-2])
        write_map(written[-1], only, param["domain_faces"], n_domain)
    return written


def main(argv=None):
    parser = argparse.ArgumentParser(prog="vertex_map_fixtures.py",
                                     description="Per-vertex map fixtures (spec/vertex_map.md).")
    sub = parser.add_subparsers(dest="command", required=True)
    w = sub.add_parser("write")
    w.add_argument("param")
    w.add_argument("outdir")
    w.add_argument("--mesh")
    p = sub.add_parser("perturb")
    p.add_argument("map")
    p.add_argument("--domain", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--swap", nargs=2, type=int, metavar=("A", "B"))
    p.add_argument("--move", type=int, metavar="V")
    p.add_argument("--edge", nargs=2, type=int, metavar=("A", "B"))
    p.add_argument("--eps", type=float, default=1e-3)
    args = parser.parse_args(argv)
    try:
        if args.command == "write":
            for path in write_fixtures(args.param, args.outdir, args.mesh):
                print(path)
        else:
            positions, faces = read_off(args.domain)
            vmap = read_plain_map(args.map)
            if args.swap:
                vmap = swap(vmap, *args.swap)
            if args.move is not None:
                vmap = move_across_edge(vmap, faces, args.move, args.edge, args.eps)
            write_map(args.out, vmap, faces, len(positions))
    except (ValueError, OSError) as exc:
        print("vertex_map_fixtures: error: %s" % str(exc).splitlines()[0], file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
