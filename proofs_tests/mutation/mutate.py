#!/usr/bin/env python3
"""`./run mutate [N] [--seed S] [--files GLOB]...`: mutation testing of fhr
(paper_notes/testing.md).

A mutant changes one operator or one constant on one line of src/. It is *caught* when a test
fails on it (or crashes, or runs past its time limit), *survives* when every test that could see
it passes, and is *stillborn* when it does not compile. A surviving mutant is code that no test
guards, unless it is *equivalent*: no program can tell it from the original (the reviewed list
proofs_tests/mutation/equivalent.txt, each entry with its reason). The score is
caught / (caught + survived); stillborn and equivalent mutants do not count.

How a campaign runs (paper_notes/testing.md, "Mutation testing"):
1. The working tree (git's tracked and untracked, not ignored files) is mirrored into
   build-mutate/tree; only files whose contents changed are copied, so the mirror's build
   (build-mutate/tree/build, release like build/, through ccache) stays incremental. Mutants are
   applied to the mirror, never to the working tree: one may edit and test while a campaign runs.
2. Every mutation site of the selected files is listed (operators below; comments, strings and
   preprocessor lines are skipped) and N of them are drawn: those whose hash of (S, the mutant's
   identity) is lowest. The same seed and sources give the same mutants, and an edit of src/
   changes the draw only by the mutants it adds or removes.
3. The unmutated mirror is built and the suites the sample needs must pass on it (each is run
   again only when its programs or the tree's scripts and data changed since it last passed);
   their times set the per-suite time limits (5 x the time + 300 s: generous, since the load of a
   shared machine varies, and a mutant that loops is caught all the same).
4. Each mutant: write it into the mirror's copy of the file, build only the test programs of
   the suites that can see it (ninja: one compile, the links), run those suites one by one,
   the mutated folder's own first, each stopping at its first failure (Catch2 -a, pytest -x),
   and stop at the first suite that fails. The original file is written back after every
   mutant, also on Ctrl-C or any error.
5. A table of every mutant (file:line, operator, the change, the result, what caught it) is
   printed and written to out/mutate/report-N-seed-S.md (and .json). A mutant judged by an
   earlier campaign keeps its verdict while neither its file nor the suites that judged it
   changed (build-mutate/verdicts.json): a second campaign re-runs only what an edit affects.

Operators, each applied to one token of one line:
  boundary   <  <=  >  >=   each to its neighbour with or without equality (< to <=, <= to <, ...)
  negate     <  >=,  >  <=,  ==  !=   each to its negation (both ways)
  arith      +  -,  *  /   (binary: spaced on both sides), and  +=  -=,  *=  /=; not + or - on a
             line with a string literal, where + mostly joins strings (- would not compile)
  logic      &&  ||,  and a unary ! removed
  constant   an integer literal n to n + 1; a floating literal x to 2x (0.0 to 1.0)
Binary operators are recognised by the surrounding spaces of the project's formatting, which keeps
template brackets (vector<int>), pointers (T* p), references (T&& x) and unary minus out; literals
inside template arguments (std::array<double, 3>) are skipped.

Which suites see a mutant: a mutant of src/fhr/F is seen by F's suite and by the suites of every
folder whose library depends on F (src/meson.build), the `fhr` command's (cli, reference-*) and the
Python package's (python), which link everything. library-* (configure, install) and the Python
package's PY-7 (pip install of a wheel) are packaging checks that rebuild fhr from a fresh copy,
and lint-* reads the tree's text, not fhr's behaviour: never run on mutants.

Usage: mutate.py [N] [--seed S] [--files GLOB]... [--list]
       mutate.py --at FILE:LINE...   every mutant of those lines (to look at one survivor)"""
