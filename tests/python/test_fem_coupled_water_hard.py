# SPDX-License-Identifier: MIT
"""Hard cases of the coupled water (issue 45): water injected at a rate that a dry joint could only
take at a pressure well above its normal stress. Stiff blocks (E = 20 GPa) redistribute σ_n, so
the joints' local response is not exact and the outer iterations have to work. With a residual
stiffness the water opens the joint near the inlet (hydraulic jacking) and the coupling still
converges; the mass balance holds (what goes in at the port comes out at the drained end) and the
water needs a lower pressure than the one-way answer. Without a residual stiffness the jacked
part carries nothing while the rest of the joint holds the block: an answer too."""
import numpy as np
import pytest

import rockjoint

from fe_stack import require_fe
require_fe()

from mpi4py import MPI  # noqa: E402

from joint_pressure_cases import SIGMA, closure, loaded_column  # noqa: E402
from rockjoint.fem import Fluid  # noqa: E402
from rockjoint.fem.water.coupled import coupled_steady  # noqa: E402
from rockjoint.fem.water.joint_flow import network_flow  # noqa: E402

E0 = 1.2e-3
FLUID = Fluid()


def transmissivity(closure):
    return (E0 - np.asarray(closure)) ** 3 / 12.0


def injected(times_sigma, residual_stiffness):
    """The loaded column, and the rate a dry joint would take at `times_sigma` × σ at the inlet."""
    model = loaded_column(2, MPI.COMM_WORLD, rock=(20e9, 0.25), mesh_size=0.25, joint_mesh_size=0.05,
                          residual_stiffness=residual_stiffness)
    model.solve(name="load")
    t_dry = transmissivity(closure(SIGMA, residual_stiffness))     # uniform σ_n = σ in the column
    return model, times_sigma * SIGMA * t_dry / FLUID.viscosity     # Q = T Δp / (μ L), L = 1 m


@pytest.mark.parametrize("times_sigma", [0.5, 3.0])
def test_injection_that_jacks_the_joint_open_converges(times_sigma):
    model, q = injected(times_sigma, residual_stiffness=1e9)
    one_way = network_flow(model, {"joint_1": transmissivity}, {"right": 1.0}, FLUID, rates={"left": q})
    water = coupled_steady(model, {"joint_1": transmissivity}, {"right": 1.0}, FLUID, rates={"left": q})
    state = model.solution.gather_joints()
    rg = FLUID.density * FLUID.gravity
    p_one, p_two = [(n.port_heads["left"] - 1.0) * rg for n in (one_way, water.network)]
    print(f"Q at {times_sigma} σ: inlet p one way {p_one * 1e-6:.3f} MPa, two way {p_two * 1e-6:.3f} MPa, "
          f"{water.iterations} iterations, smallest closure {np.min(state['closure']) * 1e3:.4f} mm")
    assert p_one == pytest.approx(times_sigma * SIGMA, rel=1e-6)        # the dry closed form
    assert p_two < p_one                                                  # the water opens its way
    assert water.network.flow_rates["right"] == pytest.approx(-q, rel=1e-9)  # mass balance
    if times_sigma > 1.0:
        assert np.min(state["closure"]) < 0.0                             # opened: held by k_r only
    assert water.iterations < 25


def test_injection_that_jacks_part_of_a_joint_without_residual_stiffness_converges():
    """Without k_r the jacked part near the inlet carries nothing, and the top block is held by
    the rest of the joint: an answer, with the water's pressure up to the normal stress there."""
    model, q = injected(3.0, residual_stiffness=0.0)
    water = coupled_steady(model, {"joint_1": transmissivity}, {"right": 1.0}, FLUID, rates={"left": q})
    state = model.solution.gather_joints()
    assert water.network.flow_rates["right"] == pytest.approx(-q, rel=1e-9)
    assert np.any(np.asarray(state["status"]) == int(rockjoint.Status.open))
