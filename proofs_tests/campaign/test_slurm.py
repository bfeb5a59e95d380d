"""A campaign on a real Slurm cluster (README "Campaigns across machines", spec/cli.md
CLI-ORACLE-7..9): a throwaway single-node Slurm started on this machine — Debian's slurm-wlm and
munge, as root, ports on 127.0.0.1, no cgroups (ProctrackType=proctrack/linuxproc,
TaskPlugin=task/none) — runs `fhr oracle-fuzz` of a deterministic adapter (peers/fhr-param, far
from its timeout) as a job array of 4 shards submitted with `sbatch --array`; the merged table is
byte-identical to the unsharded run's, and a shard cancelled with `scancel` is named by the
merge's message and exit code 2. Everything the test starts is stopped, and its folder removed.

Run by `./run test` with Debian's /usr/bin/python3 as root (Slurm's daemons run as root here); FHR
is the `fhr` command of the build. `./run` installs slurm-wlm and munge."""

import os
import shutil
import signal
import socket
import subprocess
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
FHR = os.environ["FHR"]
SHARDS = 4
CAMPAIGN = ["oracle-fuzz", "--cmd", "%s {mesh} {out}" % (ROOT / "peers/fhr-param"), "--count", "8",
            "--family", "block", "--topology", "closed", "--seed", "4", "--timeout", "120"]


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def run(args, **kwargs):
    return subprocess.run([str(a) for a in args], capture_output=True, text=True, **kwargs)


class Cluster:
    """munged, slurmctld and slurmd in `folder`, each with its pid file; `env` for the clients."""

    def __init__(self, folder):
        self.folder = folder
        folder.mkdir()
        for sub in ("munge", "state", "spool", "log"):
            (folder / sub).mkdir()
        (folder / "munge").chmod(0o700)
        self.conf = folder / "slurm.conf"
        self.env = dict(os.environ, SLURM_CONF=str(self.conf))
        self.pids = [folder / "munge/munged.pid", folder / "slurmd.pid", folder / "slurmctld.pid"]

    def start(self):
        f = self.folder
        subprocess.run(["mungekey", "--create", "--keyfile", f / "munge/munge.key", "--force"], check=True, capture_output=True)
        socket_path = f / "munge/socket"
        subprocess.run(["munged", "--force", "-S", socket_path, "--key-file", f / "munge/munge.key", "--log-file",
                        f / "log/munged.log", "--pid-file", f / "munge/munged.pid", "--seed-file", f / "munge/seed"],
                       check=True, capture_output=True)
        self.conf.write_text("\n".join([
            "ClusterName=fhrtest", "SlurmctldHost=%s(127.0.0.1)" % socket.gethostname().split(".")[0],
            "SlurmctldPort=%d" % free_port(), "SlurmdPort=%d" % free_port(), "SlurmUser=root", "SlurmdUser=root",
            "AuthType=auth/munge", "AuthInfo=socket=%s" % socket_path, "CredType=cred/munge",
            "StateSaveLocation=%s" % (f / "state"), "SlurmdSpoolDir=%s" % (f / "spool"),
            "SlurmctldPidFile=%s" % (f / "slurmctld.pid"), "SlurmdPidFile=%s" % (f / "slurmd.pid"),
            "SlurmctldLogFile=%s" % (f / "log/slurmctld.log"), "SlurmdLogFile=%s" % (f / "log/slurmd.log"),
            "ProctrackType=proctrack/linuxproc", "TaskPlugin=task/none", "SelectType=select/cons_tres",
            "SelectTypeParameters=CR_Core", "JobCompType=jobcomp/none", "AccountingStorageType=accounting_storage/none",
            "MpiDefault=none", "ReturnToService=2", "MailProg=/bin/true",
            "NodeName=fhrnode NodeAddr=127.0.0.1 CPUs=%d State=UNKNOWN" % os.cpu_count(),
            "PartitionName=fhr Nodes=fhrnode Default=YES MaxTime=INFINITE State=UP", ""]))
        subprocess.run(["slurmctld", "-f", self.conf], check=True, capture_output=True, env=self.env)
        subprocess.run(["slurmd", "-f", self.conf, "-N", "fhrnode"], check=True, capture_output=True, env=self.env)
        deadline = time.monotonic() + 60
        while run(["sinfo", "--noheader", "--format=%T"], env=self.env).stdout.strip() not in ("idle", "mixed"):
            if time.monotonic() > deadline:
                pytest.fail("the test's Slurm did not come up: see %s" % (f / "log"))
            time.sleep(0.5)

    def stop(self):
        """Cancels every job and ends the three daemons (SIGTERM, then SIGKILL after 20 s)."""
        run(["scancel", "--quiet", "--user=root"], env=self.env)
        for pid_file in self.pids:
            if not pid_file.exists():
                continue
            pid = int(pid_file.read_text().split()[0])
            try:
                os.kill(pid, signal.SIGTERM)
            except ProcessLookupError:
                continue
            deadline = time.monotonic() + 20
            while time.monotonic() < deadline and Path("/proc/%d" % pid).exists():
                time.sleep(0.1)
            if Path("/proc/%d" % pid).exists():
                os.kill(pid, signal.SIGKILL)

    def wait_until_empty(self, job, timeout=300):
        deadline = time.monotonic() + timeout
        while run(["squeue", "--noheader", "--jobs", job], env=self.env).stdout.strip():
            if time.monotonic() > deadline:
                pytest.fail("job %s did not end within %d s" % (job, timeout))
            time.sleep(0.5)