import argparse
import fnmatch
import hashlib
import json
import os
import re
import shutil
import signal
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
WORK = os.path.join(ROOT, "build-mutate")
TREE = os.path.join(WORK, "tree")
BUILD = os.path.join(TREE, "build")
EQUIVALENT = os.path.join(ROOT, "proofs_tests", "mutation", "equivalent.txt")
OUT = os.path.join(ROOT, "out", "mutate")
MESHES = {"FHR_CGAL_MESHES": os.path.join(ROOT, "out", "cgal-data", "data", "meshes"),
          "FHR_SHARED_MESHES": os.path.join(os.path.dirname(ROOT), "shared", "meshes")}
# Implementation files; headers are opt-in (--files 'src/fhr/**/*.hpp'): a header's mutant
# rebuilds every file that includes it. src/fhr/testing holds the tests' own generators, and
# src/python's bindings take minutes to compile per mutant.
DEFAULT_FILES = ["src/fhr/*/*.cpp", "src/fhr/*/*/*.cpp", "src/cli/*.cpp"]
# src/meson.build: the libraries each one uses. cli (the fhr command) and python (the module on
# libfhr) use all of them.
LIBRARY_DEPS = {
    "core": [], "io": ["core"], "exchange": ["core", "io"], "generate": ["core"], "domain": ["core", "io"],
    "geodesic": ["core"], "param": ["core"], "partition": ["core", "domain", "geodesic", "param"],
    "render": ["core", "io"], "wavelet": ["core"],
    "pipeline": ["core", "io", "domain", "geodesic", "param", "partition", "exchange", "render", "wavelet"],
}
LIBRARY_DEPS["cli"] = LIBRARY_DEPS["python"] = sorted(LIBRARY_DEPS)
SUITE_LIMIT_FACTOR, SUITE_LIMIT_EXTRA, BUILD_LIMIT = 5.0, 300.0, 3600.0
RC_PARAMS = ""  # RapidCheck's settings for every run of a campaign: set from --seed in main()
LEFT_OUT = []   # "suite: test case" failing on the unmutated code, so left out (baseline)
# PY-7 builds and pip-installs a wheel from a fresh copy of the tree: a packaging check, like the
# library-* tests, not run on mutants.
PACKAGING_TESTS = ["proofs_tests/python/test_package.py"]


# ---- mutation sites --------------------------------------------------------------------------

@dataclass
class Mutant:
    path: str         # relative to the root
    line: int         # 1-based
    col: int          # 0-based offset of the token in the line
    operator: str     # boundary, negate, arith, logic, constant
    original: str
    replacement: str
    text: str         # the line, stripped
    occurrence: int = 1  # among this line's mutants with the same original and replacement
    copy: int = 1     # the line is the copy-th of the file's lines with this text
    result: str = ""  # caught, survived, stillborn, equivalent, timeout (caught by the time limit)
    by: str = ""
    seconds: float = 0.0
    reused: bool = False  # the verdict of an earlier campaign on the same file and suites
    reason: str = field(default="", repr=False)

    def key(self):
        """The mutant's identity: not its line number, which edits elsewhere in the file change."""
        copy = (self.copy,) if self.copy > 1 else ()
        return (self.path, self.text, self.original, self.replacement, self.occurrence) + copy

    def where(self):
        return "%s:%d" % (self.path, self.line)


def code_only(lines):
    """Each line with comments and the insides of string and character literals blanked to
    spaces (same length)."""
    out, in_block = [], False
    for line in lines:
        chars, i, n = list(line), 0, len(line)
        while i < n:
            if in_block:
                end = line.find("*/", i)
                stop = n if end < 0 else end + 2
                chars[i:stop] = " " * (stop - i)
                in_block, i = end < 0, stop
            elif line.startswith("//", i):
                chars[i:] = " " * (n - i)
                break
            elif line.startswith("/*", i):
                in_block = True
            elif line[i] == '"' or (line[i] == "'" and not (i > 0 and line[i - 1].isalnum())):
                # a string or a character literal (a ' after a digit is a digit separator)
                quote, j = line[i], i + 1
                while j < n and line[j] != quote:
                    j += 2 if line[j] == "\\" else 1
                stop = min(j + 1, n)
                chars[i + 1:stop - 1] = " " * max(0, stop - i - 2)  # the quotes stay: see sites()
                i = stop
            else:
                i += 1
        out.append("".join(chars))
    return out


