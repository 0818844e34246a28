# SPDX-License-Identifier: MIT
"""rockjoint.fem.mesh.distributed_mesh under `mpirun -n 2` (ctest pytest_mpi2_meshes).

The global set of pairs gathered over ranks must equal the serial set (the JointedMesh's pairs, computed
on the input mesh); both cells of every pair are owned by the assembling rank; block volumes summed over
ranks equal the closed-form ones.
"""
import numpy as np
import pytest
from mpi4py import MPI

from rockjoint.fem.mesh.distributed_mesh import distribute, pair_vertex_positions
from rockjoint.meshes import Joint, column, jointed_block

from mesh_checks import facet_coordinates, owned_block_measures, sorted_rows

pytestmark = pytest.mark.mpi


def owned_measures(d):
    """This rank's block measures as an array ordered by block tag (for allreduce)."""
    m = owned_block_measures(d)
    return np.array([m[t] for t in sorted(m)])


def check_parallel(jm, comm, owners=None):
    d = distribute(jm, comm, owners=owners)
    p = d.pairs
    mesh = d.mesh
    tdim = mesh.topology.dim
    n_owned = mesh.topology.index_map(tdim).size_local
    # each pair on the owner of its minus cell, the plus cell owned there too
    assert np.all(p.minus_cells < n_owned) and np.all(p.plus_cells < n_owned)
    xm = facet_coordinates(mesh, p.minus_cells, p.minus_local_facets)
    xp = facet_coordinates(mesh, p.plus_cells, p.plus_local_facets)
    assert sorted_rows(xm) == sorted_rows(xp)
    pm, pp = pair_vertex_positions(d)
    x, dofs = mesh.geometry.x[:, :mesh.geometry.dim], mesh.geometry.dofmaps[0]
    assert np.array_equal(x[np.take_along_axis(dofs[p.minus_cells], pm, axis=1)],
                          x[np.take_along_axis(dofs[p.plus_cells], pp, axis=1)])
    local = list(zip(p.joint_tags.tolist(), sorted_rows(xm)))
    gathered = comm.gather(local, root=0)
    serial_count = comm.bcast(jm.joint_tags.size if comm.rank == 0 else None, root=0)
    assert comm.allreduce(len(p), op=MPI.SUM) == serial_count
    if comm.rank == 0:
        everything = sorted(t for part in gathered for t in part)
        ref = sorted(zip(jm.joint_tags.tolist(), sorted_rows(jm.points[jm.joint_facets_minus])))
        assert everything == ref  # same global set of pairs as in serial, none twice
    # no vertex added or merged by the distribution
    n_nodes = comm.bcast(jm.points.shape[0] if comm.rank == 0 else None, root=0)
    assert mesh.topology.index_map(0).size_global == n_nodes
    volumes = comm.allreduce(owned_measures(d), op=MPI.SUM)
    ref_volumes = comm.bcast(np.array([v for _, v in sorted(jm.block_measures().items())])
                             if comm.rank == 0 else None, root=0)
    assert volumes == pytest.approx(ref_volumes, rel=1e-12)
    return d


@pytest.mark.parametrize("dim", [2, 3])
def test_mpi_column_pairs_match_serial(dim):
    comm = MPI.COMM_WORLD
    jm = column(1.0, 2.0, [0.5, 1.2], dim=dim, mesh_size=0.2 if dim == 2 else 0.25, comm=comm)
    d = check_parallel(jm, comm)
    if comm.size > 1:  # the mesh really is distributed
        n_owned = d.mesh.topology.index_map(dim).size_local
        assert 0 < n_owned < d.mesh.topology.index_map(dim).size_global


def test_mpi_inclined_and_t_junction_3d():
    comm = MPI.COMM_WORLD
    js = [Joint((0.5, 0.5, 0.3), 10.0, 30.0, "h1"), Joint((0.5, 0.5, 0.7), 0.0, 90.0, "h2"),
          Joint((0.5, 0.5, 0.5), 70.0, 90.0, "v", ("h1", "h2"))]
    jm = jointed_block((1.0, 1.0, 1.0), js, mesh_size=0.2, comm=comm)
    check_parallel(jm, comm)


def test_mpi_boundary_names_on_every_rank():
    comm = MPI.COMM_WORLD
    d = distribute(column(1.0, 1.0, [0.5], dim=2, mesh_size=0.1, comm=comm), comm)
    counts = comm.allreduce(np.array([d.boundary(n).size for n in ("bottom", "top", "left", "right")]), op=MPI.SUM)
    assert np.all(counts >= 10)  # 1/0.1 edges per side at least (ghost facets may be counted twice)
    with pytest.raises(KeyError, match="available"):
        d.boundary("front")


