"""What the MeshLab adapters in peers/ (meshlab-iso, meshlab-trivial, meshlab-flat,
meshlab-voronoi) share: the command line `peers/NAME [OPTIONS] MESH OUT`, the .mlx filter script,
one run of Debian's MeshLab 2020.09 `meshlabserver` headless under `xvfb-run -a`, the check of the
atlas it writes and the exit code that says what happened.

Each run works in a fresh temporary folder: the filter script is written there, then
`xvfb-run -a meshlabserver -i MESH -o TMP/out.obj -l x -m wt -s TMP/script.mlx` runs with
OMP_NUM_THREADS=1, a 4 GiB address-space limit on every process it starts and a time limit
(FHR_PEER_TIMEOUT seconds, default 300, for the whole adapter) in a process group of its own,
killed whole when the time is up. `-l x` saves the last layer (the filters that build a new mesh
add it as the last layer; the others change the only one), `-m wt` writes per-wedge texture
coordinates: the OBJ has `vt` lines and faces `f a/t b/t c/t`. MeshLab's OBJ writer prints every
number with six decimals. Only that OBJ reaches OUT, byte for byte as MeshLab wrote it (its
`mtllib` line names a .mtl that is not kept); it is copied to a temporary name beside OUT and
renamed, so OUT is complete or untouched.

The adapter's exit codes:
  0    OUT written: an OBJ with at least one face, every face corner with a `vt`
  2    usage error, or MESH missing, unreadable or not a mesh MeshLab reads
       (one line `NAME: error: ...`)
  3    not applicable: the filter refuses the mesh's topology or size (the line says which)
  4    MeshLab ran but left no usable atlas: no output file, no faces, a corner without `vt`, or
       a filter that failed without a reason tied to the mesh
  124  FHR_PEER_TIMEOUT seconds passed
  127  meshlabserver, xvfb-run or xauth is not installed (`./run` installs meshlab, xvfb, xauth)
  other  meshlabserver's own exit code, 128 + N when signal N ended it (the line names the signal
       and, for a failed assertion, the assertion)
Every failure prints one line on stderr.

MESH is any format meshlabserver reads by its extension (OFF, PLY, STL, ...). Debian's
meshlabserver 2020.09 aborts on every OBJ it reads, so an OBJ MESH is handed to it as an OFF copy
of its vertices and faces.

meshlabserver 2020.09 prints a filter's log but not its error message, so a refusal is named
from MeshLab's "Compute Topological Measures" filter, run first by the adapters that ask for it
(`probe=True`): vertices, edges, faces, boundary edges, connected components, manifoldness and
genus, in MeshLab's own words."""

import os
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from dataclasses import dataclass, field
from typing import Callable, List, Optional, Sequence, Tuple
from xml.sax.saxutils import quoteattr

MEMORY_LIMIT = 4 << 30          # bytes of address space for each process of a run
DEFAULT_TIMEOUT = 300.0         # seconds, when FHR_PEER_TIMEOUT is not set
MESHLAB_VERSION = "Debian's meshlab 2020.09 (meshlabserver)"

EXIT_OK, EXIT_USAGE, EXIT_NOT_APPLICABLE, EXIT_NO_ATLAS = 0, 2, 3, 4
EXIT_TIMEOUT, EXIT_MISSING = 124, 127


# --- filter scripts -------------------------------------------------------------------------

@dataclass
class Param:
    """One <Param> of a MeshLab filter script: its type as MeshLab names it (RichInt, RichBool,
    RichFloat, RichEnum, RichDynamicFloat, RichString), its name, value and extra attributes."""
    kind: str
    name: str
    value: str
    extra: Tuple[Tuple[str, str], ...] = ()

    def xml(self) -> str:
        attrs = [("type", self.kind), ("name", self.name), ("value", self.value)] + list(self.extra)
        return "<Param " + " ".join(f"{k}={quoteattr(v)}" for k, v in attrs) + "/>"


