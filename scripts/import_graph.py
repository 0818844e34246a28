#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The import graph of the Python package `rockjoint`, read from the sources with `ast` (nothing is
imported, so it runs without a build): every `import` and `from ... import`, at module level and
inside functions, resolved to the package's own modules.

    python3 scripts/import_graph.py            # the package-level edges (docs/architecture.md)
    python3 scripts/import_graph.py --modules  # every module-level edge
    python3 scripts/import_graph.py --local    # the function-level imports and their reasons

Packages are the layers of docs/architecture.md: `rockjoint.<name>` for the sub-packages
(fem, scenes, scans, commands, reference, meshes) and the compiled `_rockjoint` /
`_rockjoint_fem_coupling` / `_rockjoint_dolfinx`; the top-level modules are their own layer each. Outside imports
(dolfinx, ufl, petsc4py, ...) are kept as their top-level name. tests/python/test_architecture.py
asserts that both graphs are acyclic and that the package edges are the ones the page allows.
"""
from __future__ import annotations

import argparse
import ast
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
#: where each part of the package lives in the source tree (meshes/ is copied in by the build)
SOURCES = {"rockjoint": os.path.join(ROOT, "python", "rockjoint"),
           "rockjoint.meshes": os.path.join(ROOT, "meshes")}
#: compiled modules (bindings in python/src): leaves of the graph
COMPILED = ("rockjoint._rockjoint", "rockjoint._rockjoint_fem_coupling", "rockjoint._rockjoint_dolfinx")
#: the FE stack and other outside packages a layer may need, by their import names
FE_STACK = ("dolfinx", "ufl", "basix", "petsc4py", "mpi4py", "rockjoint._rockjoint_fem_coupling",
            "rockjoint._rockjoint_dolfinx")


def modules() -> dict:
    """{module name: source path} of every module of the package."""
    out = {}
    for package, folder in SOURCES.items():
        for dirpath, dirnames, filenames in os.walk(folder):
            dirnames[:] = sorted(d for d in dirnames if d != "__pycache__")
            rel = os.path.relpath(dirpath, folder)
            prefix = package if rel == "." else package + "." + rel.replace(os.sep, ".")
            for f in sorted(filenames):
                if f.endswith(".py"):
                    name = prefix if f == "__init__.py" else f"{prefix}.{f[:-3]}"
                    out[name] = os.path.join(dirpath, f)
    return out


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    if node.level == 0:
        return node.module or ""
    parts = module.split(".")
    base = parts if is_package else parts[:-1]
    base = base[:len(base) - (node.level - 1)]
    return ".".join(base + ([node.module] if node.module else []))


def imports(mods: dict):
    """Yield (importer, imported, line, function-level?, the source line) for every import."""
    known = set(mods) | set(COMPILED)
    for name, path in mods.items():
        with open(path, encoding="utf-8") as f:
            text = f.read()
        lines = text.splitlines()
        tree = ast.parse(text, path)
        is_package = path.endswith("__init__.py")
        local = set()
        for fn in ast.walk(tree):
            if isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                local.update(id(n) for n in ast.walk(fn) if isinstance(n, (ast.Import, ast.ImportFrom)))
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = _resolve(name, is_package, node)
                # `from pkg import sub` imports the module pkg.sub when there is one
                targets = [f"{base}.{a.name}" if f"{base}.{a.name}" in known else base for a in node.names]
            else:
                continue
            for target in dict.fromkeys(targets):
                yield name, target, node.lineno, id(node) in local, lines[node.lineno - 1]


def layer(module: str) -> str:
    """The layer of a module: rockjoint.<first part> (rockjoint itself for the package's
    __init__), the compiled modules as they are, outside packages by their top-level name."""
    if module in COMPILED:
        return module
    parts = module.split(".")
    if parts[0] != "rockjoint":
        return parts[0]
    return ".".join(parts[:2])


def module_graph(mods: dict | None = None) -> dict:
    """{module: set of the package's modules it imports} (function-level imports included);
    an import of a sub-module also runs its parent packages' __init__, which is left out here
    (Python imports a package before its modules whatever the edges)."""
    mods = modules() if mods is None else mods
    graph = {m: set() for m in mods}
    for a, b, *_ in imports(mods):
        if b.startswith("rockjoint") and b != a and not a.startswith(b + "."):
            graph[a].add(b)
    return graph


def package_graph(mods: dict | None = None) -> dict:
    """{layer: set of layers it imports} (outside packages included, self-edges left out)."""
    mods = modules() if mods is None else mods
    graph = {}
    for a, b, *_ in imports(mods):
        la, lb = layer(a), layer(b)
        graph.setdefault(la, set())
        if lb != la and lb != "__future__":
            graph[la].add(lb)
    return graph


def find_cycle(graph: dict) -> list | None:
    """One cycle of the graph as a list of nodes (first == last), or None."""
    state, stack = {}, []

    def visit(n):
        state[n] = 1
        stack.append(n)
        for m in sorted(graph.get(n, ())):
            if state.get(m) == 1:
                return stack[stack.index(m):] + [m]
            if m not in state:
                found = visit(m)
                if found:
                    return found
        stack.pop()
        state[n] = 2
        return None

    for n in sorted(graph):
        if n not in state:
            found = visit(n)
            if found:
                return found
    return None


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--modules", action="store_true", help="every module edge instead of the package edges")
    ap.add_argument("--local", action="store_true", help="the function-level imports (with their lines)")
    ap.add_argument("--outside", action="store_true", help="keep edges to outside packages other than the FE stack")
    args = ap.parse_args(argv)
    mods = modules()
    if args.local:
        for a, b, line, local, source in imports(mods):
            if local:
                print(f"{os.path.relpath(mods[a], ROOT)}:{line}: {source.strip()}")
        return 0
    if args.modules:
        graph = module_graph(mods)
        for a in sorted(graph):
            for b in sorted(graph[a]):
                print(f"{a} -> {b}")
    else:
        graph = package_graph(mods)
        for a in sorted(graph):
            keep = sorted(b for b in graph[a] if b.startswith("rockjoint") or b in FE_STACK or args.outside)
            print(f"{a} -> {', '.join(keep) if keep else '(nothing of the package)'}")
    cycle = find_cycle(graph if args.modules else {a: {b for b in bs if b.startswith("rockjoint")}
                                                  for a, bs in graph.items()})
    print("cycle: " + (" -> ".join(cycle) if cycle else "none"), file=sys.stderr)
    return 1 if cycle else 0


if __name__ == "__main__":
    sys.exit(main())
