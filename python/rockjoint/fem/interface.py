"""Joint interface of a DOLFINx displacement space: facet pairs → C++ InterfaceAssembler.

This is the only place where joint pairs meet DOLFINx data (dofmaps, dof coordinates, ghosts);
the assembler itself sees plain arrays and PETSc matrices. docs/fem.md pitfalls 3-5:
pair dofs permuted to the minus order, couplings inserted in the sparsity pattern, residual
added to the local ghosted vector before the reverse ghost update, Jacobian blocks added with
MatSetValuesLocal (ADD_VALUES) with the rows/columns of constrained dofs left out.
"""
from __future__ import annotations

import numpy as np

from .. import _rockjoint  # noqa: F401  (registers the ClosureLaw types used by _rockjoint_fem)
from .. import _rockjoint_fem as _cpp

QuadratureRule = _cpp.QuadratureRule
ShearModel = _cpp.ShearModel
JointBehaviour = _cpp.JointBehaviour

#: quadrature rule names accepted by the Python API
QUADRATURE_RULES = {"nodal": QuadratureRule.nodal, "gauss": QuadratureRule.gauss}


def _facet_nodes(V, cells: np.ndarray, local_facets: np.ndarray) -> np.ndarray:
    """(n, num_facet_nodes) local node (block dof) indices of the closure of each facet."""
    tdim = V.mesh.topology.dim
    layout = V.dofmap.dof_layout
    num_facets = tdim + 1  # simplices
    closure = np.array([layout.entity_closure_dofs(tdim - 1, f) for f in range(num_facets)],
                       dtype=np.int32)
    cell_dofs = V.dofmap.list.array.reshape(-1, layout.num_dofs)
    return cell_dofs[cells[:, None], closure[local_facets]]


def _canonical_order(nodes: np.ndarray, X: np.ndarray, gdim: int, degree: int) -> np.ndarray:
    """Reorder P2 facet nodes to vertices, then midpoints of (v1,v2), (v0,v2), (v0,v1)."""
    if degree == 1:
        return nodes
    nv = gdim
    out = nodes.copy()
    verts = X[nodes[:, :nv]]
    edges = [(0, 1)] if gdim == 2 else [(1, 2), (0, 2), (0, 1)]
    mids = X[nodes[:, nv:]]  # (n, ne, 3)
    for e, (a, b) in enumerate(edges):
        target = 0.5 * (verts[:, a] + verts[:, b])
        d = np.linalg.norm(mids - target[:, None, :], axis=2)
        out[:, nv + e] = nodes[np.arange(nodes.shape[0]), nv + np.argmin(d, axis=1)]
    return out


