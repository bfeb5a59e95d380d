#!/usr/bin/env python3
"""No function of the library is long: each function of src/fhr is at most 100 lines, and each of
the code that keeps the domain (src/fhr/partition/keep.cpp, region.cpp, restricted.cpp, where the
algorithm is hardest to follow) at most 60, measured as Universal Ctags measures a function's
extent (from its first line to its closing brace; a lambda counts in the function around it).
A short function can be read as one step of the pseudocode its file opens with.
Usage: check_function_size.py SOURCE_DIR  (exit 0 when every function is within its limit)"""
import os
import subprocess
import sys

LIMIT = 100
KEEP_LIMIT = 60
KEEP_FILES = {"src/fhr/partition/keep.cpp", "src/fhr/partition/region.cpp", "src/fhr/partition/restricted.cpp"}

root = os.path.abspath(sys.argv[1])
ctags = next((c for c in ("ctags-universal", "ctags") if subprocess.run(["which", c], capture_output=True).returncode == 0), None)
if ctags is None:
    sys.exit("check_function_size: Universal Ctags is not installed (Debian's universal-ctags; ./run installs it)")
version = subprocess.run([ctags, "--version"], capture_output=True, text=True).stdout
if "Universal Ctags" not in version:
    sys.exit("check_function_size: %s is not Universal Ctags: %s" % (ctags, version.splitlines()[0] if version else "?"))
out = subprocess.run([ctags, "-R", "--languages=C++", "--kinds-C++=f", "--fields=+ne", "-x",
                      "--_xformat=%N\t%F\t%n\t%e", "src/fhr"], cwd=root, capture_output=True, text=True, check=True).stdout
functions, too_long = 0, []
for line in out.splitlines():
    name, path, first, last = line.split("\t")
    if not last:
        continue  # a declaration without a body
    functions += 1
    length = int(last) - int(first) + 1
    limit = KEEP_LIMIT if path in KEEP_FILES else LIMIT
    if length > limit:
        too_long.append("%s:%s %s: %d lines (at most %d)" % (path, first, name, length, limit))
if functions < 500:
    sys.exit("check_function_size: only %d functions found in src/fhr: ctags did not read the sources" % functions)
if too_long:
    sys.exit("check_function_size: %d functions too long:\n  %s" % (len(too_long), "\n  ".join(sorted(too_long))))
print("check_function_size: %d functions of src/fhr, none over %d lines, none of the code keeping the domain over %d"
      % (functions, LIMIT, KEEP_LIMIT))
