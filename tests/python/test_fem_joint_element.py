# SPDX-License-Identifier: MIT
"""The joint element's DOLFINx side (rockjoint.fem.JointInterface): pair dofs from V.dofmap (P1,
P2), one tangent frame per joint on every rank, the initial jump (in-situ pre-closure) and the
point-state arrays.

The 3D joint dips 40° towards azimuth 45° (north-east): its upward normal
m = (sin40 sin45, sin40 cos45, cos40) lies on the x-y bisector, the tie of the old per-facet
tangent rule. The joint's strike, e_z × m normalised, is (-1, 1, 0)/√2 (dip to its right seen
from above), and must be t1 on every point of every rank.
"""
import math

import numpy as np
import pytest

from fe_stack import require_fe  # noqa: E402
require_fe()

from dolfinx import fem  # noqa: E402
from mpi4py import MPI  # noqa: E402

import rockjoint  # noqa: E402
from rockjoint import meshes  # noqa: E402
from rockjoint.fem import JointBehaviour, JointInterface  # noqa: E402
from rockjoint.fem.mesh.distributed_mesh import distribute  # noqa: E402

DIP, AZIMUTH = 40.0, 45.0


def _interface(dim, degree, comm, law, shear_stiffness=1e9):
    centre = (0.5,) * dim
    joint = meshes.Joint(centre, DIP, AZIMUTH if dim == 3 else 90.0, "j")
    jm = meshes.jointed_block((1.0,) * dim, [joint], dim=dim, mesh_size=0.3 if dim == 2 else 0.45,
                              comm=comm)
    dmesh = distribute(jm, comm)
    V = fem.functionspace(dmesh.mesh, ("Lagrange", degree, (dmesh.mesh.geometry.dim,)))
    tags = {int(t) for t in comm.allgather(set(np.asarray(dmesh.pairs.joint_tags).tolist())) for t in t}
    behaviours = {t: JointBehaviour(law, shear_stiffness=shear_stiffness) for t in tags}
    return V, JointInterface(V, dmesh.pairs, behaviours), dmesh


def _upward_normal(dim):
    th = math.radians(DIP)
    if dim == 2:
        return np.array([math.sin(th), math.cos(th)])
    az = math.radians(AZIMUTH)
    return np.array([math.sin(th) * math.sin(az), math.sin(th) * math.cos(az), math.cos(th)])


@pytest.mark.parametrize("dim,degree", [(2, 1), (2, 2), (3, 1), (3, 2)])
def test_pair_dofs_come_from_the_dofmap_and_pair_coincident_nodes(dim, degree, comm=MPI.COMM_WORLD):
    V, ji, dmesh = _interface(dim, degree, comm, rockjoint.BartonBandis(5e10, 0.5e-3))
    dofs = ji.pair_dofs()
    nn = {1: dim, 2: 3 if dim == 2 else 6}[degree]
    assert dofs.shape == (ji.num_pairs, 2 * nn * dim)
    assert comm.allreduce(ji.num_pairs) > 0
    imap = V.dofmap.index_map
    assert dofs.min(initial=0) >= 0 and dofs.max(initial=0) < (imap.size_local + imap.num_ghosts) * dim
    # component-minor: position a*gdim + c holds component c of node a
    assert np.all(dofs % dim == np.tile(np.arange(dim), 2 * nn))
    X = V.tabulate_dof_coordinates()
    nodes = dofs[:, ::dim] // dim
    np.testing.assert_allclose(X[nodes[:, :nn]], X[nodes[:, nn:]], atol=1e-12)  # plus permuted to minus
    assert np.all(nodes[:, :nn] != nodes[:, nn:])  # split nodes
    # every pair dof belongs to its cells in V.dofmap
    cell_dofs = V.dofmap.list
    for side, cells in ((0, dmesh.pairs.minus_cells), (1, dmesh.pairs.plus_cells)):
        side_nodes = nodes[:, side * nn:(side + 1) * nn]
        assert all(set(side_nodes[p]) <= set(cell_dofs[cells[p]]) for p in range(ji.num_pairs))


