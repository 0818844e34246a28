# SPDX-License-Identifier: MIT
"""Equivalent modulus of a jointed block at small load: 1/E_m = 1/E + 1/(k_n s).

A block of height H = 4 m cut by a joint set of spacing s = 1 m normal to the load (meshes.joint_set),
at s/2, 3s/2, ... so that it holds H/s joints: one representative cell of the periodic set per s,
rollers and free sides (uniaxial stress; 2D plane stress so that E' = E). At σ = 1e-4 K_ni V_m
the Barton-Bandis joints act with k_n = K_ni to a relative 1e-4, so E_m = σ H / |u_top| must match
the series formula of Goodman (1976) to about that.
"""
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402


@pytest.mark.parametrize("dim", [2, 3])
def test_equivalent_modulus_of_joint_set(dim):
    comm = MPI.COMM_WORLD
    E, nu, Kni, Vm, s, H = 40e9, 0.25, 2e10, 0.5e-3, 1.0, 4.0
    origin = (0.5,) * (dim - 1) + (0.5 * s,)
    joints = meshes.joint_set(s, 0.0, 90.0, origin=origin, count=4, name="set")
    size = (1.0, H) if dim == 2 else (1.0, 1.0, H)
    jm = meshes.jointed_block(size, joints, dim=dim, mesh_size=0.5, comm=comm)
    dmesh = distribute(jm, comm)
    law = rockjoint.BartonBandis(Kni, Vm)
    model = JointedRockModel(dmesh, rock=(E, nu), joints={f"set_{i}": law for i in (1, 2, 3, 4)},
                             shear_stiffness=1e9, plane="stress" if dim == 2 else None)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x")
    if dim == 3:
        model.fix("front", "y")
    sigma = 1e-4 * Kni * Vm
    top = [0.0] * dim
    top[-1] = -sigma
    model.add_traction("top", top)
    model.solve()
    E_m = sigma * H / abs(model.boundary_mean_displacement("top")[dim - 1])
    E_goodman = 1.0 / (1.0 / E + 1.0 / (Kni * s))
    assert E_m == pytest.approx(E_goodman, rel=3e-4)
    assert E_m < 0.7 * E  # the joints matter at this spacing
