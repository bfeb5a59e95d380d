"""The CGAL adapters peers/cgal-* (peers/cgal/, program cgal_uv): each writes CGAL's map of a disk
as an OBJ atlas whose surface is the input bit for bit (`v` lines), with one `vt` per vertex and
every face `f a/a b/b c/c` in the input's face and corner order; exit code 3 on meshes that are
not disks (closed, annulus), 2 on a missing file, a NaN coordinate or a wrong call; `--help` names
the method. The maps themselves are judged by `fhr verify`, not here — except that the methods
CGAL guarantees (Tutte and mean value coordinates on the circle) give positively oriented
triangles and the fixed borders lie on their circle or square, which shows that vertex i's UV is
written on vertex i's line.

Run with Debian's interpreter: FHR_PEERS_BIN=build/peers /usr/bin/python3 -m pytest
proofs_tests/peers/test_cgal.py. FHR_PEERS_BIN is the folder holding the compiled cgal_uv; the
adapters are found relative to this file (the repository is two folders up)."""

import math
import os
import random
import struct
import subprocess
from pathlib import Path

import pytest

from oracle import fhr_verify

ROOT = Path(__file__).resolve().parents[2]
PEERS = ROOT / "peers"

# adapter name -> words its --help must contain (the method's CGAL classes)
ADAPTERS = {
    "cgal-tutte": ["Barycentric_mapping_parameterizer_3", "Circular_border_arc_length_parameterizer_3"],
    "cgal-tutte-square": ["Barycentric_mapping_parameterizer_3", "Square_border_arc_length_parameterizer_3"],
    "cgal-conformal": ["Discrete_conformal_map_parameterizer_3", "Circular_border_arc_length_parameterizer_3"],
    "cgal-conformal-square": ["Discrete_conformal_map_parameterizer_3", "Square_border_arc_length_parameterizer_3"],
    "cgal-authalic": ["Discrete_authalic_parameterizer_3", "Circular_border_arc_length_parameterizer_3"],
    "cgal-authalic-square": ["Discrete_authalic_parameterizer_3", "Square_border_arc_length_parameterizer_3"],
    "cgal-mvc": ["Mean_value_coordinates_parameterizer_3", "Circular_border_arc_length_parameterizer_3"],
    "cgal-mvc-square": ["Mean_value_coordinates_parameterizer_3", "Square_border_arc_length_parameterizer_3"],
    "cgal-lscm": ["LSCM_parameterizer_3"],
    "cgal-arap": ["ARAP_parameterizer_3"],
    "cgal-lscm-mvc-post": ["LSCM_parameterizer_3", "MVC_post_processor_3"],
}


@pytest.fixture(scope="module")
def env():
    """The environment of every adapter run: FHR_PEERS_BIN must name the folder of a built cgal_uv."""
    folder = os.environ.get("FHR_PEERS_BIN")
    if not folder:
        pytest.fail("FHR_PEERS_BIN is unset: set it to the folder holding the compiled cgal_uv "
                    "(build/peers of a build configured with tests or bench on)")
    program = Path(folder) / "cgal_uv"
    if not (program.is_file() and os.access(program, os.X_OK)):
        pytest.fail("FHR_PEERS_BIN=%s holds no executable cgal_uv (build the target cgal_uv)" % folder)
    return dict(os.environ, FHR_PEERS_BIN=folder)


def run(env, adapter, *args):
    return subprocess.run([str(PEERS / adapter), *[str(a) for a in args]], capture_output=True, text=True,
                          env=env, timeout=300)


# --- meshes -------------------------------------------------------------------------------------

def grid_disk(n=8, seed=20240611):
    """A triangulated n×n grid over [0,1]², interior vertices moved at random by up to 0.3 cell,
    diagonals flipped at random, lifted onto a smooth height field: a disk with one border loop."""
    rng = random.Random(seed)
    vertices = []
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i / n, j / n
            if 0 < i < n and 0 < j < n:
                x += rng.uniform(-0.3, 0.3) / n
                y += rng.uniform(-0.3, 0.3) / n
            vertices.append((x, y, 0.2 * math.sin(2.5 * x) * math.cos(1.5 * y)))
    faces = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i
            b, c, d = a + 1, a + n + 2, a + n + 1
            faces += [(a, b, d), (b, c, d)] if rng.random() < 0.4 else [(a, b, c), (a, c, d)]
    return vertices, faces


