#!/usr/bin/env python3
"""One-way layers: every `#include <fhr/FOLDER/…>` of src/ names a folder that the including
file's folder may include, by the table of paper_notes/library.md ("The layers", the rows after
its `<!-- layers: … -->` marker); a folder always includes its own headers, and every folder of
src/fhr and src/ that holds sources has a row. Usage: check_layers.py SOURCE_DIR (exit 0 when
every include follows the table)"""
import os
import re
import sys

root = os.path.abspath(sys.argv[1])
note = open(os.path.join(root, "paper_notes", "library.md"), encoding="utf-8").read()
marker = note.find("<!-- layers:")
if marker < 0:
    sys.exit("check_layers: paper_notes/library.md has no layers table (its <!-- layers: ... --> marker)")
allowed = {}
stages = []
for line in note[marker:].splitlines()[1:]:
    if not line.startswith("|"):
        if allowed:
            break
        continue
    cells = [c.strip() for c in line.strip().strip("|").split("|")]
    if cells[0] in ("folder", "---") or set(cells[0]) <= {"-"}:
        continue
    folder, may = cells[0], cells[1]
    allowed[folder] = may
    if folder.startswith("src/fhr/"):
        stages.append(folder[len("src/fhr/"):])
rules = {}
for folder, may in allowed.items():
    if may == "every folder of src/fhr":
        rules[folder] = set(stages)
    elif may in ("—", "-", ""):
        rules[folder] = set()
    else:
        rules[folder] = {m.strip() for m in may.split(",")}
    unknown = rules[folder] - set(stages)
    if unknown:
        sys.exit("check_layers: the row of %s names folders that are not in the table: %s" % (folder, ", ".join(sorted(unknown))))

include = re.compile(r'^\s*#\s*include\s*<fhr/([a-z_]+)/')
broken, files = [], 0
for base in ("src/fhr", "src/cli", "src/python"):
    for dirpath, _, names in os.walk(os.path.join(root, base)):
        for name in sorted(names):
            if not name.endswith((".hpp", ".cpp")):
                continue
            path = os.path.relpath(os.path.join(dirpath, name), root)
            parts = path.split(os.sep)
            folder = "/".join(parts[:3]) if parts[1] == "fhr" and len(parts) > 3 else "/".join(parts[:2])
            if parts[1] == "fhr" and len(parts) == 3:
                continue  # src/fhr/fhr.hpp (the umbrella header) and version.hpp
            if folder not in rules:
                broken.append("%s: its folder %s has no row in the layers table" % (path, folder))
                continue
            own = parts[2] if parts[1] == "fhr" else None
            files += 1
            for number, text in enumerate(open(os.path.join(root, path), encoding="utf-8"), 1):
                m = include.match(text)
                if m and m.group(1) != own and m.group(1) not in rules[folder]:
                    broken.append("%s:%d includes <fhr/%s/...>, which %s may not (paper_notes/library.md, The layers)"
                                  % (path, number, m.group(1), folder))
if files < 100:
    sys.exit("check_layers: only %d source files found under src/" % files)
if broken:
    sys.exit("check_layers: %d includes break the layers:\n  %s" % (len(broken), "\n  ".join(broken)))
print("check_layers: %d files of src/, every #include <fhr/...> within its folder's layers (%d folders)" % (files, len(rules)))
