#!/usr/bin/env python3
"""`./run corpus atlases`: real programs' UV atlases judged by `fhr verify` (spec/atlas.md) and,
independently, by the exact checker proofs_tests/exchange/atlas_reference.py: the adapters of
peers/ (MeshLab's iso-parameterization on closed meshes of libcgal-demo, CGAL's methods on its
disks and on generated ones, fhr's own textured.obj) run on each mesh that suits them; each atlas
is judged against its input, and the oracle's set of folded faces and its overlapping pairs must
equal the independent checker's wherever the oracle computes them (a difference is a failure of
this script, exit code 1; an atlas whose surface or UV triangles fail ATLAS-2 or -3 is `n/a`).

Each fault is also classified by size, to tell a writer's rounding from the algorithm: a folded
face whose UV area is at most the area its corners' rounding can change (ρ·perimeter, ρ half a unit
in the last decimal the file prints for its vt values), or an overlapping pair whose intersection
is at most that large, could come from rounding a valid map; anything larger comes from the
algorithm itself.

Prints one row per (program, mesh): faces, exit code, the verdict (first failed check), folds and
overlapping pairs (and how many of each are within rounding), contacts, mirrored charts, L2
stretch, σ₁/σ₂ median and maximum, seconds of the program, whether the two checkers agree. Then a
summary per program. Outputs: OUT_DIR/<program>/<mesh>.obj and OUT_DIR/results.json.

Usage: judge_atlases.py FHR MESH_DIR OUT_DIR [--programs NAME ...] [--only MESH ...]"""
import argparse
import json
import os
import subprocess
import sys
import time

from shapely.geometry import Polygon

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "proofs_tests", "exchange"))
import atlas_reference  # noqa: E402
from certify import info  # noqa: E402

# Programs and the meshes they take. MeshLab's filters: closed meshes, one component (the
# iso-parameterization refuses holes and several components; the flat plane folds any closed
# surface: a control that must be found invalid).
# CGAL's methods: disks (one boundary loop, genus 0, one component).
CLOSED = ["fandisk.off", "elephant.off", "cow.off", "bunny00.off", "camel.off", "eight.off", "couplingdown.off",
          "sphere966.off", "dino.off", "bull.off", "triceratops.off", "homer.off", "blob-closed.off"]
DISKS_GENERATED = [("disk-%d.off" % seed, ["--genus", "0", "--holes", "1", "--faces", "4000", "--seed", str(seed)])
                   for seed in (1, 2, 3)]
PROGRAMS = {
    "meshlab-iso": "closed", "meshlab-trivial": "closed", "meshlab-voronoi": "closed", "meshlab-flat": "closed-small",
    "fhr-textured": "closed",
    "cgal-tutte": "disk", "cgal-mvc": "disk", "cgal-conformal": "disk", "cgal-authalic": "disk",
    "cgal-lscm": "disk", "cgal-arap": "disk", "cgal-lscm-mvc-post": "disk", "cgal-tutte-square": "disk",
}




def uv_rounding(path):
    """Half a unit in the last decimal of the file's vt values (0 for shortest round-trip ones,
    which are exact: more than 15 significant digits)."""
    decimals, significant = 0, 0
    with open(path) as f:
        for line in f:
            if line.startswith("vt "):
                for token in line.split()[1:3]:
                    mantissa = token.split("e")[0].split("E")[0]
                    if "." in mantissa:
                        decimals = max(decimals, len(mantissa) - mantissa.index(".") - 1)
                    significant = max(significant, sum(c.isdigit() for c in mantissa.lstrip("-0.")))
    return 0.0 if significant >= 15 else 0.5 * 10.0 ** -decimals


def classify(path, verdict, rho):
    """(folds within rounding, overlapping pairs within rounding) of the oracle's lists."""
    if rho == 0:
        return 0, 0
    atlas = atlas_reference.read_atlas(path)
    tri = lambda f: [tuple(p) for p in atlas.uvs[f]]  # noqa: E731
    perimeter = lambda t: sum(((t[k][0] - t[k - 1][0]) ** 2 + (t[k][1] - t[k - 1][1]) ** 2) ** 0.5 for k in range(3))  # noqa: E731
    folds = sum(1 for f in verdict.get("folded_face_list", []) if Polygon(tri(f)).area <= rho * perimeter(tri(f)))
    overlaps = 0
    for f, g in verdict.get("overlapping_pair_list", []):
        a, b = Polygon(tri(f)).buffer(0), Polygon(tri(g)).buffer(0)
        if a.intersection(b).area <= rho * max(perimeter(tri(f)), perimeter(tri(g))):
            overlaps += 1
    return folds, overlaps