def Int(name: str, value: int) -> Param:
    return Param("RichInt", name, str(int(value)))


def Bool(name: str, value: bool) -> Param:
    return Param("RichBool", name, "true" if value else "false")


def Float(name: str, value: float) -> Param:
    return Param("RichFloat", name, repr(float(value)))


def String(name: str, value: str) -> Param:
    return Param("RichString", name, value)


def Enum(name: str, value: int, choices: Sequence[str]) -> Param:
    extra = [("enum_cardinality", str(len(choices)))]
    extra += [(f"enum_val{i}", c) for i, c in enumerate(choices)]
    return Param("RichEnum", name, str(value), tuple(extra))


def DynamicFloat(name: str, value: float, low: float, high: float) -> Param:
    return Param("RichDynamicFloat", name, repr(float(value)),
                 (("min", repr(float(low))), ("max", repr(float(high)))))


@dataclass
class Filter:
    """A MeshLab filter by its exact name, with the values the adapter gives its parameters."""
    name: str
    params: List[Param] = field(default_factory=list)

    def xml(self) -> str:
        inner = "".join(f"\n  {p.xml()}" for p in self.params)
        return f" <filter name={quoteattr(self.name)}>{inner}\n </filter>"


def filter_script(filters: Sequence[Filter]) -> str:
    body = "\n".join(f.xml() for f in filters)
    return f"<!DOCTYPE FilterScript>\n<FilterScript>\n{body}\n</FilterScript>\n"


TOPOLOGY_FILTER = Filter("Compute Topological Measures")


# --- what MeshLab measures of the mesh ----------------------------------------------------

@dataclass
class Topology:
    """The mesh as "Compute Topological Measures" reports it (genus None when not manifold)."""
    vertices: int
    edges: int
    faces: int
    boundary_edges: int
    components: int
    nonmanifold_edges: int
    nonmanifold_vertices: int
    holes: Optional[int]
    genus: Optional[int]

    def describe(self) -> str:
        text = f"{self.faces} faces, {self.components} component(s), " \
               f"{self.boundary_edges} boundary edges"
        if self.genus is not None:
            text += f", genus {self.genus}"
        return text


def _first_int(pattern: str, text: str) -> Optional[int]:
    match = re.search(pattern, text)
    return int(match.group(1)) if match else None


def parse_topology(log: str) -> Optional[Topology]:
    vef = re.search(r"V:\s*(\d+)\s+E:\s*(\d+)\s+F:\s*(\d+)", log)
    if not vef:
        return None
    return Topology(
        vertices=int(vef.group(1)), edges=int(vef.group(2)), faces=int(vef.group(3)),
        boundary_edges=_first_int(r"Boundary Edges (\d+)", log) or 0,
        components=_first_int(r"composed by (\d+) connected component", log) or 0,
        nonmanifold_edges=_first_int(r"Mesh has (\d+) non two manifold edges", log) or 0,
        nonmanifold_vertices=_first_int(r"Mesh has (\d+) non two manifold vertices", log) or 0,
        holes=_first_int(r"Mesh has (\d+) holes", log),
        genus=_first_int(r"Genus is (-?\d+)", log))


# --- one meshlabserver run ------------------------------------------------------------------

class Failure(Exception):
    """Ends the adapter: an exit code and the one line that explains it."""

    def __init__(self, code: int, kind: str, message: str):
        super().__init__(message)
        self.code, self.kind, self.message = code, kind, message


@dataclass
class Run:
    returncode: int
    log: str


def _limit_child() -> None:
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))


def _kill_group(proc: subprocess.Popen) -> None:
    for sig in (signal.SIGTERM, signal.SIGKILL):
        try:
            os.killpg(proc.pid, sig)
        except ProcessLookupError:
            return
        try:
            proc.wait(timeout=3)
            return
        except subprocess.TimeoutExpired:
            continue


