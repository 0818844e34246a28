# SPDX-License-Identifier: MIT
"""Column of N horizontal joints under uniaxial stress (2D plane strain and 3D), serial.

Supports are rollers (bottom: vertical; left: x; 3D front: y) and the sides are free, so the
exact solution is a uniform uniaxial stress σ in every block: the P1 solution is exact and
    top displacement = -(σ H / E' + N Δ(σ)),  E' = E/(1-ν²) (plane strain), E (3D),
with Δ(σ) the joint law's own inverse (Barton-Bandis closed form; the Tang & Jiao table's
closure_at_stress). Tolerance 1e-8 relative. Newton's residual norms are read back from the
printed convergence report and must show quadratic convergence.
"""
import logging
import warnings
import math
import re

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions, RangeWarning  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402

E, NU = 20e9, 0.25
HEIGHT, JOINTS = 3.0, (1.0, 2.0)
KNI, VM = 1e10, 1e-3  # Barton-Bandis K_ni [Pa/m], V_m [m]


def column_model(dim, law, mesh_size=0.5, comm=MPI.COMM_WORLD, **kw):
    jm = meshes.column(1.0, HEIGHT, JOINTS, dim=dim, mesh_size=mesh_size, comm=comm)
    dmesh = distribute(jm, comm)
    joints = {f"joint_{i + 1}": law for i in range(len(JOINTS))}
    model = JointedRockModel(dmesh, rock=(E, NU), joints=joints, shear_stiffness=1e9,
                             plane="strain" if dim == 2 else None, **kw)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    return model


def expected_top(dim, stress, closure):
    modulus = E / (1 - NU**2) if dim == 2 else E
    return -(stress * HEIGHT / modulus + len(JOINTS) * closure)


def printed_residuals(text):
    return [float(x) for x in re.findall(r"\|\|r\|\| = (\S+)", text)]


def assert_quadratic(norms):
    """Order p = log(r_{k+1}/r_k) / log(r_k/r_{k-1}) of the last three norms above round-off."""
    r0 = norms[0]
    useful = [r for r in norms if r > 1e-11 * r0]
    assert len(useful) >= 3, f"too few iterations to measure a rate: {norms}"
    a, b, c = useful[-3:]
    order = math.log(c / b) / math.log(b / a)
    assert order > 1.8, f"Newton is not quadratic: order {order:.2f} from residuals {norms}"


@pytest.mark.parametrize("dim", [2, 3])
def test_column_barton_bandis_matches_closed_form(dim, caplog):
    law = rockjoint.BartonBandis(KNI, VM)
    stress = 5e6  # σ/(K_ni V_m) = 0.5: well inside the nonlinear range
    model = column_model(dim, law)
    top = [0.0] * dim
    top[-1] = -stress
    model.add_traction("top", top)
    caplog.set_level(logging.INFO, logger="rockjoint.fem.solvers.newton")
    sol = model.solve(load_steps=1)
    closure = stress * VM / (KNI * VM + stress)  # Barton-Bandis inverse, closed form
    u_top = model.boundary_mean_displacement("top")[dim - 1]
    ref = expected_top(dim, stress, closure)
    assert u_top == pytest.approx(ref, rel=1e-8)
    joints = sol.gather_joints()
    np.testing.assert_allclose(joints["closure"], closure, rtol=1e-8)
    np.testing.assert_allclose(joints["normal_stress"], stress, rtol=1e-8)
    assert np.max(np.abs(joints["shear_traction"])) < 1e-8 * stress
    # The residual norms Newton logs (INFO, rockjoint.fem.solvers.newton) are the ones it records.
    logged = printed_residuals(caplog.text)
    assert logged == pytest.approx([n for r in sol.reports for n in r.residual_norms], rel=1e-6)
    assert_quadratic(logged)


