# SPDX-License-Identifier: MIT
"""Transient water along the joints, with storage (docs/flow.md, "Transient water"): implicit time
steps inside a stage of a jointed model.

Per unit area of joint the water stored is its opening o (= -Δ + const) filled with a fluid of
compressibility c_w; continuity along the network (F1) becomes::

    ∂o/∂t + e c_w ∂p/∂t + ∇·q = 0,   q = -(ρ g / μ) T(Δ) ∇h,   p = ρ g (h - z),          (F2)

e = (12 T)^(1/3) the hydraulic aperture (the cubic law's, for the compressed volume). The opening
changes with p through the joint's normal compliance: with the total normal stress held, a joint
of tangent stiffness k_n opens by α dp / k_n, so the local storage coefficient is::

    S = α / k_n + e c_w   [m/Pa],   and for constant T and S:  D = T / (μ S)   [m²/s],         (F3)

the hydraulic diffusivity of the linear diffusion equation ∂p/∂t = D ∂²p/∂x² (the erfc solution
of a pressure step, tests/python/test_fem_transient_water.py).

``coupling='one_way'``: the mechanics is the stage's (the closures and T as solved), the storage
is (F3) from each point's tangent stiffness; one linear solve per step. ``'two_way'``: the
opening is the mechanics' own: each step iterates the fixed-stress split (Kim, Tchelepi & Juanes
2011, the split that is unconditionally stable for poroelasticity): the flow solve at the
mechanics' last opening o^k with the storage (F3) as its stabilisation::

    S (p^{k+1} - p^k)/Δt + (o^k - o^n)/Δt + e c_w (p^{k+1} - p^n)/Δt + ∇·q^{k+1} = 0,

then the mechanics at p^{k+1} (a stage of the model, the pressure ramped over it, from the
largest closures Δ_m of the last accepted step: closure_history.keep_accepted_history), accelerated
as the steady coupling (acceleration.py), until p stops changing; at convergence the terms in S
cancel and (F2) holds with the mechanics' opening. Backward Euler in time, lumped storage on the
P1 network (network.py), the same on every rank.

What is coupled: the joints (closure, T, storage) both ways. The rock matrix is impermeable here
(no poroelastic matrix); the blocks' deformation enters through the joints' closures.
"""
from __future__ import annotations

import logging
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np

from .acceleration import accelerator
from .closure_history import converged_maximum_closure, history_state, keep_accepted_history
from .coupled import CouplingError, gathered_pressure, pressure_at_points, pressure_scale, scatter_pressure
from .joint_flow import Fluid, joint_network, network_result, point_transmissivity
from ..mesh.distributed_mesh import names_of
from .network import Conditions, boundary_nodes, solve_heads

log = logging.getLogger(__name__)

#: water's compressibility at 20 °C [1/Pa] (Fine & Millero 1973: 4.59e-10 at 0.1 MPa)
WATER_COMPRESSIBILITY = 4.59e-10


@dataclass
class TransientWater:
    """The time steps of a transient water stage: times [s], the pressure [Pa] at every joint
    point at each (gathered order), the network at each, the coupling iterations of each."""

    times: list = field(default_factory=list)
    pressures: list = field(default_factory=list)
    networks: list = field(default_factory=list)
    iterations: list = field(default_factory=list)


def node_mean(network, values: np.ndarray) -> np.ndarray:
    """The mean over the joint points at every network node of a per-point array."""
    n = network.nodes.shape[0]
    count = np.bincount(network.point_nodes, minlength=n)
    return np.bincount(network.point_nodes, weights=values, minlength=n) / np.maximum(count, 1)


def storage(model, state: dict, t_point: np.ndarray, compressibility: float) -> np.ndarray:
    """(S [m/Pa] of (F3) at every point, the compliance part only): α / k_n with k_n the law's
    tangent at the point's closure (at 0 for an open joint) plus its residual stiffness, and
    the water's e c_w with e = (12 T)^(1/3)."""
    tags = np.asarray(state["tag"])
    closure = np.maximum(np.asarray(state["closure"], dtype=float), 0.0)
    out = np.zeros(closure.size)
    for tag in np.unique(tags):
        b = model.behaviours[int(tag)]
        on = tags == tag
        k = np.asarray(b.law.normal_stiffness(closure[on]), dtype=float) + b.residual_stiffness
        out[on] = b.effective_stress_coefficient / np.maximum(k, np.finfo(float).tiny)
    return out, np.cbrt(12.0 * t_point) * compressibility


