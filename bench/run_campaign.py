#!/usr/bin/env python3
"""`./run campaign`: the oracle against real programs. Every adapter of peers/ (MeshLab's four
parameterization filters, CGAL 5.5's Surface_mesh_parameterization methods, fhr itself for each
kind of map) goes through `fhr oracle-fuzz` over each embedded family of the generator (block,
smooth, quality, valence, density, degenerate), restricted to the topology the program accepts
(closed for MeshLab, disks for CGAL, anything for fhr), twice with the same settings: a program
whose two tables differ is not deterministic.

For each program and family the table counts the runs, the valid maps, the meshes the program
declines (exit code 3: not applicable), crashes (a signal, or an exit code of 128 + N), timeouts,
other exit codes, and the invalid maps per first failed check (PARAM-k, ATLAS-k, VMAP-k), each
classed by what the method promises (PROMISES: "no promise", "broken in floating point",
"broken"); and the distortion of the maps read (spec/distortion.md): the median L2 stretch and the
worst σ₁/σ₂.
Every failure of the first run is kept by oracle-fuzz (mesh, output, reason, a shrunk mesh that
fails the same way) with a `rerun.sh` that runs the program on the shrunk mesh and judges it; the
script re-runs it — once for a deterministic program, whose reproducer must fail the same way
(else this script exits 1), five times for the others, whose failure rate is reported. fhr's
share of the wall time (generation, judging, shrinking: everything but the program) is reported
per program.

Prints the table and writes OUT/campaign.md (the table, the command line, the programs' Debian
versions) and OUT/results.json; the reproducers are in OUT/<program>/<family>/kept/mesh-i/.

Usage: run_campaign.py FHR OUT [--count N] [--seed S] [--programs NAME ...] [--families NAME ...]
       [-j J] [--timeout SECONDS]"""
import argparse
import concurrent.futures
import json
import os
import re
import shlex
import statistics
import subprocess
import sys
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
FAMILIES = ["block", "smooth", "quality", "valence", "density", "degenerate"]
# (adapter in peers/, what it writes, the topology it takes, its Debian package or None for fhr)
# and FACES_MIN, the least size a program works at: MeshLab's iso-parameterization declines or
# crashes on most meshes of 300 faces and works on nearly all from 1,000 (genus 1, each family,
# 2026-12-07), so its meshes start there (oracle-fuzz --faces-min).
FACES_MIN = {"meshlab-iso": 1000}
CGAL = ["cgal-tutte", "cgal-tutte-square", "cgal-mvc", "cgal-mvc-square", "cgal-conformal", "cgal-conformal-square",
        "cgal-authalic", "cgal-authalic-square", "cgal-lscm", "cgal-arap", "cgal-lscm-mvc-post"]
PROGRAMS = ([(name, "atlas", "closed", "meshlab") for name in ("meshlab-iso", "meshlab-trivial", "meshlab-voronoi", "meshlab-flat")]
            + [(name, "atlas", "disk", "libcgal-dev") for name in CGAL]
            + [("fhr-param", "param", "any", None), ("fhr-atlas", "atlas", "any", None),
               ("fhr-vertex-map", "vertex-map", "any", None)])
OUTPUT = {"param": "out.fhrp", "atlas": "out.obj", "vertex-map": "out"}
# What each method promises (paper_notes/campaigns.md): a one-to-one map under a condition the
# campaign's meshes meet, or nothing. An invalid map of a method without a promise is "no promise";
# of one with a promise, a triangle flattened to exactly collinear points — in UV (ATLAS-3: a
# solve in floating point can do it to a thin triangle) or in 3D (ATLAS-2, by a writer that rounds
# the positions) — is "broken in floating point", anything else "broken".
PROMISES = {
    "cgal-tutte": "one-to-one: convex combination weights, strictly convex border (Tutte 1963, Floater 2003)",
    "cgal-mvc": "one-to-one: mean value weights are positive, strictly convex border (Floater 2003)",
    "meshlab-iso": "one-to-one onto its abstract domain (Pietroni et al. 2010); the atlas cuts it into diamonds",
    "meshlab-trivial": "one-to-one: each triangle its own chart, packed apart",
    "fhr-param": "one-to-one, certified on every run (§4, Proposition 1; exact orient2d)",
    "fhr-atlas": "one-to-one: each patch in its own triangle of UV (the certified map)",
}


def debian_version(package):
    if package is None:
        return subprocess.run([FHR, "--version"], capture_output=True, text=True).stdout.strip()
    proc = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", package], capture_output=True, text=True)
    return "%s %s" % (package, proc.stdout.strip() if proc.returncode == 0 else "(not installed)")


def read_table(path):
    """The rows of an oracle-fuzz table: dicts with index, recipe, outcome, check, reason, distortion."""
    with open(path) as f:
        lines = f.read().splitlines()
    start = lines.index(next(line for line in lines if line.startswith("index\t"))) + 1
    rows = []
    for line in lines[start:]:
        f = line.split("\t")
        rows.append({"index": int(f[0]), "recipe": f[2], "outcome": f[3], "check": f[4], "reason": f[5],
                     "distortion": f[7]})
    return rows


