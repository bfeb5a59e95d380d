"""Campaigns across machines (spec/cli.md CLI-ORACLE-7..9, README "Campaigns across
machines"): two shards run by GNU parallel (Debian's `parallel`) and merged give the table of one
unsharded run — for `fhr oracle-fuzz` (byte for byte), for `./run corpus` (bench/run_corpus.py)
and for `./run families` (bench/run_families.py) (the same rows, times aside) — and a merge of
tables that are not the shards of one campaign is refused with one line and exit code 2.

Run by `./run test` with Debian's /usr/bin/python3; FHR is the `fhr` command of the build,
FHR_CGAL_MESHES the folder of libcgal-demo's meshes (default: out/cgal-data/data/meshes). The
tests use block meshes, except test_families_every_embedded_family, which needs every family of
the generator."""

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FHR = os.environ["FHR"]
MESHES = Path(os.environ.get("FHR_CGAL_MESHES", ROOT / "out/cgal-data/data/meshes"))
WRAPPER = ROOT / "peers/fhr-param"
sys.path.insert(0, str(ROOT / "bench"))
import campaign  # noqa: E402  (bench/campaign.py: TIMES)


def run(args, **kwargs):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)


def parallel(*command):
    """GNU parallel runs `command` with {} = 1 and 2 at the same time (-q: each word as given)."""
    if shutil.which("parallel") is None:
        pytest.fail("GNU parallel is missing: ./run installs Debian's `parallel`")
    return run(["parallel", "--will-cite", "-q", *command, ":::", "1", "2"])


def one_error_line(proc, prefix):
    assert proc.returncode == 2, proc.stdout + proc.stderr
    lines = proc.stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith(prefix), proc.stderr
    return lines[0]


# --- fhr oracle-fuzz --------------------------------------------------------------------------

@pytest.fixture(scope="module")
def program(tmp_path_factory):
    """The program under test: fhr's own pipeline (the wrapper of the CLI-ORACLE tests) on closed
    meshes, exit code 3 on meshes with boundary, so that a table has passes, failures and shrinks."""
    script = tmp_path_factory.mktemp("program") / "program.sh"
    script.write_text("'%s' info --json \"$1\" | grep -q '\"boundary_loops\": 0' || exit 3\n"
                      "FHR='%s' exec '%s' \"$1\" \"$2\"\n" % (FHR, FHR, WRAPPER))
    return "sh %s {mesh} {out}" % script


def fuzz(program, *extra):
    return [FHR, "oracle-fuzz", "--cmd", program, "--family", "block", "--count", "4", "--genus-max", "1",
            "--holes-max", "1", "--seed", "2", *extra]


def test_oracle_fuzz_two_shards_by_parallel_merge_to_the_unsharded_table(program, tmp_path):
    """CLI-ORACLE-8, CLI-ORACLE-9: two shards' tables merge into the unsharded run's, byte for byte."""
    whole = run(fuzz(program, "--keep", tmp_path / "keep", "--table", tmp_path / "whole.tsv"))
    shards = parallel(*fuzz(program, "--keep", tmp_path / "keep-{}", "--shard", "{}/2", "--table", tmp_path / "shard-{}.tsv"))
    assert shards.stderr == "", shards.stderr
    merged = run([FHR, "oracle-fuzz", "--merge", tmp_path / "shard-2.tsv", tmp_path / "shard-1.tsv",
                  "--table", tmp_path / "merged.tsv"])
    table = (tmp_path / "whole.tsv").read_text()
    assert (tmp_path / "merged.tsv").read_text() == table
    rows = table.splitlines()[14:]
    assert [r.split("\t")[0] for r in rows] == [str(i) for i in range(4)]
    assert any("\tvalid\t" in r for r in rows) and any("\tFAILED\texit 3\t" in r for r in rows), table
    # The shards ran their own meshes (i mod 2 = K - 1), and the merge reports what the whole run did.
    for k in (1, 2):
        shard_rows = (tmp_path / ("shard-%d.tsv" % k)).read_text().splitlines()[14:]
        assert shard_rows == rows[k - 1::2]
    failures = sum("\tFAILED\t" in r for r in rows)
    assert merged.returncode == whole.returncode == (1 if failures else 0)
    assert merged.stdout.splitlines()[-1] == whole.stdout.splitlines()[-1] == "4 meshes, %d failures" % failures
    assert merged.stdout.count(": FAILED: the program exited with code 3; smaller: fhr generate --genus 0 --holes 1 "
                               "--faces 10 ") == failures


