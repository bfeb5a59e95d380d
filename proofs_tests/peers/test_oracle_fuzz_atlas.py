"""`fhr oracle-fuzz --kind atlas --topology disk` against real programs (spec/cli.md CLI-ORACLE-10):
CGAL's Tutte map on the circle (one-to-one on every disk, in exact arithmetic) passes the smooth
family's disks (on the density family's edge-length ratios of 10⁵ its floating-point solve can
flatten a triangle: paper_notes/atlas.md); CGAL's LSCM,
which promises no embedding, folds on some, and every failure kept is a reproducer: the adapter run
again on its smaller mesh fails the same way (the same check). Bad values of the new options are
usage errors. FHR names the built fhr and FHR_PEERS_BIN the compiled CGAL adapter (the meson test
sets both)."""
import os
import re
import subprocess
from pathlib import Path

import pytest

from oracle import fhr_verify

PEERS = Path(__file__).resolve().parents[2] / "peers"


def fhr(*args, cwd=None):
    program = os.environ.get("FHR")
    if not program or not os.path.exists(program):
        pytest.fail("FHR must name the built fhr program (the meson test sets it)")
    return subprocess.run([program, *map(str, args)], capture_output=True, text=True, cwd=cwd, timeout=600)


def fuzz(adapter, tmp_path, count, *family):
    return fhr("oracle-fuzz", "--cmd", "%s {mesh} {out}" % (PEERS / adapter), "--topology", "disk", "--kind", "atlas",
               "--count", count, "--keep", tmp_path / "kept", "--table", tmp_path / "table.tsv", *family, cwd=tmp_path)


def test_tutte_on_the_circle_is_valid_on_smooth_disks(tmp_path):
    proc = fuzz("cgal-tutte", tmp_path, 8, "--family", "smooth")
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert proc.stdout.splitlines()[-1] == "8 meshes, 0 failures"
    assert all("--genus 0 --holes 1" in line for line in proc.stdout.splitlines()[:-1])
    table = (tmp_path / "table.tsv").read_text()
    assert "# topology\tdisk\n" in table and "# kind\tatlas\n" in table


def test_lscm_failures_are_kept_as_reproducers(tmp_path):
    proc = fuzz("cgal-lscm", tmp_path, 12)
    assert proc.returncode == 1, proc.stdout + proc.stderr
    failed = [line for line in proc.stdout.splitlines() if ": FAILED: " in line]
    assert failed and proc.stdout.splitlines()[-1] == "12 meshes, %d failures" % len(failed)
    for line in failed:
        index = re.match(r"mesh (\d+):", line).group(1)
        kept = tmp_path / "kept" / ("mesh-" + index)
        assert {"mesh.off", "out.obj", "smaller.off", "reason.txt"} <= {p.name for p in kept.iterdir()}
        check = re.search(r"FAILED: (ATLAS-\d+)", line).group(1)
        # The kept smaller mesh is a disk and the adapter fails on it the same way.
        info = fhr("info", "--json", kept / "smaller.off").stdout
        assert '"boundary_loops": 1' in info and '"genus": 0' in info
        out = tmp_path / ("again-%s.obj" % index)
        assert subprocess.run([str(PEERS / "cgal-lscm"), str(kept / "smaller.off"), str(out)]).returncode == 0
        assert fhr_verify(out, "--mesh", kept / "smaller.off")["first_failure"] == check


@pytest.mark.parametrize("option,value", [("--topology", "sphere"), ("--kind", "vertex")])
def test_bad_values_are_usage_errors(option, value, tmp_path):
    proc = fhr("oracle-fuzz", "--cmd", "true {mesh} {out}", "--count", 1, option, value, cwd=tmp_path)
    assert proc.returncode == 2 and proc.stderr.startswith("fhr: error:") and value in proc.stderr
