"""PY-7: the package installs like any Python package: pyproject.toml with
meson-python, `pip install --no-build-isolation .` into a fresh virtual environment (Debian's
numpy, pybind11 and meson-python through the system site packages; no network), then imported
and used from outside the source tree. The wheel holds the module only (no C++ install)."""

import os
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
from fresh_copy import fresh_copy  # noqa: E402


def test_pip_install_into_a_fresh_venv_and_import_from_outside(tmp_path):
    source, venv = tmp_path / "fhr", tmp_path / "venv"
    fresh_copy(source)
    subprocess.run([sys.executable, "-m", "venv", "--system-site-packages", str(venv)], check=True)
    python = venv / "bin" / "python"
    # builddir inside the copy: the compile commands keep relative paths, so ccache serves reruns.
    install = subprocess.run([str(python), "-m", "pip", "install", "--no-build-isolation", "--no-index",
                              "--config-settings", "builddir=build-wheel", str(source)],
                             capture_output=True, text=True, env=dict(os.environ, PIP_NO_INPUT="1"))
    assert install.returncode == 0, install.stdout[-3000:] + install.stderr[-3000:]
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    script = (
        "import fhr, fhr.testing, pathlib\n"
        "print(pathlib.Path(fhr.__file__).parent)\n"
        "V, F = fhr.generate(1, 300, seed=3, noise=0.1)\n"
        "p = fhr.parameterize(V, F, faces=30)\n"
        "assert p.certified and p.oracle['valid']\n"
        "print(sorted(f.name for f in pathlib.Path(fhr.__file__).parent.iterdir() if f.name != '__pycache__'))\n"
    )
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    run = subprocess.run([str(python), "-c", script], cwd=outside, capture_output=True, text=True, env=env)
    assert run.returncode == 0, run.stdout + run.stderr
    location, files = run.stdout.splitlines()
    assert Path(location).is_relative_to(venv)  # the installed package, not the build tree's
    assert files.startswith("['__init__.py', '_fhr.cpython-") and files.endswith("'_fhr.pyi', 'py.typed', 'testing.py']")
    wheel_files = [p for p in (venv / "lib").rglob("*") if p.suffix in (".hpp", ".a", ".pc") or p.name == "fhrConfig.cmake"]
    assert wheel_files == []  # no C++ install in the wheel
