#!/usr/bin/env python3
"""LIB-4 (spec/library.md): mixing up element kinds does not compile. Compiles small programs
against src/fhr/core/ids.hpp with the project's compiler (-fsyntax-only): the control (per-vertex data
indexed by a VertexId) must compile; indexing per-vertex data with a FaceId or a plain integer,
and passing a VertexId where a FaceId is meant, must not. Exit 0 when all hold.
Usage: check_types.py SRC_DIR COMPILER [ARGS...]"""
import os
import subprocess
import sys
import tempfile

src, compiler = sys.argv[1], sys.argv[2:]
prelude = '#include <fhr/core/ids.hpp>\nusing namespace fhr;\nvoid takes_face(FaceId) {}\nint main() {\n    VertexData<int> d(3, 7);\n'
cases = [
    ("control: VertexData indexed by a VertexId", True, "    return d[VertexId(1)] - 7;\n"),
    ("per-vertex data indexed by a FaceId", False, "    return d[FaceId(1)];\n"),
    ("per-vertex data indexed by a plain integer", False, "    return d[1];\n"),
    ("a VertexId passed where a FaceId is meant", False, "    takes_face(VertexId(1));\n    return 0;\n"),
]
failed = 0
with tempfile.TemporaryDirectory() as tmp:
    for name, should_compile, body in cases:
        path = os.path.join(tmp, "case.cpp")
        with open(path, "w") as f:
            f.write(prelude + body + "}\n")
        proc = subprocess.run(compiler + ["-std=c++20", "-fsyntax-only", "-I", src, path], capture_output=True, text=True)
        compiled = proc.returncode == 0
        ok = compiled == should_compile
        print("%s: %s (%s)" % ("ok" if ok else "FAILED", name, "compiles" if compiled else "does not compile"))
        if not ok:
            failed += 1
            print(proc.stderr[-2000:])
sys.exit(1 if failed else 0)
