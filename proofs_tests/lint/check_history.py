#!/usr/bin/env python3
"""The product speaks of itself only: no tracked text file tells how the code came to be, and every
repository path a file cites exists.

Over `git ls-files` of REPO (outside a git checkout: its files but generated ones; binary files and
the data of reference_outputs/ skipped), a line fails
- when it names a work period or one of the project's own tickets by number ("session" or
  "sessions" followed by a number, "issue" or "issues" followed by a number or "#" and a number,
  also split over two lines), unless it holds a URL (another project's ticket, cited by its
  address); measurements carry their date and commit instead, and history lives in `git log`;
- when it cites a path that does not exist: a path token that starts with a top-level folder
  (src/ spec/ paper_notes/ proofs_tests/ bench/ fuzz/ peers/ examples/ reference_outputs/) or
  with ../ and ends in a known extension, a bare file name of the design notes or developers'
  guide that live outside the repository, or the target of a relative markdown link. A path is
  resolved against the repository root and against the citing file's folder, and must exist
  inside the repository. Not citations: globs and placeholders (`*`, `{a,b}`, `<mesh>`, `$VAR`,
  upper-case folder names such as NAME), paths under out/ or build*/, and meshes looked for
  outside the repository (`../…/horse.off`: inputs ./run reads when present).
Prints one `path:line: text` per hit and exits 1, or a one-line summary and exits 0.
Usage: check_history.py REPO"""
import os
import re
import subprocess
import sys

TOP = ("src", "spec", "paper_notes", "proofs_tests", "bench", "fuzz", "peers", "examples", "reference_outputs")
EXTENSIONS = ("md", "cpp", "hpp", "py", "txt", "build", "toml", "json", "svg", "png", "off", "obj", "ply")
MESH_EXTENSIONS = ("off", "obj", "ply", "stl")

HISTORY = [re.compile(p) for p in (r"(?i)\bsessions? #?[0-9]", r"(?i)\bissues? #?[0-9]")]
# A line that ends with the word, whose next line starts (after comment leaders) with the number.
HISTORY_END = re.compile(r"(?i)\b(sessions?|issues?)\s*$")
NUMBER_START = re.compile(r"^[\s/#*>|-]*#?[0-9]")
URL = re.compile(r"https?://")

_EXT = "|".join(EXTENSIONS)
_SEGMENT = r"[\w.+-]"
PATH = re.compile(r"(?<![\w./$~{}*<>@-])"                     # a token's start, not the middle of a path
                  r"((?:\.\./)+|(?:" + "|".join(TOP) + r")/)"  # ../ or a top-level folder
                  r"((?:" + _SEGMENT + r"+/)*" + _SEGMENT + r"*?)"
                  r"\.(" + _EXT + r")(?![\w/*{}<>-]|\.\w)")
OUTSIDE_NOTES = re.compile(r"(?<![\w./-])((?:design|DEVELOPERS)\.md)\b")
MD_LINK = re.compile(r"\]\(([^)\s]+)\)")
PLACEHOLDER_DIR = re.compile(r"^[A-Z][A-Z0-9_]+$")


def tracked_files(repo):
    """git ls-files; outside a git checkout (a copy of the tree), every file but generated ones."""
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "-z"], check=True, capture_output=True).stdout
        return [p for p in out.decode("utf-8", "surrogateescape").split("\0") if p]
    except (OSError, subprocess.CalledProcessError):
        files = []
        for folder, dirs, names in os.walk(repo):
            dirs[:] = sorted(d for d in dirs if not d.startswith((".", "build", "out", "__pycache__")))
            files += [os.path.relpath(os.path.join(folder, n), repo) for n in sorted(names)]
        return files


def read_text(path):
    """The file's lines, or None for a binary file."""
    with open(path, "rb") as f:
        data = f.read()
    if b"\0" in data[:8192]:
        return None
    try:
        return data.decode("utf-8").splitlines()
    except UnicodeDecodeError:
        return None


def skipped(rel):
    return rel.startswith("reference_outputs/") and not rel.endswith(".md")


def inside(repo, path):
    root = os.path.realpath(repo)
    real = os.path.realpath(path)
    return real == root or real.startswith(root + os.sep)


def resolves(repo, rel, cited, markdown=False):
    """(exists inside the repository, some resolution leaves it)."""
    bases = [os.path.dirname(rel)] if markdown else ["", os.path.dirname(rel)]
    leaves = False
    for base in bases:
        full = os.path.normpath(os.path.join(repo, base, cited))
        if not inside(repo, full):
            leaves = True
        elif os.path.exists(full):
            return True, leaves
    return False, leaves


def path_hits(repo, rel, line):
    """The cited paths of one line that do not exist."""
    missing = []
    for m in PATH.finditer(line):
        cited = m.group(0)
        folders = cited.split("/")[:-1]
        if any(PLACEHOLDER_DIR.match(f) for f in folders):
            continue
        first = [f for f in folders if f != ".."][:1]
        if first and (first[0] == "out" or first[0].startswith("build")):
            continue  # generated files, never committed
        ok, leaves = resolves(repo, rel, cited)
        if ok:
            continue
        if cited.startswith("../") and leaves and m.group(3) in MESH_EXTENSIONS:
            continue  # an input mesh looked for outside the repository, not a citation
        missing.append(cited)
    for m in OUTSIDE_NOTES.finditer(line):
        if not resolves(repo, rel, m.group(1))[0]:
            missing.append(m.group(1))
    if rel.endswith(".md"):
        for m in MD_LINK.finditer(line):
            target = m.group(1).split("#", 1)[0]
            if not target or re.match(r"^[a-z][a-z0-9+.-]*:", target) or target.startswith("/"):
                continue
            if any(c in target for c in "*{}<>$"):
                continue
            if not resolves(repo, rel, target, markdown=True)[0]:
                missing.append(target)
    return missing


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: check_history.py REPO")
    repo = sys.argv[1]
    hits = []
    checked = 0
    for rel in tracked_files(repo):
        full = os.path.join(repo, rel)
        if skipped(rel) or not os.path.isfile(full):
            continue
        lines = read_text(full)
        if lines is None:
            continue
        checked += 1
        for i, line in enumerate(lines):
            has_url = bool(URL.search(line))
            if not has_url and any(p.search(line) for p in HISTORY):
                hits.append((rel, i + 1, line, "history"))
            elif (not has_url and HISTORY_END.search(line) and i + 1 < len(lines)
                  and NUMBER_START.match(lines[i + 1])):
                hits.append((rel, i + 1, line, "history"))
            for cited in path_hits(repo, rel, line):
                hits.append((rel, i + 1, line, "cites " + cited + ", which is not in the repository"))
    for rel, n, line, why in hits:
        print("%s:%d: %s  [%s]" % (rel, n, line.strip(), why))
    if hits:
        print("check_history: %d hits in %d tracked text files" % (len(hits), checked))
        return 1
    print("check_history: %d tracked text files speak of the product only; every cited path exists" % checked)
    return 0


if __name__ == "__main__":
    sys.exit(main())
