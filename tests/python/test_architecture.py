# SPDX-License-Identifier: MIT
"""The Python layers as docs/architecture.md draws them, read from the sources with `ast`
(scripts/import_graph.py; nothing is imported, so no FE stack is needed):

- no import cycle, between modules or between packages, function-level imports included;
- the package edges are exactly the table "The Python packages and what each may import";
- a function-level import says why (a comment on its line or the line above: only optional or
  slow dependencies are imported late);
- scenes, commands, benchmarks and demos use the public API only: no `_rockjoint`, no private name
  of another module or object, no DOLFINx / UFL / basix (the FE work is `rockjoint.fem`'s).

Each check is also shown failing on a small made-up source, so that a check that sees nothing
cannot pass unnoticed.
"""
import ast
import importlib.util
import os
import re
import textwrap

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
_spec = importlib.util.spec_from_file_location("import_graph", os.path.join(ROOT, "scripts", "import_graph.py"))
graph = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(graph)

#: Function-level imports in files another change owns (issue 29, item 3, and the Newton speed
#: work), each with what removes it; the test fails when one is gone, so the list only shrinks.
PENDING_LOCAL = {
}

FE_MODULES = ("dolfinx", "ufl", "basix")
#: the user-model demo is the user's own DOLFINx model: its UFL forms are the point of it
OWN_UFL = {"demos/demo_user_model.py"}


def rel(path):
    return os.path.relpath(path, ROOT).replace(os.sep, "/")


def test_no_import_cycle_between_modules_or_packages():
    mods = graph.modules()
    assert "rockjoint.fem.mechanics.model" in mods and "rockjoint.meshes.builders" in mods
    modules = graph.module_graph(mods)
    assert graph.find_cycle(modules) is None, graph.find_cycle(modules)
    packages = {a: {b for b in bs if b.startswith("rockjoint")} for a, bs in graph.package_graph(mods).items()}
    assert graph.find_cycle(packages) is None, graph.find_cycle(packages)


def test_the_cycle_finder_finds_a_cycle_hidden_in_a_function(tmp_path, monkeypatch):
    pkg = tmp_path / "rockjoint"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from . import b\n")
    (pkg / "b.py").write_text("def f():\n    from .a import g  # late\n")
    monkeypatch.setattr(graph, "SOURCES", {"rockjoint": str(pkg)})
    assert graph.find_cycle(graph.module_graph()) == ["rockjoint.a", "rockjoint.b", "rockjoint.a"]


def documented_edges() -> dict:
    """{package: set of imports} from docs/architecture.md's package table."""
    with open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8") as f:
        text = f.read()
    section = text.split("### The Python packages and what each may import", 1)[1].split("\n#", 1)[0]
    out = {}
    for line in section.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) == 3 and re.fullmatch(r"`rockjoint[\w.]*`", cells[0]):
            out[cells[0].strip("`")] = set(re.findall(r"`([\w.]+)`", cells[2]))
    return out


def test_package_imports_are_the_ones_the_architecture_page_draws():
    drawn = documented_edges()
    assert len(drawn) >= 20
    actual = {a: {b for b in bs if b.startswith("rockjoint") or b in graph.FE_STACK}
              for a, bs in graph.package_graph().items()}
    actual.update({c: set() for c in graph.COMPILED})
    assert set(drawn) == set(actual), f"packages not drawn: {set(actual) - set(drawn)}; " \
                                      f"drawn, not in the sources: {set(drawn) - set(actual)}"
    for package in sorted(actual):
        assert actual[package] == drawn[package], (
            f"{package}: imports {sorted(actual[package] - drawn[package])} the page does not draw, "
            f"the page draws {sorted(drawn[package] - actual[package])} it does not import "
            "(python3 scripts/import_graph.py prints the graph)")
    # the per-point materials carry no FE stack
    for package in ("rockjoint.joint", "rockjoint.continuum"):
        assert not actual[package] & set(graph.FE_STACK), package


def unexplained_local_imports(mods: dict) -> set:
    """{(file, imported module)} of function-level imports whose top-level package has no
    reason comment in that function (on an import of it or the line above)."""
    found = {}
    for name, path in mods.items():
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        tree = ast.parse("\n".join(lines), path)
        for fn in ast.walk(tree):
            if not isinstance(fn, (ast.FunctionDef, ast.AsyncFunctionDef)):
                continue
            reasons, targets = set(), []
            for node in ast.walk(fn):
                if isinstance(node, ast.Import):
                    names = [a.name for a in node.names]
                elif isinstance(node, ast.ImportFrom):
                    base = graph._resolve(name, path.endswith("__init__.py"), node)
                    names = [f"{base}.{a.name}" if f"{base}.{a.name}" in mods else base for a in node.names]
                else:
                    continue
                said = "#" in lines[node.lineno - 1] or lines[node.lineno - 2].strip().startswith("#")
                for n in names:
                    top = n if n.startswith("rockjoint") else n.split(".")[0]
                    targets.append(top)
                    if said:
                        reasons.add(top)
            for top in targets:
                if top not in reasons:
                    found[(rel(path), top)] = True
    return set(found)


