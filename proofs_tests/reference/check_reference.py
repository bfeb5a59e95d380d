#!/usr/bin/env python3
"""Reference outputs of the paper's examples (§6: the fandisk of Figs. 6-9, and a small generated
genus-1 mesh), regenerated with the built `fhr` and compared with reference_outputs/.

  check_reference.py FHR fandisk|genus1   run the case (CASES below) into a temporary folder and
                                          compare it with reference_outputs/CASE/; exit 1 on a difference
  check_reference.py FHR verify           `fhr verify --mesh --paper` on each committed exchange file (PARAM-1..11)
  check_reference.py FHR --regenerate     rewrite reference_outputs/{fandisk,genus1}/ from fresh runs

What is compared, and the reason of every tolerance in TOLERANCES, PNG_* and SVG_*:
reference_outputs/README.md. Timings are never compared (timings.json is not kept)."""
import gzip
import json
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
REF = ROOT / "reference_outputs"
MESHES = Path(os.environ.get("FHR_CGAL_MESHES", ROOT / "out/cgal-data/data/meshes"))
WAVELETS = ["--levels", "3", "--keep", "5,20", "--figures"]
PAPER_MAP = ["--map", "paper"]  # the paper reproduction: its §4 map exactly (spec/cli.md CLI-RUN-9)
CASES = {  # the input mesh, how it is made (None: from libcgal-demo), the size of D
    "fandisk": {"mesh": "fandisk.off", "generate": None, "faces": "114"},
    "genus1": {"mesh": "genus1.off", "faces": "48",
               "generate": ["--genus", "1", "--faces", "1000", "--seed", "8", "--noise", "0.1"]},
}
GZIP_ABOVE = 200_000  # bytes: param.fhrp is kept gzip-compressed above this size

# report.json: integers, booleans and strings exactly, except the keys here; other reals within
# 1e-9 relative. ("rel", r): |new − ref| ≤ r·|ref|; ("diag", a): ≤ a · T's bounding-box diagonal;
# ("abs", a): ≤ a; ("below", a): the new value alone is ≤ a (rounding noise, not a result).
TOLERANCES = {
    "windows_created": ("rel", 0.05),
    "total_length": ("rel", 1e-9),
    "min_image_angle_degrees": ("rel", 1e-3),
    "hausdorff": ("diag", 1e-4),
    "hausdorff_upper_bound": ("diag", 1e-4),
    "hausdorff_relative_to_bbox_diagonal": ("abs", 1e-4),
    "l2_error": ("rel", 1e-6),
    "reconstruction_max_error": ("below", 1e-12),
    "reconstruction_max_error_relative": ("below", 1e-12),
}
DEFAULT_REAL = ("rel", 1e-9)
PARAM_POSITION = 1e-9  # · diagonal: T′'s vertex coordinates (PARAM-11's tolerance)
PARAM_BETA = 1e-9      # absolute: every β (PARAM-10's tolerance)
PNG_LEVELS = 2         # a pixel differs when a channel differs by more than this many levels
PNG_FRACTION = 0.005   # at most this fraction of the pixels may differ
SVG_COORDINATE = 0.011  # attribute numbers (two decimals): one unit of the last place, plus rounding


def run(cmd, cwd=None):
    proc = subprocess.run([str(c) for c in cmd], cwd=cwd, capture_output=True, text=True)
    if proc.returncode != 0:
        raise SystemExit("%s: exit %d\n%s%s" % (" ".join(map(str, cmd)), proc.returncode, proc.stdout, proc.stderr))
    return proc.stdout


def produce(fhr, name, work):
    """Runs case `name` in `work`; returns (output folder, input mesh). The mesh is given by its
    file name from its own folder, so report.json's input.path is the same on every machine."""
    case = CASES[name]
    if case["generate"]:
        mesh = work / case["mesh"]
        run([fhr, "generate", *case["generate"], "--out", mesh])
    else:
        mesh = MESHES / case["mesh"]
        if not mesh.exists():
            raise SystemExit("%s is missing: run ./run demo to extract libcgal-demo's meshes" % mesh)
    out = work / "out"
    run([fhr, "run", mesh.name, "--faces", case["faces"], *WAVELETS, *PAPER_MAP, "--out", out], cwd=mesh.parent)
    return out, mesh


def diagonal(fhr, mesh):
    return json.loads(run([fhr, "info", mesh, "--json"]))["bounding_box"]["diagonal"]


