"""The assembled Newton Jacobian (bulk + joints, through PETSc) against finite differences of the
assembled residual, in 2D and 3D, for the nodal and Gauss rules and both shear models."""
import numpy as np
import pytest

pytest.importorskip("dolfinx")
pytest.importorskip("rockjoint._rockjoint_fem")

from mpi4py import MPI  # noqa: E402
from petsc4py import PETSc  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel, NewtonOptions  # noqa: E402
from rockjoint.fem.distributed_mesh import distribute  # noqa: E402


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

    rng = np.random.default_rng(0)
    u0 = model.u.x.array.copy()
    model.jacobian()
    J = model.J
    free = model._constrained == 0
    for _ in range(3):
        v = model.u.vector.duplicate()
        with v.localForm() as loc:
            loc.array[:] = rng.uniform(-1, 1, loc.array.size) * free
        v.ghostUpdate(addv=PETSc.InsertMode.INSERT, mode=PETSc.ScatterMode.FORWARD)
        Jv = v.duplicate()
        J.mult(v, Jv)
        u_max = comm.allreduce(np.abs(u0).max(), op=MPI.MAX)  # the same step on every rank
        h = 1e-4 * u_max / max(v.norm(PETSc.NormType.INFINITY), 1e-300)
        res = []
        for sign in (1.0, -1.0):
            with v.localForm() as vl:
                model.u.x.array[:] = u0 + sign * h * vl.array
            model.residual()
            res.append(model.r.copy())
        fd = res[0] - res[1]
        fd.scale(1.0 / (2 * h))
        fd.axpy(-1.0, Jv)
        assert fd.norm() < 1e-6 * Jv.norm(), f"|FD - J v| / |J v| = {fd.norm() / Jv.norm():.2e}"
    model.u.x.array[:] = u0