def run_meshlabserver(args: Sequence[str], workdir: str, deadline: float) -> Run:
    """`xvfb-run -a meshlabserver ARGS` in WORKDIR; stdout and stderr together in Run.log."""
    log_path = os.path.join(workdir, f"meshlab-{len(os.listdir(workdir))}.log")
    # TMPDIR: xvfb-run's own folder (its Xauthority) goes into WORKDIR and leaves with it
    env = dict(os.environ, OMP_NUM_THREADS="1", TMPDIR=workdir)
    env.setdefault("XDG_RUNTIME_DIR", workdir)
    with open(log_path, "wb") as log:
        proc = subprocess.Popen(["xvfb-run", "-a", "meshlabserver", *args], cwd=workdir, env=env,
                                stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                start_new_session=True, preexec_fn=_limit_child)
        try:
            proc.wait(timeout=max(0.0, deadline - time.monotonic()))
        except subprocess.TimeoutExpired:
            _kill_group(proc)
            raise Failure(EXIT_TIMEOUT, "timeout",
                          f"meshlabserver still running after {timeout_seconds():g} s "
                          "(FHR_PEER_TIMEOUT)") from None
        finally:
            try:    # whatever of the run's process group outlives xvfb-run (an Xvfb) ends too
                os.killpg(proc.pid, signal.SIGKILL)
            except (ProcessLookupError, PermissionError):
                pass
    with open(log_path, "rb") as log:
        text = log.read().decode("utf-8", "replace")
    code = proc.returncode
    return Run(128 - code if code < 0 else code, text)


def signal_name(code: int) -> str:
    try:
        return signal.Signals(code - 128).name
    except ValueError:
        return f"signal {code - 128}"


def crash_message(run: Run) -> str:
    """One line for a meshlabserver that MeshLab itself ended (signal or exit code)."""
    assertion = re.search(r"(\S+:\d+: .*Assertion .* failed\.)", run.log)
    if run.returncode > 128:
        text = f"meshlabserver died of {signal_name(run.returncode)} (exit {run.returncode})"
    else:
        text = f"meshlabserver exited with code {run.returncode}"
    if assertion:
        text += ": " + assertion.group(1)
    elif run.returncode <= 128:
        text += ": " + last_line(run.log)
    return text


def last_line(log: str) -> str:
    lines = [ln.strip() for ln in log.splitlines()
             if ln.strip() and not re.fullmatch(r"[\d.]+", ln.strip())]   # not progress numbers
    return lines[-1][:300] if lines else "no output"


def failed_filter(log: str) -> Optional[str]:
    match = re.search(r"Problem with filter: (.*)", log)
    return match.group(1).strip() if match else None


def load_failure(log: str) -> Optional[str]:
    """MeshLab's words when it could not read the input mesh, or read no face of it, else None."""
    loaded = re.search(r"Mesh (.*) loaded has (\d+) vn (\d+) fn", log)
    if loaded and int(loaded.group(3)) == 0:
        return f"it reads {loaded.group(2)} vertices and no face"
    for pattern in (r"Opening Error: .*?(?:Error details: )?([^\n]*)$",
                    r"Opening Failure: .*", r"It was not possible to (?:add|import) .*",
                    r"Unable to open file.*", r"MeshLabServer: Failed loading.*"):
        match = re.search(pattern, log, re.M)
        if match:
            return " ".join(match.group(0).split())[:300]
    return None


# --- the input ------------------------------------------------------------------------