@pytest.mark.parametrize("dim", [2, 3])
def test_column_tang_jiao_table_matches_its_inverse(dim):
    """Same column with a tabulated Tang & Jiao law (I1 over a logarithmic base)."""
    base = rockjoint.LogarithmicLaw(0.05e-3, 0.1e6)
    x = np.linspace(0.0, 1e-3, 801)
    tj = rockjoint.TangJiao(base, 50e9 / (2 * (1 - 0.25**2)), 2.5e-3, 0.05e-3,
                            overlap_closure=x, overlap_area_ratio=0.5 * (1 - np.exp(-x / 0.2e-3)),
                            maximum_area_root=0.6)
    table = rockjoint.tabulate(tj, max_stress=15e6)  # validity limit ≈ 18 MPa
    stress = 8e6
    model = column_model(dim, table)
    top = [0.0] * dim
    top[-1] = -stress
    model.add_traction("top", top)
    model.solve(load_steps=1)
    closure = table.closure_at_stress(stress)
    u_top = model.boundary_mean_displacement("top")[dim - 1]
    assert u_top == pytest.approx(expected_top(dim, stress, closure), rel=1e-8)


def test_load_steps_reach_the_same_answer_and_report_every_step():
    law = rockjoint.BartonBandis(KNI, VM)
    stress = 5e6
    model = column_model(2, law)
    model.add_traction("top", (0.0, -stress))
    sol = model.solve(load_steps=4)
    assert len([r for r in sol.reports if r.converged]) >= 2  # several steps (adaptive growth allowed)
    assert sol.reports[-1].load_factor == 1.0
    closure = stress * VM / (KNI * VM + stress)
    assert model.boundary_mean_displacement("top")[1] == pytest.approx(expected_top(2, stress, closure), rel=1e-8)


def test_body_force_joint_carries_the_weight_above():
    """Self-weight ρg of a 2-block column (rollers, free sides): the upper block is in equilibrium
    between its weight and the joint, so Σ (nodal weight × normal stress) over the joint = ρ g (H - h)
    × width exactly (FE equilibrium; the nodal rule weights are measure / 2)."""
    rho_g, width, H, h = 2.7e3 * 9.81, 2.0, 3.0, 1.0
    jm = meshes.column(width, H, (h,), dim=2, mesh_size=0.3, comm=MPI.COMM_WORLD)
    model = JointedRockModel(distribute(jm, MPI.COMM_WORLD), rock=(E, NU),
                             joints={"joint_1": rockjoint.BartonBandis(KNI, VM)}, shear_stiffness=1e9)
    model.fix("bottom", "y")
    model.fix("left", "x")
    model.add_body_force((0.0, -rho_g))
    sol = model.solve()
    state = model.interface.state()
    measures = model.interface._cpp.measures
    force = np.sum(np.repeat(measures, 2) / 2 * state["normal_stress"])
    force = MPI.COMM_WORLD.allreduce(force)
    assert force == pytest.approx(rho_g * (H - h) * width, rel=1e-9)
    joints = sol.gather_joints()
    assert np.all(joints["normal_stress"] > 0)


def test_a_table_driven_past_its_range_is_reported_not_silent():
    """A Barton-Bandis table up to 5 MPa loaded to 8 MPa: the joints answer on the table's
    linear continuation (status validity_limit); the solution says so per joint and the model
    warns (rockjoint.fem.RangeWarning, once). Inside the range nothing is reported."""
    law = rockjoint.BartonBandis(KNI, VM)
    table = rockjoint.tabulate(law, max_stress=5e6)
    model = column_model(2, table, newton=NewtonOptions(verbose=False))
    model.add_traction("top", (0.0, -8e6))
    with pytest.warns(RangeWarning, match="past its range.*joint 'joint_1'") as said:
        sol = model.solve()
    assert len([w for w in said if issubclass(w.category, RangeWarning)]) == 1
    beyond = sol.beyond_law_range()
    assert set(beyond) == {f"joint_{i + 1}" for i in range(len(JOINTS))}
    assert all(n > 0 for n in beyond.values())
    inside = column_model(2, table, newton=NewtonOptions(verbose=False))
    inside.add_traction("top", (0.0, -3e6))
    with warnings.catch_warnings():
        warnings.simplefilter("error", RangeWarning)      # silent inside the range
        assert inside.solve().beyond_law_range() == {}
