# SPDX-License-Identifier: MIT
"""The C++ layers as docs/architecture.md's first table draws them (issue 44, item 6), read from
the sources (text only, no build needed):

- a header of another layer is included as <rockjoint/<folder>/<file>.hpp>, one of the same
  folder as "file.hpp" (it sits beside it, in the tree and installed), and the file exists;
- a layer includes only the layers its row of the table names in "may depend on";
- each check is shown failing on a made-up include, so a check that sees nothing cannot pass.
"""
import os
import re

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
LAYERS = ("constitutive", "topography", "contact", "flow", "joint", "continuum", "fem_coupling")
_INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def allowed_layers() -> dict:
    """{layer: set of layers its row of the table names} from docs/architecture.md."""
    with open(os.path.join(ROOT, "docs", "architecture.md"), encoding="utf-8") as fh:
        page = fh.read()
    out = {}
    for line in page.splitlines():
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        if len(cells) != 4:
            continue
        own = re.match(r"`(\w+)/`", cells[1])
        if own and own.group(1) in LAYERS:
            out[own.group(1)] = set(re.findall(r"`(\w+)/`", cells[3])) & set(LAYERS)
    return out


def include_problems(layer: str, name: str, text: str, allowed: set) -> list:
    problems = []
    for kind, path in _INCLUDE.findall(text):
        if kind == '"':
            if "/" in path or not os.path.exists(os.path.join(ROOT, layer, path)):
                problems.append(f'{layer}/{name}: "{path}" is not a header of {layer}/ (use <rockjoint/...>)')
            continue
        found = re.match(r"rockjoint/(\w+)/([\w.]+)$", path)
        if not found:
            continue                     # a library's header (Eigen, GSL, FFTW, PETSc, std)
        other, header = found.groups()
        if other == layer:
            problems.append(f"{layer}/{name}: <{path}> is its own folder's header (use \"{header}\")")
        elif other not in allowed:
            problems.append(f"{layer}/{name}: includes {other}/, which its row of docs/architecture.md "
                            f"does not allow ({', '.join(sorted(allowed)) or 'no other layer'})")
        elif not os.path.exists(os.path.join(ROOT, other, header)):
            problems.append(f"{layer}/{name}: <{path}> does not exist")
    return problems


def test_every_layer_has_its_row():
    assert set(allowed_layers()) == set(LAYERS)


def test_layers_include_only_what_the_architecture_page_allows():
    allowed = allowed_layers()
    problems, seen = [], 0
    for layer in LAYERS:
        for name in sorted(os.listdir(os.path.join(ROOT, layer))):
            if name.endswith((".hpp", ".cpp")):
                with open(os.path.join(ROOT, layer, name), encoding="utf-8") as fh:
                    problems += include_problems(layer, name, fh.read(), allowed[layer])
                seen += 1
    assert seen > 60
    assert not problems, "\n".join(problems)


def test_a_wrong_include_is_caught():
    allowed = allowed_layers()
    assert include_problems("joint", "x.cpp", "#include <rockjoint/fem_coupling/local_frame.hpp>\n",
                            allowed["joint"])
    assert include_problems("joint", "x.cpp", '#include "../constitutive/closure_law.hpp"\n', allowed["joint"])
    assert include_problems("joint", "x.cpp", "#include <rockjoint/joint/joint_slip.hpp>\n", allowed["joint"])
    assert include_problems("continuum", "x.cpp", "#include <rockjoint/joint/no_such.hpp>\n",
                            allowed["continuum"])
    assert not include_problems("joint", "x.cpp", '#include "joint_slip.hpp"\n#include <Eigen/Dense>\n'
                                "#include <rockjoint/constitutive/closure_law.hpp>\n", allowed["joint"])
