# SPDX-License-Identifier: MIT
"""The assembled Newton Jacobian (bulk + joints, through PETSc) against finite differences of the
assembled residual, in 2D and 3D, for the nodal and Gauss rules and both shear models."""
import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

from jacobian_checks import assert_jacobian_matches_fd, sheared_block  # noqa: E402


@pytest.mark.parametrize("dim,quadrature,shear", [(2, "nodal", "constant"), (2, "gauss", "proportional"),
                                                  (3, "nodal", "proportional"), (3, "gauss", "constant")])
def test_global_jacobian_matches_finite_differences(dim, quadrature, shear):
    kw = {"shear_stiffness": 5e9} if shear == "constant" else {"shear_stiffness_ratio": 0.4}
    model = sheared_block(dim, MPI.COMM_WORLD, quadrature=quadrature, **kw)
    model.solve()  # a state with closed, sheared joints (Δ ≈ 0.3 V_m)
    assert np.all(model.interface.state()["closure"] > 0.1e-3)

    assert_jacobian_matches_fd(model, model.u.x.array.copy(), relative_step=1e-4)
