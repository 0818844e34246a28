#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The project's source files and their licence line: `python3 scripts/spdx_headers.py` lists the
files without `SPDX-License-Identifier: MIT` in their first lines, `--add` writes it (after a
shebang line), as `//` in C++ and `#` elsewhere. tests/python/test_licence.py checks every file."""
import os
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
#: folders of the project's own sources (build trees, the Debian roots, data files are not sources)
SOURCE_DIRS = ("bench", "cmake", "constitutive", "contact", "continuum", "demos", "fem_coupling",
               "flow", "fuzz", "joint", "meshes", "python", "scripts", "tests", "topography", ".ci")
LINE = "SPDX-License-Identifier: MIT"


def comment(path: str) -> str | None:
    """The comment marker of a source file, or None for a file that is not a source."""
    name = os.path.basename(path)
    if name.endswith((".cpp", ".hpp")):
        return "//"
    if name.endswith((".py", ".sh", ".cmake")) or name in ("CMakeLists.txt", "run") or name.endswith(".cmake.in"):
        return "#"
    return None


def source_files() -> list:
    out = [os.path.join(ROOT, "CMakeLists.txt"), os.path.join(ROOT, "conftest.py")]
    for top in SOURCE_DIRS:
        for dirpath, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = sorted(d for d in dirs if d not in ("__pycache__", "corpus", "regressions", "results"))
            out += [os.path.join(dirpath, f) for f in sorted(files) if comment(f)]
    return [p for p in out if os.path.isfile(p)]


def has_line(path: str) -> bool:
    with open(path, encoding="utf-8", errors="replace") as fh:
        return any(LINE in fh.readline() for _ in range(3))


def add(path: str) -> None:
    with open(path, encoding="utf-8") as fh:
        lines = fh.readlines()
    at = 1 if lines and lines[0].startswith("#!") else 0
    lines.insert(at, f"{comment(path)} {LINE}\n")
    with open(path, "w", encoding="utf-8") as fh:
        fh.writelines(lines)


if __name__ == "__main__":
    missing = [p for p in source_files() if not has_line(p)]
    if "--add" in sys.argv[1:]:
        for p in missing:
            add(p)
    print("\n".join(os.path.relpath(p, ROOT) for p in missing) or "every source file has its licence line")
