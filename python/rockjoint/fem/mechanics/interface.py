# SPDX-License-Identifier: MIT
"""Joint interface of a DOLFINx displacement space: facet pairs → C++ InterfaceAssembler.

This is the only place where joint pairs meet DOLFINx data (dofmaps, dof coordinates, ghosts);
the assembler itself sees plain arrays and PETSc matrices. docs/fem.md pitfalls 3-5:
pair dofs (unrolled, from V.dofmap) permuted to the minus order, couplings inserted in the
sparsity pattern, residual added to the local ghosted vector before the reverse ghost update,
Jacobian blocks added with MatSetValuesLocal (ADD_VALUES) with the rows/columns of constrained
dofs left out. The tangent frame of each 3D joint comes from one reference direction computed
over all ranks (docs/fem.md, "The joint element").
"""
from __future__ import annotations

import numpy as np
from dolfinx import cpp as _dcpp
from mpi4py import MPI
from petsc4py import PETSc

from ... import _rockjoint  # noqa: F401  (registers the ClosureLaw and JointBehaviour types used by _rockjoint_fem_coupling)
from ... import _rockjoint_fem_coupling as _cpp

QuadratureRule = _cpp.QuadratureRule

#: quadrature rule names accepted by the Python API
QUADRATURE_RULES = {"nodal": QuadratureRule.nodal, "gauss": QuadratureRule.gauss}


def _facet_nodes(V, cells: np.ndarray, local_facets: np.ndarray) -> np.ndarray:
    """(n, num_facet_nodes) local node (block dof) indices of the closure of each facet."""
    tdim = V.mesh.topology.dim
    layout = V.dofmap.dof_layout
    num_facets = tdim + 1  # simplices
    closure = np.array([layout.entity_closure_dofs(tdim - 1, f) for f in range(num_facets)],
                       dtype=np.int32)
    cell_dofs = V.dofmap.list
    return cell_dofs[cells[:, None], closure[local_facets]]


def _unrolled(blocks: np.ndarray, bs: int) -> np.ndarray:
    """(n, k) block (node) dofs → (n, k * bs) unrolled dofs, node-major, component-minor."""
    return (blocks[:, :, None] * bs + np.arange(bs, dtype=blocks.dtype)).reshape(
        blocks.shape[0], blocks.shape[1] * bs)


