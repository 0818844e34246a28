# SPDX-License-Identifier: MIT
"""One law registry (rockjoint.law_registry): a toy law registered in one place becomes available
to make_law, tabulation, the CLI (tabulate and calibrate, through ROCKJOINT_LAWS), calibration
and the FE joint; every answer is checked against the toy law's closed form
Δ(σ) = V_m (1 - exp(-σ/(k0 V_m))). And a law's identity lives in the registry only: no
spelling of a law key elsewhere in the package, and the docs table is the registry's."""
import os
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest

import rockjoint
from rockjoint import law_registry
from rockjoint.calibration import ClosureCurve, calibrate
from rockjoint.laws import make_law

from demo_runner import SOURCE
from fe_stack import require_fe

import toy_law_plugin as toy  # noqa: E402  registers the toy law on import (for the CLI) ...
law_registry.unregister(toy.KEY)              # ... which other test modules must not see


@pytest.fixture(autouse=True, scope="module")
def _toy_law_registered_for_this_module_only():
    """Other test modules see the built-in laws only."""
    law_registry.REGISTRY.setdefault(toy.KEY, toy.RECORD)
    yield
    law_registry.unregister(toy.KEY)

K0, VM = 2e10, 0.5e-3          # [Pa/m], [m]
STRESS = np.array([0.5, 1, 2, 4, 7, 10, 15, 20]) * 1e6   # [Pa]


def test_make_law_and_tabulation_take_the_registered_law():
    law = make_law(toy.KEY, initial_normal_stiffness=K0, maximum_closure=VM)
    np.testing.assert_allclose(law.closure_at_stress(STRESS), toy.closure(STRESS, K0, VM), rtol=1e-12)
    table = rockjoint.tabulate(law, max_stress=25e6, tolerance=1e-6)
    np.testing.assert_allclose(table.closure_at_stress(STRESS), toy.closure(STRESS, K0, VM), rtol=1e-5)
    with pytest.raises(ValueError, match="unknown parameter"):
        make_law(toy.KEY, stiffness=K0)
    with pytest.raises(ValueError, match="registered already"):
        law_registry.register(law_registry.REGISTRY[toy.KEY])


def test_calibration_recovers_the_toy_parameters():
    rng = np.random.default_rng(3)
    noise = 0.002 * VM
    closure = toy.closure(STRESS, K0, VM) + rng.normal(0.0, noise, STRESS.size)
    fit = calibrate(ClosureCurve(STRESS, closure, None, np.arange(STRESS.size), "generated"), toy.KEY)
    for truth, p in zip((K0, VM), fit.parameters):
        assert abs(p.value - truth) <= 3 * p.standard_error, (p.name, p.value, truth, p.standard_error)
        assert p.standard_error < 0.1 * truth


