# SPDX-License-Identifier: MIT
"""Steady flow along the joint network of a solved jointed model (docs/flow.md).

Each joint point carries a transmissivity T(Δ) [m³] from its current closure (a transmissivity
law per joint: docs/flow.md); the network carries the flow along the joints between the heads,
pressures or injected rates given on named boundaries (network.py):

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
The discrete network (nodes, elements, conductance, boundary conditions) is network.py.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from ..mesh.distributed_mesh import names_of
from .closure_history import with_closure_history
from .network import Conditions, Network, boundary_nodes, solve_heads


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
    flow_rates: dict             # {boundary: Q into the network there [m³/s; m²/s in 2D]}, every condition
    heads: dict                  # the heads given {boundary: h [m]}
    fluid: Fluid = field(default_factory=Fluid)
    #: the node of every joint point (result.gather_joints order): p there = ρ g (h - z)
    point_nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    pressures: dict = field(default_factory=dict)   #: the pressures given {boundary: p [Pa]}
    rates: dict = field(default_factory=dict)       #: the rates injected {boundary: Q}
    port_heads: dict = field(default_factory=dict)  #: the head at every rate boundary {boundary: h [m]}

    @property
    def pressure(self) -> np.ndarray:
        """p = ρ g (h - z) [Pa] at the nodes (NaN where no head reaches)."""
        return self.fluid.density * self.fluid.gravity * (self.head - self.nodes[:, -1])

    def write(self, path: str, comm=None) -> str:
        """The network as an XDMF grid for ParaView (segments in 2D, triangles in 3D; HDF5 data
        beside it): head_m and pressure_Pa (p = ρ g (h - z)) at the nodes (NaN where no head
        reaches), transmissivity_m3 and joint_tag per element. Written by rank 0 of `comm`
        (default: this process). Returns path."""
        if comm is not None and comm.rank != 0:
            comm.barrier()
            return path
        import meshio  # Debian python3-meshio; only needed for files
        xyz = np.zeros((self.nodes.shape[0], 3))
        xyz[:, :self.nodes.shape[1]] = self.nodes
        kind = "line" if self.elements.shape[1] == 2 else "triangle"
        nodal = {"head_m": self.head, "pressure_Pa": self.pressure}
        meshio.write(path, meshio.Mesh(xyz, [(kind, self.elements)], point_data=nodal,
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
    closure: transmissivity[joint name](closure [m]) for the joint of each point; a law with
    history (``has_history``: rockjoint.flow_history, given as the law or its bound
    ``transmissivity``) also gets each point's largest closure Δ_m = max(state's
    ``maximum_closure``, closure) (joint_network puts the C++ point state's Δ_m there, in the
    closure's measure: with_closure_history). ValueError naming a joint without a transmissivity
    law, or one whose T is negative or not finite."""
    missing = sorted(set(joint_names) - set(transmissivity))
    if missing:
        raise ValueError(f"no transmissivity for joint(s) {missing}: give transmissivity={{joint name: "
                         f"T(closure)}} for every joint: {sorted(joint_names)}")
    unknown = sorted(set(transmissivity) - set(joint_names))
    if unknown:
        raise ValueError(f"transmissivity: unknown joint(s) {unknown}; joints: {sorted(joint_names)}")
    closure = np.asarray(state["closure"], dtype=float)
    peak = np.maximum(np.asarray(state.get("maximum_closure", closure), dtype=float), closure)
    tags = np.asarray(state["tag"])
    out = np.zeros(closure.size)
    for name, tag in joint_names.items():
        on = tags == tag
        if np.any(on):
            law = transmissivity[name]
            history = getattr(getattr(law, "__self__", law), "has_history", False)
            law = getattr(law, "transmissivity", law) if history else law
            values = np.asarray(law(closure[on], peak[on]) if history else law(closure[on]), dtype=float)
            if values.shape != (int(on.sum()),) or not np.all(np.isfinite(values) & (values >= 0)):
                raise ValueError(f"transmissivity of joint {name!r}: T(closure) must give one finite "
                                 "value >= 0 [m³] per point")
            out[on] = values
    return out


def network_flow(model, transmissivity: Mapping[str, Callable], heads: Mapping[str, float] | None = None,
                 fluid: Fluid = Fluid(), stage=None, *, pressures: Mapping[str, float] | None = None,
                 rates: Mapping[str, float] | None = None) -> NetworkFlow:
    """Steady flow (F1) along the joints of a solved JointedRockModel `model` with transmissivity
    {joint name: T(closure [m]) -> [m³]} per joint (docs/flow.md), at the closures of `stage` (a
    StageResult of the model; default: its last, model.solution), between the boundary conditions
    on named boundaries of the mesh (network.py): heads {boundary: h [m]}, pressures {boundary: p
    [Pa]} and rates {boundary: Q injected [m³/s; m²/s in 2D]}. Collective; the same NetworkFlow on
    every rank. Needs the nodal joint rule on P1 (the joint points are the facet vertices)."""
    result = model.solution if stage is None else stage
    if result is None:
        raise ValueError("network_flow: the model has no solved stage yet (solve() it first)")
    conditions = Conditions.given(model, heads, pressures, rates)
    network, state, t_point = joint_network(model, transmissivity, result)
    return steady_network(network, state, t_point, conditions, boundary_nodes(model, network, conditions), fluid)


def steady_network(network, state, t_point, conditions, owner, fluid) -> NetworkFlow:
    """The steady NetworkFlow on `network` with T [m³] at its points and the boundary `owner` of
    every node (network.boundary_nodes)."""
    t_element = t_point.reshape(network.elements.shape).mean(axis=1)
    K = network.conductance(fluid.conductivity_factor * t_element)
    head = solve_heads(network, K, conditions, owner, fluid, t_element > 0)
    return network_result(network, state, K, head, owner, conditions, t_element, t_point, fluid)


def joint_network(model, transmissivity: Mapping[str, Callable], result):
    """(Network, the gathered joint state, T [m³] at every point) of a solved stage `result`."""
    if model.degree != 1 or model.quadrature != "nodal":
        raise ValueError("network_flow: the joint network is built from the joint points as facet "
                         "vertices: P1 with quadrature='nodal' is needed, got degree "
                         f"{model.degree}, quadrature {model.quadrature!r}")
    state = with_closure_history(result)
    t_point = point_transmissivity(state, transmissivity, names_of(model.dmesh, "joints"))
    x = np.asarray(state["coordinates"], dtype=float).reshape(-1, model.gdim)
    return Network.of_points(x), state, t_point


def network_result(network, state, K, head, owner, conditions, t_element, t_point, fluid) -> NetworkFlow:
    """The NetworkFlow of heads solved on `network` (net inflow per boundary from K h)."""
    inflow = K @ np.where(np.isnan(head), 0.0, head)     # net flow into the network at each node
    named = conditions.named()
    rates = {name: float(inflow[owner == k].sum()) for k, (name, _) in enumerate(named)}
    ports = {name: float(head[owner == k][0]) for k, (name, kind) in enumerate(named)
             if kind == "rates" and np.any(owner == k)}
    tags = np.asarray(state["tag"]).reshape(network.elements.shape)[:, 0]
    given = {**conditions.heads}
    return NetworkFlow(network.nodes, head, network.elements, tags, t_element, t_point, rates, given,
                       fluid, network.point_nodes, dict(conditions.pressures), dict(conditions.rates), ports)
