#!/usr/bin/env python3
"""FHR bench -- fhr.parameterize from Python, against pipeline::run from C++ (bench/bench_run.cpp;
the goal: within 10 %). The arrays are read once, outside the timing; the call
includes their validation, as every fhr call does.
Usage: bench_python.py MESH FACES RUNS  (with the package on PYTHONPATH). Prints the median and
minimum wall time of RUNS calls."""
import statistics
import sys
import time

import fhr

mesh, faces, runs = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
V, F = fhr.read_mesh(mesh)
ms, certified = [], True
for _ in range(runs):
    start = time.perf_counter()
    certified = fhr.parameterize(V, F, faces=faces).certified and certified
    ms.append(1e3 * (time.perf_counter() - start))
print("fhr.parameterize median %.1f ms, min %.1f ms (%d runs, %s)" % (statistics.median(ms), min(ms), runs,
                                                                       "certified" if certified else "NOT certified"))
sys.exit(0 if certified else 1)
