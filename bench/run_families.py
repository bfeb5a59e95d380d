#!/usr/bin/env python3
"""`./run families [COUNT]`: fhr's own pipeline on the generator's families (meshes as
hard as real ones). For each embedded family (block, smooth, quality, valence, density,
degenerate: src/fhr/generate/random_mesh.hpp; `--families a,b` for some of them) COUNT random
meshes (default 500), each run through `fhr run` at default settings and `fhr verify --mesh`
exactly as `./run corpus` runs its meshes (certify.py: the domain size rule, what counts as
certified). Prints, in markdown for paper_notes, one row per family (meshes, certified, failures)
and a total, then every failure with the `fhr generate` command of its mesh and the first line of
its error; the exit code is 0 when every mesh is certified with its domain kept, else 1.

Mesh i of family f is drawn from (seed, f, i) alone (family_recipes.py: genus 0–3, 0–5 boundary
loops, 1–3 components, 1,000–20,000 faces, default knobs), so the recipes do not depend on
COUNT's other meshes, on --families, or on the shard.

A campaign (campaign.py): the items are family-major, item f·COUNT + i being mesh i of the f-th
family asked for; `--shard K/N` runs the items i with i mod N = K − 1, `-j J` runs J meshes at a
time, `--merge` prints the table of the shards' results as the unsharded run prints it.
Outputs: OUT_DIR/results.json (results-K-of-N.json for a shard); a failing mesh keeps its folder
OUT_DIR/<family>-<i>/ (mesh.off, run/ and run.stderr), a certified one leaves nothing.

Usage: run_families.py FHR OUT_DIR [COUNT] [--families a,b] [--seed S] [--genus-max G]
                       [--holes-max H] [--components-max C] [--faces-min A] [--faces-max B]
                       [--timeout SECONDS] [--shard K/N] [-j J]
       run_families.py --merge RESULTS... [--results FILE]   (results files, or folders holding them)"""
import argparse
import os
import shutil
import subprocess

import campaign
import certify
import family_recipes

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("paths", nargs="*", metavar="FHR OUT_DIR [COUNT] | RESULTS")
family_recipes.add_options(parser)
parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per `fhr run`")
campaign.add_options(parser)
options = parser.parse_args()


def start():
    if len(options.paths) not in (2, 3) or (len(options.paths) == 3 and not options.paths[2].isdigit()):
        parser.error("give FHR OUT_DIR [COUNT] (or --merge RESULTS...)")
    fhr, out_dir = options.paths[:2]
    count = int(options.paths[2]) if len(options.paths) == 3 else 500
    families = options.families.split(",")

    def work(index):
        family, i = families[index // count], index % count
        args, faces, genus, holes, components = family_recipes.recipe(fhr, options, family, i)
        folder = os.path.join(out_dir, "%s-%d" % (family, i))
        os.makedirs(folder, exist_ok=True)
        mesh = os.path.join(folder, "mesh.off")
        generated = subprocess.run([fhr, "generate"] + args + ["--out", mesh], capture_output=True, text=True)
        if generated.returncode != 0:
            row = {"certified": False, "seconds": 0.0, "closed_connected": holes == 0 and components == 1,
                   "failure": "fhr generate exit %d: %s" % (generated.returncode, certify.error_line(generated.stderr))}
        else:
            row = certify.certify(fhr, mesh, os.path.join(folder, "run"), faces, genus, holes, components, options.timeout)
        if not row["failure"]:
            shutil.rmtree(folder)
        return dict(row, index=index, family=family, i=i, mesh="%s-%d" % (family, i),
                    recipe="fhr generate %s --out mesh.off" % " ".join(args))

    params = {"seed": options.seed, "count": count, "families": families, "genus_max": options.genus_max,
              "holes_max": options.holes_max, "components_max": options.components_max,
              "faces": [options.faces_min, options.faces_max], "timeout": options.timeout}
    os.makedirs(out_dir, exist_ok=True)
    return params, count * len(families), work, out_dir


def describe(row):
    return "%s: %s (%.2f s)" % (row["mesh"], row["failure"] or "certified", row["seconds"])


def report(rows):
    def line(label, rs):
        certified = sum(r["certified"] for r in rs)
        return "| %s | %d | %d (%.1f %%) | %d |" % (label, len(rs), certified, 100.0 * certified / max(len(rs), 1),
                                                   sum(1 for r in rs if r["failure"]))
    families = list(dict.fromkeys(r["family"] for r in rows))
    print("| family | meshes | certified | failures |")
    print("|---|---:|---:|---:|")
    for family in families:
        print(line(family, [r for r in rows if r["family"] == family]))
    print(line("all", rows))
    failures = [r for r in rows if r["failure"]]
    if failures:
        print("\nFailures (the mesh's `fhr generate` command; the first line of the error):\n")
        print("| family | mesh | recipe | error |")
        print("|---|---:|---|---|")
        for r in failures:
            print("| %s | %d | `%s` | %s |" % (r["family"], r["i"], r["recipe"], r["failure"].splitlines()[0].replace("|", "\\|")))
    print("\nfhr run: %.1f s in all" % sum(r["seconds"] for r in rows))
    return 1 if failures else 0


campaign.main("families", options, options.paths, start, describe, report)