def _cli(args, cwd):
    tests = os.path.dirname(__file__)
    env = dict(os.environ, ROCKJOINT_LAWS="toy_law_plugin", MPLBACKEND="Agg",
               PYTHONPATH=os.pathsep.join([tests] + [p for p in sys.path if p]))
    return subprocess.run([sys.executable, "-m", "rockjoint", *args], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def test_cli_tabulates_and_calibrates_a_plugin_law(tmp_path):
    (tmp_path / "toy.toml").write_text(
        f'[law]\nmodel = "{toy.KEY}"\ninitial_normal_stiffness_MPa_per_mm = {K0 / 1e9}\n'
        f'maximum_closure_mm = {VM * 1e3}\n[table]\nmaximum_stress_MPa = 25\n')
    r = _cli(["tabulate", "toy.toml", "-o", "toy.rjt"], tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    table = rockjoint.TabulatedLaw.load(str(tmp_path / "toy.rjt"))
    np.testing.assert_allclose(table.closure_at_stress(STRESS), toy.closure(STRESS, K0, VM), rtol=1e-5)
    with open(tmp_path / "curve.csv", "w") as f:
        f.write("normal_stress [MPa],closure [mm]\n")
        for s, d in zip(STRESS, toy.closure(STRESS, K0, VM)):
            f.write(f"{float(s) / 1e6!r},{float(d) * 1e3!r}\n")
    r = _cli(["calibrate", "curve.csv", "--law", toy.KEY], tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    assert "k0" in r.stdout and "V_m" in r.stdout
    r = _cli(["calibrate", "curve.csv", "--law", "no_such_law"], tmp_path)
    assert r.returncode == 2 and "invalid choice" in r.stderr


def test_fe_joint_takes_the_registered_law():
    require_fe()
    from test_fem_column import column_model, expected_top
    stress = 10e6
    model = column_model(2, make_law(toy.KEY, initial_normal_stiffness=K0, maximum_closure=VM))
    model.add_traction("top", (0.0, -stress))
    model.solve(load_steps=2)
    top = model.boundary_mean_displacement("top")[1]
    assert top == pytest.approx(expected_top(2, stress, float(toy.closure(stress, K0, VM))), rel=1e-8)


def test_law_keys_are_spelled_only_in_the_registry():
    """Any string literal of the package (parsed, not grepped: comparisons, arguments, dict keys,
    defaults) equal to a registered law key (topography-derived ones included) is in the file that
    registers it: law_registry.py, or contact.py for the walls' exact contact (registered beside
    its BEM solver); so is any string ending like the derived keys' suffixes of old ("_empirical")."""
    import ast
    package = pathlib.Path(SOURCE) / "python" / "rockjoint"
    keys = {k for k in law_registry.REGISTRY if k != toy.KEY}
    assert {"exact_contact", "tang_jiao_i2_gw", "greenwood_williamson_empirical"} <= keys
    offenders = []
    for path in package.rglob("*.py"):
        if path.name == "law_registry.py":
            continue
        own = {"exact_contact"} if path.name == "contact.py" else set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and (
                    node.value in keys - own or node.value.endswith("_empirical")):
                offenders.append(f"{path.relative_to(package)}:{node.lineno}: {node.value!r}")
    assert not offenders, offenders


def test_architecture_page_shows_the_registry_table():
    builtin = {k: r for k, r in law_registry.REGISTRY.items() if k != toy.KEY}
    saved = dict(law_registry.REGISTRY)
    try:
        law_registry.REGISTRY.clear()
        law_registry.REGISTRY.update(builtin)
        table = law_registry.docs_table()
    finally:
        law_registry.REGISTRY.clear()
        law_registry.REGISTRY.update(saved)
    page = (pathlib.Path(SOURCE) / "docs" / "architecture.md").read_text(encoding="utf-8")
    assert table in page, "docs/architecture.md: regenerate the law table with law_registry.docs_table()"


def _recipe_files() -> list:
    """The numbered file list of docs/architecture.md, "Adding a closure law"."""
    page = (pathlib.Path(SOURCE) / "docs" / "architecture.md").read_text(encoding="utf-8")
    start = page.index("## Adding a closure law")
    section = page[start:page.index("\n## ", start)]
    return re.findall(r"^\d+\. `([^`]+)`", section, re.M)


def _naming(root: pathlib.Path, word: str, skip=()) -> set:
    """Files of the repository's sources (C++, Python, CMake, docs) that contain `word`."""
    found = set()
    for path in root.rglob("*"):
        rel = path.relative_to(root)
        if (not path.is_file() or rel.parts[0].startswith(".") or rel.parts[0].startswith("build")
                or rel.parts[0] in skip or path.suffix not in (".hpp", ".cpp", ".py", ".txt", ".md", ".cmake")
                or "__pycache__" in rel.parts):
            continue
        if word in path.read_text(encoding="utf-8", errors="ignore"):
            found.add(rel.as_posix())
    return found


def test_the_recipe_lists_every_file_a_cpp_law_touches():
    """ExponentialLaw (<law> = empirical_laws) is named by exactly the recipe's library files;
    the recipe's test file names it too; users of the law (other tests, benches, docs of use)
    are not part of adding it."""
    files = [f.replace("<law>", "empirical_laws") for f in _recipe_files()]
    assert len(files) == 8, files
    root = pathlib.Path(SOURCE)
    library = {f for f in files if not f.startswith(("tests/", "docs/"))}
    assert _naming(root, "ExponentialLaw", skip=("tests", "bench", "demos", "docs")) == library
    assert all((root / f).exists() for f in files), files
    assert "ExponentialLaw" in (root / "tests/cpp/test_empirical_laws.cpp").read_text(encoding="utf-8")


def test_a_composed_law_is_one_file():
    """The toy law is named by its plugin file and its own test only (the recipe: one record in
    one file)."""
    assert _naming(pathlib.Path(SOURCE), toy.KEY) == {"tests/python/toy_law_plugin.py"}


def test_parameters_units_and_ranges_are_the_cpp_laws_own():
    """Every parametric record's quantities are its C++ class's parameter_specs() (names, symbols,
    file units, ranges): nothing re-declared in Python. The ranges are checked against their
    definitions (positivity; r in [0, 1), m >= 1: docs/hysteresis.md, H1-H2)."""
    for key, cls in (("barton_bandis", rockjoint.BartonBandis), ("logarithmic", rockjoint.LogarithmicLaw),
                     ("exponential", rockjoint.ExponentialLaw), ("normal_hysteresis", rockjoint.NormalHysteresis)):
        record = law_registry.get(key)
        specs = cls.parameter_specs()
        assert [(q.name, q.symbol, q.unit) for q in record.quantities()] == \
            [(s.name, s.symbol, s.file_unit) for s in specs], key
    r, m = law_registry.HISTORY_PARAMETERS
    assert (r.problem(0.0), r.problem(0.999), m.problem(1.0)) == (None, None, None)
    assert r.problem(1.0) == "must be in [0, 1)" and m.problem(0.5) == "must be finite and >= 1"
    assert law_registry.get("barton_bandis").quantities()[1].problem(-1e-3) == "must be finite and > 0"
    assert [q.name for q in law_registry.get("greenwood_williamson").quantities()] == \
        ["summit_density", "summit_radius", "summit_height_std"]


def test_one_range_check_for_files_and_scenes(tmp_path):
    """A parameter out of its C++ range is named the same way by a TOML parameter file and by a
    scene (the record's Quantity.problem), before any law is built."""
    from rockjoint.laws import read_law_file
    from rockjoint.scenes import SceneError, load_scene
    from scene_cases import COLUMN, write
    toml = tmp_path / "h.toml"
    toml.write_text('[law]\nmodel = "normal_hysteresis"\nvirgin = "barton_bandis"\npermanent_fraction = 1.2\n'
                    'unloading_exponent = 3.0\ninitial_normal_stiffness_MPa_per_mm = 20.0\n'
                    'maximum_closure_mm = 0.3\n', encoding="utf-8")
    with pytest.raises(ValueError, match=r"permanent_fraction = 1.2 is out of range: r must be in \[0, 1\)"):
        read_law_file(toml)
    scene = COLUMN.replace("model: barton_bandis\n", "model: normal_hysteresis\n      virgin: barton_bandis\n").replace(
        "parameters: {initial_normal_stiffness", "parameters: {permanent_fraction: 1.2, unloading_exponent: 3, "
        "initial_normal_stiffness")
    with pytest.raises(SceneError, match=r"permanent_fraction.*out of range: must be in \[0, 1\)"):
        load_scene(write(tmp_path, scene))


def test_the_exact_contact_registers_itself_beside_its_solver():
    """The registry does not import the BEM; contact.py registers the walls' exact contact."""
    import ast
    from rockjoint import contact
    source = (pathlib.Path(SOURCE) / "python" / "rockjoint" / "law_registry.py").read_text(encoding="utf-8")
    imported = {a.name for n in ast.walk(ast.parse(source)) if isinstance(n, ast.ImportFrom) for a in n.names}
    assert "contact" not in imported
    record = law_registry.topography_laws()[contact.EXACT_CONTACT]
    assert record.needs == "walls" and not record.parametric
    assert contact.EXACT_CONTACT not in law_registry.parametric_laws()
