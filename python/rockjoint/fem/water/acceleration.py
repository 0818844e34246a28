# SPDX-License-Identifier: MIT
"""Acceleration of the staggered water coupling (coupled.py, transient.py): the fixed point
p = H(p) on the joint pressures, H one mechanical stage and one network solve. Given the iterate
p_k and H(p_k), each accelerator returns p_{k+1}.

- ``aitken``: Aitken's dynamic relaxation (Küttler & Wall 2008, Eq. 44), one scalar ω per
  iteration::

      r_k = H(p_k) - p_k,   ω_k = -ω_{k-1} r_{k-1}·(r_k - r_{k-1}) / |r_k - r_{k-1}|²,   p_{k+1} = p_k + ω_k r_k.

- ``iqn-ils``: the interface quasi-Newton method with an inverse Jacobian from a least-squares
  model (Degroote, Bathe & Vierendeels 2009, Eqs. 12-16; Anderson mixing): the columns of
  V = [r_k - r_{k-1}, ...] and W = [H(p_k) - H(p_{k-1}), ...] since the first iterate, c from
  min ``|V c + r_k|``, then::

      p_{k+1} = H(p_k) + W c.

  It learns the pressure's response to itself along every direction seen so far (a Newton step in
  that subspace), where Aitken has one number.

Both start with the plain step p_1 = H(p_0). The choice of the default is measured:
bench/bench_coupled_water.py (iterations and time of each on the verification cases).
"""
from __future__ import annotations

from typing import Callable

import numpy as np


def accelerator(kind: str) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    """A fresh accelerator f(p_k, H(p_k)) -> p_{k+1} of `kind` ('iqn-ils' or 'aitken')."""
    if kind == "aitken":
        return _aitken()
    if kind == "iqn-ils":
        return _iqn_ils()
    raise ValueError(f"acceleration = {kind!r}: choose 'iqn-ils' or 'aitken'")


def _aitken():
    memory = {"omega": 1.0, "r": None}

    def step(p, h):
        r = h - p
        if memory["r"] is not None:
            d = r - memory["r"]
            dd = float(d @ d)
            if dd > 0.0:
                memory["omega"] = -memory["omega"] * float(memory["r"] @ d) / dd
        memory["r"] = r
        return p + memory["omega"] * r
    return step


def _iqn_ils():
    memory = {"r": [], "h": []}

    def step(p, h):
        r = h - p
        memory["r"].append(r)
        memory["h"].append(h)
        if len(memory["r"]) == 1:
            return h
        # columns r_k - r_{k-1}, r_{k-1} - r_{k-2}, ... (newest first), and the same of H
        V = -np.diff(np.array(memory["r"][::-1]), axis=0).T
        W = -np.diff(np.array(memory["h"][::-1]), axis=0).T
        c, *_ = np.linalg.lstsq(V, -r, rcond=1e-12)
        return h + W @ c
    return step
