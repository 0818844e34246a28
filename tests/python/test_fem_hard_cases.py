# SPDX-License-Identifier: MIT
"""Hard cases of the joint model: step control past K_ni·V_m, a very stiff joint, an open joint
holding a block (singular → clear error; residual stiffness → documented exact behaviour)."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, LinearSolveError, NewtonOptions  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402

E, NU = 20e9, 0.25


def column(height, joints, width=1.0, mesh_size=0.25):
    jm = meshes.column(width, height, joints, dim=2, mesh_size=mesh_size, comm=MPI.COMM_WORLD)
    return distribute(jm, MPI.COMM_WORLD)


def test_load_far_beyond_kni_vm_in_one_step_converges_by_closure_limiting():
    """σ = 30 K_ni V_m in one load step: plain Newton from Δ = 0 would close the joints past V_m
    (σ = ∞); the closure-limiting step keeps every trial inside (0, V_m) and converges to the
    closed form Δ = σ V_m / (K_ni V_m + σ) = 0.968 V_m."""
    Kni, Vm = 1e10, 1e-3
    law = rockjoint.BartonBandis(Kni, Vm)
    stress = 30 * Kni * Vm
    model = JointedRockModel(column(3.0, (1.0, 2.0)), rock=(E, NU),
                             joints={"joint_1": law, "joint_2": law}, shear_stiffness=1e9)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -stress))
    sol = model.solve(load_steps=1)
    assert sol.reports[0].converged and len(sol.reports) == 1  # no load-step cut was needed
    assert min(sol.reports[0].step_lengths) < 1.0  # ... because the step limiter acted
    closure = stress * Vm / (Kni * Vm + stress)
    ref = -(stress * 3.0 * (1 - NU**2) / E + 2 * closure)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)
    assert np.all(sol.gather_joints()["closure"] < Vm)


def test_load_step_cut_and_regrowth_without_limiter():
    """With the limiter switched off (closure_limit → 1 would still limit, so allow only a few
    iterations) a failed step is cut and the load is still reached."""
    Kni, Vm = 1e10, 1e-3
    law = rockjoint.BartonBandis(Kni, Vm)
    stress = 30 * Kni * Vm
    opts = NewtonOptions(max_iterations=6, verbose=False)
    model = JointedRockModel(column(2.0, (1.0,)), rock=(E, NU), joints={"joint_1": law},
                             shear_stiffness=1e9, newton=opts)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -stress))
    sol = model.solve(load_steps=1)
    assert any(not r.converged for r in sol.reports)  # at least one cut
    assert sol.reports[-1].converged and sol.reports[-1].load_factor == 1.0
    closure = stress * Vm / (Kni * Vm + stress)
    ref = -(stress * 2.0 * (1 - NU**2) / E + closure)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)


def _profile(joints):
    """Normal stress along x (points at the same x merged), sorted by x."""
    x, s = joints["coordinates"][:, 0], joints["normal_stress"]
    xs = np.unique(np.round(x, 10))
    return xs, np.array([s[np.isclose(x, v, atol=1e-9)].mean() for v in xs])


def test_very_stiff_joint_has_smooth_tractions_with_nodal_quadrature():
    """k_n h / E = 1e4 under a cantilevered upper block (clamped on its left side, loaded on top):
    the joint opens near the wall and the traction rises to a single peak. With the nodal rule the
    profile is smooth: non-negative, one maximum (no zig-zag), and every node on both sides agrees."""
    h = 0.1
    dmesh = column(1.0, (0.5,), width=2.0, mesh_size=h)
    kn = 1e4 * E / h
    law = rockjoint.BartonBandis(kn, 1.0)  # V_m ≫ closures: a linear spring of stiffness k_n
    model = JointedRockModel(dmesh, rock=(E, 0.2), joints={"joint_1": law}, shear_stiffness=kn,
                             quadrature="nodal", newton=NewtonOptions(verbose=False))
    model.fix("bottom", "all")
    model.fix("left", "all", block="block_2")
    p = 1e6
    model.add_traction("top", (0.0, -p))
    sol = model.solve()
    xs, s = _profile(sol.gather_joints())
    assert s.min() >= 0.0
    slope_signs = np.sign(np.diff(s)[np.abs(np.diff(s)) > 1e-9 * p])
    turns = np.count_nonzero(slope_signs[1:] != slope_signs[:-1])
    assert turns <= 1, f"oscillating joint traction profile: {s / p}"
    # Equilibrium: the joint carries the load not taken by the wall; bounded by the applied force.
    assert 0.0 < s.max() < 2 * p


def test_open_joint_holding_a_block_is_a_clear_error():
    """Top block pulled off its only support, the joint (law: σ = k = 0 when open): the Jacobian is
    singular; solve() raises LinearSolveError naming the cause, it never returns garbage."""
    model = JointedRockModel(column(2.0, (1.0,)), rock=(E, NU),
                             joints={"joint_1": rockjoint.BartonBandis(1e10, 1e-3)}, shear_stiffness=1e9)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, 1e6))
    with pytest.raises(LinearSolveError, match="singular"):
        model.solve()


@pytest.mark.parametrize("source", ["assembler", "table"])
def test_residual_stiffness_gives_the_documented_opening(source):
    """With a residual stiffness k_r (assembler option, or the TabulatedLaw's own k_res for Δ <= 0)
    the open joint is a linear spring: opening = p / k_r, top displacement = p H/E' + p/k_r."""
    p, kr, H = 1e5, 1e9, 2.0
    bb = rockjoint.BartonBandis(1e10, 1e-3)
    if source == "assembler":
        law, extra = bb, {"residual_stiffness": kr}
    else:
        law, extra = rockjoint.tabulate(bb, max_stress=20e6, residual_stiffness=kr), {}
    model = JointedRockModel(column(H, (1.0,)), rock=(E, NU), joints={"joint_1": law}, shear_stiffness=1e9,
                             **extra)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, p))
    sol = model.solve()
    ref = p * H * (1 - NU**2) / E + p / kr
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)
    joints = sol.gather_joints()
    np.testing.assert_allclose(joints["closure"], -p / kr, rtol=1e-8)
    assert np.all(joints["status"] == int(rockjoint.Status.open))


def test_backtracking_line_search_option_reaches_the_same_answer():
    """NewtonOptions(line_search=True): Armijo backtracking after the closure limit, same answer,
    and at least one step shorter than the closure limit alone would give."""
    Kni, Vm = 1e10, 1e-3
    law = rockjoint.BartonBandis(Kni, Vm)
    stress = 30 * Kni * Vm
    model = JointedRockModel(column(2.0, (1.0,)), rock=(E, NU), joints={"joint_1": law}, shear_stiffness=1e9,
                             newton=NewtonOptions(line_search=True, verbose=False))
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_traction("top", (0.0, -stress))
    sol = model.solve()
    assert all(r.converged for r in sol.reports)
    norms = sol.reports[-1].residual_norms
    assert all(b < a for a, b in zip(norms, norms[1:]))  # monotone decrease: the Armijo condition
    closure = stress * Vm / (Kni * Vm + stress)
    ref = -(stress * 2.0 * (1 - NU**2) / E + closure)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(ref, rel=1e-8)