def _match_to(reference: np.ndarray, other: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Permute each row of `other` so that its nodes coincide with those of `reference`."""
    xr, xo = X[reference], X[other]  # (n, k, 3)
    d = np.linalg.norm(xr[:, :, None, :] - xo[:, None, :, :], axis=3)  # (n, k, k)
    perm = np.argmin(d, axis=2)
    matched = np.take_along_axis(other, perm, axis=1)
    scale = max(np.ptp(X, axis=0).max(), 1e-300) if X.size else 1.0
    gap = np.take_along_axis(d, perm[:, :, None], axis=2).max() if d.size else 0.0
    if gap > 1e-8 * scale or any(len(set(r)) != r.size for r in perm):
        raise ValueError(f"joint pairs: plus-facet nodes do not coincide with the minus-facet nodes "
                         f"(largest gap {gap:.3e} m): the pairs are not matched facets of split nodes")
    return matched


class JointInterface:
    """All joint pairs of this rank, bound to the displacement space V.

    behaviours: {joint tag: JointBehaviour}. quadrature: "nodal" (default) or "gauss".
    """

    def __init__(self, V, pairs, behaviours: dict, quadrature: str = "nodal"):
        if quadrature not in QUADRATURE_RULES:
            raise ValueError(f"quadrature must be one of {sorted(QUADRATURE_RULES)}, got {quadrature!r}")
        mesh = V.mesh
        self.V = V
        gdim = mesh.geometry.dim
        tdim = mesh.topology.dim
        degree = V.ufl_element().degree()
        self.gdim, self.degree = gdim, degree
        X = V.tabulate_dof_coordinates()  # (num local nodes incl. ghosts, 3)

        minus_cells = np.asarray(pairs.minus_cells, dtype=np.int32)
        plus_cells = np.asarray(pairs.plus_cells, dtype=np.int32)
        minus = _facet_nodes(V, minus_cells, np.asarray(pairs.minus_local_facets, dtype=np.int32))
        plus = _facet_nodes(V, plus_cells, np.asarray(pairs.plus_local_facets, dtype=np.int32))
        minus = _canonical_order(minus, X, gdim, degree)
        plus = _match_to(minus, plus, X)
        self.minus_nodes, self.plus_nodes = minus, plus

        verts = X[minus[:, :gdim], :gdim]  # (n, gdim, gdim)
        geo = mesh.geometry
        cell_geom = geo.dofmap.array.reshape(-1, tdim + 1)  # affine simplices
        interior = geo.x[cell_geom[minus_cells]][:, :, :gdim].mean(axis=1)
        self.tags = np.asarray(pairs.joint_tags, dtype=np.int32)
        self._cpp = _cpp.InterfaceAssembler(
            gdim, degree, QUADRATURE_RULES[quadrature], minus.ravel(), plus.ravel(),
            np.ascontiguousarray(verts).ravel(), np.ascontiguousarray(interior).ravel(), self.tags,
            behaviours)
        self._pair_block_dofs = np.hstack([minus, plus]).astype(np.int32)

    # ---- assembly ------------------------------------------------------------------------
    @property
    def num_pairs(self) -> int:
        return self._cpp.num_pairs

    def insert_sparsity(self, pattern) -> None:
        """Insert the node-to-node couplings of every pair (block indices) into `pattern`."""
        for dofs in self._pair_block_dofs:
            pattern.insert(dofs, dofs)

    def add_residual(self, u_local: np.ndarray, r_local: np.ndarray) -> bool:
        """Add the joint forces at u into the local ghosted array r (before the reverse ghost
        update). False if a traction is not finite (closure beyond the law's maximum)."""
        return self._cpp.assemble_residual(u_local, r_local)

    def add_jacobian(self, A, u_local: np.ndarray, constrained: np.ndarray, scale: float = 1.0) -> None:
        """MatSetValuesLocal/ADD_VALUES of `scale` × the joint tangent (no flush); rows/columns
        with constrained != 0 are left out. scale=0 reserves the couplings with explicit zeros."""
        self._cpp.assemble_matrix(A, u_local, constrained, scale)

    def maximum_closure_ratio(self, u_local: np.ndarray) -> float:
        """max Δ / Δ_max over this rank's points (0 for laws without a maximum closure)."""
        return self._cpp.maximum_closure_ratio(u_local)

    def pair_matrix(self, pair: int, u_local: np.ndarray) -> np.ndarray:
        return self._cpp.pair_matrix(pair, u_local)

    def pair_dofs(self) -> np.ndarray:
        """(num_pairs, pair_size) unrolled local dofs (minus nodes then plus nodes)."""
        return self._cpp.pair_dofs()

    # ---- state ---------------------------------------------------------------------------
    def update_state(self, u_local: np.ndarray) -> None:
        self._cpp.update_state(u_local)

    def state(self) -> dict:
        """Point state on this rank: coordinates, tag, closure [m], normal_stress [Pa, compression +],
        shear_traction [Pa] (points, gdim-1), status (rockjoint.Status values), normal (of the pair)."""
        c = self._cpp
        npp = c.num_points_per_pair
        return {
            "coordinates": c.point_coordinates,
            "tag": c.point_tags,
            "closure": c.closure,
            "normal_stress": c.normal_stress,
            "shear_traction": c.shear_traction,
            "status": c.status,
            "normal": np.repeat(c.normals, npp, axis=0) if c.num_pairs else np.zeros((0, self.gdim)),
        }
