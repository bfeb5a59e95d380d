#!/usr/bin/env python3
"""fhr posing as "another implementation" for `fhr oracle-fuzz` (spec/cli.md CLI-ORACLE-*).
Usage: fhr_as_other_program.py FHR MESH OUT [--flip]

Runs `FHR run MESH --faces N` into a temporary folder and copies its param.fhrp to OUT. Domain
size: N = min(F/4, 60) rounded down to even, at least 4 + 12·genus (above the fewest faces of a
closed surface of that genus, min_closed_faces); when the decimation cannot reach N (exit 2)
the next try doubles it, up to F (then D = T). Exits with fhr's code when it fails otherwise.
With --flip it is a deliberately broken implementation: it swaps the β of the first two corners
of the first face of T′, which folds that image triangle over (spec/param.md PARAM-7, PARAM-8)."""
import json, shutil, subprocess, sys, tempfile

fhr, mesh, out = sys.argv[1:4]
info = json.loads(subprocess.run([fhr, "info", "--json", mesh], capture_output=True, text=True, check=True).stdout)
faces, genus = info["faces"], info["genus"]
n = max(min(faces // 4, 60) // 2 * 2, 4 + 12 * genus)
with tempfile.TemporaryDirectory() as tmp:
    while True:
        run = subprocess.run([fhr, "run", mesh, "--faces", str(min(n, faces)), "--out", tmp], capture_output=True, text=True)
        if run.returncode != 2 or n >= faces:
            break
        n *= 2
    if run.returncode != 0:
        sys.stderr.write(run.stderr)
        sys.exit(run.returncode)
    lines = open(tmp + "/param.fhrp").read().split("\n")
if "--flip" in sys.argv[4:]:
    first = next(i for i, line in enumerate(lines) if line.startswith("surface_faces")) + 1
    t = lines[first].split()
    t[4:7], t[7:10] = t[7:10], t[4:7]
    lines[first] = " ".join(t)
open(out, "w").write("\n".join(lines))
