# SPDX-License-Identifier: MIT
"""The joint network as a discrete system (docs/flow.md): its nodes and P1 elements from the joint
points of a solved stage, the conductance matrix of (F1), the boundary conditions on named
boundaries, and the solve for the heads. Used by the steady flow (joint_flow.network_flow) and the
transient one (transient.py), which adds storage on the diagonal.

Boundary conditions, each on a named boundary of the mesh (the joint nodes on it):

- ``heads``: the hydraulic head h [m] is given there;
- ``pressures``: the water pressure p [Pa] is given there: h = z + p / (ρ g) at each node (p = 0
  on a drained opening);
- ``rates``: a flow Q [m³/s; m²/s per metre in 2D] is injected there (Q < 0: extracted) into a
  port: the boundary's joint nodes share one unknown head (a borehole or a lab core's inlet
  plenum, where the water stands at one level), so the rate spreads over the joints by their
  conductance.

A node on two boundaries takes the first condition listed (heads, then pressures, then rates).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import spsolve
from scipy.spatial import cKDTree

from dolfinx import mesh as dmesh

from ..mesh.distributed_mesh import lookup

#: points of the network closer than this fraction of its extent are one node (round-off only:
#: the mesh's smallest element is many orders larger)
MERGE_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Conditions:
    """Boundary conditions of the network (module docstring): {boundary: value} each."""

    heads: Mapping[str, float]
    pressures: Mapping[str, float]
    rates: Mapping[str, float]

    @classmethod
    def given(cls, model, heads=None, pressures=None, rates=None, *, steady: bool = True) -> "Conditions":
        """Checked conditions: names of the mesh's boundaries, finite numbers, each boundary once;
        a steady network needs a head or a pressure somewhere (ValueError naming the problem)."""
        out = cls(dict(heads or {}), dict(pressures or {}), dict(rates or {}))
        seen = set()
        for kind, unit in (("heads", "m"), ("pressures", "Pa"), ("rates", "m³/s")):
            for name, value in getattr(out, kind).items():
                lookup(model.dmesh, "boundaries", name)   # ValueError naming the available boundaries
                if not (isinstance(value, (int, float)) and math.isfinite(value)):
                    raise ValueError(f"network_flow: {kind[:-1]} on {name!r} = {value!r} "
                                     f"must be a finite number [{unit}]")
                if name in seen:
                    raise ValueError(f"network_flow: boundary {name!r} has two conditions: give it one of "
                                     "heads, pressures, rates")
                seen.add(name)
        if steady and not (out.heads or out.pressures):
            raise ValueError("network_flow: give heads={boundary name: h [m]} or pressures={boundary name: "
                             "p [Pa]} on at least one boundary (a steady flow needs a level somewhere)")
        return out

    def named(self) -> list:
        """[(boundary, kind)] in the order of precedence."""
        return [(n, k) for k in ("heads", "pressures", "rates") for n in getattr(self, k)]


@dataclass
class Network:
    """Nodes (n, gdim) [m], P1 elements (m, gdim) node indices, the node of every joint point
    (gathered order), and the merge tolerance [m]."""

    nodes: np.ndarray
    elements: np.ndarray
    point_nodes: np.ndarray
    tolerance: float
    _pattern: tuple | None = field(default=None, repr=False)   #: conductance's element integrals and sparsity

    @classmethod
    def of_points(cls, x: np.ndarray) -> "Network":
        """The network of the gathered joint points x (points, gdim): one node per position (the
        split copies of a joint node and the points of joints meeting there are one node), one
        element per joint pair (its gdim facet vertices, P1)."""
        tolerance = MERGE_TOLERANCE * max(float(np.ptp(x, axis=0).max()) if x.size else 0.0, 1e-300)
        nodes, index = merge_points(x, tolerance)
        return cls(nodes, index.reshape(-1, x.shape[1]), index, tolerance)

    def conductance(self, factor: np.ndarray) -> sp.csr_matrix:
        """K = Σ_e factor_e ∫ ∇N_i·∇N_j (factor per element, e.g. ρ g T / μ for heads). The
        element integrals and the matrix's sparsity are computed once per network: the coupled
        solves assemble K at every iteration, with new factors only."""
        if self._pattern is None:
            per = self.elements.shape[1]
            n = self.nodes.shape[0]
            keys = (np.repeat(self.elements, per, axis=1).ravel() * n + np.tile(self.elements, (1, per)).ravel())
            unique, position = np.unique(keys, return_inverse=True)
            indptr = np.searchsorted(unique // n, np.arange(n + 1))
            self._pattern = (element_conductance(self.nodes[self.elements]), position, unique % n, indptr)
        local, position, indices, indptr = self._pattern
        data = np.bincount(position, weights=(local * factor[:, None, None]).ravel(), minlength=indices.size)
        n = self.nodes.shape[0]
        return sp.csr_matrix((data, indices, indptr), shape=(n, n))

    def lumped_measure(self) -> np.ndarray:
        """∫ N_i over the network: each node's share of the joint length (2D) or area (3D) [m, m²]."""
        x = self.nodes[self.elements]
        if x.shape[1] == 2:
            size = np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
        else:
            size = 0.5 * np.linalg.norm(np.cross(x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]), axis=1)
        out = np.zeros(self.nodes.shape[0])
        np.add.at(out, self.elements, np.repeat(size[:, None] / x.shape[1], x.shape[1], axis=1))
        return out


