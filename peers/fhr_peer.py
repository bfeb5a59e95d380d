"""fhr itself as a peer (peers/fhr-param, peers/fhr-atlas, peers/fhr-vertex-map): `fhr run` on MESH
with a domain size chosen from the mesh, and its param.fhrp or its textured.obj copied to OUT, or
its map written per vertex of MESH into the folder OUT (map.vmap, with the domain D.off: each
vertex of T with the β of a face of T′ holding it, by proofs_tests/exchange/vertex_map_fixtures.py),
so that fhr is judged by the same rules and campaigns as the other programs. The fhr program is
$FHR, else the repository's build/src/fhr.

Domain size: N = min(F/4, 60) rounded down to even, at least 4 + 12·genus (above the fewest faces of
a closed surface of that genus); when the decimation cannot reach N (exit 2) the next try doubles
it, up to F. Exits with fhr's code when it fails otherwise.

With --flip it is a deliberately broken program: param.fhrp gets the β of the first two corners of
its first face of T′ swapped (an image triangle turned over: PARAM-7, PARAM-8), textured.obj the vt of
its first face's first corner reflected through the middle of the opposite side (the face turned
over: a fold, ATLAS-4, where the vt is shared with its neighbours; else an overlap, ATLAS-6, or,
where the face lands beyond its chart's boundary, a mirrored chart of its own, ATLAS-4 with
--no-mirror), the per-vertex map the images of its first and last vertices exchanged."""
import json
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "proofs_tests", "exchange"))
import vertex_map_fixtures  # noqa: E402

USAGE = """usage: %(name)s MESH OUT [--flip]
       %(name)s --help

fhr itself (Floater, Hormann, Reimers 2001): `fhr run MESH --faces N`, N = min(F/4, 60) rounded
down to even and at least 4 + 12 genus (doubled while the decimation cannot reach it), with $FHR or
the repository's build/src/fhr. Writes OUT: %(what)s. Any topology fhr accepts (boundary loops,
several components). Exit code: fhr's. --flip: a deliberately broken output (%(flip)s).
"""


def flip_param(text):
    lines = text.split("\n")
    first = next(i for i, line in enumerate(lines) if line.startswith("surface_faces")) + 1
    t = lines[first].split()
    t[4:7], t[7:10] = t[7:10], t[4:7]
    lines[first] = " ".join(t)
    return "\n".join(lines)


def flip_atlas(text):
    lines = text.split("\n")
    vt = [i for i, line in enumerate(lines) if line.startswith("vt ")]
    first = next(line for line in lines if line.startswith("f "))
    a, b, c = (int(corner.split("/")[1]) - 1 for corner in first.split()[1:4])
    uv = {k: [float(x) for x in lines[vt[k]].split()[1:3]] for k in (a, b, c)}
    # corner a's texture coordinates reflected through the middle of the opposite side
    lines[vt[a]] = "vt %r %r" % (uv[b][0] + uv[c][0] - uv[a][0], uv[b][1] + uv[c][1] - uv[a][1])
    return "\n".join(lines)


def write_vertex_map(fhr, mesh, run, out, flip):
    """The folder OUT: map.vmap (MESH's vertices, each with the β of a face of T′ holding it) and D.off."""
    partial = "%s.tmp-%d" % (out, os.getpid())
    os.makedirs(partial)
    t_off = os.path.join(run, "T.off")
    subprocess.run([fhr, "convert", mesh, "--out", t_off], check=True, capture_output=True)
    param = vertex_map_fixtures.read_param(os.path.join(run, "param.fhrp"))
    vmap = vertex_map_fixtures.restrict_to_mesh(vertex_map_fixtures.map_of_param(param), param["surface_vertices"],
                                                vertex_map_fixtures.read_off(t_off)[0], mesh)
    if flip:
        vmap = vertex_map_fixtures.swap(vmap, 0, len(vmap) - 1)
    vertex_map_fixtures.write_map(os.path.join(partial, "map.vmap"), vmap, param["domain_faces"], len(param["domain_vertices"]))
    vertex_map_fixtures.write_off(os.path.join(partial, "D.off"), param["domain_vertices"], param["domain_faces"])
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.replace(partial, out)


KINDS = {
    "fhr-param": ("param.fhrp", flip_param, "the `fhr-param 1` file param.fhrp (spec/param.md)",
                  "two corners' β swapped in the first face"),
    "fhr-atlas": ("textured.obj", flip_atlas, "the UV atlas textured.obj (spec/atlas.md)",
                  "a corner's vt of the first face reflected over the opposite side"),
    "fhr-vertex-map": (None, None, "a folder with the per-vertex map map.vmap of MESH onto the domain D.off "
                       "(spec/vertex_map.md)", "the images of the first and last vertices exchanged"),
}


def main(name):
    output, flip, what, flipped = KINDS[name]
    args = sys.argv[1:]
    if args[:1] == ["--help"]:
        sys.stdout.write(USAGE % {"name": name, "what": what, "flip": flipped})
        return 0
    if len(args) not in (2, 3) or (len(args) == 3 and args[2] != "--flip"):
        sys.stderr.write("%s: error: expected MESH OUT [--flip] (see --help)\n" % name)
        return 2
    mesh, out = args[0], args[1]
    fhr = os.environ.get("FHR") or os.path.join(ROOT, "build", "src", "fhr")
    proc = subprocess.run([fhr, "info", "--json", mesh], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.stderr.write(proc.stderr)
        return proc.returncode
    info = json.loads(proc.stdout)
    faces, genus = info["faces"], info["genus"]
    n = max(min(faces // 4, 60) // 2 * 2, 4 + 12 * genus)
    with tempfile.TemporaryDirectory() as tmp:
        while True:
            run = subprocess.run([fhr, "run", mesh, "--faces", str(min(n, faces)), "--out", tmp], capture_output=True,
                                 text=True)
            if run.returncode != 2 or n >= faces:
                break
            n *= 2
        if run.returncode != 0:
            sys.stderr.write(run.stderr)
            return run.returncode
        if output is None:
            write_vertex_map(fhr, mesh, tmp, out, len(args) == 3)
            return 0
        with open(os.path.join(tmp, output)) as f:
            text = f.read()
    if len(args) == 3:
        text = flip(text)
    partial = "%s.tmp-%d" % (out, os.getpid())
    with open(partial, "w") as f:
        f.write(text)
    os.replace(partial, out)
    return 0
