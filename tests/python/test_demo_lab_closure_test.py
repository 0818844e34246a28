"""The main demo (laboratory joint-closure test) runs as it is, serially and on 2 ranks, and its
FE joint closure (jointed minus intact cube) equals the closure law's own inverse.

Tolerance: the FE model uses the Tang & Jiao *table* (σ within 1e-6 relative of the law); for a
convex σ(Δ) with σ(0) = 0, σ <= kΔ, so the closure error is at most the same 1e-6 relative; the
Newton tolerance (1e-10) adds nothing visible. Serial and parallel agree to solver tolerance.
"""
import numpy as np
import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem_coupling")

import demo_runner  # noqa: E402



def run_demo(out, ranks):
    demo_runner.run_demo("demo_lab_closure_test.py", out, ranks, ("--mesh-size", "0.05"))
    for name in ("lab_closure_test.png", "lab_closure_test_table.txt", "granite_tang_jiao.rjt",
                 "jointed_cube.xdmf", "jointed_cube_joints.xdmf", "intact_cube.xdmf"):
        assert (out / name).exists(), name
    # columns: σ [MPa], intact top, jointed top, closure FE, closure law [mm], rel. difference
    return np.loadtxt(out / "lab_closure_test_table.txt", comments="#")


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    return run_demo(tmp_path_factory.mktemp("serial"), 1)


def test_fe_closure_equals_the_law(serial):
    closure_fe, closure_law = serial[:, 3], serial[:, 4]
    assert np.all(closure_law > 0)
    np.testing.assert_allclose(closure_fe, closure_law, rtol=1e-6)
    # The jointed cube settles more than the intact one, by more at higher stress.
    assert np.all(serial[:, 2] > serial[:, 1]) and np.all(np.diff(closure_fe) > 0)


def test_two_ranks_give_the_serial_answer(serial, tmp_path):
    parallel = run_demo(tmp_path, 2)
    np.testing.assert_allclose(parallel[:, 1:5], serial[:, 1:5], rtol=1e-8)