TOKEN = re.compile(r"<<=|>>=|<=>|->|<<|>>|<=|>=|==|!=|&&|\|\||\+\+|--|\+=|-=|\*=|/=|%=|&=|\|=|\^=|::|[-+*/<>!]")
BINARY = {
    "<": [("boundary", "<="), ("negate", ">=")], "<=": [("boundary", "<"), ("negate", ">")],
    ">": [("boundary", ">="), ("negate", "<=")], ">=": [("boundary", ">"), ("negate", "<")],
    "==": [("negate", "!=")], "!=": [("negate", "==")],
    "+": [("arith", "-")], "-": [("arith", "+")], "*": [("arith", "/")], "/": [("arith", "*")],
    "+=": [("arith", "-=")], "-=": [("arith", "+=")], "*=": [("arith", "/=")], "/=": [("arith", "*=")],
    "&&": [("logic", "||")], "||": [("logic", "&&")],
}
NUMBER = re.compile(r"(?<![\w.'])(\d[\d']*(\.\d*)?([eE][+-]?\d+)?|\.\d+([eE][+-]?\d+)?)([uUlLfF]*)(?![\w.'])")


def in_template_arguments(code, col):
    """True when position col lies inside <...> template brackets (an unspaced '<' after a name)."""
    depth = 0
    for i in range(col - 1, -1, -1):
        c = code[i]
        if c in ")]}" or (c == ">" and i > 0 and code[i - 1] not in " -"):  # not a > b, not p->x
            depth += 1
        elif c in "([{<":
            if depth:
                depth -= 1
            elif c == "<":
                return i > 0 and (code[i - 1].isalnum() or code[i - 1] == "_") and code[i + 1:i + 2] != " "
            else:
                return False
    return False


def nudged(literal):
    digits = literal.replace("'", "")
    if re.fullmatch(r"\d+", digits):
        if len(digits) > 1 and digits.startswith("0"):
            return None  # octal: left alone
        return str(int(digits) + 1)
    value = float(digits)
    return "1.0" if value == 0 else repr(2 * value)


def sites(path, text):
    lines = text.split("\n")
    found, copies = [], {}
    for number, (line, code) in enumerate(zip(lines, code_only(lines)), start=1):
        stripped = code.strip()
        if not stripped or stripped.startswith("#") or stripped.startswith("static_assert"):
            continue
        here = []
        for m in TOKEN.finditer(code):
            tok, a, b = m.group(), m.start(), m.end()
            if tok in BINARY and a > 0 and code[a - 1] == " " and code[b:b + 1] == " ":
                if tok in ("+", "-") and '"' in code:
                    continue  # + joins strings on such lines (a message): - would not compile
                here += [(a, op, tok, repl) for op, repl in BINARY[tok]]
            elif tok == "!" and code[b:b + 1] not in ("", " ", "="):
                here.append((a, "logic", "!", ""))
        for m in NUMBER.finditer(code):
            new = nudged(m.group(1))
            if new is not None and not in_template_arguments(code, m.start()):
                here.append((m.start(1), "constant", m.group(1), new))
        seen = {}
        copies[line.strip()] = copies.get(line.strip(), 0) + 1
        for col, op, orig, repl in sorted(here):
            seen[(orig, repl)] = seen.get((orig, repl), 0) + 1
            found.append(Mutant(path, number, col, op, orig, repl, line.strip(), seen[(orig, repl)], copies[line.strip()]))
    return found


def draw_rank(m, seed):
    """A mutant's place in the draw of seed S: a hash of S and the mutant's identity (file, line
    text, change, occurrence; not its line number). The N lowest are drawn, so an edit of src/
    changes the draw only where it adds or removes mutants, not everywhere after it."""
    return hashlib.sha256(repr((seed,) + m.key()).encode()).hexdigest()