def compare_report(ref, new, diag, path="report.json"):
    """Every difference between two parsed report.json trees beyond TOLERANCES."""
    if isinstance(ref, dict) and isinstance(new, dict):
        if list(ref) != list(new):
            return ["%s: keys %s, reference %s" % (path, list(new), list(ref))]
        return [e for k in ref for e in compare_report(ref[k], new[k], diag, path + "." + k)]
    if isinstance(ref, list) and isinstance(new, list):
        if len(ref) != len(new):
            return ["%s: %d items, reference %d" % (path, len(new), len(ref))]
        return [e for i, (r, n) in enumerate(zip(ref, new)) for e in compare_report(r, n, diag, "%s[%d]" % (path, i))]
    key = path.rsplit(".", 1)[-1]
    numbers = all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in (ref, new))
    if not numbers or (isinstance(ref, int) and isinstance(new, int) and key not in TOLERANCES):
        return [] if ref == new else ["%s: %r, reference %r" % (path, new, ref)]
    kind, tol = TOLERANCES.get(key, DEFAULT_REAL)
    bound = {"rel": tol * abs(ref), "diag": tol * diag, "abs": tol}.get(kind)
    ok = new <= tol if kind == "below" else abs(new - ref) <= bound
    return [] if ok else ["%s: %r, reference %r (tolerance %s %g)" % (path, new, ref, kind, tol)]


def param_sections(text):
    """The four sections of a `fhr-param 1` file (spec/param.md) as token lists."""
    tokens = text.split()
    assert tokens[:2] == ["fhr-param", "1"], "not a fhr-param 1 file"
    sections, at = {}, 2
    for name, width in (("domain_vertices", 3), ("domain_faces", 3), ("surface_vertices", 3), ("surface_faces", 13)):
        assert tokens[at] == name, "expected %s" % name
        count = int(tokens[at + 1])
        sections[name] = [tokens[at + 2 + width * i: at + 2 + width * (i + 1)] for i in range(count)]
        at += 2 + width * count
    return sections


def compare_param(ref_text, new_text, diag):
    """Counts, D, connectivity and patches exactly; T′'s coordinates and the β within tolerance."""
    ref, new = param_sections(ref_text), param_sections(new_text)
    errors = ["param.fhrp: %s %d, reference %d" % (k, len(new[k]), len(ref[k])) for k in ref if len(ref[k]) != len(new[k])]
    if errors:
        return errors
    for name in ("domain_vertices", "domain_faces"):
        bad = [i for i, (r, n) in enumerate(zip(ref[name], new[name])) if r != n]
        if bad:
            errors.append("param.fhrp: %d of %s differ, the first %d: %s, reference %s" % (len(bad), name, bad[0], new[name][bad[0]], ref[name][bad[0]]))
    worst = max((abs(float(a) - float(b)), i) for i, (r, n) in enumerate(zip(ref["surface_vertices"], new["surface_vertices"])) for a, b in zip(r, n))
    if worst[0] > PARAM_POSITION * diag:
        errors.append("param.fhrp: surface vertex %d moved by %g > %g" % (worst[1], worst[0], PARAM_POSITION * diag))
    faces = [i for i, (r, n) in enumerate(zip(ref["surface_faces"], new["surface_faces"])) if r[:4] != n[:4]]
    if faces:
        errors.append("param.fhrp: %d surface faces differ in corners or patch, the first %d: %s, reference %s" % (len(faces), faces[0], new["surface_faces"][faces[0]][:4], ref["surface_faces"][faces[0]][:4]))
    else:
        worst = max((abs(float(a) - float(b)), i) for i, (r, n) in enumerate(zip(ref["surface_faces"], new["surface_faces"])) for a, b in zip(r[4:], n[4:]))
        if worst[0] > PARAM_BETA:
            errors.append("param.fhrp: a β of surface face %d differs by %g > %g" % (worst[1], worst[0], PARAM_BETA))
    return errors


