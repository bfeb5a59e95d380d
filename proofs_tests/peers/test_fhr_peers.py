"""fhr itself as a peer (peers/fhr-param, peers/fhr-atlas; peers/fhr_peer.py): each writes fhr's
output for a generated mesh of genus 1 with a boundary loop, judged valid by the oracle (param.fhrp
with --paper: it is the paper's map); with --flip each writes a broken output that the oracle
catches (PARAM-7 for the swapped β; for the reflected vt ATLAS-4 or, where textured.obj gives the
corner a vt of its own, ATLAS-6); --help names the output; a
wrong call is exit code 2. FHR names the built fhr (the meson test sets it)."""
import os
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
    verdict = fhr_verify(good, "--mesh", mesh, *(["--paper"] if adapter == "fhr-param" else []))
    assert verdict["valid"], verdict["first_failure"]
    assert subprocess.run([str(PEERS / adapter), str(mesh), str(bad), "--flip"]).returncode == 0
    assert fhr_verify(bad, "--mesh", mesh)["first_failure"] in flipped
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([good.name, bad.name])  # no temporary left


@pytest.mark.parametrize("adapter", ["fhr-param", "fhr-atlas"])
def test_help_and_usage(adapter, tmp_path):
    helped = subprocess.run([str(PEERS / adapter), "--help"], capture_output=True, text=True)
    assert helped.returncode == 0 and helped.stdout.startswith("usage: %s MESH OUT" % adapter)
    wrong = subprocess.run([str(PEERS / adapter), "only-one-argument"], capture_output=True, text=True)
    assert wrong.returncode == 2 and wrong.stderr.startswith(adapter + ": error:")