def _reference_directions(cpp, comm, tags) -> dict:
    """{joint tag: reference tangent direction} from Σ A n nᵀ summed over all ranks, so that
    every rank (and a serial run) gives a joint the same t1."""
    tags = sorted(set().union(*comm.allgather({int(t) for t in tags})))
    local = cpp.normal_moments()
    moments = np.array([local.get(t, np.zeros((3, 3))) for t in tags]).reshape(len(tags), 9)
    total = np.zeros_like(moments)
    comm.Allreduce(np.ascontiguousarray(moments), total)
    return {t: _cpp.joint_reference_direction(total[i].reshape(3, 3))
            for i, t in enumerate(tags) if total[i].any()}  # tags with pairs on some rank


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
    """All joint pairs of this rank, bound to the displacement space V (collective: the joint
    reference directions are reduced over V.mesh.comm).

    behaviours: {joint tag: JointBehaviour}. quadrature: "nodal" (default) or "gauss".
    Points are pair-major: point k belongs to pair k // num_points_per_pair.
    """

    def __init__(self, V, pairs, behaviours: dict, quadrature: str = "nodal"):
        if quadrature not in QUADRATURE_RULES:
            raise ValueError(f"quadrature must be one of {sorted(QUADRATURE_RULES)}, got {quadrature!r}")
        mesh = V.mesh
        self.V = V
        gdim = mesh.geometry.dim
        tdim = mesh.topology.dim
        degree = V.ufl_element().embedded_superdegree
        self.gdim, self.degree = gdim, degree
        bs = V.dofmap.index_map_bs
        if bs != gdim:
            raise ValueError(f"JointInterface: V must be a vector space with block size gdim = {gdim}, "
                             f"got block size {bs}")
        X = V.tabulate_dof_coordinates()  # (num local nodes incl. ghosts, 3)

        minus_cells = np.asarray(pairs.minus_cells, dtype=np.int32)
        plus_cells = np.asarray(pairs.plus_cells, dtype=np.int32)
        minus = _facet_nodes(V, minus_cells, np.asarray(pairs.minus_local_facets, dtype=np.int32))
        plus = _facet_nodes(V, plus_cells, np.asarray(pairs.plus_local_facets, dtype=np.int32))
        minus = _canonical_order(minus, X, gdim, degree)
        plus = _match_to(minus, plus, X)
        #: (num_pairs, 2 * num_facet_nodes * gdim) unrolled local dofs given to the assembler
        self._pair_dofs = np.hstack([_unrolled(minus, bs), _unrolled(plus, bs)]).astype(np.int32)

        verts = X[minus[:, :gdim], :gdim]  # (n, gdim, gdim)
        geo = mesh.geometry
        cell_geom = geo.dofmaps[0]  # affine simplices
        interior = geo.x[cell_geom[minus_cells]][:, :, :gdim].mean(axis=1)
        self.tags = np.asarray(pairs.joint_tags, dtype=np.int32)
        self._cpp = _cpp.InterfaceAssembler(
            gdim, degree, QUADRATURE_RULES[quadrature], self._pair_dofs.ravel(),
            np.ascontiguousarray(verts).ravel(), np.ascontiguousarray(interior).ravel(), self.tags,
            behaviours)
        if gdim == 3:
            self._cpp.set_reference_directions(_reference_directions(self._cpp, mesh.comm, behaviours))

    # ---- assembly ------------------------------------------------------------------------
    @property
    def num_pairs(self) -> int:
        """Number of node pairs across the joints on this rank."""
        return self._cpp.num_pairs

    @property
    def num_points(self) -> int:
        """Number of joint quadrature points on this rank."""
        return self._cpp.num_pairs * self._cpp.num_points_per_pair

    def insert_sparsity(self, pattern) -> None:
        """Insert the couplings of every pair into `pattern` (blocked: node indices = the pair
        dofs divided by the block size)."""
        blocks = self._pair_dofs[:, ::self.gdim] // self.gdim
        for b in blocks:
            pattern.insert(b, b)

    def add_residual(self, u_local: np.ndarray, r_local: np.ndarray) -> bool:
        """Add the joint forces at u into the local ghosted array r (before the reverse ghost
        update). False if a traction is not finite (closure beyond the law's maximum)."""
        return self._cpp.assemble_residual(u_local, r_local)

    def add_jacobian(self, A, u_local: np.ndarray, constrained: np.ndarray, scale: float = 1.0) -> None:
        """MatSetValuesLocal/ADD_VALUES of `scale` × the joint tangent (no flush); rows/columns
        with constrained != 0 are left out. scale=0 reserves the couplings with explicit zeros."""
        self._cpp.assemble_matrix(A.handle, u_local, constrained, scale)

    def create_matrix(self, pattern):
        """A PETSc matrix of an assembled sparsity pattern that holds the pairs' couplings
        (insert_sparsity), with those couplings reserved by explicit zeros and flushed: PETSc
        drops preallocated entries never set at a final assembly (docs/fem.md, pitfall 4), and a
        Jacobian refreshed with SAME_NONZERO_PATTERN needs them."""
        A = _dcpp.la.petsc.create_matrix(self.V.mesh.comm, pattern)  # an AIJ (block-free) Mat
        imap, bs = self.V.dofmap.index_map, self.V.dofmap.index_map_bs
        n_local = (imap.size_local + imap.num_ghosts) * bs
        self.add_jacobian(A, np.zeros(n_local), np.zeros(n_local, dtype=np.int8), scale=0.0)
        A.assemblyBegin(PETSc.Mat.AssemblyType.FLUSH)
        A.assemblyEnd(PETSc.Mat.AssemblyType.FLUSH)
        return A

    def admissible_step(self, u_local: np.ndarray, du_local: np.ndarray, fraction: float) -> float:
        """Largest α in (0, 1] such that no closure along u + α du moves past `fraction` of its
        remaining room to its law's maximum closure (docs/fem.md, pitfall 7). Collective: the
        minimum over the ranks of V.mesh.comm, so every rank takes the same step."""
        alpha = self._cpp.admissible_step_length(u_local, du_local, fraction)
        return float(self.V.mesh.comm.allreduce(alpha, op=MPI.MIN))

    def maximum_closure_ratio(self, u_local: np.ndarray) -> float:
        """max Δ / Δ_max over this rank's points (0 for laws without a maximum closure)."""
        return self._cpp.maximum_closure_ratio(u_local)

    def pair_matrix(self, pair: int, u_local: np.ndarray) -> np.ndarray:
        """Dense consistent Jacobian [N/m] of pair `pair` at the local displacement `u_local` [m]."""
        return self._cpp.pair_matrix(pair, u_local)

    def pair_dofs(self) -> np.ndarray:
        """(num_pairs, pair_size) unrolled local dofs (minus nodes then plus nodes)."""
        return self._cpp.pair_dofs()

    # ---- frames, initial jump, path-dependent state -----------------------------------------
    def point_frames(self) -> np.ndarray:
        """(num_points, gdim, gdim) local frame of every point: rows n, t1[, t2] in global
        components (t_local = F @ (σ0 @ n) is the local traction of a stress σ0)."""
        return np.repeat(self._cpp.frames, self._cpp.num_points_per_pair, axis=0)

    def set_initial_jump(self, initial_jump) -> None:
        """Initial local jump j0 (num_points, gdim) [m], components (normal, t1[, t2]): the law
        sees j = j0 + Q [[u]]; a joint pre-closed to Δ0 has j0[:, 0] = -Δ0."""
        j0 = np.asarray(initial_jump, dtype=float)
        expected = (self.num_points, self.gdim)
        if j0.shape != expected:
            raise ValueError(f"set_initial_jump: initial_jump has shape {j0.shape}; expected {expected} "
                             f"(num_points, gdim) on this rank")
        bad = ~np.isfinite(j0)
        if bad.any():
            k = tuple(np.argwhere(bad)[0])
            raise ValueError(f"set_initial_jump: initial_jump{list(k)} = {j0[k]}; entries must be finite [m]")
        self._cpp.set_initial_jump(np.ascontiguousarray(j0).ravel())

    def initial_jump(self) -> np.ndarray:
        """(num_points, gdim) initial local jump j0 [m] of this rank's joint points."""
        return self._cpp.initial_jump

    def set_pore_pressure(self, pressure) -> None:
        """Fluid pressure p [Pa] in the joint at every point of this rank (num_points,): the law
        and the strength see σ'_n = σ_n - α p, the water pushes the walls apart with α p
        (joint/joint_behaviour.hpp)."""
        p = np.asarray(pressure, dtype=float)
        if p.shape != (self.num_points,):
            raise ValueError(f"set_pore_pressure: pressure has shape {p.shape}; expected ({self.num_points},) "
                             "(one value per joint point on this rank)")
        if not np.all(np.isfinite(p)):
            raise ValueError(f"set_pore_pressure: pressure[{int(np.argmax(~np.isfinite(p)))}] is not finite [Pa]")
        self._cpp.set_pore_pressure(np.ascontiguousarray(p))

    def pore_pressure(self) -> np.ndarray:
        """The fluid pressure p [Pa] set at every point of this rank."""
        return self._cpp.pore_pressure

    def commit_state(self) -> None:
        """Accept the trial point state (after a converged load step)."""
        self._cpp.commit_state()

    def revert_state(self) -> None:
        """Discard the trial point state (after a failed load step)."""
        self._cpp.revert_state()

    def reset_state(self) -> None:
        """Virgin point state everywhere (no slip, no dilation, bonds intact): a new analysis."""
        self._cpp.reset_state()

    def maximum_closure(self) -> np.ndarray:
        """Δ_m [m] of every point of this rank in the converged state: the largest elastic closure
        of the committed load steps (every closure law; joint/joint_point_state.hpp)."""
        return np.asarray(self._cpp.point_state(True)["maximum_closure"], dtype=float)

    def set_maximum_closure(self, values) -> None:
        """Set Δ_m [m] of every point of this rank (converged and trial): a staggered coupling
        puts back the Δ_m of its last accepted state before each iterate (fem.water.closure_history)."""
        v = np.asarray(values, dtype=float).reshape(-1)
        if v.shape != (self.num_points,):
            raise ValueError(f"set_maximum_closure: {v.size} values for the {self.num_points} joint points "
                             "on this rank")
        self._cpp.set_maximum_closure(np.ascontiguousarray(v))

    def update_state(self, u_local: np.ndarray) -> None:
        """Refresh the trial point state at the local displacement `u_local` [m] without assembling."""
        self._cpp.update_state(u_local)

    def shear_states(self) -> np.ndarray:
        """rockjoint.fem.ShearState value (stick, slip, open) of every point on this rank."""
        return self._cpp.shear_state

    def state(self) -> dict:
        """Point state on this rank: coordinates, tag, closure [m], normal_stress [Pa, compression +],
        shear_traction [Pa] (points, gdim-1) along t1[, t2], status (rockjoint.Status values),
        shear_state (rockjoint.fem.ShearState values: stick, slip, open), normal (of the pair), and
        the trial path-dependent state: slip [m] (points, gdim-1), dilation [m],
        accumulated_slip [m], bond_broken, maximum_closure Δ_m [m] (the largest elastic closure
        of the converged states and this trial, every closure law)."""
        c = self._cpp
        npp = c.num_points_per_pair
        out = {
            "coordinates": c.point_coordinates,
            "tag": c.point_tags,
            "closure": c.closure,
            "normal_stress": c.normal_stress,
            "shear_traction": c.shear_traction,
            "status": c.status,
            "shear_state": c.shear_state,
            "normal": np.repeat(c.normals, npp, axis=0) if c.num_pairs else np.zeros((0, self.gdim)),
        }
        out.update(c.point_state())
        return out