@pytest.fixture(scope="module")
def tables(tmp_path_factory):
    """Shard tables of cheap campaigns (the program fails at once on every mesh)."""
    d = tmp_path_factory.mktemp("tables")
    base = [FHR, "oracle-fuzz", "--cmd", "exit 3 # {mesh} {out}", "--family", "block", "--keep", d / "keep"]
    for name, extra in [("a1", ["--count", "5", "--shard", "1/2"]), ("a2", ["--count", "5", "--shard", "2/2"]),
                        ("seed", ["--count", "5", "--seed", "9", "--shard", "2/2"]),
                        ("count", ["--count", "6", "--shard", "2/2"]), ("n3", ["--count", "5", "--shard", "2/3"])]:
        assert run(base + extra + ["--table", d / (name + ".tsv")]).returncode == 1
    return d


@pytest.mark.parametrize("case, files, message", [
    ("missing shard", ["a1"], "fhr: error: shard 2/2 is missing (mesh 1 is in none of the tables)"),
    ("a shard twice", ["a1", "a2", "a1"], "fhr: error: %(d)s/a1.tsv: shard 1/2 again (so is %(d)s/a1.tsv)"),
    ("another seed", ["a1", "seed"], "fhr: error: %(d)s/seed.tsv: seed '9' where %(d)s/a1.tsv has '1'"),
    ("another count", ["a1", "count"], "fhr: error: %(d)s/count.tsv: count '6' where %(d)s/a1.tsv has '5'"),
    ("another N", ["a1", "n3"], "fhr: error: %(d)s/n3.tsv: shard 2/3 where %(d)s/a1.tsv is shard 1/2"),
    ("unreadable", ["a1", "absent"], "fhr: error: %(d)s/absent.tsv: cannot open"),
    ("cut short", ["a1", "cut"], "fhr: error: %(d)s/cut.tsv:"),
    ("a row missing", ["a1", "lacking"], "fhr: error: %(d)s/lacking.tsv: shard 2/2 lacks mesh 3"),
    ("a row out of its shard", ["a1", "moved"], "fhr: error: %(d)s/moved.tsv:16: mesh 2 where shard 2/2 has mesh 3"),
] + [("a valid row with field %d set" % k, ["a1", "valid%d" % k],
      "fhr: error: %%(d)s/valid%d.tsv:16: a malformed row (empty field, a bad escape, or '-' missing after 'valid')" % k)
     for k in (4, 5, 6)])
def test_oracle_fuzz_merge_errors(tables, case, files, message):
    """CLI-ORACLE-9: a merge of tables that are not one campaign's shards names the file and the mismatch."""
    a2 = (tables / "a2.tsv").read_text()
    (tables / "cut.tsv").write_text(a2[:len(a2) - 20])
    lines = a2.splitlines(keepends=True)
    (tables / "lacking.tsv").write_text("".join(lines[:-1]))
    (tables / "moved.tsv").write_text("".join(lines[:-1]) + lines[-1].replace("3\t", "2\t", 1))
    for k in (4, 5, 6):  # 'valid' needs '-' in the check, reason and smaller fields (4, 5, 6)
        row = lines[-1].rstrip("\n").split("\t")
        fields = row[:3] + ["valid", "-", "-", "-"] + row[7:]  # the distortion as written
        fields[k] = "x"
        (tables / ("valid%d.tsv" % k)).write_text("".join(lines[:-1]) + "\t".join(fields) + "\n")
    out = tables / ("merged-%s.tsv" % case.replace(" ", "-"))
    proc = run([FHR, "oracle-fuzz", "--merge", *[tables / (f + ".tsv") for f in files], "--table", out])
    assert one_error_line(proc, message % {"d": tables}) is not None
    assert proc.stdout == ""
    assert not out.exists()  # nothing written on an error


# --- ./run corpus and ./run families ------------------------------------------------------------

def script(name, *args):
    return [sys.executable, ROOT / "bench" / name, *args]


def rows_without_times(path):
    d = json.loads(Path(path).read_text())
    return d["params"], d["count"], [{k: v for k, v in r.items() if k not in campaign.TIMES} for r in d["rows"]]


def table_without_times(stdout):
    return [line for line in stdout.splitlines() if not line.startswith("fhr run:")]


def check_same_campaign(name, before, after, tmp_path):
    """`FHR *before OUT_DIR *after` run unsharded into tmp/whole, and as shards 1/2, 2/2 by GNU
    parallel into tmp/shards; the merge of the shards' folder gives the unsharded run's results
    and table (times aside)."""
    whole = run(script(name, FHR, *before, tmp_path / "whole", *after))
    assert whole.returncode in (0, 1), whole.stderr
    shards = parallel(*script(name, FHR, *before, tmp_path / "shards", *after, "--shard", "{}/2"))
    assert shards.returncode in (0, 1, 2), shards.stderr  # parallel: the number of shards that failed
    assert {"results-1-of-2.json", "results-2-of-2.json"} <= set(os.listdir(tmp_path / "shards"))
    merged = run(script(name, "--merge", tmp_path / "shards", "--results", tmp_path / "merged.json"))
    assert merged.returncode == whole.returncode, merged.stderr
    assert rows_without_times(tmp_path / "merged.json") == rows_without_times(tmp_path / "whole" / "results.json")
    assert json.loads((tmp_path / "merged.json").read_text())["shard"] == "1/1"
    if name == "run_corpus.py":  # its table has a time column: compare the counts and failures
        keep = lambda out: [l for l in out.splitlines() if "certified (" in l or "kept on" in l or l.startswith("FAILED")]
        assert keep(merged.stdout) == keep(whole.stdout)
    else:
        assert table_without_times(merged.stdout) == table_without_times(whole.stdout)
    return whole


