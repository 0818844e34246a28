# SPDX-License-Identifier: MIT
"""The largest closure each joint point has reached, for transmissivity laws with history
(rockjoint.flow_history; docs/flow.md, "Transmissivity with history (issue 41)").

Δ_m is kept per point by the C++ joint state (``JointPointState::maximum_closure``), for every
closure law: the largest elastic closure Δ_e = -j_n + d of the converged states, the trial copy
following each evaluation and the converged one growing only when a converged load step is
committed (Newton iterates never enter it). The gathered state carries it (``maximum_closure`` of
the bindings' ``point_state``), so no maximum over the model's stage ends is needed any more: it
would only miss the closures reached inside a stage whose load path is not monotone, and count
the iterates of a coupled water solve, which the staggered solvers now keep out of Δ_m themselves
(`keep_accepted_history`, fem.water.coupled and fem.water.transient).

The transmissivity law is a function of the closure Δ = -j_n (the opening of dilation included),
so Δ_m is handed to it in that measure: Δ_m - d with the point's dilation d now (equal to Δ_m for
a joint that does not dilate; at its largest load a dilated joint is then on its virgin curve, as
it is in the closure law's own measure).
"""
from __future__ import annotations

import numpy as np


def with_closure_history(result) -> dict:
    """The gathered joint state of the solved stage `result` (collective) with ``maximum_closure``
    [m] the largest closure of each point so far in the closure's measure (module docstring)."""
    state = result.gather_joints()
    return history_state(state, state["maximum_closure"])


def history_state(state: dict, elastic_peak) -> dict:
    """`state` (gathered) with ``maximum_closure`` = Δ_m - d [m], never below the closure, from
    the largest elastic closures `elastic_peak` (gathered order) and the state's dilation d."""
    closure = np.asarray(state["closure"], dtype=float)
    peak = np.asarray(elastic_peak, dtype=float) - np.asarray(state["dilation"], dtype=float)
    return dict(state, maximum_closure=np.maximum(peak, closure))


def converged_maximum_closure(model) -> tuple:
    """(this rank's, gathered) Δ_m [m] of the joint points in the model's converged state
    (collective; gathered in the order of StageResult.gather_joints)."""
    model.prepare()
    local = model.interface.maximum_closure()
    return local, np.concatenate(model.comm.allgather(local))


def keep_accepted_history(model, accepted: np.ndarray) -> None:
    """Put back Δ_m = `accepted` (converged_maximum_closure of the last accepted state, this
    rank's points) before a coupling iterate is solved: a staggered water-mechanics iterate is a
    trial of the coupled state, not a state the joint reached, so only the iterate the coupling
    accepts (the last one solved) adds its closures to Δ_m. IQN-ILS may overshoot a closure
    before it converges; without this the overshoot would stay in Δ_m for good."""
    model.interface.set_maximum_closure(accepted)