def apply(text, m):
    lines = text.split("\n")
    line = lines[m.line - 1]
    assert line[m.col:m.col + len(m.original)] == m.original
    lines[m.line - 1] = line[:m.col] + m.replacement + line[m.col + len(m.original):]
    return "\n".join(lines)


def folder(path):
    parts = path.split("/")
    return parts[2] if parts[:2] == ["src", "fhr"] else parts[1]


# ---- the reviewed equivalent mutants -----------------------------------------------------------

def read_equivalents():
    """equivalent.txt: entries of `file:`, `line:` (the line, stripped), `mutant: ORIG -> REPL (K)`
    (K-th such change on the line), `copy: C` when the file has several such lines and it is the
    C-th (else the first), and `why:` (continued on more indented lines)."""
    entries, current = {}, None
    if not os.path.exists(EQUIVALENT):
        return entries

    def close():
        if current:
            missing = {"file", "line", "mutant", "why"} - set(current)
            if missing:
                sys.exit("equivalent.txt: an entry lacks %s: %s" % (", ".join(sorted(missing)), current))
            m = re.fullmatch(r"(\S*) -> (\S*) \((\d+)\)", current["mutant"])
            if not m:
                sys.exit("equivalent.txt: bad mutant %r (expected ORIG -> REPL (K))" % current["mutant"])
            copy = int(current.get("copy", "1"))
            entries[(current["file"], current["line"], m.group(1), m.group(2), int(m.group(3))) +
                    ((copy,) if copy > 1 else ())] = current["why"]

    last = None
    for raw in open(EQUIVALENT, encoding="utf-8"):
        line = raw.rstrip("\n")
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        m = re.match(r"(- )?(file|line|mutant|copy|why): ?(.*)$", line.strip())
        if m and (m.group(1) or current is not None):
            if m.group(1):
                close()
                current = {}
            current[m.group(2)] = m.group(3).strip()
            last = m.group(2)
        elif current is not None and last == "why":
            current["why"] += " " + line.strip()
        else:
            sys.exit("equivalent.txt: cannot read line %r" % line)
    close()
    return entries


def equivalent_entry(m):
    return "- file: %s\n  line: %s\n  mutant: %s -> %s (%d)\n%s  why: " % (
        m.path, m.text, m.original, m.replacement, m.occurrence, "  copy: %d\n" % m.copy if m.copy > 1 else "")


# ---- the mirror and its build -----------------------------------------------------------------