def test_function_level_imports_say_why():
    missing = unexplained_local_imports(graph.modules())
    assert missing == set(PENDING_LOCAL), (
        f"function-level imports without a reason: {sorted(missing - set(PENDING_LOCAL))}; "
        f"listed as pending but gone (drop them from PENDING_LOCAL): {sorted(set(PENDING_LOCAL) - missing)}")


def test_an_unexplained_function_level_import_is_caught(tmp_path):
    pkg = tmp_path / "rockjoint"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "m.py").write_text(textwrap.dedent("""\
        def plot():
            import matplotlib  # slow: only when drawing
            import matplotlib.pyplot as plt
            import json
            return plt, json
        """))
    found = unexplained_local_imports({"rockjoint": str(pkg / "__init__.py"), "rockjoint.m": str(pkg / "m.py")})
    assert {top for _, top in found} == {"json"}


def below_public_api(path: str) -> list:
    """What a file of scenes/, commands/, bench/ or demos/ uses below the public API."""
    with open(path, encoding="utf-8") as f:
        tree = ast.parse(f.read(), path)
    out = []
    fe_ok = rel(path) in OWN_UFL
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if "_rockjoint" in a.name or (a.name.split(".")[0] in FE_MODULES and not fe_ok):
                    out.append(f"{node.lineno}: import {a.name}")
        elif isinstance(node, ast.ImportFrom):
            module = node.module or ""
            if "_rockjoint" in module or (module.split(".")[0] in FE_MODULES and node.level == 0 and not fe_ok):
                out.append(f"{node.lineno}: from {module} import ...")
            out += [f"{node.lineno}: imports {a.name}" for a in node.names
                    if a.name.startswith("_") and not a.name.startswith("__")]
        elif isinstance(node, ast.Attribute) and node.attr.startswith("_") and not node.attr.startswith("__"):
            if not (isinstance(node.value, ast.Name) and node.value.id in ("self", "cls")):
                out.append(f"{node.lineno}: {ast.unparse(node)}")
    return out


def client_files() -> list:
    roots = [os.path.join(ROOT, "python", "rockjoint", "scenes"), os.path.join(ROOT, "python", "rockjoint", "commands"),
             os.path.join(ROOT, "bench"), os.path.join(ROOT, "demos")]
    return sorted(os.path.join(d, f) for r in roots for d, _, fs in os.walk(r) for f in fs if f.endswith(".py"))


def test_scenes_commands_bench_and_demos_use_the_public_api_only():
    files = client_files()
    assert len(files) > 30
    bad = {rel(f): below_public_api(f) for f in files}
    bad = {f: v for f, v in bad.items() if v}
    assert not bad, bad


def test_reaching_below_the_public_api_is_caught(tmp_path):
    f = tmp_path / "client.py"
    f.write_text(textwrap.dedent("""\
        from rockjoint import _rockjoint, meshes
        import ufl
        from dolfinx.fem import petsc
        from rockjoint.topography import _save
        model._prepare()
        self._fine = 1
        """))
    found = below_public_api(str(f))
    assert [line.split(":")[0] for line in found] == ["1", "2", "3", "4", "5"], found


def test_jointed_rock_model_is_small_and_sets_its_attributes_in_init():
    """Issue 29, item 2: JointedRockModel at most 300 lines, composed of parts; every attribute it
    assigns anywhere is first assigned in __init__ (no state appearing later)."""
    path = os.path.join(os.path.dirname(__file__), "..", "..", "python", "rockjoint", "fem", "mechanics", "model.py")
    with open(path, encoding="utf-8") as fh:
        tree = ast.parse(fh.read())
    (cls,) = [n for n in tree.body if isinstance(n, ast.ClassDef) and n.name == "JointedRockModel"]
    assert cls.end_lineno - cls.lineno + 1 <= 300

    def assigned(fn):
        out = set()
        for node in ast.walk(fn):
            targets = node.targets if isinstance(node, ast.Assign) else \
                [node.target] if isinstance(node, (ast.AugAssign, ast.AnnAssign)) else []
            for t in targets:
                for sub in ast.walk(t):
                    if isinstance(sub, ast.Attribute) and isinstance(sub.value, ast.Name) and sub.value.id == "self":
                        out.add(sub.attr)
        return out

    methods = {m.name: m for m in cls.body if isinstance(m, ast.FunctionDef)}
    in_init = assigned(methods["__init__"])
    later = {name: assigned(m) - in_init for name, m in methods.items() if name != "__init__"}
    assert not any(later.values()), {k: v for k, v in later.items() if v}
