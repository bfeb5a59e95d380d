"""fhr itself as a peer (peers/fhr-param, peers/fhr-atlas): `fhr run` on MESH with a domain size
chosen from the mesh, and its param.fhrp or its textured.obj copied to OUT, so that fhr is judged
by the same rules and campaigns as the other programs. The fhr program is $FHR, else the
repository's build/src/fhr.

Domain size: N = min(F/4, 60) rounded down to even, at least 4 + 12·genus (above the fewest faces of
a closed surface of that genus); when the decimation cannot reach N (exit 2) the next try doubles
it, up to F. Exits with fhr's code when it fails otherwise.

With --flip it is a deliberately broken program: param.fhrp gets the β of the first two corners of
its first face of T′ swapped (an image triangle turned over: PARAM-7, PARAM-8), textured.obj the vt of
its first face's first corner reflected through the middle of the opposite side (the face turned
over onto its neighbours: a fold, ATLAS-4, where the vt is shared with them, else an overlap,
ATLAS-6)."""
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

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


KINDS = {
    "fhr-param": ("param.fhrp", flip_param, "the `fhr-param 1` file param.fhrp (spec/param.md)",
                  "two corners' β swapped in the first face"),
    "fhr-atlas": ("textured.obj", flip_atlas, "the UV atlas textured.obj (spec/atlas.md)",
                  "a corner's vt of the first face reflected over the opposite side"),
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
        with open(os.path.join(tmp, output)) as f:
            text = f.read()
    if len(args) == 3:
        text = flip(text)
    partial = "%s.tmp-%d" % (out, os.getpid())
    with open(partial, "w") as f:
        f.write(text)
    os.replace(partial, out)
    return 0
