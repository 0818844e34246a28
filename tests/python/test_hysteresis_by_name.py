# SPDX-License-Identifier: MIT
"""A law with history by name (law registry record, docs/hysteresis.md "By name"): built by the law
factory, read from a parameter file, named in a scene with its parameters or calibrated there to
load cycles, and tabulated. Every value is checked against the closed forms of (H1-H2) over the
Barton-Bandis hyperbola written out here, not against the library's own evaluation; the scene's
column unloads on its branch (jointed minus intact top settlement), not on the virgin curve."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import rockjoint  # noqa: E402
from rockjoint import law_registry  # noqa: E402
from rockjoint.laws import make_law, read_law_file  # noqa: E402
from rockjoint.scenes import SceneError, load_scene, make_plan, run_scene  # noqa: E402
from scene_cases import COLUMN, cli, write  # noqa: E402

KNI, VM = 20e9, 0.2e-3          # Barton-Bandis K_ni [Pa/m], V_m [m] (the scene column's law)
R, M = 0.25, 3.0                # permanent fraction, unloading exponent
PEAK, LOW = 10e6, 2e6           # the column's load and the stress it is unloaded to [Pa]
LAW_TEXT = """      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
"""
HISTORY_TEXT = """      model: normal_hysteresis
      virgin: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm,
                   permanent_fraction: 0.25, unloading_exponent: 3}
"""
UNLOAD = """  - name: unload
    loads: {top: {traction: [0 MPa, -2 MPa]}}
