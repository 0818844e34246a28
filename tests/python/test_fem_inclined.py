# SPDX-License-Identifier: MIT
"""An inclined joint under uniaxial compression: joint tractions = σ·n of a uniform stress state.

Block [0,1]^d cut by one joint dipping 30° (toward +x) through its centre. Supports only under the
lower block (rollers: bottom, and left/front restricted to block_1), so the upper block is held by
the joint alone and may slide on it: the exact solution is the uniform uniaxial stress σ_vv = -p in
both blocks plus a rigid relative translation (the joint jump). With n = (sin θ, [0,] cos θ) the
joint's upward normal, the traction the joint carries is σ·n:
    normal stress (compression +)  σ_n = p cos²θ,
    shear traction magnitude        |τ| = p sin θ cos θ   (2D: t1 = (n_y, -n_x); 3D: t1 = strike e_y),
whatever the joint stiffnesses. The P1 solution reproduces a uniform stress state exactly.
"""
import math

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointedRockModel  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402

DIP = 30.0


@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("quadrature", ["nodal", "gauss"])
def test_inclined_joint_tractions_match_uniform_stress_state(dim, quadrature):
    comm = MPI.COMM_WORLD
    centre = (0.5,) * dim
    jm = meshes.jointed_block((1.0,) * dim, [meshes.Joint(centre, DIP, 90.0, "inclined")], dim=dim,
                              mesh_size=0.25 if dim == 2 else 0.35, comm=comm)
    dmesh = distribute(jm, comm)
    law = rockjoint.BartonBandis(5e10, 0.5e-3)
    model = JointedRockModel(dmesh, rock=(30e9, 0.2), joints={"inclined": law}, shear_stiffness=2e10,
                             plane="stress" if dim == 2 else None, quadrature=quadrature)
    model.fix("bottom", "y" if dim == 2 else "z")
    model.fix("left", "x", block="block_1")
    if dim == 3:
        model.fix("front", "y", block="block_1")
    p = 4e6
    top = [0.0] * dim
    top[-1] = -p
    model.add_traction("top", top)
    sol = model.solve()
    joints = sol.gather_joints()

    theta = math.radians(DIP)
    n = np.array([math.sin(theta), math.cos(theta)] if dim == 2 else [math.sin(theta), 0.0, math.cos(theta)])
    np.testing.assert_allclose(joints["normal"], np.broadcast_to(n, joints["normal"].shape), atol=1e-12)
    sigma_n = p * math.cos(theta) ** 2
    tau = p * math.sin(theta) * math.cos(theta)
    np.testing.assert_allclose(joints["normal_stress"], sigma_n, rtol=1e-8)
    shear = np.linalg.norm(joints["shear_traction"], axis=1)
    np.testing.assert_allclose(shear, tau, rtol=1e-8)
    # Direction: T = σ·n = -p n_z e_z (e_y in 2D). 2D: t1 = (n_y, -n_x), so T·t1 = p n_y n_x.
    # 3D: t1 = strike of the joint = e_z × n = e_y (dip towards +x), t2 = n × t1 = (-n_z, 0, n_x),
    # so T·t1 = 0 and T·t2 = -p n_z n_x on every point (one frame per joint).
    if dim == 2:
        np.testing.assert_allclose(joints["shear_traction"][:, 0], p * n[1] * n[0], rtol=1e-8)
    else:
        np.testing.assert_allclose(joints["shear_traction"][:, 0], 0.0, atol=1e-8 * p)
        np.testing.assert_allclose(joints["shear_traction"][:, 1], -p * n[2] * n[0], rtol=1e-8)
    np.testing.assert_allclose(joints["closure"], law.closure_at_stress(sigma_n), rtol=1e-8)
