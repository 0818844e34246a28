# SPDX-License-Identifier: MIT
"""Water pressure in the joints of a JointedRockModel, acting back on them (docs/flow.md, "Water
that pushes back"): each joint point carries a fluid pressure p; its closure law and its strength
see the effective normal stress σ'_n = σ_n - α p (α: the joint's effective_stress_coefficient, 1
by default) and the water pushes both walls apart with α p (joint/joint_behaviour.hpp, in C++:
the joint element learns σ'_n without knowing about flow).

A pressure set here is the value at the end of the model's next stage: it ramps over that stage
from the value at its start (0 before any), like the loads, so a joint that water opens
(hydraulic jacking, p above the total normal stress) is approached load step by load step.
Where such a joint has no residual stiffness the opened part carries nothing; that is an answer
where the blocks are held otherwise (a tension crack in a slope: the water a load on its walls),
and a singular system where a block is held only by that joint. `set_joint_pressure` finds the
joints without k_r that the water would open (points in contact in the solved state whose total
normal stress it reaches) and, if the next solve then finds no equilibrium (LinearSolveError),
the error names them, the pressure and the stress, as it names an open joint for tension.

Water already in place in the initial state (a water table above the rock mass: hydrostatic p0 =
ρ g (z_table - z)) is set with `set_initial_joint_pressure` before the first solve: the in-situ
stress is then the total stress, the joints are pre-closed at the effective stress σ_n0 - α p0
(mechanics/joint_initial_state.py) and every later stage ramps from p0.
"""
from __future__ import annotations

from typing import Callable, Union

import numpy as np
from mpi4py import MPI

from ..mesh.distributed_mesh import names_of

Pressure = Union[float, Callable, np.ndarray]


def joint_point_coordinates(model) -> np.ndarray:
    """(num_points, gdim) coordinates [m] of the model's joint points on this rank."""
    model.prepare()
    return np.asarray(model.interface.state()["coordinates"], dtype=float).reshape(-1, model.gdim)


def set_joint_pressure(model, pressure: Pressure) -> np.ndarray:
    """Water pressure p [Pa] in the joints at the end of the next stage: one value, a callable
    f(x) of the points' coordinates x (gdim, n) [m] returning n values (e.g. hydrostatic
    ρ g (h - z)), or an array of one value per joint point of this rank (the order of
    model.interface.state()). Returns the values set on this rank. ValueError for a non-finite
    pressure or a wrong size."""
    p = _values(model, pressure)
    model.problem().failure_hints = _jacking(model, p)
    model.problem().set_pressure_target(p)
    return p


def set_initial_joint_pressure(model, pressure: Pressure) -> np.ndarray:
    """Water p0 [Pa] in the joints from the initial state on (given as for set_joint_pressure):
    the model's in-situ stress is the total stress, its joints are pre-closed at the effective
    normal stress σ_n0 - α p0, and the first stage starts (and ramps) from p0. Before the first
    solve, after set_in_situ_stress (RuntimeError otherwise: without an in-situ stress nothing holds
    the water). Returns the values set on this rank."""
    if model.stages:
        raise RuntimeError("set_initial_joint_pressure: the initial water belongs to the initial state; "
                           "set it before the first solve() (later: set_joint_pressure)")
    if model.load_path.in_situ is None:
        raise RuntimeError("set_initial_joint_pressure: the initial water needs the in-situ stress that holds "
                           "it: set_in_situ_stress first")
    p = _values(model, pressure)
    model.problem().initial_pressure = p
    model.load_path.stage.initial_state_set = False    # pre-close the joints again, with p0
    model.prepare()
    return p


def _values(model, pressure: Pressure) -> np.ndarray:
    """The pressure [Pa] at every joint point of this rank from one value, a callable or an array."""
    x = joint_point_coordinates(model)
    if callable(pressure):
        p = np.asarray(pressure(x.T), dtype=float).reshape(-1)
    elif np.ndim(pressure) == 0:
        p = np.full(x.shape[0], float(pressure))
    else:
        p = np.asarray(pressure, dtype=float).reshape(-1)
    if p.shape != (x.shape[0],):
        raise ValueError(f"set_joint_pressure: {p.size} values for {x.shape[0]} joint points on this rank")
    if not np.all(np.isfinite(p)):
        raise ValueError(f"set_joint_pressure: the pressure is not finite at point {int(np.argmax(~np.isfinite(p)))} "
                         f"(x = {x[int(np.argmax(~np.isfinite(p)))]} m) [Pa]")
    return p


def _jacking(model, pressure: np.ndarray) -> list:
    """[what to say if the next solve is singular]: the joints without a residual stiffness where
    α p would reach the total normal stress σ_n = σ' + α p_now of points in contact in the last
    solved state (collective; nothing before a first solve)."""
    if not model.stages:
        return []
    state = model.interface.state()
    tags = np.asarray(state["tag"])
    alpha = np.array([model.behaviours[int(t)].effective_stress_coefficient for t in tags])
    total = np.asarray(state["normal_stress"]) + alpha * model.interface.pore_pressure()
    problems = []
    for name, tag in sorted(names_of(model.dmesh, "joints").items()):
        if model.behaviours[tag].residual_stiffness > 0.0:
            continue
        at = (tags == tag) & (total > 0.0) & (alpha * pressure >= total)
        count = model.comm.allreduce(int(np.sum(at)))
        if count:
            top = model.comm.allreduce(float(np.max(pressure[at], initial=0.0)), op=MPI.MAX)
            low = model.comm.allreduce(float(np.min(total[at], initial=np.inf)), op=MPI.MIN)
            problems.append(f"joint {name!r}: {count} point(s), water up to {top * 1e-6:.4g} MPa against a total "
                            f"normal stress down to {low * 1e-6:.4g} MPa")
    if not problems:
        return []
    return ["The water opens joints without a residual stiffness (hydraulic jacking): " + "; ".join(problems)
            + ". Nothing holds what it opens: give those joints a residual_stiffness, or lower the pressure."]