def coupled_transient(model, transmissivity: Mapping[str, Callable], duration: float, steps: int,
                      heads: Mapping[str, float] | None = None, fluid: Fluid = Fluid(), *,
                      pressures: Mapping[str, float] | None = None, rates: Mapping[str, float] | None = None,
                      coupling: str = "two_way", compressibility: float = WATER_COMPRESSIBILITY,
                      tolerance: float = 1e-8, max_iterations: int = 40, acceleration: str = "iqn-ils",
                      name: str = "water") -> TransientWater:
    """`steps` implicit steps over `duration` [s] of (F2) from the pressure the joints carry now
    (set_joint_pressure and a solved stage; 0 if none), with the boundary conditions held from
    t = 0 on (heads, pressures, rates: network.py) and transmissivity {joint: T(closure) [m³]}.
    coupling 'two_way' (fixed-stress iterations, each a mechanical stage named '<name> t=..., k')
    or 'one_way' (the solved stage's mechanics). compressibility c_w [1/Pa] of the fluid.
    Returns TransientWater; CouplingError if a step does not converge. Collective."""
    if coupling not in ("one_way", "two_way"):
        raise ValueError(f"coupled_transient: coupling = {coupling!r}: choose 'one_way' or 'two_way'")
    for label, value in (("duration", duration), ("compressibility", compressibility)):
        if not (np.isfinite(value) and value >= (0.0 if label == "compressibility" else np.finfo(float).tiny)):
            raise ValueError(f"coupled_transient: {label} = {value!r} must be finite and "
                             f"{'>= 0 [1/Pa]' if label == 'compressibility' else '> 0 [s]'}")
    if int(steps) != steps or steps < 1:
        raise ValueError(f"coupled_transient: steps = {steps!r} must be an integer >= 1")
    if model.solution is None:
        raise ValueError("coupled_transient: solve the model's stage before the water's (its closures are the start)")
    conditions = Conditions.given(model, heads, pressures, rates, steady=False)
    rg = fluid.density * fluid.gravity
    dt = duration / steps
    result = model.solution
    network, state, t_point = joint_network(model, transmissivity, result)
    owner = boundary_nodes(model, network, conditions)
    joints = names_of(model.dmesh, "joints")
    z = network.nodes[:, -1]
    measure = network.lumped_measure()
    p_n = node_mean(network, gathered_pressure(model))
    opening_n = -node_mean(network, np.asarray(state["closure"], dtype=float))
    out = TransientWater()
    rise = max(pressure_scale(fluid, heads, pressures), float(np.max(np.abs(p_n), initial=0.0)))
    for step in range(1, int(steps) + 1):
        t = step * dt
        accelerate = accelerator(acceleration)
        p_k = gathered_pressure(model)
        accepted, history = converged_maximum_closure(model)  # Δ_m of the last accepted step
        for k in range(1, (max_iterations if coupling == "two_way" else 1) + 1):
            compliance, water = storage(model, state, t_point, compressibility)
            s_fs, s_w = node_mean(network, compliance), node_mean(network, water)
            t_element = t_point.reshape(network.elements.shape).mean(axis=1)
            K = network.conductance(fluid.conductivity_factor * t_element)
            opening = -node_mean(network, np.asarray(state["closure"], dtype=float))
            if coupling == "one_way":      # the compliance as storage, the mechanics held
                opening, p_ref = opening_n, p_n
            else:                          # fixed stress: S (p - p^k), the opening the mechanics'
                p_ref = node_mean(network, p_k)
            diagonal = measure * rg * (s_fs + s_w) / dt
            rhs = measure / dt * (s_fs * rg * (p_ref / rg + z) + s_w * rg * (p_n / rg + z) - (opening - opening_n))
            head = solve_heads(network, K, conditions, owner, fluid, t_element > 0, diagonal, rhs)
            flow = network_result(network, state, K, head, owner, conditions, t_element, t_point, fluid)
            x = np.asarray(state["coordinates"], dtype=float).reshape(-1, model.gdim)
            target = pressure_at_points(flow, x, fluid)
            if coupling == "one_way":
                p_k = target
                break
            step_p = accelerate(p_k, target) - p_k
            scale = max(float(np.linalg.norm(p_k)), float(np.linalg.norm(target))) + rise * np.sqrt(p_k.size)
            change = float(np.linalg.norm(step_p)) / scale if scale > 0.0 else 0.0
            if model.comm.rank == 0:
                log.info("%s t = %.4g s, %d: |Δp| / scale = %.3e", name, t, k, change)
            if change <= tolerance and k > 1:
                break
            p_k = p_k + step_p
            scatter_pressure(model, result, p_k)
            keep_accepted_history(model, accepted)           # iterates do not add to Δ_m
            result = model.solve(1, name=f"{name} t={t:.6g} s, {k}")
            state = history_state(result.gather_joints(), history)
            t_point = point_transmissivity(state, transmissivity, joints)
        else:
            raise CouplingError(f"coupled_transient: step {step} (t = {t:g} s) has not converged in "
                                f"{max_iterations} iterations (|Δp| / scale = {change:.3e})")
        out.times.append(t)
        out.pressures.append(p_k)
        out.networks.append(flow)
        out.iterations.append(k)
        p_n = node_mean(network, p_k)
        opening_n = -node_mean(network, np.asarray(state["closure"], dtype=float))
    return out
