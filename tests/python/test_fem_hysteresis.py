# SPDX-License-Identifier: MIT
"""FE column with a hysteretic joint (docs/hysteresis.md) loaded, unloaded and reloaded: the
joint closure equals the closed form at every stage (virgin, branch, permanent closure, reload,
virgin again), the top keeps the permanent closure at zero load, the Newton Jacobian matches
finite differences on both sides of the branch switch, and an in-situ pre-closed joint unloads
on its branch."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from jacobian_checks import assert_jacobian_matches_fd  # noqa: E402
from hysteresis_cases import (KNI, M, PEAK, R, VM, check_cycle, expected_closures,  # noqa: E402
                              hysteretic_column, run_cycle, virgin_closure)

import rockjoint  # noqa: E402
from rockjoint.fem import InSituStress  # noqa: E402


def test_column_follows_the_hysteretic_law_through_a_cycle():
    check_cycle(*run_cycle(hysteretic_column()))


@pytest.mark.parametrize("shear", [{"shear_stiffness": 1e9}, {"shear_stiffness_ratio": 0.1}],
                         ids=["constant k_s", "k_s = 0.1 k_n"])
def test_jacobian_on_both_sides_of_the_branch_switch(shear):
    """Converged at the peak (Δ_m set), then u scaled to 0.9 (on the branch) and 1.1 (past Δ_m,
    virgin), and exactly at the peak (the switch itself, where the virgin tangent applies): the
    assembled tangent equals finite differences of the residual (central off the switch). With
    k_s ∝ k_n the shear tangent carries dk/dΔ, taken on the branch in force."""
    model = hysteretic_column(**shear)
    model.advance(1.0, load_steps=2)
    u_peak = model.u.x.array.copy()
    for scale in (0.9, 1.1):
        u = scale * u_peak
        assert_jacobian_matches_fd(model, u, relative_step=1e-7, label=f"u = {scale} u_peak: ")


def test_sheared_joint_jacobian_at_and_around_the_switch():
    """A block on a 25° hysteretic joint under 8 MPa normal and 1 MPa shear, k_s = 0.1 k_n: after
    the converged load the Newton start sits exactly on Δ_m. k_s follows the virgin k (continuous
    there; the branch's k jumps, which would make the shear traction jump and put k_v/h ~ 1e17 into
    the matrix through dk_s/dΔ); around it the tangent matches central differences on each side,
    and a small unloading from the peak converges."""
    from mpi4py import MPI
    from rockjoint import meshes
    from rockjoint.fem import JointedRockModel, NewtonOptions
    from rockjoint.fem.mesh.distributed_mesh import distribute
    comm = MPI.COMM_WORLD
    jm = meshes.jointed_block((1.0, 1.0), [meshes.Joint((0.5, 0.5), 25.0, 90.0, "j")], dim=2,
                              mesh_size=0.35, comm=comm)
    law = rockjoint.NormalHysteresis(rockjoint.BartonBandis(2e10, 1e-3), R, M)
    model = JointedRockModel(distribute(jm, comm), rock=(10e9, 0.3), joints={"j": law}, plane="strain",
                             shear_stiffness_ratio=0.1, newton=NewtonOptions(verbose=False))
    model.fix("bottom", "all")
    model.add_traction("top", [1e6, -8e6])
    model.advance(1.0, load_steps=2)
    u_peak = model.u.x.array.copy()
    norms = {}
    for scale in (1.0, 1.1):
        model.u.x.array[:] = scale * u_peak
        problem = model.problem()
        problem.residual_norm()
        problem.update_jacobian()
        norms[scale] = problem.J.norm()
    assert norms[1.0] < 2 * norms[1.1]
    for scale in (0.9, 1.1):
        assert_jacobian_matches_fd(model, scale * u_peak, relative_step=1e-7, label=f"u = {scale} u_peak: ")
    model.u.x.array[:] = u_peak
    # One step, no cut: the shear traction is continuous at Δ_m, so the unloading step from the
    # peak converges in one load step (advance raises instead of cutting it), with full Newton
    # steps only and few of them (measured: 3 on PETSc 3.25).
    result = model.advance(0.999, load_steps=1)
    (report,) = result.reports
    assert report.converged and set(report.step_lengths) == {1.0} and report.iterations <= 5, report


def test_branch_tangent_is_stiffer_than_the_virgin_one_at_the_peak():
    """A 1 % unloading from the peak moves the top less than a 1 % loading: (H4) ratio
    m σ_m / ((1 - r) Δ_m k_v) > 1 for these parameters."""
    model = hysteretic_column()
    model.advance(1.0, load_steps=2)
    top = model.boundary_mean_displacement("top")[1]
    model.advance(0.99)
    down = abs(model.boundary_mean_displacement("top")[1] - top)
    model.advance(1.0)
    model.advance(1.01)
    up = abs(model.boundary_mean_displacement("top")[1] - top)
    dm = virgin_closure(PEAK)
    ratio = M * PEAK / ((1 - R) * dm) / (KNI / (1 - dm / VM) ** 2)
    assert ratio > 1 and down < up


def test_in_situ_pre_closure_unloads_on_the_branch():
    """A joint closed by an in-situ σ_v = 8 MPa was loaded to that closure on its virgin curve:
    excavation-like unloading to σ_v/4 and to σ_v/100 follows the branch from Δ(σ_v) down toward
    the permanent closure r Δ(σ_v), not toward zero."""
    model = hysteretic_column(top_traction=False)
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-2e6, -PEAK])))
    joints = model.solve(name="in-situ").gather_joints()
    if joints is not None:
        np.testing.assert_allclose(joints["closure"], virgin_closure(PEAK), rtol=1e-10)
    release = model.excavate("top", fraction_left=0.25)
    expected = expected_closures([PEAK, 0.25 * PEAK, 0.01 * PEAK])
    for stage, target in ((1, 0.25), (2, 0.01)):
        release.value = target
        joints = model.solve(load_steps=2).gather_joints()
        if joints is not None:
            np.testing.assert_allclose(joints["closure"], expected[stage], rtol=1e-8)
    # an elastic joint would spring back to Δ(σ_v/100) = 8e-6 m; this one stays above r Δ(σ_v)
    assert expected[2] > R * virgin_closure(PEAK) > 10 * virgin_closure(0.01 * PEAK)