def working_files():
    listed = subprocess.run(["git", "-C", ROOT, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
                            check=True, capture_output=True).stdout.decode().split("\0")
    return sorted(p for p in set(listed) if p and os.path.isfile(os.path.join(ROOT, p)))


def sync_mirror():
    """Copies changed files into the mirror, removes the ones gone; returns a digest of the files
    other than C++ sources, notes and this runner (the scripts and data the suites read: see
    baseline)."""
    files = working_files()
    manifest = os.path.join(WORK, "mirrored.txt")
    before = set(open(manifest).read().split("\n")) - {""} if os.path.exists(manifest) else set()
    digest, copied = hashlib.sha256(), 0
    for rel in files:
        src, dst = os.path.join(ROOT, rel), os.path.join(TREE, rel)
        data = open(src, "rb").read()
        if not rel.endswith((".cpp", ".hpp", ".md")) and not rel.startswith("proofs_tests/mutation/"):
            digest.update(rel.encode() + b"\0" + hashlib.sha256(data).digest())
        if not os.path.exists(dst) or open(dst, "rb").read() != data:
            os.makedirs(os.path.dirname(dst), exist_ok=True)
            with open(dst, "wb") as f:  # a fresh mtime: ninja rebuilds what depends on it
                f.write(data)
            shutil.copymode(src, dst)
            copied += 1
    for rel in before - set(files):
        if os.path.exists(os.path.join(TREE, rel)):
            os.remove(os.path.join(TREE, rel))
    with open(manifest, "w") as f:
        f.write("\n".join(files) + "\n")
    print("mirror: %d files, %d copied" % (len(files), copied), flush=True)
    return digest.hexdigest()


def configure():
    """Configures the mirror's build, or reconfigures it when a meson.build changed, so that its
    introspection (the suites and their programs) is the tree's before anything is built."""
    if not os.path.exists(os.path.join(BUILD, "build.ninja")):
        print("configuring %s (release)" % BUILD, flush=True)
        subprocess.run(["meson", "setup", BUILD, TREE, "--buildtype=release"], check=True, stdout=subprocess.DEVNULL)
    else:
        code, out = run_limited(["ninja", "-C", BUILD, "build.ninja"], BUILD_LIMIT)
        if code != 0:
            sys.exit("the mirror's build does not configure:\n" + out[-3000:])


def introspect(what):
    return json.loads(subprocess.run(["meson", "introspect", BUILD, what], check=True, capture_output=True,
                                     text=True).stdout)


@dataclass
class Suite:
    name: str
    folder: str       # the src/ folder whose code it tests (its level in LIBRARY_DEPS)
    cmd: list
    env: dict
    workdir: str
    targets: list     # ninja targets it needs
    kind: str         # catch2, pytest or exit (judged by its exit code)
    seconds: float = 0.0
    left_out: list = field(default_factory=list)  # its test cases that fail on the unmutated code
    key: str = ""     # its programs, scripts, data and seed as they passed the baseline


def suites():
    targets = {t["id"]: t for t in introspect("--targets")}
    found = []
    for t in introspect("--tests"):
        name = t["name"]
        if name.startswith(("library-", "lint-")):
            continue
        cmd = list(t["cmd"])
        kind = "catch2" if os.path.basename(cmd[0]).startswith("test_") else \
            "pytest" if "pytest" in cmd else "exit"
        # pytest: the Python package's suite, or the campaign suite, which runs the fhr command and
        # bench/'s scripts (a cli-level suite).
        level = name if kind == "catch2" else "python" if name == "python" else "cli"
        needed = [os.path.relpath(f, BUILD) for d in t.get("depends") or [] for f in targets[d]["filename"]]
        if kind == "catch2":
            needed.append(os.path.relpath(cmd[0], BUILD))
        found.append(Suite(name, level, cmd, dict(t.get("env") or {}), t.get("workdir") or BUILD, needed, kind))
    return found


def users(lib):
    """The folders whose code uses lib's library, lib included."""
    def closure(f, seen):
        for d in LIBRARY_DEPS.get(f, []):
            if d not in seen:
                seen.add(d)
                closure(d, seen)
        return seen
    return {f for f in LIBRARY_DEPS if f == lib or lib in closure(f, set())}


def suites_for(m, all_suites):
    """The suites that can see mutant m, its own folder's first, then the fastest first."""
    own = folder(m.path)
    chosen = [s for s in all_suites if s.folder in users(own)]
    return sorted(chosen, key=lambda s: (s.folder != own, s.seconds))


def run_limited(cmd, limit, **kw):
    """Runs cmd in its own process group; returns (exit code or None on timeout, output)."""
    # SIGINT back to its default: a shell's background job ignores it, and the child would inherit
    # that (the Python suite interrupts itself on purpose).
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, start_new_session=True,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL), **kw)
    try:
        out, _ = proc.communicate(timeout=limit)
        return proc.returncode, out.decode(errors="replace")
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        out, _ = proc.communicate()
        return None, out.decode(errors="replace")
    except BaseException:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
        raise


def build(targets):
    return run_limited(["ninja", "-C", BUILD] + sorted(set(targets)), BUILD_LIMIT)


