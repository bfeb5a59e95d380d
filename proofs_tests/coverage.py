#!/usr/bin/env python3
"""`./run coverage`: line and branch coverage of src/ by the test suites, per folder
(paper_notes/testing.md).

Runs every suite of BUILD_DIR (a build with -Db_coverage=true, see ./run) through run_suites.py,
after clearing the counters of any earlier run, with 4 times the usual time limits (the build is
instrumented and barely optimized); the library-* checks are left out, since they build copies
of fhr elsewhere and add no counts here. gcovr then reads the counters of src/ and
writes an HTML report (OUT_DIR/index.html, one page per file) and a table per folder of src/fhr
(and src/cli, src/python): lines and branches covered. Printed, and written to OUT_DIR/summary.md.

Branches are gcov's (each outcome of each condition, `&&` and `||` counted per operand), without
the branches that only the compiler's exception unwinding takes (--exclude-throw-branches) and
those on lines without code (--exclude-unreachable-branches), and the lines that only open a class
(`struct Certificate {`): gcov puts there the branches of the compiler's implicit members (copies,
destructors, their inlined std::vector and std::string code), which no condition of ours decides.

Usage: coverage.py BUILD_DIR OUT_DIR"""
import json
import os
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLASS_OPENING = r"^\s*(struct|class)\s+\w+[^;]*\{\s*$"
build, out = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
os.makedirs(out, exist_ok=True)

for folder, _, files in os.walk(build):
    for name in files:
        if name.endswith(".gcda"):
            os.remove(os.path.join(folder, name))
tests = subprocess.run([sys.executable, os.path.join(root, "proofs_tests", "run_suites.py"), build,
                        "--timeout-multiplier", "4", "--except", "library-"])

summary_json = os.path.join(out, "summary.json")
subprocess.run(["gcovr", "--root", root, "--object-directory", build, "--filter", os.path.join(root, "src") + "/",
                "--exclude-throw-branches", "--exclude-unreachable-branches",
                "--exclude-lines-by-pattern", CLASS_OPENING, "-j", "2",
                "--html-details", os.path.join(out, "index.html"), "--html-title", "fhr: coverage of src/ by ./run test",
                "--json-summary", summary_json], check=True, cwd=root, stdout=subprocess.DEVNULL)

per_folder = {}
for f in json.load(open(summary_json))["files"]:
    parts = f["filename"].split("/")
    name = "/".join(parts[:3]) if parts[:2] == ["src", "fhr"] and len(parts) > 3 else "/".join(parts[:2])
    acc = per_folder.setdefault(name, [0, 0, 0, 0])
    for i, key in enumerate(("line_covered", "line_total", "branch_covered", "branch_total")):
        acc[i] += f[key]


def percent(covered, total):
    return "%.1f %%" % (100.0 * covered / total) if total else "-"


rows = ["| folder | lines covered | line % | branches covered | branch % |", "|---|---|---|---|---|"]
totals = [0, 0, 0, 0]
for name in sorted(per_folder):
    lc, lt, bc, bt = per_folder[name]
    totals = [a + b for a, b in zip(totals, per_folder[name])]
    rows.append("| %s | %d / %d | %s | %d / %d | %s |" % (name, lc, lt, percent(lc, lt), bc, bt, percent(bc, bt)))
lc, lt, bc, bt = totals
rows.append("| all of src/ | %d / %d | %s | %d / %d | %s |" % (lc, lt, percent(lc, lt), bc, bt, percent(bc, bt)))
text = "\n".join(rows) + "\n"
with open(os.path.join(out, "summary.md"), "w") as f:
    f.write(text)
print("\n" + text + "\nHTML report: %s" % os.path.join(out, "index.html"))
if tests.returncode != 0:
    sys.exit("some tests failed (above): the coverage counts what ran")
