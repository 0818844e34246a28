# SPDX-License-Identifier: MIT
"""The rock blocks of a jointed mesh as DOLFINx objects: the displacement space, the Lamé fields
and the density per block (DG0), strain and stress, and the bulk forms. No loads, no joints:
JointedRockModel adds those (load_path.LoadPath, coupling.JointCoupling).

Linear elasticity, tension positive: σ(w) = 2 μ ε(w) + λ tr ε(w) I, ε(w) = sym ∇w; in plane
stress λ is replaced by 2 λ μ / (λ + 2 μ).
"""
from __future__ import annotations

import numpy as np
import ufl
from dolfinx import fem

from ..mesh.distributed_mesh import names_of


class ElasticBlocks:
    """Space and forms of the blocks of `dmesh`.

    rock: {block tag: (E [Pa], ν)} for every block; densities: {block name: ρ [kg/m³]} (blocks
    not named have ρ = 0); degree: 1 or 2; plane: "strain" or "stress" in 2D, None in 3D.
    Attributes: V, u (the displacement), du (a Newton increment), w (a displacement whose internal
    force is wanted: lifts, reactions), v (the test function), rho (DG0), a_form (the bilinear
    form), internal_form (∫ε(v):σ(w) dx), ds (over the named boundaries), normal, cell_tag.
    """

    def __init__(self, dmesh, rock: dict, densities: dict, degree: int, plane: str | None):
        mesh = dmesh.mesh
        gdim, tdim = mesh.geometry.dim, mesh.topology.dim
        self.mesh, self.gdim, self.degree, self.plane = mesh, gdim, degree, plane
        V = fem.functionspace(mesh, ("Lagrange", degree, (gdim,)))
        self.V = V
        self.u = fem.Function(V, name="displacement")
        self.du = fem.Function(V)
        self.w = fem.Function(V)

        # Lamé parameters and density per cell from the block tags (DG0).
        Q = fem.functionspace(mesh, ("DG", 0))
        lam, mu, rho = fem.Function(Q), fem.Function(Q), fem.Function(Q)
        tags = dmesh.cell_blocks
        ncells = mesh.topology.index_map(tdim).size_local + mesh.topology.index_map(tdim).num_ghosts
        cell_tag = np.full(ncells, -1, dtype=np.int64)
        cell_tag[tags.indices] = tags.values
        self.cell_tag = cell_tag
        blocks = names_of(dmesh, "blocks")
        # Per block, then to the cells through the block's position among the sorted tags (one
        # mask per block cost 0.17 s for the 11k blocks and 23k cells of the continuum bench's
        # discrete tunnel).
        block_tags = np.array(sorted(rock), dtype=np.int64)
        E = np.array([rock[t][0] for t in block_tags], dtype=np.float64)
        nu = np.array([rock[t][1] for t in block_tags], dtype=np.float64)
        mu_b = E / (2 * (1 + nu))
        lam_b = E * nu / ((1 + nu) * (1 - 2 * nu))
        if plane == "stress":
            lam_b = 2 * lam_b * mu_b / (lam_b + 2 * mu_b)
        density = {blocks[name]: value for name, value in densities.items()}
        rho_b = np.array([density.get(int(t), 0.0) for t in block_tags], dtype=np.float64)
        at = np.minimum(np.searchsorted(block_tags, cell_tag), max(block_tags.size - 1, 0))
        known = block_tags.size > 0 and np.all(block_tags[at] == cell_tag) if ncells else True
        if not known:
            raise ValueError("some cells carry no block tag with rock properties")
        lam_a, mu_a, rho_a = lam_b[at], mu_b[at], rho_b[at]
        dofs = Q.dofmap.list.ravel()
        lam.x.array[dofs] = lam_a
        mu.x.array[dofs] = mu_a
        rho.x.array[dofs] = rho_a
        self.lame, self.rho = (lam, mu), rho

        trial, v = ufl.TrialFunction(V), ufl.TestFunction(V)
        self.v = v
        self.a_form = fem.form(ufl.inner(self.sigma(trial), self.eps(v)) * ufl.dx)
        self.internal_form = fem.form(ufl.inner(self.sigma(self.w), self.eps(v)) * ufl.dx)
        self.ds = ufl.Measure("ds", domain=mesh, subdomain_data=dmesh.boundaries)
        self.normal = ufl.FacetNormal(mesh)
        mesh.topology.create_connectivity(tdim - 1, tdim)
        imap, bs = V.dofmap.index_map, V.dofmap.index_map_bs
        #: local unrolled dofs of V, ghosts included
        self.num_local_dofs = (imap.size_local + imap.num_ghosts) * bs

    @staticmethod
    def eps(w):
        """Small-strain tensor ε(w) = sym(∇w) [-] of a displacement w (UFL)."""
        return ufl.sym(ufl.grad(w))

    def sigma(self, w):
        """Stress of displacement w [Pa, tension positive]."""
        lam, mu = self.lame
        return 2 * mu * self.eps(w) + lam * ufl.tr(self.eps(w)) * ufl.Identity(self.gdim)
