# SPDX-License-Identifier: MIT
"""Joint slip on 2 ranks (ctest: mpirun -n 2 ... -m mpi): the Jacobian against finite differences
in stick, slip and open states, and a partially slipping block equal to its serial solve."""
import math

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import test_fem_joint_slip as slip  # noqa: E402  (tests/python is on sys.path under pytest)
from mpi_ranks import two_ranks  # noqa: E402


@pytest.mark.mpi
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("case", ["stick", "slip", "open"])
def test_jacobian_matches_finite_differences_on_two_ranks(dim, case):
    two_ranks()
    slip.jacobian_against_finite_differences(dim, case)


@pytest.mark.mpi
def test_partial_slip_on_two_ranks_equals_serial():
    two_ranks()
    phi = math.radians(18.0)
    parallel, _ = slip._friction_block(phi, shear=0.3)
    par = parallel.solve(load_steps=2).gather_joints()
    serial, _ = slip._friction_block(phi, shear=0.3, comm=MPI.COMM_SELF)
    ser = serial.solve(load_steps=2).gather_joints()
    assert len(par["slip"]) == len(ser["slip"])
    assert np.count_nonzero(np.linalg.norm(ser["slip"], axis=1)) > 0
    a = np.lexsort(np.round(par["coordinates"], 9).T[::-1])
    b = np.lexsort(np.round(ser["coordinates"], 9).T[::-1])
    # Coincident points of a pair's two facets share coordinates: compare the sorted values.
    for key in ("normal_stress", "closure"):
        scale = np.abs(ser[key]).max()
        np.testing.assert_allclose(np.sort(par[key][a]), np.sort(ser[key][b]), atol=1e-8 * scale)
    for key in ("slip", "shear_traction"):
        scale = np.abs(ser[key]).max()
        np.testing.assert_allclose(par[key][a], ser[key][b], atol=1e-8 * scale)
    # Which points slipped (the re-evaluated stick/slip flag of a point on the cone is round-off).
    np.testing.assert_array_equal(np.linalg.norm(par["slip"][a], axis=1) > 0,
                                  np.linalg.norm(ser["slip"][b], axis=1) > 0)
    u_par = parallel.boundary_mean_displacement("top")
    u_ser = serial.boundary_mean_displacement("top")
    np.testing.assert_allclose(u_par, u_ser, atol=1e-9 * np.abs(u_ser).max())
