"""Equivalent continuum on 2 ranks: the smeared column, the mixed column and a slipping inclined
set give the serial answers (closed forms, and the serial run of the slip case on COMM_SELF)."""
import numpy as np
import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem_coupling")

from mpi4py import MPI  # noqa: E402

from rockjoint import _rockjoint  # noqa: E402
from continuum_cases import (HEIGHT, bb_closure, behaviour, column, material, rock_strain,  # noqa: E402
                             top_load, vertical, E, NU)

STRESS = 5e6


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_smeared_and_mixed_columns_in_parallel(dim):
    assert MPI.COMM_WORLD.size == 2
    smeared = column(dim, smeared={"block_1": material(dim, [(vertical(dim), HEIGHT / 2)])})
    top_load(smeared, dim, STRESS)
    smeared.solve()
    closed = -(rock_strain(dim, STRESS) * HEIGHT + 2 * bb_closure(STRESS))
    assert smeared.boundary_mean_displacement("top")[dim - 1] == pytest.approx(closed, rel=1e-9)
    mixed = column(dim, (1.0, 2.0), smeared={"block_3": material(dim, [(vertical(dim), 0.25)])})
    top_load(mixed, dim, STRESS)
    mixed.solve()
    closed = -(rock_strain(dim, STRESS) * HEIGHT + 6 * bb_closure(STRESS))
    assert mixed.boundary_mean_displacement("top")[dim - 1] == pytest.approx(closed, rel=1e-9)


def slipping_column(comm):
    """A set at 35° with φ = 20° smeared in the column, loaded past its strength in 3 steps."""
    th = np.radians(35.0)
    strength = _rockjoint.joint.JointStrength(_rockjoint.joint.StrengthModel.coulomb,
                                              friction_angle=np.radians(20.0))
    c = _rockjoint.continuum
    mat = c.EquivalentContinuum(2, E, NU, [c.JointSet([-np.sin(th), np.cos(th)], 0.5,
                                                      behaviour(strength))])
    model = column(2, smeared={"block_1": mat}, comm=comm)
    top_load(model, 2, 2e6)
    model.add_traction("right", (-0.5e6, 0.0))
    model.solve(load_steps=3)
    slip = model.smeared.points[1].set_state(0)["slip"]
    return model.boundary_mean_displacement("top"), model.boundary_mean_displacement("right"), \
        comm.allreduce(float(np.abs(slip).max(initial=0.0)), op=MPI.MAX)


@pytest.mark.mpi
def test_slipping_set_in_parallel_equals_serial():
    top, right, slip = slipping_column(MPI.COMM_WORLD)
    assert slip > 1e-5  # the set slips
    serial = slipping_column(MPI.COMM_SELF)
    np.testing.assert_allclose(top, serial[0], rtol=1e-8)
    np.testing.assert_allclose(right, serial[1], rtol=1e-8)
    assert slip == pytest.approx(serial[2], rel=1e-8)