def obj_as_off(path: str, off_path: str) -> None:
    """Debian's meshlab 2020.09 aborts on reading any OBJ (an assertion in vcglib's OBJ importer,
    Debian bug 1054006), so an OBJ MESH reaches MeshLab as OFF: its `v` lines (the first three
    numbers, as written) and `f` lines (the vertex of each corner, relative indices resolved), in
    their order; everything else (vt, vn, groups, materials) is left out."""
    vertices: List[str] = []
    faces: List[List[int]] = []
    with open(path, "r", encoding="utf-8", errors="replace") as obj:
        for number, line in enumerate(obj, 1):
            tokens = line.split()
            if not tokens:
                continue
            try:
                if tokens[0] == "v":
                    for t in tokens[1:4]:
                        float(t)
                    if len(tokens) < 4:
                        raise ValueError("a vertex with fewer than three coordinates")
                    vertices.append(" ".join(tokens[1:4]))
                elif tokens[0] == "f":
                    face = []
                    for corner in tokens[1:]:
                        i = int(corner.split("/")[0])
                        i = i - 1 if i > 0 else len(vertices) + i
                        if not 0 <= i < len(vertices):
                            raise ValueError(f"corner {corner} names no vertex")
                        face.append(i)
                    if len(face) < 3:
                        raise ValueError("a face with fewer than three corners")
                    faces.append(face)
            except ValueError as e:
                raise Failure(EXIT_USAGE, "error", f"cannot read {path} as OBJ: line {number}: "
                              f"{e}") from None
    if not faces:
        raise Failure(EXIT_USAGE, "error", f"cannot read {path} as OBJ: no face")
    with open(off_path, "w") as off:
        off.write(f"OFF\n{len(vertices)} {len(faces)} 0\n")
        off.writelines(v + "\n" for v in vertices)
        off.writelines(f"{len(f)} {' '.join(map(str, f))}\n" for f in faces)


def meshlab_input(mesh: str, workdir: str) -> str:
    """The path meshlabserver reads MESH from: MESH itself, or for an OBJ its OFF copy."""
    if mesh.lower().endswith(".obj"):
        off = os.path.join(workdir, "input.off")
        obj_as_off(mesh, off)
        return off
    return mesh


# --- the atlas --------------------------------------------------------------------------

@dataclass
class Atlas:
    vertices: int
    texcoords: int
    faces: int


def check_atlas(path: str) -> Atlas:
    """The OBJ at PATH has faces, and every corner of every face names a `vt` that exists."""
    if not os.path.isfile(path):
        raise Failure(EXIT_NO_ATLAS, "no atlas", "meshlabserver wrote no output file")
    v = vt = faces = 0
    with open(path, "r", encoding="utf-8", errors="replace") as obj:
        for number, line in enumerate(obj, 1):
            head, _, rest = line.partition(" ")
            if head == "v":
                v += 1
            elif head == "vt":
                vt += 1
            elif head == "f":
                faces += 1
                corners = rest.split()
                if len(corners) < 3:
                    raise Failure(EXIT_NO_ATLAS, "no atlas", f"line {number}: a face with "
                                  f"{len(corners)} corners")
                for corner in corners:
                    parts = corner.split("/")
                    if len(parts) < 2 or not parts[1]:
                        raise Failure(EXIT_NO_ATLAS, "no atlas",
                                      f"line {number}: face corner {corner!r} has no vt")
                    t = int(parts[1])
                    if not (1 <= t <= vt or -vt <= t <= -1):
                        raise Failure(EXIT_NO_ATLAS, "no atlas",
                                      f"line {number}: face corner {corner!r} names a missing vt")
    if faces == 0:
        raise Failure(EXIT_NO_ATLAS, "no atlas", "the output OBJ has no faces")
    return Atlas(v, vt, faces)


def publish(source: str, out: str) -> None:
    """Copy SOURCE to OUT through a temporary name beside OUT and a rename."""
    folder = os.path.dirname(os.path.abspath(out))
    fd, temp = tempfile.mkstemp(prefix="." + os.path.basename(out) + ".", suffix=".tmp",
                                dir=folder)
    try:
        with os.fdopen(fd, "wb") as dst, open(source, "rb") as src:
            shutil.copyfileobj(src, dst)
        os.chmod(temp, 0o644)
        os.replace(temp, out)
    except BaseException:
        if os.path.exists(temp):
            os.unlink(temp)
        raise


# --- the adapter ------------------------------------------------------------------------

