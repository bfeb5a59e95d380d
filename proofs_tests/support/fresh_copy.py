"""Test support: a fresh copy of the source tree for the tests that build fhr as a user would
(proofs_tests/library/check_install.py, proofs_tests/python/test_package.py): the files git knows,
tracked or new and not ignored, as they are on disk now (so uncommitted work is tested too)."""
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def fresh_copy(dest):
    names = subprocess.run(["git", "-C", str(ROOT), "ls-files", "--cached", "--others", "--exclude-standard", "-z"],
                           capture_output=True, check=True).stdout.decode().split("\0")
    for name in filter(None, names):
        if (ROOT / name).is_file():
            (Path(dest) / name).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / name, Path(dest) / name)