@pytest.mark.parametrize("dim", [2, 3])
def test_one_tangent_frame_per_joint_on_every_rank(dim, comm=MPI.COMM_WORLD):
    _, ji, _ = _interface(dim, 1, comm, rockjoint.BartonBandis(5e10, 0.5e-3))
    F = ji.point_frames()
    assert F.shape == (ji.num_points, dim, dim)
    m = _upward_normal(dim)
    # Normals minus → plus: the lower block is the minus side here, so n = m on every point.
    n = F[:, 0]
    np.testing.assert_allclose(n, np.broadcast_to(m, n.shape), atol=1e-12)
    np.testing.assert_allclose(n, ji.state()["normal"], atol=0)
    t1_expected = np.array([m[1], -m[0]]) if dim == 2 else np.array([-1.0, 1.0, 0.0]) / math.sqrt(2.0)
    np.testing.assert_allclose(F[:, 1], np.broadcast_to(t1_expected, F[:, 1].shape), atol=1e-12)
    # orthonormal rows; right-handed in 3D (t2 = n × t1)
    np.testing.assert_allclose(F @ F.transpose(0, 2, 1), np.broadcast_to(np.eye(dim), F.shape), atol=1e-13)
    if dim == 3:
        np.testing.assert_allclose(np.linalg.det(F), 1.0, atol=1e-13)


@pytest.mark.parametrize("dim", [2, 3])
def test_initial_jump_from_an_in_situ_stress_preloads_the_joint(dim, comm=MPI.COMM_WORLD):
    # In-situ stress σ0 = -p I (compression -): local traction t = F σ0 n = (-p, 0[, 0]). The
    # joint carries it at u = 0 if j0_n = -Δ(p), Δ(p) = law.closure_at_stress(p). Then the plus
    # side's joint forces sum to -p Σ A n (the law's value times ∫N_a dA, summed), and the
    # minus side's to the opposite.
    law = rockjoint.BartonBandis(5e10, 0.5e-3)
    V, ji, dmesh = _interface(dim, 1, comm, law, shear_stiffness=2e9)
    p = 3e6
    F = ji.point_frames()
    sigma0 = -p * np.eye(dim)
    t_local = np.einsum("kij,jl,kl->ki", F, sigma0, F[:, 0])
    np.testing.assert_allclose(t_local[:, 1:], 0.0, atol=1e-9 * p)
    j0 = np.zeros((ji.num_points, dim))
    j0[:, 0] = -law.closure_at_stress(-t_local[:, 0].mean() if ji.num_points else p)
    ji.set_initial_jump(j0)
    np.testing.assert_array_equal(ji.initial_jump(), j0)

    n_local = V.dofmap.index_map.size_local + V.dofmap.index_map.num_ghosts
    u = np.zeros(n_local * dim)
    r = np.zeros_like(u)
    assert ji.add_residual(u, r)
    dofs = ji.pair_dofs()
    half = dofs.shape[1] // 2
    force_plus = np.zeros(dim)
    force_minus = np.zeros(dim)
    # each pair's dofs are its own (split nodes may be shared by neighbouring pairs): sum per
    # distinct dof
    plus_dofs = np.unique(dofs[:, half:])
    minus_dofs = np.unique(dofs[:, :half])
    for c in range(dim):
        force_plus[c] = r[plus_dofs[plus_dofs % dim == c]].sum()
        force_minus[c] = r[minus_dofs[minus_dofs % dim == c]].sum()
    area_normal = (ji._cpp.measures[:, None] * ji._cpp.normals).sum(axis=0)
    force_plus, force_minus, area_normal = (comm.allreduce(a) for a in (force_plus, force_minus, area_normal))
    scale = p * np.linalg.norm(area_normal)
    np.testing.assert_allclose(force_plus, -p * area_normal, atol=1e-9 * scale)
    np.testing.assert_allclose(force_minus, p * area_normal, atol=1e-9 * scale)
    np.testing.assert_allclose(ji.state()["normal_stress"], p, rtol=1e-9)


def test_initial_jump_and_state_arrays_are_checked(comm=MPI.COMM_WORLD):
    _, ji, _ = _interface(3, 1, comm, rockjoint.BartonBandis(5e10, 0.5e-3))
    n = ji.num_points
    with pytest.raises(ValueError, match=rf"shape \({n + 1}, 3\); expected \({n}, 3\)"):
        ji.set_initial_jump(np.zeros((n + 1, 3)))
    bad = np.zeros((n, 3))
    if n:
        bad[n - 1, 2] = np.nan
        with pytest.raises(ValueError, match=r"must be finite"):
            ji.set_initial_jump(bad)
    state = ji.state()
    assert state["slip"].shape == (n, 2)
    assert state["dilation"].shape == (n,) and state["accumulated_slip"].shape == (n,)
    ji.commit_state()
    ji.revert_state()
    assert np.all(ji.state()["accumulated_slip"] == 0.0)