def timeout_seconds() -> float:
    text = os.environ.get("FHR_PEER_TIMEOUT", "")
    if not text:
        return DEFAULT_TIMEOUT
    try:
        value = float(text)
    except ValueError:
        value = -1.0
    if not value > 0:
        raise Failure(EXIT_USAGE, "error", f"FHR_PEER_TIMEOUT={text!r} is not a positive number")
    return value


@dataclass
class Adapter:
    """One adapter: its name, what --help says, its own options (flag -> help line), the filters
    for a mesh (given the options and, with probe=True, MeshLab's topology of the mesh) and the
    reason a failed filter refused the mesh (None: no reason tied to the mesh)."""
    name: str
    summary: str
    filters: Callable[[dict, Optional[Topology]], List[Filter]]
    filters_help: str
    options: dict = field(default_factory=dict)
    probe: bool = False
    refusal: Callable[[str, Run, Optional[Topology], List[Filter]], Optional[str]] = \
        lambda filter_name, run, topo, filters: None
    writes: str = ""


def usage(adapter: Adapter) -> str:
    def fill(text: str) -> str:
        return textwrap.fill(text, width=96)

    opts = "".join(f" [{flag} VALUE]" for flag in adapter.options)
    lines = [f"usage: {adapter.name}{opts} MESH OUT.obj", f"       {adapter.name} --help", "",
             fill(adapter.summary), "",
             "Runs, in a fresh temporary folder:",
             "  OMP_NUM_THREADS=1 xvfb-run -a meshlabserver -i MESH -o TMP/out.obj -l x -m wt "
             "-s TMP/script.mlx",
             fill(f"with {MESHLAB_VERSION}, a 4 GiB address-space limit per process and a time "
                  f"limit of FHR_PEER_TIMEOUT seconds (default {DEFAULT_TIMEOUT:g}) for the "
                  "whole adapter."), "",
             "Filters and parameters:", adapter.filters_help]
    if adapter.options:
        lines += ["", "Options:"] + [f"  {flag} VALUE  {text}" for flag, text in adapter.options.items()]
    lines += ["", "Writes:", adapter.writes,
              "MESH: any format meshlabserver reads by its extension (OFF, PLY, STL, ...), and OBJ",
              "  (handed to MeshLab as OFF: Debian's meshlabserver 2020.09 aborts on reading OBJ).", "",
              fill("Exit codes: 0 OUT written; 2 usage error or unreadable MESH; 3 not applicable "
                   "(MeshLab refuses the mesh's topology or size); 4 no usable atlas; 124 "
                   "timeout; 127 meshlabserver, xvfb-run or xauth missing (./run installs them); "
                   "otherwise meshlabserver's exit code (128 + N for signal N). A failure prints "
                   "one line on stderr.")]
    return "\n".join(lines)


def parse_args(adapter: Adapter, argv: Sequence[str]) -> Tuple[dict, str, str]:
    options: dict = {}
    positional: List[str] = []
    i = 0
    while i < len(argv):
        arg = argv[i]
        if arg in adapter.options:
            if i + 1 >= len(argv):
                raise Failure(EXIT_USAGE, "error", f"{arg} needs a value")
            options[arg] = argv[i + 1]
            i += 2
            continue
        if arg == "--":
            positional += argv[i + 1:]
            break
        if arg.startswith("-") and len(arg) > 1:
            raise Failure(EXIT_USAGE, "error", f"unknown option {arg} (see --help)")
        positional.append(arg)
        i += 1
    if len(positional) != 2:
        raise Failure(EXIT_USAGE, "error", f"expected MESH and OUT, got {len(positional)} "
                      "argument(s) (see --help)")
    mesh, out = positional
    if not os.path.exists(mesh):
        raise Failure(EXIT_USAGE, "error", f"cannot read {mesh}: no such file")
    if not os.path.isfile(mesh):
        raise Failure(EXIT_USAGE, "error", f"cannot read {mesh}: not a regular file")
    try:
        with open(mesh, "rb") as f:
            f.read(1)
    except OSError as e:
        raise Failure(EXIT_USAGE, "error", f"cannot read {mesh}: {e.strerror}") from None
    if not out.lower().endswith(".obj"):
        raise Failure(EXIT_USAGE, "error", f"OUT must be an .obj path, got {out}")
    if os.path.isdir(out):
        raise Failure(EXIT_USAGE, "error", f"OUT {out} is a folder")
    folder = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(folder):
        raise Failure(EXIT_USAGE, "error", f"the folder of {out} does not exist")
    return options, os.path.abspath(mesh), out


