# SPDX-License-Identifier: MIT
"""Staged analyses on 2 ranks equal the serial answer (mpirun -n 2 ... -m mpi).

Each case is solved on MPI.COMM_WORLD (2 ranks) and on MPI.COMM_SELF (every rank alone, the
serial reference), and compared through the mean boundary displacements, reactions and the
gathered joint state.
"""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

from rockjoint.fem import InSituStress, JointedRockModel  # noqa: E402
from staged_cases import E, NU, QUIET, column, quarter_annulus  # noqa: E402
from mpi_ranks import two_ranks  # noqa: E402


def jointed_column_path(comm):
    """In-situ, excavation-like unloading of the top, displacement-controlled reloading."""
    model = column(comm=comm, mesh_size=0.2)
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-2e6, -5e6])))
    model.solve(name="in-situ")
    model.excavate("top", fraction_left=0.2)
    model.solve(load_steps=2, name="unloading")
    model.fix("top", "y", value=-2e-4)
    model.solve(load_steps=2, name="reloading")
    return model


def excavated_hole(comm):
    model = JointedRockModel(quarter_annulus(1.0, 3.0, 8, 24, comm=comm), element_degree=2, rock=(E, NU),
                             newton=QUIET)
    model.fix("left", "x")
    model.fix("bottom", "y")
    model.set_in_situ_stress(InSituStress.uniform(np.diag([-10e6, -6e6])))
    model.solve(name="in-situ")
    model.excavate("inner")
    model.solve(load_steps=2, name="excavation")
    model.add_pressure("inner", 1e6)
    model.solve(name="lining")
    return model


def summary(model, boundaries):
    out = []
    for stage in model.stages:
        out.extend(sorted(stage.reactions.items()))
    out += [(b, tuple(model.boundary_mean_displacement(b))) for b in boundaries]
    return out


@pytest.mark.mpi
@pytest.mark.parametrize("case, boundaries", [(jointed_column_path, ("top", "right")),
                                              (excavated_hole, ("inner", "outer"))])
def test_staged_analysis_on_two_ranks_equals_serial(case, boundaries):
    comm = two_ranks()
    parallel = case(comm)
    assert comm.allreduce(parallel.mesh.topology.index_map(2).size_local > 0, op=MPI.LAND)
    serial = case(MPI.COMM_SELF)
    for (k1, v1), (k2, v2) in zip(summary(parallel, boundaries), summary(serial, boundaries)):
        assert k1 == k2
        np.testing.assert_allclose(v1, v2, rtol=1e-8, atol=1e-8 * max(np.abs(v2).max(), 1e-30), err_msg=str(k1))
    for sp, ss in zip(parallel.stages, serial.stages):
        jp, js = sp.gather_joints(), ss.gather_joints()
        assert jp["closure"].shape == js["closure"].shape
        np.testing.assert_allclose(np.sort(jp["closure"]), np.sort(js["closure"]), rtol=1e-8)
