# SPDX-License-Identifier: MIT
"""Steady water along one joint, coupled both ways (issue 45, items 2-3): the joint under a
uniform normal stress σ between two heads. With q the flow per unit width, T(Δ) the cubic law of
the aperture e0 - Δ and Δ(σ') Barton-Bandis' inverse, continuity gives T dp/dx = -μ q, so

    G(p) = ∫_p^{p_L} T(Δ(σ - α p')) dp' = μ q x,   μ q = G(p_R) / L,

a profile that is nonlinear because T depends on p. The reference is that quadrature (SciPy quad
and brentq on the closed forms), independent of the code under test; the FE joint network
converges to it at second order in the element size."""

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from joint_pressure_cases import KNI, SIGMA, VM, loaded_column  # noqa: E402  (the column and its joint)
from rockjoint.fem import Fluid  # noqa: E402
from rockjoint.fem.water.coupled import coupled_steady  # noqa: E402

E0 = 1.2e-3                     # the joint's aperture with no load [m]
P_LEFT, P_RIGHT = 4e6, 1e6      # water pressure at the ends [Pa]
LENGTH, Z = 1.0, 1.0            # the joint: 0 <= x <= 1 m at z = 1 m
FLUID = Fluid()


def transmissivity(closure):
    return (E0 - np.asarray(closure)) ** 3 / 12.0


def closure_at(effective):
    return effective * VM / (KNI * VM + effective)


def reference_pressure(x):
    """p(x) from G(p) = (x / L) G(p_R) (module docstring)."""
    g = lambda p: quad(lambda s: float(transmissivity(closure_at(SIGMA - s))), p, P_LEFT, epsabs=0, epsrel=1e-13)[0]  # noqa: E731
    total = g(P_RIGHT)
    fraction = np.clip(np.asarray(x) / LENGTH, 0.0, 1.0)     # round-off of the mesh's end points
    return np.array([P_LEFT if f == 0 else P_RIGHT if f == 1 else
                     brentq(lambda p: g(p) - f * total, P_RIGHT, P_LEFT, xtol=1e-6, rtol=1e-14) for f in fraction])


def coupled_joint(joint_size, comm=MPI.COMM_WORLD, dim=2, **options):
    # Soft blocks (E << the joint's stiffness × length) pass the top traction to the joint
    # undistributed: σ_n = σ along it, as the reference assumes (checked below).
    model = loaded_column(dim, comm, rock=(1e5, 0.0), shear_stiffness=1e6, mesh_size=0.25 if dim == 2 else 0.5,
                          joint_mesh_size=joint_size)
    heads = {"left": Z + P_LEFT / (FLUID.density * FLUID.gravity), "right": Z + P_RIGHT / (FLUID.density * FLUID.gravity)}
    water = coupled_steady(model, {"joint_1": transmissivity}, heads, FLUID, tolerance=1e-10, **options)
    state = model.solution.gather_joints()
    x = np.asarray(state["coordinates"]).reshape(-1, dim)[:, 0]
    return model, water, state, x


def test_steady_water_along_a_joint_is_the_nonlinear_quadrature():
    errors = []
    for h in (0.1, 0.05):
        model, water, state, x = coupled_joint(h)
        total = np.asarray(state["normal_stress"]) + water.pressure          # σ'_n + α p
        np.testing.assert_allclose(total, SIGMA, rtol=1e-3)                   # the uniform σ assumed
        ref = reference_pressure(x)
        errors.append(np.max(np.abs(water.pressure - ref)) / (P_LEFT - P_RIGHT))
        print(f"h = {h} m: max |p - p_ref| / (p_L - p_R) = {errors[-1]:.3e}, {water.iterations} iterations, "
              f"σ_n within {np.max(np.abs(total / SIGMA - 1)):.1e} of σ")
    # the profile is not the linear one of a joint that the water does not open
    linear = P_LEFT + (P_RIGHT - P_LEFT) * x / LENGTH
    assert np.max(np.abs(ref - linear)) > 50 * errors[-1] * (P_LEFT - P_RIGHT)
    assert errors[-1] < 1e-3 and errors[-1] < 0.35 * errors[0]   # second order: halving h quarters it
    # under a uniform σ_n the joints' local response (local_response.py, L1) is the mechanics'
    # own: the coupling is done once the mechanics has seen the pressure it predicts
    assert water.iterations <= 4


@pytest.mark.parametrize("options", [{"network_step": "frozen"}, {"network_step": "frozen", "acceleration": "aitken"},
                                     {"acceleration": "aitken"}])
def test_every_scheme_reaches_the_same_coupled_state(options):
    """The network steps and accelerations are ways to the one fixed point (bench/results/
    coupled_water.md measures their cost): the same pressures to the coupling's tolerance."""
    _, water, _, x = coupled_joint(0.1, **options)
    _, default, _, xd = coupled_joint(0.1)
    np.testing.assert_allclose(water.pressure[np.argsort(x, kind="stable")], default.pressure[np.argsort(xd, kind="stable")],
                               rtol=0, atol=1e-6 * P_LEFT)
    assert water.iterations > default.iterations or options.get("network_step") != "frozen"


def test_steady_water_along_a_joint_plane_in_3d():
    """The same joint as a plane in a 3D column (flow along x, uniform across): the same profile,
    converging with the size of the joint's triangles."""
    errors = []
    for h in (0.1, 0.05):
        model, water, state, x = coupled_joint(h, dim=3)
        total = np.asarray(state["normal_stress"]) + water.pressure
        np.testing.assert_allclose(total, SIGMA, rtol=1e-3)
        errors.append(np.max(np.abs(water.pressure - reference_pressure(x))) / (P_LEFT - P_RIGHT))
        print(f"3D, h = {h} m: max |p - p_ref| / (p_L - p_R) = {errors[-1]:.3e}, {water.iterations} iterations")
    assert errors[-1] < 1e-4 and errors[-1] < 0.5 * errors[0]
