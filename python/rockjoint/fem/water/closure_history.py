# SPDX-License-Identifier: MIT
"""The largest closure each joint point has reached, for transmissivity laws with history
(rockjoint.flow_history; docs/flow.md, "Transmissivity with history (issue 41)").

Δ_m of a point is the larger of

* the largest closure of the point at the ends of the model's solved stages up to the one asked.
  The loads ramp linearly inside a stage and a closure law, with or without history, closes
  monotonically under a monotone ramp, so this is the largest closure reached along the path of
  stage loads. For a NormalHysteresis joint it is the law's own Δ_m (its converged largest
  closure, kept per point in the C++ JointPointState), found without it: the bindings'
  ``point_state`` does not expose that member (python/src/fem_coupling/module.cpp);
* the state's ``maximum_closure``, wherever a state carries one (the bindings' point state once
  it exposes Δ_m: it then also covers a stage whose load path is not monotone).

So a transmissivity law with history works on any closure law. Caveat: the iterates of a coupled
water solve (fem.water.coupled) are stages of the model too, and enter the maximum.
"""
from __future__ import annotations

import numpy as np


def with_closure_history(model, result) -> dict:
    """The gathered joint state of the solved stage `result` of `model` (collective) with
    ``maximum_closure`` [m] the largest closure of each point so far (module docstring)."""
    state = result.gather_joints()
    closure = np.asarray(state["closure"], dtype=float)
    peak = np.maximum(np.asarray(state.get("maximum_closure", closure), dtype=float), closure)
    stages = list(model.stages)
    before = stages[:next((k for k, s in enumerate(stages) if s is result), len(stages))]
    for stage in before:
        earlier = np.asarray(stage.gather_joints()["closure"], dtype=float)
        if earlier.shape == peak.shape:   # the same joint points (every stage of one model)
            peak = np.maximum(peak, earlier)
    return dict(state, maximum_closure=peak)
