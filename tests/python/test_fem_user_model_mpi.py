# SPDX-License-Identifier: MIT
"""The coupling API in a user's model on 2 ranks (mpirun -n 2 ... -m mpi): the answer of a
serial solve of the same gmsh model on MPI.COMM_SELF, both solved by SNES (JointedNonlinearProblem).

Dof numbers differ between 1 and 2 ranks, so the comparison is on quantities that do not
depend on them: boundary means of u and the joint point state matched by coordinates.
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

import gmsh  # noqa: E402
import ufl  # noqa: E402
from dolfinx import fem  # noqa: E402
from mpi4py import MPI  # noqa: E402

from rockjoint.meshes.builders import _ensure_gmsh  # noqa: E402

import user_model_case as case  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402


def boundary_means(problem, dmesh):
    """{boundary: ∫u ds / ∫ds} over the named boundaries [m] (collective)."""
    comm = dmesh.mesh.comm
    out = {}
    for tag, name in dmesh.names["boundaries"].items():
        ds = ufl.Measure("ds", domain=dmesh.mesh, subdomain_data=dmesh.boundaries)(tag)
        area = comm.allreduce(fem.assemble_scalar(fem.form(fem.Constant(dmesh.mesh, 1.0) * ds)))
        out[name] = np.array([comm.allreduce(fem.assemble_scalar(fem.form(problem.u[i] * ds)))
                              for i in range(dmesh.mesh.geometry.dim)]) / area
    return out


def joint_points(problem):
    """Closure and normal stress of all points of all ranks, sorted by coordinates."""
    comm = problem.u.function_space.mesh.comm
    state = problem.coupling.state(problem.u)
    x = np.concatenate(comm.allgather(np.asarray(state["coordinates"])))
    values = [np.concatenate(comm.allgather(np.asarray(state[k]))) for k in ("closure", "normal_stress")]
    order = np.lexsort(np.round(x, 9).T[::-1])
    return x[order], [v[order] for v in values]


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
def test_two_ranks_give_the_serial_answer(dim):
    comm = two_ranks()
    _ensure_gmsh(gmsh)  # every rank meshes for its own serial solve
    gmsh.option.setNumber("General.Terminal", 0)
    size = 0.25 if dim == 2 else 0.6
    results = []
    for c in (comm, MPI.COMM_SELF):
        dmesh = case.distributed_case(gmsh, dim, size, c)
        problem = case.user_problem(dmesh)
        case.solve(problem)
        results.append((boundary_means(problem, dmesh), joint_points(problem), dmesh))
    (par_means, (xp, par_values), dpar), (ser_means, (xs, ser_values), _) = results
    # Both ranks own cells and joint pairs are split between them or not, but all are there.
    assert comm.allreduce(dpar.mesh.topology.index_map(dim).size_local > 0, op=MPI.LAND)
    scale = max(np.abs(v).max() for v in ser_means.values())
    for name in ser_means:
        np.testing.assert_allclose(par_means[name], ser_means[name], rtol=0, atol=1e-8 * scale, err_msg=name)
    np.testing.assert_allclose(xp, xs, atol=1e-12)
    np.testing.assert_allclose(par_values[0], ser_values[0], rtol=0, atol=1e-8 * np.abs(ser_values[0]).max())
    np.testing.assert_allclose(par_values[1], ser_values[1], rtol=0, atol=1e-8 * np.abs(ser_values[1]).max())
