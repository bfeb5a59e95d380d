#!/usr/bin/env python3
"""How hard the generator's meshes are, beside real ones (the table of
paper_notes/generator.md): for each family COUNT meshes (default 100) drawn as `./run families`
draws them (family_recipes.py), and for each libcgal-demo mesh that is closed and valid, the
smallest corner angle, the largest valence and the longest/shortest edge ratio (`fhr info --json`:
fhr::shape_stats and the edge-length statistics). Prints a markdown table, one row per family and
one for the real meshes: per figure the median over the meshes and the extremes (the least and the
greatest of the per-mesh values). Then the generator's per-mesh guarantees with default knobs — every
quality mesh's smallest angle ≤ 10⁻³°, every valence mesh's largest valence ≥ 50, every density
mesh's ratio ≥ 10⁴ — each as `every mesh: yes`, or the meshes that miss it; the exit code is 1
when one is missed.

Usage: generator_stats.py FHR OUT_DIR [COUNT] [--cgal MESHES_DIR] [--families a,b] [recipe options]"""
import argparse
import json
import os
import statistics
import subprocess
import sys

import family_recipes

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("fhr")
parser.add_argument("out_dir")
parser.add_argument("count", nargs="?", type=int, default=100)
parser.add_argument("--cgal", help="the libcgal-demo meshes folder (data/meshes)")
family_recipes.add_options(parser, family_recipes.EMBEDDED + ("immersed",))
options = parser.parse_args()

# The generator's guarantees with default knobs (spec/generator.md): (family, figure, test, what it means).
GUARANTEES = [("quality", "angle", lambda x: x <= 1e-3, "smallest angle <= 1e-3 deg"),
              ("valence", "valence", lambda x: x >= 50, "largest valence >= 50"),
              ("density", "ratio", lambda x: x >= 1e4, "edge-length ratio >= 1e4")]


def figures(path):
    """(smallest angle in degrees, largest valence, longest/shortest edge) of a mesh, or None when
    fhr info does not call it valid."""
    proc = subprocess.run([options.fhr, "info", "--json", path], capture_output=True, text=True)
    info = json.loads(proc.stdout) if proc.stdout.strip() else {}
    if proc.returncode != 0 or not info.get("valid"):
        return None, info
    e = info["edge_length"]
    return {"angle": info["corner_angle_deg"]["min"], "valence": info["valence"]["max"],
            "ratio": e["max"] / e["min"]}, info


def row(label, values):
    def cell(key, fmt):
        xs = [v[key] for v in values]
        return "%s (%s – %s)" % (fmt % statistics.median(xs), fmt % min(xs), fmt % max(xs))
    return "| %s | %d | %s | %s | %s |" % (label, len(values), cell("angle", "%.3g"), cell("valence", "%d"),
                                           cell("ratio", "%.3g"))


def main():
    os.makedirs(options.out_dir, exist_ok=True)
    print("| meshes | count | smallest angle, deg: median (least – greatest) | largest valence | "
          "longest/shortest edge |")
    print("|---|---:|---|---|---|")
    missed = []
    for family in options.families.split(","):
        values = []
        for i in range(options.count):
            args, *_ = family_recipes.recipe(options.fhr, options, family, i)
            mesh = os.path.join(options.out_dir, "%s-%d.off" % (family, i))
            subprocess.run([options.fhr, "generate"] + args + ["--out", mesh], check=True)
            v, _ = figures(mesh)
            os.remove(mesh)
            if v is None:
                sys.exit("fhr info calls `fhr generate %s` invalid" % " ".join(args))
            values.append(v)
            for fam, key, ok, what in GUARANTEES:
                if fam == family and not ok(v[key]):
                    missed.append("%s mesh %d (`fhr generate %s`): %s is %g" % (family, i, " ".join(args), what, v[key]))
        print(row(family, values))
    if options.cgal:
        real = []
        for name in sorted(os.listdir(options.cgal)):
            v, info = figures(os.path.join(options.cgal, name))
            if v is not None and info.get("boundary_loops") == 0:
                real.append(v)
        print(row("libcgal-demo closed", real))
    print()
    for fam, key, ok, what in GUARANTEES:
        if fam in options.families.split(","):
            bad = [m for m in missed if m.startswith(fam + " ")]
            print("- %s, %s: %s" % (fam, what, "every mesh: yes" if not bad else "%d meshes miss it" % len(bad)))
    for m in missed:
        print("  - " + m)
    return 1 if missed else 0


sys.exit(main())
