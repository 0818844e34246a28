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
    model.problem().failure_hints = _jacking(model, p)
    model.problem().set_pressure_target(p)
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
