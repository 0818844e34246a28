"""The assembled Newton Jacobian (bulk + joints, through PETSc) against finite differences of the
assembled residual, in 2D and 3D, for the nodal and Gauss rules and both shear models."""
import numpy as np
import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem")

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions  # noqa: E402
from rockjoint.fem.distributed_mesh import distribute  # noqa: E402
from jacobian_checks import assert_jacobian_matches_fd  # noqa: E402


@pytest.mark.parametrize("dim,quadrature,shear", [(2, "nodal", "constant"), (2, "gauss", "proportional"),
                                                  (3, "nodal", "proportional"), (3, "gauss", "constant")])
def test_global_jacobian_matches_finite_differences(dim, quadrature, shear):
    comm = MPI.COMM_WORLD
    centre = (0.5,) * dim
    jm = meshes.jointed_block((1.0,) * dim, [meshes.Joint(centre, 25.0, 90.0, "j")], dim=dim,
                              mesh_size=0.35 if dim == 2 else 0.5, comm=comm)
    dmesh = distribute(jm, comm)
    law = rockjoint.BartonBandis(2e10, 1e-3)
    kw = {"shear_stiffness": 5e9} if shear == "constant" else {"shear_stiffness_ratio": 0.4}
    model = JointedRockModel(dmesh, rock=(10e9, 0.3), joints={"j": law}, quadrature=quadrature,
                             plane="strain" if dim == 2 else None, newton=NewtonOptions(verbose=False), **kw)
    model.fix("bottom", "all")
    top = [0.0] * dim
    top[0], top[-1] = 1e6, -8e6
    model.add_traction("top", top)
    model.solve()  # a state with closed, sheared joints (Δ ≈ 0.3 V_m)
    assert np.all(model.interface.state()["closure"] > 0.1e-3)

    assert_jacobian_matches_fd(model, model.u.x.array.copy(), relative_step=1e-4)
