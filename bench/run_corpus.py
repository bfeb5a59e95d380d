#!/usr/bin/env python3
"""`./run corpus`: `fhr run` with default settings on every mesh of libcgal-demo's data/meshes that
`fhr info --json` calls valid (without --triangulate): closed, with boundary loops, with several
components — and on ../shared/meshes/{horse,rocker}.off when present; each output is checked by
`fhr verify --mesh` (the domain size rule and what counts as certified: certify.py). Prints one row
per mesh (mesh, genus, boundary loops, components, faces, domain faces requested -> final, §3
retries, domain edges that are exact geodesics / restricted shortest paths / boundary arcs,
certified, time), then `K of N certified (P %)`, `D kept on K of N`, the same two counts for the
closed connected meshes alone and for the others, the total time, and every failure with its exit
code and message; and a second table, the distortion of each map (report.json's, spec/distortion.md:
L2 stretch, σ₁/σ₂ percentiles weighted by area, maximum, faces above 10) (a domain that §3 does not keep is one). The exit code is 0 when every mesh is
certified with its domain kept, else 1.

A campaign (campaign.py): the items are the candidate files, sorted (libcgal-demo's, then the
shared ones), item i the i-th; `--shard K/N` runs the items i with i mod N = K − 1 (`fhr info`
included, so a shard reads only its own meshes), `-j J` runs J meshes at a time (a progress line on
stderr as each ends; the table once all have), and `--merge` prints the table of the shards'
results as the unsharded run prints it (times aside). The parameters the shards must share are
the candidates' names and the timeout.
Outputs: OUT_DIR/<mesh>/ (fhr run's folder), OUT_DIR/<mesh>.stderr (its progress lines) and
OUT_DIR/results.json (results-K-of-N.json for a shard).

Usage: run_corpus.py FHR MESH_DIR OUT_DIR [--shared DIR] [--timeout SECONDS] [--only NAME ...]
                     [--shard K/N] [-j J]
       run_corpus.py --merge RESULTS... [--results FILE]   (results files, or folders holding them)"""
import argparse
import os

import campaign
import certify

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("paths", nargs="*", metavar="FHR MESH_DIR OUT_DIR | RESULTS")
parser.add_argument("--shared", help="folder holding horse.off and rocker.off")
parser.add_argument("--timeout", type=float, default=1800.0, help="seconds per `fhr run`")
parser.add_argument("--only", nargs="*", help="run only these mesh file names")
campaign.add_options(parser)
options = parser.parse_args()




def start():
    if len(options.paths) != 3:
        parser.error("give FHR MESH_DIR OUT_DIR (or --merge RESULTS...)")
    fhr, mesh_dir, out_dir = options.paths
    candidates = sorted(os.path.join(mesh_dir, m) for m in os.listdir(mesh_dir))
    if options.shared:
        candidates += [os.path.join(options.shared, m) for m in ("horse.off", "rocker.off")
                       if os.path.exists(os.path.join(options.shared, m))]
    if options.only:
        candidates = [p for p in candidates if os.path.basename(p) in options.only]
    os.makedirs(out_dir, exist_ok=True)

    def work(i):
        path = candidates[i]
        d = certify.info(fhr, path)
        if not (d and d.get("valid")):
            return {"index": i, "mesh": os.path.basename(path), "valid": False}
        out = os.path.join(out_dir, os.path.basename(path))
        row = certify.certify(fhr, path, out, d["faces"], d["genus"], d["boundary_loops"], d["components"], options.timeout)
        return dict(row, index=i, valid=True)

    params = {"meshes": [os.path.basename(p) for p in candidates], "timeout": options.timeout}
    return params, len(candidates), work, out_dir


def describe(row):
    if not row["valid"]:
        return "%s: not a valid input, skipped" % row["mesh"]
    return "%s: %s (%.2f s)" % (row["mesh"], "certified" if row["certified"] and not row["failure"] else row["failure"],
                                row["seconds"])


def summary(rows, label):
    certified = sum(r["certified"] for r in rows)
    print("%s%d of %d certified (%.1f %%)" % (label, certified, len(rows), 100.0 * certified / max(len(rows), 1)))
    print("%sD kept on %d of %d" % (label, sum(certify.kept(r) for r in rows), len(rows)))


def report(all_rows):
    rows = [r for r in all_rows if r["valid"]]
    print("%-33s %5s %5s %5s %8s %22s %7s %17s %9s %8s  %s" % (
        "mesh", "genus", "loops", "comp.", "faces", "domain faces", "retries", "geod/restr/bound/moved", "certified", "time s", "note"))
    for row in rows:
        domain = "%s -> %s" % (row["requested"], row["final"])
        if row["delivered"] not in ("-", row["requested"]):
            domain += " (§2: %s)" % row["delivered"]
        print("%-33s %5d %5d %5d %8d %22s %7s %17s %9s %8.2f  %s" % (
            row["mesh"], row["genus"], row["loops"], row["components"], row["faces"], domain, row["retries"],
            row["curves"], "yes" if row["certified"] else "NO", row["seconds"], row["note"]))
    print("\ndistortion of each map (spec/distortion.md: σ₁/σ₂ of each face of T′, percentiles weighted by area)")
    print("%-33s %9s %8s %8s %8s %10s %10s %9s" % ("mesh", "T' faces", "L2", "p50", "p99", "p99.9", "max", "faces>10"))
    for row in rows:
        d = row.get("distortion")
        if d:
            g = lambda x: "-" if x is None else "%.3g" % x  # noqa: E731
            print("%-33s %9d %8s %8s %8s %10s %10s %9d" % (row["mesh"], d["faces"], g(d["l2"]), g(d["p50"]), g(d["p99"]),
                                                          g(d["p999"]), g(d["max"]), d["above_10"]))
    print()
    summary(rows, "")
    summary([r for r in rows if r["closed_connected"]], "closed and connected: ")
    summary([r for r in rows if not r["closed_connected"]], "with boundary or several components: ")
    print("fhr run: %.1f s in all" % sum(r["seconds"] for r in rows))
    for r in rows:
        if r["failure"]:
            print("FAILED %s (genus %d, %d loops, %d components, %d faces, --faces %s): %s" % (
                r["mesh"], r["genus"], r["loops"], r["components"], r["faces"], r["requested"], r["failure"]))
    return 0 if all(r["certified"] and certify.kept(r) for r in rows) else 1


campaign.main("corpus", options, options.paths, start, describe, report)