def adapter_env():
    """The adapters' own time limit ends them, and the programs they start in sessions of their own,
    before oracle-fuzz's (which kills the adapter's process group only) would."""
    return dict(os.environ, FHR_PEER_TIMEOUT=str(max(OPTIONS.timeout - 15, OPTIONS.timeout / 2)))


def fuzz(program, kind, topology, family, folder, run):
    """One oracle-fuzz run of `program` over `family`; the program's own seconds summed in a log."""
    os.makedirs(folder, exist_ok=True)
    log = os.path.join(folder, "seconds-%d.txt" % run)
    if os.path.exists(log):
        os.remove(log)
    cmd = "/usr/bin/time -q -f %%e -a -o %s %s {mesh} {out}" % (shlex.quote(log), shlex.quote(os.path.join(ROOT, "peers", program)))
    table = os.path.join(folder, "table-%d.tsv" % run)
    start = time.monotonic()
    proc = subprocess.run([FHR, "oracle-fuzz", "--cmd", cmd, "--count", str(OPTIONS.count), "--seed", str(OPTIONS.seed),
                           "--family", family, "--topology", topology, "--kind", kind, "--timeout", str(OPTIONS.timeout),
                           "--faces-min", str(FACES_MIN.get(program, 0)),
                           "--keep", os.path.join(folder, "kept" if run == 1 else "kept-again"), "--table", table],
                          capture_output=True, text=True, cwd=folder, env=adapter_env())
    wall = time.monotonic() - start
    if proc.returncode not in (0, 1):
        raise SystemExit("run_campaign: oracle-fuzz failed for %s/%s: %s" % (program, family, proc.stderr.strip()))
    seconds = 0.0
    if os.path.exists(log):
        with open(log) as f:
            seconds = sum(float(x) for x in f.read().split() if re.fullmatch(r"[0-9.]+", x))
    return read_table(table), wall, seconds


def rerun(program, kind, kept, failure_kind, times):
    """Runs the program on a kept shrunk mesh `times` times; how many fail the same way. Writes rerun.sh."""
    out = "again-" + OUTPUT[kind]
    judge = {"param": "%s verify {out} --mesh smaller.off",
             "atlas": "%s verify {out} --mesh smaller.off",
             "vertex-map": "%s verify --vertex-map {out}/map.vmap --domain {out}/D.off --mesh smaller.off"}[kind] % shlex.quote(FHR)
    with open(os.path.join(kept, "rerun.sh"), "w") as f:
        f.write("#!/bin/sh\n# the program on the shrunk mesh, then the oracle on what it wrote\ncd \"$(dirname \"$0\")\"\n"
                "rm -rf {out}\n%s smaller.off {out} || exit\n%s\n".replace("{out}", out)
                % (shlex.quote(os.path.join(ROOT, "peers", program)), judge.replace("{out}", out)))
    os.chmod(os.path.join(kept, "rerun.sh"), 0o755)
    same = 0
    for _ in range(times):
        proc = subprocess.run(["sh", os.path.join(kept, "rerun.sh")], capture_output=True, text=True, env=adapter_env())
        first = re.search(r"INVALID: ((PARAM|ATLAS|VMAP)-\d+)", proc.stdout)
        outcome = first.group(1) if first else ("exit %d" % proc.returncode if proc.returncode != 0 else "valid")
        same += outcome == failure_kind or (failure_kind.startswith("exit") and outcome == failure_kind)
    return same


def classify(program, check, reason):
    if program not in PROMISES:
        return "no promise"
    flattened = check == "ATLAS-3" or (check == "ATLAS-2" and "is degenerate" in reason)
    return "broken in floating point" if flattened else "broken"


def summarize(program, rows):
    s = {"runs": len(rows), "valid": 0, "not applicable": 0, "crashes": 0, "timeouts": 0, "other exits": 0, "invalid": {},
         "classes": {}}
    l2, worst = [], []
    for r in rows:
        if r["distortion"] != "-":
            v = r["distortion"].split()
            l2.append(float(v[1]))
            worst.append(float(v[5]))
        c = r["check"]
        if r["outcome"] == "valid":
            s["valid"] += 1
        elif c == "exit 3":
            s["not applicable"] += 1
        elif c.startswith("signal") or (c.startswith("exit ") and int(c.split()[1]) >= 128 and c != "exit 124"):
            s["crashes"] += 1
        elif c in ("timeout", "exit 124"):
            s["timeouts"] += 1
        elif c.startswith("exit") or c == "no output":
            s["other exits"] += 1
        else:
            s["invalid"][c] = s["invalid"].get(c, 0) + 1
            k = classify(program, c, r["reason"])
            s["classes"][k] = s["classes"].get(k, 0) + 1
    s["l2_median"] = statistics.median(l2) if l2 else None
    s["anisotropy_worst"] = max(worst) if worst else None
    return s


