#!/usr/bin/env python3
"""`./run families [COUNT]`: fhr's own pipeline on the generator's families (issue 17: meshes as
hard as real ones). For each embedded family (block, smooth, quality, valence, density,
degenerate: src/fhr/generate/random_mesh.hpp; `--families a,b` for some of them) COUNT random
meshes (default 500), each run through `fhr run` at default settings and `fhr verify --mesh`
exactly as `./run corpus` runs its meshes (certify.py: the domain size rule, what counts as
certified). Prints, in markdown for paper_notes, one row per family (meshes, certified, failures)
and a total, then every failure with the `fhr generate` command of its mesh and the first line of
its error; the exit code is 0 when every mesh is certified with its domain kept, else 1.

Mesh i of family f is drawn from (seed, f, i) alone — Python's random.Random seeded with the
string "S f i" (SHA-512 of the string: the same on every platform and Python ≥ 3.2) — so the
recipes do not depend on COUNT's other meshes, on --families, or on the shard: genus in
[0, --genus-max] (default 3), boundary loops in [0, --holes-max] (default 5), components in
[1, --components-max] (default 3), genus and loops being totals over the components as in `fhr
generate`; faces uniform in [max(1000, min_faces), 20000] (--faces-min, --faces-max; the even
ones without holes), min_faces being the family's least for that topology (`fhr generate
--min-faces`); a seed below 2^63; the family's knobs at their defaults.

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
import functools
import os
import random
import shutil
import subprocess

import campaign
import certify

EMBEDDED = ("block", "smooth", "quality", "valence", "density", "degenerate")

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("paths", nargs="*", metavar="FHR OUT_DIR [COUNT] | RESULTS")
parser.add_argument("--families", default=",".join(EMBEDDED), help="comma-separated (default: every embedded family)")
parser.add_argument("--seed", type=int, default=1)
parser.add_argument("--genus-max", type=int, default=3)
parser.add_argument("--holes-max", type=int, default=5)
parser.add_argument("--components-max", type=int, default=3)
parser.add_argument("--faces-min", type=int, default=1000)
parser.add_argument("--faces-max", type=int, default=20000)
parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per `fhr run`")
campaign.add_options(parser)
options = parser.parse_args()


def start():
    if len(options.paths) not in (2, 3) or (len(options.paths) == 3 and not options.paths[2].isdigit()):
        parser.error("give FHR OUT_DIR [COUNT] (or --merge RESULTS...)")
    fhr, out_dir = options.paths[:2]
    count = int(options.paths[2]) if len(options.paths) == 3 else 500
    families = options.families.split(",")

    @functools.lru_cache(maxsize=None)
    def min_faces(family, genus, holes, components):
        proc = subprocess.run([fhr, "generate", "--family", family, "--genus", str(genus), "--holes", str(holes),
                               "--components", str(components), "--min-faces"], capture_output=True, text=True)
        if proc.returncode != 0:
            raise campaign.CampaignError("fhr generate --family %s --min-faces: %s" % (family, certify.error_line(proc.stderr)))
        return int(proc.stdout)

    def recipe(family, i):
        """Mesh i of the family: its `fhr generate` arguments (without --out) and sizes."""
        rng = random.Random("%d %s %d" % (options.seed, family, i))
        genus = rng.randint(0, options.genus_max)
        holes = rng.randint(0, options.holes_max)
        components = rng.randint(1, options.components_max)
        least = max(options.faces_min, min_faces(family, genus, holes, components))
        if least > options.faces_max:
            raise campaign.CampaignError("%s meshes of genus %d with %d holes in %d components need %d faces, more than --faces-max"
                                         % (family, genus, holes, components, least))
        faces = rng.randint(least, options.faces_max) if holes else 2 * rng.randint((least + 1) // 2, options.faces_max // 2)
        args = ([] if family == "block" else ["--family", family]) + ["--genus", str(genus)]
        args += (["--holes", str(holes)] if holes else []) + (["--components", str(components)] if components > 1 else [])
        args += ["--faces", str(faces), "--seed", str(rng.getrandbits(63))]
        return args, faces, genus, holes, components

    def work(index):
        family, i = families[index // count], index % count
        args, faces, genus, holes, components = recipe(family, i)
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
