#!/usr/bin/env python3
"""LIB-5 and LIB-6 (spec/library.md): fhr as an installed library and as a subproject.

  check_install.py SOURCE_DIR install CXX...
      Copies the source tree (the files git knows, committed or not) to a temporary folder,
      configures it with -Dtests=false -Dbench=false -Dpython=false --libdir=lib, builds it and installs it
      with `meson install --destdir` into a temporary prefix. Checks that the prefix holds exactly
      the public headers that spec/library.md lists (no other header: no detail/, app/ or render/),
      that <fhr/fhr.hpp> includes every one of them but <fhr/testing/rapidcheck.hpp>, and libfhr,
      fhr.pc and the CMake package files. Then builds examples/parameterize.cpp,
      examples/verify.cpp and every ```cpp snippet of README.md (its #include lines first, the rest
      as the body of main) with nothing but the compiler and
      `pkg-config --define-prefix --cflags --libs fhr` against that prefix, and runs the examples on the
      fandisk: parameterize prints, for every vertex of T, the domain face and β that the
      reference run of `fhr run` wrote for it (reference_outputs/fandisk/param.fhrp.gz); verify
      says `valid` for that file and `INVALID PARAM-5` for a copy with one β made 1.5. Finally a
      CMake project that calls find_package(fhr) builds examples/verify.cpp and gives the same
      two verdicts.
  check_install.py SOURCE_DIR subproject
      A meson project with fhr in subprojects/fhr, using dependency('fhr'), builds
      examples/verify.cpp and gives the same two verdicts.

The fandisk is read from FHR_CGAL_MESHES or out/cgal-data/data/meshes, as in the reference tests.
Exit 0 when everything holds."""
import gzip
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from fresh_copy import fresh_copy  # noqa: E402

source, mode = Path(sys.argv[1]).resolve(), sys.argv[2]
cxx = sys.argv[3:]
meshes = Path(os.environ.get("FHR_CGAL_MESHES", source / "out/cgal-data/data/meshes"))
fandisk = meshes / "fandisk.off"
if not fandisk.exists():
    sys.exit("fandisk.off not found in %s (./run fetches libcgal-demo's meshes; FHR_CGAL_MESHES)" % meshes)


def run(cmd, **kw):
    proc = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, cwd=tmp, **kw)
    if proc.returncode != 0:
        sys.exit("failed (%d): %s\n%s%s" % (proc.returncode, " ".join(map(str, cmd)), proc.stdout[-3000:],
                                          proc.stderr[-3000:]))
    return proc.stdout


def reference_param(tmp):
    """reference_outputs/fandisk/param.fhrp, and a copy with one β out of [0, 1] (PARAM-5)."""
    text = gzip.decompress((source / "reference_outputs/fandisk/param.fhrp.gz").read_bytes()).decode()
    good = tmp / "good.fhrp"
    good.write_text(text)
    lines = text.split("\n")
    last = lines[-2].split()  # the last face: a b c patch β... (spec/param.md)
    assert len(last) == 13, "unexpected face line: " + lines[-2]
    last[4] = "1.5"
    lines[-2] = " ".join(last)
    bad = tmp / "bad.fhrp"
    bad.write_text("\n".join(lines))
    return good, bad, text


def public_headers():
    """The list of spec/library.md after its `<!-- public headers -->` marker."""
    text = (source / "spec/library.md").read_text(encoding="utf-8")
    marker = text.find("<!-- public headers -->")
    if marker < 0:
        sys.exit("spec/library.md has no list of public headers (its <!-- public headers --> marker)")
    listed = []
    for line in text[marker:].splitlines()[1:]:
        m = re.fullmatch(r"\s*- `(fhr/[^`]+\.hpp)`", line)
        if not m:
            break
        listed.append(m.group(1))
    if not listed:
        sys.exit("spec/library.md lists no public header after its marker")
    return sorted(listed)


def readme_programs(tmp):
    """Every ```cpp block of README.md as a program: its #include lines, then the rest in main()."""
    text = (source / "README.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```cpp\n(.*?)```", text, re.S)
    if not blocks:
        sys.exit("README.md has no ```cpp snippet")
    programs = []
    for i, block in enumerate(blocks):
        lines = block.splitlines()
        includes = [l for l in lines if l.startswith("#include")]
        body = [l for l in lines if not l.startswith("#include")]
        program = tmp / ("readme_snippet_%d.cpp" % i)
        program.write_text("\n".join(includes) + "\n\nint main() {\n" + "\n".join(body) + "\n    return 0;\n}\n")
        programs.append(program)
    return programs