def annulus():
    """The grid without its 2×2 middle cells: one component, two border loops, genus 0."""
    vertices, faces = grid_disk()
    n = 8
    kept = [f for k, f in enumerate(faces) if not (3 <= (k // 2) % n <= 4 and 3 <= (k // 2) // n <= 4)]
    used = sorted({i for f in kept for i in f})
    index = {old: new for new, old in enumerate(used)}
    return [vertices[i] for i in used], [tuple(index[i] for i in f) for f in kept]


def octahedron():
    vertices = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
    faces = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]
    return vertices, faces


def write_off(path, vertices, faces):
    lines = ["OFF", "%d %d 0" % (len(vertices), len(faces))]
    lines += ["%r %r %r" % tuple(float(c) for c in v) for v in vertices]  # repr: the shortest exact decimal
    lines += ["3 %d %d %d" % f for f in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_obj(path, vertices, faces):
    lines = ["# a disk", "o disk"] + ["v %r %r %r" % tuple(float(c) for c in v) for v in vertices]
    lines += ["f %d %d %d" % tuple(i + 1 for i in f) for f in faces]
    path.write_text("\n".join(lines) + "\n")
    return path


def write_ply(path, vertices, faces, binary):
    header = ["ply", "format %s 1.0" % ("binary_little_endian" if binary else "ascii"),
              "element vertex %d" % len(vertices), "property double x", "property double y", "property double z",
              "property uchar red", "element face %d" % len(faces), "property list uchar int vertex_indices",
              "end_header"]
    if binary:
        body = b"".join(struct.pack("<dddB", *map(float, v), 7) for v in vertices)
        body += b"".join(struct.pack("<Biii", 3, *f) for f in faces)
        path.write_bytes(("\n".join(header) + "\n").encode() + body)
    else:
        rows = ["%r %r %r 7" % tuple(float(c) for c in v) for v in vertices] + ["3 %d %d %d" % f for f in faces]
        path.write_text("\n".join(header + rows) + "\n")
    return path


# --- reading an atlas ---------------------------------------------------------------------------

def read_atlas(path):
    """The atlas's comment lines, positions, UVs and faces (each a tuple of (vertex, uv) pairs, 0-based);
    any line that is not a comment, v, vt or f fails the test."""
    comments, positions, uvs, faces = [], [], [], []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        words = line.split()
        assert words, "%s:%d: blank line" % (path, number)
        if words[0].startswith("#"):
            comments.append(line)
        elif words[0] == "v":
            assert len(words) == 4, line
            positions.append(tuple(float(w) for w in words[1:]))
        elif words[0] == "vt":
            assert len(words) == 3, line
            uvs.append(tuple(float(w) for w in words[1:]))
        elif words[0] == "f":
            assert len(words) == 4, line
            corners = []
            for corner in words[1:]:
                parts = corner.split("/")
                assert len(parts) == 2, "corner %r is not a/t" % corner
                corners.append((int(parts[0]) - 1, int(parts[1]) - 1))
            faces.append(tuple(corners))
        else:
            pytest.fail("%s:%d: unexpected line %r" % (path, number, line))
    return comments, positions, uvs, faces


def orient(p, q, r):
    return (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])


def border_vertices(faces):
    count = {}
    for f in faces:
        for k in range(3):
            edge = tuple(sorted((f[k], f[(k + 1) % 3])))
            count[edge] = count.get(edge, 0) + 1
    return {v for edge, c in count.items() if c == 1 for v in edge}


# --- tests --------------------------------------------------------------------------------------

def test_every_cgal_adapter_is_tested():
    on_disk = sorted(p.name for p in PEERS.glob("cgal-*"))
    assert on_disk == sorted(ADAPTERS), on_disk
    for name in on_disk:
        assert os.access(PEERS / name, os.X_OK), "%s is not executable" % name


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_disk_gives_the_input_with_one_uv_per_vertex(env, adapter, tmp_path):
    vertices, faces = grid_disk()
    mesh = write_off(tmp_path / "disk.off", vertices, faces)
    out = tmp_path / "atlas.obj"
    proc = run(env, adapter, mesh, out)
    assert proc.returncode == 0, proc.stderr
    assert proc.stderr == ""
    assert sorted(p.name for p in tmp_path.iterdir()) == ["atlas.obj", "disk.off"], "a temporary was left"
    comments, positions, uvs, atlas_faces = read_atlas(out)
    assert out.read_text().startswith("#") and len(comments) == 1
    assert adapter in comments[0] and "CGAL 5." in comments[0]
    # The surface is the input, bit for bit, in the input's vertex order.
    assert positions == [tuple(float(c) for c in v) for v in vertices]
    # One finite UV per vertex; every corner's UV is its vertex's.
    assert len(uvs) == len(vertices)
    assert all(math.isfinite(c) for uv in uvs for c in uv)
    assert len(atlas_faces) == len(faces)
    for face, atlas_face in zip(faces, atlas_faces):
        assert tuple(v for v, _ in atlas_face) == face, "face order or corner order changed"
        assert all(v == t for v, t in atlas_face)


@pytest.mark.parametrize("adapter", ["cgal-tutte", "cgal-mvc"])
def test_guaranteed_methods_keep_every_triangle_positive(env, adapter, tmp_path):
    """Tutte and mean value maps onto the circle are embeddings: with UVs on the right vertices,
    every triangle is positively oriented and the border lies on CGAL's circle."""
    vertices, faces = grid_disk()
    out = tmp_path / "atlas.obj"
    assert run(env, adapter, write_off(tmp_path / "disk.off", vertices, faces), out).returncode == 0
    _, _, uvs, _ = read_atlas(out)
    for a, b, c in faces:
        assert orient(uvs[a], uvs[b], uvs[c]) > 0
    for v in border_vertices(faces):
        assert abs(math.hypot(uvs[v][0] - 0.5, uvs[v][1] - 0.5) - 0.5) < 1e-12
    for v in set(range(len(vertices))) - border_vertices(faces):
        assert math.hypot(uvs[v][0] - 0.5, uvs[v][1] - 0.5) < 0.5


@pytest.mark.parametrize("adapter", [a for a in sorted(ADAPTERS) if a.endswith("-square")])
def test_square_border_lies_on_the_unit_square(env, adapter, tmp_path):
    vertices, faces = grid_disk()
    out = tmp_path / "atlas.obj"
    assert run(env, adapter, write_off(tmp_path / "disk.off", vertices, faces), out).returncode == 0
    _, _, uvs, _ = read_atlas(out)
    for v in border_vertices(faces):
        u, w = uvs[v]
        assert 0 <= u <= 1 and 0 <= w <= 1 and min(u, 1 - u, w, 1 - w) < 1e-12, (v, uvs[v])


@pytest.mark.parametrize("kind", ["obj", "ply-ascii", "ply-binary"])
def test_obj_and_ply_inputs_give_the_off_input_atlas(env, kind, tmp_path):
    vertices, faces = grid_disk()
    reference = tmp_path / "off.obj"
    assert run(env, "cgal-tutte", write_off(tmp_path / "disk.off", vertices, faces), reference).returncode == 0
    if kind == "obj":
        mesh = write_obj(tmp_path / "disk.obj", vertices, faces)
    else:
        mesh = write_ply(tmp_path / "disk.ply", vertices, faces, binary=kind == "ply-binary")
    out = tmp_path / "other.obj"
    proc = run(env, "cgal-tutte", mesh, out)
    assert proc.returncode == 0, proc.stderr
    assert out.read_text() == reference.read_text()


def one_error_line(proc, adapter, code):
    assert proc.returncode == code, (proc.returncode, proc.stderr)
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(adapter + ": error: "), proc.stderr
    return lines[0]


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_not_a_disk_is_not_applicable(env, adapter, tmp_path):
    closed = write_off(tmp_path / "closed.off", *octahedron())
    line = one_error_line(run(env, adapter, closed, tmp_path / "a.obj"), adapter, 3)
    assert "closed surface" in line
    ring = write_off(tmp_path / "annulus.off", *annulus())
    line = one_error_line(run(env, adapter, ring, tmp_path / "b.obj"), adapter, 3)
    assert "annulus" in line and "2 boundary loops" in line
    assert sorted(p.name for p in tmp_path.iterdir()) == ["annulus.off", "closed.off"]


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_unreadable_mesh_is_a_usage_error(env, adapter, tmp_path):
    line = one_error_line(run(env, adapter, tmp_path / "missing.off", tmp_path / "a.obj"), adapter, 2)
    assert "missing.off" in line
    vertices, faces = grid_disk()
    vertices[5] = (vertices[5][0], float("nan"), vertices[5][2])
    text = write_off(tmp_path / "nan.off", vertices, faces).read_text()
    assert "nan" in text
    line = one_error_line(run(env, adapter, tmp_path / "nan.off", tmp_path / "b.obj"), adapter, 2)
    assert "NaN" in line
    one_error_line(run(env, adapter, tmp_path / "nan.off"), adapter, 2)  # OUT missing
    assert sorted(p.name for p in tmp_path.iterdir()) == ["nan.off"]


@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_help_names_the_method(env, adapter):
    proc = run(env, adapter, "--help")
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.startswith("usage: %s MESH OUT" % adapter)
    for word in ADAPTERS[adapter]:
        assert word in proc.stdout
    assert "CGAL promises" in proc.stdout


def test_missing_program_is_a_usage_error(tmp_path):
    proc = subprocess.run([str(PEERS / "cgal-tutte"), "a.off", "b.obj"], capture_output=True, text=True,
                          env=dict(os.environ, FHR_PEERS_BIN=str(tmp_path)))
    line = one_error_line(proc, "cgal-tutte", 2)
    assert "cgal_uv" in line and "FHR_PEERS_BIN" in line


# --- judged by the oracle -----------------------------------------------------------------------



@pytest.mark.parametrize("adapter", sorted(ADAPTERS))
def test_every_adapters_atlas_is_judged(env, adapter, tmp_path):
    """Each adapter once on a generated disk, its atlas judged against the input. The methods that
    promise an embedding (Tutte and mean value on the circle: a convex border, positive weights)
    must be valid; every judged atlas has the input's surface (ATLAS-8) and distortion figures."""
    mesh = write_off(tmp_path / "disk.off", *grid_disk())
    out = tmp_path / "atlas.obj"
    assert run(env, adapter, mesh, out).returncode == 0
    verdict = fhr_verify(out, "--mesh", mesh)
    assert verdict["kind"] == "atlas"
    assert verdict["distortion"]["l2_stretch"] is not None and verdict["distortion"]["l2_stretch"] >= 1
    if verdict["first_failure"] != "ATLAS-3":  # the square border's degenerate triangles skip the rest
        assert verdict["charts"] == 1
        assert {c["id"]: c["result"] for c in verdict["checks"]}["ATLAS-8"] == "pass"
    if adapter in ("cgal-tutte", "cgal-mvc"):
        assert verdict["valid"], verdict["first_failure"]
        assert verdict["mirrored_charts"] == 0


def replace_vt(source, target, moves):
    """A copy of an OBJ atlas with the vt lines of `moves` (0-based index -> (u, v)) replaced."""
    lines, k = [], 0
    for line in source.read_text().splitlines():
        if line.startswith("vt "):
            if k in moves:
                line = "vt %r %r" % moves[k]
            k += 1
        lines.append(line)
    target.write_text("\n".join(lines) + "\n")
    return target


def test_a_fold_and_an_overlap_made_from_a_real_atlas_are_caught(env, tmp_path):
    vertices, faces = grid_disk()
    mesh = write_off(tmp_path / "disk.off", vertices, faces)
    out = tmp_path / "tutte.obj"
    assert run(env, "cgal-tutte", mesh, out).returncode == 0
    _, _, uvs, _ = read_atlas(out)
    assert fhr_verify(out)["valid"]
    # A fold: an interior vertex moved to the far side of the disk turns faces around it over.
    inner = min(set(range(len(vertices))) - border_vertices(faces))
    u, v = uvs[inner]
    folded = fhr_verify(replace_vt(out, tmp_path / "fold.obj", {inner: (1 - u, 1 - v)}), "--list")
    assert not folded["valid"] and folded["first_failure"] == "ATLAS-4"
    assert any(inner in faces[f] for f in folded["folded_face_list"])
    # An overlap: a border vertex pulled across the disk lays its faces over others.
    rim = sorted(border_vertices(faces))[len(vertices) // 7 % len(border_vertices(faces))]
    u, v = uvs[rim]
    over = fhr_verify(replace_vt(out, tmp_path / "over.obj", {rim: (0.5 + 0.9 * (0.5 - u), 0.5 + 0.9 * (0.5 - v))}))
    assert not over["valid"]
    assert over["overlapping_pairs"] > 0
