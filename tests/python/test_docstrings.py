# SPDX-License-Identifier: MIT
"""Public names of rockjoint have docstrings (issue 42, item 3: the API reference is built from
them, and a name without one is an empty entry).

Public: every module of the package whose dotted path has no part starting with '_'; in it, every
class or function it defines, lists in __all__ or re-exports from the compiled modules (as
rockjoint.topography re-exports Surface) whose name does not start with '_'; and every public
method or property of those classes, pybind11 ones included (their docstrings come from the C++
bindings, python/src/).

The 126 names that had no docstring when this check was written (the ratchet file
tests/python/undocumented_names.txt) have one since; the file is gone and any public name without
a docstring fails.
"""
import importlib
import inspect
import pkgutil

import rockjoint


def _public_modules():
    """The public modules of rockjoint (no part of the dotted name starts with '_')."""
    names = ["rockjoint"]
    for info in pkgutil.walk_packages(rockjoint.__path__, "rockjoint."):
        if not any(part.startswith("_") for part in info.name.split(".")):
            names.append(info.name)
    return sorted(set(names))


def _documented(obj, name) -> bool:
    """obj has a docstring beyond a pybind11 signature line."""
    doc = getattr(obj, "__doc__", None) or ""
    return bool("\n".join(line for line in doc.splitlines()
                          if not line.startswith(f"{name}(")).strip())


def _exported(module):
    """(name, object) of the public classes and functions module owns or exports."""
    exported = getattr(module, "__all__", None)
    for name, obj in vars(module).items():
        if name.startswith("_") or not (inspect.isclass(obj) or inspect.isroutine(obj)):
            continue
        owner = getattr(obj, "__module__", "") or ""
        compiled = owner.startswith("rockjoint._")
        if (exported is not None and name in exported) or owner == module.__name__ or compiled:
            yield name, obj


def _members(cls):
    """(name, object) of the public methods and properties a class defines: not the values of an
    enumeration, nor pybind11's own 'name' and 'value' of one."""
    enum_values = getattr(cls, "__members__", None)
    for name, value in vars(cls).items():
        if name.startswith("_") or isinstance(value, cls):
            continue
        if enum_values is not None and (name in enum_values or name in ("name", "value")):
            continue
        if inspect.isroutine(value) or isinstance(value, property):
            yield name, value


def undocumented_names():
    """Every public name of rockjoint without a docstring, each object once (where first seen)."""
    missing, seen = [], set()
    for module_name in _public_modules():
        module = importlib.import_module(module_name)
        if not _documented(module, module_name):
            missing.append(module_name)
        for name, obj in _exported(module):
            if id(obj) in seen:
                continue
            seen.add(id(obj))
            qual = f"{module_name}.{name}"
            if not _documented(obj, name):
                missing.append(qual)
            if inspect.isclass(obj):
                missing += [f"{qual}.{m}" for m, v in _members(obj) if not _documented(v, m)]
    return sorted(missing)


def test_public_names_have_docstrings():
    """Every public name of rockjoint has a docstring."""
    missing = undocumented_names()
    assert not missing, "public names without a docstring:\n  " + "\n  ".join(missing)
