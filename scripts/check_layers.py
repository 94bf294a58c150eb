#!/usr/bin/env python3
"""Fails when a part of src/ includes a part it must not.

The allowed matrix is read from docs/ARCHITECTURE.md (the table under
"## Layers"), so it is written once. Usage: check_layers.py [REPO_ROOT]
"""
import pathlib
import re
import sys

root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else pathlib.Path(__file__).resolve().parent.parent)
doc = (root / "docs" / "ARCHITECTURE.md").read_text()

# The table rows: | part | may include | (a part, or one file of a part: "core/error.h")
section = doc.split("## Layers", 1)[1].split("\n## ", 1)[0]
allowed = {}
for line in section.splitlines():
    cells = [c.strip(" `") for c in line.strip().strip("|").split("|")]
    if len(cells) < 2 or not re.fullmatch(r"[a-z]+", cells[0]):
        continue
    allowed[cells[0]] = {p.strip(" `") for p in cells[1].split(",") if p.strip(" `")} | {cells[0]}

parts = sorted(p.name for p in (root / "src").iterdir() if p.is_dir())
problems = [f"src/{p}: no row in docs/ARCHITECTURE.md's layer table" for p in parts if p not in allowed]
include = re.compile(r'^\s*#\s*include\s+"(([a-z_]+)/[^"]+)"', re.M)
for part in parts:
    for f in sorted((root / "src" / part).rglob("*")):
        if f.suffix not in (".h", ".cpp"):
            continue
        for m in include.finditer(f.read_text()):
            path, target = m.group(1), m.group(2)
            if target in parts and not allowed.get(part, set()) & {target, path}:
                line = f.read_text()[: m.start()].count("\n") + 1
                problems.append(f"{f.relative_to(root)}:{line}: {part} includes {target}/ (allowed: "
                                f"{', '.join(sorted(allowed.get(part, set())))})")
# Embree stays behind src/geometry's .cpp files: its headers are included only by those
# and by geometry/embree_impl.h, which nothing outside src/geometry includes, so the
# parts, tests and benchmarks that use TraceScene compile without them.
embree = re.compile(r'^\s*#\s*include\s+[<"]embree\d*/', re.M)
embree_impl = re.compile(r'^\s*#\s*include\s+"geometry/embree_impl\.h"', re.M)
geometry = root / "src" / "geometry"
for top in ("src", "tests", "bench", "fuzz"):
    if not (root / top).is_dir():
        continue
    for f in sorted((root / top).rglob("*")):
        if f.suffix not in (".h", ".hpp", ".cpp"):
            continue
        text = f.read_text()
        inside = f.parent == geometry
        for m in embree.finditer(text):
            if not inside or (f.suffix != ".cpp" and f.name != "embree_impl.h"):
                line = text[: m.start()].count("\n") + 1
                problems.append(f"{f.relative_to(root)}:{line}: includes Embree (only src/geometry/*.cpp and "
                                "geometry/embree_impl.h may)")
        for m in embree_impl.finditer(text):
            if not inside:
                line = text[: m.start()].count("\n") + 1
                problems.append(f"{f.relative_to(root)}:{line}: includes geometry/embree_impl.h (private to "
                                "src/geometry)")


def light_type_outside_seam(root):
    """A light type is named (LightType::) only in the light seam (src/core/light*,
    src/core/lights/) and in io/light_reader.cpp's reader table; the rest asks its traits."""
    found = []
    for f in sorted((root / "src").rglob("*")):
        rel = f.relative_to(root).as_posix()
        if f.suffix not in (".h", ".cpp") or rel.startswith("src/core/light") or rel == "src/io/light_reader.cpp":
            continue
        for n, text in enumerate(f.read_text().splitlines(), 1):
            if "LightType::" in text:
                found.append(f"{rel}:{n}: names LightType:: outside the light seam (ask lightTraits or a "
                             "core/light_sample.h function)")
    return found


problems += light_type_outside_seam(root)
for p in problems:
    print(p)
print(f"layers: {len(parts)} parts checked, {len(problems)} problem(s)")
sys.exit(1 if problems else 0)
