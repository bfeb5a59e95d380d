#!/usr/bin/env python3
"""`./run corpus`: `fhr run` with default settings on every mesh of libcgal-demo's data/meshes that
`fhr info --json` calls valid (without --triangulate): closed, with boundary loops, with several
components — and on ../shared/meshes/{horse,rocker}.off when present; each output is checked by
`fhr verify --mesh`. Prints one row per mesh (mesh, genus, boundary loops, components, faces,
domain faces requested -> final, §3 retries, domain edges that are exact geodesics / restricted
shortest paths / boundary arcs, certified, time), then `K of N certified (P %)`, `D kept on K of N`, the same two
counts for the closed connected meshes alone, the total time, and every failure with its exit code
and message (a domain that §3 does not keep is one).

Domain size rule, N = the --faces given to `fhr run`:
- closed and connected: N = F/100 rounded down to even, at most 1000, at least
  max(24, 2·min_closed_faces(genus)) (twice the fewest faces of a closed surface of that genus),
  and at most F (then D = T). `fhr run` delivers exactly N.
- with boundary or several components: N = F/100 rounded down to even, at most 1000, at least 24,
  at most F. `fhr info` gives only totals (genus, loops, components), so the per-component minima
  are left to §2 (domain::component_targets): it shares N among the components by area and raises
  each share to the least its topology allows (min_closed_faces(g) closed, 5b + 4g − 4 with b
  loops), and a component with boundary stops above its share when its loops and boundary corners
  need more faces. Then D has more than N faces, as `fhr run` says on its `domain: V vertices,
  F faces` line (report.json: domain.faces_requested is §2's D); the table shows `N -> F (§2: M)`
  and that run is fine. §3 must keep §2's D: domain.faces = domain.faces_requested.
When §2 cannot reach N under its validity rules it says `decimation stopped at K faces`; the run is
then repeated once with --faces K (noted in the table).
A mesh is certified when `fhr run` exits 0 and `fhr verify --mesh` accepts its param.fhrp.
Outputs: OUT_DIR/<mesh>/ (fhr run's folder) and OUT_DIR/<mesh>.stderr (its progress lines).

Usage: run_corpus.py FHR MESH_DIR OUT_DIR [--shared DIR] [--timeout SECONDS] [--only NAME ...]"""
import argparse
import json
import math
import os
import re
import subprocess
import sys
import time

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("fhr")
parser.add_argument("mesh_dir")
parser.add_argument("out_dir")
parser.add_argument("--shared", help="folder holding horse.off and rocker.off")
parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per `fhr run`")
parser.add_argument("--only", nargs="*", help="run only these mesh file names")
options = parser.parse_args()
fhr, mesh_dir, out_dir, shared_dir, timeout = options.fhr, options.mesh_dir, options.out_dir, options.shared, options.timeout


def min_closed_faces(genus):
    """domain::min_closed_faces: F = 2(V − χ), V from Heawood's bound (10 for genus 2)."""
    v = 10 if genus == 2 else math.ceil((7 + math.sqrt(1 + 48 * genus)) / 2)
    return 2 * (v - (2 - 2 * genus))