def element_conductance(x: np.ndarray) -> np.ndarray:
    """∫ ∇N_i·∇N_j over each P1 element (segments in 2D, triangles in 3D): (m, k, k)."""
    if x.shape[1] == 2:                                   # segments: [[1, -1], [-1, 1]] / L
        length = np.linalg.norm(x[:, 1] - x[:, 0], axis=1)
        return np.array([[1.0, -1.0], [-1.0, 1.0]])[None] / length[:, None, None]
    jac = np.stack([x[:, 1] - x[:, 0], x[:, 2] - x[:, 0]], axis=2)      # (m, 3, 2)
    metric = np.einsum("mki,mkj->mij", jac, jac)                        # JᵀJ
    area = 0.5 * np.sqrt(np.linalg.det(metric))
    ref = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])             # ∂N/∂ξ
    inv = np.linalg.inv(metric)
    return area[:, None, None] * np.einsum("ia,mab,jb->mij", ref, inv, ref)


def boundary_points(model, name: str) -> np.ndarray:
    """Coordinates of the vertices of the boundary group `name` (all ranks)."""
    mesh = model.mesh
    tdim = mesh.topology.dim
    facets = model.dmesh.boundary(name)
    mesh.topology.create_connectivity(tdim - 1, tdim)
    x = np.zeros((0, mesh.geometry.dim))
    if facets.size:   # DOLFINx 0.9's entities_to_geometry divides by zero on an empty list
        nodes = dmesh.entities_to_geometry(mesh, tdim - 1, facets, False)
        x = mesh.geometry.x[np.unique(nodes.ravel())][:, :mesh.geometry.dim]
    return np.concatenate(mesh.comm.allgather(x), axis=0)


def boundary_nodes(model, network: Network, conditions: Conditions) -> np.ndarray:
    """(n,) index into conditions.named() of the condition on every node, -1 where none."""
    owner = np.full(network.nodes.shape[0], -1)
    for k, (name, _) in enumerate(conditions.named()):
        points = boundary_points(model, name)
        if points.size and network.nodes.size:
            distance, at = cKDTree(network.nodes).query(points, distance_upper_bound=network.tolerance)
            at = at[np.isfinite(distance)]
            owner[at[owner[at] < 0]] = k
    return owner