def one(program, kind, topology, family):
    folder = os.path.join(OPTIONS.out, program, family)
    first, wall1, own1 = fuzz(program, kind, topology, family, folder, 1)
    second, wall2, own2 = fuzz(program, kind, topology, family, folder, 2)
    deterministic = [(r["outcome"], r["check"], r["reason"], r["distortion"]) for r in first] == \
                    [(r["outcome"], r["check"], r["reason"], r["distortion"]) for r in second]
    reproducers = []
    for r in first:
        if r["outcome"] != "FAILED" or r["check"] == "timeout":
            continue
        kept = os.path.join(folder, "kept", "mesh-%d" % r["index"])
        times = 1 if deterministic else 5
        reproducers.append({"mesh": r["index"], "check": r["check"], "reruns": times,
                            "same": rerun(program, kind, kept, r["check"], times), "folder": kept})
    return {"program": program, "family": family, "summary": summarize(program, first), "deterministic": deterministic,
            "wall": wall1 + wall2, "program_seconds": own1 + own2, "reproducers": reproducers}


def cell(s):
    invalid = ", ".join("%s %d" % kv for kv in sorted(s["invalid"].items())) or "-"
    if s["classes"]:
        invalid += " (%s)" % ", ".join("%s %d" % kv for kv in sorted(s["classes"].items()))
    fmt = lambda x: "-" if x is None else "%.3g" % x  # noqa: E731
    return "%d | %d | %d | %d | %d | %d | %s | %s | %s" % (s["runs"], s["valid"], s["not applicable"], s["crashes"], s["timeouts"],
                                                          s["other exits"], invalid, fmt(s["l2_median"]), fmt(s["anisotropy_worst"]))


def main():
    global FHR, OPTIONS
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fhr")
    parser.add_argument("out")
    parser.add_argument("--count", type=int, default=3)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--timeout", type=float, default=60)
    parser.add_argument("--programs", nargs="+")
    parser.add_argument("--families", nargs="+", default=FAMILIES)
    parser.add_argument("-j", type=int, default=os.cpu_count())
    OPTIONS = parser.parse_args()
    FHR = os.path.abspath(OPTIONS.fhr)
    OPTIONS.out = os.path.abspath(OPTIONS.out)
    programs = [p for p in PROGRAMS if not OPTIONS.programs or p[0] in OPTIONS.programs]
    if OPTIONS.programs and len(programs) != len(OPTIONS.programs):
        raise SystemExit("run_campaign: unknown program among %s (known: %s)" % (OPTIONS.programs, ", ".join(p[0] for p in PROGRAMS)))
    start = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(OPTIONS.j) as pool:
        jobs = [pool.submit(one, name, kind, topology, family) for name, kind, topology, _ in programs for family in OPTIONS.families]
        results = [j.result() for j in jobs]
    versions = {name: debian_version(package) for name, _, _, package in programs}
    lines = ["# Campaign: %s" % " ".join(shlex.quote(a) for a in sys.argv), "",
             "%d meshes per program and family (seed %d), each run twice; %.0f s wall on %d workers." %
             (OPTIONS.count, OPTIONS.seed, time.monotonic() - start, OPTIONS.j), "",
             "| program | version | family | runs | valid | n/a | crashes | timeouts | other exits | invalid (first check) "
             "| L2 median | σ₁/σ₂ worst | deterministic |", "|" + "---|" * 13]
    failed_reproducers = []
    for r in results:
        lines.append("| %s | %s | %s | %s | %s |" % (r["program"], versions[r["program"]], r["family"], cell(r["summary"]),
                                                     "yes" if r["deterministic"] else "no"))
        for rep in r["reproducers"]:
            if r["deterministic"] and rep["same"] != rep["reruns"]:
                failed_reproducers.append(rep["folder"])
    lines += ["", "| program | promise | fhr's share of the wall time | reproducers (failing the same way when re-run) |",
              "|---|---|---|---|"]
    for name, _, _, _ in programs:
        mine = [r for r in results if r["program"] == name]
        wall, own = sum(r["wall"] for r in mine), sum(r["program_seconds"] for r in mine)
        reps = [rep for r in mine for rep in r["reproducers"]]
        rate = "%d of %d re-runs" % (sum(x["same"] for x in reps), sum(x["reruns"] for x in reps)) if reps else "-"
        lines.append("| %s | %s | %.0f %% (%.1f s of %.1f s) | %s |" % (name, PROMISES.get(name, "none"),
                                                                       100 * max(wall - own, 0) / wall if wall else 0, wall - own,
                                                                       wall, rate))
    text = "\n".join(lines) + "\n"
    print(text)
    with open(os.path.join(OPTIONS.out, "campaign.md"), "w") as f:
        f.write(text)
    with open(os.path.join(OPTIONS.out, "results.json"), "w") as f:
        json.dump({"versions": versions, "results": results}, f, indent=1)
    if failed_reproducers:
        print("run_campaign: reproducers of deterministic programs that did not fail the same way again:\n  " +
              "\n  ".join(failed_reproducers), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
