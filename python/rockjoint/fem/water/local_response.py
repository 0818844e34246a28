# SPDX-License-Identifier: MIT
"""The network step of the staggered coupling with the joints' local response (coupled.py,
``network_step='local'``): the mechanics of the last iteration gave every joint point its
closure Δ^k at the effective stress σ'^k = σ_n - α p^k. Where the total normal stress stays put
(the rock around a joint stiffer than the joint, or soft blocks under a given traction), a
pressure p changes the closure as the joint's own law says::

    Δ(p) = Δ^k + C(σ'^k - α (p - p^k)) - C(σ'^k),                                     (L1)

C the closure of the law (with its residual stiffness k_r for σ' < 0: C = σ'/k_r, 0 without
one), exact at p = p^k for any law, on any branch. The network is solved with T(Δ(p)), nonlinear
in p, by Picard sweeps (accelerated as the coupling, acceleration.py). The rock's own
redistribution of σ_n, which (L1) leaves out, is what the outer iterations still correct; where
(L1) holds exactly (a joint under a uniform σ_n) the coupling converges in two iterations. This is
the fixed-stress idea of the transient split (transient.py) applied to the steady state.
"""
from __future__ import annotations

import numpy as np

from ...joint import closure_at_normal_stress
from .acceleration import accelerator


class LocalResponse:
    """Δ(p) of (L1) at every joint point (gathered order) of a solved state."""

    def __init__(self, model, state: dict, pressure: np.ndarray):
        self.tags = np.asarray(state["tag"])
        self.closure = np.asarray(state["closure"], dtype=float)
        self.effective = np.asarray(state["normal_stress"], dtype=float)
        self.pressure = np.asarray(pressure, dtype=float)
        self.behaviours = {int(t): model.behaviours[int(t)] for t in np.unique(self.tags)}
        self.alpha = np.zeros(self.closure.size)
        for tag, b in self.behaviours.items():
            self.alpha[self.tags == tag] = b.effective_stress_coefficient
        self.base = self._c(self.effective)

    def _c(self, effective: np.ndarray) -> np.ndarray:
        out = np.zeros(effective.size)
        for tag, b in self.behaviours.items():
            on = self.tags == tag
            s = effective[on]
            closed = closure_at_normal_stress(b, np.maximum(s, 0.0))
            opened = np.minimum(s, 0.0) / b.residual_stiffness if b.residual_stiffness > 0.0 else 0.0
            out[on] = closed + opened
        return out

    def closure_at(self, pressure: np.ndarray) -> np.ndarray:
        """Δ [m] at every point under the joint pressure p [Pa] (L1)."""
        return self.closure + self._c(self.effective - self.alpha * (pressure - self.pressure)) - self.base


def local_network(response: LocalResponse, solve, transmissivity_at, tolerance: float,
                  max_sweeps: int = 100) -> tuple:
    """(p [Pa] at the points, the network flow) with T(Δ(p)) consistent to `tolerance`
    (relative change of p in a sweep): solve(t_point) -> (flow, p at points) is one linear network
    solve at the points' T; transmissivity_at(closure) -> T at the points."""
    p = response.pressure
    accelerate = accelerator("iqn-ils")
    for _ in range(max_sweeps):
        flow, target = solve(transmissivity_at(response.closure_at(p)))
        scale = max(float(np.linalg.norm(target)), float(np.linalg.norm(p)), np.finfo(float).tiny)
        if np.linalg.norm(target - p) <= tolerance * scale:
            return target, flow
        p = np.maximum(accelerate(p, target), 0.0)
    raise RuntimeError(f"local_network: the network with the joints' local response has not converged in "
                       f"{max_sweeps} sweeps")
