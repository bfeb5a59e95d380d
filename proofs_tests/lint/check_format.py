#!/usr/bin/env python3
"""Every C++ file of the repository is as .clang-format (120 columns) lays it out: clang-format
--dry-run -Werror on each tracked .cpp and .hpp finds nothing to change. Debian's clang-format
(the version ./run installs) decides; `git ls-files '*.cpp' '*.hpp' | xargs clang-format -i`
applies it. Usage: check_format.py SOURCE_DIR (exit 0 when every file is formatted)"""
import shutil
import subprocess
import sys

root = sys.argv[1]
if shutil.which("clang-format") is None:
    sys.exit("check_format: clang-format is not installed (Debian's clang-format; ./run installs it)")
files = subprocess.run(["git", "-C", root, "ls-files", "*.cpp", "*.hpp"], capture_output=True, text=True,
                       check=True).stdout.split()
if len(files) < 100:
    sys.exit("check_format: only %d C++ files tracked under %s" % (len(files), root))
r = subprocess.run(["clang-format", "--dry-run", "-Werror", *files], cwd=root, capture_output=True, text=True)
if r.returncode != 0:
    unformatted = sorted({line.split(":")[0] for line in r.stderr.splitlines() if ": error:" in line})
    sys.exit("check_format: %d files are not as .clang-format lays them out (clang-format -i them):\n  %s"
             % (len(unformatted), "\n  ".join(unformatted) or r.stderr[-2000:]))
print("check_format: %d C++ files as .clang-format lays them out" % len(files))
