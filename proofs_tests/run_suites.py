#!/usr/bin/env python3
"""Runs every test registered in meson (meson introspect --tests) and prints one closing line,
`N passed, N failed`, counting Catch2 test cases (each suite writes Catch2's XML report), pytest's
cases (a test whose environment names FHR_JUNIT_XML, pytest's JUnit report) and any other test as
one case judged by its exit code. Two suites run at a time (2 cores). A Catch2 case that ran
nothing because an optional mesh of ../shared/meshes is absent (its warning starts with
"optional data absent: ") is counted as skipped, never as passed, and listed before the last line.
Usage: run_suites.py BUILD_DIR [--timeout-multiplier F] [--except PREFIX...]
  --timeout-multiplier F: F times each test's time limit (./run coverage: its instrumented build
  is slower); --except: leave out the tests whose names start with a PREFIX (./run coverage leaves
  out library-*, which builds copies of fhr elsewhere)"""
import concurrent.futures
import json
import os
import subprocess
import sys
import time
import xml.etree.ElementTree as ET

build = os.path.abspath(sys.argv[1])
options = sys.argv[2:]
multiplier = 1.0
if options[:1] == ["--timeout-multiplier"]:
    multiplier, options = float(options[1]), options[2:]
left_out = tuple(options[1:]) if options[:1] == ["--except"] else ()
tests = [t for t in json.loads(subprocess.run(["meson", "introspect", build, "--tests"], check=True,
                                              capture_output=True, text=True).stdout)
         if not (left_out and t["name"].startswith(left_out))]
results_dir = os.path.join(build, "test-results")
OPTIONAL_DATA_ABSENT = "optional data absent: "  # support/test_support.hpp's optional_data_absent
os.makedirs(results_dir, exist_ok=True)


def run(test):
    name, cmd = test["name"], list(test["cmd"])
    env = dict(os.environ, **(test.get("env") or {}))
    is_catch = os.path.basename(cmd[0]).startswith("test_")
    junit = (test.get("env") or {}).get("FHR_JUNIT_XML")
    if junit and os.path.exists(junit):
        os.remove(junit)  # never count a report from an earlier run
    xml = os.path.join(results_dir, name + ".xml")
    if is_catch:
        cmd += ["-r", "xml", "-o", xml]
    start = time.monotonic()
    try:
        proc = subprocess.run(cmd, env=env, cwd=test.get("workdir") or build, capture_output=True,
                              text=True, errors="replace", timeout=multiplier * (test.get("timeout") or 600))
        code, output = proc.returncode, proc.stdout + proc.stderr
    except subprocess.TimeoutExpired:
        code, output = -1, "timed out"
    seconds = time.monotonic() - start
    if junit:  # pytest: one count per test case (a skipped case counts as failed: none is expected)
        try:
            suite = ET.parse(junit).getroot()
            suite = suite if suite.tag == "testsuite" else suite.find("testsuite")
            total = int(suite.get("tests"))
            bad = int(suite.get("failures")) + int(suite.get("errors")) + int(suite.get("skipped"))
        except (ET.ParseError, FileNotFoundError, AttributeError, TypeError):
            return name, seconds, 0, 1, [(name, "no JUnit report (exit %d)\n%s" % (code, output[-4000:]))], []
        if code != 0 and bad == 0:
            bad = 1
        return name, seconds, total - min(bad, total), bad, [] if bad == 0 else [(name, output[-4000:])], []
    if not is_catch:
        ok = code == 0
        return name, seconds, int(ok), int(not ok), [] if ok else [(name, output[-4000:])], []
    try:
        root = ET.parse(xml).getroot()
    except (ET.ParseError, FileNotFoundError):
        return name, seconds, 0, 1, [(name, "no Catch2 report (exit %d)\n%s" % (code, output[-4000:]))], []
    failures = []
    for case in root.iter("TestCase"):
        result = case.find("OverallResult")
        if result is not None and result.get("success") != "true":
            details = []
            for expr in case.iter("Expression"):
                if expr.get("success") == "false":
                    orig = (expr.findtext("Original") or "").strip()
                    exp = (expr.findtext("Expanded") or "").strip()
                    details.append("%s:%s  %s  (%s)" % (expr.get("filename"), expr.get("line"), orig, exp))
            for tag in ("Exception", "FatalErrorCondition", "Failure"):
                for el in case.iter(tag):
                    details.append("%s:%s  %s: %s" % (el.get("filename"), el.get("line"), tag, (el.text or "").strip()))
            failures.append((name + ": " + case.get("name"), "\n".join(details[:10])))
    totals = root.find("OverallResultsCases")
    passed = int(totals.get("successes")) if totals is not None else 0
    failed = int(totals.get("failures")) if totals is not None else 1
    if code != 0 and failed == 0:  # crashed after the report, or failed outside any test case
        failed, failures = 1, [(name, "exit %d\n%s" % (code, output[-4000:]))]
    # A case that ran nothing because an optional mesh of ../shared/meshes is absent says so with a
    # warning (FHR_SHARED_MESH_OR_SKIP, support/test_support.hpp): skipped, not passed.
    skipped = [case.get("name") for case in root.iter("TestCase")
               if (case.find("OverallResult") is None or case.find("OverallResult").get("success") == "true")
               and any((w.text or "").strip().startswith(OPTIONAL_DATA_ABSENT) for w in case.iter("Warning"))]
    return name, seconds, passed - len(skipped), failed, failures, skipped


passed = failed = 0
all_failures, all_skipped = [], []
with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    for name, seconds, p, f, fails, skips in pool.map(run, tests):
        print("%-20s %4d passed, %d failed%s  (%.1f s)" % (name, p, f, ", %d skipped" % len(skips) if skips else "", seconds),
              flush=True)
        passed, failed = passed + p, failed + f
        all_failures += fails
        all_skipped += ["%s: %s" % (name, case) for case in skips]
for title, details in all_failures:
    print("\nFAILED %s\n%s" % (title, details))
if all_skipped:
    print("\n%d skipped (optional data absent: ../shared/meshes):\n  %s" % (len(all_skipped), "\n  ".join(all_skipped)))
print("%d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
