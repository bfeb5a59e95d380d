#!/usr/bin/env python3
"""LIB-1 (spec/library.md): with -Dtests=false -Dbench=false, configuring fhr needs
only the library's own dependencies. Configures SOURCE_DIR in a fresh temporary build folder and
checks that `meson introspect --dependencies` names none of CGAL, Catch2, RapidCheck and
GeographicLib, and that no test or benchmark is defined. Exit 0 when all hold.
Usage: check_configure.py SOURCE_DIR"""
import json
import subprocess
import sys
import tempfile

source = sys.argv[1]
with tempfile.TemporaryDirectory() as build:
    setup = subprocess.run(["meson", "setup", build, source, "-Dtests=false", "-Dbench=false"],
                           capture_output=True, text=True)
    if setup.returncode != 0:
        sys.exit("meson setup -Dtests=false -Dbench=false failed:\n" + setup.stdout[-3000:] + setup.stderr[-3000:])
    deps = json.loads(subprocess.run(["meson", "introspect", build, "--dependencies"], check=True,
                                     capture_output=True, text=True).stdout)
    names = sorted({d["name"].lower() for d in deps})
    forbidden = [n for n in names if any(f in n for f in ("cgal", "catch", "rapidcheck", "geographiclib"))]
    tests = json.loads(subprocess.run(["meson", "introspect", build, "--tests"], check=True,
                                      capture_output=True, text=True).stdout)
    print("dependencies:", ", ".join(names))
    if forbidden:
        sys.exit("the library's configuration needs test or benchmark dependencies: " + ", ".join(forbidden))
    if tests:
        sys.exit("tests are defined although -Dtests=false: " + ", ".join(t["name"] for t in tests))
print("LIB-1: configuring without tests and benchmarks needs none of CGAL, Catch2, RapidCheck, GeographicLib")