def png_rows(data):
    """(width, height, rows of RGB bytes) of an 8-bit RGB non-interlaced PNG (our writer's, REN-1),
    decoded with zlib and the five PNG filters undone."""
    assert data[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    at, idat = 8, b""
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        body = data[at + 8:at + 8 + length]
        at += 12 + length
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert (depth, colour, interlace) == (8, 2, 0), "not 8-bit RGB without interlace"
        elif kind == b"IDAT":
            idat += body
    raw, stride, rows = zlib.decompress(idat), 3 * width, []
    prev = bytearray(stride)
    for y in range(height):
        start = y * (stride + 1)
        kind, row = raw[start], bytearray(raw[start + 1:start + 1 + stride])
        for i in range(stride) if kind else ():
            a = row[i - 3] if i >= 3 else 0
            b, c = prev[i], (prev[i - 3] if i >= 3 else 0)
            if kind == 1:
                row[i] = (row[i] + a) & 255
            elif kind == 2:
                row[i] = (row[i] + b) & 255
            elif kind == 3:
                row[i] = (row[i] + (a + b) // 2) & 255
            else:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                row[i] = (row[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(row)
        prev = row
    return width, height, rows


def compare_png(name, ref, new):
    if ref == new:  # the same bytes are the same pixels
        return []
    (rw, rh, rrows), (nw, nh, nrows) = png_rows(ref), png_rows(new)
    if (rw, rh) != (nw, nh):
        return ["%s: %d × %d pixels, reference %d × %d" % (name, nw, nh, rw, rh)]
    differing = 0
    for r, n in zip(rrows, nrows):
        if r != n:
            differing += sum(1 for x in range(0, len(r), 3) if max(abs(r[x + k] - n[x + k]) for k in range(3)) > PNG_LEVELS)
    if differing > PNG_FRACTION * rw * rh:
        return ["%s: %d pixels differ by more than %d levels, more than %g of %d" % (name, differing, PNG_LEVELS, PNG_FRACTION, rw * rh)]
    return []


def compare_svg(name, ref, new):
    """The same text, numbers inside attribute values within SVG_COORDINATE."""
    split = lambda s: re.split(r'("[^"]*")', s)
    r, n = split(ref), split(new)
    if len(r) != len(n) or any(a != b for a, b in zip(r[0::2], n[0::2])):
        return ["%s: the elements or the text differ" % name]
    number = r"-?[0-9]+(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?"
    for a, b in zip(r[1::2], n[1::2]):
        if re.sub(number, "#", a) != re.sub(number, "#", b) or any(
                abs(float(x) - float(y)) > SVG_COORDINATE for x, y in zip(re.findall(number, a), re.findall(number, b))):
            return ["%s: attribute %s, reference %s" % (name, b[:80], a[:80])]
    return []


def read_param(folder):
    gz = folder / "param.fhrp.gz"
    return gzip.decompress(gz.read_bytes()).decode() if gz.exists() else (folder / "param.fhrp").read_text()


def compare(fhr, name, work):
    out, mesh = produce(fhr, name, work)
    ref = REF / name
    diag = diagonal(fhr, mesh)
    errors = []
    if CASES[name]["generate"] and mesh.read_bytes() != (ref / mesh.name).read_bytes():
        errors.append("%s: the generator gave another mesh (GEN-4 says it is bit-reproducible)" % mesh.name)
    errors += compare_report(json.loads((ref / "report.json").read_text()), json.loads((out / "report.json").read_text()), diag)
    errors += compare_param(read_param(ref), (out / "param.fhrp").read_text(), diag)
    names, new_names = sorted(p.name for p in (ref / "figures").iterdir()), sorted(p.name for p in (out / "figures").iterdir())
    if names != new_names:
        errors.append("figures: %s, reference %s" % (new_names, names))
    for f in sorted(set(names) & set(new_names)):
        a, b = (ref / "figures" / f).read_bytes(), (out / "figures" / f).read_bytes()
        errors += compare_png(f, a, b) if f.endswith(".png") else compare_svg(f, a.decode(), b.decode())
    return errors


def verify(fhr, work):
    """fhr verify --mesh on the committed exchange files: the references themselves are valid."""
    errors = []
    for name, case in CASES.items():
        param = work / (name + ".fhrp")
        param.write_text(read_param(REF / name))
        mesh = REF / name / case["mesh"] if case["generate"] else MESHES / case["mesh"]
        proc = subprocess.run([fhr, "verify", str(param), "--mesh", str(mesh), "--paper"], capture_output=True, text=True)
        if proc.returncode != 0:
            errors.append("fhr verify %s: exit %d\n%s%s" % (name, proc.returncode, proc.stdout, proc.stderr))
    return errors


def regenerate(fhr, work):
    for name, case in CASES.items():
        (work / name).mkdir()
        out, mesh = produce(fhr, name, work / name)
        ref = REF / name
        shutil.rmtree(ref, ignore_errors=True)
        shutil.copytree(out / "figures", ref / "figures")
        shutil.copy(out / "report.json", ref)
        param = (out / "param.fhrp").read_bytes()
        if len(param) > GZIP_ABOVE:
            (ref / "param.fhrp.gz").write_bytes(gzip.compress(param, compresslevel=9, mtime=0))
        else:
            (ref / "param.fhrp").write_bytes(param)
        if case["generate"]:
            shutil.copy(mesh, ref)
        for f in sorted(ref.rglob("*")):
            if f.is_file():
                print("%9d  %s" % (f.stat().st_size, f.relative_to(ROOT)))


def main():
    if len(sys.argv) != 3 or sys.argv[2] not in (*CASES, "verify", "--regenerate"):
        raise SystemExit(__doc__)
    fhr, what = Path(sys.argv[1]).resolve(), sys.argv[2]
    with tempfile.TemporaryDirectory(prefix="fhr-reference-") as tmp:
        work = Path(tmp)
        if what == "--regenerate":
            return regenerate(fhr, work)
        errors = verify(fhr, work) if what == "verify" else compare(fhr, what, work)
    for e in errors:
        print("DIFFERENT " + e)
    print("%s: %s" % (what, "%d differences" % len(errors) if errors else
                      "the committed exchange files are valid" if what == "verify" else "matches reference_outputs/"))
    sys.exit(1 if errors else 0)


if __name__ == "__main__":
    main()