def run_suite(s, limit, first_failure, report=None):
    """Runs suite s; a Catch2 suite without the test cases left out, writing its XML report to
    `report` when given. RapidCheck's seed is the campaign's (RC_PARAMS): a property sees the same
    cases on the mutant as on the unmutated code, and a failure is the mutant's doing."""
    cmd = list(s.cmd)
    if s.kind == "catch2":
        cmd += ['~"%s"' % name.replace("\\", "\\\\").replace(",", "\\,").replace('"', '\\"') for name in s.left_out]
        cmd += ["-r", "xml", "-o", report] if report else []
        cmd += ["-a", "-r", "compact"] if first_failure else []
    elif s.kind == "pytest":
        for node in PACKAGING_TESTS + s.left_out:
            cmd += ["--deselect", node]
        cmd += ["-x"] if first_failure else []
    env = dict(os.environ, **MESHES, **s.env, RC_PARAMS=RC_PARAMS)
    return run_limited(cmd, limit, env=env, cwd=s.workdir)


def failing_cases(s, report):
    """The failed test cases of suite s's last run: Catch2's names from its XML report, pytest's
    node ids from its JUnit report; None when there is no report."""
    try:
        root = ET.parse(s.env["FHR_JUNIT_XML"] if s.kind == "pytest" else report).getroot()
    except (ET.ParseError, FileNotFoundError, KeyError):
        return None
    if s.kind == "pytest":
        failed = [c for c in root.iter("testcase") if c.find("failure") is not None or c.find("error") is not None]
        if any(not c.get("classname") for c in failed):
            return []  # a module that does not even import: no test case to leave out, the suite fails
        return ["%s.py::%s" % (c.get("classname").replace(".", "/"), c.get("name")) for c in failed]
    return [c.get("name") for c in root.iter("TestCase")
            if c.find("OverallResult") is not None and c.find("OverallResult").get("success") != "true"]


def first_failure_line(s, output):
    """What a failing suite says first: Catch2's compact `file:line: failed: ...`, pytest's FAILED."""
    for line in output.splitlines():
        if (s.kind == "catch2" and ": failed:" in line) or (s.kind == "pytest" and line.startswith("FAILED")):
            return line.strip()[:200]
    return ""


