# SPDX-License-Identifier: MIT
"""The blocky rock-mass demo runs as it is, serially and on 2 ranks, with and without joint slip.

Reference for the intact section (uniform biaxial plane-strain state, rollers on the left and
bottom): ε_yy = [(1-ν²)σ_v - ν(1+ν)σ_h]/E, ε_xx = [(1-ν²)σ_h - ν(1+ν)σ_v]/E, so the top settles
H ε_yy and the right face moves W ε_xx (P1 is exact for a uniform state), at every stage of the
load path. The jointed sections must settle more; slip can only add to it. The slipping joints'
points are checked against the strength the demo states (Coulomb, φ = 30°, c = 0: the basic
friction angle of wet granite, Barton & Choubey 1977), written independently here: a slipping
point lies on |τ| = c + σ_n tan φ, slips in the direction of its shear stress, a sticking point
lies strictly inside, an open point carries (next to) no traction. The elastic joints must break
that envelope somewhere (otherwise the scene would show no slip). 2 ranks give the serial answer.
"""
import math
import re

import numpy as np
import pytest

from fe_stack import require, require_fe  # noqa: E402
require_fe()
meshio = require("meshio")

import demo_runner  # noqa: E402

E, NU, W, H, SH = 50e9, 0.25, 12.0, 8.0, 5e6
STAGE_SV = (10e6, 20e6)                       # vertical stress at the end of stages 1, 2 [Pa]
PHI, COHESION = math.radians(30.0), 0.0       # the stated joint strength
STICK, SLIP, OPEN = 0, 1, 2                   # ShearState values (joint/joint_behaviour.hpp)
MM = 1.5e-9                                   # the demo prints 6 decimals of mm [m]


def run_demo(out, ranks):
    demo_runner.run_demo("demo_blocky_rock_mass.py", out, ranks, ("--mesh-size", "0.8"))
    for name in ("blocky_rock_mass.png", "blocky_joint_slip.png", "blocky_rock_mass.txt",
                 "blocky_intact.xdmf", "blocky_jointed.xdmf", "blocky_jointed_joints.xdmf",
                 "blocky_slip.xdmf", "blocky_slip_joints.xdmf"):
        assert (out / name).exists(), name
    text = (out / "blocky_rock_mass.txt").read_text()
    rows = {}
    for stage in (1, 2):
        for key in ("top settlement", "right face inward"):
            m = re.search(rf"^stage {stage} {key} \[mm\]\s+(\S+)\s+(\S+)\s+(\S+)$", text, re.M)
            assert m, text
            rows[(stage, key)] = tuple(float(v) * 1e-3 for v in m.groups())  # intact, elastic, slip [m]
    joints = {}
    for m in re.finditer(r"^slip\s+(\d)\s+(\w+)\s+(\d+)\s+(\d+)\s+(\d+)\s+(\S+)", text, re.M):
        joints[(int(m[1]), m[2])] = (int(m[3]), int(m[4]), int(m[5]), float(m[6]) * 1e-3)
    assert set(joints) == {(s, j) for s in (1, 2) for j in ("bedding", "cross")}, text
    return rows, joints, out


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def joint_points(path):
    cloud = meshio.read(str(path))
    d = cloud.point_data
    return (d["normal_stress_Pa"], np.abs(d["shear_traction_Pa"][:, 0]), d["shear_state"],
            d["slip_m"][:, 0], d["shear_traction_Pa"][:, 0])


def test_intact_section_is_the_closed_form_at_every_stage(serial):
    rows = serial[0]
    for stage, sv in zip((1, 2), STAGE_SV):
        eyy = ((1 - NU**2) * sv - NU * (1 + NU) * SH) / E
        exx = ((1 - NU**2) * SH - NU * (1 + NU) * sv) / E
        assert rows[(stage, "top settlement")][0] == pytest.approx(H * eyy, abs=MM)
        assert rows[(stage, "right face inward")][0] == pytest.approx(W * exx, abs=MM)


def test_joints_add_settlement_and_slip_adds_more_never_less(serial):
    rows, joints, _ = serial
    for stage in (1, 2):
        intact, elastic, slipping = rows[(stage, "top settlement")]
        assert elastic > intact
        assert slipping >= elastic - MM
    # stage 1 stays inside the strength everywhere: the slipping model is the elastic one
    assert all(joints[(1, s)][1] == 0 and joints[(1, s)][3] == 0.0 for s in ("bedding", "cross"))
    for key in ("top settlement", "right face inward"):
        assert rows[(1, key)][2] == pytest.approx(rows[(1, key)][1], abs=MM)
    # the raised vertical load makes the cross joints slip: more settlement, and the blocks
    # riding down the cross joints push the right face further out (inward move more negative)
    assert joints[(2, "cross")][1] > 0
    assert rows[(2, "top settlement")][2] > rows[(2, "top settlement")][1] + 10 * MM
    assert rows[(2, "right face inward")][2] < rows[(2, "right face inward")][1] - 10 * MM


def test_elastic_joints_break_the_strength_the_slipping_ones_respect(serial):
    out = serial[2]
    sn, tau, _, _, _ = joint_points(out / "blocky_jointed_joints.xdmf")
    closed = sn > 0
    assert (tau[closed] > COHESION + sn[closed] * math.tan(PHI)).any()


def test_slipping_points_lie_on_the_coulomb_envelope(serial):
    _, joints, out = serial
    sn, tau, state, slip, tau_signed = joint_points(out / "blocky_slip_joints.xdmf")
    strength = COHESION + np.maximum(sn, 0.0) * math.tan(PHI)
    on = state == SLIP
    assert on.sum() == sum(joints[(2, s)][1] for s in ("bedding", "cross"))
    assert np.allclose(tau[on], strength[on], rtol=1e-6, atol=0.0)
    # the slip follows the shear stress (monotonic load path: slip and τ have one sign)
    moving = on & (np.abs(slip) > 0)
    assert moving.any() and (np.sign(slip[moving]) == np.sign(tau_signed[moving])).all()
    stick = state == STICK
    assert stick.any() and (tau[stick] < strength[stick]).all()
    opened = state == OPEN
    # an open joint only keeps the table's opening stiffness k_res = 1e-6 σ_max/Δ_max: < 1 kPa
    assert (np.abs(sn[opened]) < 1e3).all() and (tau[opened] < 1e3).all()
    assert np.abs(slip).max() == pytest.approx(max(joints[(2, s)][3] for s in ("bedding", "cross")),
                                               abs=1.5e-9)


def test_two_ranks_give_the_serial_answer(serial, tmp_path):
    rows, joints, _ = serial
    p_rows, p_joints, _ = run_demo(tmp_path, 2)
    for key in rows:
        assert p_rows[key] == pytest.approx(rows[key], abs=MM)
    for key in joints:
        assert p_joints[key][:3] == joints[key][:3]
        assert p_joints[key][3] == pytest.approx(joints[key][3], abs=MM)
