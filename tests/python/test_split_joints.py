# SPDX-License-Identifier: MIT
"""split_joints: a mesh read by DOLFINx's gmsh reader (dolfinx.io.gmsh.model_to_mesh), split along its joint facets,
is the mesh rockjoint's own gmsh reader makes: same blocks, the same joint facets paired (by their
coordinates), same named boundaries; bad tags are named. Serially and on 2 ranks (mpi mark)."""
import gmsh
import numpy as np
import pytest

from fe_stack import require  # noqa: E402
require("dolfinx")
from rockjoint.fem.compat import io_gmsh  # noqa: E402  (dolfinx.io.gmsh on 0.10+)
from mpi4py import MPI  # noqa: E402

from rockjoint import meshes  # noqa: E402
from rockjoint.fem import distribute, split_joints  # noqa: E402
from rockjoint.meshes.builders import _ensure_gmsh  # noqa: E402

import user_model_geometry as case  # noqa: E402
from mesh_checks import facet_coordinates, sorted_rows  # noqa: E402


def _groups(dim):
    """{name: physical tag} of the current gmsh model."""
    return {gmsh.model.getPhysicalName(d, t): t for d, t in gmsh.model.getPhysicalGroups() if d >= dim - 1}


def _both_routes(dim, comm):
    groups = None
    if comm.rank == 0:
        _ensure_gmsh(gmsh)
        case.build_gmsh_model(gmsh, dim, 0.5)
        groups = _groups(dim)
    groups = comm.bcast(groups, root=0)
    mesh_data = io_gmsh.model_to_mesh(gmsh.model if comm.rank == 0 else None, comm, 0, gdim=dim)
    boundaries = {n: t for n, t in groups.items() if n not in ("lower", "upper", "fault")}
    split = split_joints(mesh_data, joints={"fault": groups["fault"]},
                         blocks={"lower": groups["lower"], "upper": groups["upper"]}, boundaries=boundaries)
    reference = distribute(meshes.from_gmsh_model(joints=["fault"], comm=comm), comm)
    if comm.rank == 0:
        gmsh.model.remove()
    return split, reference, groups


def _pair_set(d, comm):
    p = d.pairs
    xm = facet_coordinates(d.mesh, p.minus_cells, p.minus_local_facets)
    return sorted(t for part in comm.allgather(sorted_rows(np.round(xm, 12))) for t in part)


def _check_same(split, reference, comm):
    assert sorted(split.names["blocks"].values()) == sorted(reference.names["blocks"].values())
    assert sorted(split.names["boundaries"].values()) == sorted(reference.names["boundaries"].values())
    assert comm.allreduce(len(split.pairs)) == comm.allreduce(len(reference.pairs)) > 0
    assert _pair_set(split, comm) == _pair_set(reference, comm)
    def owned(d, name):  # boundary facets owned by this rank (ghosts differ between partitions)
        return int(np.sum(d.boundary(name) < d.mesh.topology.index_map(d.mesh.topology.dim - 1).size_local))

    for name in split.names["boundaries"].values():
        assert comm.allreduce(owned(split, name)) == comm.allreduce(owned(reference, name)) > 0


@pytest.mark.parametrize("dim", [2, 3])
def test_gmsh_reader_mesh_split_is_the_mesh_of_the_gmsh_reader(dim):
    split, reference, _ = _both_routes(dim, MPI.COMM_WORLD)
    _check_same(split, reference, MPI.COMM_WORLD)


@pytest.mark.mpi
def test_gmsh_reader_mesh_split_on_two_ranks():
    split, reference, _ = _both_routes(2, MPI.COMM_WORLD)
    _check_same(split, reference, MPI.COMM_WORLD)


def test_bad_tags_are_named():
    comm = MPI.COMM_WORLD
    _ensure_gmsh(gmsh)
    case.build_gmsh_model(gmsh, 2, 0.5)
    groups = _groups(2)
    data = io_gmsh.model_to_mesh(gmsh.model, comm, 0, gdim=2)
    mesh, cells, facets = data.mesh, data.cell_tags, data.facet_tags
    gmsh.model.remove()
    with pytest.raises(ValueError, match=r"joints\['fault'\] = 999: no entity carries tag 999"):
        split_joints(mesh, cells, facets, joints={"fault": 999})
    with pytest.raises(ValueError, match=r"cells with tags \[\d+\] belong to no named block"):
        split_joints(mesh, cells, facets, joints={"fault": groups["fault"]}, blocks={"lower": groups["lower"]})
    with pytest.raises(ValueError, match=rf"named both as a joint and as a boundary "
                                         rf"\(tag {groups['fault']}: joint fault, boundary f\)"):
        split_joints(mesh, cells, facets, joints={"fault": groups["fault"]}, boundaries={"f": groups["fault"]})
