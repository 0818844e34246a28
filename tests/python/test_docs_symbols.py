# SPDX-License-Identifier: MIT
"""Every file and symbol docs/architecture.md names exists (issue 44, item 6): a file written
in backticks is found (by its path, or a bare name by its directory in the same row or anywhere
in the tree), and each name in backticks in the parentheses after a file is defined: in that
file or directory (a Python def/class/assignment, a C++ class/struct/function/enumerator). No
FE stack needed: text only."""
import os
import re

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
SOURCE_DIRS = ("python", "constitutive", "contact", "flow", "joint", "continuum", "fem_coupling",
               "topography", "meshes", "tests", "bench", "demos", "scripts", "cmake", "fuzz")
_FILE = re.compile(r"`((?:[\w.-]+/)*[\w-]+(?:\.[\w]+)*(?:\.py|\.hpp|\.cpp|\.sh|/))`(?:\s*\(([^)]*)\))?")
_NAME = re.compile(r"`([A-Za-z_][\w]*(?:(?:\.|::)[A-Za-z_]\w*)*)`")


def _tree():
    """{basename: [relative paths]} of the project's source files."""
    out = {}
    for top in SOURCE_DIRS:
        for dirpath, dirs, files in os.walk(os.path.join(ROOT, top)):
            dirs[:] = [d for d in dirs if not d.startswith(".") and d != "__pycache__"]
            for f in files:
                out.setdefault(f, []).append(os.path.relpath(os.path.join(dirpath, f), ROOT))
    return out


TREE = _tree()
#: module and namespace names the page writes in backticks (not symbols of the named file)
OTHER_MODULES = ("rockjoint.", "rockjoint::", "dolfinx.", "petsc4py.", "ufl.", "gmsh.")


def _read(path):
    with open(os.path.join(ROOT, path), encoding="utf-8", errors="replace") as fh:
        return fh.read()


def _defines(text: str, name: str) -> bool:
    n = re.escape(name)
    return re.search(rf"^\s*(?:async\s+)?(?:def|class)\s+{n}\b|^\s*{n}\s*(?::[^=\n]*)?=|"          # Python
                     rf"\b(?:class|struct|enum(?:\s+class)?|namespace)\s+{n}\b|"                # C++ types
                     rf"\b{n}\s*\(|^\s*{n}\s*[,=]|\.def\(\"{n}\"|\"{n}\"", text, re.M) is not None  # calls, enumerators


def _resolve(path: str, near: str | None):
    """The relative path of a file named in the doc, or None."""
    for candidate in (path, os.path.join("python", "rockjoint", path),
                      os.path.join(near, path) if near else None):
        if candidate and os.path.exists(os.path.join(ROOT, candidate)):
            return candidate
    if "/" not in path.rstrip("/") and path in TREE:
        return TREE[path][0]
    if "/" in path:   # a tail of a path (scans/frame.py)
        hits = [p for ps in TREE.values() for p in ps if p.endswith("/" + path)]
        return hits[0] if hits else None
    return None


def named_in_architecture():
    """(line, file, names) of every file the page names, with the names in parentheses after it."""
    page = _read(os.path.join("docs", "architecture.md"))
    out = []
    for number, line in enumerate(page.splitlines(), 1):
        near = None
        for m in _FILE.finditer(line):
            resolved = _resolve(m.group(1), near)
            out.append((number, m.group(1), resolved, _NAME.findall(m.group(2) or "")))
            if resolved:
                near = resolved if resolved.endswith("/") else os.path.dirname(resolved)
    return out


def test_every_file_the_architecture_page_names_exists():
    named = named_in_architecture()
    assert len(named) > 80, len(named)
    missing = [f"line {n}: {f}" for n, f, resolved, _ in named if resolved is None]
    assert not missing, "docs/architecture.md names files that do not exist:\n" + "\n".join(missing)


def test_every_symbol_the_architecture_page_names_is_defined():
    unknown, count = [], 0
    for number, written, resolved, names in named_in_architecture():
        if resolved is None:
            continue
        if resolved.endswith("/") or os.path.isdir(os.path.join(ROOT, resolved)):
            text = "\n".join(_read(p) for ps in TREE.values() for p in ps if p.startswith(resolved.rstrip("/") + "/"))
        else:
            text = _read(resolved)
        for name in names:
            if re.search(r"\.(py|hpp|cpp|h|md)$", name) or name.startswith(OTHER_MODULES):
                continue            # a file, or a module/namespace (ours or DOLFINx's)
            count += 1
            for part in re.split(r"\.|::", name):
                if not _defines(text, part):
                    unknown.append(f"line {number}: {written}: {name}")
                    break
    assert count > 60, count
    assert not unknown, "docs/architecture.md names symbols that are not defined:\n" + "\n".join(unknown)