"""


def virgin_stress(d):
    return KNI * d / (1 - d / VM)


def virgin_closure(s):
    return s * VM / (KNI * VM + s)


def branch_closure(s, top):
    """(H1-H2) inverted: closure at stress s <= top after loading to top on the virgin curve."""
    dm = virgin_closure(top)
    dp = R * dm
    return dp + (dm - dp) * (s / top) ** (1 / M)


def test_factory_builds_the_law_with_history():
    law = make_law("normal_hysteresis", virgin="barton_bandis", initial_normal_stiffness=KNI,
                   maximum_closure=VM, permanent_fraction=R, unloading_exponent=M)
    assert law.has_history and not law.virgin.has_history
    assert law.name == law_registry.get(law.name).key      # the C++ name() is the registry key
    dm, d = 0.1e-3, 0.06e-3
    x = (d - R * dm) / (dm - R * dm)
    assert law.evaluate_with_history(d, dm)["normal_stress"] == pytest.approx(virgin_stress(dm) * x ** M,
                                                                                 rel=1e-12)
    assert law.normal_stress(d) == pytest.approx(virgin_stress(d), rel=1e-12)   # no history: virgin
    ready = make_law("normal_hysteresis", virgin=law.virgin, permanent_fraction=R, unloading_exponent=M)
    assert ready.evaluate_with_history(d, dm)["normal_stress"] == pytest.approx(virgin_stress(dm) * x ** M)
    with pytest.raises(ValueError, match="permanent_fraction"):
        make_law("normal_hysteresis", virgin="barton_bandis", initial_normal_stiffness=KNI, maximum_closure=VM)
    with pytest.raises(ValueError, match="virgin"):
        make_law("normal_hysteresis", virgin="normal_hysteresis", permanent_fraction=R, unloading_exponent=M)
    with pytest.raises(ValueError, match="unloading_exponent"):   # the C++ constructor's range
        make_law("normal_hysteresis", virgin=law.virgin, permanent_fraction=R, unloading_exponent=0.5)


def test_tabulating_keeps_the_branches_around_the_virgin_table():
    law = make_law("normal_hysteresis", virgin="barton_bandis", initial_normal_stiffness=KNI,
                   maximum_closure=VM, permanent_fraction=R, unloading_exponent=M)
    table = rockjoint.tabulate(law, max_stress=30e6, tolerance=1e-7)
    assert table.has_history and isinstance(table.virgin, rockjoint.TabulatedLaw)
    assert (table.permanent_fraction, table.unloading_exponent) == (R, M)
    dm = virgin_closure(PEAK)
    for s in (0.5e6, LOW, 7e6):
        d = branch_closure(s, PEAK)
        assert table.evaluate_with_history(d, dm)["normal_stress"] == pytest.approx(s, rel=1e-6)
    with pytest.raises(ValueError, match="has history"):
        rockjoint.TabulatedLaw.from_stress(law, 30e6, 1e-6, None, 20000)


def test_parameter_file_and_its_errors(tmp_path):
    text = ('[law]\nmodel = "normal_hysteresis"\nvirgin = "barton_bandis"\n'
            'initial_normal_stiffness_MPa_per_mm = 20.0\nmaximum_closure_mm = 0.2\n'
            'permanent_fraction = 0.25\nunloading_exponent = 3.0\n[table]\nmaximum_stress_MPa = 30\n')
    path = tmp_path / "h.toml"
    path.write_text(text)
    named, _ = read_law_file(path)
    dm = virgin_closure(PEAK)
    d = branch_closure(LOW, PEAK)
    assert named.law.evaluate_with_history(d, dm)["normal_stress"] == pytest.approx(LOW, rel=1e-12)
    for edit, words in ((("permanent_fraction = 0.25\n", ""), "missing permanent_fraction"),
                        (('virgin = "barton_bandis"', 'virgin = "normal_hysteresis"'), "virgin"),
                        (("maximum_closure_mm = 0.2\n", ""), "missing maximum_closure_mm"),
                        (("unloading_exponent = 3.0", "unloading_exponent = 0.5"), "unloading_exponent"),
                        (("maximum_closure_mm = 0.2", "maximum_closure_mm = 0.2\nseating = 1"), "unknown key")):
        path.write_text(text.replace(*edit))
        with pytest.raises(ValueError, match=words):
            read_law_file(path)
    path.write_text(text)
    code, _, err = cli("tabulate", path, "-o", tmp_path / "h.rjt")
    assert code != 0 and "with history" in err and "virgin" in err and "Traceback" not in err


def _unloaded_closure(tmp_path, law_text):
    """(jointed - intact top settlement) after loading the scene column to PEAK and unloading to LOW."""
    assert LAW_TEXT in COLUMN
    load = "    loads: {top: {traction: [0 MPa, -10 MPa]}}\n"
    assert load in COLUMN
    scene = load_scene(write(tmp_path, COLUMN.replace(LAW_TEXT, law_text).replace(load, load + UNLOAD)))
    result = run_scene(scene, make_plan(scene), str(tmp_path / "out"))
    out = []
    for stage in ("load", "unload"):
        j, i = result.row("jointed", stage), result.row("intact", stage)
        out.append(i.monitors["top"][1] - j.monitors["top"][1])
    return out


def test_scene_names_the_law_with_its_parameters(tmp_path):
    loaded, unloaded = _unloaded_closure(tmp_path, HISTORY_TEXT)
    assert loaded == pytest.approx(virgin_closure(PEAK), rel=1e-3)
    assert unloaded == pytest.approx(branch_closure(LOW, PEAK), rel=1e-3)
    # the branch keeps far more closure than the virgin curve would at the same stress
    assert unloaded > 1.4 * virgin_closure(LOW)   # 1.48 by the closed forms


def test_scene_calibrates_the_law_to_load_cycles(tmp_path):
    """Cycles generated from the closed form (load to PEAK, unload to 0.5 MPa, reload beyond)."""
    up = np.linspace(0.5e6, PEAK, 8)
    down = np.linspace(PEAK, 0.5e6, 8)[1:]
    further = np.array([4e6, 8e6, PEAK, 12e6, 14e6])
    rows = [(s, virgin_closure(s)) for s in up] + [(s, branch_closure(s, PEAK)) for s in down]
    rows += [(s, branch_closure(s, PEAK) if s <= PEAK else virgin_closure(s)) for s in further]
    (tmp_path / "cycles.csv").write_text("normal_stress [MPa], closure [mm]\n"
                                         + "".join(f"{s * 1e-6:.6f}, {d * 1e3:.9f}\n" for s, d in rows))
    loaded, unloaded = _unloaded_closure(tmp_path, "      cycles: cycles.csv\n      fit: barton_bandis\n")
    assert loaded == pytest.approx(virgin_closure(PEAK), rel=1e-3)
    assert unloaded == pytest.approx(branch_closure(LOW, PEAK), rel=1e-3)


@pytest.mark.parametrize("edit, words", [
    (("permanent_fraction: 0.25", "permanent_fraction: 1.0"), "permanent_fraction.*in \\[0, 1\\)"),
    (("unloading_exponent: 3", "unloading_exponent: 0.5"), "unloading_exponent.*>= 1"),
    (("      virgin: barton_bandis\n", ""), "virgin"),
    (("virgin: barton_bandis", "virgin: normal_hysteresis"), "virgin"),
    ((", unloading_exponent: 3", ""), "missing parameter 'unloading_exponent'"),
])
def test_scene_refuses_a_bad_law_with_history(tmp_path, edit, words):
    with pytest.raises(SceneError, match=words):
        load_scene(write(tmp_path, COLUMN.replace(LAW_TEXT, HISTORY_TEXT.replace(*edit))))


def test_scene_refuses_cycles_without_fit(tmp_path):
    (tmp_path / "cycles.csv").write_text("normal_stress [MPa], closure [mm]\n1, 0.01\n")
    with pytest.raises(SceneError, match="cycles needs fit"):
        load_scene(write(tmp_path, COLUMN.replace(LAW_TEXT, "      cycles: cycles.csv\n")))
