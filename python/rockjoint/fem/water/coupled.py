# SPDX-License-Identifier: MIT
"""Water that pushes back, steady (docs/flow.md): the flow along the joint network and the
equilibrium of the jointed rock mass, coupled both ways.

One way (joint_flow.network_flow): the closures of a solved stage give every point its
transmissivity T(Δ), and the network its heads. Two ways: the water's pressure at every joint
point, p = ρ g (h - z), acts back on the joints (joint_pressure: σ'_n = σ_n - α p, the walls
pushed apart), which changes the closures, hence T, hence the heads. Solved here as a fixed point
p = H(p) on the joint pressures (block Gauss-Seidel: H is the mechanics at p, then the network at
the new closures, by default with each joint's local response to the pressure, local_response.py),
accelerated (acceleration.py: IQN-ILS by default); the choices are measured in
bench/results/coupled_water.md. Iterated until::

    |p_{k+1} - p_k| <= tolerance (max(|p_k|, |H(p_k)|) + ρ g Δh √n),

Δh the spread of the heads given. Each mechanical solve is a stage of the model (the pressure
ramps over it from the last value, see joint_pressure), so the model's stages record the
iterations; each starts from the largest closures Δ_m of the state before the coupling
(closure_history.keep_accepted_history), so that only the accepted iterate adds to them. The
network is gathered (the same on every rank) and so are the iterates: every rank takes the same
step and the answer does not depend on the partition.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from ..mesh.distributed_mesh import names_of
from .acceleration import accelerator
from .closure_history import converged_maximum_closure, history_state, keep_accepted_history
from .joint_flow import Fluid, NetworkFlow, joint_network, point_transmissivity, steady_network
from .joint_pressure import set_joint_pressure
from .local_response import LocalResponse, local_network
from .network import Conditions, boundary_nodes

log = logging.getLogger(__name__)


@dataclass
class CoupledWater:
    """The coupled steady state: the network at the last closures, the pressure p [Pa] at every
    joint point (gathered order, the same on every rank), and the iteration history."""

    network: NetworkFlow
    pressure: np.ndarray
    iterations: int
    increments: list = field(default_factory=list)   #: ``|p_{k+1} - p_k|`` / scale per iteration


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


def scatter_pressure(model, result, p: np.ndarray) -> None:
    """Set this rank's share of the gathered joint pressures p (result.gather_joints order)."""
    comm = model.comm
    counts = comm.allgather(int(np.asarray(result.joints["closure"]).size))
    start = sum(counts[:comm.rank])
    set_joint_pressure(model, p[start:start + counts[comm.rank]])


def pressure_scale(fluid: Fluid, heads, pressures) -> float:
    """ρ g Δh [Pa]: the spread of the levels given (heads and pressures) as a pressure."""
    levels = [fluid.density * fluid.gravity * h for h in (heads or {}).values()] + list((pressures or {}).values())
    return (max(levels) - min(levels)) if levels else 0.0


def coupled_steady(model, transmissivity: Mapping[str, Callable], heads: Mapping[str, float] | None = None,
                   fluid: Fluid = Fluid(), *, pressures: Mapping[str, float] | None = None,
                   rates: Mapping[str, float] | None = None, tolerance: float = 1e-8,
                   max_iterations: int = 60, load_steps: int = 1, acceleration: str = "iqn-ils",
                   network_step: str = "local", name: str = "water") -> CoupledWater:
    """The steady two-way coupled state of `model` (its loads as set now) with the network's
    boundary conditions (heads {boundary: h [m]}, pressures {boundary: p [Pa]}, rates {boundary:
    Q}: network.py) and transmissivity {joint name: T(closure) [m³]}: each iteration solves a
    stage of the model at the current joint pressure (`load_steps` steps, named '<name> k') and
    the network at its closures: `network_step` 'local' (the network solved with the joints'
    local response to p, local_response.py) or 'frozen' (T at the closures of the last
    mechanics); `acceleration` 'iqn-ils' or 'aitken' (acceleration.py). Returns CoupledWater;
    CouplingError if ``|Δp|`` has not fallen below `tolerance` (relative) in `max_iterations`.
    Needs P1 with the nodal joint rule. Collective."""
    if not (0.0 < tolerance < 1.0):
        raise ValueError(f"coupled_steady: tolerance = {tolerance!r} must be in (0, 1)")
    if network_step not in ("local", "frozen"):
        raise ValueError(f"coupled_steady: network_step = {network_step!r}: choose 'local' or 'frozen'")
    conditions = Conditions.given(model, heads, pressures, rates)
    rise = pressure_scale(fluid, heads, pressures)
    accelerate = accelerator(acceleration)
    p = gathered_pressure(model)
    accepted, history = converged_maximum_closure(model)   # Δ_m before the coupling (this rank's, all)
    network = owner = None
    increments = []
    for k in range(1, max_iterations + 1):
        keep_accepted_history(model, accepted)              # iterates do not add to Δ_m
        result = model.solve(load_steps, name=f"{name} {k}")
        if network is None:       # the network's geometry and its conditions, once
            network, state, t_point = joint_network(model, transmissivity, result)
            owner = boundary_nodes(model, network, conditions)
            joints = names_of(model.dmesh, "joints")
        state = history_state(result.gather_joints(), history)
        x = np.asarray(state["coordinates"], dtype=float).reshape(-1, model.gdim)

        def solve(t_point):
            flow = steady_network(network, state, t_point, conditions, owner, fluid)
            return flow, pressure_at_points(flow, x, fluid)

        def t_at(closure):
            return point_transmissivity(dict(state, closure=closure), transmissivity, joints)

        if network_step == "local":
            target, flow = local_network(LocalResponse(model, state, p), solve, t_at, 1e-2 * tolerance)
        else:
            flow, target = solve(t_at(np.asarray(state["closure"], dtype=float)))
        step = accelerate(p, target) - p
        scale = max(float(np.linalg.norm(p)), float(np.linalg.norm(target))) + rise * np.sqrt(max(p.size, 1))
        increments.append(float(np.linalg.norm(step)) / scale if scale > 0.0 else 0.0)
        if model.comm.rank == 0:
            log.info("%s %d: |Δp| / scale = %.3e", name, k, increments[-1])
        if increments[-1] <= tolerance:
            return CoupledWater(flow, target, k, increments)
        p = p + step
        scatter_pressure(model, result, p)
    raise CouplingError(f"coupled_steady: |Δp| / scale = {increments[-1]:.3e} after {max_iterations} "
                        f"iterations, above the tolerance {tolerance:g}")


def gathered_pressure(model) -> np.ndarray:
    """The joint pressure set now at every point (gathered order)."""
    model.prepare()
    return np.concatenate(model.comm.allgather(np.asarray(model.interface.pore_pressure(), dtype=float)))
