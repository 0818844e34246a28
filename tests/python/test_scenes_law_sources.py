# SPDX-License-Identifier: MIT
"""A scene's joint law from a saved table and from a measured curve to calibrate: the FE closure
of the scene's column (jointed minus intact top settlement) equals the closure of the law that
made the table / the curve (Barton-Bandis, K_ni = 20 MPa/mm, V_m = 0.2 mm, built here by the law
factory). Table: rtol 1e-5 (a 1e-6 table); curve: rtol 1e-3 (a least-squares fit of exact data)."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import rockjoint  # noqa: E402
from rockjoint.laws import make_law  # noqa: E402
from rockjoint.scenes import load_scene, make_plan, run_scene  # noqa: E402
from scene_cases import COLUMN, write  # noqa: E402

LAW_TEXT = """      model: barton_bandis
      parameters: {initial_normal_stiffness: 20 MPa/mm, maximum_closure: 0.2 mm}
"""
STRESS = 10e6   # the column's load [Pa]


def reference():
    return make_law("barton_bandis", initial_normal_stiffness=20e9, maximum_closure=0.2e-3)


def joint_closure(tmp_path, text):
    scene = load_scene(write(tmp_path, text))
    result = run_scene(scene, make_plan(scene), str(tmp_path / "out"))
    j, i = result.row("jointed", "load"), result.row("intact", "load")
    return i.monitors["top"][1] - j.monitors["top"][1], result


def test_law_from_a_saved_table(tmp_path):
    rockjoint.tabulate(reference(), max_stress=20e6, tolerance=1e-6).save(str(tmp_path / "joint.rjt"))
    assert LAW_TEXT in COLUMN
    closure, result = joint_closure(tmp_path, COLUMN.replace(LAW_TEXT, "      table: joint.rjt\n"))
    assert closure == pytest.approx(reference().closure_at_stress(STRESS), rel=1e-5)
    assert result.tables["joint"].table_maximum_stress == pytest.approx(20e6)   # used as saved


def test_law_calibrated_to_a_measured_curve(tmp_path):
    stress = np.array([0.5, 1, 2, 4, 6, 8, 12, 16, 20]) * 1e6
    closure = np.array([reference().closure_at_stress(s) for s in stress])
    rows = "\n".join(f"{c * 1e3:.9f}, {s * 1e-6:.6f}" for c, s in zip(closure, stress))
    (tmp_path / "curve.csv").write_text("closure [mm], normal_stress [MPa]\n" + rows + "\n")
    text = COLUMN.replace(LAW_TEXT, "      curve: curve.csv\n      fit: barton_bandis\n")
    fe, _ = joint_closure(tmp_path, text)
    assert fe == pytest.approx(reference().closure_at_stress(STRESS), rel=1e-3)