def test_mpi_intact_block_has_no_pairs():
    comm = MPI.COMM_WORLD
    jm = jointed_block((1.0, 1.0, 1.0), [], mesh_size=0.25, comm=comm)
    d = check_parallel(jm, comm)
    assert comm.allreduce(len(d.pairs), op=MPI.SUM) == 0


def test_mpi_partition_balance_is_reported_and_even():
    """The balance report adds up to the global mesh and the pairs; keeping both sides of every
    joint on one rank still leaves the owned cells within 25 % of the mean (METIS-class
    partitioners aim at a few per cent)."""
    comm = MPI.COMM_WORLD
    js = [Joint((0.5, 0.5, 0.3), 10.0, 30.0, "h1"), Joint((0.5, 0.5, 0.7), 0.0, 90.0, "h2"),
          Joint((0.5, 0.5, 0.5), 70.0, 90.0, "v", ("h1", "h2"))]
    jm = jointed_block((1.0, 1.0, 1.0), js, mesh_size=0.2, comm=comm)
    d = distribute(jm, comm)
    b = d.partition_balance()
    assert len(b["cells"]) == len(b["pairs"]) == comm.size
    assert sum(b["cells"]) == d.mesh.topology.index_map(3).size_global
    assert sum(b["vertices"]) == d.mesh.topology.index_map(0).size_global
    assert sum(b["pairs"]) == comm.bcast(jm.joint_tags.size if comm.rank == 0 else None, root=0)
    assert b == comm.bcast(b, root=0)   # the same report on every rank
    assert 1.0 <= b["cell_imbalance"] <= 1.25


def _chained(jm):
    """Cells that are in a chain of paired cells (their owner follows the chain's first cell)."""
    chained = np.zeros(jm.cells.shape[0], dtype=bool)
    chained[jm.joint_facet_cells.ravel()] = True
    return chained


def test_mpi_given_owners_reproduce_a_partition():
    """cell_owners() of one distribution, given back to distribute, rebuilds the same partition
    (every rank owns the same input cells); a partition of our own (by the x of the cell centre)
    is followed for every cell outside a chain of paired cells, and the result passes the same
    checks as DOLFINx's partition."""
    comm = MPI.COMM_WORLD
    js = [Joint((0.5, 0.5, 0.3), 10.0, 30.0, "h1"), Joint((0.5, 0.5, 0.7), 0.0, 90.0, "h2")]
    jm = jointed_block((1.0, 1.0, 1.0), js, mesh_size=0.2, comm=comm)

    def owned_input_cells(d):
        n = d.mesh.topology.index_map(3).size_local
        return np.sort(np.asarray(d.mesh.topology.original_cell_index[:n], dtype=np.int64))

    first = distribute(jm, comm)
    owners = first.cell_owners()
    if comm.rank == 0:
        assert owners.min() >= 0 and owners.max() < comm.size
    again = distribute(jm, comm, owners=owners)
    assert np.array_equal(owned_input_cells(again), owned_input_cells(first))

    mine = None
    if comm.rank == 0:
        centre = jm.points[jm.cells].mean(axis=1)[:, 0]
        mine = np.minimum((centre * comm.size).astype(np.int64), comm.size - 1)
    d = distribute(jm, comm, owners=mine)
    cells = owned_input_cells(d)
    gathered = comm.gather(cells, root=0)
    if comm.rank == 0:
        free = ~_chained(jm)
        for rank, c in enumerate(gathered):
            assert np.all(mine[c][free[c]] == rank)
        assert sum(c.size for c in gathered) == jm.cells.shape[0]
    check_parallel(jm, comm, owners=mine)


@pytest.mark.parametrize("bad, message", [
    (lambda n, size: np.zeros(n - 1, dtype=np.int64), "one rank per cell"),
    (lambda n, size: np.full(n, size, dtype=np.int64), r"must lie in \[0,"),
    (lambda n, size: np.zeros(n, dtype=float), "integer array"),
])
def test_mpi_bad_owners_are_refused_on_every_rank(bad, message):
    comm = MPI.COMM_WORLD
    jm = column(1.0, 1.0, [0.5], dim=2, mesh_size=0.25, comm=comm)
    owners = bad(jm.cells.shape[0], comm.size) if comm.rank == 0 else None
    with pytest.raises(ValueError, match=message):
        distribute(jm, comm, owners=owners)
