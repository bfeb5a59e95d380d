"""`fhr run` at default settings, then `fhr verify --mesh`, on one mesh: what `./run corpus`
(run_corpus.py) and `./run families` (run_families.py) do to each of their meshes.

Domain size rule, N = the --faces given to `fhr run`:
- closed and connected: N = F/100 rounded down to even, at most 1000, at least
  max(24, 2·min_closed_faces(genus)) (twice the fewest faces of a closed surface of that genus),
  and at most F (then D = T). `fhr run` delivers exactly N.
- with boundary or several components: N = F/100 rounded down to even, at most 1000, at least 24,
  at most F. Only totals (genus, loops, components) are given, so the per-component minima are
  left to §2 (domain::component_targets): it shares N among the components by area and raises
  each share to the least its topology allows (min_closed_faces(g) closed, 5b + 4g − 4 with b
  loops), and a component with boundary stops above its share when its loops and boundary corners
  need more faces. Then D has more than N faces, as `fhr run` says on its `domain: V vertices,
  F faces` line (report.json: domain.faces_requested is §2's D); the table shows `N -> F (§2: M)`
  and that run is fine. §3 must keep §2's D: domain.faces = domain.faces_requested.
When §2 cannot reach N under its validity rules it says `decimation stopped at K faces` and names
a request that succeeds, `ask for more faces (--faces K' succeeds)` (DOM-9); the run is then repeated
with --faces K' (noted in the row), up to `attempts` runs in all. Asking for K itself would not do:
with several components K's shares differ from N's, so §2 could stop again.
A mesh is certified when `fhr run` exits 0 and `fhr verify --mesh` accepts its param.fhrp; its
row's failure is also set (the mesh then counts as failed) when §3 changed §2's domain, or §2 gave
a closed connected mesh another size than N."""
import json
import math
import os
import re
import subprocess
import time

# Runs of `fhr run` per mesh: the first, then one per `decimation stopped at K faces` (module doc).
attempts = 4


def info(fhr, path):
    """`fhr info --json PATH` as a dict, or None when fhr cannot read it."""
    proc = subprocess.run([fhr, "info", "--json", path], capture_output=True, text=True)
    try:
        return json.loads(proc.stdout)
    except json.JSONDecodeError:
        return None


def min_closed_faces(genus):
    """domain::min_closed_faces: F = 2(V − χ), V from Heawood's bound (10 for genus 2)."""
    v = 10 if genus == 2 else math.ceil((7 + math.sqrt(1 + 48 * genus)) / 2)
    return 2 * (v - (2 - 2 * genus))


def domain_faces(faces, genus, closed_connected):
    n = min(faces // 100 // 2 * 2, 1000)
    least = max(24, 2 * min_closed_faces(genus)) if closed_connected else 24
    return min(max(n, least), faces)


def error_line(stderr):
    lines = [l for l in stderr.splitlines() if l.startswith("fhr: error") or l.startswith("fhr: internal")]
    return lines[-1] if lines else (stderr.strip().splitlines() or ["(no message)"])[-1]


def certify(fhr, path, out, faces, genus, loops, components, timeout):
    """Runs `fhr run path --faces N --out out` (N by the rule above; its progress lines to
    out.stderr) and `fhr verify`; the row: the mesh's sizes, domain faces requested, delivered by
    §2 and final, §3 retries, edges that are exact geodesics / restricted paths / boundary arcs,
    certified, seconds, a note, and the failure (None when there is none)."""
    closed_connected = loops == 0 and components == 1
    target = domain_faces(faces, genus, closed_connected)
    row = {"mesh": os.path.basename(path), "genus": genus, "loops": loops, "components": components, "faces": faces,
           "requested": target, "delivered": "-", "final": "-", "retries": "-", "curves": "-", "certified": False,
           "seconds": 0.0, "note": "", "failure": None, "closed_connected": closed_connected}
    start = time.monotonic()
    for attempt in range(attempts):
        try:
            proc = subprocess.run([fhr, "run", path, "--faces", str(target), "--out", out], capture_output=True,
                                  text=True, errors="replace", timeout=timeout)
            code, stderr = proc.returncode, proc.stderr
        except subprocess.TimeoutExpired as e:  # e.stderr: what it printed before it was killed
            partial = e.stderr.decode(errors="replace") if isinstance(e.stderr, bytes) else (e.stderr or "")
            code, stderr = -1, partial + "timed out after %g s\n" % timeout
        stopped = re.search(r"decimation stopped at (\d+) faces", stderr)
        if code == 2 and stopped and attempt + 1 < attempts:
            # The request the message names as reached (DOM-9); with several components the count
            # where §2 stopped, asked for again, may stop once more (its shares differ).
            named = re.search(r"ask for more faces \(--faces (\d+) succeeds\)", stderr)
            row["note"] = (row["note"] + "; " if row["note"] else "") + "§2 stopped at %s, not %d" % (stopped.group(1), target)
            target = int(named.group(1) if named else stopped.group(1))
            row["requested"] = target
            continue
        break
    row["seconds"] = time.monotonic() - start
    with open(out + ".stderr", "w") as f:  # fhr run's progress and error lines, for the failures
        f.write(stderr)
    report = os.path.join(out, "report.json")
    if os.path.exists(report) and code in (0, 4):
        with open(report) as f:
            r = json.load(f)
        d, p = r["domain"], r["partition"]
        row["delivered"], row["final"], row["retries"] = d["faces_requested"], d["faces"], d["retries"]
        row["curves"] = "%d / %d / %d / %d" % (p["geodesic_edges"], p["restricted_edges"], p["boundary_edges"],
                                               p["straightened_edges"])
        dist = r["parameterization"].get("distortion")  # spec/distortion.md, as fhr verify measures it
        if dist:
            row["distortion"] = {"l2": dist["l2_stretch"], "p50": dist["anisotropy"]["p50"], "p99": dist["anisotropy"]["p99"],
                                 "p999": dist["anisotropy"]["p999"], "max": dist["anisotropy"]["max"],
                                 "above_10": dist["anisotropy"]["above_10"], "faces": p["refined_faces"]}
    if code == -1:
        progress = stderr.splitlines()[:-1]
        row["failure"] = "fhr run timed out after %g s; its last line: %s" % (timeout, progress[-1] if progress else "-")
        return row
    if code != 0:
        row["failure"] = "fhr run exit %d: %s" % (code, error_line(stderr))
        return row
    verify = subprocess.run([fhr, "verify", os.path.join(out, "param.fhrp"), "--mesh", path], capture_output=True,
                            text=True, errors="replace")
    if verify.returncode != 0:
        row["failure"] = "fhr verify exit %d: %s" % (verify.returncode,
                                                     (verify.stdout.splitlines() or [error_line(verify.stderr)])[0])
        return row
    row["certified"] = True
    if row["final"] != row["delivered"]:
        row["failure"] = "§3 changed the domain: §2 gave %s faces, the partition has %s" % (row["delivered"], row["final"])
    elif closed_connected and row["delivered"] != target:
        row["failure"] = "§2 gave %s faces, not the %d requested" % (row["delivered"], target)
    return row


def kept(row):
    """§3 kept §2's domain, and §2 gave exactly N on a closed connected mesh."""
    return row["final"] == row["delivered"] and (not row["closed_connected"] or row["delivered"] == row["requested"])
