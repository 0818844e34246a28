# SPDX-License-Identifier: MIT
"""DOLFINx 0.11 and 0.9 from one code base: the only module that reads the DOLFINx version.

rockjoint is written against DOLFINx 0.11 (what the FEniCSx documentation and demos describe);
0.9 (Debian 13) is adapted to 0.11's names and ways here, never the reverse. Everything else in
the package uses 0.11's API directly where 0.9 has the same call, and these names where it does
not::

    =========================  ====================================  ==================================
    name here                  DOLFINx 0.11 (0.10+)                  DOLFINx 0.9
    =========================  ====================================  ==================================
    ``io_gmsh``                ``dolfinx.io.gmsh``                   ``dolfinx.io.gmshio``, its
                                                                     ``model_to_mesh`` returning
                                                                     0.11's ``MeshData``
    ``create_cell_partitioner``  ``(ghost_mode, max_facet_to_cell_links)``  ``(ghost_mode)``
    ``create_vector(V)``       ``fem.petsc.create_vector(V)``        ``la.create_petsc_vector`` of V's
                                                                     index map (0.9 wants a form)
    ``la_petsc.create_vector``  ``dolfinx.la.petsc.create_vector``      ``la.create_petsc_vector(map, bs)``
                               ``([(index_map, bs)])``                (one map)
    ``Geometry.dofmaps``,      ``mesh.geometry.dofmaps[0]``,         added to 0.9's Geometry here
    ``Geometry.cmaps``         ``cmaps[0]`` (``dofmap``, ``cmap``    (= its ``dofmap``, ``cmap``)
                               deprecated)
    ``element.interpolation_   a property                            a method: 0.9's FiniteElement
    points``                                                         gets the property here
    ``cpp_adjacency_list``     the C++ list inside 0.10's Python     ``graph.adjacencylist`` (already
                               ``graph.AdjacencyList`` (what a       the C++ object)
                               cell partitioner must return)
    ``create_serial_mesh``     ``create_mesh`` keeping the cells'       ``dolfinx.mesh.create_mesh``
                               order (our _rockjoint_dolfinx, C++     (no hook for the order: GPS
                               ``create_mesh(..., reorder_fn)``)      reordering, see below)
    =========================  ====================================  ==================================

Release notes read for this: python/doc/source/release_notes.md of DOLFINx v0.11.0 (sections
v0.10.0 and v0.11.0).
"""
from __future__ import annotations

import typing

import numpy as np

import dolfinx
import dolfinx.graph
import dolfinx.la
import dolfinx.mesh
from dolfinx.fem import petsc as _fem_petsc

__all__ = ["DOLFINX_RELEASE", "DOLFINX_VERSION", "MeshData", "cpp_adjacency_list", "create_cell_partitioner",
           "create_vector", "io_gmsh", "la_petsc"]

#: (major, minor) of the DOLFINx in use
DOLFINX_VERSION: tuple[int, int] = tuple(int(p) for p in dolfinx.__version__.split(".")[:2])
#: the full release string (e.g. "0.11.0.post0"), for reports
DOLFINX_RELEASE: str = dolfinx.__version__
_LEGACY = DOLFINX_VERSION < (0, 10)