@pytest.fixture
def cluster(tmp_path):
    missing = [p for p in ("munged", "mungekey", "slurmctld", "slurmd", "sbatch") if shutil.which(p) is None]
    if missing:
        pytest.fail("slurm-wlm and munge must be installed (./run installs them): %s not found" % ", ".join(missing))
    if os.geteuid() != 0:
        pytest.fail("the throwaway Slurm runs its daemons as root; run the tests as root")
    c = Cluster(tmp_path / "slurm")
    try:
        c.start()
        yield c
    finally:
        c.stop()
        shutil.rmtree(tmp_path / "slurm", ignore_errors=True)


def shard_script(folder, cancelled=None):
    """The job array's script: shard $SLURM_ARRAY_TASK_ID of SHARDS into shard-K.tsv; shard `cancelled`
    first waits long enough to be cancelled while it runs."""
    wait = 'if [ "$SLURM_ARRAY_TASK_ID" = %d ]; then sleep 300; fi\n' % cancelled if cancelled else ""
    script = folder / "shard.sh"
    script.write_text("#!/bin/sh\n" + wait + "exec %s %s --shard \"$SLURM_ARRAY_TASK_ID/%d\" --table shard-$SLURM_ARRAY_TASK_ID.tsv\n"
                      % (FHR, " ".join("'%s'" % a for a in CAMPAIGN), SHARDS))
    return script


def test_a_slurm_job_array_gives_the_unsharded_table(cluster, tmp_path):
    work = tmp_path / "work"
    work.mkdir()
    whole = run([FHR, *CAMPAIGN, "--table", work / "whole.tsv"], cwd=work)
    assert whole.returncode in (0, 1), whole.stderr
    submitted = run(["sbatch", "--array=1-%d" % SHARDS, "--wait", "--chdir", work, "--output", work / "out-%a.txt",
                     shard_script(work)], env=cluster.env, timeout=600)
    assert submitted.returncode == whole.returncode, submitted.stdout + submitted.stderr  # a shard with failures exits 1
    assert sorted(p.name for p in work.glob("shard-*.tsv")) == ["shard-%d.tsv" % k for k in range(1, SHARDS + 1)]
    merged = run([FHR, "oracle-fuzz", "--merge", *sorted(work.glob("shard-*.tsv")), "--table", work / "merged.tsv"])
    assert merged.returncode == whole.returncode, merged.stderr
    assert (work / "merged.tsv").read_bytes() == (work / "whole.tsv").read_bytes()
    rows = (work / "whole.tsv").read_text().splitlines()[14:]
    assert len(rows) == 8 and all(row.split("\t")[7].startswith("l2 ") for row in rows)  # the maps' distortion
    assert merged.stdout.splitlines()[-1] == whole.stdout.splitlines()[-1] == "8 meshes, 0 failures"


def test_a_cancelled_shard_is_named_by_the_merge(cluster, tmp_path):
    work = tmp_path / "work"
    work.mkdir()
    submitted = run(["sbatch", "--parsable", "--array=1-%d" % SHARDS, "--chdir", work, "--output", work / "out-%a.txt",
                     shard_script(work, cancelled=3)], env=cluster.env)
    assert submitted.returncode == 0, submitted.stderr
    job = submitted.stdout.strip().split(";")[0]
    deadline = time.monotonic() + 120
    while run(["squeue", "--noheader", "--format=%T", "--jobs", "%s_3" % job], env=cluster.env).stdout.strip() != "RUNNING":
        assert time.monotonic() < deadline, "shard 3 never ran"
        time.sleep(0.5)
    assert run(["scancel", "%s_3" % job], env=cluster.env).returncode == 0
    cluster.wait_until_empty(job)
    assert not (work / "shard-3.tsv").exists()
    merged = run([FHR, "oracle-fuzz", "--merge", *sorted(work.glob("shard-*.tsv"))])
    assert merged.returncode == 2
    assert merged.stderr.count("\n") == 1 and "shard 3/4 is missing" in merged.stderr