# ---- the campaign -----------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("count", nargs="?", type=int, default=100, help="mutants to draw (default 100)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--files", action="append", metavar="GLOB",
                        help="files to mutate, relative to the root (repeatable; default: %s)" % " ".join(DEFAULT_FILES))
    parser.add_argument("--at", action="append", metavar="FILE:LINE",
                        help="instead of a sample, every mutant of this line (repeatable): to look at one survivor")
    parser.add_argument("--list", action="store_true", help="print the drawn mutants and stop")
    args = parser.parse_args()
    globs = args.files or DEFAULT_FILES
    global RC_PARAMS
    RC_PARAMS = "seed=%d noshrink=1" % args.seed  # no shrinking: a mutant needs one failure, not the least
    if args.at:
        globs = [a.rsplit(":", 1)[0] for a in args.at]

    candidates = [p for p in working_files() if any(fnmatch.fnmatch(p, g) for g in globs)]
    if not candidates:
        sys.exit("no file matches %s" % " ".join(globs))
    everything = [m for p in candidates for m in sites(p, open(os.path.join(ROOT, p), encoding="utf-8").read())]
    if args.at:
        drawn = [m for m in everything if m.where() in args.at]
        print("%d mutants on %s" % (len(drawn), ", ".join(args.at)), flush=True)
    else:
        drawn = sorted(everything, key=lambda m: draw_rank(m, args.seed))[:args.count]
        print("%d mutation sites in %d files; %d drawn with seed %d" % (len(everything), len(candidates), len(drawn),
                                                                     args.seed), flush=True)
    drawn.sort(key=lambda m: (m.path, m.line, m.col, m.replacement))
    equivalents = read_equivalents()
    for m in drawn:
        if m.key() in equivalents:
            m.result, m.reason = "equivalent", equivalents[m.key()]
    if args.list:
        for i, m in enumerate(drawn, 1):
            print("%3d %-42s %-8s %s -> %s   %s" % (i, m.where(), m.operator, m.original, m.replacement or "(removed)",
                                                   m.text))
        return 0

    os.makedirs(TREE, exist_ok=True)
    digest = sync_mirror()
    configure()
    all_suites = suites()
    # In the order of the draw: the first n judged are the draw of `n --seed S`, whose verdicts a
    # later, smaller campaign takes from verdicts.json.
    todo = sorted((m for m in drawn if m.result != "equivalent"), key=lambda m: draw_rank(m, args.seed))
    needed = sorted({s.name: s for m in todo for s in suites_for(m, all_suites)}.values(), key=lambda s: s.name)
    baseline(needed, digest)

    os.makedirs(OUT, exist_ok=True)
    # A verdict is kept from an earlier campaign when neither the mutated file nor any suite that
    # judged it changed since (build-mutate/verdicts.json).
    verdicts_file = os.path.join(WORK, "verdicts.json")
    verdicts = json.load(open(verdicts_file)) if os.path.exists(verdicts_file) else {}
    start = time.monotonic()
    try:
        for i, m in enumerate(todo, 1):
            chosen = suites_for(m, all_suites)
            vkey = hashlib.sha256((repr(m.key()) + "".join(s.key for s in chosen)).encode() +
                                  open(os.path.join(TREE, m.path), "rb").read()).hexdigest()
            known = verdicts.get(repr(m.key()), {})
            if known.get("key") == vkey:
                m.result, m.by, m.seconds, m.reused = known["result"], known["by"], known["seconds"], True
            else:
                run_mutant(m, chosen)
                verdicts[repr(m.key())] = {"key": vkey, "result": m.result, "by": m.by, "seconds": round(m.seconds, 1)}
                with open(verdicts_file, "w") as f:
                    json.dump(verdicts, f, indent=1)
            print("[%d/%d] %-42s %-9s %s -> %-9s %-9s %6.0f s  %s%s" % (
                i, len(todo), m.where(), m.operator, m.original, m.replacement or "(removed)", m.result, m.seconds,
                "(earlier run) " if m.reused else "", m.by), flush=True)
    finally:
        report(drawn, args, time.monotonic() - start)
    return 0


def baseline(needed, digest):
    """Builds the unmutated mirror and runs each needed suite on it; their times set the time
    limits. A suite is run again only when its programs (their bytes), the tree's scripts and data
    (digest) or RapidCheck's seed changed since (build-mutate/baseline.json). A Catch2 test case
    that fails on the unmutated code cannot judge a mutant: it is left out of the mutants' runs and
    named in the report; any other failure stops the campaign."""
    cache = os.path.join(WORK, "baseline.json")
    known = json.load(open(cache)) if os.path.exists(cache) else {}
    code, out = build([t for s in needed for t in s.targets])
    if code != 0:
        sys.exit("the unmutated tree does not build:\n" + out[-3000:])
    for s in needed:
        key = hashlib.sha256((digest + RC_PARAMS).encode())
        for t in sorted(set(s.targets)):
            key.update(open(os.path.join(BUILD, t), "rb").read())
        key = key.hexdigest()
        if known.get(s.name, {}).get("key") != key:
            print("baseline: %s ..." % s.name, end=" ", flush=True)
            report = os.path.join(WORK, "baseline-%s.xml" % s.name)
            t0 = time.monotonic()
            code, out = run_suite(s, 3600, first_failure=False, report=report)
            failed = failing_cases(s, report) if s.kind != "exit" and code else []
            if code is None or failed is None or (code and not failed):
                sys.exit("the unmutated code fails %s (exit %s): fix it first\n%s" % (s.name, code, out[-3000:]))
            known[s.name] = {"key": key, "seconds": time.monotonic() - t0, "left_out": failed}
            print("%.1f s%s" % (known[s.name]["seconds"], "; fails on the unmutated code, left out: %s" % failed
                                if failed else ""), flush=True)
            with open(cache, "w") as f:
                json.dump(known, f, indent=1)
        s.seconds, s.left_out, s.key = known[s.name]["seconds"], known[s.name]["left_out"], key
        LEFT_OUT.extend("%s: %s" % (s.name, name) for name in s.left_out)