if _LEGACY:
    from dolfinx.io import gmshio as _gmsh_module

    class MeshData(typing.NamedTuple):
        """What 0.11's ``dolfinx.io.gmsh.model_to_mesh`` returns (0.9 returns a 3-tuple)."""

        mesh: dolfinx.mesh.Mesh
        cell_tags: dolfinx.mesh.MeshTags | None
        facet_tags: dolfinx.mesh.MeshTags | None
        ridge_tags: dolfinx.mesh.MeshTags | None = None
        peak_tags: dolfinx.mesh.MeshTags | None = None
        physical_groups: dict | None = None

    class _Gmsh09:
        """0.9's gmshio under 0.11's ``dolfinx.io.gmsh`` names."""

        cell_perm_array = staticmethod(_gmsh_module.cell_perm_array)
        ufl_mesh = staticmethod(_gmsh_module.ufl_mesh)
        extract_geometry = staticmethod(_gmsh_module.extract_geometry)
        extract_topology_and_markers = staticmethod(_gmsh_module.extract_topology_and_markers)
        MeshData = MeshData

        @staticmethod
        def model_to_mesh(model, comm, rank: int, gdim: int = 3, partitioner=None, **kwargs) -> MeshData:
            kwargs.pop("max_facet_to_cell_links", None)  # 0.9 has no branching meshes: 2 links
            mesh, cell_tags, facet_tags = _gmsh_module.model_to_mesh(model, comm, rank, gdim=gdim,
                                                                     partitioner=partitioner, **kwargs)
            return MeshData(mesh, cell_tags, facet_tags)

        @staticmethod
        def read_from_msh(filename: str, comm, rank: int = 0, gdim: int = 3, partitioner=None) -> MeshData:
            mesh, cell_tags, facet_tags = _gmsh_module.read_from_msh(filename, comm, rank, gdim=gdim,
                                                                     partitioner=partitioner)
            return MeshData(mesh, cell_tags, facet_tags)

    #: ``dolfinx.io.gmsh`` (0.11) or its 0.9 equivalent with 0.11's return types
    io_gmsh = _Gmsh09()

    def create_cell_partitioner(ghost_mode: dolfinx.mesh.GhostMode):
        """DOLFINx's default cell partitioner (a facet joins at most two cells)."""
        return dolfinx.mesh.create_cell_partitioner(ghost_mode)

    def create_vector(V) -> "PETSc.Vec":  # noqa: F821
        """A ghosted PETSc vector in the layout of the function space V."""
        return dolfinx.la.create_petsc_vector(V.dofmap.index_map, V.dofmap.index_map_bs)

    class _LaPetsc09:
        """0.9's PETSc vector creation under 0.11's ``dolfinx.la.petsc`` name."""

        @staticmethod
        def create_vector(maps, kind=None) -> "PETSc.Vec":  # noqa: F821
            if kind is not None or len(maps) != 1:
                raise ValueError(f"compat.la_petsc.create_vector on DOLFINx 0.9 takes one (index map, "
                                 f"block size) pair and no kind; got {len(maps)} pair(s), kind={kind!r}")
            (index_map, bs), = maps
            return dolfinx.la.create_petsc_vector(index_map, bs)

    #: ``dolfinx.la.petsc`` (0.10+) or its 0.9 equivalent
    la_petsc = _LaPetsc09()

    # 0.10 added Geometry.dofmaps and .cmaps (one per cell type) and deprecated .dofmap, .cmap.
    if not hasattr(dolfinx.mesh.Geometry, "dofmaps"):
        dolfinx.mesh.Geometry.dofmaps = property(lambda self: [self.dofmap],
                                                 doc="The geometry dofmaps, one per cell type (0.10+).")
    # 0.10 made FiniteElement.interpolation_points a property (a method of 0.9's C++ element).
    import dolfinx.cpp.fem as _cpp_fem
    for _name in ("FiniteElement_float32", "FiniteElement_float64"):
        _cls = getattr(_cpp_fem, _name, None)
        if _cls is not None and not isinstance(_cls.__dict__.get("interpolation_points"), property):
            _cls.interpolation_points = property(lambda self, _method=_cls.interpolation_points: _method(self),
                                                 doc="Interpolation points on the reference cell (0.10+).")
    if not hasattr(dolfinx.mesh.Geometry, "cmaps"):
        dolfinx.mesh.Geometry.cmaps = property(lambda self: [self.cmap],
                                               doc="The coordinate elements, one per cell type (0.10+).")

else:
    import dolfinx.la.petsc as la_petsc  # noqa: F401
    from dolfinx.io import gmsh as io_gmsh  # noqa: F401  (0.10 renamed gmshio)
    from dolfinx.io.gmsh import MeshData  # noqa: F401

    def create_cell_partitioner(ghost_mode: dolfinx.mesh.GhostMode):
        """DOLFINx's default cell partitioner (a facet joins at most two cells)."""
        return dolfinx.mesh.create_cell_partitioner(ghost_mode, 2)

    def create_vector(V) -> "PETSc.Vec":  # noqa: F821
        """A ghosted PETSc vector in the layout of the function space V."""
        return _fem_petsc.create_vector(V)


def cpp_adjacency_list(data, offsets=None):
    """The C++ AdjacencyList of (data, offsets): what a cell partitioner returns to DOLFINx's C++
    (0.10 wraps it in a Python ``dolfinx.graph.AdjacencyList``; returning that wrapper from a
    partitioner raises std::bad_cast)."""
    adj = dolfinx.graph.adjacencylist(data) if offsets is None else dolfinx.graph.adjacencylist(data, offsets)
    return getattr(adj, "_cpp_object", adj)


try:  # built against DOLFINx >= 0.10 only (python/CMakeLists.txt)
    from .._rockjoint_dolfinx import create_mesh_in_order
except ImportError:
    create_mesh_in_order = None


def create_serial_mesh(comm, cells, domain, x):
    """dolfinx.mesh.create_mesh(comm, cells, domain, x) on one rank, the cells kept in the order
    given where this build has rockjoint._rockjoint_dolfinx (DOLFINx >= 0.10): create_mesh's
    Gibbs-Poole-Stockmeyer reordering costs a pass over the whole mesh per connected component, and
    every block of a jointed mesh is one (0.66 of 0.7 s for the 11k blocks of the continuum bench's
    discrete tunnel; python/src/dolfinx_mesh/module.cpp). DOLFINx 0.9 has no hook for it."""
    if create_mesh_in_order is None or comm.size != 1:
        return dolfinx.mesh.create_mesh(comm, cells, e=domain, x=x)
    cmap = dolfinx.fem.coordinate_element(domain.ufl_coordinate_element().basix_element)
    msh = create_mesh_in_order(comm, np.ascontiguousarray(cells, dtype=np.int64), cmap._cpp_object,
                               np.ascontiguousarray(x, dtype=np.float64))
    return dolfinx.mesh.Mesh(msh, domain)