def check_verdicts(verify_program, good, bad, who):
    ok = subprocess.run([str(verify_program), str(good), str(fandisk)], capture_output=True, text=True)
    if ok.returncode != 0 or ok.stdout.strip() != "valid":
        sys.exit("%s: the reference parameterization is not 'valid' (exit %d): %s%s" % (who, ok.returncode, ok.stdout,
                                                                                     ok.stderr))
    broken = subprocess.run([str(verify_program), str(bad), str(fandisk)], capture_output=True, text=True)
    if broken.returncode != 1 or not broken.stdout.startswith("INVALID PARAM-5: "):
        sys.exit("%s: a β of 1.5 is not 'INVALID PARAM-5' (exit %d): %s%s" % (who, broken.returncode, broken.stdout,
                                                                            broken.stderr))
    print("%s: valid, and %s" % (who, broken.stdout.strip()))


def check_parameterize(program, reference_text):
    """Every vertex of T gets a (domain face, β) that the reference file gives that vertex."""
    out = subprocess.run([str(program), str(fandisk), "114"], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit("parameterize fandisk 114 failed (exit %d): %s" % (out.returncode, out.stderr))
    lines = reference_text.split("\n")
    n_domain_vertices, n_domain_faces = int(lines[1].split()[1]), 0
    # spec/param.md: header, "domain_vertices N", N lines, "domain_faces M", M lines,
    # "surface_vertices P", P lines, "surface_faces Q", Q lines.
    i = 2 + n_domain_vertices
    n_domain_faces = int(lines[i].split()[1])
    i += 1 + n_domain_faces
    n_surface_vertices = int(lines[i].split()[1])
    i += 1 + n_surface_vertices
    n_faces = int(lines[i].split()[1])
    allowed = {}
    for line in lines[i + 1:i + 1 + n_faces]:
        t = line.split()
        for k in range(3):
            allowed.setdefault(int(t[k]), set()).add((int(t[3]),) + tuple(float(x) for x in t[4 + 3 * k:7 + 3 * k]))
    rows = [r.split() for r in out.stdout.splitlines()]
    n_vertices = int(open(fandisk).read().split()[1])
    if len(rows) != n_vertices:
        sys.exit("parameterize printed %d lines for %d vertices" % (len(rows), n_vertices))
    for r in rows:
        v, entry = int(r[0]), (int(r[1]),) + tuple(float(x) for x in r[2:5])
        if entry not in allowed.get(v, ()):
            sys.exit("vertex %d: parameterize gives %s, the reference run one of %s" % (v, entry, allowed.get(v)))
    print("parameterize: the %d vertices of the fandisk get the reference run's domain faces and β" % n_vertices)


with tempfile.TemporaryDirectory() as tmp_name:
    tmp = Path(tmp_name)  # also the commands' working folder (meson and cmake write scratch files there)
    good, bad, reference_text = reference_param(tmp)
    if mode == "install":
        copy, dest = tmp / "fhr", tmp / "dest"
        fresh_copy(copy)
        run(["meson", "setup", copy / "build", copy, "-Dtests=false", "-Dbench=false", "-Dpython=false",
             "--prefix=/usr/local", "--libdir=lib"])
        run(["meson", "compile", "-C", copy / "build"])
        run(["meson", "install", "-C", copy / "build", "--destdir", dest])
        prefix = dest / "usr/local"
        headers = sorted(str(p.relative_to(prefix / "include")) for p in (prefix / "include").rglob("*.hpp"))
        listed = public_headers()
        missing = [h for h in listed if h not in headers]
        unlisted = [h for h in headers if h not in listed]
        if missing or unlisted:
            sys.exit("installed headers against spec/library.md's list: missing %s, not listed %s" % (missing, unlisted))
        umbrella = re.findall(r"#include <(fhr/[^>]+)>", (prefix / "include/fhr/fhr.hpp").read_text(encoding="utf-8"))
        expected = [h for h in listed if h not in ("fhr/fhr.hpp", "fhr/testing/rapidcheck.hpp")]
        if sorted(umbrella) != expected:
            sys.exit("<fhr/fhr.hpp> and the public list differ by %s (it must include every public header but "
                     "itself and the RapidCheck one)" % sorted(set(umbrella) ^ set(expected)))
        for f in ["lib/libfhr.a", "lib/pkgconfig/fhr.pc", "lib/cmake/fhr/fhrConfig.cmake",
                  "lib/cmake/fhr/fhrConfigVersion.cmake"]:
            if not (prefix / f).exists():
                sys.exit("not installed: " + f)
        print("installed: the %d public headers of spec/library.md and no other, fhr.hpp including all but "
              "the RapidCheck one, libfhr.a, fhr.pc, fhrConfig.cmake" % len(headers))
        # CLI-RUN-8: the copy holds no web/node_modules, so this fhr has no page: --html exits 2 at
        # once, saying how to build it, and writes nothing.
        page_out = tmp / "page"
        refused = subprocess.run([prefix / "bin/fhr", "run", fandisk, "--faces", "114", "--html", "--out", page_out],
                                 capture_output=True, text=True)
        if refused.returncode != 2 or "-Dpage=enabled" not in refused.stderr or page_out.exists():
            sys.exit("fhr built without its page: `fhr run --html` gave exit %d, %r, and %s" % (
                refused.returncode, refused.stderr.strip(), "wrote " + str(page_out) if page_out.exists() else "no output"))
        print("without its page: fhr run --html exits 2:", refused.stderr.strip())

        env = dict(os.environ, PKG_CONFIG_PATH=str(prefix / "lib/pkgconfig"))
        flags = run(["pkg-config", "--define-prefix", "--cflags", "--libs", "fhr"], env=env).split()
        print("pkg-config --cflags --libs fhr:", " ".join(flags))
        for example in ["parameterize", "verify"]:
            run(cxx + ["-std=c++20", "-O2", copy / "examples" / (example + ".cpp"), "-o", tmp / example] + flags)
        check_parameterize(tmp / "parameterize", reference_text)
        snippets = readme_programs(tmp)
        for program in snippets:
            run(cxx + ["-std=c++20", "-O1", program, "-o", program.with_suffix("")] + flags)
        print("README.md: its %d C++ snippet(s) compile and link against the installed library" % len(snippets))
        check_verdicts(tmp / "verify", good, bad, "verify (pkg-config)")

        cmake_project = tmp / "cmake_consumer"
        cmake_project.mkdir()
        shutil.copy2(copy / "examples/verify.cpp", cmake_project)
        (cmake_project / "CMakeLists.txt").write_text(
            "cmake_minimum_required(VERSION 3.16)\nproject(consumer CXX)\nfind_package(fhr 0.1 REQUIRED)\n"
            "add_executable(verify verify.cpp)\ntarget_link_libraries(verify PRIVATE fhr::fhr)\n")
        run(["cmake", "-S", cmake_project, "-B", cmake_project / "build", "-DCMAKE_BUILD_TYPE=Release",
             "-DCMAKE_PREFIX_PATH=" + str(prefix), "-DCMAKE_CXX_COMPILER=" + cxx[-1]] +
            (["-DCMAKE_CXX_COMPILER_LAUNCHER=" + cxx[0]] if len(cxx) > 1 else []))
        run(["cmake", "--build", cmake_project / "build"])
        check_verdicts(cmake_project / "build/verify", good, bad, "verify (CMake find_package)")
    elif mode == "subproject":
        consumer = tmp / "consumer"
        fresh_copy(consumer / "subprojects" / "fhr")
        shutil.copy2(source / "examples/verify.cpp", consumer)
        (consumer / "meson.build").write_text(
            "project('consumer', 'cpp', default_options : ['cpp_std=c++20'])\n"
            "fhr = dependency('fhr', fallback : 'fhr')\n"
            "executable('verify', 'verify.cpp', dependencies : fhr)\n")
        run(["meson", "setup", consumer / "build", consumer, "--wrap-mode=forcefallback", "--buildtype=release"])
        run(["meson", "compile", "-C", consumer / "build", "verify"])
        check_verdicts(consumer / "build/verify", good, bad, "verify (meson subproject)")
    else:
        sys.exit("unknown mode " + mode)
