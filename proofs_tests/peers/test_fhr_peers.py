"""fhr itself as a peer (peers/fhr-param, peers/fhr-atlas, peers/fhr-vertex-map; peers/fhr_peer.py):
each writes fhr's output for a generated mesh, judged valid by the oracle (param.fhrp as fhr's default
map, its chord length reported, not judged; textured.obj with --no-mirror: its charts are turned,
never mirrored); with
--flip each writes a broken output that the oracle catches (PARAM-7 for the swapped β; for the
reflected vt ATLAS-4 — a fold, or the face cut off its chart as a mirrored chart of its own — or
ATLAS-6, an overlap; for the exchanged images VMAP-5 or VMAP-6); `fhr oracle-fuzz --kind vertex-map`
judges the per-vertex map's folder and keeps it with a failure; --help names the output; a wrong
call is exit code 2. FHR names the built fhr (the meson test sets it)."""
import json
import os
import re
import subprocess
from pathlib import Path

import pytest

from oracle import fhr_verify

PEERS = Path(__file__).resolve().parents[2] / "peers"


@pytest.fixture(scope="module")
def mesh(tmp_path_factory):
    program = os.environ.get("FHR")
    if not program or not os.path.exists(program):
        pytest.fail("FHR must name the built fhr program (the meson test sets it)")
    path = tmp_path_factory.mktemp("mesh") / "g1.off"
    subprocess.run([program, "generate", "--genus", "1", "--holes", "1", "--faces", "801", "--seed", "3", "--out", path],
                   check=True, capture_output=True)
    return path


@pytest.mark.parametrize("adapter,out,flipped", [("fhr-param", "out.fhrp", {"PARAM-7"}),
                                                  ("fhr-atlas", "out.obj", {"ATLAS-4", "ATLAS-6"})])
def test_fhr_as_a_peer_is_judged(adapter, out, flipped, mesh, tmp_path):
    good, bad = tmp_path / out, tmp_path / ("flipped-" + out)
    assert subprocess.run([str(PEERS / adapter), str(mesh), str(good)]).returncode == 0
    strict = [] if adapter == "fhr-param" else ["--no-mirror"]
    verdict = fhr_verify(good, "--mesh", mesh, *strict)
    assert verdict["valid"], verdict["first_failure"]
    assert subprocess.run([str(PEERS / adapter), str(mesh), str(bad), "--flip"]).returncode == 0
    assert fhr_verify(bad, "--mesh", mesh, *strict)["first_failure"] in flipped
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([good.name, bad.name])  # no temporary left


@pytest.mark.parametrize("adapter", ["fhr-param", "fhr-atlas", "fhr-vertex-map"])
def test_help_and_usage(adapter, tmp_path):
    helped = subprocess.run([str(PEERS / adapter), "--help"], capture_output=True, text=True)
    assert helped.returncode == 0 and helped.stdout.startswith("usage: %s MESH OUT" % adapter)
    wrong = subprocess.run([str(PEERS / adapter), "only-one-argument"], capture_output=True, text=True)
    assert wrong.returncode == 2 and wrong.stderr.startswith(adapter + ": error:")


def vertex_map_verdict(folder, mesh):
    proc = subprocess.run([os.environ["FHR"], "verify", "--vertex-map", folder / "map.vmap", "--domain", folder / "D.off",
                           "--mesh", mesh, "--json", "--list"], capture_output=True, text=True)
    assert proc.returncode in (0, 1), proc.stderr
    return json.loads(proc.stdout)


def test_fhr_vertex_map_as_a_peer_is_judged(tmp_path):
    # A closed genus-1 mesh where fhr's map, given on T's vertices alone, is valid under the rule
    # adjacent (paper_notes/vertex_map.md: where an edge of T straddles a curve near a vertex of D
    # it need not be).
    mesh = tmp_path / "g1.off"
    subprocess.run([os.environ["FHR"], "generate", "--genus", "1", "--faces", "800", "--seed", "3", "--out", mesh],
                   check=True, capture_output=True)
    good, bad = tmp_path / "out", tmp_path / "flipped"
    assert subprocess.run([str(PEERS / "fhr-vertex-map"), str(mesh), str(good)]).returncode == 0
    assert sorted(p.name for p in good.iterdir()) == ["D.off", "map.vmap"]
    verdict = vertex_map_verdict(good, mesh)
    assert verdict["valid"], verdict["first_failure"]
    assert verdict["surface"]["vertices"] == 400
    assert subprocess.run([str(PEERS / "fhr-vertex-map"), str(mesh), str(bad), "--flip"]).returncode == 0
    flipped = vertex_map_verdict(bad, mesh)
    assert flipped["first_failure"] in ("VMAP-5", "VMAP-6")
    assert all(0 in e or 399 in e for e in flipped["edges_without_image_list"])
    assert sorted(p.name for p in tmp_path.iterdir()) == ["flipped", "g1.off", "out"]  # no temporary left


def test_oracle_fuzz_judges_per_vertex_maps(tmp_path):
    proc = subprocess.run([os.environ["FHR"], "oracle-fuzz", "--cmd", "%s {mesh} {out} --flip" % (PEERS / "fhr-vertex-map"),
                           "--kind", "vertex-map", "--topology", "closed", "--count", "2", "--keep", tmp_path / "kept",
                           "--table", tmp_path / "table.tsv", "--faces-min", "300"],
                          capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    assert proc.stdout.splitlines()[-1] == "2 meshes, 2 failures"
    table = (tmp_path / "table.tsv").read_text()
    assert "# kind\tvertex-map\n" in table and "# faces-min\t300\n" in table
    # --faces-min: no mesh drawn or shrunk below 300 faces
    sizes = [int(n) for n in re.findall(r"--faces (\d+)", table)]
    assert len(sizes) == 4 and min(sizes) >= 300
    kept = tmp_path / "kept" / "mesh-0"
    assert {"mesh.off", "out", "smaller.off", "reason.txt"} <= {p.name for p in kept.iterdir()}
    assert (kept / "out" / "map.vmap").is_file()
    assert re.search(r"reason: VMAP-[56]", (kept / "reason.txt").read_text())
