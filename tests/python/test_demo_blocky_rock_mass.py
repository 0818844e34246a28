"""The blocky rock-mass demo runs as it is, serially and on 2 ranks.

Reference for the intact section (uniform biaxial plane-strain state, rollers on the left and
bottom): ε_yy = [(1-ν²)σ_v - ν(1+ν)σ_h]/E, ε_xx = [(1-ν²)σ_h - ν(1+ν)σ_v]/E, so the top settles
H ε_yy and the right face moves W ε_xx (P1 is exact for a uniform state). The jointed section
must settle more, and 2 ranks must give the serial answer to solver tolerance.
"""
import re

import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem")

import demo_runner  # noqa: E402

E, NU, W, H, SV, SH = 50e9, 0.25, 12.0, 8.0, 10e6, 5e6


def run_demo(out, ranks):
    demo_runner.run_demo("demo_blocky_rock_mass.py", out, ranks, ("--mesh-size", "0.8"))
    for name in ("blocky_rock_mass.png", "blocky_rock_mass.txt", "blocky_jointed.xdmf",
                 "blocky_jointed_joints.xdmf", "blocky_intact.xdmf"):
        assert (out / name).exists(), name
    text = (out / "blocky_rock_mass.txt").read_text()
    rows = {}
    for key in ("top settlement", "right face inward"):
        m = re.search(rf"^{key} \[mm\]\s+(\S+)\s+(\S+)$", text, re.M)
        assert m, text
        rows[key] = tuple(float(v) * 1e-3 for v in m.groups())  # (intact, jointed) [m]
    return rows


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def test_intact_section_is_the_closed_form_and_joints_add_deformation(serial):
    eyy = ((1 - NU**2) * SV - NU * (1 + NU) * SH) / E
    exx = ((1 - NU**2) * SH - NU * (1 + NU) * SV) / E
    # the demo prints 6 decimals of mm (1e-9 m): compare to that resolution
    assert serial["top settlement"][0] == pytest.approx(H * eyy, abs=1.5e-9)
    assert serial["right face inward"][0] == pytest.approx(W * exx, abs=1.5e-9)
    assert serial["top settlement"][1] > serial["top settlement"][0]
    assert serial["right face inward"][1] > serial["right face inward"][0]


def test_two_ranks_give_the_serial_answer(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    for key in serial:
        assert parallel[key] == pytest.approx(serial[key], abs=1.5e-9)