def adapter_command(fhr, program, mesh, out):
    if program == "fhr-textured":  # fhr's own atlas, as fhr run writes it
        folder = out + ".run"
        return [fhr, "run", mesh, "--faces", "200", "--out", folder], os.path.join(folder, "textured.obj")
    return [os.path.join(ROOT, "peers", program), mesh, out], out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fhr")
    parser.add_argument("mesh_dir")
    parser.add_argument("out_dir")
    parser.add_argument("--programs", nargs="*", default=list(PROGRAMS))
    parser.add_argument("--only", nargs="*")
    options = parser.parse_args()
    fhr, out_dir = options.fhr, options.out_dir
    os.makedirs(out_dir, exist_ok=True)
    disks = []
    for name in sorted(os.listdir(options.mesh_dir)):
        i = info(fhr, os.path.join(options.mesh_dir, name))
        if i and i.get("valid") and i.get("components") == 1 and i.get("boundary_loops") == 1 and i.get("genus") == 0:
            disks.append(os.path.join(options.mesh_dir, name))
    for name, args in DISKS_GENERATED:
        path = os.path.join(out_dir, name)
        if not os.path.exists(path):
            subprocess.run([fhr, "generate", *args, "--out", path], check=True, stdout=subprocess.DEVNULL)
        disks.append(path)
    closed = [os.path.join(options.mesh_dir, m) for m in CLOSED if os.path.exists(os.path.join(options.mesh_dir, m))]
    rows, disagreements = [], 0
    print("%-20s %-26s %8s %4s %-9s %11s %11s %7s %4s %8s %8s %10s %7s %s" % (
        "program", "mesh", "faces", "exit", "verdict", "folds(rnd)", "overlaps(rnd)", "contact", "mirr", "L2",
        "σ p50", "σ max", "seconds", "agree"))
    for program in options.programs:
        # The flat plane folds half of every closed surface over the other: millions of overlapping
        # pairs on the larger meshes, which the exact checker in Python would take hours over.
        small = [m for m in closed if (info(fhr, m) or {}).get("faces", 0) <= 15000]
        meshes = {"closed": closed, "closed-small": small, "disk": disks}[PROGRAMS[program]]
        for mesh in meshes:
            name = os.path.basename(mesh)
            if options.only and name not in options.only:
                continue
            os.makedirs(os.path.join(out_dir, program), exist_ok=True)
            cmd, atlas = adapter_command(fhr, program, mesh, os.path.join(out_dir, program, os.path.splitext(name)[0] + ".obj"))
            start = time.monotonic()
            proc = subprocess.run(cmd, capture_output=True, text=True)
            seconds = time.monotonic() - start
            row = {"program": program, "mesh": name, "exit": proc.returncode, "seconds": seconds}
            if proc.returncode != 0:
                row["error"] = (proc.stderr.strip().splitlines() or [""])[-1]
                rows.append(row)
                print("%-20s %-26s %8s %4d %s" % (program, name, "", proc.returncode, row["error"][:90]))
                continue
            judged = subprocess.run([fhr, "verify", atlas, "--mesh", mesh, "--json", "--list"], capture_output=True, text=True)
            verdict = json.loads(judged.stdout)
            reference = atlas_reference.analyze(atlas_reference.read_atlas(atlas))
            # The sets are compared where the oracle computed them: ATLAS-4..7 are skipped when the
            # welded surface is no manifold (ATLAS-2) or a UV triangle is degenerate (ATLAS-3).
            skipped = {c["id"]: c["result"] for c in verdict["checks"]}.get("ATLAS-4") == "skipped"
            agree = None if skipped else (
                verdict.get("folded_face_list") == reference["folded_faces"] and
                [tuple(p) for p in verdict.get("overlapping_pair_list", [])] == [tuple(p) for p in reference["overlapping_pairs"]])
            disagreements += agree is False
            rho = uv_rounding(atlas)
            small_folds, small_overlaps = classify(atlas, verdict, rho)
            d = verdict["distortion"]
            row.update(faces=verdict["surface"]["faces"], valid=verdict["valid"], first_failure=verdict["first_failure"],
                       folds=verdict.get("folded_faces"), folds_within_rounding=small_folds,
                       overlaps=verdict.get("overlapping_pairs"), overlaps_within_rounding=small_overlaps,
                       contacts=verdict.get("contacts"), mirrored=verdict.get("mirrored_charts"), uv_rounding=rho,
                       distortion=d, agree=agree)
            rows.append(row)
            fmt = lambda x: "-" if x is None else "%.3g" % x  # noqa: E731
            print("%-20s %-26s %8d %4d %-9s %11s %11s %7s %4s %8s %8s %10s %7.1f %s" % (
                program, name, row["faces"], 0, row["first_failure"] or "valid",
                "%s(%d)" % (row["folds"], small_folds), "%s(%d)" % (row["overlaps"], small_overlaps), row["contacts"],
                row["mirrored"], fmt(d["l2_stretch"]), fmt(d["anisotropy"]["p50"]), fmt(d["anisotropy"]["max"]), seconds,
                "n/a" if agree is None else "yes" if agree else "NO"))
    with open(os.path.join(out_dir, "results.json"), "w") as f:
        json.dump(rows, f, indent=1)
    print("\nper program: runs, refused or failed (exit != 0), valid, invalid")
    for program in options.programs:
        mine = [r for r in rows if r["program"] == program]
        print("  %-20s %3d runs, %3d exit != 0, %3d valid, %3d invalid" % (
            program, len(mine), sum(r["exit"] != 0 for r in mine), sum(r.get("valid") is True for r in mine),
            sum(r.get("valid") is False for r in mine)))
    print("the oracle and the independent checker %s" % ("agree on every atlas" if disagreements == 0 else
                                                         "DISAGREE on %d atlases" % disagreements))
    return 1 if disagreements else 0


if __name__ == "__main__":
    sys.exit(main())
