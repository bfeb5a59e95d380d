#!/usr/bin/env python3
"""LIB-4 (spec/library.md): mixing up element kinds, or the elements of meshes that meet, does not
compile. Compiles small programs against src/fhr/core/trimesh.hpp with the project's compiler
(-fsyntax-only): the controls (per-vertex data indexed by a VertexId; a face of D named as a face
of D's own TriMesh by an explicit conversion; per-face data of D sized from D's mesh) must compile;
indexing per-vertex data with a FaceId or a plain integer, passing a VertexId where a FaceId is
meant, a face of D (DFaceId) where a face of T′ or T is meant or the other way round, per-edge
data of D indexed by a TriMesh's EdgeId, and per-face data of the final T′ indexed by a face of D,
must not. Exit 0 when all hold.
Usage: check_types.py SRC_DIR COMPILER [ARGS...]"""
import os
import subprocess
import sys
import tempfile

src, compiler = sys.argv[1], sys.argv[2:]
eigen = subprocess.run(["pkg-config", "--cflags", "eigen3"], capture_output=True, text=True, check=True).stdout.split()
prelude = ('#include <fhr/core/trimesh.hpp>\nusing namespace fhr;\nvoid takes_face(FaceId) {}\n'
           'void takes_d_face(DFaceId) {}\nint main() {\n    VertexData<int> d(3, 7);\n'
           '    IdVector<DEdgeId, int> d_edges(3, 1);\n    IdVector<RefinedFaceId, DFaceId> face_patch(3, DFaceId(0));\n')
cases = [
    ("control: VertexData indexed by a VertexId", True, "    return d[VertexId(1)] - 7;\n"),
    ("per-vertex data indexed by a FaceId", False, "    return d[FaceId(1)];\n"),
    ("per-vertex data indexed by a plain integer", False, "    return d[1];\n"),
    ("a VertexId passed where a FaceId is meant", False, "    takes_face(VertexId(1));\n    return 0;\n"),
    ("control: a face of D named as a face of its TriMesh, explicitly", True,
     "    takes_face(FaceId(face_patch[RefinedFaceId(0)]));\n    takes_d_face(DFaceId(FaceId(2)));\n    return 0;\n"),
    ("control: per-face data of D sized from D's mesh", True,
     "    const TriMesh D = TriMesh::from_triangles({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},\n"
     "                                              std::vector<Triangle>{{0, 1, 2}, {0, 2, 1}});\n"
     "    const IdVector<DFaceId, int> per_face(D, 0);\n    return per_face.fits(D) && per_face.size() == 2 ? 0 : 1;\n"),
    ("a face of D passed where a face of a TriMesh is meant", False, "    takes_face(DFaceId(1));\n    return 0;\n"),
    ("a face of a TriMesh passed where a face of D is meant", False, "    takes_d_face(FaceId(1));\n    return 0;\n"),
    ("a face of D assigned to a face of T", False, "    TFaceId t = DFaceId(1);\n    return t.valid();\n"),
    ("per-edge data of D indexed by a TriMesh's EdgeId", False, "    return d_edges[EdgeId(1)];\n"),
    ("per-face data of the final T' indexed by a face of D", False,
     "    return face_patch[DFaceId(1)].valid();\n"),
]
failed = 0
with tempfile.TemporaryDirectory() as tmp:
    for name, should_compile, body in cases:
        path = os.path.join(tmp, "case.cpp")
        with open(path, "w") as f:
            f.write(prelude + body + "}\n")
        proc = subprocess.run(compiler + ["-std=c++20", "-fsyntax-only", "-I", src] + eigen + [path],
                              capture_output=True, text=True)
        compiled = proc.returncode == 0
        # A refusal counts only as a type error in the case's own line, never a missing header.
        ok = compiled == should_compile and (compiled or ("fatal error" not in proc.stderr and "case.cpp" in proc.stderr))
        print("%s: %s (%s)" % ("ok" if ok else "FAILED", name, "compiles" if compiled else "does not compile"))
        if not ok:
            failed += 1
            print(proc.stderr[-2000:])
sys.exit(1 if failed else 0)
