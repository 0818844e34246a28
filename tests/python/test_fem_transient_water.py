# SPDX-License-Identifier: MIT
"""Transient water along one stiff joint (issue 45, item 3; rockjoint.fem.water.transient): a
pressure step Δp at x = 0 of a joint 0 <= x <= L under a uniform total normal stress, no flow at
x = L. With T constant and the storage S = α/k_n + e c_w of the joint's normal stiffness and the
water's compressibility, the pressure diffuses (linear diffusion, D = T / (μ S)); the reference is
the closed form, the erfc solution with its images for the closed end (Carslaw & Jaeger 1959,
§2.5)::

    p(x, t) = p0 + Δp Σ_n (-1)^n [erfc((2nL + x) / (2√(Dt))) + erfc((2(n+1)L - x) / (2√(Dt)))].

k_n is Barton-Bandis' tangent K_ni / (1 - Δ/V_m)² at the closure of the closed form, with a V_m
so large that it stays constant to 1e-6 over the step (a stiff, linear joint). Two way, the
opening is the mechanics' own (soft blocks pass the top traction to the joint undistributed);
one way, the storage coefficient stands in for it: both must follow the closed form, converging
at first order in the time step (backward Euler)."""
import math

import numpy as np
import pytest
from scipy.special import erfc

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import Fluid, JointedRockModel, NewtonOptions, distribute  # noqa: E402
from rockjoint.fem.water.joint_pressure import set_joint_pressure  # noqa: E402
from rockjoint.fem.water.transient import coupled_transient  # noqa: E402

KNI, VM = 1e10, 1.0          # a stiff joint, linear to 1e-6 (V_m >> Δ)
SIGMA = 5e6                  # total normal stress [Pa]
P0, DP = 1e6, 1e6            # initial pressure and the step at x = 0 [Pa]
T0 = (1e-4) ** 3 / 12.0      # transmissivity of a 0.1 mm hydraulic aperture [m³]
LENGTH = 1.0
FLUID = Fluid()


def stiffness(effective):
    """Barton-Bandis' tangent at the closure of σ' (closed forms)."""
    d = effective * VM / (KNI * VM + effective)
    return KNI / (1.0 - d / VM) ** 2


def reference(x, t, compressibility):
    s = 1.0 / stiffness(SIGMA - P0) + (12.0 * T0) ** (1.0 / 3.0) * compressibility
    d = T0 / (FLUID.viscosity * s)
    r = 2.0 * math.sqrt(d * t)
    series = sum((-1) ** n * (erfc((2 * n * LENGTH + x) / r) + erfc((2 * (n + 1) * LENGTH - x) / r)) for n in range(6))
    return P0 + DP * series, d


def wet_column(dim, comm, joint_size):
    jm = meshes.column(LENGTH, 2.0, [1.0], dim=dim, mesh_size=0.25 if dim == 2 else 0.5, joint_mesh_size=joint_size,
                       comm=comm)
    model = JointedRockModel(distribute(jm, comm), rock=(1e5, 0.0), joints={"joint_1": rockjoint.BartonBandis(KNI, VM)},
                             shear_stiffness=1e6, plane="strain" if dim == 2 else None,
                             newton=NewtonOptions(verbose=False))
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    model.add_traction("top", (0.0,) * (dim - 1) + (-SIGMA,))
    set_joint_pressure(model, P0)
    model.solve(name="in situ, wet")
    return model


def run(coupling, steps, dim=2, comm=MPI.COMM_WORLD, joint_size=0.025, duration=0.05,
        compressibility=4.59e-10):
    model = wet_column(dim, comm, joint_size)
    water = coupled_transient(model, {"joint_1": lambda d: np.full_like(d, T0)}, duration, steps,
                              pressures={"left": P0 + DP}, fluid=FLUID, coupling=coupling,
                              compressibility=compressibility, tolerance=1e-10)
    state = model.solution.gather_joints()
    x = np.asarray(state["coordinates"]).reshape(-1, dim)[:, 0]
    p_ref, d = reference(np.clip(x, 0, LENGTH), duration, compressibility)
    error = np.max(np.abs(water.pressures[-1] - p_ref)) / DP
    return model, water, state, error, d


@pytest.mark.parametrize("coupling", ["two_way", "one_way"])
def test_a_pressure_step_diffuses_as_the_erfc_solution(coupling):
    errors = []
    for steps in (10, 20):
        model, water, state, error, d = run(coupling, steps)
        errors.append(error)
        print(f"{coupling}, {steps} steps: max |p - p_ref| / Δp = {error:.3e} (D = {d:.3g} m²/s, "
              f"iterations per step {water.iterations})")
    # the front has travelled (not a trivial answer): half the step reaches x ≈ √(D t)
    assert 0.2 < math.sqrt(d * 0.05) < 0.5
    assert errors[-1] < 0.02 and errors[-1] < 0.65 * errors[0]       # first order in Δt
    if coupling == "two_way":
        # the mechanics' opening is the joint's compliance: σ'_n = σ - p at every point
        np.testing.assert_allclose(np.asarray(state["normal_stress"]) + water.pressures[-1], SIGMA, rtol=1e-3)
        assert max(water.iterations) < 15


def test_the_water_compressibility_is_storage_too():
    """A compressible fluid (c_w e comparable to 1/k_n) slows the diffusion as (F3) says."""
    c = 2.0 / (stiffness(SIGMA - P0) * (12.0 * T0) ** (1.0 / 3.0))     # e c_w = 2 / k_n: S triples
    _, _, _, error, d = run("one_way", 20, compressibility=c)
    _, _, _, error_water, d_water = run("one_way", 20)
    assert d == pytest.approx(d_water / 3.0, rel=1e-3)
    assert error < 0.02


def test_3d_joint_plane_follows_the_same_closed_form():
    _, water, _, error, _ = run("two_way", 10, dim=3, joint_size=0.1)
    print(f"3D: max |p - p_ref| / Δp = {error:.3e}")
    assert error < 0.03


def test_bad_input_is_refused_by_name():
    model = wet_column(2, MPI.COMM_WORLD, 0.1)
    law = {"joint_1": lambda d: np.full_like(d, T0)}
    with pytest.raises(ValueError, match="coupling"):
        coupled_transient(model, law, 1.0, 2, pressures={"left": P0}, coupling="both")
    with pytest.raises(ValueError, match="duration"):
        coupled_transient(model, law, -1.0, 2, pressures={"left": P0})
    with pytest.raises(ValueError, match="steps"):
        coupled_transient(model, law, 1.0, 0, pressures={"left": P0})
    with pytest.raises(ValueError, match="pressure on 'left'"):
        coupled_transient(model, law, 1.0, 2, pressures={"left": float("nan")})