def test_corpus_two_shards_by_parallel_merge_to_the_unsharded_table(tmp_path):
    if not (MESHES / "sphere.off").exists():
        pytest.fail("libcgal-demo's meshes are missing from %s: ./run extracts them" % MESHES)
    # Closed, with a handle, with a boundary loop, the smallest closed one, and a file that is not
    # a valid input (a quad mesh without --triangulate: skipped, in every shard alike).
    whole = check_same_campaign("run_corpus.py", [MESHES], ["--only", "sphere.off", "pipe.off", "patch-21.off",
                                                            "tetrahedron.off", "quad.off"], tmp_path)
    assert whole.returncode == 0, whole.stdout + whole.stderr
    assert "4 of 4 certified (100.0 %)" in whole.stdout


def test_families_two_shards_by_parallel_merge_to_the_unsharded_table(tmp_path):
    whole = check_same_campaign("run_families.py", [], ["3", "--families", "block", "--faces-max", "4000"], tmp_path)
    assert whole.returncode == 0, whole.stdout + whole.stderr
    assert "| block | 3 | 3 (100.0 %) | 0 |" in whole.stdout
    assert os.listdir(tmp_path / "whole") == ["results.json"]  # certified meshes leave nothing behind
    rows = json.loads((tmp_path / "whole" / "results.json").read_text())["rows"]
    assert all(1000 <= r["faces"] <= 4000 and 0 <= r["genus"] <= 3 for r in rows)
    # Mesh i's recipe comes from (seed, family, i): the same in a campaign of another size.
    fewer = run(script("run_families.py", FHR, tmp_path / "fewer", "2", "--families", "block", "--faces-max", "4000"))
    assert [r["recipe"] for r in json.loads((tmp_path / "fewer" / "results.json").read_text())["rows"]] == \
        [r["recipe"] for r in rows[:2]]


def test_campaign_merge_errors(tmp_path):
    args = ["--families", "block", "--faces-max", "1500"]
    for shard, seed in (("1/2", "1"), ("1/3", "1"), ("2/2", "4")):
        proc = run(script("run_families.py", FHR, tmp_path / ("s-%s-%s" % (shard.replace("/", "of"), seed)), "2",
                          *args, "--seed", seed, "--shard", shard))
        assert proc.returncode == 0, proc.stderr
    a1 = tmp_path / "s-1of2-1" / "results-1-of-2.json"
    for files, message in [
            ([a1], "run_families.py: error: shard 2/2 is missing (item 1 is in none of the results)"),
            ([a1, a1], "run_families.py: error: %s: shard 1/2 again" % a1),
            ([a1, tmp_path / "s-2of2-4"], "run_families.py: error: %s: seed 4 where %s has 1: not the same campaign" % (
                tmp_path / "s-2of2-4" / "results-2-of-2.json", a1)),
            ([a1, tmp_path / "s-1of3-1"], "run_families.py: error: %s: shard 1/3 where %s is shard 1/2" % (
                tmp_path / "s-1of3-1" / "results-1-of-3.json", a1)),
            ([a1, tmp_path / "absent.json"], "run_families.py: error: %s: cannot read" % (tmp_path / "absent.json")),
            ([tmp_path], "run_families.py: error: %s: no results-K-of-N.json in this folder" % tmp_path)]:
        one_error_line(run(script("run_families.py", "--merge", *files)), message)
    # Results of one campaign are not results of another.
    one_error_line(run(script("run_corpus.py", "--merge", a1)), "run_corpus.py: error: %s: results of `families`" % a1)


def test_families_every_embedded_family(tmp_path):
    """Needs every family of the generator: one mesh of each, all certified."""
    proc = run(script("run_families.py", FHR, tmp_path, "1", "-j", "2"))
    assert proc.returncode == 0, proc.stdout + proc.stderr
    for family in ("block", "smooth", "quality", "valence", "density", "degenerate"):
        assert "| %s | 1 | 1 (100.0 %%) | 0 |" % family in proc.stdout
    assert "| all | 6 | 6 (100.0 %) | 0 |" in proc.stdout
