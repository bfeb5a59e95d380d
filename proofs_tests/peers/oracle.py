"""What the adapters' tests share: the oracle's verdict on an atlas, `fhr verify ... --json`, with
FHR naming the built fhr (the meson test sets it)."""
import json
import os
import subprocess

import pytest


def fhr_verify(*args):
    """The verdict as a dict; the oracle must read the file (exit code 0 or 1)."""
    program = os.environ.get("FHR")
    if not program or not os.path.exists(program):
        pytest.fail("FHR must name the built fhr program (the meson test sets it)")
    proc = subprocess.run([program, "verify", *map(str, args), "--json"], capture_output=True, text=True)
    assert proc.returncode in (0, 1), proc.stderr
    return json.loads(proc.stdout)
