# SPDX-License-Identifier: MIT
"""Water that pushes back, steady (docs/flow.md): the flow along the joint network and the
equilibrium of the jointed rock mass, coupled both ways.

One way (joint_flow.network_flow): the closures of a solved stage give every point its
transmissivity T(Δ), and the network its heads. Two ways: the water's pressure at every joint
point, p = ρ g (h - z), acts back on the joints (joint_pressure: σ'_n = σ_n - α p, the walls
pushed apart), which changes the closures, hence T, hence the heads. Solved here by a staggered
fixed point on p (block Gauss-Seidel: mechanics at the current p, then the network at the new
closures) with Aitken's dynamic relaxation (Küttler & Wall 2008, Eq. 44)::

    r_k = p̃_k - p_k,   ω_k = -ω_{k-1} r_{k-1}·(r_k - r_{k-1}) / |r_k - r_{k-1}|²,   p_{k+1} = p_k + ω_k r_k,

until ``|p_{k+1} - p_k| <= tolerance (|p| + ρ g Δh_max)``. Each mechanical solve is a stage of the
model (the pressure ramps over it from the last value, see joint_pressure), so the model's
stages record the iterations. The network is gathered (the same on every rank) and so are the
iterates: every rank takes the same ω and the answer does not depend on the partition.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from .joint_flow import Fluid, NetworkFlow, network_flow
from .joint_pressure import set_joint_pressure

log = logging.getLogger(__name__)


@dataclass
class CoupledWater:
    """The coupled steady state: the network at the last closures, the pressure p [Pa] at every
    joint point (gathered order, the same on every rank), and the iteration history."""

    network: NetworkFlow
    pressure: np.ndarray
    iterations: int
    increments: list = field(default_factory=list)   #: ``|p_{k+1} - p_k|`` / scale per iteration
    relaxation: list = field(default_factory=list)   #: Aitken's ω per iteration


class CouplingError(RuntimeError):
    """The staggered coupling did not converge in its iterations."""


def pressure_at_points(network: NetworkFlow, coordinates: np.ndarray, fluid: Fluid) -> np.ndarray:
    """p = ρ g (h - z) [Pa] at every joint point (gathered order) from the network's heads; 0 on
    parts of the network no head reaches (drained) and never below 0 (no suction in an open
    joint: the water column breaks)."""
    z = coordinates[:, -1]
    head = network.head[network.point_nodes]
    p = fluid.density * fluid.gravity * (np.where(np.isnan(head), z, head) - z)
    return np.maximum(p, 0.0)


def coupled_steady(model, transmissivity: Mapping[str, Callable], heads: Mapping[str, float],
                   fluid: Fluid = Fluid(), *, tolerance: float = 1e-8, max_iterations: int = 60,
                   load_steps: int = 1, name: str = "water") -> CoupledWater:
    """The steady two-way coupled state of `model` (its loads as set now) with heads {boundary:
    h [m]} and transmissivity {joint name: T(closure) [m³]}: each iteration solves a stage of the
    model at the current joint pressure (`load_steps` steps, named '<name> k') and the network at
    its closures. Returns CoupledWater; CouplingError if ``|Δp|`` has not fallen below `tolerance`
    (relative) in `max_iterations`. Needs P1 with the nodal joint rule (network_flow). Collective."""
    if not (0.0 < tolerance < 1.0):
        raise ValueError(f"coupled_steady: tolerance = {tolerance!r} must be in (0, 1)")
    comm = model.comm
    rise = fluid.density * fluid.gravity * (max(heads.values()) - min(heads.values()))
    p = r_old = None
    omega = 1.0
    increments, relaxation = [], []
    for k in range(1, max_iterations + 1):
        result = model.solve(load_steps, name=f"{name} {k}")
        network = network_flow(model, transmissivity, heads, fluid, stage=result)
        x = np.asarray(result.gather_joints()["coordinates"], dtype=float).reshape(-1, model.gdim)
        target = pressure_at_points(network, x, fluid)
        if p is None:
            p = np.zeros_like(target)
        r = target - p
        if r_old is not None:
            d = r - r_old
            dd = float(d @ d)
            omega = -omega * float(r_old @ d) / dd if dd > 0.0 else omega
        step = omega * r
        scale = float(np.linalg.norm(p)) + rise * np.sqrt(max(p.size, 1))
        increments.append(float(np.linalg.norm(step)) / scale)
        relaxation.append(omega)
        if comm.rank == 0:
            log.info("%s %d: |Δp| / scale = %.3e (ω = %.3g)", name, k, increments[-1], omega)
        if increments[-1] <= tolerance:
            return CoupledWater(network, target, k, increments, relaxation)
        p, r_old = p + step, r
        counts = comm.allgather(int(np.asarray(result.joints["closure"]).size))
        start = sum(counts[:comm.rank])
        set_joint_pressure(model, p[start:start + counts[comm.rank]])
    raise CouplingError(f"coupled_steady: |Δp| / scale = {increments[-1]:.3e} after {max_iterations} "
                        f"iterations, above the tolerance {tolerance:g}")