def domain_faces(faces, genus, closed_connected):
    n = min(faces // 100 // 2 * 2, 1000)
    least = max(24, 2 * min_closed_faces(genus)) if closed_connected else 24
    return min(max(n, least), faces)


def info(path):
    proc = subprocess.run([fhr, "info", "--json", path], capture_output=True, text=True)
    try:
        return json.loads(proc.stdout)
    except json.JSONDecodeError:
        return None


def error_line(stderr):
    lines = [l for l in stderr.splitlines() if l.startswith("fhr: error") or l.startswith("fhr: internal")]
    return lines[-1] if lines else (stderr.strip().splitlines() or ["(no message)"])[-1]


def run_one(path, faces, genus, loops, components):
    name = os.path.basename(path)
    out = os.path.join(out_dir, name)
    closed_connected = loops == 0 and components == 1
    target = domain_faces(faces, genus, closed_connected)
    row = {"mesh": name, "genus": genus, "loops": loops, "components": components, "faces": faces,
           "requested": target, "delivered": "-", "final": "-", "retries": "-", "curves": "-", "certified": False,
           "seconds": 0.0, "note": "", "failure": None, "closed_connected": closed_connected}
    start = time.monotonic()
    for attempt in range(2):
        try:
            proc = subprocess.run([fhr, "run", path, "--faces", str(target), "--out", out], capture_output=True,
                                  text=True, errors="replace", timeout=timeout)
            code, stderr = proc.returncode, proc.stderr
        except subprocess.TimeoutExpired as e:  # e.stderr: what it printed before it was killed
            partial = e.stderr.decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
            code, stderr = -1, partial + "timed out after %g s\n" % timeout
        stopped = re.search(r"decimation stopped at (\d+) faces", stderr)
        if code == 2 and stopped and attempt == 0:
            row["note"] = "§2 reached %s, not %d" % (stopped.group(1), target)
            target = int(stopped.group(1))
            row["requested"] = target
            continue
        break
    row["seconds"] = time.monotonic() - start
    with open(out + ".stderr", "w") as f:  # fhr run's progress and error lines, for the failures
        f.write(stderr)
    report = os.path.join(out, "report.json")
    if os.path.exists(report) and code in (0, 4):
        with open(report) as f:
            r = json.load(f)
        d, p = r["domain"], r["partition"]
        row["delivered"], row["final"], row["retries"] = d["faces_requested"], d["faces"], d["retries"]
        row["curves"] = "%d / %d / %d" % (p["geodesic_edges"], p["restricted_edges"], p["boundary_edges"])
    if code == -1:
        progress = stderr.splitlines()[:-1]
        row["failure"] = "fhr run timed out after %g s; its last line: %s" % (timeout, progress[-1] if progress else "-")
        return row
    if code != 0:
        row["failure"] = "fhr run exit %d: %s" % (code, error_line(stderr))
        return row
    verify = subprocess.run([fhr, "verify", os.path.join(out, "param.fhrp"), "--mesh", path], capture_output=True,
                            text=True, errors="replace")
    if verify.returncode != 0:
        row["failure"] = "fhr verify exit %d: %s" % (verify.returncode,
                                                     (verify.stdout.splitlines() or [error_line(verify.stderr)])[0])
        return row
    row["certified"] = True
    if row["final"] != row["delivered"]:
        row["failure"] = "§3 changed the domain: §2 gave %s faces, the partition has %s" % (row["delivered"], row["final"])
    elif closed_connected and row["delivered"] != target:
        row["failure"] = "§2 gave %s faces, not the %d requested" % (row["delivered"], target)
    return row


def kept(row):
    """§3 kept §2's domain, and §2 gave exactly N on a closed connected mesh."""
    return row["final"] == row["delivered"] and (not row["closed_connected"] or row["delivered"] == row["requested"])


def summary(rows, label):
    certified = sum(r["certified"] for r in rows)
    print("%s%d of %d certified (%.1f %%)" % (label, certified, len(rows), 100.0 * certified / max(len(rows), 1)))
    print("%sD kept on %d of %d" % (label, sum(kept(r) for r in rows), len(rows)))


candidates = sorted(os.path.join(mesh_dir, m) for m in os.listdir(mesh_dir))
if shared_dir:
    candidates += [os.path.join(shared_dir, m) for m in ("horse.off", "rocker.off")
                   if os.path.exists(os.path.join(shared_dir, m))]
if options.only:
    candidates = [p for p in candidates if os.path.basename(p) in options.only]
inputs = []
for path in candidates:
    d = info(path)
    if d and d.get("valid"):
        inputs.append((path, d["faces"], d["genus"], d["boundary_loops"], d["components"]))
os.makedirs(out_dir, exist_ok=True)

print("%-33s %5s %5s %5s %8s %22s %7s %17s %9s %8s  %s" % (
    "mesh", "genus", "loops", "comp.", "faces", "domain faces", "retries", "geod/restr/bound", "certified", "time s", "note"))
rows = []
for path, faces, genus, loops, components in inputs:
    row = run_one(path, faces, genus, loops, components)
    rows.append(row)
    domain = "%s -> %s" % (row["requested"], row["final"])
    if row["delivered"] not in ("-", row["requested"]):
        domain += " (§2: %s)" % row["delivered"]
    print("%-33s %5d %5d %5d %8d %22s %7s %17s %9s %8.2f  %s" % (
        row["mesh"], row["genus"], row["loops"], row["components"], row["faces"], domain, row["retries"],
        row["curves"], "yes" if row["certified"] else "NO", row["seconds"], row["note"]), flush=True)
summary(rows, "")
summary([r for r in rows if r["closed_connected"]], "closed and connected: ")
summary([r for r in rows if not r["closed_connected"]], "with boundary or several components: ")
print("fhr run: %.1f s in all" % sum(r["seconds"] for r in rows))
for r in rows:
    if r["failure"]:
        print("FAILED %s (genus %d, %d loops, %d components, %d faces, --faces %s): %s" % (
            r["mesh"], r["genus"], r["loops"], r["components"], r["faces"], r["requested"], r["failure"]))
sys.exit(0 if all(r["certified"] and kept(r) for r in rows) else 1)