def run_mutant(m, chosen):
    path = os.path.join(TREE, m.path)
    original = open(path, encoding="utf-8").read()
    t0 = time.monotonic()
    try:
        with open(path, "w", encoding="utf-8") as f:
            f.write(apply(original, m))
        code, out = build([t for s in chosen for t in s.targets])
        if code != 0:
            m.result = "stillborn"
            m.by = "build timed out" if code is None else ""
            return
        m.result = "survived"
        for s in chosen:
            code, out = run_suite(s, SUITE_LIMIT_FACTOR * s.seconds + SUITE_LIMIT_EXTRA, first_failure=True)
            if code is None:
                m.result, m.by = "timeout", s.name
                return
            if code != 0:
                m.result = "caught"
                m.by = s.name + (": " + first_failure_line(s, out) if first_failure_line(s, out) else " (exit %d)" % code)
                return
    finally:
        with open(path, "w", encoding="utf-8") as f:
            f.write(original)
        m.seconds = time.monotonic() - t0


def report(drawn, args, seconds):
    counts = {r: sum(m.result == r for m in drawn) for r in ("caught", "timeout", "survived", "stillborn", "equivalent")}
    counts["not run"] = sum(not m.result for m in drawn)
    killed = counts["caught"] + counts["timeout"]
    scored = killed + counts["survived"]
    command = "".join(" --at %s" % a for a in args.at) if args.at else " %d --seed %d%s" % (
        args.count, args.seed, "".join(" --files '%s'" % g for g in args.files or []))
    lines = ["# ./run mutate" + command,
             "",
             "| # | where | operator | change | result | caught by / why equivalent |",
             "|---|---|---|---|---|---|"]
    for i, m in enumerate(drawn, 1):
        change = "`%s` → `%s`" % (m.original, m.replacement) if m.replacement else "`%s` removed" % m.original
        note = m.reason if m.result == "equivalent" else m.by
        lines.append("| %d | %s | %s | %s | %s | %s |" % (i, m.where(), m.operator, change, m.result or "not run",
                                                          note.replace("|", "\\|")))
    summary = ", ".join("%d %s" % (n, r) for r, n in counts.items() if n)
    score = "%.1f %%" % (100.0 * killed / scored) if scored else "n/a"
    reused = sum(m.reused for m in drawn)
    lines += ["", "%s; score %s (caught / (caught + survived)); %.0f min%s" % (
        summary, score, seconds / 60, "; %d verdicts from earlier runs on the same files and suites" % reused if reused else "")]
    if LEFT_OUT:
        lines += ["", "Left out of every mutant's run, since they fail on the unmutated code:"]
        lines += ["- " + name for name in LEFT_OUT]
    survivors = [m for m in drawn if m.result == "survived"]
    if survivors:
        lines += ["", "Survivors (kill each with a test, or add it to proofs_tests/mutation/equivalent.txt with its reason):"]
        lines += ["", "```"] + [equivalent_entry(m) for m in survivors] + ["```"]
    text = "\n".join(lines) + "\n"
    name = "report-at" if args.at else "report-%d-seed-%d" % (args.count, args.seed)
    with open(os.path.join(OUT, name + ".md"), "w") as f:
        f.write(text)
    with open(os.path.join(OUT, name + ".json"), "w") as f:
        json.dump([{"where": m.where(), "operator": m.operator, "original": m.original, "replacement": m.replacement,
                    "line": m.text, "result": m.result, "by": m.by, "seconds": round(m.seconds, 1)} for m in drawn],
                  f, indent=1)
    print("\n" + text + "\n(written to %s.md)" % os.path.join(OUT, name), flush=True)


if __name__ == "__main__":
    def interrupted(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, interrupted)
    try:
        sys.exit(main())
    except KeyboardInterrupt:
        sys.exit("interrupted: every mutated file was restored")