def _run(adapter: Adapter, argv: Sequence[str]) -> int:
    if any(a in ("-h", "--help") for a in argv):
        print(usage(adapter))
        return EXIT_OK
    options, mesh, out = parse_args(adapter, argv)
    deadline = time.monotonic() + timeout_seconds()
    for tool in ("meshlabserver", "xvfb-run", "xauth"):
        if shutil.which(tool) is None:
            raise Failure(EXIT_MISSING, "error", f"{tool} not found: ./run installs Debian's "
                          "meshlab, xvfb and xauth")
    with tempfile.TemporaryDirectory(prefix=adapter.name + "-") as tmp:
        source = meshlab_input(mesh, tmp)
        topo = None
        if adapter.probe:
            probe_script = os.path.join(tmp, "probe.mlx")
            with open(probe_script, "w") as f:
                f.write(filter_script([TOPOLOGY_FILTER]))
            run = run_meshlabserver(["-i", source, "-s", probe_script], tmp, deadline)
            reason = load_failure(run.log)
            if reason:
                raise Failure(EXIT_USAGE, "error", f"MeshLab cannot read {mesh}: {reason}")
            if run.returncode != 0:
                raise Failure(run.returncode, "failed", "measuring the mesh: " + crash_message(run))
            topo = parse_topology(run.log)
            if topo is None:
                raise Failure(EXIT_NO_ATLAS, "no atlas", "MeshLab's topological measures are "
                              "missing from its log: " + last_line(run.log))
        filters = adapter.filters(options, topo)
        script = os.path.join(tmp, "script.mlx")
        with open(script, "w") as f:
            f.write(filter_script(filters))
        result = os.path.join(tmp, "out.obj")
        run = run_meshlabserver(["-i", source, "-o", result, "-l", "x", "-m", "wt", "-s", script],
                                tmp, deadline)
        reason = load_failure(run.log)
        if reason:
            raise Failure(EXIT_USAGE, "error", f"MeshLab cannot read {mesh}: {reason}")
        if "Xvfb failed to start" in run.log:
            raise Failure(run.returncode or 1, "failed", "xvfb-run: Xvfb failed to start")
        name = failed_filter(run.log)
        if name is not None:
            why = adapter.refusal(name, run, topo, filters)
            if why:
                raise Failure(EXIT_NOT_APPLICABLE, "not applicable", why)
            raise Failure(EXIT_NO_ATLAS, "no atlas",
                          f'MeshLab\'s filter "{name}" failed (meshlabserver prints no reason)'
                          + (f"; the mesh: {topo.describe()}" if topo else ""))
        if run.returncode != 0:
            raise Failure(run.returncode, "failed", crash_message(run))
        if "has NOT been saved" in run.log:
            raise Failure(EXIT_NO_ATLAS, "no atlas", last_line(run.log))
        check_atlas(result)
        publish(result, out)
    return EXIT_OK


def main(adapter: Adapter, argv: Optional[Sequence[str]] = None) -> int:
    try:
        return _run(adapter, sys.argv[1:] if argv is None else argv)
    except Failure as failure:
        print(f"{adapter.name}: {failure.kind}: {failure.message}", file=sys.stderr)
        return failure.code
    except KeyboardInterrupt:
        print(f"{adapter.name}: failed: interrupted", file=sys.stderr)
        return 130