def solve_heads(network: Network, K: sp.csr_matrix, conditions: Conditions, owner: np.ndarray,
                fluid, flowing: np.ndarray, diagonal: np.ndarray | None = None,
                rhs: np.ndarray | None = None) -> np.ndarray:
    """Heads h [m] at the nodes of (K + diag(diagonal)) h = rhs + injected rates, with the heads and
    pressures given; the nodes of a rate boundary share one head. Steady (no diagonal): NaN on the
    parts of the network that no head or pressure reaches through the `flowing` elements (mask:
    T > 0); ValueError if a port injects into such a part (no steady state). With a positive
    diagonal (storage) every node has a head."""
    n = network.nodes.shape[0]
    named = conditions.named()
    # dof map: every node its own dof, except the nodes of each port, which share the first one's
    dof = np.arange(n)
    for k, (name, kind) in enumerate(named):
        at = np.flatnonzero(owner == k)
        if kind == "rates":
            if at.size == 0:
                raise ValueError(f"network_flow: no joint meets boundary {name!r}: nothing to inject the rate into")
            dof[at] = at[0]
    used, dof = np.unique(dof, return_inverse=True)
    if used.size == n:           # no port: the nodes are the dofs
        A, b = K, (np.zeros(n) if rhs is None else np.array(rhs, dtype=float))
        if diagonal is not None:
            A = (K + sp.diags(diagonal)).tocsr()
    else:
        P = sp.csr_matrix((np.ones(n), (np.arange(n), dof)), shape=(n, used.size))
        A = (P.T @ K @ P).tocsr()
        b = np.zeros(used.size) if rhs is None else P.T @ rhs
        if diagonal is not None:
            A = (A + sp.diags(P.T @ diagonal)).tocsr()
    h = np.full(used.size, np.nan)
    z = network.nodes[:, -1]
    for k, (name, kind) in enumerate(named):
        at = owner == k
        if kind == "heads":
            h[dof[at]] = conditions.heads[name]
        elif kind == "pressures":
            h[dof[at]] = z[at] + conditions.pressures[name] / (fluid.density * fluid.gravity)
        elif np.any(at):
            b[dof[at][0]] += conditions.rates[name]
    known = ~np.isnan(h)
    free = ~known
    if diagonal is None:     # steady: only the parts connected to a given level have a head
        edges = dof[network.elements[flowing]]
        per = edges.shape[1]
        graph = sp.coo_matrix((np.ones(edges.size * per), (np.repeat(edges, per, axis=1).ravel(),
                                                          np.tile(edges, (1, per)).ravel())),
                              shape=(used.size, used.size))
        _, part = connected_components(graph, directed=False)
        reached = np.isin(part, part[known])
        for k, (name, kind) in enumerate(named):
            if kind == "rates" and not reached[dof[owner == k][0]]:
                raise ValueError(f"network_flow: the rate injected on {name!r} reaches no boundary with a head "
                                 "or a pressure through open joints: there is no steady state")
        free &= reached
    if np.any(free):
        rows = A[free]
        h[free] = spsolve(rows[:, free].tocsc(), b[free] - rows[:, known] @ h[known])
    return h[dof]


def merge_points(x: np.ndarray, tolerance: float):
    """(nodes, index): the distinct positions among the rows of x (points closer than `tolerance`
    are one), sorted lexicographically so that the numbering does not depend on the partition,
    and the node of every row."""
    if x.shape[0] == 0:
        return x.copy(), np.zeros(0, dtype=np.int64)
    pairs = cKDTree(x).query_pairs(tolerance, output_type="ndarray")
    n = x.shape[0]
    graph = sp.coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    count, label = connected_components(graph, directed=False)
    centre = np.zeros((count, x.shape[1]))
    np.add.at(centre, label, x)
    centre /= np.bincount(label, minlength=count)[:, None]
    # by x, then y (then z), each rounded to the tolerance: round-off (which differs with the
    # partition) does not reorder nodes on one line x = const
    order = np.lexsort(np.round(centre / tolerance).T[::-1])
    rank = np.empty(count, dtype=np.int64)
    rank[order] = np.arange(count)
    return centre[order], rank[label]
