# SPDX-License-Identifier: MIT
"""Steady flow along the joint network of a solved jointed model (docs/flow.md).

Each joint point carries a transmissivity T(Δ) [m³] from its current closure (a transmissivity
law per joint: docs/flow.md); the network carries the flow along the joints between heads given on
named boundaries:

    q = -(ρ g / μ) T ∇h   along a joint [m²/s: flow per unit width of the joint],     (F1)
    ∇·q = 0                on the network (continuity; where joints meet, the flows add up).

The network is the joint facets themselves: every joint pair is one element (a segment in 2D, a
triangle in 3D) whose vertices are the pair's points; points of any joint at the same position are
one node, so the flow passes along a joint and from one joint into another where they meet. P1
elements, each with the mean T of its points (the joint element's own nodal rule). In 2D the
section is a slice of unit thickness: a joint trace stands for a joint plane and flow rates are per
metre out of plane [m²/s]; in 3D they are [m³/s].

Why not a DOLFINx sub-mesh of the joint facets: where three or more joint facets meet at a point
(every T- or X-junction of a network) the facet mesh branches, which DOLFINx reads from 0.10 on
only (FEniCS/dolfinx PR 3916); 0.9, which rockjoint supports too, refuses it, and the split mesh
holds the two walls' copies of every joint node, not one network. The network is small beside the
rock mass (one node per joint point position), so it is gathered and solved here by a sparse
direct solve (SciPy's SuperLU), the same on every rank: results do not depend on the partition.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components
from scipy.sparse.linalg import spsolve
from scipy.spatial import cKDTree

from dolfinx import mesh as dmesh

from ..mesh.distributed_mesh import lookup, names_of


#: points of the network closer than this fraction of its extent are one node (round-off only:
#: the mesh's smallest element is many orders larger)
_MERGE_TOLERANCE = 1e-9


@dataclass(frozen=True)
class Fluid:
    """The fluid in the joints (default: water at 20 °C, density and viscosity from the CRC
    Handbook of Chemistry and Physics; standard gravity)."""

    density: float = 998.2        # ρ [kg/m³]
    viscosity: float = 1.002e-3   # μ [Pa s]
    gravity: float = 9.80665      # g [m/s²]

    def __post_init__(self):
        for name in ("density", "viscosity", "gravity"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise ValueError(f"Fluid: {name} = {value!r} must be finite and > 0")

    @property
    def conductivity_factor(self) -> float:
        """ρ g / μ [1/(m s)]: hydraulic conductivity per unit intrinsic permeability (F1)."""
        return self.density * self.gravity / self.viscosity


@dataclass
class NetworkFlow:
    """Steady flow on the joint network (the same on every rank)."""

    nodes: np.ndarray            # (n, gdim) node coordinates [m]
    head: np.ndarray             # (n,) hydraulic head [m]; NaN on parts of the network no head reaches
    elements: np.ndarray         # (m, gdim) node indices of each element (one per joint pair)
    element_tags: np.ndarray     # (m,) joint tag of each element
    element_transmissivity: np.ndarray   # (m,) T [m³], the mean of its points'
    point_transmissivity: np.ndarray     # T [m³] at every joint point (result.gather_joints order)
    flow_rates: dict             # {boundary: Q into the network there [m³/s; m²/s in 2D]}
    heads: dict                  # the heads given {boundary: h [m]}
    fluid: Fluid = field(default_factory=Fluid)
    #: the node of every joint point (result.gather_joints order): p there = ρ g (h - z)
    point_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))

    def write(self, path: str, comm=None) -> str:
        """The network as an XDMF grid for ParaView (segments in 2D, triangles in 3D; HDF5 data
        beside it): head_m at the nodes (NaN where no head reaches), transmissivity_m3 and
        joint_tag per element. Written by rank 0 of `comm` (default: this process). Returns path."""
        if comm is not None and comm.rank != 0:
            comm.barrier()
            return path
        import meshio  # Debian python3-meshio; only needed for files
        xyz = np.zeros((self.nodes.shape[0], 3))
        xyz[:, :self.nodes.shape[1]] = self.nodes
        kind = "line" if self.elements.shape[1] == 2 else "triangle"
        meshio.write(path, meshio.Mesh(xyz, [(kind, self.elements)], point_data={"head_m": self.head},
                                       cell_data={"transmissivity_m3": [self.element_transmissivity],
                                                  "joint_tag": [self.element_tags.astype(np.int32)]}),
                     file_format="xdmf")
        if comm is not None:
            comm.barrier()
        return path

    @property
    def unreached_nodes(self) -> int:
        """Nodes on parts of the network that touch no boundary with a head (no flow there)."""
        return int(np.count_nonzero(np.isnan(self.head)))


def point_transmissivity(state: dict, transmissivity: Mapping[str, Callable], joint_names: Mapping[str, int]
                         ) -> np.ndarray:
    """T [m³] at every point of a joint state (dict of JointInterface.state, or gathered) from its
    closure: transmissivity[joint name](closure [m]) for the joint of each point. ValueError naming
    a joint without a transmissivity law, or one whose T is negative or not finite."""
    missing = sorted(set(joint_names) - set(transmissivity))
    if missing:
        raise ValueError(f"no transmissivity for joint(s) {missing}: give transmissivity={{joint name: "
                         f"T(closure)}} for every joint: {sorted(joint_names)}")
    unknown = sorted(set(transmissivity) - set(joint_names))
    if unknown:
        raise ValueError(f"transmissivity: unknown joint(s) {unknown}; joints: {sorted(joint_names)}")
    closure = np.asarray(state["closure"], dtype=float)
    tags = np.asarray(state["tag"])
    out = np.zeros(closure.size)
    for name, tag in joint_names.items():
        on = tags == tag
        if np.any(on):
            values = np.asarray(transmissivity[name](closure[on]), dtype=float)
            if values.shape != (int(on.sum()),) or not np.all(np.isfinite(values) & (values >= 0)):
                raise ValueError(f"transmissivity of joint {name!r}: T(closure) must give one finite "
                                 "value >= 0 [m³] per point")
            out[on] = values
    return out


def _element_conductance(x: np.ndarray) -> np.ndarray:
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


def _boundary_points(model, name: str) -> np.ndarray:
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


def network_flow(model, transmissivity: Mapping[str, Callable], heads: Mapping[str, float],
                 fluid: Fluid = Fluid(), stage=None) -> NetworkFlow:
    """Steady flow (F1) along the joints of a solved JointedRockModel `model` with heads
    {boundary name: h [m]} on named boundaries of the mesh and transmissivity {joint name:
    T(closure [m]) -> [m³]} per joint (docs/flow.md), at the closures of `stage` (a StageResult
    of the model; default: its last, model.solution). Collective; the same NetworkFlow on every
    rank. Needs the nodal joint rule on P1 (the joint points are the facet vertices)."""
    result = model.solution if stage is None else stage
    if result is None:
        raise ValueError("network_flow: the model has no solved stage yet (solve() it first)")
    if model.degree != 1 or model.quadrature != "nodal":
        raise ValueError("network_flow: the joint network is built from the joint points as facet "
                         "vertices: P1 with quadrature='nodal' is needed, got degree "
                         f"{model.degree}, quadrature {model.quadrature!r}")
    if len(heads) < 1:
        raise ValueError("network_flow: give heads={boundary name: h [m]} on at least one boundary")
    for name, h in heads.items():
        lookup(model.dmesh, "boundaries", name)     # ValueError naming the available boundaries
        if not (isinstance(h, (int, float)) and math.isfinite(h)):
            raise ValueError(f"network_flow: head on {name!r} = {h!r} must be a finite number [m]")
    state = result.gather_joints()
    joints = names_of(model.dmesh, "joints")
    t_point = point_transmissivity(state, transmissivity, joints)
    gdim = model.gdim
    x = np.asarray(state["coordinates"], dtype=float).reshape(-1, gdim)
    per = gdim                                      # points per pair: the facet's vertices (P1)
    # One node per position: the split copies of a joint node and the points of joints meeting
    # there are one mesh node (their coordinates, interpolated per pair, agree to round-off).
    tolerance = _MERGE_TOLERANCE * max(float(np.ptp(x, axis=0).max()) if x.size else 0.0, 1e-300)
    nodes, index = _merge_points(x, tolerance)
    elements = index.reshape(-1, per)
    tags = np.asarray(state["tag"]).reshape(-1, per)[:, 0]
    t_element = t_point.reshape(-1, per).mean(axis=1)
    local = _element_conductance(nodes[elements]) * (fluid.conductivity_factor * t_element)[:, None, None]
    n = nodes.shape[0]
    rows = np.repeat(elements, per, axis=1).ravel()
    cols = np.tile(elements, (1, per)).ravel()
    K = sp.csr_matrix((local.ravel(), (rows, cols)), shape=(n, n))
    # Heads: nodes at the vertices of each named boundary (the first boundary named wins at a corner)
    fixed = np.full(n, -1)
    for k, name in enumerate(heads):
        points = _boundary_points(model, name)
        at = np.zeros(0, dtype=int)
        if points.size and nodes.size:
            distance, at = cKDTree(nodes).query(points, distance_upper_bound=tolerance)
            at = at[np.isfinite(distance)]
        fixed[at[fixed[at] < 0]] = k
    values = np.array(list(heads.values()), dtype=float)
    head = np.full(n, np.nan)
    # Parts of the network connected (through elements with T > 0) to a node with a head
    open_ = np.repeat((t_element > 0).astype(float), per * per)
    flowing = sp.csr_matrix((open_, (rows, cols)), shape=(n, n))
    flowing.eliminate_zeros()
    _, part = connected_components(flowing, directed=False)
    reached = np.isin(part, part[fixed >= 0])
    known = fixed >= 0
    head[known] = values[fixed[known]]
    free = reached & ~known
    if np.any(free):
        A = K[free][:, free].tocsc()
        b = -K[free][:, known] @ head[known]
        head[free] = spsolve(A, b)
    h = np.where(np.isnan(head), 0.0, head)
    inflow = K @ h                                      # net flow into the network at each node
    rates = {name: float(inflow[fixed == k].sum()) for k, name in enumerate(heads)}
    return NetworkFlow(nodes, head, elements, tags, t_element, t_point, rates, dict(heads), fluid, index)


def _merge_points(x: np.ndarray, tolerance: float):
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
